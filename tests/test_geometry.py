"""One polygon validator for the whole package (issue 11), under near-degenerate polygons.

``segplan.collides``, ``segplan.make_scenario``, ``segplan.load_scenario`` (file text) and
``segplan.plan`` validate obstacles with :func:`segplan.geometry.check_convex_polygon`
(turns within ``ANGLE_TOL = 1e-9`` rad of 0 or pi are collinear vertices; edges shorter
than ``LENGTH_TOL = 1e-12`` of the largest coordinate repeat a vertex). The property test
builds convex polygons directly (points on a circle in angular order, any vertex count)
and spoils them slightly: a duplicated vertex (exact or nearly), a point inserted on an
edge or just off it (a collinear run, a tiny turn either way), the ring closed by
repeating the first vertex, the orientation reversed. The convex validator and
``collides`` (the paper's test of convex polygons) accept and reject exactly the same
polygons; so do the three scenario entry points, which also take simple non-convex
polygons (issue 14, split by :mod:`segplan.decompose`): every convex polygon, and a
non-convex one only if it is simple (shapely's ``is_valid``). Rejection names the polygon.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

import segplan
from segplan import geometry as geo

L = 1.0
START, GOAL = (-3000.0, 2500.0, 0.0), (-2990.0, 2500.0, 0.0)  # far from every polygon: a free direct union
FAR_UNION = segplan.Union(START, GOAL, 0.0, L)

OFFSETS = [0.0, 1e-16, 1e-14, 1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-6, 1e-3]


@st.composite
def near_degenerate_polygons(draw):
    k = draw(st.integers(3, 9))
    scale = draw(st.sampled_from([1e-3, 1.0, 37.0, 1e3]))
    gaps = np.array(draw(st.lists(st.floats(0.2, 1.0), min_size=k, max_size=k)))
    ang = np.cumsum(gaps) / gaps.sum() * 2.0 * math.pi + draw(st.floats(0.0, 6.3))
    v = scale * np.column_stack((np.cos(ang), np.sin(ang)))
    pts = [list(map(float, p)) for p in v]
    how = draw(st.sampled_from(["none", "duplicate", "near_duplicate", "on_edge", "off_edge", "close_ring"]))
    i = draw(st.integers(0, k - 1))
    a, b = np.array(pts[i]), np.array(pts[(i + 1) % k])
    eps = draw(st.sampled_from(OFFSETS)) * scale * draw(st.sampled_from([1.0, -1.0]))
    if how == "duplicate":
        pts.insert(i + 1, list(pts[i]))
    elif how == "near_duplicate":
        pts.insert(i + 1, [pts[i][0] + eps, pts[i][1]])
    elif how in ("on_edge", "off_edge"):
        t = draw(st.floats(0.05, 0.95))
        e = b - a
        n = np.array([e[1], -e[0]]) / math.hypot(*e)  # outward (counter-clockwise ring)
        p = a + t * e + (eps * n if how == "off_edge" else 0.0)
        pts.insert(i + 1, [float(p[0]), float(p[1])])
    elif how == "close_ring":
        pts.append(list(pts[0]))
    if draw(st.booleans()):
        pts.reverse()
    return pts


def accepted(fn) -> bool:
    try:
        fn()
    except segplan.NoPathError:  # pragma: no cover - the direct union is free
        raise
    except ValueError as exc:
        assert "obstacles[0]" in str(exc) or "polygon" in str(exc), str(exc)
        return False
    return True


def scenario_text(pts) -> str:
    return json.dumps({"L": L, "start": list(START), "goal": list(GOAL), "obstacles": [pts]})


@settings(max_examples=300, deadline=None)
@given(near_degenerate_polygons())
def test_every_entry_point_accepts_the_same_polygons(pts):
    by_validator = accepted(lambda: geo.check_convex_polygon(pts))
    by_collides = accepted(lambda: segplan.collides(FAR_UNION, pts))
    by_make = accepted(lambda: segplan.make_scenario(segplan.Robot(L), START, GOAL, [pts]))
    by_load = accepted(lambda: segplan.world.loads_scenario(scenario_text(pts)))
    by_plan = accepted(lambda: segplan.plan(START, GOAL, [pts], L))
    assert by_collides == by_validator  # the paper's collision test: convex polygons
    assert by_make == by_load == by_plan  # scenarios: any simple polygon
    if by_validator:
        assert by_make  # convex input is accepted as always
    elif by_make:  # a tiny notch: a simple non-convex polygon, split into convex pieces
        assert shapely.Polygon(pts).is_valid
        sc = segplan.make_scenario(segplan.Robot(L), START, GOAL, [pts])
        assert all(accepted(lambda p=p: geo.check_convex_polygon(p)) for p in sc.obstacles)


@pytest.mark.parametrize(
    ("pts", "ok"),
    [
        ([[0, 0], [1, 0], [0, 1]], True),
        ([[0, 0], [1, 0], [1, 0], [0, 1]], False),  # duplicate
        ([[0, 0], [0.5, 0], [1, 0], [0, 1]], False),  # collinear run
        ([[0, 0], [0.5, -1e-12], [1, 0], [0, 1]], False),  # a turn of 4e-12 rad: below ANGLE_TOL
        ([[0, 0], [0.5, -1e-6], [1, 0], [0, 1]], True),  # a turn of 4e-6 rad: a real vertex
        ([[0, 0], [1, 0], [0, 1], [0, 0]], False),  # closed ring
    ],
)
def test_tolerances_are_the_stated_ones(pts, ok):
    assert accepted(lambda: geo.check_convex_polygon(pts)) is ok
    assert accepted(lambda: segplan.collides(FAR_UNION, pts)) is ok
    assert accepted(lambda: segplan.plan(START, GOAL, [pts], L)) is ok


def test_one_bounds_validator():
    for bad in [(0, 0, 1), (0, 0, -1, 1), (0, 0, math.inf, 1), "abcd", None]:
        with pytest.raises(ValueError, match="bounds"):
            geo.check_bounds(bad)
        with pytest.raises(ValueError, match="bounds"):
            segplan.union_in_bounds(FAR_UNION, bad)
        with pytest.raises(ValueError, match="bounds"):
            segplan.pose_in_bounds(START, L, bad)
    assert geo.check_bounds([0, 0, 3, 2]) == (0.0, 0.0, 3.0, 2.0)


def test_segment_predicate_tolerance_is_explicit():
    square = geo.ConvexPolygon([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    a, b = (1.0 + 1e-10, 0.2), (2.0, 0.2)  # 1e-10 right of the square
    assert not geo.segment_hits_polygon(a, b, square)  # exact
    assert not geo.segment_hits_polygon(a, b, square, tol=1e-11)
    assert geo.segment_hits_polygon(a, b, square, tol=1e-9)  # within the tolerance: touching
    assert geo.segment_hits_polygon((1.0, 0.2), b, square)  # touching counts


def test_as_polygon_validates_by_default():
    """``as_polygon`` checks convexity unless told not to (``check=False``)."""
    from segplan.geometry import as_polygon

    dart = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.5], [1.0, 2.0]]
    with pytest.raises(ValueError, match="convex"):
        as_polygon(dart)
    assert len(as_polygon(dart, check=False)) == 4
