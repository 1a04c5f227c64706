"""Study helpers (segplan.studies) against independent oracles.

- rear_length: scipy's adaptive quadrature of |dA/dx|, and the sampled rear polyline;
- shortest_point_path: shapely's exact predicates for visibility (a segment is blocked iff
  its interior meets a polygon's interior) and scipy's Floyd-Warshall on the same vertices;
  analytic paths around a square; and the bound property: every plan's front and rear
  paths are at least as long as the point bounds.
"""

import math
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.sparse.csgraph import csgraph_from_dense, floyd_warshall

import segplan
from segplan import Robot, Union, make_scenario, plan_scenario, random_world
from segplan.floor.random_floors import random_convex_polygon
from segplan.model.pose import feasible_alpha_interval, intrinsic
from segplan.studies.searches import (
    plan_rear_length,
    point_lower_bounds,
    rear_length,
    run_searches,
    search_table,
    shortest_point_path,
)

SCENARIOS = Path(__file__).resolve().parent.parent / "scenarios"


# -- rear length ------------------------------------------------------------------------
@settings(max_examples=40)
@given(
    x=st.floats(-5, 5),
    y=st.floats(-5, 5),
    t0=st.floats(-3.1, 3.1),
    t1=st.floats(-3.1, 3.1),
    frac=st.floats(0.1, 0.9),
    L=st.floats(0.2, 3.0),
)
def test_rear_length_matches_quad_and_is_at_most_longd(x, y, t0, t1, frac, L):
    p0, p1 = (0.0, 0.0, t0), (x, y, t1)
    if math.hypot(x, y) < 0.5:
        return
    geo = intrinsic(p0, p1)
    try:
        lo, hi = feasible_alpha_interval(geo.phi0, geo.phi1)
    except ValueError:  # no cubic joins these headings
        return
    if not hi - lo > 1e-3:
        return
    alpha = lo + frac * (hi - lo)
    u = Union(p0, p1, alpha, L)
    got = rear_length(u)
    ref = quad(lambda s: math.sqrt(1.0 + float(u.slope(s)) ** 2), 0.0, u.x_end, epsrel=1e-12, limit=200)[0]
    assert math.isclose(got, ref, rel_tol=1e-8)
    # |dB/dx|^2 = |dA/dx|^2 + L^2 f''^2 / (1 + f'^2)^2 >= |dA/dx|^2
    assert got <= segplan.longd_exact(p0, p1, alpha, L) * (1 + 1e-9)


def test_rear_length_of_a_straight_union_and_polyline():
    u = Union((1.0, 2.0, 0.3), (1.0 + 4 * math.cos(0.3), 2.0 + 4 * math.sin(0.3), 0.3), 0.0, 1.0)
    assert math.isclose(rear_length(u), 4.0, rel_tol=1e-12)
    v = Union((0.0, 0.0, 0.5), (4.0, 1.0, -0.4), 0.2, 1.0)
    a = v.rear(20001)
    poly = float(np.sum(np.hypot(*np.diff(a, axis=0).T)))
    assert math.isclose(rear_length(v), poly, rel_tol=1e-7)


def test_rear_length_rejects_bad_input():
    with pytest.raises(ValueError, match="union"):
        rear_length((0, 0, 0))
    u = Union((0.0, 0.0, 0.0), (3.0, 0.0, 0.0), 0.0, 1.0)
    with pytest.raises(ValueError, match="rtol"):
        rear_length(u, rtol=0.0)
    with pytest.raises(ValueError, match="plan"):
        plan_rear_length([u])


# -- run_searches ---------------------------------------------------------------------------
def test_run_searches_records_match_plan_scenario():
    sc = segplan.load_scenario(SCENARIOS / "single_obstacle.json")
    searches = {"h'=a": {"heuristic": "a"}, "h'=b": {"heuristic": "b"}, "distance": {"cost": "distance"}}
    records = run_searches(sc, searches)
    assert [r["search"] for r in records] == list(searches)
    for r, kw in zip(records, searches.values(), strict=True):
        p = plan_scenario(sc, **kw, planner="paper")
        assert r["solved"] and r["reason"] == "solved"
        assert r["cost"] == p.cost and r["expanded"] == p.expanded and r["generated"] == p.generated
        assert r["nodes"] == len(p.nodes) and r["plan"].nodes == p.nodes
        assert math.isclose(r["rear"], sum(rear_length(u) for u in p.unions), rel_tol=1e-12)
        assert r["rear"] <= r["cost"]


def test_run_searches_records_failures():
    sc = segplan.load_scenario(SCENARIOS / "turn_around.json")
    (r,) = run_searches(sc, {"tiny": {}}, max_expansions=1)
    assert not r["solved"] and r["reason"] == "expansions" and r["expanded"] == 1
    assert r["cost"] is None and r["plan"] is None and r["seconds"] >= 0


def test_run_searches_rejects_bad_input():
    sc = segplan.load_scenario(SCENARIOS / "single_obstacle.json")
    with pytest.raises(ValueError, match="scenario"):
        run_searches("scenario", {"a": {}})
    with pytest.raises(ValueError, match="searches"):
        run_searches(sc, {})
    with pytest.raises(ValueError, match="searches"):
        run_searches(sc, {"a": "heuristic"})
    with pytest.raises(ValueError, match="heuristic"):
        run_searches(sc, {"a": {"heuristic": "z"}})


def test_search_table_labels_every_record_and_drops_the_plans():
    cases = [
        ({"name": n}, segplan.load_scenario(SCENARIOS / f"{n}.json"))
        for n in ("single_obstacle", "empty_room")
    ]
    searches = {"h'=a": {"heuristic": "a"}, "tiny": {"max_expansions": 1}}
    table = search_table(cases, searches)
    expected = []
    for labels, sc in cases:
        for r in run_searches(sc, searches):
            del r["plan"], r["seconds"]
            expected.append({**labels, **r})
    assert [{k: v for k, v in r.items() if k != "seconds"} for r in table] == expected
    assert list(table[0])[:2] == ["name", "search"]  # the labels first
    with pytest.raises(ValueError, match="cases"):
        search_table([("single_obstacle", cases[0][1])], searches)


# -- shortest point path --------------------------------------------------------------------
SQUARE = np.array([[4.0, -1.0], [6.0, -1.0], [6.0, 1.0], [4.0, 1.0]])


def test_free_straight_line_and_empty_world():
    length, path = shortest_point_path((0.0, 3.0), (10.0, 3.0), [SQUARE])
    assert length == 10.0 and path.shape == (2, 2)
    length, _ = shortest_point_path((0.0, 0.0), (3.0, 4.0), [])
    assert length == 5.0
    # sliding along an edge and grazing a vertex are allowed
    length, _ = shortest_point_path((0.0, 1.0), (10.0, 1.0), [SQUARE])
    assert length == 10.0
    length, _ = shortest_point_path((2.0, -1.0), (6.0, 3.0), [SQUARE])
    assert math.isclose(length, math.hypot(4.0, 4.0), rel_tol=1e-15)


def test_around_a_square_analytic():
    length, path = shortest_point_path((0.0, 0.0), (10.0, 0.0), [SQUARE])
    expected = 2 * math.hypot(4.0, 1.0) + 2.0  # over the top or under the bottom edge
    assert math.isclose(length, expected, rel_tol=1e-12)
    assert len(path) == 4 and np.allclose(np.abs(path[1:3, 1]), 1.0)
    # a wall just above the square leaves only the way below
    length, path = shortest_point_path((0.0, 0.0), (10.0, 0.0), [SQUARE], bounds=(-1, -3, 11, 1.0))
    assert math.isclose(length, expected, rel_tol=1e-12) and np.allclose(path[1:3, 1], [-1.0, -1.0])
    # walls on both sides: no way round
    length, path = shortest_point_path((0.0, 0.0), (10.0, 0.0), [SQUARE], bounds=(-1, -0.5, 11, 0.5))
    assert length == math.inf and path.shape == (0, 2)


def test_rejects_bad_input():
    with pytest.raises(ValueError, match="start"):
        shortest_point_path((5.0, 0.0), (10.0, 0.0), [SQUARE])
    with pytest.raises(ValueError, match="goal"):
        shortest_point_path((0.0, 0.0), (20.0, 0.0), [SQUARE], bounds=(-1, -3, 11, 3))
    with pytest.raises(ValueError, match="start"):
        shortest_point_path((0.0, math.nan), (10.0, 0.0), [SQUARE])
    with pytest.raises(ValueError, match=r"polygons\[0\]"):
        shortest_point_path((0.0, 0.0), (10.0, 0.0), [[[0, 0], [1, 1]]])
    with pytest.raises(ValueError, match="bounds"):
        shortest_point_path((0.0, 0.0), (10.0, 0.0), [SQUARE], bounds=(0, 0, -1, 1))
    with pytest.raises(ValueError, match="scenario"):
        point_lower_bounds(None)


def _oracle(start, goal, polygons, bounds):
    """Shortest path on the same candidate vertices, visibility decided by shapely."""
    shapes = [shapely.Polygon(p) for p in polygons]
    verts = [v for p in polygons for v in p]
    box = shapely.box(*bounds)
    keep = [
        v
        for v in verts
        if box.covers(shapely.Point(v)) and not any(s.contains(shapely.Point(v)) for s in shapes)
    ]
    nodes = np.array([start, goal, *keep])
    m = len(nodes)
    w = np.full((m, m), np.inf)
    for i in range(m):
        for j in range(i + 1, m):
            seg = shapely.LineString([nodes[i], nodes[j]])
            # blocked iff the interiors meet (DE-9IM interior/interior)
            if not any(shapely.relate_pattern(seg, s, "T********") for s in shapes):
                w[i, j] = w[j, i] = math.dist(nodes[i], nodes[j])
    np.fill_diagonal(w, 0.0)
    dist = floyd_warshall(csgraph_from_dense(w, null_value=np.inf), directed=False)
    return float(dist[0, 1])


@settings(max_examples=25)
@given(seed=st.integers(0, 10_000), k=st.integers(1, 6))
def test_matches_shapely_floyd_warshall_oracle(seed, k):
    rng = np.random.default_rng(seed)
    # random convex polygons that may overlap each other and cross the walls
    polys = [
        random_convex_polygon(rng, rng.uniform([1, -4], [11, 4]), rng.uniform(0.5, 2.5)) for _ in range(k)
    ]
    bounds = (-1.0, -5.0, 13.0, 5.0)
    shapes = [shapely.Polygon(p) for p in polys]
    start, goal = (-0.5, rng.uniform(-4, 4)), (12.5, rng.uniform(-4, 4))
    if any(s.contains(shapely.Point(q)) for s in shapes for q in (start, goal)):
        return
    length, path = shortest_point_path(start, goal, polys, bounds)
    ref = _oracle(start, goal, polys, bounds)
    if ref == math.inf:
        assert length == math.inf
        return
    assert math.isclose(length, ref, rel_tol=1e-9)
    # the returned polyline: right ends, right length, and free per shapely
    assert np.array_equal(path[0], start) and np.array_equal(path[-1], goal)
    assert math.isclose(float(np.sum(np.hypot(*np.diff(path, axis=0).T))), length, rel_tol=1e-12)
    line = shapely.LineString(path)
    # the polyline may touch the polygons but not cross them (shrunk by 1e-7 for rounding)
    assert not any(shapely.relate_pattern(line, s.buffer(-1e-7), "T********") for s in shapes)


def test_point_bounds_are_below_every_plan():
    """The bound property on planned scenarios: front (LONGD) and rear lengths exceed the point paths."""
    cases = [segplan.load_scenario(SCENARIOS / f"{n}.json") for n in ("fig5_example1", "fig6_example2")]
    cases += [random_world(seed, 12) for seed in range(3)]
    for sc in cases:
        lb = point_lower_bounds(sc)
        L = sc.robot.L
        a0, b0 = (
            sc.start[:2],
            np.add(sc.start[:2], L * np.array([math.cos(sc.start.theta), math.sin(sc.start.theta)])),
        )
        assert np.allclose(lb["rear_path"][0], a0) and np.allclose(lb["front_path"][0], b0)
        for h in "ab":
            try:
                p = plan_scenario(sc, heuristic=h, planner="paper")
            except segplan.NoPathError:
                continue
            assert p.cost >= lb["front"] * (1 - 1e-9)
            assert plan_rear_length(p) >= lb["rear"] * (1 - 1e-9)


def test_point_bounds_without_obstacles():
    sc = make_scenario(Robot(1.0, 0.2), (0.0, 0.0, 0.0), (8.0, 3.0, 1.0), [], (-2, -2, 12, 6))
    lb = point_lower_bounds(sc)
    assert math.isclose(lb["rear"], math.hypot(8.0, 3.0), rel_tol=1e-15)
    b1 = (8.0 + math.cos(1.0), 3.0 + math.sin(1.0))
    assert math.isclose(lb["front"], math.dist((1.0, 0.0), b1), rel_tol=1e-15)
