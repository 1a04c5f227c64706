"""The rectangular body swept exactly (beyond the paper, issue 26).

The paper's robot is the segment A->B, "enlarged" by its half-width through the obstacles
(section "Collision-detection algorithm"; :mod:`segplan.floor.collision`). A forklift or a
car is a *rectangle* ``[t0, t1] x [-w, w]`` of its own frame (A at the origin, the heading
along ``+t``; ``t0 = -rear_overhang``, ``t1 = L + front_overhang``, ``w = half_width``:
:class:`segplan.Robot` with ``rectangle=True``). The segment enlarged by a disk is the
round-ended body that contains it; testing that body is conservative for the rectangle and
pessimistic by its two round caps. This module tests the rectangle itself, against the
*raw* obstacles and walls.

How the paper's method generalises
----------------------------------
The rectangle is the union of the segments parallel to the axis at lateral offsets
``s`` in ``[-w, w]`` (the axis segment "and its parallel offsets"), and every point

    ``P(x; t, s) = A(x) + t u(x) + s n(x)``,  ``n = J u`` (``u`` turned a quarter left),

is rigidly attached to the robot, as the segment's points ``A + t u`` are. Two facts carry
the segment's certified sweep (:mod:`segplan.floor.collision`, stage 1) over to it:

1. *Bend.* ``n'' = J u''``, so ``t u'' + s n'' = (t I + s J) u''`` has the norm
   ``sqrt(t^2 + s^2) |u''|``: every point of the body obeys
   ``|P''| <= |A''| + rho |u''|``, ``rho = sqrt(max(-t0, t1)^2 + w^2)`` (the farthest
   corner from A), the segment's bound with its reach replaced by ``rho``
   (:meth:`segplan.floor.sweep.Sweep.bend`). On a piece of length ``dx`` every point moves
   within ``e = K dx^2 / 8`` of its chord.
2. *Hull.* Each chord joins a point's positions at the piece's two ends, which lie in the
   two rectangles; so the piece's swept set lies in the convex hull of the two rectangles
   (eight corners) grown by ``e``.

The first contact (the argument of :mod:`segplan.floor.collision`, with a convex polygon in
place of the segment) is the start pose, a corner of the rectangle on an edge of the
obstacle, or a vertex of the obstacle on a side of the rectangle. The corner events are
point paths, like the front wheel's (event iii); a vertex on a long side solves
``h_V(x) = +-w sqrt(1 + f'^2)`` (degree 6 once squared), on an end side
``(V - A) . u = t_end``: no longer cubics. So every event is decided as the segment's event
(iii) is, by a certified subdivision to the touching tolerance ``tol``:

* a piece whose hull lies farther than ``e`` from the polygon is free (separating axes: the
  polygon's edge normals and the normals of the 28 corner pairs, among which every edge of
  the hull);
* a position where the rectangle touches the polygon within ``tol`` (separating axes: the
  polygon's normals, ``u`` and ``n``) is a collision;
* other pieces are halved; once a live piece's ``e`` is below ``tol`` (or more than
  ``_MAX_PIECES`` are live) the answer is a conservative "collision".

Every "free" is certified and every "collision" is a position within ``tol`` or a piece
whose hull comes within ``e <= tol`` of the polygon: the test never misses a contact and
its false alarms are near-touches of about ``tol``, the standard of the segment's test
(``tests/test_body_sweep.py`` checks both against a dense shapely oracle of the rectangle).
The walls: the body lies inside the rectangular bounds iff its four corners do, each corner's
path certified the same way.

Use. The planner (:class:`segplan.planning.validity.Workspace`) sweeps the axis segment
against the obstacles enlarged by ``w`` first (exact for the round body, which contains the
rectangle: a pair it finds free is free); only the pairs it finds colliding are asked again
here, with the raw obstacle (:class:`RectangleBody`).
"""

from __future__ import annotations

import math

import numpy as np

from ..model.pose import as_pose
from .geometry import TOUCH_RTOL, Bounds, ConvexPolygon, check_bounds, enlargement_excess, finite_number
from .sweep import Sweep

__all__ = ["RectangleBody", "rectangle_collides", "rectangle_in_bounds"]

_PIECES = 32  # level-0 pieces of the subdivision
_MAX_PIECES = 4096  # guard: beyond this many live pieces, answer "collision"
_S0 = np.linspace(0.0, 1.0, _PIECES + 1)
_S0.flags.writeable = False
_PAIR_I, _PAIR_J = np.triu_indices(8, 1)  # the 28 pairs of the two rectangles' eight corners
#: Outward normals of the walls ``(xmin, ymin, xmax, ymax)``: left, right, bottom, top.
_WALL_NORMALS = np.array([[-1.0, 0.0], [1.0, 0.0], [0.0, -1.0], [0.0, 1.0]])


def _check_body(sw: Sweep, half_width: float) -> float:
    if not isinstance(sw, Sweep):
        raise ValueError(f"sweep must be a segplan.floor.sweep.Sweep, got {type(sw).__name__}")
    return finite_number(half_width, "half_width", minimum=0.0)


def _frames(sw: Sweep, s: np.ndarray, w: float):
    """Frame rear point ``A`` and unit heading ``u`` ``(n, 2)`` at ``s = x / X``, and the
    rectangle's corners ``(n, 4, 2)``: ``(t0, -w), (t1, -w), (t1, w), (t0, w)``."""
    x, fx, ux, uy = sw.segment(s)
    A = np.stack((x, fx), axis=-1)
    U = np.stack((ux, uy), axis=-1)
    Nn = np.stack((-uy, ux), axis=-1)  # n = J u
    C = np.empty((len(s), 4, 2))
    for k, (t, lat) in enumerate(((sw.t0, -w), (sw.t1, -w), (sw.t1, w), (sw.t0, w))):
        C[:, k] = A + t * U + lat * Nn  # P = A + t u + s n
    return A, U, C


def _touching(A, U, C, t0: float, t1: float, w: float, V, N, H, tol: float) -> np.ndarray:
    """Rectangle-polygon separating-axis test at each position: touching within ``tol``?

    Axes: the polygon's outward edge normals (every corner beyond one edge), the heading
    ``u`` (every vertex beyond an end side) and ``n`` (every vertex beyond a long side).
    """
    g = C @ N.T - H  # (n, 4, k): n_e . corner - h_e
    sep = (g.min(axis=1) > tol).any(axis=1)
    Dx = V[None, :, 0] - A[:, None, 0]
    Dy = V[None, :, 1] - A[:, None, 1]
    pu = Dx * U[:, None, 0] + Dy * U[:, None, 1]  # (V - A) . u
    pn = Dy * U[:, None, 0] - Dx * U[:, None, 1]  # (V - A) . n
    sep |= (pu.min(axis=1) > t1 + tol) | (pu.max(axis=1) < t0 - tol)
    sep |= (pn.min(axis=1) > w + tol) | (pn.max(axis=1) < -w - tol)
    return ~sep


def _hull_gaps(C_lo, C_hi, V, N, H) -> np.ndarray:
    """A lower bound of the distance between the hull of each pair of rectangles and the polygon.

    Separating-axis gaps along the polygon's edge normals and the unit normals of the 28
    corner pairs (every edge of the hull joins two corners); any axis gives a lower bound.
    """
    P8 = np.concatenate((C_lo, C_hi), axis=1)  # (m, 8, 2)
    gap_poly = (P8 @ N.T - H).min(axis=1).max(axis=1)
    D = P8[:, _PAIR_J] - P8[:, _PAIR_I]  # (m, 28, 2)
    ln = np.hypot(D[..., 0], D[..., 1])
    ln[ln == 0.0] = np.inf  # a degenerate pair gives a null axis (gap 0)
    nrm = np.stack((-D[..., 1] / ln, D[..., 0] / ln), axis=-1)
    q = np.einsum("mad,mpd->map", nrm, P8)  # (m, 28, 8)
    pv = nrm @ V.T  # (m, 28, k)
    gap = np.maximum(pv.min(axis=2) - q.max(axis=2), q.min(axis=2) - pv.max(axis=2)).max(axis=1)
    return np.maximum(gap, gap_poly)


def rectangle_collides(sw: Sweep, polygon: ConvexPolygon, half_width: float) -> bool:
    """Does the rectangle ``[t0, t1] x [-w, w]`` touch ``polygon`` anywhere along the union?

    The certified subdivision of the module docstring: never a miss, false alarms only
    within about the touching tolerance ``TOUCH_RTOL`` times the scene.

    Parameters
    ----------
    sw : segplan.floor.sweep.Sweep
        The union's sweep, built with the robot's overhangs (``t0 = sw.t0``, ``t1 = sw.t1``).
    polygon : ConvexPolygon
        A *raw* obstacle (not enlarged).
    half_width : float
        ``w`` (>= 0, m).
    """
    w = _check_body(sw, half_width)
    if not isinstance(polygon, ConvexPolygon):
        raise ValueError(f"polygon must be a ConvexPolygon, got {type(polygon).__name__}")
    V, N, H = sw.local(polygon)
    cx, cy = V.mean(axis=0)
    tol = TOUCH_RTOL * (sw.size + 2.0 * w + polygon.radius + math.hypot(cx, cy) + sw.mag)
    # quick: the frame box of the axis segment grown by w holds the body
    x_lo, x_hi, y_lo, y_hi = sw.box
    if (
        V[:, 0].max() < x_lo - w - tol or V[:, 0].min() > x_hi + w + tol
        or V[:, 1].max() < y_lo - w - tol or V[:, 1].min() > y_hi + w + tol
    ):  # fmt: skip
        return False
    rho = math.hypot(max(-sw.t0, sw.t1), w)
    s = _S0
    A, U, C = _frames(sw, s, w)
    if _touching(A, U, C, sw.t0, sw.t1, w, V, N, H, tol).any():
        return True
    s_lo, s_hi, C_lo, C_hi = s[:-1], s[1:], C[:-1], C[1:]
    dx = sw.X / _PIECES
    while True:
        e = sw.bend(s_lo, s_hi, reach=rho) * (dx * dx / 8.0)  # every point within e of its chord
        live = _hull_gaps(C_lo, C_hi, V, N, H) <= e
        if not live.any():
            return False
        if np.any(e[live] <= tol) or np.count_nonzero(live) > _MAX_PIECES:
            return True  # within ~tol of touching: conservative
        s_lo, s_hi, C_lo, C_hi = s_lo[live], s_hi[live], C_lo[live], C_hi[live]
        s_mid = 0.5 * (s_lo + s_hi)
        A, U, C_mid = _frames(sw, s_mid, w)
        if _touching(A, U, C_mid, sw.t0, sw.t1, w, V, N, H, tol).any():
            return True
        s_lo, s_hi = np.concatenate((s_lo, s_mid)), np.concatenate((s_mid, s_hi))
        C_lo, C_hi = np.concatenate((C_lo, C_mid)), np.concatenate((C_mid, C_hi))
        dx *= 0.5


def rectangle_in_bounds(sw: Sweep, bounds: Bounds, half_width: float) -> bool:
    """Does the rectangle lie strictly inside the walls ``bounds`` all along the union?

    The body is convex and the bounds a rectangle: it lies inside iff its four corners do;
    each corner's path is certified as the front wheel's (module docstring). Touching a
    wall (within the tolerance) is leaving the bounds.

    Parameters
    ----------
    sw : segplan.floor.sweep.Sweep
    bounds : (xmin, ymin, xmax, ymax)
        The raw walls (checked by :func:`segplan.floor.geometry.check_bounds`).
    half_width : float
    """
    w = _check_body(sw, half_width)
    xmin, ymin, xmax, ymax = check_bounds(bounds)
    tol = TOUCH_RTOL * (sw.size + 2.0 * w + (xmax - xmin) + (ymax - ymin) + math.hypot(sw.x0, sw.y0))
    N = _WALL_NORMALS @ sw.rot
    H = np.array([-xmin, xmax, -ymin, ymax]) - _WALL_NORMALS @ sw.p0
    rho = math.hypot(max(-sw.t0, sw.t1), w)
    s = _S0
    g = _frames(sw, s, w)[2] @ N.T - H  # (n, 4 corners, 4 walls)
    if np.any(g >= -tol):
        return False
    s_lo, s_hi, g_lo, g_hi = s[:-1], s[1:], g[:-1], g[1:]
    dx = sw.X / _PIECES
    while True:
        e = sw.bend(s_lo, s_hi, reach=rho) * (dx * dx / 8.0)
        live = np.any(np.maximum(g_lo, g_hi) + e[:, None, None] >= -tol, axis=(1, 2))
        if not live.any():
            return True
        if np.any(e[live] <= tol) or np.count_nonzero(live) > _MAX_PIECES:
            return False
        s_lo, s_hi, g_lo, g_hi = s_lo[live], s_hi[live], g_lo[live], g_hi[live]
        s_mid = 0.5 * (s_lo + s_hi)
        g_mid = _frames(sw, s_mid, w)[2] @ N.T - H
        if np.any(g_mid >= -tol):
            return False
        s_lo, s_hi = np.concatenate((s_lo, s_mid)), np.concatenate((s_mid, s_hi))
        g_lo, g_hi = np.concatenate((g_lo, g_mid)), np.concatenate((g_mid, g_hi))
        dx *= 0.5


class RectangleBody:
    """A rectangular robot body among the raw obstacles and walls: the exact tests.

    Parameters
    ----------
    obstacles : sequence of (k, 2) arrays or ConvexPolygon
        The *raw* convex obstacles (:attr:`segplan.Scenario.obstacles`), in the order of the
        enlarged ones the planner's :class:`~segplan.planning.validity.Workspace` holds.
    half_width : float
        ``w`` (> 0, m).
    bounds : (xmin, ymin, xmax, ymax) or None
        The raw walls.
    L, rear, front : float
        The robot's length and overhangs: the rectangle is ``[-rear, L + front] x [-w, w]``.
    """

    def __init__(self, obstacles, half_width: float, bounds, L: float, rear: float = 0.0, front: float = 0.0):
        self.convex = [
            p if isinstance(p, ConvexPolygon) else ConvexPolygon(p, check=False) for p in obstacles
        ]
        self.w = w = finite_number(half_width, "half_width", minimum=0.0)
        self.bounds = None if bounds is None else check_bounds(bounds)
        self.L, self.rear, self.front = float(L), float(rear), float(front)
        #: How deep inside an enlarged obstacle (or beyond a moved wall) a point of A->B
        #: must lie for the rectangle to touch for certain (m): the rectangle holds the disk
        #: of radius ``rho = min(w, rear, front)`` around every point of A->B, and the
        #: enlarged polygon lies within ``w + excess`` of the raw one
        #: (:func:`segplan.floor.geometry.enlargement_excess`), so a point deeper than
        #: ``w + excess - rho`` is within ``rho`` of the raw obstacle. The planner's point
        #: screens (the clearance grid's blocked cells, the refinement's certain failures)
        #: use it in place of 0, the round body's.
        self.depth = w + enlargement_excess(w) - min(w, self.rear, self.front)

    def collides(self, sw: Sweep, i: int) -> bool:
        """Does the body along the union of ``sw`` touch obstacle ``i``? (:func:`rectangle_collides`)"""
        return rectangle_collides(sw, self.convex[i], self.w)

    def in_bounds(self, sw: Sweep) -> bool:
        """Does the body stay strictly inside the walls along the union? (:func:`rectangle_in_bounds`)"""
        return self.bounds is None or rectangle_in_bounds(sw, self.bounds, self.w)

    def corners(self, pose) -> np.ndarray:
        """World corners ``(4, 2)`` of the body at ``pose`` (radians)."""
        p = as_pose(pose)
        c, s = math.cos(p.theta), math.sin(p.theta)
        t0, t1, w = -self.rear, self.L + self.front, self.w
        return np.array(
            [[p.x + c * t - s * q, p.y + s * t + c * q] for t, q in ((t0, -w), (t1, -w), (t1, w), (t0, w))]
        )

    def pose_conflict(self, pose) -> str | None:
        """Why the body at ``pose`` is not free (``"bounds"`` or ``"obstacles[i]"``), or None.

        The rectangle against the walls (every corner strictly inside) and each obstacle
        (separating axes), touching within ``TOUCH_RTOL`` times the scene counting.
        """
        p = as_pose(pose)
        C = self.corners(p)
        scale = self.L + self.rear + self.front + 2.0 * self.w + max(abs(p.x), abs(p.y))
        if self.bounds is not None:
            xmin, ymin, xmax, ymax = self.bounds
            tol = TOUCH_RTOL * (scale + (xmax - xmin) + (ymax - ymin))
            if not (
                C[:, 0].min() > xmin + tol and C[:, 0].max() < xmax - tol
                and C[:, 1].min() > ymin + tol and C[:, 1].max() < ymax - tol
            ):  # fmt: skip
                return "bounds"
        A = np.array([[p.x, p.y]])
        U = np.array([[math.cos(p.theta), math.sin(p.theta)]])
        for i, poly in enumerate(self.convex):
            tol = TOUCH_RTOL * (scale + poly.radius + math.hypot(poly.centre[0] - p.x, poly.centre[1] - p.y))
            x0, y0, x1, y1 = poly.box
            if (
                C[:, 0].min() > x1 + tol
                or C[:, 0].max() < x0 - tol
                or C[:, 1].min() > y1 + tol
                or C[:, 1].max() < y0 - tol
            ):
                continue
            if _touching(
                A,
                U,
                C[None],
                -self.rear,
                self.L + self.front,
                self.w,
                poly.vertices,
                poly.normals,
                poly.offsets,
                tol,
            )[0]:
                return f"obstacles[{i}]"
        return None
