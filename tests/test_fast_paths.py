"""The planner's scalar fast paths (issue 3, speed) give the values of the general code.

Each fast path is compared with the general function it replaces, on random and on
boundary cases: bit for bit where the fast path performs the same floating-point
operations, to rounding where it cannot (the heuristic frame's scalar and array paths).
"""

import math

import numpy as np
import pytest

from segplan import Union, random_world
from segplan.floor import collision
from segplan.floor.geometry import (
    ConvexPolygon,
    edge_list,
    pose_collides,
    pose_conflict,
    segment_hits_edges,
    segment_hits_polygon,
    touch_tolerance,
)
from segplan.model import cost
from segplan.model.cost import longd_intrinsic_scalar
from segplan.model.frame import _exponents, _features, heuristic_alpha, heuristic_coefficients
from segplan.model.pose import Pose, alpha_interval, intrinsic, intrinsic_interval
from segplan.planning.links import LONGD_RTOL, PREFETCH_MIN_HEURISTIC, LinkModel
from segplan.planning.validity import Workspace


def _random_cases(n, seed, wide=1.5):
    """``(d, phi0, phi1, alpha, L)`` with a feasible alpha."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        d, L = float(rng.uniform(0.3, 30.0)), float(rng.uniform(0.5, 2.0))
        p0, p1 = (float(v) for v in rng.uniform(-wide, wide, 2))
        lo, hi = alpha_interval(p0, p1)
        if hi - lo > 1e-6:
            out.append((d, p0, p1, float(rng.uniform(lo, hi)), L))
    return out


@pytest.mark.parametrize("shape", [(), (1,), (7,), (3, 4)])
def test_features_equal_the_monomials_bit_for_bit(shape):
    rng = np.random.default_rng(0)
    p0, p1, ell = rng.uniform(-1.5, 1.5, shape), rng.uniform(-1.5, 1.5, shape), rng.uniform(-2, 5, shape)
    s, q = 0.5 * (p0 + p1), (0.5 * (p0 - p1)) ** 2
    for degree in (3, 5):
        ref = np.stack([s**i * q**j * ell**k for i, j, k in _exponents(degree)], axis=-1)
        got = _features(p0, p1, ell, degree)
        assert got.shape == ref.shape and got.flags.c_contiguous
        assert np.array_equal(got, ref)
        coef = rng.normal(size=ref.shape[-1])
        assert np.array_equal(got @ coef, ref @ coef)


def test_heuristic_scalar_path_matches_array_path():
    fit = heuristic_coefficients()
    cases = _random_cases(400, 1)
    d, p0, p1, _, L = (np.array(v) for v in zip(*cases, strict=True))
    arr = heuristic_alpha(d, p0, p1, L, fit=fit)
    one = np.array([heuristic_alpha(a, b, c, e, fit=fit) for a, b, c, _, e in cases])
    np_one = np.array([heuristic_alpha(np.float64(a), b, c, e, fit=fit) for a, b, c, _, e in cases])
    assert np.array_equal(one, np_one)  # plain floats and numpy scalars: the same scalar path
    assert np.max(np.abs(one - arr)) < 1e-12


def test_intrinsic_fast_path_equals_array_path():
    rng = np.random.default_rng(2)
    specials = [math.pi, -math.pi, 3 * math.pi, 0.0, 2 * math.pi, 7 * math.pi / 2, -1e-300]
    for i in range(3000):
        a = [float(v) for v in rng.uniform(-50, 50, 3)]
        b = [float(v) for v in rng.uniform(-50, 50, 3)]
        if i % 5 == 0:
            a[2], b[2] = float(rng.choice(specials)), float(rng.choice(specials))
        p0, p1 = (Pose(*a), Pose(*b)) if i % 2 else (tuple(a), tuple(b))
        fast = intrinsic(p0, p1)
        batch = intrinsic(np.array([a]), np.array([b]))  # the array path
        assert all(type(v) is float for v in fast)
        assert tuple(fast) == tuple(float(v[0]) for v in batch)
    with pytest.raises(ValueError, match="coincident"):
        intrinsic((1.0, 2.0, 0.0), (1.0, 2.0, 1.0))
    with pytest.raises(ValueError, match="finite"):
        intrinsic((1.0, math.nan, 0.0), (3.0, 2.0, 1.0))
    with pytest.raises(ValueError):
        intrinsic((1.0, 2.0), (3.0, 2.0, 1.0))


def test_intrinsic_interval_equals_intrinsic_and_alpha_interval():
    """pose.intrinsic_interval (the link model's scalar path: math module, wrap_fmod) gives the
    array path's intrinsic parameters and alpha interval (shrunk by the margin) to rounding,
    and None exactly where the interval is empty."""
    rng = np.random.default_rng(5)
    margin = 1e-9
    empty = 0
    for i in range(3000):
        a = tuple(float(v) for v in rng.uniform(-50, 50, 3))
        b = tuple(float(v) for v in rng.uniform(-50, 50, 3))
        p0, p1 = (Pose(*a), Pose(*b)) if i % 2 else (a, b)
        got = intrinsic_interval(p0, p1, margin)
        ref = intrinsic(np.array([a]), np.array([b]))
        lo, hi = alpha_interval(ref.phi0, ref.phi1)
        lo, hi = float(lo[0]) + margin, float(hi[0]) - margin
        if not hi - lo > 1e-12:
            empty += 1
            assert got is None or got[5] - got[4] < 1e-12
            continue
        assert got is not None
        expected = (float(ref.d[0]), float(ref.psi[0]), float(ref.phi0[0]), float(ref.phi1[0]), lo, hi)
        assert got == pytest.approx(expected, rel=1e-12, abs=1e-12)
    assert 100 < empty < 2900  # both kinds of pair were drawn
    assert intrinsic_interval((1.0, 2.0, 0.0), (1.0, 2.0, 1.0)) is None  # coincident points
    assert intrinsic_interval((0.0, 0.0, 0.0), (1.0, 0.0, math.pi)) is None  # goal heading back


def test_scalar_segment_test_equals_the_array_test_and_pose_collides():
    """geometry.segment_hits_edges (scalar) makes the decisions of the array path, with tolerance."""
    rng = np.random.default_rng(3)
    world = random_world(5, 10)
    hits = near = 0
    for poly in world.enlarged:
        c_poly = ConvexPolygon(poly, check=False)
        v = c_poly.vertices
        edges = edge_list(c_poly)
        c, r = v.mean(axis=0), 2.0 * float(np.abs(v - v.mean(axis=0)).max())
        for j in range(300):
            a = c + rng.uniform(-r, r, 2)
            if j % 3 == 0:  # start on a vertex or an edge: touching cases
                k = int(rng.integers(len(v)))
                a = v[k] + (float(rng.random()) if j % 2 else 0.0) * (v[(k + 1) % len(v)] - v[k])
            if j % 7 == 0:  # just off a vertex, within or beyond the tolerance
                k = int(rng.integers(len(v)))
                a = v[k] + c_poly.normals[k] * float(rng.choice([1e-12, 1e-9, 1e-8, 1e-6]))
            th = float(rng.uniform(-math.pi, math.pi))
            A = (float(a[0]), float(a[1]))
            dx, dy = 1.2 * math.cos(th), 1.2 * math.sin(th)
            tol = touch_tolerance(A[0], A[1], 1.2, c_poly.centre, c_poly.radius)
            expected = segment_hits_polygon(A, (A[0] + dx, A[1] + dy), c_poly, tol)
            assert segment_hits_edges(A[0], A[1], dx, dy, edges, tol) == expected
            assert pose_collides((A[0], A[1], th), 1.2, c_poly) == expected
            exact = segment_hits_polygon(A, (A[0] + dx, A[1] + dy), v)
            assert expected or not exact  # the tolerance only adds touching cases
            near += expected != exact
            hits += expected
    assert hits > 100


def test_workspace_pose_free_is_the_one_pose_predicate():
    """Workspace.pose_free (scalar) agrees with geometry.pose_conflict, also at near-touches."""
    world = random_world(11, 10)
    ws = Workspace(world.enlarged, world.robot.L, world.free_bounds, world.robot.max_curvature)
    rng = np.random.default_rng(8)
    x0, y0, x1, y1 = world.free_bounds
    L = world.robot.L
    # the oracle on polygon objects built once (given arrays, pose_conflict builds them on
    # every call: that was two thirds of this test's time); the same predicate
    polygons = [ConvexPolygon(p, check=False) for p in world.enlarged]
    free = 0
    for j in range(3000):
        p = Pose(
            float(rng.uniform(x0 - 1, x1 + 1)), float(rng.uniform(y0 - 1, y1 + 1)), float(rng.uniform(-3, 3))
        )
        if j % 4 == 0:  # B just at a wall, or A just at an enlarged vertex
            poly = world.enlarged[int(rng.integers(len(world.enlarged)))]
            vx, vy = poly[int(rng.integers(len(poly)))]
            eps = float(rng.choice([-1e-9, 0.0, 1e-9, 1e-6]))
            p = Pose(float(vx) + eps, float(vy), p.theta) if j % 8 else Pose(x1 - L + eps, p.y, 0.0)
        expected = pose_conflict(p, L, polygons, world.free_bounds) is None
        assert ws.pose_free(p) == expected
        if j % 4 == 0 or j % 10 == 1:  # Scenario.is_free: pose_conflict on the arrays (its wiring)
            assert world.is_free(p) == expected
        free += expected
    assert 300 < free < 2700


def test_scalar_longd_equals_cost_module_bit_for_bit():
    for d, p0, p1, alpha, L in _random_cases(300, 4):
        for rtol in (LONGD_RTOL, 1e-8):
            assert longd_intrinsic_scalar(d, p0, p1, alpha, L, rtol) == float(
                cost.longd_intrinsic(d, p0, p1, alpha, L, rtol=rtol)
            )


def test_workspace_caches_give_the_uncached_answers():
    world = random_world(7, 10)
    ws = Workspace(world.enlarged, world.robot.L, world.free_bounds, world.robot.max_curvature)
    links = LinkModel(ws)
    rng = np.random.default_rng(5)
    n_polygons = len(ws.polygons)
    checked = 0
    for _ in range(60):
        p0 = Pose(float(rng.uniform(1, 29)), float(rng.uniform(1, 19)), float(rng.uniform(-3, 3)))
        u = links.union(p0, world.goal)
        if u is None:
            continue
        checked += 1
        fresh = Workspace(
            world.enlarged, world.robot.L, world.free_bounds, world.robot.max_curvature, cache=False
        )
        only = [int(i) for i in rng.permutation(n_polygons)[: int(rng.integers(1, n_polygons + 1))]]
        # the same questions twice (the second time from the cache) and in another order
        for _ in range(2):
            assert ws.colliding(u, only=only) == fresh.colliding(u, only=only)
            assert ws.colliding(u, first=False) == fresh.colliding(u, first=False)
            assert ws.colliding(u) == fresh.colliding(u)
            assert ws.curvature_ok(u) == fresh._curvature_ok(u)
            assert ws.in_bounds(u) == collision.union_in_bounds(u, world.free_bounds)
            truth = [i for i in range(n_polygons) if collision.collides(u, ws.convex[i], check=False)]
            assert ws.colliding(u, first=False) == sorted(truth, key=lambda i: ws.facts(u).near[i])
            expected = cost.longd_intrinsic(u.d, u.phi0, u.phi1, u.alpha, u.L, LONGD_RTOL)
            assert links.link_cost(u) == float(expected)
    assert checked > 20


def test_small_heuristic_batches_use_the_scalar_path():
    world = random_world(3, 10)
    ws = Workspace(world.enlarged, world.robot.L, world.free_bounds, world.robot.max_curvature)
    links = LinkModel(ws)
    pairs = [(Pose(2.0 + i, 3.0, 0.1 * i), world.goal) for i in range(4)]
    links.prefetch(pairs)
    assert ws.stats.batched == 0  # left to union(), pair by pair
    for p0, p1 in pairs:
        u = links.union(p0, p1)
        geo = intrinsic(p0, p1)
        assert u.alpha == pytest.approx(heuristic_alpha(geo.d, geo.phi0, geo.phi1, ws.L), abs=1e-12)


def test_large_heuristic_batches_give_the_scalar_paths_alphas():
    """From ``PREFETCH_MIN_HEURISTIC`` pairs on, the heuristic frame's array path batches them;
    each union then has the alpha of the scalar path (to rounding)."""
    world = random_world(3, 10)
    ws = Workspace(world.enlarged, world.robot.L, world.free_bounds, world.robot.max_curvature)
    links = LinkModel(ws)
    pairs = [
        (Pose(2.0 + 0.3 * i, 3.0 - 0.1 * i, 0.1 * i), world.goal) for i in range(PREFETCH_MIN_HEURISTIC + 2)
    ]
    links.prefetch(pairs)
    assert ws.stats.batched == len(pairs)
    for p0, p1 in pairs:
        u = links.union(p0, p1)
        geo = intrinsic(p0, p1)
        assert u is not None
        assert u.alpha == pytest.approx(heuristic_alpha(geo.d, geo.phi0, geo.phi1, ws.L), abs=1e-12)


def test_exact_frames_of_two_pairs_are_batched():
    """The exact method batches from two pairs on (its array path costs far less per pair):
    each union then has the alpha of one array call on the pairs not yet known."""
    from segplan.model.frame import optimal_alpha_intrinsic

    world = random_world(3, 10)
    ws = Workspace(world.enlarged, world.robot.L, world.free_bounds, world.robot.max_curvature)
    links = LinkModel(ws, alpha_method="exact")
    pairs = [(Pose(2.0, 3.0, 0.1), world.goal), (Pose(2.5, 2.0, -0.2), world.goal)]
    known = (Pose(1.0, 1.0, 0.0), world.goal)
    links.union(*known)  # known already: not batched again
    links.prefetch([known, pairs[0]])
    assert ws.stats.batched == 0  # one unknown pair: nothing to batch
    links.prefetch([known, *pairs])
    assert ws.stats.batched == 2
    geos = [intrinsic(p0, p1) for p0, p1 in pairs]
    d, phi0, phi1 = (np.array([getattr(g, k) for g in geos]) for k in ("d", "phi0", "phi1"))
    batch = optimal_alpha_intrinsic(d, phi0, phi1, ws.L, method="exact")
    for (p0, p1), a in zip(pairs, batch, strict=True):
        assert links.union(p0, p1).alpha == pytest.approx(float(a), abs=1e-12)


@pytest.mark.parametrize("origin", [(0.0, 0.0), (1e3, 0.0), (0.0, -1e3), (-1e3, 1e3)])
def test_link_model_coincidence_tolerance(origin):
    """Points closer than 1e-9 x max(1, |coordinates|) have no union; a little farther, one."""
    links = LinkModel(Workspace([], 1.0, None, 1.0))
    scale = max(1.0, *map(abs, origin))
    p0 = Pose(origin[0], origin[1], 0.0)
    for factor, exists in ((0.5, False), (1.5, True)):
        step = factor * 1e-9 * scale
        for p1 in (Pose(origin[0] + step, origin[1], 0.0), Pose(origin[0], origin[1] + step, math.pi / 2)):
            assert (links.union(p0, p1) is not None) == exists, (p1, factor)


def test_certain_hits_are_real_hits_near_obstacles():
    """The sampled certain-hit shortcut never claims an obstacle that the exact test clears.

    Unions pass close to obstacles (their ends near a vertex), so the broad phase keeps
    many pairs and the shortcut decides some of them: its answers, and the exact test's,
    are checked against :func:`segplan.floor.collision.collides` on every obstacle.
    """
    rng = np.random.default_rng(11)
    certain = near_misses = 0
    for seed in range(4):
        world = random_world(seed, 8)
        ws = Workspace(world.enlarged, world.robot.L, world.free_bounds, world.robot.max_curvature)
        links = LinkModel(ws)
        for _ in range(80):
            poly = world.enlarged[int(rng.integers(len(world.enlarged)))]
            v = poly[int(rng.integers(len(poly)))]
            heading = float(rng.uniform(-np.pi, np.pi))
            back, ahead = rng.uniform(0.5, 3.0, 2)
            p0 = Pose(v[0] - back * math.cos(heading), v[1] - back * math.sin(heading), heading)
            turn = heading + float(rng.uniform(-0.4, 0.4))
            p1 = Pose(v[0] + ahead * math.cos(turn), v[1] + ahead * math.sin(turn), turn)
            u = links.union(p0, p1)
            if u is None:
                continue
            truth = {i for i in range(len(ws.polygons)) if collision.collides(u, ws.convex[i], check=False)}
            before = ws.stats.certain_hits
            assert set(ws.colliding(u, first=False)) == truth
            certain += ws.stats.certain_hits - before
            near = ws.facts(u).near  # obstacles kept by the broad phase
            near_misses += sum(1 for i, x in near.items() if x is not None and i not in truth)
    assert certain > 20 and near_misses > 20  # both kinds of answer were exercised


@pytest.mark.parametrize("piece", [0, 8, 15])
@pytest.mark.parametrize("k", [20.0, 100.0, 200.0, 400.0])
def test_curvature_bound_uses_the_slopes_vertex(k, piece):
    """An S-curve whose slope's vertex lies inside a piece between the curvature samples.

    In the frame, ``f'(x) = k (x - x_v)^2`` (``x_v`` in the middle of piece ``piece`` of the
    16 between the 17 samples, the first and the last included): the
    curvature peaks on both sides of ``x_v``, between the samples, where ``|f'|`` is below
    its values at the piece's ends. The piecewise bound must use the least ``|f'|`` on the
    piece (at the vertex of the parabola ``f'``): with the ends' values only, it would pass
    a union whose curvature exceeds the limit. Checked just below and above the exact maximum.
    """
    X = 4.0
    xv = X * (piece + 0.5) / 16
    fX = k / 3.0 * ((X - xv) ** 3 + xv**3)
    p0 = Pose(0.0, 0.0, math.atan(k * xv**2))
    p1 = Pose(X, fX, math.atan(k * (X - xv) ** 2))
    u = Union(p0, p1, math.atan2(fX, X), 1.0)
    assert u.coefficients[3] == pytest.approx(k / 3.0, rel=1e-9)
    ref = u.max_curvature()
    assert not Workspace([], 1.0, None, ref * 0.999).curvature_ok(u)
    assert Workspace([], 1.0, None, ref * 1.001).curvature_ok(u)
