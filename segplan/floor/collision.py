"""On-line collision detection of a union's swept segment with convex polygons.

Section "Collision-detection algorithm": "The inputs ... are the trajectory of the
reference point ... which includes a cubic polynomial and limiting abscissa, and the
obstacle modelled by a convex polygon. The output is a boolean variable which states if
there is collision or not, of some of the successive positions of the segment ... with
the polygon." The robot is the closed segment ``S(x) = [A(x), B(x)]``: the rear point
``A(x) = (x, f(x))`` on the union's cubic (alpha frame, ``x`` in ``[0, X]``) and the front
wheel ``B(x) = A(x) + L u(x)``, ``u = (1, f') / sqrt(1 + f'^2)``. Obstacles are closed
convex polygons; touching is a collision.

Quick checks (the paper's, applied first)
-----------------------------------------
* Box: the swept set lies in the frame rectangle ``[0, X + L] x [y_lo, y_hi]`` built from
  the extremes of ``f`` and of the direction ``u`` (closed forms: ``f'`` is a quadratic).
* ``d_c``: the paper's test "``d_c`` = minimum distance from the centre of the polygon to
  the cubic spline, ``r_max`` = maximum radius of the polygon, computed off-line, ``M`` =
  bound of the difference between the cubic and the trajectory of the front wheel ...
  (for ``M``, much better values than ``L`` can be found)". If ``d_c > r_max + M`` the
  polygon cannot be touched. The OCR prints ``d_c < r_max + M``; the inequality must be
  ``>`` for the sentence ("there can be no intersection") to hold, and that is what we
  implement. ``M = L`` is always valid (every point of ``S(x)`` is within ``L`` of
  ``A(x)``). The better value: a point ``A(x) + s u(x)`` (``0 <= s <= L``) has abscissa
  ``x + h`` with ``h = s / sqrt(1 + f'^2) <= L`` and its height differs from the cubic's
  at that abscissa by the Taylor remainder ``|f''(xi)| h^2 / 2``, so every point of the
  swept set is within ``M' = L^2 max|f''| / 2`` (max over ``[0, X + L]``) of the graph of
  the cubic *extended* to ``[0, X + L]``. We use the smaller of the two bounds with its
  curve. ``d_c`` itself is bounded from below by the distance to an inscribed polyline
  minus its chord error ``max|f''| dx^2 / 8``, so the test stays a rigorous rejection.

The exact test and why it is complete
-------------------------------------
The set ``{x : S(x) meets P}`` is closed (``S`` moves continuously, ``P`` is closed).
Suppose ``S(0)`` misses ``P`` but some ``S(x)`` meets it, and let ``x*`` be the first such
abscissa (``x* > 0``). ``S(x*)`` cannot contain a point of the *interior* of ``P``: the
interior is open, so slightly earlier positions would meet it too. A segment that meets
a convex polygon only on its boundary touches it either at one of its end points, or at
a polygon vertex, or lies along an edge, and then the contact set is a segment whose ends
are end points of ``S`` or vertices. Hence the first contact is one of

(i)   ``S(0)`` meets ``P`` (the start pose: one segment-polygon test);
(ii)  ``A(x*)`` on an edge: ``a_e(x) = n_e . A(x) - h_e = n_x x + n_y f(x) - h_e = 0``, a
      *cubic* in ``x`` for each edge ``e`` (outward unit normal ``n_e``, offset ``h_e``);
(iii) ``B(x*)`` on an edge: the front-wheel path meets ``P``;
(iv)  a vertex ``V`` on ``S(x*)``: ``V`` on the segment's line,
      ``cross(u, V - A) = 0``, i.e. ``h_V(x) = (V_y - f(x)) - f'(x) (V_x - x) = 0``, again a
      *cubic*; its derivative factors as ``h_V'(x) = (x - V_x) f''(x)``.

Each event is also sufficient for a collision, so: collision iff (i) or one of the events
happens at some ``x``. Identically vanishing event equations (a straight union lying on an
edge's line, or passing through a vertex) need no roots: the contact then starts at a
vertex, which is an event of an adjacent edge whose equation does not vanish, or at an end
point of the segment (events (ii), (iii)).

How we decide it: two stages
----------------------------
1. Certified sweep (fast, decides nearly every case). The positions at ``s = x / X`` on a
   grid of 32 pieces are tested exactly (separating axes); a touching position is a
   collision. Between two positions, every point ``P = A + t u`` of the segment
   (``P = (1 - t/L) A + (t/L) B``) moves on a curve within ``e = K dx^2 / 8`` of its chord,
   ``K`` a rigorous bound of ``|P''|`` on the piece and ``dx`` its length in ``x``, and
   that chord lies in the convex hull of the two segments. So the swept set of the piece
   lies in the hull (four points) grown by ``e``: if the separating-axis gap between the
   hull and the polygon (a lower bound of their distance; axes: the polygon's edge normals
   and the normals of the six point pairs) exceeds ``e``, the piece is free. Undecided
   pieces are halved three times. The bound: ``|P''| <= |A''| + L |u''|`` with
   ``A'' = (0, f'')``, ``u'' = theta'' n - theta'^2 u``, ``theta' = f'' / (1 + f'^2)``,
   ``|theta''| <= |f'''| + 2 (3 sqrt(3) / 16) f''^2`` (``|t| / (1 + t^2)^2 <= 3 sqrt(3) / 16``),
   so ``K = max|f''| + L (6 |c3| + 1.65 max|f''|^2)`` over the piece.
2. Event test (exact; for the cases the sweep leaves undecided, i.e. near-touches).
   Events (ii) and (iv) are cubics: their real roots (eigenvalues of the companion
   matrices, polished by Newton; the real part of a complex pair, the abscissa of a
   near-double root, is kept too) and their stationary points (for (ii) the paper's
   "points of the curve where the derivative is equal to the slope of the segment", here
   of the edge; for (iv) ``x = V_x`` and the inflection point; all in closed form, so that
   a grazing contact, a double root, is located accurately) are candidate abscissae, with
   both end poses; one separating-axis test per candidate decides. Event (iii), the
   front-wheel path: squaring ``n . B = h`` gives a degree-10 polynomial with spurious
   roots; we use a certified subdivision of the path instead (a piece within ``e`` of its
   chord, same ``K``, whose chord is farther than ``e`` from the polygon is free; a sample
   of ``B`` inside is a collision; others are halved until ``e`` reaches the tolerance,
   where the answer is a conservative "collision").

Footprints: overhangs (beyond the paper)
----------------------------------------
A robot with overhangs (:class:`segplan.Robot`: ``front_overhang`` beyond B,
``rear_overhang`` behind A) sweeps the longer axis segment ``S(x) = [R(x), F(x)]``,
``R = A - r u`` and ``F = A + (L + f) u``: a :class:`segplan.floor.sweep.Sweep` built with
``rear=r, front=f``. Its points ``A + t u`` (``-r <= t <= L + f``) are rigidly attached
to the robot, so the argument above carries over with A->B replaced by R->F: the first
contact is (i) the start pose, (ii') ``R(x*)`` on an edge, (iii) ``F(x*)`` on an edge,
or (iv) a vertex on ``S(x*)``, i.e. on the segment's line, which is the axis through A:
the same cubic ``h_V``. Only (ii') changes: ``R`` is no longer on the cubic (for ``r >
0``), so its path is decided like the front end's, by the certified subdivision (its bound
``K`` holds for every ``|t| <= reach = max(r, L + f)``, the curvature bounds of the sweep
and of ``M`` take ``reach`` for ``L``; the cubic candidates of (ii) are kept: each is
still decided by an exact position test). The walls likewise: both end paths, certified.

The body. The obstacles are enlarged off-line by the half-width ``w`` (a polygon that
contains the exact Minkowski sum with the disk of radius ``w``,
:func:`segplan.floor.geometry.enlarge_polygon`); so ``S(x)`` missing an enlarged obstacle
means the *rounded body* ``S(x) + disk(w)`` (the points within ``w`` of the axis segment,
the paper's "curved rectangle" when ``r = f = 0``) misses the obstacle itself, and this
test is exact for that body (up to the enlargement's polygonal excess, conservative). A
rectangular body ``[-r, L + f] x [-w, w]`` (``Robot(rectangle=True)``) lies inside the
rounded one: this test is conservative for it, pessimistic only where an obstacle enters
the two half-discs beyond its ends (``tests/test_footprint_collision.py`` proves the
absence of misses against a dense shapely oracle of the rectangle and measures how often
it is pessimistic). No tighter body of the form "segment plus disk" contains the
rectangle, and the enlargement by a disk is what keeps it off-line: the rectangle's own
Minkowski sum with an obstacle turns with the robot. So the planner asks the rectangle
itself, against the raw obstacle, only where this test finds the rounded body touching
(:mod:`segplan.floor.body`: the same certified sweep, for the segment's parallel offsets).

Tolerance. Contacts are decided with a tiny conservative tolerance
``tol = TOUCH_RTOL * (L + X + r_max + |c| + |p0|)`` (``|c|``: distance of the polygon's
centre from the union's start ``p0``; ``|p0|``, its largest world coordinate, for the
rounding of the change of frame): a position within about ``tol`` of the polygon
(separating-axis sense) counts as a collision. Floating-point error at double roots thus turns into rare
false alarms (a contact closer than ``tol``), never into misses.

Counters
--------
A caller who wants counts passes a :class:`CollisionStats` as ``stats=`` and every query
updates it, so a benchmark can report checks per second: ``stats = CollisionStats()``,
run, then read ``stats.calls`` (union-polygon queries), ``stats.rejected`` (by a quick
check), ``stats.exact`` and ``stats.events``. Without ``stats`` nothing is counted: the
module keeps no state.

Speed
-----
Per-polygon data (:class:`segplan.floor.geometry.ConvexPolygon`: normals, offsets, centre,
``r_max``) and per-union data (:class:`segplan.floor.sweep.Sweep`: frame, box, ``M``, bounds, the
level-0 positions) are computed once per object. Nothing is cached behind the caller's
back: an array polygon is validated at each call and a :class:`segplan.Union` gets a new
sweep; callers that test often pass :class:`~segplan.floor.geometry.ConvexPolygon` and
:class:`~segplan.floor.sweep.Sweep` objects (the planner's :class:`segplan.planning.validity.Workspace`
does); :func:`union_free` tests one union against many obstacles, quick checks first.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..model.union import Union
from .geometry import TOUCH_RTOL, Bounds, ConvexPolygon, as_polygon, check_bounds
from .sweep import Sweep, as_sweep, corners, cubic_points, hull_axes, quadratic_points

__all__ = [
    "CollisionStats",
    "collides",
    "collision_witness",
    "sweep_in_bounds",
    "union_free",
    "union_in_bounds",
]

_SWEEP_LEVELS = 3  # refinements of the certified sweep before the event test
_FRONT_PIECES = 16  # initial pieces of the front-wheel subdivision
_FRONT_MAX_PIECES = 4096  # guard: beyond this many live pieces, answer "collision"
_S_FRONT = np.linspace(0.0, 1.0, _FRONT_PIECES + 1)
_S_FRONT.flags.writeable = False


# -- counters ------------------------------------------------------------------------------
@dataclass
class CollisionStats:
    """Counters of collision queries.

    Attributes
    ----------
    calls : int
        Union-polygon queries (:func:`collides`, and each obstacle of :func:`union_free`).
    rejected : int
        Queries answered by a quick check (box or ``d_c``).
    exact : int
        Queries that ran the exact test.
    events : int
        Exact tests that the certified sweep left undecided, decided by the event test.
    collisions : int
        Queries answered "collision".
    """

    calls: int = 0
    rejected: int = 0
    exact: int = 0
    events: int = 0
    collisions: int = 0

    def reset(self) -> None:
        """Set every counter to zero."""
        self.calls = self.rejected = self.exact = self.events = self.collisions = 0


# -- exact test ----------------------------------------------------------------------------------
def _touching(sw: Sweep, s, V, N, H, tol):
    """Segment-polygon separating-axis test at abscissae ``s``; index of the first hit or -1."""
    x, fx, ux, uy = sw.segment(s)
    gA = np.multiply.outer(x, N[:, 0]) + np.multiply.outer(fx, N[:, 1]) - H  # n . A - h
    nu = np.multiply.outer(ux, N[:, 0]) + np.multiply.outer(uy, N[:, 1])
    gB = gA + sw.t1 * nu  # n . B - h, at the front end
    if sw.t0 != 0.0:  # the rear end, behind A
        gA = gA + sw.t0 * nu
    sep = np.minimum(gA, gB).max(axis=1) > tol
    side = np.multiply.outer(ux, V[:, 1]) - np.multiply.outer(uy, V[:, 0]) + (uy * x - ux * fx)[:, None]
    sep |= (side.min(axis=1) > tol) | (side.max(axis=1) < -tol)
    hit = np.flatnonzero(~sep)
    return int(hit[0]) if hit.size else -1


def _hull_gaps(P4, V, N, H):
    """Separating-axis gap between the hull of each ``P4`` (``(m, 4, 2)``) and the polygon."""
    nrm, qmin, qmax = hull_axes(P4)
    pv = nrm @ V.T  # (m, 6, k)
    gap = np.maximum(pv.min(axis=2) - qmax, qmin - pv.max(axis=2)).max(axis=1)
    g4 = P4 @ N.T - H  # (m, 4, k)
    return np.maximum(gap, g4.min(axis=1).max(axis=1))


def _sweep(sw: Sweep, V, N, H, tol):
    """Certified sweep: ``(x, None)`` on a contact, ``(None, None)`` if free, else
    ``(None, undecided)`` after :data:`_SWEEP_LEVELS` refinements.

    Between two positions ``s_lo < s_hi``, every point ``P = A + t u`` of the segment moves
    on a curve within ``e = |P''|_max dx^2 / 8`` of its chord (``dx = X (s_hi - s_lo)``),
    and that chord lies in the convex hull of the two segments; so the swept set lies in
    the hull grown by ``e``. A hull whose separating-axis gap to the polygon exceeds ``e``
    certifies the piece free; a sampled position that touches is a collision.
    """
    g = sw.grid()
    k = len(H)
    gA = g.A @ N.T - H
    gB = g.B @ N.T - H
    m = np.minimum(gA, gB)
    side = g.nseg @ V.T - g.oseg[:, None]
    touch = (m.max(axis=1) <= tol) & (side.min(axis=1) <= tol) & (side.max(axis=1) >= -tol)
    if touch.any():
        return float(g.s[np.argmax(touch)]) * sw.X, None
    # the gap is the larger of two lower bounds, along the polygon's edge normals and along
    # the hull's axes; a piece is live only if both are <= e, so when the first certifies
    # every piece (most pairs) the hull's axes are not needed
    gap_poly = np.minimum(m[:-1], m[1:]).max(axis=1)
    if not (gap_poly <= g.e).any():
        return None, None
    if g.nrm is None:
        nrm, g.qmin, g.qmax = hull_axes(corners(g.A[:-1], g.B[:-1], g.A[1:], g.B[1:]))
        g.nrm = nrm.reshape(-1, 2)
    pv = (g.nrm @ V.T).reshape(-1, 6, k)
    gap = np.maximum(pv.min(axis=2) - g.qmax, g.qmin - pv.max(axis=2)).max(axis=1)
    gap = np.maximum(gap, gap_poly)
    live = gap <= g.e
    if not live.any():
        return None, None
    s_lo, s_hi, kx = g.s[:-1][live], g.s[1:][live], g.kx[live]
    A_lo, B_lo, A_hi, B_hi = g.A[:-1][live], g.B[:-1][live], g.A[1:][live], g.B[1:][live]
    dx = g.dx
    for _ in range(_SWEEP_LEVELS):
        s_mid = 0.5 * (s_lo + s_hi)
        i = _touching(sw, s_mid, V, N, H, tol)
        if i >= 0:
            return float(s_mid[i]) * sw.X, None
        A_mid, B_mid = sw.ends(s_mid)
        s_lo, s_hi = np.concatenate((s_lo, s_mid)), np.concatenate((s_mid, s_hi))
        A_lo, A_hi = np.concatenate((A_lo, A_mid)), np.concatenate((A_mid, A_hi))
        B_lo, B_hi = np.concatenate((B_lo, B_mid)), np.concatenate((B_mid, B_hi))
        kx = np.concatenate((kx, kx))
        dx *= 0.5
        live = _hull_gaps(corners(A_lo, B_lo, A_hi, B_hi), V, N, H) <= kx * (dx * dx / 8.0)
        if not live.any():
            return None, None
        s_lo, s_hi, kx = s_lo[live], s_hi[live], kx[live]
        A_lo, B_lo, A_hi, B_hi = A_lo[live], B_lo[live], A_hi[live], B_hi[live]
    return None, (s_lo, s_hi)


def _event_abscissae(sw: Sweep, V, N, H) -> np.ndarray:
    """Candidate ``s = x / X`` of the events (ii) and (iv) and the two end poses."""
    X, c1, c2, c3 = sw.X, sw.c1, sw.c2, sw.c3
    F1, F2, F3 = c1 * X, c2 * X * X, c3 * X**3  # f(X s) = F1 s + F2 s^2 + F3 s^3
    nx, ny = N[:, 0], N[:, 1]
    vx, vy = V[:, 0], V[:, 1]
    k = len(H)
    # (ii) a_e(s) = -h + (n_x X + n_y F1) s + n_y F2 s^2 + n_y F3 s^3
    # (iv) h_V(s) = (V_y - c1 V_x) - 2 c2 X V_x s + (c2 - 3 c3 V_x) X^2 s^2 + 2 c3 X^3 s^3
    roots = cubic_points(
        np.concatenate((ny * F3, np.full(k, 2.0 * F3))),
        np.concatenate((ny * F2, (c2 - 3.0 * c3 * vx) * X * X)),
        np.concatenate((nx * X + ny * F1, -2.0 * c2 * X * vx)),
        np.concatenate((-H, vy - c1 * vx)),
    )
    # stationary points: a_e' = 0 where f' equals the edge's slope; h_V' = 0 at x = V_x, f'' = 0
    crit = quadratic_points(3.0 * ny * F3, 2.0 * ny * F2, nx * X + ny * F1)
    extra = [vx / X, np.array([0.0, 1.0])]
    if c3 != 0.0:
        extra.append(np.array([-c2 / (3.0 * c3 * X)]))
    s = np.concatenate((roots.ravel(), crit.ravel(), *extra))
    s = s[np.isfinite(s)]
    return np.clip(s, 0.0, 1.0)


def _front_meets(sw: Sweep, V, N, H, tol, t: float | None = None) -> float | None:
    """Certified test of event (iii): does the front-wheel path meet the polygon?

    Or the path of the point ``A + t u`` (``t``: default the front end ``sw.t1``, the front
    wheel B without an overhang; ``sw.t0``, the rear end). Returns an abscissa ``s`` of a
    (near-)contact, or ``None`` if the path is free.
    """
    t = sw.t1 if t is None else t
    s = _S_FRONT
    B = sw.point(s, t)
    g = B @ N.T - H
    inside = np.flatnonzero(np.all(g <= tol, axis=1))
    if inside.size:
        return float(s[inside[0]])
    s_lo, s_hi, B_lo, B_hi, g_lo, g_hi = s[:-1], s[1:], B[:-1], B[1:], g[:-1], g[1:]
    h = 1.0 / _FRONT_PIECES
    while True:
        e = sw.K * h * h / 8.0  # the piece of path stays within e of its chord
        gap = np.max(np.minimum(g_lo, g_hi), axis=1)  # polygon edge normals
        d = B_hi - B_lo
        ln = np.hypot(d[:, 0], d[:, 1])
        ok = ln > 0
        mx = np.where(ok, -d[:, 1] / np.where(ok, ln, 1.0), 0.0)
        my = np.where(ok, d[:, 0] / np.where(ok, ln, 1.0), 0.0)
        side = np.multiply.outer(mx, V[:, 0]) + np.multiply.outer(my, V[:, 1])
        side -= (mx * B_lo[:, 0] + my * B_lo[:, 1])[:, None]
        chord_gap = np.where(ok, np.maximum(side.min(axis=1), -side.max(axis=1)), -np.inf)
        live = np.maximum(gap, chord_gap) <= e
        if not np.any(live):
            return None
        if e <= tol or np.count_nonzero(live) > _FRONT_MAX_PIECES:
            # within ~tol of touching: conservative; report the closest sampled position
            cand = np.concatenate((s_lo[live], s_hi[live], 0.5 * (s_lo[live] + s_hi[live])))
            return float(cand[np.argmin((sw.point(cand, t) @ N.T - H).max(axis=1))])
        s_lo, s_hi, B_lo, B_hi, g_lo, g_hi = (a[live] for a in (s_lo, s_hi, B_lo, B_hi, g_lo, g_hi))
        s_mid = 0.5 * (s_lo + s_hi)
        B_mid = sw.point(s_mid, t)
        g_mid = B_mid @ N.T - H
        inside = np.flatnonzero(np.all(g_mid <= tol, axis=1))
        if inside.size:
            return float(s_mid[inside[0]])
        s_lo, s_hi = np.concatenate((s_lo, s_mid)), np.concatenate((s_mid, s_hi))
        B_lo, B_hi = np.concatenate((B_lo, B_mid)), np.concatenate((B_mid, B_hi))
        g_lo, g_hi = np.concatenate((g_lo, g_mid)), np.concatenate((g_mid, g_hi))
        h *= 0.5


def _events(sw: Sweep, V, N, H, tol: float) -> float | None:
    """The event test (module docstring): frame abscissa of a contact, or None."""
    s = _event_abscissae(sw, V, N, H)
    i = _touching(sw, s, V, N, H, tol)
    if i >= 0:
        return float(s[i]) * sw.X
    s_hit = _front_meets(sw, V, N, H, tol)
    if s_hit is None and sw.t0 != 0.0:  # event (ii'): the rear end's path, behind A
        s_hit = _front_meets(sw, V, N, H, tol, sw.t0)
    return None if s_hit is None else s_hit * sw.X


def _exact(sw: Sweep, poly: ConvexPolygon, tol: float, stats: CollisionStats) -> float | None:
    """The exact test: frame abscissa ``x`` of a contact, or None (free)."""
    V, N, H = sw.local(poly)
    x, undecided = _sweep(sw, V, N, H, tol)
    if undecided is None:
        return x
    stats.events += 1
    return _events(sw, V, N, H, tol)


def _query(union, polygon, check, stats) -> float | None:
    stats = CollisionStats() if stats is None else stats  # counts nobody reads
    sw = as_sweep(union)
    poly = as_polygon(polygon, check)
    stats.calls += 1
    reject, tol = sw.quick_reject(poly)
    if reject:
        stats.rejected += 1
        return None
    stats.exact += 1
    x = _exact(sw, poly, tol, stats)
    if x is not None:
        stats.collisions += 1
    return x


def collides(
    union: Union | Sweep, polygon, *, check: bool = True, stats: CollisionStats | None = None
) -> bool:
    """Does any position of the segment along ``union`` touch the convex ``polygon``?

    Section "Collision-detection algorithm": quick checks first (box, then the paper's
    ``d_c > r_max + M``), then the exact test of the module docstring: a certified sweep
    that decides nearly every case, and for near-touches the event test (start pose; rear
    point on an edge; vertex swept by the segment; front-wheel path against the polygon).
    Touching counts as collision (closed sets), with a tiny conservative tolerance
    (:data:`TOUCH_RTOL`): never a miss, rarely a false alarm closer than ~1e-9 of the scene.

    Parameters
    ----------
    union : Union or Sweep
        A :class:`Sweep` reuses the per-union data across polygons.
    polygon : ConvexPolygon or array_like (k, 2)
        Convex, either orientation. A :class:`ConvexPolygon` is not re-validated.
    check : bool
        Validate an array polygon (``ValueError`` if malformed); pass ``False`` for
        pre-validated obstacles.
    stats : CollisionStats, optional
        Counters to update (default: none; nothing is counted).

    Returns
    -------
    bool
    """
    return _query(union, polygon, check, stats) is not None


def collision_witness(
    union: Union | Sweep, polygon, *, check: bool = True, stats: CollisionStats | None = None
) -> float | None:
    """Frame abscissa ``x`` in ``[0, union.x_end]`` of a position that touches ``polygon``.

    Like :func:`collides`, but returns where (not necessarily the first contact), or
    ``None`` when the union is free of the polygon.
    """
    return _query(union, polygon, check, stats)


def union_free(
    union: Union | Sweep,
    obstacles,
    bounds=None,
    *,
    check: bool = True,
    stats: CollisionStats | None = None,
) -> bool:
    """Is every position of the segment along ``union`` clear of all obstacles and walls?

    Quick rejections run for every obstacle first; then the bounds; then the exact tests
    of the obstacles that survived.

    Parameters
    ----------
    union : Union or Sweep
    obstacles : iterable of ConvexPolygon or (k, 2) arrays
    bounds : (xmin, ymin, xmax, ymax), optional
        See :func:`union_in_bounds`.
    check : bool
        Validate array polygons.
    stats : CollisionStats, optional
        Counters to update (default: none; nothing is counted).
    """
    stats = CollisionStats() if stats is None else stats  # counts nobody reads
    sw = as_sweep(union)
    near = []
    for i, p in enumerate(obstacles):
        poly = as_polygon(p, check, name=f"obstacles[{i}]")
        stats.calls += 1
        reject, tol = sw.quick_reject(poly)
        if reject:
            stats.rejected += 1
        else:
            near.append((poly, tol))
    if bounds is not None and not union_in_bounds(sw, bounds):
        return False
    for poly, tol in near:
        stats.exact += 1
        if _exact(sw, poly, tol, stats) is not None:
            stats.collisions += 1
            return False
    return True


# -- walls --------------------------------------------------------------------------------------
def _front_reaches(sw: Sweep, N, H, tol, t: float | None = None) -> bool:
    """Certified: does ``max_s n_j . B(s) - h_j >= -tol`` for some wall ``j``?

    ``B = A + t u``: default the front end (``t = sw.t1``); ``sw.t0``, the rear end.
    """
    t = sw.t1 if t is None else t
    s = _S_FRONT
    g = sw.point(s, t) @ N.T - H  # (n, m)
    if np.any(g >= -tol):
        return True
    s_lo, s_hi, g_lo, g_hi = s[:-1], s[1:], g[:-1], g[1:]
    h = 1.0 / _FRONT_PIECES
    while True:
        e = sw.K * h * h / 8.0
        live = np.any(np.maximum(g_lo, g_hi) + e >= -tol, axis=1)
        if not np.any(live):
            return False
        if e <= tol or np.count_nonzero(live) > _FRONT_MAX_PIECES:
            return True
        s_lo, s_hi, g_lo, g_hi = s_lo[live], s_hi[live], g_lo[live], g_hi[live]
        s_mid = 0.5 * (s_lo + s_hi)
        g_mid = sw.point(s_mid, t) @ N.T - H
        if np.any(g_mid >= -tol):
            return True
        s_lo, s_hi = np.concatenate((s_lo, s_mid)), np.concatenate((s_mid, s_hi))
        g_lo, g_hi = np.concatenate((g_lo, g_mid)), np.concatenate((g_mid, g_hi))
        h *= 0.5


def union_in_bounds(union: Union | Sweep, bounds) -> bool:
    """Does every position of the segment lie strictly inside the rectangle ``bounds``?

    The rectangle is convex, so a segment lies inside iff both end points do: the rear
    cubic (its extremes along each wall normal: ends and roots of a quadratic, exact) and
    the front-wheel path (certified subdivision, as for event (iii)). Touching a wall is
    leaving the bounds (walls are closed obstacles), with the tolerance of
    :func:`collides`. A quick sufficient test first: the corners of the union's frame box.

    Parameters
    ----------
    union : Union or Sweep
    bounds : (xmin, ymin, xmax, ymax)
    """
    checked = check_bounds(bounds)  # checked before the union, as always
    return sweep_in_bounds(as_sweep(union), checked)


def sweep_in_bounds(sw: Sweep, bounds: Bounds) -> bool:
    """:func:`union_in_bounds` of a sweep, for bounds checked by
    :func:`segplan.floor.geometry.check_bounds`."""
    xmin, ymin, xmax, ymax = bounds
    tol = TOUCH_RTOL * (sw.size + (xmax - xmin) + (ymax - ymin) + math.hypot(sw.x0, sw.y0))
    x_lo, x_hi, y_lo, y_hi = sw.box
    # the frame box in world coordinates: centre and half extents of its bounding rectangle
    mx, my, hw, hh = 0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi), 0.5 * (x_hi - x_lo), 0.5 * (y_hi - y_lo)
    wx, wy = sw.x0 + sw.cos * mx - sw.sin * my, sw.y0 + sw.sin * mx + sw.cos * my
    ex, ey = abs(sw.cos) * hw + abs(sw.sin) * hh, abs(sw.sin) * hw + abs(sw.cos) * hh
    if xmin + tol < wx - ex and wx + ex < xmax - tol and ymin + tol < wy - ey and wy + ey < ymax - tol:
        return True
    Nw = np.array([[-1.0, 0.0], [1.0, 0.0], [0.0, -1.0], [0.0, 1.0]])  # outward wall normals
    Hw = np.array([-xmin, xmax, -ymin, ymax])
    N = Nw @ sw.rot
    H = Hw - Nw @ sw.p0
    X, c1, c2, c3 = sw.X, sw.c1, sw.c2, sw.c3
    nx, ny = N[:, 0], N[:, 1]
    # rear: a_j(s) = n_x X s + n_y f(X s) - h, maximal at s in {0, 1} or a_j'(s) = 0
    crit = quadratic_points(3.0 * ny * c3 * X**3, 2.0 * ny * c2 * X * X, nx * X + ny * c1 * X)
    s = np.concatenate((crit.ravel(), [0.0, 1.0]))
    s = np.clip(s[np.isfinite(s)], 0.0, 1.0)
    x, fx, _, _ = sw.segment(s)
    if np.any(np.multiply.outer(x, nx) + np.multiply.outer(fx, ny) - H >= -tol):
        return False
    if sw.t0 != 0.0 and _front_reaches(sw, N, H, tol, sw.t0):  # the rear end, behind A
        return False
    return not _front_reaches(sw, N, H, tol)
