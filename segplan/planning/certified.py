"""A certified "surely free" screen of a union, ahead of the exact test (beyond the paper).

The refinement (:mod:`segplan.planning.refine`) checks a few thousand links per floor, nine
in ten of them free; the exact test of a free link (:meth:`segplan.planning.validity.Workspace.union_free`:
the broad phase over every obstacle, then per obstacle near the link a certain-hit test, the
paper's quick checks and the certified sweep of :mod:`segplan.floor.collision`; for the walls
:func:`segplan.floor.collision.sweep_in_bounds`) costs about half a millisecond, mostly
Python overhead per obstacle. :class:`FreeScreen` answers "free" for most such links with a
few array operations over all obstacles at once, and only where the exact test would answer
"free" too; otherwise it leaves the question to the exact test. So every decision, hence
every plan, is the one of the exact test alone.

Why a "free" of the screen is the exact test's answer
-----------------------------------------------------
The screen uses the level-0 grid of the union's sweep (:meth:`segplan.floor.sweep.Sweep.grid`,
shared with the exact test): the rear point ``A_i`` and front wheel ``B_i`` at 33 positions and,
per piece ``i`` between two positions, the bound ``e_i`` such that every point of the swept
segment over the piece lies within ``e_i`` of the convex hull of ``A_i, B_i, A_{i+1},
B_{i+1}`` (:mod:`segplan.floor.collision`, "Certified sweep"; the exact test relies on the same
bound). ``m`` is a margin far above the rounding by which our arithmetic and the exact test's
can differ (:data:`MARGIN_RTOL` times the scene's magnitude, against rounding errors of some
1e-15 of it), so a strict inequality proved here with ``m`` to spare holds in the exact test's
own arithmetic too.

*Obstacles* (:meth:`FreeScreen.obstacles_clear`). Every obstacle that
:meth:`~segplan.planning.validity.Workspace.colliding` could examine (all of them, or on floors of
more than ``VECTOR_SCREEN_MIN`` obstacles those its index returns for a box holding the one its
broad phase queries) is cleared in one of three ways:

1. its circle lies farther than its inflated radius plus ``m`` from the frame box of the swept
   segment, or its frame bounding box is separated from that box by more than ``m``: the broad
   phase rejects it (the same two tests, decided with ``m`` to spare);
2. otherwise, on every piece ``i``, the separating-axis gap along the polygon's edge normals,
   ``max_k min(n_k . P - h_k)`` over the piece's four points ``P``, exceeds ``max(e_i, tol) + m``
   (``tol``: the exact test's touching tolerance of the pair, :meth:`Sweep.quick_reject`). Then
   the exact test's certified sweep answers "free" at its first step: no sampled position
   touches (each one's gap is at least that of a piece it bounds, above ``tol``) and no piece is
   live (its gap exceeds ``e_i``); its quick checks can only answer "free" earlier. Nor can the
   certain-hit test fire: each of its samples (rear point, middle, front wheel at a ninth of the
   span, level-0 positions) lies outside some edge's half-plane, by more than ``m``, since both
   ends of its segment do.

So ``colliding`` finds no obstacle.

*Walls* (:meth:`FreeScreen.walls_clear`). Let ``c`` be the least, over the pieces and the four
walls, of the distance inside the wall that the hull bound guarantees (``-(max over the four
points of n . P - h) - e_i``): every point of the swept segment lies at least ``c`` inside every
wall. If ``c > 2 tol_w + K / (8 * 8192^2) + m`` (``tol_w``, ``K``: the exact test's wall
tolerance and front-wheel bound), :func:`~segplan.floor.collision.sweep_in_bounds` answers
"inside": its rear test evaluates rear points (all at least ``c > tol_w`` inside); its
front-wheel subdivision keeps a piece of parameter length ``h`` only if ``K h^2 / 8 >= c - tol_w
> tol_w``, so it never stops on its tolerance, and it could stop on more than 4096 live pieces
only at ``h <= 1 / 8192``, where ``K h^2 / 8 < c - tol_w``: no piece is kept there.

Tested against the exact test and against the dense shapely oracle by
``tests/test_certified.py``.
"""

from __future__ import annotations

import math

import numpy as np

from ..floor.geometry import TOUCH_RTOL
from ..floor.sweep import Sweep, corners, hull_axes
from ..model.union import Union
from .validity import VECTOR_SCREEN_MIN, Workspace, _padded

__all__ = ["MARGIN_RTOL", "FreeScreen"]

#: The screen's margin relative to the scene's magnitude (the union's span and robot length,
#: the coordinates of its start and of the obstacles near it): a million times the rounding
#: (a few 1e-15) by which its arithmetic and the exact test's may differ, and of the order of
#: the exact test's own touching tolerance (``TOUCH_RTOL``), so the screen gives up only on
#: links within some 1e-9 of the scene of a decision.
MARGIN_RTOL = 1e-9

# the front-wheel subdivision of :func:`segplan.floor.collision.sweep_in_bounds` stops on more
# than 4096 live pieces: at the earliest once its pieces are 1/8192 of the span (module docstring)
_FRONT_GUARD = 8192.0


class FreeScreen:
    """The certified screen of one workspace's unions (module docstring).

    Parameters
    ----------
    workspace : Workspace
        The validity checker whose answers the screen anticipates; its obstacles are read
        once (arrays of their circles, vertices, normals and offsets).

    Attributes
    ----------
    walls_certified, obstacles_certified : int
        Unions found surely inside the walls, surely clear of every obstacle.
    """

    def __init__(self, workspace: Workspace):
        if not isinstance(workspace, Workspace):
            raise ValueError(f"workspace must be a Workspace, got {type(workspace).__name__}")
        self.ws = workspace
        convex = workspace.convex
        self.centres = np.array([c.centre for c in convex], dtype=float).reshape(-1, 2)
        radius = np.array([c.radius for c in convex], dtype=float)
        self.radius = radius
        # the broad phase's circles (validity.Workspace) are these radii inflated so
        self.reach = radius * (1.0 + 1e-9) + 1e-9
        k = max((len(c.vertices) for c in convex), default=1)
        self.vertices = _padded([c.vertices for c in convex], k, 2)
        self.normals = _padded([c.normals for c in convex], k, 2)
        self.offsets = _padded([c.offsets for c in convex], k)
        # the largest coordinate of each obstacle (for the margin)
        self.extent = np.abs(self.vertices).max(axis=(1, 2)) if len(convex) else np.zeros(0)
        self.walls_certified = 0
        self.obstacles_certified = 0

    def union_free(self, u: Union) -> bool:
        """:meth:`Workspace.union_free`'s answer: the steering limit, then the walls and the
        obstacles, each by the screen first and by the exact test where it is unsure."""
        ws = self.ws
        if not ws.curvature_ok(u):
            return False
        sw = ws.sweep(u)
        if not (self.walls_clear(sw) or ws.in_bounds(u)):
            return False
        return self.obstacles_clear(sw) or not ws.colliding(u)

    def _margin(self, sw: Sweep, extent: float) -> float:
        return MARGIN_RTOL * (1.0 + sw.size + sw.mag + extent)

    def walls_clear(self, sw: Sweep) -> bool:
        """True only if the swept segment lies surely inside the walls (module docstring):
        then :meth:`Workspace.in_bounds` answers True. False: unsure."""
        bounds = self.ws.bounds
        if bounds is None:
            return True
        xmin, ymin, xmax, ymax = bounds
        g = sw.grid()
        # the walls in the frame: outward normals and offsets (as sweep_in_bounds)
        Nw = np.array([[-1.0, 0.0], [1.0, 0.0], [0.0, -1.0], [0.0, 1.0]])
        N = Nw @ sw.rot
        H = np.array([-xmin, xmax, -ymin, ymax]) - Nw @ sw.p0
        vA, vB = g.A @ N.T - H, g.B @ N.T - H  # (33, 4): n . P - h, negative inside
        v = np.maximum(vA, vB)
        reach = np.maximum(v[:-1], v[1:]).max(axis=1) + g.e  # per piece: the hull bound
        tol = TOUCH_RTOL * (sw.size + (xmax - xmin) + (ymax - ymin) + math.hypot(sw.x0, sw.y0))
        m = self._margin(sw, max(abs(xmin), abs(ymin), abs(xmax), abs(ymax)))
        need = 2.0 * tol + sw.K / (8.0 * _FRONT_GUARD * _FRONT_GUARD) + m
        if bool(-reach.max() > need):  # False on nan (an unbounded K or e)
            self.walls_certified += 1
            return True
        return False

    def obstacles_clear(self, sw: Sweep) -> bool:
        """True only if the swept segment is surely clear of every obstacle (module
        docstring): then :meth:`Workspace.colliding` finds none. False: unsure."""
        ws = self.ws
        n = len(self.radius)
        if n == 0:
            return True
        x0, x1, y0, y1 = sw.box
        c, s, ox, oy = sw.cos, sw.sin, sw.x0, sw.y0
        if n > VECTOR_SCREEN_MIN:
            # the world box of the frame box, as the broad phase queries it, grown further
            wx = [ox + c * fx - s * fy for fx in (x0, x1) for fy in (y0, y1)]
            wy = [oy + s * fx + c * fy for fx in (x0, x1) for fy in (y0, y1)]
            grow = 1e-6 * (1.0 + max(map(abs, wx + wy)))
            S = ws.index.query(min(wx) - grow, min(wy) - grow, max(wx) + grow, max(wy) + grow)
            if S.size == 0:
                self.obstacles_certified += 1
                return True
        else:
            S = np.arange(n)
        m = self._margin(sw, float(self.extent[S].max()))
        # 1. the broad phase's circle test, with m to spare
        C = self.centres[S]
        dx, dy = C[:, 0] - ox, C[:, 1] - oy
        fx, fy = c * dx + s * dy, c * dy - s * dx
        ex = np.maximum(np.maximum(x0 - fx, 0.0), fx - x1)
        ey = np.maximum(np.maximum(y0 - fy, 0.0), fy - y1)
        near = ~(np.hypot(ex, ey) > self.reach[S] + m)
        S, fx, fy = S[near], fx[near], fy[near]
        if S.size:
            # ... and its frame bounding boxes
            V = (self.vertices[S] - sw.p0) @ sw.rot
            px, py = V[:, :, 0], V[:, :, 1]
            sep = np.maximum(
                np.maximum(x0 - px.max(axis=1), px.min(axis=1) - x1),
                np.maximum(y0 - py.max(axis=1), py.min(axis=1) - y1),
            )
            near = ~(sep > m)
            S, fx, fy, V = S[near], fx[near], fy[near], V[near]
        if S.size:
            # 2. the certified sweep's first step, every polygon left at once
            N = self.normals[S] @ sw.rot  # (P, k, 2), frame
            H = self.offsets[S] - self.normals[S] @ sw.p0  # (P, k)
            g = sw.grid()
            tol = TOUCH_RTOL * (sw.size + self.radius[S] + np.hypot(fx, fy) + sw.mag) + m
            # no sampled position touches: apart along an edge normal or the segment's normal
            mm = np.minimum(np.einsum("ij,pkj->ipk", g.A, N), np.einsum("ij,pkj->ipk", g.B, N)) - H
            side = np.einsum("ij,pkj->ipk", g.nseg, V) - g.oseg[:, None, None]
            apart = (mm.max(axis=2) > tol) | (side.min(axis=2) > tol) | (side.max(axis=2) < -tol)
            if not apart.all():
                return False
            # no piece is live: its gap along the edge normals, else along the hull's axes, exceeds e
            need = g.e[:, None] + m
            gap = np.minimum(mm[:-1], mm[1:]).max(axis=2)  # (32, P)
            if not np.all(gap > need):  # False on nan
                if g.nrm is None:  # the hull axes, as the exact test builds (and keeps) them
                    nrm, g.qmin, g.qmax = hull_axes(corners(g.A[:-1], g.B[:-1], g.A[1:], g.B[1:]))
                    g.nrm = nrm.reshape(-1, 2)
                pv = np.einsum("ij,pkj->ipk", g.nrm, V).reshape(len(g.e), 6, len(S), -1)
                hull = np.maximum(
                    pv.min(axis=3) - g.qmax[:, :, None], g.qmin[:, :, None] - pv.max(axis=3)
                ).max(axis=1)
                if not np.all(np.maximum(gap, hull) > need):
                    return False
        self.obstacles_certified += 1
        return True
