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
broad phase queries) must be cleared, in three stages:

1. (all of them at once) the broad phase rejects it: its circle lies farther than its inflated
   radius plus ``m`` from the frame box of the swept segment (the broad phase's own test,
   decided with ``m`` to spare);
2. (those left at once, world coordinates) on every piece ``i``, the separating-axis gap along
   the polygon's edge normals, ``max_k min(n_k . P - h_k)`` over the piece's four points ``P``,
   exceeds ``max(e_i + m, tol + m)`` (``tol``: a bound of the exact test's touching tolerances of
   these obstacles, :meth:`Sweep.quick_reject`, with ``|c - p0| <= |c| + |p0|``; the gap does not
   depend on the frame but for rounding). Then the exact test's certified sweep answers "free"
   at its first step: no sampled position touches (each one's gap along the edge normals is at
   least that of a piece it bounds, above ``tol``) and no piece is live (its gap exceeds
   ``e_i``); its quick checks can only answer "free" earlier. Nor can the certain-hit test
   fire: each of its samples (rear point, middle, front wheel at each eighth of the span, level-0
   positions) lies outside some edge's half-plane, since both ends of its segment do.
3. (those left, in the union's frame, with the exact test's own axes) the broad phase rejects
   it by its frame bounding box, separated from the sweep's frame box by more than ``m``; or
   the certified sweep's first step answers "free" with its other axes: every sampled position
   is apart along an edge normal or along the segment's own normal (all vertices on one side
   of its line) by more than ``tol + m``, so none touches and no certain hit lies inside; and on
   every piece the gap along the edge normals or along the axes of the piece's hull
   (:func:`segplan.floor.sweep.hull_axes`, the very arrays the exact test builds and keeps on
   the sweep) exceeds ``e_i + m``.

So ``colliding`` finds no obstacle.

*Walls* (:meth:`FreeScreen.walls_clear`). Let ``c`` be the least distance inside the walls of
the 66 points ``A_i, B_i`` less the largest ``e_i``: every point of the swept segment lies at
least ``c`` inside every wall (each lies within ``e_i`` of a hull of four of the points). If
``c > 2 tol_w + K / (8 * 8192^2) + m`` (``tol_w``, ``K``: the exact test's wall tolerance and
front-wheel bound), :func:`~segplan.floor.collision.sweep_in_bounds` answers "inside": its rear
test evaluates rear points (all at least ``c > tol_w`` inside); its front-wheel subdivision
keeps a piece of parameter length ``h`` only if ``K h^2 / 8 >= c - tol_w > tol_w``, so it never
stops on its tolerance, and it could stop on more than 4096 live pieces only at
``h <= 1 / 8192``, where ``K h^2 / 8 < c - tol_w``: no piece is kept there.

The argument relies on the exact test as :mod:`segplan.floor.collision` implements it (its
level-0 grid, tolerances and guards): a change there must keep this screen's premises, which
``tests/test_certified.py`` checks on random worlds (the screen's "free" against the exact
test's answer and the dense shapely oracle).

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
        self.radius = np.array([c.radius for c in convex], dtype=float)
        # the broad phase's circles (validity.Workspace) are these radii inflated so
        self.reach = self.radius * (1.0 + 1e-9) + 1e-9
        self.k = k = max((len(c.vertices) for c in convex), default=1)
        self.vertices = _padded([c.vertices for c in convex], k, 2)
        self.normals = _padded([c.normals for c in convex], k, 2)
        self.offsets = _padded([c.offsets for c in convex], k)
        # every edge of every obstacle in a row (the first stage's one product)
        self.normal_rows = self.normals.reshape(-1, 2).T.copy()  # (2, n k)
        self.offset_rows = self.offsets.ravel()
        # per obstacle: its largest coordinate (the margin) and radius plus centre's norm (tol)
        self.extent = np.abs(self.vertices).max(axis=(1, 2)) if len(convex) else np.zeros(0)
        self.far = self.radius + np.hypot(self.centres[:, 0], self.centres[:, 1])
        self.walls_certified = 0
        self.obstacles_certified = 0

    def union_free(self, u: Union) -> bool:
        """:meth:`Workspace.union_free`'s answer: the steering limit, then the walls and the
        obstacles, each by the screen first and by the exact test where it is unsure."""
        ws = self.ws
        if not ws.curvature_ok(u):
            return False
        sw = ws.sweep(u)
        A, B = self._world(sw)
        if not (self.walls_clear(sw, A, B) or ws.in_bounds(u)):
            return False
        return self.obstacles_clear(sw, A, B) or not ws.colliding(u)

    @staticmethod
    def _world(sw: Sweep) -> tuple[np.ndarray, np.ndarray]:
        """The level-0 rear and front points of the sweep (:meth:`Sweep.grid`) in the world."""
        g = sw.grid()
        back = sw.rot.T  # frame -> world for row vectors
        return g.A @ back + sw.p0, g.B @ back + sw.p0

    def walls_clear(self, sw: Sweep, A: np.ndarray | None = None, B: np.ndarray | None = None) -> bool:
        """True only if the swept segment lies surely inside the walls (module docstring):
        then :meth:`Workspace.in_bounds` answers True. False: unsure.

        ``A``, ``B``: the sweep's level-0 points in the world (:meth:`_world`), if at hand.
        """
        bounds = self.ws.bounds
        if bounds is None:
            return True
        if A is None or B is None:
            A, B = self._world(sw)
        xmin, ymin, xmax, ymax = bounds
        P = np.concatenate((A, B))
        (x0, y0), (x1, y1) = P.min(axis=0).tolist(), P.max(axis=0).tolist()
        # every point of the swept segment lies within the largest e of the points' hulls
        c = min(x0 - xmin, y0 - ymin, xmax - x1, ymax - y1) - float(sw.grid().e.max())
        tol = TOUCH_RTOL * (sw.size + (xmax - xmin) + (ymax - ymin) + math.hypot(sw.x0, sw.y0))
        m = self._margin(sw, max(abs(xmin), abs(ymin), abs(xmax), abs(ymax)))
        if c > 2.0 * tol + sw.K / (8.0 * _FRONT_GUARD * _FRONT_GUARD) + m:  # False on nan
            self.walls_certified += 1
            return True
        return False

    def _margin(self, sw: Sweep, extent: float) -> float:
        return MARGIN_RTOL * (1.0 + sw.size + sw.mag + extent)

    def obstacles_clear(self, sw: Sweep, A: np.ndarray | None = None, B: np.ndarray | None = None) -> bool:
        """True only if the swept segment is surely clear of every obstacle (module
        docstring): then :meth:`Workspace.colliding` finds none. False: unsure.

        ``A``, ``B``: the sweep's level-0 points in the world (:meth:`_world`), if at hand.
        """
        n = len(self.radius)
        if n == 0:
            return True
        if A is None or B is None:
            A, B = self._world(sw)
        S = self._indexed(sw) if n > VECTOR_SCREEN_MIN else np.arange(n)
        if S.size:
            m = self._margin(sw, float(self.extent[S].max()))
            # stage 1: the broad phase's circle test, with m to spare, all of them at once
            x0, x1, y0, y1 = sw.box
            c, s = sw.cos, sw.sin
            C = self.centres[S]
            dx, dy = C[:, 0] - sw.x0, C[:, 1] - sw.y0
            fx, fy = c * dx + s * dy, c * dy - s * dx
            ex = np.maximum(np.maximum(x0 - fx, 0.0), fx - x1)
            ey = np.maximum(np.maximum(y0 - fy, 0.0), fy - y1)
            S = S[~(np.hypot(ex, ey) > self.reach[S] + m)]
        if S.size:
            # stage 2, in the world: every edge normal of the obstacles left at once
            g = sw.grid()
            normals = self.normals[S].reshape(-1, 2).T
            mm = (np.minimum(A @ normals, B @ normals) - self.offsets[S].ravel()).reshape(len(A), -1, self.k)
            gap = np.minimum(mm[:-1], mm[1:]).max(axis=2)  # (32, obstacles)
            # the largest touching tolerance of these obstacles (|c - p0| <= |c| + |p0|)
            far = float(self.far[S].max())
            tol = TOUCH_RTOL * (sw.size + far + math.hypot(sw.x0, sw.y0) + sw.mag) + m
            left = ~np.all(gap > np.maximum(g.e + m, tol)[:, None], axis=0)  # False on nan
            # stage 3, in the frame, for the obstacles left: as the broad phase and the exact test
            if left.any() and not self._frame_clear(sw, S[left], mm[:, left], tol, m):
                return False
        self.obstacles_certified += 1
        return True

    def _indexed(self, sw: Sweep) -> np.ndarray:
        """The obstacles the index files near the world box of the sweep's frame box (a
        superset of those the broad phase of :meth:`Workspace.colliding` examines)."""
        x0, x1, y0, y1 = sw.box
        c, s, ox, oy = sw.cos, sw.sin, sw.x0, sw.y0
        wx = [ox + c * fx - s * fy for fx in (x0, x1) for fy in (y0, y1)]
        wy = [oy + s * fx + c * fy for fx in (x0, x1) for fy in (y0, y1)]
        grow = 1e-6 * (1.0 + max(map(abs, wx + wy)))
        return self.ws.index.query(min(wx) - grow, min(wy) - grow, max(wx) + grow, max(wy) + grow)

    def _frame_clear(self, sw: Sweep, S: np.ndarray, mm: np.ndarray, tol: float, m: float) -> bool:
        """Stage 3 (module docstring): obstacles ``S`` rejected by the broad phase's
        bounding-box test, or cleared by the certified sweep's first step with the segment's
        and the hull's axes. ``mm``: stage 2's ``min(n . A - h, n . B - h)`` of these obstacles,
        ``tol``: a bound of their touching tolerances, ``m`` included."""
        x0, x1, y0, y1 = sw.box
        # ... and its frame bounding boxes
        V = (self.vertices[S] - sw.p0) @ sw.rot  # (P, k, 2), frame
        px, py = V[:, :, 0], V[:, :, 1]
        sep = np.maximum(
            np.maximum(x0 - px.max(axis=1), px.min(axis=1) - x1),
            np.maximum(y0 - py.max(axis=1), py.min(axis=1) - y1),
        )
        near = ~(sep > m)
        if not near.any():
            return True
        V, mm = V[near], mm[:, near]
        g = sw.grid()
        # no sampled position touches: apart along an edge normal or the segment's normal
        side = np.einsum("ij,pkj->ipk", g.nseg, V) - g.oseg[:, None, None]
        apart = (mm.max(axis=2) > tol) | (side.min(axis=2) > tol) | (side.max(axis=2) < -tol)
        if not apart.all():
            return False
        # no piece is live: its gap along the edge normals, else along the hull's axes, exceeds e
        if g.nrm is None:  # the hull axes, as the exact test builds (and keeps) them
            nrm, g.qmin, g.qmax = hull_axes(corners(g.A[:-1], g.B[:-1], g.A[1:], g.B[1:]))
            g.nrm = nrm.reshape(-1, 2)
        pv = np.einsum("ij,pkj->ipk", g.nrm, V).reshape(len(g.e), 6, len(V), -1)
        hull = np.maximum(pv.min(axis=3) - g.qmax[:, :, None], g.qmin[:, :, None] - pv.max(axis=3)).max(
            axis=1
        )
        gap = np.minimum(mm[:-1], mm[1:]).max(axis=2)
        return bool(np.all(np.maximum(gap, hull) > (g.e + m)[:, None]))
