"""The conservative fallbacks of the collision test, forced and checked (issue 15).

Two certified subdivisions of the front-wheel path answer "collision" when they cannot
decide cheaply: ``_front_meets`` (event (iii) against an obstacle) and ``_front_reaches``
(the walls), once a piece's error bound falls below the tolerance or more than
``_FRONT_MAX_PIECES`` pieces are live. On random unions those branches almost never run,
so here they are forced: the certified sweep gets no refinement level (every near case
goes to the event test) and the subdivision no live piece. Against a dense
shapely sampling the forced answers must

* never miss a collision or a wall that the samples touch, and
* raise a false alarm only near the front-wheel path: a live piece has a lower bound of its
  distance below ``e = K h^2 / 8``; for the regular polygons used here (angles >= 60 deg)
  the path then lies within ``2 (e + l)`` of the polygon (``l``: a piece's chord) and within
  ``e`` of a wall.

The forced fallback must also have raised false alarms (else nothing was exercised).
"""

import math
from contextlib import contextmanager

import numpy as np
import shapely
from test_collision import N_DENSE, dense_collides, ngon, random_union, segments_at

from segplan import union_in_bounds
from segplan.floor import collision as col


# -- the reach into internals ------------------------------------------------------------------
@contextmanager
def forced_fallbacks():
    """No sweep refinement and no live front piece allowed (internal constants)."""
    saved = col._SWEEP_LEVELS, col._FRONT_MAX_PIECES
    col._SWEEP_LEVELS, col._FRONT_MAX_PIECES = 0, 0
    try:
        yield
    finally:
        col._SWEEP_LEVELS, col._FRONT_MAX_PIECES = saved


def first_level(u):
    """``(e, l)`` of the first level of the front-wheel subdivision (internal)."""
    sw = col.Sweep(u)
    h = 1.0 / col._FRONT_PIECES
    B = sw.front(np.linspace(0.0, 1.0, col._FRONT_PIECES + 1))
    return sw.K * h * h / 8.0, float(np.hypot(*np.diff(B, axis=0).T).max())


def front_path(u, n=N_DENSE):
    _, B = segments_at(u, u.xs(n))
    return B


# -- obstacles -------------------------------------------------------------------------------------
def outer_side(rng, u):
    """A random point of the front-wheel path (away from its ends) and the unit normal there
    on the outer side of the front wheel's turn (where the front wheel meets an obstacle first)."""
    B = front_path(u, 201)
    i = int(rng.integers(20, 181))
    t = B[i + 1] - B[i - 1]
    t /= np.hypot(*t)
    (ax, ay), (bx, by) = B[i] - B[i - 1], B[i + 1] - B[i]
    return B[i], np.array([t[1], -t[0]]) * (1.0 if ax * by - ay * bx > 0 else -1.0)


def near_front_cases(seed, n):
    """Unions and regular polygons placed next to the front-wheel path (some overlapping it)."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        u = random_union(rng)
        point, nrm = outer_side(rng, u)
        r = u.L * rng.uniform(0.2, 1.0)
        gap = u.L * 10.0 ** rng.uniform(-7.0, -1.5) * rng.choice([-1.0, 1.0, 1.0, 1.0])  # near-touches
        centre = point + nrm * (r + gap)
        yield u, ngon(centre, r, int(rng.integers(3, 9)), rng.uniform(0, 2 * math.pi))


def test_forced_front_fallback_never_misses_and_alarms_only_near():
    alarms = 0
    for u, poly in near_front_cases(7, 150):
        truth = dense_collides(u, poly)
        with forced_fallbacks():
            forced = col.collides(u, poly)
        if truth:
            assert forced, "forced fallback missed a collision"
        elif forced:
            alarms += 1
            e, ln = first_level(u)
            d = shapely.distance(shapely.LineString(front_path(u)), shapely.Polygon(poly))
            assert d <= 2.0 * (e + ln) + 1e-9, (d, e, ln)
            assert not col.collides(u, poly)  # unforced, the same case is decided free
    assert alarms >= 10  # the conservative branch ran and answered "collision"


def near_wall_cases(seed, n):
    """Unions and bounds with one wall next to the front-wheel path's extreme (some crossing it)."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        u = random_union(rng)
        A, B = segments_at(u, u.xs(201))
        pts = np.vstack((A, B))
        lo, hi = pts.min(axis=0) - u.L, pts.max(axis=0) + u.L
        side = int(rng.integers(4))
        axis, top = side % 2, side >= 2
        reach = B[:, axis].max() if top else B[:, axis].min()
        delta = u.L * rng.uniform(-0.01, 0.1)
        if top:
            hi[axis] = reach + delta
        else:
            lo[axis] = reach - delta
        yield u, (lo[0], lo[1], hi[0], hi[1])


def test_forced_wall_fallback_never_misses_and_alarms_only_near():
    alarms = 0
    for u, bounds in near_wall_cases(11, 150):
        A, B = segments_at(u, u.xs(N_DENSE))
        pts = np.vstack((A, B))
        xmin, ymin, xmax, ymax = bounds
        clearance = min(
            (pts[:, 0] - xmin).min(),
            (xmax - pts[:, 0]).min(),
            (pts[:, 1] - ymin).min(),
            (ymax - pts[:, 1]).min(),
        )
        with forced_fallbacks():
            forced = union_in_bounds(u, bounds)
        if clearance <= 0.0:
            assert not forced, "forced fallback let a union through a wall"
        elif not forced:
            alarms += 1
            e, _ = first_level(u)
            assert clearance <= e + 1e-9 * (1 + abs(xmax) + abs(ymax)), (clearance, e)
            assert union_in_bounds(u, bounds)  # unforced: inside
    assert alarms >= 5


# -- the front-wheel subdivision, unforced, against thin wedges -----------------------------------
@contextmanager
def events_only():
    """No sweep refinement (internal constant): every near case goes to the event test."""
    saved = col._SWEEP_LEVELS
    col._SWEEP_LEVELS = 0
    try:
        yield
    finally:
        col._SWEEP_LEVELS = saved


def wedge(tip, axis, half_angle, length) -> np.ndarray:
    """A thin triangle (counter-clockwise) with its sharp tip at ``tip``, pointing against ``axis``."""
    a = math.atan2(axis[1], axis[0])
    sides = (a - half_angle, a + half_angle)
    pts = [tip] + [tip + length * np.array([math.cos(b), math.sin(b)]) for b in sides]
    return np.array(shapely.geometry.polygon.orient(shapely.Polygon(pts), 1).exterior.coords[:-1])


def test_front_subdivision_separates_a_thin_wedge_by_its_chords():
    """A 4-degree wedge whose tip nearly touches the front-wheel path (outside it).

    Its edge normals barely separate it from a piece of the path: the piece's chord (its
    unit normal) must. The subdivision then decides every case exactly (no false alarm
    at gaps of 1e-4 L and more, no miss).
    """
    rng = np.random.default_rng(5)
    decided = 0
    for _ in range(60):
        u = random_union(rng)
        point, nrm = outer_side(rng, u)
        for gap in (1e-4, 1e-3, 1e-2):
            poly = wedge(point + nrm * gap * u.L, nrm, math.radians(2.0), u.L)
            truth = dense_collides(u, poly)
            with events_only():
                assert col.collides(u, poly) == truth, (gap, truth)
            decided += not truth
    assert decided > 100  # most wedges are free: the false alarms were the risk
