"""The robot and its world: convex polygons, enlargement, scenario files, random worlds (issue 3).

Oracles: shapely (exact predicates on polygons, buffers and distances) and closed forms.
"""

import hashlib
import json
import math
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from shapely.geometry import LineString, Point, Polygon

import segplan
from segplan import Robot, ScenarioError, load_scenario, make_scenario, random_world, save_scenario
from segplan.floor.geometry import (
    DEFAULT_MAX_ARC,
    check_convex_polygon,
    enlarge_polygon,
    enlargement_excess,
    pose_segment,
    segment_hits_polygon,
)
from segplan.floor.random_floors import random_convex_polygon
from segplan.floor.scenario import loads_scenario, scenario_from_dict

SCENARIOS = Path(__file__).resolve().parent.parent / "scenarios"
SQUARE = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]


def base_dict():
    """A small valid scenario in file form (angles in degrees)."""
    return {
        "L": 1.0,
        "half_width": 0.2,
        "max_steer_deg": 40,
        "start": [1.0, 1.0, 0.0],
        "goal": [8.0, 4.0, 90.0],
        "bounds": [0, 0, 10, 6],
        "obstacles": [[[4, 2], [6, 2], [6, 4], [4, 4]], [[7, 0.5], [9, 0.5], [8, 2]]],
    }


# -- robot ----------------------------------------------------------------------------
def test_robot_defaults_and_curvature_bound():
    r = Robot(1.25)
    assert r.half_width == 0.0
    assert r.max_steer == pytest.approx(math.radians(45))
    assert r.max_curvature == pytest.approx(1.0 / 1.25)  # tan(45 deg) / L
    r = Robot(2.0, 0.3, math.radians(30))
    assert r.max_curvature == pytest.approx(math.tan(math.radians(30)) / 2.0)
    assert r.min_turning_radius == pytest.approx(1.0 / r.max_curvature)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"L": 0.0}, "L"),
        ({"L": float("nan")}, "L"),
        ({"L": 1.0, "half_width": -0.1}, "half_width"),
        ({"L": 1.0, "half_width": float("inf")}, "half_width"),
        ({"L": 1.0, "half_width": True}, "half_width"),
        ({"L": 1.0, "max_steer": 0.0}, "max_steer"),
        ({"L": 1.0, "max_steer": math.pi / 2}, "max_steer"),
        ({"L": 1.0, "max_steer": "45"}, "max_steer"),
    ],
)
def test_robot_rejects_bad_parameters(kwargs, name):
    with pytest.raises(ValueError, match=name):
        Robot(**kwargs)


# -- convexity checks -----------------------------------------------------------------
def test_check_convex_polygon_returns_counter_clockwise_copy():
    cw = SQUARE[::-1]
    out = check_convex_polygon(cw)
    assert Polygon(out).exterior.is_ccw
    assert out.dtype == float and out.shape == (4, 2)
    np.testing.assert_array_equal(check_convex_polygon(SQUARE), np.array(SQUARE))


STAR = [[math.cos(a), math.sin(a)] for a in np.arange(5) * 4 * math.pi / 5]


@pytest.mark.parametrize(
    "vertices, pattern",
    [
        ([[0, 0], [1, 0]], "at least 3 vertices, got 2"),
        ([], "shape"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], "shape"),
        ([[0, 0], [1, 0], [float("nan"), 1]], "vertex 2: coordinates must be finite"),
        ([[0, 0], [1, 0], [float("inf"), 1]], "vertex 2: coordinates must be finite"),
        ([[0, 0], [1, 0], [0, 0], [0, 1]], "vertex 2 repeats vertex 0"),
        ([[0, 0], [1, 0], [1, 0], [0, 1]], "vertex 2 repeats vertex 1"),
        ([[0, 0], [1, 0], [2, 0]], "degenerate.*collinear"),
        ([[0, 0], [2, 0], [1, 0], [1, 1]], r"vertex 1 \[2.0, 0.0\] doubles back"),
        ([[0, 0], [2, 0], [1, 0.2], [1, 2]], "not convex.*vertex 2"),
        ([[0, 0], [1, 1], [1, 0], [0, 1]], "not convex"),  # bow tie
        (STAR, "self-intersecting.*2 x 360"),
        ([["a", 0], [1, 0], [0, 1]], "numbers"),
    ],
)
def test_check_convex_polygon_rejects(vertices, pattern):
    with pytest.raises(ValueError, match=pattern) as info:
        check_convex_polygon(vertices, where="room.json: obstacles[3]")
    assert str(info.value).startswith("room.json: obstacles[3]")


@pytest.mark.parametrize(
    "vertices, kept",
    [
        ([[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]], [[0, 0], [1, 0], [1, 1], [0, 1]]),  # a closed ring
        ([[0, 0], [1, 0], [2, 0], [1, 1]], [[0, 0], [2, 0], [1, 1]]),  # a collinear vertex
        ([[0, 1], [1, 1], [1, 0], [0, 0], [0, 1]], [[0, 0], [1, 0], [1, 1], [0, 1]]),  # closed, clockwise
        # a union of grid cells as shapely gives it: closed, every cell corner on the boundary kept
        (
            [[0, 0], [0, 1], [0, 2], [1, 2], [2, 2], [3, 2], [3, 1], [3, 0], [2, 0], [1, 0], [0, 0]],
            [[0, 0], [3, 0], [3, 2], [0, 2]],
        ),
    ],
)
def test_check_convex_polygon_drops_closing_and_collinear_vertices(vertices, kept):
    """Issue 27: a closing copy of the first vertex and collinear vertices are dropped, not refused."""
    out = check_convex_polygon(vertices)
    assert {tuple(p) for p in out.tolist()} == {tuple(map(float, p)) for p in kept}
    assert len(out) == len(kept) and Polygon(out).exterior.is_ccw
    assert Polygon(out).equals(Polygon(vertices))


def test_star_pentagon_turns_one_way_only():
    # the case a sign-only convexity test misses: every turn has the same sign
    v = np.array(STAR)
    e = np.roll(v, -1, axis=0) - v
    p = np.roll(e, 1, axis=0)
    assert np.all(p[:, 0] * e[:, 1] - p[:, 1] * e[:, 0] > 0)
    with pytest.raises(ValueError, match="self-intersecting"):
        check_convex_polygon(v)
    with pytest.raises(ValueError, match="self-intersecting"):
        check_convex_polygon(v[::-1])  # clockwise: the same star, turning the other way


grid_polygons = st.lists(st.tuples(st.integers(0, 6), st.integers(0, 6)), min_size=3, max_size=7)


def strict_hull(points) -> list:
    """Counter-clockwise convex hull of integer points, collinear points dropped (monotone chain)."""
    pts = sorted(set(points))

    def half(seq):
        out = []
        for p in seq:
            while len(out) >= 2:
                (ax, ay), (bx, by) = out[-2], out[-1]
                if (bx - ax) * (p[1] - ay) - (by - ay) * (p[0] - ax) > 0:
                    break
                out.pop()
            out.append(p)
        return out[:-1]

    return half(pts) + half(pts[::-1])


@st.composite
def hull_polygons(draw, size: int = 12, most: int = 16):
    """Convex lattice polygons with any number of vertices: hull-ordered points, not filtered lists."""
    points = draw(st.lists(st.tuples(st.integers(0, size), st.integers(0, size)), min_size=3, max_size=most))
    hull = strict_hull(points)
    assume(len(hull) >= 3)  # all points collinear: rare
    return hull


@settings(max_examples=400)
@given(grid_polygons)
@example([(0, 0), (2, 0), (1, 1), (2, 2), (0, 2)])
@example([(0, 0), (3, 0), (3, 3), (0, 3)])
def test_check_convex_polygon_agrees_with_shapely(pts):
    """Accepted iff the ring is simple and equals its convex hull; the output has no redundant vertex.

    A closing copy of the first vertex and collinear vertices are dropped (issue 27), so the
    output's vertices are the hull's (GEOS drops collinear points from a hull).
    """
    if len(pts) > 3 and pts[0] == pts[-1]:
        ring = pts[:-1]  # a closing copy: dropped
    else:
        ring = pts
    v = np.array(ring, dtype=float)
    distinct = len({tuple(p) for p in ring}) == len(ring)
    poly = Polygon(v)
    hull = shapely.convex_hull(shapely.MultiPoint(v))
    oracle = (
        distinct
        and poly.is_valid
        and poly.area > 0
        and hull.geom_type == "Polygon"
        and abs(poly.area - hull.area) < 1e-12
    )
    try:
        out = check_convex_polygon(pts)
    except ValueError:
        assert not oracle
    else:
        assert oracle
        assert Polygon(out).exterior.is_ccw and Polygon(out).equals(poly)
        assert len(out) == len(hull.exterior.coords) - 1  # no collinear vertex left


# -- enlargement ----------------------------------------------------------------------
@st.composite
def convex_polygons(draw):
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    r = draw(st.floats(0.05, 5.0))
    poly = random_convex_polygon(rng, (draw(st.floats(-20, 20)), draw(st.floats(-20, 20))), r, 8)
    return check_convex_polygon(poly)


def excess(ours: np.ndarray, polygon: np.ndarray, r: float) -> float:
    """Hausdorff distance from our polygon to the exact Minkowski sum (ours contains it).

    The distance to a convex set is convex along each edge, so its maximum over our
    boundary is at a vertex: max over vertices of dist(vertex, polygon) - r.
    """
    p = Polygon(polygon)
    return max(p.distance(Point(q)) for q in ours) - r


ACUTE = [[0.0, 0.0], [4.0, 0.0], [0.0, 0.3]]  # 4.3 deg corner: a mitre would spike 25 r


@settings(max_examples=150)
@given(
    convex_polygons(), st.floats(0.01, 2.0), st.sampled_from([DEFAULT_MAX_ARC, math.radians(20), math.pi / 2])
)
@example(check_convex_polygon(ACUTE), 0.35, DEFAULT_MAX_ARC)
def test_enlarged_polygon_contains_buffer_and_excess_is_bounded(polygon, r, max_arc):
    ours = enlarge_polygon(polygon, r, max_arc)
    check_convex_polygon(ours)  # convex, counter-clockwise, simple
    exact = Polygon(polygon).buffer(r, quad_segs=64)  # inscribed in the exact sum
    assert Polygon(ours).buffer(1e-9 * (1 + r)).contains(exact)
    bound = enlargement_excess(r, max_arc)
    got = excess(ours, polygon, r)
    assert -1e-9 <= got <= bound + 1e-9 * (1 + r)
    # the offset edges are exact: every edge of ours is tangent to the disk sum (distance r)
    mids = 0.5 * (ours + np.roll(ours, -1, axis=0))
    d = np.array([Polygon(polygon).distance(Point(m)) for m in mids])
    assert np.all(d >= r - 1e-9 * (1 + r))


def test_enlargement_excess_is_attained_on_a_square():
    r = 0.35
    ours = enlarge_polygon(check_convex_polygon(SQUARE), r)
    assert len(ours) == 8  # two tangent edges per right angle
    assert excess(ours, np.array(SQUARE), r) == pytest.approx(enlargement_excess(r), rel=1e-12)
    assert enlargement_excess(1.0) == pytest.approx(1 / math.cos(math.radians(22.5)) - 1)  # 0.0824


def test_enlarge_zero_width_is_a_copy_and_bad_arguments_raise():
    p = check_convex_polygon(SQUARE)
    q = enlarge_polygon(p, 0.0)
    np.testing.assert_array_equal(p, q)
    assert q is not p
    with pytest.raises(ValueError, match="half_width"):
        enlarge_polygon(p, -1.0)
    with pytest.raises(ValueError, match="max_arc"):
        enlarge_polygon(p, 1.0, max_arc=0.0)


# -- segment and polygon tests ----------------------------------------------------------
grid_point = st.tuples(st.integers(-2, 8), st.integers(-2, 8))


@settings(max_examples=200)  # every example reaches the assertion (was ~15 % of 400)
@given(hull_polygons(8), grid_point, grid_point)
@example([(0, 0), (4, 0), (4, 4), (0, 4)], (4, -1), (4, 6))  # along an edge
@example([(0, 0), (4, 0), (4, 4), (0, 4)], (5, 5), (6, 6))  # on the diagonal's line, outside
@example([(0, 0), (4, 0), (0, 4)], (3, 3), (5, 1))  # parallel to the hypotenuse, outside
def test_segment_hits_polygon_agrees_with_shapely(pts, a, b):
    """Integer coordinates: exact arithmetic, touching cases included (touching is a hit)."""
    poly = check_convex_polygon(pts)
    geom = Point(a) if a == b else LineString([a, b])
    assert segment_hits_polygon(a, b, poly) == geom.intersects(Polygon(poly))


@settings(max_examples=200)
@given(
    convex_polygons(), st.floats(-25, 25), st.floats(-25, 25), st.floats(-math.pi, math.pi), st.floats(0.1, 8)
)
def test_segment_hits_polygon_agrees_with_shapely_floats(poly, x, y, th, L):
    a, b = pose_segment((x, y, th), L)
    seg = LineString([a, b])
    dist = seg.distance(Polygon(poly))
    assume(not 0.0 < dist < 1e-9)  # too close to call in floating point
    assert segment_hits_polygon(a, b, poly) == (dist == 0.0)


# (polygons_overlap against shapely: tests/test_geometry.py)


# -- scenarios ------------------------------------------------------------------------
SHIPPED = sorted(SCENARIOS.glob("*.json"))


def test_scenarios_are_shipped():
    names = {p.stem for p in SHIPPED}
    assert {"fig5_example1", "fig6_example2", "empty_room", "single_obstacle", "turn_around"} <= names


@pytest.mark.parametrize("path", SHIPPED, ids=lambda p: p.stem)
def test_every_shipped_scenario_loads_and_round_trips(path, tmp_path):
    sc = load_scenario(path)
    assert sc.path == path and sc.name == path.stem
    assert "degrees" in sc.description  # the file says its units
    assert sc.is_free(sc.start) and sc.is_free(sc.goal)
    again = load_scenario(save_scenario(sc, tmp_path / path.name))
    assert again.to_dict() == sc.to_dict()
    # the file's own text is what to_json writes (files are generated, not hand-mangled)
    assert json.loads(path.read_text()) == sc.to_dict()


def test_fig5_and_fig6_share_positions_not_orientations():
    f5 = load_scenario(SCENARIOS / "fig5_example1.json")
    f6 = load_scenario(SCENARIOS / "fig6_example2.json")
    assert f5.start[:2] == f6.start[:2] and f5.goal[:2] == f6.goal[:2]
    assert f5.start.theta != f6.start.theta and f5.goal.theta != f6.goal.theta
    assert f5.to_dict()["obstacles"] == f6.to_dict()["obstacles"]
    assert 8 <= len(f5.obstacles) <= 12
    x0, y0, x1, y1 = f5.bounds
    assert (x1 - x0, y1 - y0) == (30.0, 20.0)
    assert 1.0 <= f5.L <= 1.5 and 0.3 <= f5.robot.half_width <= 0.4


@pytest.mark.parametrize(
    "name, centre, along",
    [("fig5_example1", (13.0, 9.4), 0.0), ("narrow_passage", (7.0, 4.0), 0.0)],
)
def test_narrow_passage_is_passed_only_well_oriented(name, centre, along):
    """Segment centred in the passage: free up to asin(w / L) from its axis, w the enlarged width."""
    sc = load_scenario(SCENARIOS / f"{name}.json")
    w = 1.2 - 2 * sc.robot.half_width
    limit = math.asin(w / sc.L)  # 24.6 deg for w = 0.5, L = 1.2
    for base in (along, along + math.pi):
        for tilt, free in ((0.0, True), (limit - 0.01, True), (limit + 0.01, False), (math.pi / 2, False)):
            for sgn in (1, -1):
                th = base + sgn * tilt
                pose = (centre[0] - 0.5 * sc.L * math.cos(th), centre[1] - 0.5 * sc.L * math.sin(th), th)
                assert sc.is_free(pose) == free, (tilt, sgn, base)


def test_turn_around_goal_opposes_start():
    sc = load_scenario(SCENARIOS / "turn_around.json")
    assert abs(abs(sc.goal.theta - sc.start.theta) - math.pi) < 1e-12


@pytest.fixture(scope="module")
def fig5():
    """Fig. 5's scenario, loaded once for the examples below (~6 ms a load; read only). A
    fixture, not a module constant: each pytest session (each mutant's run) loads it afresh."""
    return load_scenario(SCENARIOS / "fig5_example1.json")


@settings(max_examples=150)
@given(st.integers(0, 10**6), st.floats(-math.pi, math.pi), st.floats(0, 1), st.floats(0, 1))
def test_is_free_against_shapely_distance(fig5, seed, th, u, v):
    """Collision iff the segment comes within half_width of a raw obstacle, up to the excess."""
    sc = fig5
    x0, y0, x1, y1 = sc.free_bounds
    pose = (x0 + 1.5 + u * (x1 - x0 - 3), y0 + 1.5 + v * (y1 - y0 - 3), th)
    a, b = pose_segment(pose, sc.L)
    dist = min(LineString([a, b]).distance(Polygon(p)) for p in sc.obstacles)
    r = sc.robot.half_width
    if dist <= r:
        assert not sc.is_free(pose)
    elif dist > r + enlargement_excess(r) + 1e-9:
        assert sc.is_free(pose)


def test_scenario_is_immutable():
    sc = load_scenario(SCENARIOS / "single_obstacle.json")
    with pytest.raises(AttributeError):
        sc.robot = Robot(1.0)
    with pytest.raises(ValueError):
        sc.obstacles[0][0, 0] = 99.0
    with pytest.raises(ValueError):
        sc.enlarged[0][0, 0] = 99.0


def test_file_angles_are_degrees_api_radians():
    sc = scenario_from_dict(base_dict())
    assert sc.goal.theta == pytest.approx(math.pi / 2)
    assert sc.robot.max_steer == pytest.approx(math.radians(40))
    assert sc.to_dict()["goal"][2] == pytest.approx(90.0)


def test_defaults_and_optional_keys():
    d = base_dict()
    for k in ("half_width", "max_steer_deg", "bounds"):
        del d[k]
    sc = scenario_from_dict(d)
    assert sc.robot.half_width == 0.0 and sc.robot.max_steer == pytest.approx(math.radians(45))
    assert sc.bounds is None and sc.free_bounds is None
    d["bounds"] = None
    assert scenario_from_dict(d).bounds is None
    d["obstacles"] = []
    assert scenario_from_dict(d).obstacles == ()


def test_clockwise_obstacles_are_accepted_and_stored_counter_clockwise():
    d = base_dict()
    d["obstacles"][0] = d["obstacles"][0][::-1]
    sc = scenario_from_dict(d)
    assert all(Polygon(p).exterior.is_ccw for p in sc.obstacles)


def mutate(path: tuple, value):
    d = base_dict()
    target = d
    for key in path[:-1]:
        target = target[key]
    if value is DELETE:
        del target[path[-1]]
    else:
        target[path[-1]] = value
    return d


DELETE = object()
CASES = [
    (("colour",), "red", r"unknown key 'colour'"),
    (("start",), DELETE, r"missing key 'start'"),
    (("obstacles",), DELETE, r"missing key 'obstacles'"),
    (("L",), True, r"L must be a number, got bool"),
    (("L",), "1.2", r"L must be a number, got str"),
    (("L",), -1, r"L must be a positive"),
    (("half_width",), -0.1, r"half_width must be >= 0"),
    (("max_steer_deg",), 90, r"max_steer_deg must lie in \(0, 90\)"),
    (("start",), [1, 1], r"start must have 3 numbers"),
    (("start",), {"x": 1}, r"start must be a list"),
    (("goal", 2), None, r"goal\[2\] must be a number"),
    (("bounds",), [0, 0, 10], r"bounds must have 4 numbers"),
    (("bounds",), [10, 0, 0, 6], r"not a rectangle"),
    (("bounds",), [0, 0, 10, 0], r"not a rectangle"),
    (("bounds",), [0, 0, 0.3, 6], r"no room for half_width"),
    (("obstacles",), {"a": 1}, r"obstacles must be a list of polygons"),
    (("obstacles", 1), 5, r"obstacles\[1\] must be a list of \[x, y\] vertices"),
    (("obstacles", 1, 2), [8], r"obstacles\[1\] vertex 2 must have 2 numbers"),
    (("obstacles", 1, 2, 0), "8", r"obstacles\[1\] vertex 2\[0\] must be a number"),
    (("obstacles", 1, 2), [9, 0.5], r"obstacles\[1\]: vertex 2 repeats vertex 1"),
    (("obstacles", 0, 2), [3, 3], r"obstacles\[0\]: not a simple .* edges leaving vertex 1 and vertex 3"),
    (("obstacles", 1), [[7, 0.5], [8, 0.5], [9, 0.5]], r"obstacles\[1\]: degenerate polygon"),
    (("obstacles", 1), [[7, 0.5], [9, 0.5]], r"obstacles\[1\]: a polygon needs at least 3 vertices"),
    (("start",), [4.5, 3.0, 0], r"start pose .* collides with obstacles\[0\]"),
    (("start",), [3.0, 3.0, 0], r"start pose .* collides with obstacles\[0\]"),  # front reaches 4.0 - 0.2
    (("goal",), [9.5, 3.0, 0], r"goal pose .* out of bounds"),
    (("goal",), [5.0, 5.85, 180], r"goal pose .* out of bounds"),  # within half_width of the wall
    (("name",), 3, r"name must be a string"),
]


@pytest.mark.parametrize("path, value, pattern", CASES)
def test_validation_errors_name_file_key_obstacle_and_vertex(path, value, pattern, tmp_path):
    f = tmp_path / "bad.json"
    f.write_text(json.dumps(mutate(path, value)))
    with pytest.raises(ScenarioError, match=pattern) as info:
        load_scenario(f)
    assert str(info.value).startswith(str(f))


@pytest.mark.parametrize(
    "text, pattern",
    [
        (b"", "empty"),
        (b"   \n", "empty"),
        (b"\xff\xfe{}", "not UTF-8"),
        (b"[1, 2]", "top level must be a JSON object"),
        (b'{"L": NaN}', "non-finite literal NaN"),
        (b'{"L": -Infinity}', "non-finite literal -Infinity"),
        (b'{"L": 1e999, "start": [0,0,0], "goal": [1,1,0], "obstacles": []}', "L must be finite"),
        (b'{"L": 1, "L": 2}', "key 'L' is repeated"),
        (b'{"L": 1,', "invalid JSON"),
        (b"[" * 100_000 + b"]" * 100_000, "invalid JSON"),
        (b'{"L": ' + b"9" * 5000 + b"}", "invalid JSON"),
        (b'{"L": 1' + b"0" * 400 + b', "start": [0,0,0], "goal": [1,1,0], "obstacles": []}', "too large"),
    ],
)
def test_malformed_text(text, pattern):
    with pytest.raises(ScenarioError, match=pattern):
        loads_scenario(text, source="x.json")


@pytest.mark.parametrize(
    "change, pattern",
    [
        ({"L": 1e-7}, r"L=1e-07 is outside"),
        ({"L": 2e6}, r"L=2000000.0 is outside"),
        ({"half_width": 1e-9}, r"half_width=1e-09 must be 0 or within"),
        ({"goal": [2e6, 0, 0]}, r"goal: coordinates .* exceed"),
        ({"bounds": [-1e300, 0, 10, 6]}, r"bounds: coordinates .* exceed"),
        ({"obstacles": [[[0, 0], [1e7, 0], [0, 1e7]]]}, r"obstacles\[0\] vertex 1: coordinates exceed"),
    ],
)
def test_world_scale_limits(change, pattern):
    """Coordinates and lengths within 1e6 and L >= 1e-6: no overflow, no denormal robots."""
    d = base_dict() | change
    with pytest.raises(ScenarioError, match=pattern):
        scenario_from_dict(d, source="s.json")


def test_huge_polygons_are_checked_without_overflow():
    big = np.array(SQUARE) * 1e307 - 1e307
    np.testing.assert_array_equal(check_convex_polygon(big[::-1]), big)
    with pytest.raises(ValueError, match="not convex"):
        check_convex_polygon([[-1e308, -1e308], [1e308, -1e308], [0, -1e307], [0, 1e308]])


def test_unreadable_file_is_a_scenario_error(tmp_path):
    with pytest.raises(ScenarioError, match="missing.json: cannot read"):
        load_scenario(tmp_path / "missing.json")
    with pytest.raises(ScenarioError, match="cannot read"):
        load_scenario(tmp_path)


def test_make_scenario_python_api_uses_radians():
    sc = make_scenario(Robot(1.0), (3, 1, math.pi / 2), (5, 5, 0.0), [SQUARE], None)
    assert sc.start.theta == math.pi / 2
    with pytest.raises(ScenarioError, match="<python>: start"):
        make_scenario(Robot(1.0), (1, 1), (5, 5, 0.0))
    with pytest.raises(ScenarioError, match="robot must be a Robot"):
        make_scenario(1.0, (1, 1, 0), (5, 5, 0.0))


# -- fuzzing --------------------------------------------------------------------------
json_scalars = (
    st.none()
    | st.booleans()
    | st.integers(-(10**400), 10**400)
    | st.floats(allow_nan=True, allow_infinity=True)
    | st.text(max_size=8)
)
json_values = st.recursive(
    json_scalars,
    lambda inner: st.lists(inner, max_size=5) | st.dictionaries(st.text(max_size=6), inner, max_size=5),
    max_leaves=25,
)
KEYS = ["L", "half_width", "max_steer_deg", "start", "goal", "bounds", "obstacles", "name", "description"]


@st.composite
def mutated_files(draw):
    """A valid scenario with some parts replaced by hostile values, serialised to bytes."""
    d = base_dict()
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.integers(0, 4))
        if kind == 0:  # replace or add a top-level key
            d[draw(st.sampled_from([*KEYS, "extra"]))] = draw(json_values)
        elif kind == 1 and d:  # delete a key
            del d[draw(st.sampled_from(sorted(d)))]
        elif kind == 2 and isinstance(d.get("obstacles"), list) and d["obstacles"]:  # a vertex or polygon
            obs = d["obstacles"]
            i = draw(st.integers(0, len(obs) - 1))
            if isinstance(obs[i], list) and obs[i] and draw(st.booleans()):
                obs[i][draw(st.integers(0, len(obs[i]) - 1))] = draw(json_values)
            else:
                obs[i] = draw(json_values)
        elif kind == 3:  # a number anywhere in start/goal/bounds
            key = draw(st.sampled_from(["start", "goal", "bounds"]))
            if isinstance(d.get(key), list) and d[key]:
                d[key][draw(st.integers(0, len(d[key]) - 1))] = draw(json_scalars)
        else:  # shuffle an obstacle's vertices
            if (
                isinstance(d.get("obstacles"), list)
                and d["obstacles"]
                and isinstance(d["obstacles"][0], list)
            ):
                d["obstacles"][0] = draw(st.permutations(d["obstacles"][0]))
    text = json.dumps(d, allow_nan=True)  # may write NaN / Infinity literals
    if draw(st.booleans()):  # truncate or corrupt some bytes
        raw = bytearray(text.encode())
        for _ in range(draw(st.integers(1, 3))):
            raw[draw(st.integers(0, len(raw) - 1))] = draw(st.integers(0, 255))
        return bytes(raw)
    return text.encode()


hostile = (
    mutated_files()
    | json_values.map(lambda v: json.dumps(v).encode())
    | st.binary(max_size=200)
    | st.text(max_size=200).map(str.encode)
    | st.integers(1, 3000).map(lambda n: b'{"obstacles": ' + b"[" * n + b"]" * n + b"}")
)


@settings(max_examples=600)
@given(hostile)
@example(b"")
@example(b"\x00\x01\x02")
@example(b"\xef\xbb\xbf{}")
@example(
    b'{"L": 1, "start": [0, 0, 0], "goal": [1e308, 0, 0], "obstacles": [], "bounds": [-1e308, -1, 1e308, 1]}'
)
@example(b'{"L": 1e308, "start": [0, 0, 0], "goal": [5, 5, 0], "obstacles": [[[0,0],[1e308,0],[0,1e308]]]}')
@example(b'{"L": 1e-320, "half_width": 1e308, "start": [0, 0, 0], "goal": [5, 5, 0], "obstacles": []}')
def test_fuzz_hostile_files_load_or_raise_scenario_error(raw):
    try:
        sc = loads_scenario(raw, source="fuzz.json")
    except ScenarioError as exc:
        assert str(exc).startswith("fuzz.json")
        return
    # whatever loads is a valid scenario that survives a round trip (degrees <-> radians
    # may move a heading by an ulp)
    assert sc.is_free(sc.start) and sc.is_free(sc.goal)
    again = loads_scenario(sc.to_json()).to_dict()
    for key, value in sc.to_dict().items():
        if key in ("start", "goal"):
            np.testing.assert_allclose(again[key], value, rtol=1e-14, atol=0)
        else:
            assert again[key] == value


def test_fuzz_through_files(tmp_path):
    """The same contract through load_scenario on disk, for a few hostile byte strings."""
    for i, raw in enumerate([b"\x80\x81", b"{", b"null", b'"text"', b"[[[[[]]]]]", b'{"L": Infinity}']):
        f = tmp_path / f"f{i}.json"
        f.write_bytes(raw)
        with pytest.raises(ScenarioError, match=str(f).replace("\\", "\\\\")):
            load_scenario(f)


# -- random worlds --------------------------------------------------------------------
def test_random_world_is_deterministic_and_valid():
    a = random_world(7, 10)
    b = random_world(7, 10)
    assert a.to_dict() == b.to_dict()
    assert a.to_dict() != random_world(8, 10).to_dict()
    assert len(a.obstacles) == 10
    assert a.is_free(a.start) and a.is_free(a.goal)
    # obstacles lie within the bounds; enlarged obstacles do not overlap (min_gap=0)
    box = shapely.box(*a.bounds)
    assert all(box.contains(Polygon(p)) for p in a.obstacles)
    polys = [Polygon(e) for e in a.enlarged]
    assert not any(p.intersects(q) for i, p in enumerate(polys) for q in polys[i + 1 :])
    # it is a scenario like any other: it survives the file round trip
    assert loads_scenario(a.to_json()).to_dict() == a.to_dict()


@settings(max_examples=25)
@given(st.integers(0, 10**9), st.integers(0, 12), st.just(0.0) | st.floats(1e-6, 0.5))
def test_random_world_property(seed, n, hw):
    robot = Robot(1.0, hw)
    w = random_world(seed, n, (0, 0, 25, 18), robot, clearance=0.5)
    assert len(w.obstacles) == n and w.robot == robot
    for pose in (w.start, w.goal):
        a, b = pose_segment(pose, w.L)
        seg = LineString([a, b])
        assert all(seg.distance(Polygon(p)) > hw + 0.5 - 1e-9 for p in w.obstacles)


def test_random_world_given_poses_and_overlap_allowed():
    start, goal = (2.0, 10.0, 0.0), (27.0, 10.0, math.pi)
    w = random_world(3, 25, start=start, goal=goal, min_gap=None)
    assert w.start == start and w.goal == goal and len(w.obstacles) == 25


@pytest.mark.parametrize(
    "seed, kwargs, digest",
    [
        (0, {}, "49533e0a0641d3c6"),
        (1, {"min_gap": None}, "3c8a02b051b975a4"),
        (2, {"min_gap": 0.5, "clearance": 0.2}, "1f5854d5d007212e"),
    ],
)
def test_random_world_stays_the_same_world(seed, kwargs, digest):
    """Tests, benchmarks and notebooks keep drawing the same worlds: the digests (poses and
    vertices to 1e-9 m) were recorded with the placement loop random_world had before
    segplan.floor.random_floors.place_disjoint served it and the study floors (issue 11)."""
    w = random_world(seed, 8, **kwargs)
    data = [[round(float(v), 9) for v in p] for p in (w.start, w.goal)]
    data += [[round(float(v), 9) for v in np.ravel(p)] for p in w.obstacles]
    assert hashlib.sha256(json.dumps(data).encode()).hexdigest()[:16] == digest


@pytest.mark.parametrize(
    "kwargs, pattern",
    [
        ({"n_obstacles": -1}, "n_obstacles"),
        ({"n_obstacles": 2.5}, "n_obstacles"),
        ({"n_obstacles": 40, "radius": (3.0, 4.0), "max_tries": 400}, "placed only 1[0-9] of 40"),
        ({"n_obstacles": 3, "bounds": (0, 0, 3, 3)}, "bounds"),
        ({"n_obstacles": 3, "bounds": (0, 0, 30)}, "bounds"),
        ({"n_obstacles": 3, "radius": (2.0, 1.0)}, "radius"),
        ({"n_obstacles": 3, "max_vertices": 2}, "max_vertices"),
        ({"n_obstacles": 3, "robot": 1.0}, "robot"),
    ],
)
def test_random_world_rejects_bad_arguments(kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        random_world(0, **kwargs)


def test_public_names():
    for name in ("Robot", "Scenario", "ScenarioError", "load_scenario", "save_scenario", "random_world"):
        assert name in segplan.__all__
    assert issubclass(ScenarioError, ValueError)


# -- non-convex obstacles (issue 14): split into convex pieces ---------------------------
L_RACK = SCENARIOS / "beyond_the_paper" / "l_shaped_rack.json"
L_SHAPE = [[4, 2], [6, 2], [6, 3], [5, 3], [5, 5], [4, 5]]  # an L in base_dict's world


def test_l_shaped_rack_is_shipped_loads_round_trips_and_keeps_its_outlines(tmp_path):
    sc = load_scenario("l_shaped_rack")
    assert sc.to_json() == load_scenario(L_RACK).to_json() == L_RACK.read_text()
    assert len(sc.outlines) == 3 and len(sc.obstacles) > 3  # the rack and the bay are split
    assert sc.outline_of == tuple(sorted(sc.outline_of)) and set(sc.outline_of) == {0, 1, 2}
    for k, outline in enumerate(sc.outlines):
        pieces = [Polygon(p) for p, o in zip(sc.obstacles, sc.outline_of, strict=True) if o == k]
        assert shapely.union_all(pieces).symmetric_difference(Polygon(outline)).area < 1e-9
    assert len(sc.enlarged) == len(sc.obstacles)
    again = load_scenario(save_scenario(sc, tmp_path / "again.json"))
    assert again.to_dict() == sc.to_dict()
    assert all(np.array_equal(a, b) for a, b in zip(again.obstacles, sc.obstacles, strict=True))


def test_the_default_planner_solves_the_l_shaped_rack_without_collision():
    sc = load_scenario("l_shaped_rack")
    plan = segplan.plan_scenario(sc)
    m = segplan.measure_scenario_path(segplan.plan_poses(plan), sc)
    assert not m.collides and m.clearance > 0.0
    # the bay's convex hull holds the goal: only the non-convex obstacle leaves it free
    hull = Polygon(sc.outlines[1]).convex_hull
    assert hull.contains(Point(sc.goal.x, sc.goal.y))


def test_convex_obstacles_give_the_same_scenario_as_before():
    sc = scenario_from_dict(base_dict())
    assert sc.outlines == sc.obstacles and all(a is b for a, b in zip(sc.outlines, sc.obstacles, strict=True))
    assert sc.outline_of == (0, 1)


def test_non_convex_file_obstacle_is_split_and_a_collision_names_it_and_its_piece(tmp_path):
    d = base_dict()
    d["obstacles"][0] = L_SHAPE
    sc = scenario_from_dict(d)
    assert len(sc.outlines) == 2 and len(sc.obstacles) == 3 and sc.outline_of == (0, 0, 1)
    assert sc.to_dict()["obstacles"][0] == [[float(x), float(y)] for x, y in L_SHAPE]
    d["start"] = [4.2, 4.5, 0.0]  # in the L's upright
    f = tmp_path / "bad.json"
    f.write_text(json.dumps(d))
    with pytest.raises(ScenarioError, match=r"start pose .* collides with obstacles\[0\] \(its convex piece"):
        load_scenario(f)


def test_shapely_obstacles_in_make_scenario_and_plan():
    robot = Robot(1.0, 0.2, math.radians(40))
    start, goal = (1.0, 1.0, 0.0), (8.0, 4.0, math.radians(90))
    as_lists = make_scenario(robot, start, goal, [L_SHAPE], (0, 0, 10, 6))
    as_shapely = make_scenario(robot, start, goal, [Polygon(L_SHAPE)], (0, 0, 10, 6))
    assert as_shapely.to_json() == as_lists.to_json()
    multi = shapely.MultiPolygon([Polygon(L_SHAPE), shapely.box(7, 0.5, 9, 2)])
    sc = make_scenario(robot, start, goal, [multi], (0, 0, 10, 6))
    assert len(sc.outlines) == 2
    plan = segplan.plan(start, goal, [multi], 1.0, (0, 0, 10, 6), half_width=0.2, max_steer=math.radians(40))
    assert not segplan.measure_scenario_path(segplan.plan_poses(plan), sc).collides


@pytest.mark.parametrize(
    ("obstacle", "pattern"),
    [
        (
            shapely.Polygon([[3, 1], [7, 1], [7, 5], [3, 5]], [[[4, 2], [5, 2], [5, 3], [4, 3]]]),
            r"<python>: obstacles\[0\]: a polygon with 1 hole\(s\) is not supported",
        ),
        (shapely.LineString([[3, 1], [7, 1]]), r"obstacles\[0\]: a LineString is not an obstacle"),
        ([[3, 1], [5, 3], [5, 1], [3, 3]], r"obstacles\[0\]: not a simple polygon .* vertex"),
        (
            shapely.MultiPolygon([shapely.box(3, 1, 4, 2), Polygon([[5, 1], [6, 2], [6, 1], [5, 2]])]),
            r"obstacles\[0\] part 1: not a simple polygon",
        ),
    ],
)
def test_holes_and_self_intersections_are_scenario_errors(obstacle, pattern):
    with pytest.raises(ScenarioError, match=pattern):
        make_scenario(Robot(1.0), (1.0, 1.0, 0.0), (8.0, 4.0, 0.0), [obstacle], (0, 0, 10, 6))


@pytest.mark.parametrize("theta", [90.0, -7.0, 2 * math.pi + 1e-9])
def test_a_heading_beyond_two_pi_is_refused_naming_radians(theta):
    """Issue 27: goal=(8, 5, 90) meant as degrees was planned as 90 rad; now refused."""
    robot = Robot(1.0, 0.3)
    refused = r"goal heading theta=.* rad is beyond 2 pi .*headings are in radians"
    with pytest.raises(ScenarioError, match=refused):
        make_scenario(robot, (1.0, 1.0, 0.0), (8.0, 5.0, theta), [], (0.0, 0.0, 10.0, 10.0))
    make_scenario(robot, (1.0, 1.0, 0.0), (8.0, 5.0, 2 * math.pi), [], (0.0, 0.0, 10.0, 10.0))  # on the edge


def test_messages_print_headings_in_degrees():
    """Issue 27: no-path messages printed headings in radians while files and output use degrees."""
    from segplan import NoPathError, plan_scenario

    robot = Robot(1.0, 0.3)
    walls = [[[5, 0], [5.2, 0], [5.2, 10], [5, 10]]]
    sc = make_scenario(robot, (1.0, 5.0, 0.0), (8.0, 5.0, math.pi / 2), walls, (0.0, 0.0, 10.0, 10.0))
    for planner in ("lattice", "paper"):
        message = r"no path from \(x=1, y=5, theta=0 deg\) to \(x=8, y=5, theta=90 deg\)"
        with pytest.raises(NoPathError, match=message):
            plan_scenario(sc, planner=planner, max_expansions=200)
