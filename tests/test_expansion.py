"""Graph expansion: intermediate nodes near obstacle vertices and turn states (issue 3).

Oracles: scipy's clamped CubicSpline, brute-force geometry, a dense shapely sampling of
the swept segment, and the exact LONGD [1].
"""

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.interpolate import CubicSpline

import segplan
from segplan import Robot, make_scenario
from segplan.floor.random_floors import random_convex_polygon
from segplan.model.cost import longd_exact
from segplan.model.pose import Pose
from segplan.planning.paper.bisectrix import clamped_spline_tangent, outward_bisectors, tangent_vertices
from segplan.planning.paper.expansion import Expander
from segplan.planning.validity import Workspace

L = 1.2
KAPPA = math.tan(math.radians(45.0)) / L
BOX = np.array([[4.0, -1.0], [8.0, -1.0], [8.0, 1.0], [4.0, 1.0]])
TRIANGLE = np.array([[4.0, -1.5], [7.0, -1.0], [5.0, 1.0]])
DIAMOND = np.array([[4.0, 0.0], [5.5, -1.2], [7.0, 0.0], [5.5, 1.2]])


def swept_hits(union, polygon, n=400) -> bool:
    """Dense shapely check: does the sampled swept segment touch the polygon?"""
    a, b = union.rear(n), union.front(n)
    poly = shapely.Polygon(polygon)
    segs = shapely.linestrings(np.stack((a, b), axis=1))
    return bool(
        np.any(shapely.intersects(poly, segs))
        or poly.intersects(shapely.LineString(a))
        or poly.intersects(shapely.LineString(b))
    )


def expander(obstacles, bounds=None, **kw):
    ws = Workspace(obstacles, L, bounds, KAPPA)
    return Expander(ws, **kw)


# -- geometry helpers ------------------------------------------------------------------
@settings(max_examples=40)
@given(
    st.lists(st.floats(-5, 5), min_size=4, max_size=4),
    st.floats(-math.pi, math.pi),
    st.floats(-math.pi, math.pi),
)
def test_clamped_spline_tangent_matches_scipy(xy, t0, t2):
    p0 = (0.0, 0.0, t0)
    mid = (xy[0], xy[1])
    p1 = (xy[2] + 6.0, xy[3], t2)
    h1 = math.hypot(mid[0] - p0[0], mid[1] - p0[1])
    h2 = math.hypot(p1[0] - mid[0], p1[1] - mid[1])
    if min(h1, h2) < 1e-3:
        return
    knots = [0.0, h1, h1 + h2]
    pts = np.array([p0[:2], mid, p1[:2]])
    cs = CubicSpline(
        knots,
        pts,
        bc_type=((1, np.array([math.cos(t0), math.sin(t0)])), (1, np.array([math.cos(t2), math.sin(t2)]))),
    )
    dx, dy = cs(h1, 1)
    got = clamped_spline_tangent(p0, mid, p1)
    assert abs(math.remainder(got - math.atan2(dy, dx), 2 * math.pi)) < 1e-9


def test_clamped_spline_tangent_rejects_coincident_points():
    with pytest.raises(ValueError, match="point"):
        clamped_spline_tangent((0, 0, 0), (0, 0), (1, 0, 0))


@settings(max_examples=30)
@given(st.integers(0, 10_000))
def test_bisectors_and_tangent_vertices_brute_force(seed):
    rng = np.random.default_rng(seed)
    poly = random_convex_polygon(rng, (0.0, 0.0), 2.0, 7)
    area2 = np.sum(poly[:, 0] * np.roll(poly[:, 1], -1) - np.roll(poly[:, 0], -1) * poly[:, 1])
    if area2 < 0:
        poly = poly[::-1]
    b = outward_bisectors(poly)
    shp = shapely.Polygon(poly)
    for i, v in enumerate(poly):
        # outward: a point a little along b is outside; equal angles with both edges
        assert not shp.contains(shapely.Point(v + 1e-3 * b[i]))
        e1 = poly[i - 1] - v
        e2 = poly[(i + 1) % len(poly)] - v
        a1 = math.acos(np.dot(-b[i], e1) / np.linalg.norm(e1))
        a2 = math.acos(np.dot(-b[i], e2) / np.linalg.norm(e2))
        assert abs(a1 - a2) < 1e-9
    point = rng.uniform(-8, 8, 2)
    if shp.distance(shapely.Point(point)) < 0.1:
        return
    ccw, cw = tangent_vertices(poly, point)
    for k, sign in ((ccw, 1.0), (cw, -1.0)):
        d = poly[k] - point
        cross = d[0] * (poly[:, 1] - point[1]) - d[1] * (poly[:, 0] - point[0])
        # every vertex lies clockwise of the ccw tangent (and vice versa)
        assert np.all(sign * cross <= 1e-9 * np.abs(poly).max() ** 2)


# -- intermediate nodes ------------------------------------------------------------------
@pytest.mark.parametrize("version", ["b", "a"])
@pytest.mark.parametrize("polygon", [BOX, TRIANGLE], ids=["box", "triangle"])
def test_intermediate_node_frees_both_unions(version, polygon):
    ex = expander([polygon], version=version)
    start, goal = Pose(0.0, 0.0, 0.0), Pose(12.0, 0.0, 0.0)
    direct = ex.direct(start, goal)
    assert ex.ws.colliding(direct) == [0]
    assert swept_hits(direct, polygon)
    found = 0
    for side in (1, -1):
        cand = ex.intermediate(start, goal, 0, side)
        assert 1 <= cand.iterations <= ex.max_iterations
        if not cand.ok:
            continue
        found += 1
        assert not swept_hits(cand.union_in, polygon)
        assert cand.union_in.p1 == cand.pose
        assert cand.union_in.max_curvature() <= KAPPA
        if cand.complete:
            # one node passes the obstacle: both new unions free of it (the paper's criterion)
            assert cand.union_out.p0 == cand.pose
            assert cand.union_out.max_curvature() <= KAPPA
            assert not swept_hits(cand.union_out, polygon)
        else:
            assert cand.union_out is None
        if version == "a" and cand.complete:
            # one reference system shared by both pieces (Fig. 4, top)
            assert math.isclose(
                math.remainder(cand.union_in.frame_angle - cand.union_out.frame_angle, 2 * math.pi),
                0.0,
                abs_tol=1e-9,
            )
        # the node is on the side asked for: left of the chord for side +1
        assert np.sign(cand.pose.y) == side
    assert found >= 1
    # every candidate's iterate count is recorded
    assert len(ex.stats.iterations) == 2
    assert all(1 <= it <= ex.max_iterations for it, _, _ in ex.stats.iterations)


def test_diamond_passed_by_one_node_in_few_iterates():
    """The paper: 'two or three iterates at the most are normally needed'."""
    ex = expander([DIAMOND])
    start, goal = Pose(0.0, 0.0, 0.0), Pose(12.0, 0.0, 0.0)
    cands = [ex.intermediate(start, goal, 0, side) for side in (1, -1)]
    assert all(c.ok and c.complete for c in cands)
    assert max(c.iterations for c in cands) <= 3


def test_long_obstacle_needs_a_chain_of_nodes():
    """A long box: the tangent vertices seen from start and goal differ, one node is not enough."""
    ex = expander([np.array([[3.0, -1.0], [10.0, -1.0], [10.0, 1.0], [3.0, 1.0]])])
    cand = ex.intermediate(Pose(0.0, 0.0, 0.0), Pose(13.0, 0.0, 0.0), 0, 1)
    assert cand.ok and not cand.complete
    assert cand.pose.x < 6.5  # near the first corner


@pytest.mark.parametrize(
    "start, goal",
    [
        ((0.0, 0.0, 0.6), (12.0, 0.0, -0.6)),
        ((0.0, -0.5, 0.0), (12.0, 1.0, 0.8)),
        ((0.0, 0.0, 0.0), (12.0, 0.0, 0.0)),
    ],
)
def test_version_b_is_no_worse_than_a(start, goal):
    """Fig. 4: one intermediate node joined in one shared frame (a) or one optimal frame per piece (b)."""
    start, goal = Pose(*start), Pose(*goal)
    ex_b = expander([BOX], version="b", steer_fallback=False, alpha_method="exact")
    ex_a = expander([BOX], version="a", alpha_method="exact")
    beta = ex_a.shared_frame(start, goal)
    compared = found = 0
    for side in (1, -1):
        cand = ex_b.intermediate(start, goal, 0, side)
        if not cand.ok:
            continue
        found += 1
        u1 = cand.union_in
        u2 = cand.union_out or ex_b.links.union(cand.pose, goal)
        if u2 is None:
            continue
        cost_b = longd_exact(u1.p0, u1.p1, u1.alpha, L) + longd_exact(u2.p0, u2.p1, u2.alpha, L)
        a1, a2 = ex_a.links.union(start, cand.pose, beta), ex_a.links.union(cand.pose, goal, beta)
        if a1 is None or a2 is None:
            continue  # no cubic in the shared frame: version a cannot use this node at all
        cost_a = longd_exact(a1.p0, a1.p1, a1.alpha, L) + longd_exact(a2.p0, a2.p1, a2.alpha, L)
        assert cost_b <= cost_a * (1 + 1e-3)
        compared += 1
    assert found >= 1 and compared >= 1  # at least one node compared in both versions


@pytest.mark.parametrize(
    "start, goal", [((0.0, -0.5, 0.0), (12.0, 1.0, 0.8)), ((0.0, 0.0, 0.5), (12.0, 1.0, 0.0))]
)
def test_version_a_shares_the_optimal_frame_of_the_direct_union(start, goal):
    """Version "a": the shared frame is the direct union's optimal frame (exact method: the
    frame of least LONGD [1], found here by a bounded scalar minimisation over the feasible
    interval), not the chord's, which costs more here."""
    from scipy.optimize import minimize_scalar

    from segplan.model.pose import intrinsic_interval

    start, goal = Pose(*start), Pose(*goal)
    beta = expander([BOX], version="a", alpha_method="exact").shared_frame(start, goal)
    _, psi, _, _, lo, hi = intrinsic_interval(start, goal)
    grid = np.linspace(lo, hi, 41)[1:-1]
    a0 = grid[np.argmin([longd_exact(start, goal, a, L) for a in grid])]
    step = (hi - lo) / 40
    best = minimize_scalar(
        lambda a: longd_exact(start, goal, a, L), bounds=(a0 - step, a0 + step), method="bounded",
        options={"xatol": 1e-10},
    )  # fmt: skip
    shared = longd_exact(start, goal, psi - beta, L)  # the direct union in the shared frame
    assert shared <= best.fun * (1 + 1e-9)
    assert longd_exact(start, goal, 0.0, L) > shared * 1.005  # the chord's frame is dearer


def test_iteration_counts_over_random_worlds():
    """Distribution of iterates of successful candidates: mostly one to three."""
    from segplan import random_world

    counts = []
    for seed in range(6):
        sc = random_world(seed, 8)
        ws = Workspace(sc.enlarged, sc.L, sc.free_bounds, sc.robot.max_curvature)
        ex = Expander(ws)
        u = ex.direct(sc.start, sc.goal)
        if u is None:
            continue
        for poly in ws.colliding(u, first=False):
            for side in (1, -1):
                ex.intermediate(sc.start, sc.goal, poly, side)
        counts += [it for it, ok, _ in ex.stats.iterations if ok]
    assert counts
    assert np.mean(np.array(counts) <= 3) >= 0.75


# -- difficult cases: turning around --------------------------------------------------------
def test_goal_behind_gives_turn_states():
    ex = expander([])
    start, goal = Pose(0.0, 0.0, 0.0), Pose(-4.0, 0.0, math.pi)
    assert ex.direct(start, goal) is None  # no alpha frame joins opposed headings
    succ = ex.successors(start, goal)
    assert succ and all(s.kind == "turn" for s in succ)
    for s in succ:
        assert s.union.p0 == start and s.union.p1 == s.pose
        assert s.union.max_curvature() <= KAPPA
        assert s.union.x_end > 0
    # no turn states when the caller forbids them
    assert ex.successors(start, goal, turns=False) == []


def test_turn_around_plan_forward_only():
    from segplan import plan

    result = plan((0.0, 0.0, 0.0), (0.0, 3.0, math.pi), [], L, bounds=(-6, -4, 8, 8), planner="paper")
    assert result.nodes[-1] == Pose(0.0, 3.0, math.pi)
    assert len(result.unions) >= 2
    assert "turn" in result.kinds
    for u in result.unions:
        assert u.max_curvature() <= KAPPA * (1 + 1e-9)
        a = u.rear(200)
        h = u.heading(u.xs(200))
        step = np.diff(a, axis=0)
        assert np.all(step[:, 0] * np.cos(h[:-1]) + step[:, 1] * np.sin(h[:-1]) > 0)  # forward


def test_successors_are_free_and_keyed():
    sc = make_scenario(Robot(L), (0.0, 0.0, 0.0), (12.0, 0.0, 0.0), [BOX], (-3, -6, 15, 6))
    ws = Workspace(sc.enlarged, L, sc.free_bounds, KAPPA)
    ex = Expander(ws)
    succ = ex.successors(sc.start, sc.goal)
    assert len(succ) == 2 and {s.kind for s in succ} == {"vertex"}
    assert len({s.key for s in succ}) == 2
    for s in succ:
        assert not swept_hits(s.union, sc.enlarged[0])
        assert ws.union_free(s.union)


def test_expander_rejects_bad_options():
    ws = Workspace([], L)
    for kw, name in (
        ({"version": "c"}, "version"),
        ({"alpha_method": "magic"}, "alpha_method"),
        ({"max_iterations": 0}, "max_iterations"),
        ({"r0": -1.0}, "r0"),
        ({"growth": 1.0}, "growth"),
        ({"spline_weight": 2.0}, "spline_weight"),
        ({"turn_angles": (4.0,)}, "turn_angles"),
    ):
        with pytest.raises(ValueError, match=name):
            Expander(ws, **kw)
    # the closed ends of the documented ranges are accepted
    for kw in (
        {"spline_weight": 0.0},
        {"spline_weight": 1.0},
        {"turn_angles": (math.pi / 2,)},
        {"max_iterations": 1},
    ):
        Expander(ws, **kw)


@settings(max_examples=60)
@given(
    st.floats(0.5, 10.0),
    st.floats(-5.0, 5.0),
    st.floats(-1.3, 1.3),
    st.floats(-1.3, 1.3),
    st.floats(-0.5, 0.5),
)
def test_curvature_check_agrees_with_union_max_curvature(x1, y1, t0, t1, alpha):
    """The workspace's steering check (cheap bounds first) against Union.max_curvature."""
    try:
        u = segplan.Union((0.0, 0.0, t0), (x1, y1, t1), alpha, 1.0)
    except ValueError:
        return
    ref = u.max_curvature()
    ws = Workspace([], 1.0, None, ref * 1.001)
    assert ws.curvature_ok(u)
    if ref > 1e-9:
        ws = Workspace([], 1.0, None, ref * 0.999)
        assert not ws.curvature_ok(u)


@settings(max_examples=60)
@given(
    st.floats(-20, 20),
    st.floats(-20, 20),
    st.floats(-math.pi, math.pi),
    st.floats(-math.pi, math.pi),
    st.floats(0.01, 0.99),
)
def test_union_from_intrinsic_equals_union(x1, y1, t0, t1, frac):
    """The planner's fast constructor (no validation) builds the same union."""
    from segplan.model.pose import alpha_interval, intrinsic

    p0, p1 = Pose(0.5, -0.25, t0), Pose(x1, y1, t1)
    if math.hypot(x1 - 0.5, y1 + 0.25) < 1e-3:
        return
    geo = intrinsic(p0, p1)
    lo, hi = alpha_interval(geo.phi0, geo.phi1)
    if not hi - lo > 1e-6:
        return
    alpha = lo + frac * (hi - lo)
    ref = segplan.Union(p0, p1, alpha, 1.3)
    fast = segplan.Union.from_intrinsic(p0, p1, alpha, 1.3, *geo)
    assert fast.p0 == ref.p0 and fast.p1 == ref.p1 and fast.alpha == ref.alpha and fast.L == ref.L
    assert np.allclose(
        fast.coefficients, ref.coefficients, rtol=1e-9, atol=1e-12 * max(1.0, *map(abs, ref.coefficients))
    )
    assert math.isclose(fast.x_end, ref.x_end, rel_tol=1e-12)
    assert np.allclose(fast.rear(50), ref.rear(50), atol=1e-9)
