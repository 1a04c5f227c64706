"""One polygon validator for the whole package (issue 11), under near-degenerate polygons.

``segplan.collides``, ``segplan.make_scenario``, ``segplan.load_scenario`` (file text) and
``segplan.plan`` validate obstacles with :func:`segplan.floor.geometry.check_convex_polygon`
(turns within ``ANGLE_TOL = 1e-9`` rad of 0 or pi are collinear vertices; edges shorter
than ``LENGTH_TOL = 1e-12`` of the largest coordinate repeat a vertex). The property test
builds convex polygons directly (points on a circle in angular order, any vertex count)
and spoils them slightly: a duplicated vertex (exact or nearly), a point inserted on an
edge or just off it (a collinear run, a tiny turn either way), the ring closed by
repeating the first vertex, the orientation reversed (since issue 27 a collinear vertex and
a closing copy are dropped by every entry point alike, no longer refused). The convex validator and
``collides`` (the paper's test of convex polygons) accept and reject exactly the same
polygons; so do the three scenario entry points, which also take simple non-convex
polygons (issue 14, split by :mod:`segplan.floor.decompose`): every convex polygon, and a
non-convex one only if it is simple (shapely's ``is_valid``). Rejection names the polygon.

The segment and polygon predicates against shapely: ``polygons_overlap`` (exact, closed
polygons: lattice coordinates decide touching exactly, a gap of one ulp is apart) and the
planner's scalar ``segment_hits_edges`` with a tolerance (a segment within ``tol`` is a hit,
a hit lies within the polygon grown by ``tol`` with mitred corners; hand cases at exactly
``tol`` and one ulp past it, for each kind of separating axis and the bounding box).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import shapely
from hypothesis import event, example, given, settings
from hypothesis import strategies as st

import segplan
from segplan.floor import geometry as geo
from segplan.floor.random_floors import random_convex_polygon

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
    by_load = accepted(lambda: segplan.floor.scenario.loads_scenario(scenario_text(pts)))
    # the default planner without refining its plan (a straight union 2.5 km from the polygon:
    # refining it checks no input and took two thirds of this test's time)
    by_plan = accepted(lambda: segplan.plan(START, GOAL, [pts], L, refine=False))
    assert by_collides == by_validator  # the paper's collision test: convex polygons
    assert by_make == by_load == by_plan  # scenarios: any simple polygon
    if by_validator:
        assert by_make  # convex input is accepted as always
    elif by_make:  # a tiny notch: a simple non-convex polygon, split into convex pieces
        assert shapely.Polygon(pts).is_valid
        sc = segplan.make_scenario(segplan.Robot(L), START, GOAL, [pts])
        assert all(accepted(lambda p=p: geo.check_convex_polygon(p)) for p in sc.obstacles)


@pytest.mark.parametrize(
    ("pts", "kept"),
    [
        ([[0, 0], [1, 0], [0, 1]], 3),
        ([[0, 0], [1, 0], [1, 0], [0, 1]], None),  # duplicate
        # issue 27: a collinear vertex and a closing copy of the first are dropped, not refused
        ([[0, 0], [0.5, 0], [1, 0], [0, 1]], 3),  # collinear run
        ([[0, 0], [0.5, -1e-12], [1, 0], [0, 1]], 3),  # a turn of 4e-12 rad: below ANGLE_TOL, dropped
        ([[0, 0], [0.5, -1e-6], [1, 0], [0, 1]], 4),  # a turn of 4e-6 rad: a real vertex
        ([[0, 0], [1, 0], [0, 1], [0, 0]], 3),  # closed ring
        ([[0, 0], [1, 0], [2, 0], [3, 0], [3, 1], [0, 1], [0, 0]], 4),  # both, a straight run of three
        ([[0, 0], [2, 0], [1, 0], [1, 1]], None),  # doubles back: refused
    ],
)
def test_tolerances_are_the_stated_ones(pts, kept):
    ok = kept is not None
    assert accepted(lambda: geo.check_convex_polygon(pts)) is ok
    assert accepted(lambda: segplan.collides(FAR_UNION, pts)) is ok
    assert accepted(lambda: segplan.plan(START, GOAL, [pts], L)) is ok
    if ok:
        v = geo.check_convex_polygon(pts)
        assert len(v) == kept and geo._area2(v) > 0
        # the polygon is the same point set: dropping a collinear vertex moves nothing
        assert shapely.Polygon(v).symmetric_difference(shapely.Polygon(pts).buffer(0)).area < 1e-11


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
    from segplan.floor.geometry import as_polygon

    dart = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.5], [1.0, 2.0]]
    with pytest.raises(ValueError, match="convex"):
        as_polygon(dart)
    assert len(as_polygon(dart, check=False)) == 4


# -- the segment and polygon predicates against shapely --------------------------------------
# (issue 15's mutation run: polygons_overlap and segment_hits_edges had no targeted test)
def lattice_hull(points) -> list:
    """Counter-clockwise strict convex hull of integer points (monotone chain), or [] if flat."""
    pts = sorted(set(points))

    def half(seq):
        out = []
        for p in seq:
            while len(out) >= 2 and (
                (out[-1][0] - out[-2][0]) * (p[1] - out[-2][1])
                - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])
                <= 0
            ):
                out.pop()
            out.append(p)
        return out[:-1]

    hull = half(pts) + half(pts[::-1])
    return hull if len(hull) >= 3 else []


lattice_polygons = (
    st.lists(st.tuples(st.integers(0, 10), st.integers(0, 10)), min_size=3, max_size=12)
    .map(lattice_hull)
    .filter(bool)  # all points collinear: rare
)
UNIT = [(0, 0), (1, 0), (1, 1), (0, 1)]


# 150 examples: on a 10 x 10 lattice, touching (shared vertices, shared edges, a vertex on an
# edge) is common; the hand examples pin each kind and the one-sided separations.
@settings(max_examples=150)
@given(lattice_polygons, lattice_polygons)
@example(UNIT, [(1, 0), (2, 0), (2, 1), (1, 1)])  # a shared edge
@example(UNIT, [(1, 1), (2, 1), (2, 2)])  # a shared vertex
@example(UNIT, [(1, 0), (3, -1), (3, 2)])  # q's vertex on p's edge
@example(UNIT, [(0, 2), (1, 2), (1, 3)])  # apart along p's axis only
@example(UNIT, [(2, 0), (2, 2), (0, 2)])  # apart along q's (slanted) axis only: x + y = 2 vs 1 + 1
@example([(2, 0), (2, 2), (0, 2)], UNIT)  # ... and the other way round
@example([(0, 2), (2, 0), (2, 2)], [(0, 0), (1, 0), (1, 1), (0, 1)])  # touching at the corner (1, 1)
@example(UNIT, [(-1, -1), (3, -1), (3, 3), (-1, 3)])  # one inside the other
def test_polygons_overlap_agrees_with_shapely(p, q):
    """Integer coordinates: exact arithmetic, so touching is decided exactly (touching overlaps)."""
    p, q = geo.check_convex_polygon(p), geo.check_convex_polygon(q)
    want = shapely.Polygon(p).intersects(shapely.Polygon(q))
    assert geo.polygons_overlap(p, q) == want
    assert geo.polygons_overlap(q, p) == want


def test_polygons_overlap_at_one_ulp():
    """Closed polygons: a shared edge overlaps, a gap of one ulp does not (no tolerance)."""
    p = geo.check_convex_polygon(UNIT)
    x = math.nextafter(1.0, 2.0)
    apart = geo.check_convex_polygon([(x, 0.0), (2.0, 0.0), (2.0, 1.0), (x, 1.0)])
    touching = geo.check_convex_polygon([(1.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0)])
    assert not geo.polygons_overlap(p, apart) and not geo.polygons_overlap(apart, p)
    assert geo.polygons_overlap(p, touching) and geo.polygons_overlap(touching, p)
    # the slanted case: q's hypotenuse x + y = 2 + 4e-16 (the sum of two floats) misses p's corner
    y = math.nextafter(2.0, 3.0)
    q = geo.check_convex_polygon([(y, 0.0), (y, y), (0.0, y)])
    assert not geo.polygons_overlap(p, q) and not geo.polygons_overlap(q, p)
    assert shapely.Polygon(q).distance(shapely.Polygon(p)) > 0


def mitred(poly: np.ndarray, tol: float):
    """The polygon grown by ``tol`` with mitred corners (the intersection of its offset half-planes)."""
    return shapely.Polygon(poly).buffer(tol, join_style="mitre", mitre_limit=1e6)


@st.composite
def segments_near_polygons(draw):
    """A convex polygon (radius 0.3-5), a tolerance and a segment starting within ~3 tol of its boundary."""
    k = draw(st.integers(3, 9))
    r = draw(st.floats(0.3, 5.0))
    gaps = np.array(draw(st.lists(st.floats(0.2, 1.0), min_size=k, max_size=k)))
    ang = np.cumsum(gaps) / gaps.sum() * 2.0 * math.pi + draw(st.floats(0.0, 6.3))
    centre = np.array([draw(st.floats(-20.0, 20.0)), draw(st.floats(-20.0, 20.0))])
    poly = geo.check_convex_polygon(centre + r * np.column_stack((np.cos(ang), np.sin(ang))))
    tol = draw(st.floats(1e-3, 0.5)) * r
    # the start: a boundary point (a vertex, or a point of an edge), moved out by 0..3 tol
    i = draw(st.integers(0, len(poly) - 1))
    t = draw(st.sampled_from([0.0, 0.5, 1.0]) | st.floats(0.0, 1.0))
    p = poly[i] + t * (poly[(i + 1) % len(poly)] - poly[i])
    out = math.atan2(*(p - centre)[::-1]) + draw(st.floats(-1.2, 1.2))  # outwards, roughly
    a = p + draw(st.floats(0.0, 3.0)) * tol * np.array([math.cos(out), math.sin(out)])
    th = out + draw(st.floats(-1.8, 1.8))  # mostly away from the polygon: near-misses, not crossings
    length = draw(st.floats(1e-3, 3.0)) * r
    b = a + length * np.array([math.cos(th), math.sin(th)])
    return poly, tol, a, b


@settings(max_examples=200)  # ~60 % hits within tol, ~30 % apart; the edges by hand below
@given(segments_near_polygons())
def test_segment_hits_edges_within_tolerance_against_shapely(case):
    """The planner's scalar predicate with a tolerance (separating axes, ``tol > 0``):

    - never a miss: a segment within ``tol`` of the polygon (shapely's distance) is a hit;
    - never far off: a hit meets the polygon grown by ``tol`` with mitred corners (every
      separating axis is a unit edge normal or the segment's normal, so an answer "apart"
      needs a separation above ``tol`` on one of them; the mitred polygon is what no axis
      separates by more than ``tol`` from the polygon's own edge half-planes).
    """
    poly, tol, a, b = case
    P = geo.ConvexPolygon(poly)
    hit = geo.segment_hits_edges(float(a[0]), float(a[1]), *(b - a).tolist(), geo.edge_list(P), tol)
    seg = shapely.LineString([a, b])
    scale = 1e-9 * (1.0 + np.abs(poly).max())
    dist = seg.distance(shapely.Polygon(poly))
    if dist <= tol - scale:
        event("within tol: a hit")
        assert hit, f"missed a segment at {dist:.6g} <= tol {tol:.6g}"
    elif seg.distance(mitred(poly, tol)) > scale:
        event("outside the mitred polygon: apart")
        assert not hit, f"a hit at {dist:.6g} (tol {tol:.6g}) outside the mitred polygon"
    else:
        event("between: either answer")
    # the array path decides the same (the same separating axes, the same order)
    assert hit == geo.segment_hits_polygon(a, b, P, tol=tol)


SQUARE = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]


def hits(a, b, poly, tol) -> bool:
    return geo.segment_hits_edges(
        a[0], a[1], b[0] - a[0], b[1] - a[1], geo.edge_list(geo.ConvexPolygon(poly)), tol
    )


def test_segment_hits_edges_at_the_tolerance_edges():
    """Exactly representable cases: a separation of exactly ``tol`` touches, one ulp more is apart."""
    tol, above = 0.25, math.nextafter(1.25, 2.0)
    # 1. an edge normal separates: a segment parallel to the top edge, at distance tol
    assert hits((0.25, 1.25), (0.75, 1.25), SQUARE, tol)
    assert not hits((0.25, above), (0.75, above), SQUARE, tol)
    assert not hits((0.25, 1.25), (0.75, 1.25), SQUARE, math.nextafter(tol, 0.0))
    # 2. only the segment's normal separates: direction (6, 8), its line 0.25 from the vertex (1, 0)
    a, b = (-1.6875, -4.0), (4.3125, 4.0)
    assert shapely.LineString([a, b]).distance(shapely.Polygon(SQUARE)) == pytest.approx(0.25, abs=1e-15)
    assert hits(a, b, SQUARE, tol)
    assert not hits(a, b, SQUARE, math.nextafter(tol, 0.0))
    assert hits(a, b, SQUARE, 0.2500001) and not hits(a, b, SQUARE, 0.2499999)
    # 3. the mitred corner counts as touching: 0.25 from both edges of the corner (1, 1) is
    # 0.354 from the square, yet no axis separates by more than 0.25 (conservative, never a miss)
    a, b = (1.25, 1.25), (3.0, 1.25)
    assert shapely.LineString([a, b]).distance(shapely.Polygon(SQUARE)) > tol
    assert hits(a, b, SQUARE, tol)
    assert not hits(a, b, SQUARE, 0.24)
    # 4. the bounding box rejects what the axes alone would not: beyond the acute corner (1, 0)
    # of a right triangle, 0.5 tol below its base, more than tol right of its box
    tri = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]
    a, b = (1.375, -0.125), (1.55, -0.125)
    assert shapely.LineString([a, b]).distance(shapely.Polygon(tri)) > tol
    assert shapely.LineString([a, b]).intersects(mitred(np.array(tri), tol))  # inside the mitre
    assert not hits(a, b, tri, tol)
    assert hits((1.25, -0.125), b, tri, tol)  # its end on the box's grown edge: not rejected
    # 5. a segment across the polygon, with both ends outside every edge's band
    assert hits((-5.0, 0.5), (5.0, 0.5), SQUARE, tol)
    assert hits((0.5, 0.5), (0.6, 0.5), SQUARE, tol)  # inside, both ends


@pytest.mark.parametrize(
    ("pts", "pattern"),
    [
        ([[0, 0], [2, 0], [1, 0], [1, 1]], r"vertex 1 \[2.0, 0.0\] doubles back"),
        ([[0, 0], [1, 0], [2, 0], [1, 1], [1, 0.5]], r"turns clockwise at vertex 4 \[1.0, 0.5\]"),
        (
            [[0, 0], [2, 0], [2, 2], [1, 0.5], [0, 2]],
            r"turns clockwise at vertex 3 \[1.0, 0.5\] but counter-clockwise at vertex 0",
        ),
        (
            [[0, 0], [0, 2], [1, 0.5], [2, 2], [2, 0]],
            r"turns counter-clockwise at vertex 2 \[1.0, 0.5\] but clockwise at vertex 0",
        ),
    ],
)
def test_rejection_says_what_is_wrong(pts, pattern):
    """The validator's message names the vertex and the fault: a vertex that doubles back is
    not "collinear", and a dent is named by the sense it turns against the rest of the ring."""
    with pytest.raises(ValueError, match=pattern):
        geo.check_convex_polygon(pts)


def test_a_figure_eight_is_named_by_its_larger_lobe():
    """A ring that turns through 0 in all (a bow tie) has no sense of its own: the validator
    takes that of its larger lobe (the sign of its area; GEOS's orientation agrees), so the
    smaller lobe's vertices are named as turning against it."""
    bow_tie = [[3.0, -2.0], [3.0, 2.0], [-1.0, -0.5], [-1.0, 0.5]]  # lobes of area 4.8 and 1.2
    ring = shapely.LinearRing(bow_tie)
    assert not ring.is_simple and ring.is_ccw
    with pytest.raises(ValueError, match=r"turns clockwise at vertex 2 .* but counter-clockwise at vertex 0"):
        geo.check_convex_polygon(bow_tie)
    with pytest.raises(ValueError, match=r"turns counter-clockwise at vertex 0 .* but clockwise at vertex 2"):
        geo.check_convex_polygon(bow_tie[::-1])


def test_a_ring_closed_by_repeating_its_first_vertex_is_opened_and_other_repeats_refused():
    """A closing copy of the first vertex (GeoJSON, WKT, CAD) is dropped (issue 27); a vertex
    repeated elsewhere is still refused, naming both."""
    closed = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [0.0, 0.0]]
    assert geo.check_convex_polygon(closed).tolist() == closed[:4]
    with pytest.raises(ValueError, match=r"vertex 3 repeats vertex 1 \[2.0, 0.0\]$"):
        geo.check_convex_polygon([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]])


def test_a_polygon_made_without_checks_has_float_vertices():
    """``ConvexPolygon(..., check=False)`` (the caller vouches for convexity) still stores
    float vertices, from integer ones too."""
    p = geo.ConvexPolygon([[0, 0], [2, 0], [0, 2]], check=False)
    assert p.vertices.dtype == np.float64 and p.vertices.tolist() == [[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]]


@pytest.mark.parametrize("check", [True, False])
def test_a_polygons_circle_is_its_bounding_boxs_centre_and_farthest_vertex(check):
    """``centre``: the bounding box's centre; ``radius``: the farthest vertex from it (the
    paper's ``r_max``), against shapely's box and distances."""
    rng = np.random.default_rng(4)
    for _ in range(20):
        pts = random_convex_polygon(rng, tuple(rng.uniform(-50.0, 50.0, 2)), float(rng.uniform(0.1, 10.0)), 8)
        p = geo.ConvexPolygon(pts, check=check)
        shape = shapely.Polygon(pts)
        x0, y0, x1, y1 = shape.bounds
        assert p.centre == pytest.approx((0.5 * (x0 + x1), 0.5 * (y0 + y1)), abs=1e-12)
        centre = shapely.Point(p.centre)
        far = max(centre.distance(shapely.Point(q)) for q in pts)
        assert p.radius == pytest.approx(far, rel=1e-12)
        assert p.box == pytest.approx(shape.bounds, abs=0.0)


def test_the_touching_tolerance_is_relative_to_the_scene():
    """Scaling the scene (the segment, the polygon's circle, their place) scales it."""
    base = geo.touch_tolerance(1.0, -2.0, 1.5, (3.0, 0.5), 0.8)
    assert base > 0.0
    for k in (1e-3, 10.0, 1e4):
        scaled = geo.touch_tolerance(k * 1.0, k * -2.0, k * 1.5, (k * 3.0, k * 0.5), k * 0.8)
        assert scaled == pytest.approx(k * base, rel=1e-12)
