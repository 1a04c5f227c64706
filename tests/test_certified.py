"""The certified screen (:mod:`segplan.planning.certified`) against the exact test and the dense
shapely oracle, and the refinement's restricted failure search against the full one.

A "free" of the screen must be the exact test's answer (``Workspace.in_bounds`` True,
``Workspace.colliding`` empty) and the truth (no densely sampled position touches an
obstacle or a wall); the screen may only give up, never decide otherwise. Worlds are random
unions among polygons of every kind of ``tests/test_collision.py`` (grazing, dipping, sharp
vertices, thin), put at distances from a touch to a few robot lengths, in walls from tight to
loose.
"""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_collision import KINDS, dense_collides, hull, random_polygon, random_union, segments_at

from segplan.floor import geometry as geo
from segplan.planning.certified import FreeScreen
from segplan.planning.refine import certain_failures
from segplan.planning.validity import VECTOR_SCREEN_MIN, Workspace


def random_world(seed: int):
    """A union, polygons near it (some pushed away by up to 3 L) and walls around it."""
    rng = np.random.default_rng(seed)
    u = random_union(rng)
    L = u.L
    polys = []
    while len(polys) < int(rng.integers(1, 7)):
        poly = random_polygon(rng, u, KINDS[int(rng.integers(len(KINDS)))])
        if rng.random() < 0.8:  # pushed away from the sweep along a random direction
            t = rng.uniform(0, 2 * math.pi)
            poly = poly + L * rng.choice([1e-3, 0.05, 0.3, 1.0, 3.0]) * np.array([math.cos(t), math.sin(t)])
        try:
            polys.append(geo.ConvexPolygon(poly).vertices)
        except ValueError:  # a degenerate hull
            continue
    pts = np.concatenate(segments_at(u, u.xs(201)))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    if rng.random() < 0.5:  # walls clear of the sweep by a tenth of L or more
        gap = L * rng.choice([0.1, 1.0], size=4)
    else:  # anything from crossing to grazing to loose
        gap = L * rng.choice([-0.05, 1e-9, 1e-6, 1e-3, 0.1, 1.0], size=4)
    bounds = (lo[0] - gap[0], lo[1] - gap[1], hi[0] + gap[2], hi[1] + gap[3])
    return u, polys, bounds


def dense_inside(u, bounds, n: int = 2001) -> bool:
    """Every sampled segment strictly inside the walls (a segment: both end points)."""
    pts = np.concatenate(segments_at(u, u.xs(n)))
    return bool(np.all(pts > bounds[:2]) and np.all(pts < bounds[2:]))


def check_world(u, polys, bounds) -> tuple[bool, bool]:
    """The screen's two answers on one world, each checked against the exact test and the oracle."""
    ws = Workspace(polys, u.L, bounds)
    screen = FreeScreen(ws)
    sw = ws.sweep(u)
    walls, obstacles = screen.walls_clear(sw), screen.obstacles_clear(sw)
    if walls:
        assert ws.in_bounds(u)
        assert dense_inside(u, bounds)
    if obstacles:
        assert ws.colliding(u, first=False) == []
        assert not any(dense_collides(u, p) for p in polys)
    exact = Workspace(polys, u.L, bounds, cache=False)
    assert screen.union_free(u) == exact.union_free(u)
    return walls, obstacles


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1))
def test_screen_free_is_the_exact_answer_and_the_truth(seed):
    check_world(*random_world(seed))


def test_screen_decides_most_clear_worlds():
    """Not vacuous: on fixed worlds the screen clears many unions, and each clearance checks out."""
    walls = obstacles = free = 0
    for seed in range(120):
        u, polys, bounds = random_world(seed)
        w, o = check_world(u, polys, bounds)
        walls += w
        obstacles += o
        free += Workspace(polys, u.L, None).union_free(u)
    assert walls >= 30 and obstacles >= free / 2 and free >= 10, (walls, obstacles, free)


def test_screen_gives_up_on_touching_and_crossing_obstacles():
    """A polygon across the sweep, or one grazing it within the touching tolerance: never cleared."""
    rng = np.random.default_rng(5)
    for _ in range(40):
        u = random_union(rng)
        A, B = segments_at(u, [0.5 * u.x_end])
        mid = 0.5 * (A[0] + B[0])
        square = mid + 0.05 * u.L * np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]])
        ws = Workspace([square], u.L, None)
        assert not FreeScreen(ws).obstacles_clear(ws.sweep(u))
        # walls through the middle of the sweep
        ws = Workspace([], u.L, (mid[0] - 100, mid[1] - 100, mid[0], mid[1] + 100))
        assert not FreeScreen(ws).walls_clear(ws.sweep(u))


def test_many_obstacles_use_the_index_and_agree():
    """Above ``VECTOR_SCREEN_MIN`` obstacles the screen examines those the index files near the
    sweep: the same answers as the exact test over all of them."""
    rng = np.random.default_rng(9)
    cleared = 0
    for _ in range(25):
        u = random_union(rng)
        pts = np.concatenate(segments_at(u, u.xs(201)))
        lo, hi = pts.min(axis=0) - 2 * u.L, pts.max(axis=0) + 2 * u.L
        polys = []
        while len(polys) <= VECTOR_SCREEN_MIN + 10:
            c = rng.uniform(lo, hi)
            polys.append(c + 0.08 * u.L * np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]))
        ws = Workspace(polys, u.L, None)
        screen = FreeScreen(ws)
        if screen.obstacles_clear(ws.sweep(u)):
            cleared += 1
            assert ws.colliding(u, first=False) == []
            assert not any(dense_collides(u, p) for p in polys)
        assert screen.union_free(u) == Workspace(polys, u.L, None, cache=False).union_free(u)
    assert cleared >= 1


def test_bad_workspace_is_refused():
    with pytest.raises(ValueError, match="workspace"):
        FreeScreen([np.zeros((3, 2))])


def test_certain_failures_only_looks_where_asked():
    """``only``: the links looked at get the answers of the full search (the same points, the
    same exact comparisons); the others are reported free at most where the full search is."""
    from segplan.model.frame import heuristic_alpha
    from segplan.model.pose import wrap
    from segplan.model.union import cubic_coefficients

    rng = np.random.default_rng(3)
    polys = [
        geo.ConvexPolygon(hull(rng.uniform(0, 10, 2) + rng.normal(size=(8, 2)))).vertices for _ in range(12)
    ]
    for n_obstacles in (len(polys), VECTOR_SCREEN_MIN + 1):
        obstacles = (polys * 8)[:n_obstacles]
        ws = Workspace(obstacles, 1.0, (-1.0, -1.0, 11.0, 11.0), max_curvature=1.0)
        A = np.column_stack((rng.uniform(0, 10, (300, 2)), rng.uniform(-math.pi, math.pi, 300)))
        B = np.column_stack((rng.uniform(0, 10, (300, 2)), rng.uniform(-math.pi, math.pi, 300)))
        d = np.hypot(*(B[:, :2] - A[:, :2]).T)
        psi = np.arctan2(B[:, 1] - A[:, 1], B[:, 0] - A[:, 0])
        phi0, phi1 = wrap(A[:, 2] - psi), wrap(B[:, 2] - psi)
        keep = (np.abs(phi0) < 1.2) & (np.abs(phi1) < 1.2) & (d > 0.5)
        A, d, psi, phi0, phi1 = A[keep], d[keep], psi[keep], phi0[keep], phi1[keep]
        alpha = heuristic_alpha(d, phi0, phi1, 1.0)
        cubic = cubic_coefficients(d, phi0, phi1, alpha)
        full = certain_failures(ws, A, psi - alpha, *cubic)
        assert 0 < full.sum() < len(full)
        only = rng.random(len(A)) < 0.5
        part = certain_failures(ws, A, psi - alpha, *cubic, only=only)
        assert np.array_equal(part[only], full[only])
        assert not np.any(part & ~full)


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1), st.floats(0.0, 1.0), st.floats(0.0, 1.0))
def test_screen_with_overhangs_is_the_exact_answer(seed, rear, front):
    """A robot with a body (issue 26): the sweep's points are the ends of the longer axis
    segment, and the screen's "free" is still the exact test's answer (the exact test with
    overhangs is checked against the dense body oracle in test_footprint_collision)."""
    u, polys, bounds = random_world(seed)
    rear, front = rear * u.L, front * u.L
    ws = Workspace(polys, u.L, bounds, rear=rear, front=front)
    screen = FreeScreen(ws)
    sw = ws.sweep(u)
    if screen.obstacles_clear(sw):
        assert ws.colliding(u, first=False) == []
    if screen.walls_clear(sw):
        assert ws.in_bounds(u)
    exact = Workspace(polys, u.L, bounds, cache=False, rear=rear, front=front)
    assert screen.union_free(u) == exact.union_free(u)
