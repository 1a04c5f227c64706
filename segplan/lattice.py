"""A resolution-complete planner: A* over a lattice of cubic-union primitives (beyond the paper).

Issue 12. The paper's search (:mod:`segplan.search`) expands few successors per node and
gives up when they run out (an enclosed goal, but also many floors a sampling planner
solves). This planner keeps the paper's pieces (cubic unions, LONGD costs, the on-line
collision test, the steering limit) and makes the search complete on a lattice, in the
shape of Hybrid A* (Dolgov et al. 2008):

* **States** are the lattice states of :mod:`segplan.primitives` laid out in the start's
  frame: the start is the state ``(0, 0, 0)``, a state ``(i, j, h)`` is the rear point
  ``start + rot(theta_s) (i r, j r)`` heading ``theta_s + angle(h)``. The start is thus
  exactly on the lattice; the goal need not be.
* **Edges** are the primitives (short unions, tight turns near the minimum radius),
  costs their exact LONGD [1].
* **Analytic expansion**: from every expanded state near the goal (and from every
  ``analytic_every``-th one, the start first) the paper's direct union to the goal is
  tried, in its optimal reference system (with the steering fallback of
  :class:`segplan.expansion.Expander`); if it is free and within the steering limit, the
  goal enters the open list with ``g + LONGD``. The search ends when the goal is taken
  from the open list.
* **h'** is ``weight`` times the Dubins length of the rear point to the goal with radius
  ``R`` (:func:`segplan.dubins.dubins_length`), a lower bound of LONGD: with
  ``weight = 1`` the plan is the cheapest over the lattice and the final unions.
* **Collision**: a per-plan grid of lower bounds of the distance to the enlarged
  obstacles and walls (a conservative rasterisation and a Euclidean distance transform)
  screens all primitives of a node at once by their sampled points
  (:attr:`segplan.primitives.Primitive.points`): a primitive whose points are all farther
  than its covering radius from every obstacle is free; one with a point in a cell lying
  wholly inside an obstacle is not; the others go to the package's certified test
  (:meth:`segplan.expansion.Workspace.colliding`, walls by
  :meth:`~segplan.expansion.Workspace.in_bounds`). Every union of the returned plan is
  checked again by the certified test.
* **Completeness**: the search expands every reachable lattice state before it says
  ``NoPathError(reason="exhausted")``, and says at which resolution; by default it then
  tries once more at half the cell size. Before searching, the grid's free cells
  (8-connected) must join the start's rear point to the goal's: if they do not, no path
  exists at all and the error comes at once (an enclosed goal).

:func:`plan_lattice` returns a :class:`segplan.search.Plan` (``version="lattice"``);
:func:`segplan.plan_scenario` calls it (``planner="lattice"``, the default) and refines
the plan (:mod:`segplan.refine`).
"""

from __future__ import annotations

import heapq
import math
import time

import numpy as np
from scipy import ndimage

from .collision import ConvexPolygon
from .cost import longd_exact_intrinsic
from .dubins import dubins_length, dubins_length_scalar
from .primitives import heading_angles, primitive_set
from .union import Union

__all__ = ["ClearanceGrid", "DistanceField", "lattice_search", "plan_lattice"]

_ANGLES = heading_angles()
#: Samples of a union screened by the grid: abscissae and positions along the segment.
_U_S = np.linspace(0.0, 1.0, 33)
_U_T = np.linspace(0.0, 1.0, 9)


class ClearanceGrid:
    """Lower bounds of the distance to the enlarged obstacles and walls, on a square grid.

    The grid lies in the lattice's frame (origin at the start's rear point, x-axis along
    its heading), with cell size ``resolution / k`` and cell corners on multiples of the
    cell, so that a lattice state's cell and the cells of its primitives' points are
    integer offsets of each other (:meth:`offsets`, :meth:`base`).

    Parameters
    ----------
    convex : sequence of segplan.collision.ConvexPolygon
        The enlarged obstacles (world coordinates).
    frame : (x, y, theta)
        The lattice's origin and x-axis angle in the world.
    bounds : (xmin, ymin, xmax, ymax) or None
        The free bounds (world); without them the grid covers the obstacles, start and
        goal with a margin ``margin`` and points beyond are at least that far from any
        obstacle.
    cell : float
        Cell size (m).
    pad : int
        Cells added around the area (room for the points of a state's primitives).
    goal : (x, y, theta)
        Included in the area without bounds.
    margin : float
        See ``bounds``.

    Notes
    -----
    A cell is *occupied* when its centre lies within ``h = cell sqrt(2) / 2`` of an
    obstacle (the obstacle's edge lines moved out by ``h``, a superset) or of the walls: the
    occupied squares cover every obstacle and everything outside the walls. For a point
    ``p`` in a free cell ``c``, the distance to any obstacle or wall is at least
    ``edt(c) cell - 2 h``, with ``edt`` the distance between the centres of ``c`` and of
    the nearest occupied cell (:func:`scipy.ndimage.distance_transform_edt`). A cell is
    *blocked* when its centre lies deeper than ``h`` inside an obstacle or beyond a wall:
    the whole square is, and the robot's segment cannot touch it.
    """

    def __init__(self, convex, frame, bounds, cell: float, pad: int, goal, margin: float):
        sx, sy, th = (float(v) for v in frame)
        c, s = math.cos(th), math.sin(th)
        self.frame = (sx, sy, th)
        self.rot = np.array([[c, -s], [s, c]])  # lattice -> world
        self.cell = g = float(cell)
        self.walls = bounds is not None
        polys = [(p.vertices - (sx, sy)) @ self.rot for p in convex]  # world -> lattice frame
        if self.walls:
            xmin, ymin, xmax, ymax = bounds
            pts = self.to_lattice(np.array([(xmin, ymin), (xmax, ymin), (xmax, ymax), (xmin, ymax)]))
            self.margin = -1.0
        else:
            pts = np.concatenate([self.to_lattice(np.array([frame[:2], goal[:2]]))] + polys)
            pts = np.concatenate(
                (pts.min(axis=0, keepdims=True) - margin, pts.max(axis=0, keepdims=True) + margin)
            )
            self.margin = float(margin) - 1e-9
        lo = np.floor(pts.min(axis=0) / g).astype(int) - pad
        hi = np.ceil(pts.max(axis=0) / g).astype(int) + pad
        self.i0, self.j0 = int(lo[0]), int(lo[1])
        self.nx, self.ny = int(hi[0] - lo[0]), int(hi[1] - lo[1])
        self.pad = int(pad)
        h = g * math.sqrt(0.5)
        cx = (self.i0 + np.arange(self.nx) + 0.5) * g
        cy = (self.j0 + np.arange(self.ny) + 0.5) * g
        occ = np.zeros((self.nx, self.ny), dtype=bool)
        blocked = np.zeros_like(occ)
        if self.walls:
            wx = sx + c * cx[:, None] - s * cy[None, :]
            wy = sy + s * cx[:, None] + c * cy[None, :]
            wall = np.minimum(np.minimum(wx - xmin, xmax - wx), np.minimum(wy - ymin, ymax - wy))
            occ |= wall <= h
            blocked |= wall < -h
        for v in polys:
            poly = ConvexPolygon(v, check=False)
            a = np.floor((v.min(axis=0) - 2 * h) / g).astype(int) - (self.i0, self.j0)
            b = np.ceil((v.max(axis=0) + 2 * h) / g).astype(int) - (self.i0, self.j0) + 1
            i0, j0 = max(int(a[0]), 0), max(int(a[1]), 0)
            i1, j1 = min(int(b[0]), self.nx), min(int(b[1]), self.ny)
            if i0 >= i1 or j0 >= j1:
                continue
            px = cx[i0:i1, None, None]
            py = cy[None, j0:j1, None]
            sd = np.max(px * poly.normals[:, 0] + py * poly.normals[:, 1] - poly.offsets, axis=-1)
            occ[i0:i1, j0:j1] |= sd <= h
            blocked[i0:i1, j0:j1] |= sd < -h
        edt = ndimage.distance_transform_edt(~occ) if occ.any() else np.full(occ.shape, 1e9)
        lower = edt * g - 2.0 * h
        lower[occ] = -1.0
        self.lower, self.blocked = lower, blocked
        self.lower_flat, self.blocked_flat = lower.ravel(), blocked.ravel()

    def to_lattice(self, pts: np.ndarray) -> np.ndarray:
        """World points ``(..., 2)`` in the lattice frame."""
        return (np.asarray(pts, dtype=float) - self.frame[:2]) @ self.rot

    def cells(self, pts: np.ndarray):
        """Cell indices of lattice-frame points ``(..., 2)`` and whether they lie in the grid."""
        i = np.floor(pts[..., 0] / self.cell).astype(np.int64) - self.i0
        j = np.floor(pts[..., 1] / self.cell).astype(np.int64) - self.j0
        inside = (i >= 0) & (i < self.nx) & (j >= 0) & (j < self.ny)
        return np.where(inside, i, 0), np.where(inside, j, 0), inside

    def screen(self, pts: np.ndarray, delta) -> tuple[np.ndarray, np.ndarray]:
        """Certainly free / certainly failing, for lattice-frame point sets ``(m, n, 2)``, radii ``delta``.

        Returns two boolean arrays ``(m,)``: all points farther than ``delta`` from every
        obstacle and wall; some point inside a blocked cell (or outside the grid, with walls).
        """
        i, j, inside = self.cells(pts)
        lb = np.where(inside, self.lower[i, j], self.margin)
        bad = inside & self.blocked[i, j]
        if self.walls:
            bad |= ~inside
        return np.min(lb, axis=-1) > delta, np.any(bad, axis=-1)

    def offsets(self, pts: np.ndarray) -> np.ndarray:
        """Flat-index offsets of lattice-frame points ``(..., 2)`` relative to a lattice point's cell."""
        i = np.floor(pts[..., 0] / self.cell).astype(np.int64)
        j = np.floor(pts[..., 1] / self.cell).astype(np.int64)
        return i * self.ny + j

    def base(self, i: int, j: int) -> int | None:
        """Flat index of the cell of the lattice point ``(i, j)`` (in grid cells), or None
        if it lies within ``pad`` of the grid's edge."""
        a, b = i - self.i0, j - self.j0
        if self.pad <= a < self.nx - self.pad and self.pad <= b < self.ny - self.pad:
            return a * self.ny + b
        return None

    def component(self, pts: np.ndarray) -> np.ndarray:
        """Labels of the 8-connected components of unblocked cells at lattice-frame points (-1 outside)."""
        if not hasattr(self, "_labels"):
            self._labels, _ = ndimage.label(~self.blocked, structure=np.ones((3, 3), dtype=int))
        i, j, inside = self.cells(pts)
        return np.where(inside, self._labels[i, j], -1)


class DistanceField:
    """Shortest distances to the goal over the free cells of a coarse grid: a dead-end aware ``h'``.

    A coarse cell (``k x k`` cells of a :class:`ClearanceGrid`) is blocked when all its
    cells are blocked (wholly inside obstacles or beyond the walls), so the free coarse
    cells contain every position of the rear point A. Distances run between cell centres
    over the 8-connected free cells (Dijkstra, :func:`scipy.sparse.csgraph.dijkstra`). A
    path of A of length ``l`` visits a chain of such cells whose octile length is at most
    ``1.0824 l + 2 sqrt(2) c`` (``c`` the coarse cell), so :meth:`lower` =
    ``(D - 2 sqrt(2) c) / 1.0824`` never exceeds the length of A's path, nor LONGD. From a
    cell not joined to the goal's cell the goal cannot be reached at all (``inf``).
    Lattice-frame coordinates.
    """

    def __init__(self, grid: ClearanceGrid, goal_xy, coarse: float):
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import dijkstra

        k = max(1, int(round(coarse / grid.cell)))
        self.c = k * grid.cell
        self.x0, self.y0 = grid.i0 * grid.cell, grid.j0 * grid.cell
        nx, ny = -(-grid.nx // k), -(-grid.ny // k)
        padded = np.zeros((nx * k, ny * k), dtype=bool)
        padded[: grid.nx, : grid.ny] = grid.blocked
        free = ~padded.reshape(nx, k, ny, k).all(axis=(1, 3))
        self.nx, self.ny = nx, ny
        ids = np.arange(nx * ny).reshape(nx, ny)
        rows, cols, w = [], [], []
        for di, dj, length in ((1, 0, 1.0), (0, 1, 1.0), (1, 1, math.sqrt(2)), (1, -1, math.sqrt(2))):
            i0, i1, j0, j1 = max(0, -di), nx - max(0, di), max(0, -dj), ny - max(0, dj)
            both = free[i0:i1, j0:j1] & free[i0 + di : i1 + di, j0 + dj : j1 + dj]
            rows.append(ids[i0:i1, j0:j1][both])
            cols.append(ids[i0 + di : i1 + di, j0 + dj : j1 + dj][both])
            w.append(np.full(int(both.sum()), length * self.c))
        r, c_, ww = np.concatenate(rows), np.concatenate(cols), np.concatenate(w)
        graph = coo_matrix((ww, (r, c_)), shape=(nx * ny, nx * ny)).tocsr()
        gi, gj = self.cell(goal_xy[0], goal_xy[1])
        if 0 <= gi < nx and 0 <= gj < ny and free[gi, gj]:
            dist = dijkstra(graph, directed=False, indices=int(ids[gi, gj]))
        else:
            dist = np.zeros(nx * ny)
        self.table = np.maximum((dist.reshape(nx, ny) - 2.0 * math.sqrt(2.0) * self.c) / 1.0824, 0.0)

    def cell(self, x: float, y: float) -> tuple[int, int]:
        return int(math.floor((x - self.x0) / self.c)), int(math.floor((y - self.y0) / self.c))

    def lower(self, x: float, y: float) -> float:
        """A lower bound of the length of A's path from ``(x, y)`` to the goal (``inf``: none)."""
        i, j = self.cell(x, y)
        if 0 <= i < self.nx and 0 <= j < self.ny:
            return float(self.table[i, j])
        return 0.0


def _union_points(u: Union) -> tuple[np.ndarray, float]:
    """World points of a union's swept segment and their covering radius (as the primitives')."""
    x = u.x_end * _U_S
    A = u.to_world(x, u.f(x))
    h = u.heading(x)
    U = np.column_stack((np.cos(h), np.sin(h)))
    B = A + u.L * U
    pts = (A[:, None, :] + u.L * _U_T[None, :, None] * U[:, None, :]).reshape(-1, 2)
    step = max(np.hypot(*np.diff(A, axis=0).T).max(), np.hypot(*np.diff(B, axis=0).T).max())
    # chords underestimate arcs; 1.25 covers the curvature of a union within the steering limit
    return pts, 0.5 * 1.25 * step + 0.5 * u.L * (_U_T[1] - _U_T[0])


GOAL = ("goal",)


class _LatticeSearch:
    """A* over the lattice laid out in the start's frame (module docstring)."""

    def __init__(
        self, scenario, ws, ex, grid, field, resolution, weight, analytic_every, goal_radius, banned
    ):
        robot = scenario.robot
        self.ws, self.ex, self.grid, self.field = ws, ex, grid, field
        self.L, self.R = robot.L, robot.min_turning_radius
        self.r = r = float(resolution)
        self.q = int(round(r / grid.cell))  # grid cells per lattice cell (exact by construction)
        self.start, self.goal = scenario.start, scenario.goal
        self.weight, self.every, self.goal_radius = weight, analytic_every, goal_radius
        self.banned = banned
        self.approach_after, self.approach_tries, self.approach_limit = 32, 2, 60
        self.approach_budget = math.pi * self.R + 2.0 * self.L
        ps = primitive_set(robot.L, robot.max_steer, r)
        self.prims = ps.by_heading
        th = self.start.theta
        self.c, self.s = math.cos(th), math.sin(th)
        gx, gy = grid.to_lattice(np.array(self.goal[:2])).tolist()
        self.goal_l = (gx, gy, math.remainder(self.goal.theta - th, 2 * math.pi))  # lattice frame
        self.offsets, self.delta, self.step, self.cost, self.points = [], [], [], [], []
        for prims in ps.by_heading:
            pts = np.stack([p.points for p in prims])
            self.points.append(pts)
            self.offsets.append(grid.offsets(pts))
            self.delta.append(np.array([p.delta for p in prims]) + 1e-9)
            self.step.append([(p.di, p.dj, p.h1) for p in prims])
            self.cost.append([p.cost for p in prims])

    def pose(self, key):
        """World pose of a lattice state."""
        i, j, h = key
        x, y = i * self.r, j * self.r
        sx, sy, th = self.start
        return (
            sx + self.c * x - self.s * y,
            sy + self.s * x + self.c * y,
            math.remainder(th + _ANGLES[h], 2 * math.pi),
        )

    def union(self, key, m, P0=None) -> Union:
        """The union of primitive ``m`` from state ``key``, between the two states' world poses."""
        from .pose import Pose

        p = self.prims[key[2]][m]
        di, dj, h1 = self.step[key[2]][m]
        P0 = Pose(*(P0 or self.pose(key)))
        P1 = Pose(*self.pose((key[0] + di, key[1] + dj, h1)))
        psi = math.atan2(P1.y - P0.y, P1.x - P0.x)
        return Union.from_intrinsic(P0, P1, p.alpha, self.L, p.d, psi, p.phi0, p.phi1)

    def near(self, pts: np.ndarray, margin: float) -> list[int]:
        """Obstacles whose bounding box meets the bounding box of world points ``pts`` grown by ``margin``."""
        bb = self.ws._bbox
        if not len(bb):
            return []
        lo, hi = pts.min(axis=0) - margin, pts.max(axis=0) + margin
        hit = (bb[:, 0] <= hi[0]) & (bb[:, 2] >= lo[0]) & (bb[:, 1] <= hi[1]) & (bb[:, 3] >= lo[1])
        return np.flatnonzero(hit).tolist()

    def certified(self, u: Union, pts: np.ndarray, delta: float | None = None) -> bool:
        """Is the union free? The package's certified test (walls, then the obstacles near it).

        With ``delta`` (every point of the swept segment lies within ``delta`` of the world
        points ``pts``), a finer screen first: the signed distances of the points to the
        edge lines of the obstacles near them (their largest, a lower bound of the
        distance to a convex polygon) and to the walls. All above ``delta``: free; a point
        strictly inside an obstacle or beyond a wall: not free. Otherwise the certified test.
        """
        near = self.near(pts, self.L if delta is None else 1.01 * delta + 1e-9)
        if delta is not None:
            lb = math.inf
            for k in near:
                poly = self.ws.convex[k]
                sd = np.max(pts @ poly.normals.T - poly.offsets, axis=1)
                if sd.min() < 0.0:
                    return False
                lb = min(lb, float(sd.min()))
            b = self.ws.bounds
            if b is not None:
                w = min(float(pts[:, 0].min()) - b[0], b[2] - float(pts[:, 0].max()))
                w = min(w, float(pts[:, 1].min()) - b[1], b[3] - float(pts[:, 1].max()))
                if w <= 0.0:
                    return False
                lb = min(lb, w)
            if lb > delta:
                return True
        self.certified_calls += 1
        return self.ws.in_bounds(u) and not self.ws.colliding(u, only=near)

    def h(self, x, y, th):
        """``weight`` times the larger of two lower bounds of LONGD: Dubins, and the grid
        distance (lattice frame)."""
        gx, gy, gth = self.goal_l
        return self.weight * max(dubins_length_scalar(x, y, th, gx, gy, gth, self.R), self.field.lower(x, y))

    def try_goal(self, key, P, g):
        """Analytic expansion: the direct union from state ``key`` (world pose ``P``) to the goal."""
        from .pose import Pose

        u = self.ex.union(Pose(*P), self.goal)
        if u is None or not self.ws.curvature_ok(u):
            return
        c = self.ex.link_cost(u)
        if not g + c < self.goal_g:
            return
        pts, dl = _union_points(u)
        free, bad = self.grid.screen(self.grid.to_lattice(pts)[None], dl)
        if bad[0] or not (free[0] or self.certified(u, pts, dl)):
            return
        self.goal_g, self.goal_parent = g + c, (key, [u])
        heapq.heappush(self.heap, (self.goal_g, -1, GOAL))

    # -- the goal's approach tree ----------------------------------------------------------
    def goal_pose(self, key):
        """World pose of a state of the lattice laid out in the goal's frame."""
        i, j, h = key
        x, y = i * self.r, j * self.r
        c, s = math.cos(self.goal.theta), math.sin(self.goal.theta)
        return (
            self.goal.x + c * x - s * y,
            self.goal.y + s * x + c * y,
            math.remainder(self.goal.theta + _ANGLES[h], 2 * math.pi),
        )

    def build_approaches(self, budget: float, limit: int):
        """States from which a chain of free primitives ends exactly at the goal (backward Dijkstra).

        The goal is the state ``(0, 0, 0)`` of a lattice laid out in its own frame; the
        predecessors of a state are reached by the primitives backwards. Every edge is
        screened and, where unsure, checked by the certified test. Keeps the states within
        ``budget`` (LONGD to the goal), at most ``limit`` of them.
        """
        from .pose import Pose

        into = [[] for _ in range(len(self.prims))]  # heading -> [(h0, m)] of primitives ending at it
        for h0, prims in enumerate(self.prims):
            for m, p in enumerate(prims):
                into[p.h1].append((h0, m))
        goal_key = (0, 0, 0)
        cost = {goal_key: 0.0}
        nxt = {goal_key: None}  # key -> (next key, union to it)
        done = set()
        heap = [(0.0, goal_key)]
        out = []
        while heap and len(out) < limit:
            c, key = heapq.heappop(heap)
            if key in done:
                continue
            done.add(key)
            if key != goal_key:
                out.append(key)
            i, j, h = key
            P1 = Pose(*self.goal_pose(key))
            for h0, m in into[h]:
                p = self.prims[h0][m]
                prev = (i - p.di, j - p.dj, h0)
                nc = c + p.cost
                if prev in done or nc > budget or not nc < cost.get(prev, math.inf):
                    continue
                P0 = Pose(*self.goal_pose(prev))
                psi = math.atan2(P1.y - P0.y, P1.x - P0.x)
                u = Union.from_intrinsic(P0, P1, p.alpha, self.L, p.d, psi, p.phi0, p.phi1)
                pts, dl = _union_points(u)
                free, bad = self.grid.screen(self.grid.to_lattice(pts)[None], dl)
                if bad[0] or not (free[0] or self.certified(u, pts, dl)):
                    continue
                cost[prev], nxt[prev] = nc, (key, u)
                heapq.heappush(heap, (nc, prev))
        self.approach_keys = out
        self.approach_cost = np.array([cost[k] for k in out])
        self.approach_next = nxt
        poses = np.array([self.goal_pose(k) for k in out]).reshape(-1, 3)
        self.approach_poses = poses
        self.approach_lattice = (
            np.column_stack((self.grid.to_lattice(poses[:, :2]), poses[:, 2] - self.start.theta))
            if len(out)
            else np.zeros((0, 3))
        )

    def approach_chain(self, key) -> list:
        """Unions from an approach state to the goal."""
        out = []
        while self.approach_next[key] is not None:
            key, u = self.approach_next[key]
            out.append(u)
        return out

    def try_approaches(self, key, P, g, x, y, th, tries: int):
        """Unions from state ``key`` to the ``tries`` most promising approach states."""
        from .pose import Pose

        if not len(self.approach_keys):
            return
        a = self.approach_lattice
        est = g + self.approach_cost + dubins_length(x, y, th, a[:, 0], a[:, 1], a[:, 2], self.R)
        for k in np.argsort(est, kind="stable")[:tries]:
            if not est[k] < self.goal_g:
                break
            Q = Pose(*self.approach_poses[k].tolist())
            u = self.ex.union(Pose(*P), Q)
            if u is None or not self.ws.curvature_ok(u):
                continue
            c = self.ex.link_cost(u)
            total = g + c + float(self.approach_cost[k])
            if not total < self.goal_g:
                continue
            pts, dl = _union_points(u)
            free, bad = self.grid.screen(self.grid.to_lattice(pts)[None], dl)
            if bad[0] or not (free[0] or self.certified(u, pts, dl)):
                continue
            self.goal_g = total
            self.goal_parent = (key, [u] + self.approach_chain(self.approach_keys[k]))
            heapq.heappush(self.heap, (self.goal_g, -1, GOAL))

    def run(self, max_expansions: int, deadline: float):
        start = (0, 0, 0)
        self.g = {start: 0.0}
        self.parent = {start: None}
        self.goal_g, self.goal_parent = math.inf, None
        self.certified_calls = 0
        self.approach_keys = None
        self.heap = [(self.h(0.0, 0.0, 0.0), 0, start)]
        closed = set()
        counter = 1
        expanded = 0
        gx, gy, _ = self.goal_l
        self.best, best_d = start, math.hypot(gx, gy)
        reason = "exhausted"
        heap, r, q, grid = self.heap, self.r, self.q, self.grid
        lower, blocked = grid.lower_flat, grid.blocked_flat
        while heap:
            if expanded >= max_expansions:
                reason = "expansions"
                break
            if expanded % 64 == 0 and time.perf_counter() > deadline:
                reason = "time"
                break
            _, _, key = heapq.heappop(heap)
            if key == GOAL:
                return ("found", expanded)
            if key in closed:
                continue
            closed.add(key)
            expanded += 1
            i, j, h = key
            g = self.g[key]
            x, y = i * r, j * r
            hd = math.hypot(gx - x, gy - y)
            if hd < best_d:
                self.best, best_d = key, hd
            P = None
            if expanded == 1 or hd <= self.goal_radius or expanded % self.every == 0:
                P = self.pose(key)
                self.try_goal(key, P, g)
            if self.approach_keys is None and expanded >= self.approach_after and self.goal_parent is None:
                self.build_approaches(self.approach_budget, self.approach_limit)
            if self.approach_keys and hd <= self.goal_radius:
                P = P or self.pose(key)
                self.try_approaches(key, P, g, x, y, _ANGLES[h], self.approach_tries)
            b = grid.base(i * q, j * q)
            if b is None:
                continue  # at the edge of the grid (no walls): the lattice ends there
            idx = self.offsets[h] + b
            free = lower[idx].min(axis=1) > self.delta[h]
            bad = blocked[idx].any(axis=1)
            for m, (di, dj, h1) in enumerate(self.step[h]):
                if bad[m]:
                    continue
                nk = (i + di, j + dj, h1)
                if nk in closed:
                    continue
                ng = g + self.cost[h][m]
                if not ng < self.g.get(nk, math.inf):
                    continue
                if (key, m) in self.banned:
                    continue
                hs = self.h((i + di) * r, (j + dj) * r, _ANGLES[h1])
                if hs == math.inf:
                    continue  # the goal's region cannot be reached from there
                if not free[m]:
                    P = P or self.pose(key)
                    world = (self.points[h][m] + (x, y)) @ grid.rot.T + (self.start.x, self.start.y)
                    if not self.certified(self.union(key, m, P), world, self.delta[h][m]):
                        continue
                self.g[nk] = ng
                self.parent[nk] = (key, m)
                heapq.heappush(heap, (ng + hs, counter, nk))
                counter += 1
        return (reason, expanded)

    def chain(self, key):
        """``[(parent_key, m), ...]``: the lattice edges from the start to ``key``."""
        out = []
        while self.parent[key] is not None:
            out.append(self.parent[key])
            key = out[-1][0]
        out.reverse()
        return out

    def make_plan(self, edges, final, expanded, t0):
        """A :class:`segplan.search.Plan` of lattice edges and the final unions to the goal (a list)."""
        from .pose import Pose
        from .search import Plan

        nodes = [Pose(*self.start)]
        unions = []
        cost = 0.0
        for key, m in edges:
            u = self.union(key, m)
            unions.append(u)
            nodes.append(u.p1)
            cost += self.cost[key[2]][m]
        kinds = ["start"] + ["lattice"] * len(edges)
        for k, u in enumerate(final or []):
            unions.append(u)
            nodes.append(u.p1)
            cost += float(longd_exact_intrinsic(u.d, u.phi0, u.phi1, u.alpha, u.L, rtol=1e-8))
            kinds.append("goal" if k == len(final) - 1 else "approach")
        st = self.ws.stats
        return Plan(
            nodes=tuple(nodes),
            unions=tuple(unions),
            cost=cost,
            search_cost=self.goal_g if final is not None else cost,
            expanded=expanded,
            generated=len(self.g),
            seconds=time.perf_counter() - t0,
            heuristic="dubins",
            cost_kind="longd",
            version="lattice",
            collision_checks=st.collision_checks,
            exact_checks=st.exact_checks,
            iterations=(),
            kinds=tuple(kinds),
        )


def _check(value, name, lo, integer=False, allow_none=False):
    if value is None and allow_none:
        return None
    ok = (
        not isinstance(value, bool) and isinstance(value, int | float) and math.isfinite(value) and value > lo
    )
    if ok and integer:
        ok = int(value) == value
    if not ok:
        kind = "an integer" if integer else "a finite number"
        raise ValueError(f"{name} must be {kind} > {lo}, got {value!r}")
    return int(value) if integer else float(value)


def plan_lattice(
    scenario,
    *,
    resolution: float | None = None,
    weight: float = 2.0,
    max_expansions: int = 200_000,
    time_limit: float = 10.0,
    retry: bool = True,
    analytic_every: int = 8,
    goal_radius: float | None = None,
    cell: float | None = None,
):
    """Plan on the lattice of cubic-union primitives (module docstring).

    Parameters
    ----------
    scenario : segplan.Scenario
    resolution : float, optional
        Lattice cell size (m); default ``L / 4``.
    weight : float
        Factor on the admissible ``h'`` (>= 1; 1: the cheapest plan over the lattice).
    max_expansions, time_limit : int, float
        Limits (NoPathError with ``reason="expansions"`` or ``"time"``).
    retry : bool
        After an exhausted lattice, search once more at half the cell size.
    analytic_every : int
        Far from the goal, try the direct union every this many expansions.
    goal_radius : float, optional
        Within this distance of the goal every expanded state tries the direct union;
        default ``4 R + 2 L``.
    cell : float, optional
        Cell size of the clearance grid (default from the floor's area, at least ``L / 20``).

    Returns
    -------
    segplan.Plan
        ``version="lattice"``, ``kinds`` ``"start"``, ``"lattice"`` and ``"goal"``.

    Raises
    ------
    NoPathError
        ``reason="exhausted"`` (no path on the lattice at the resolutions tried, named in
        the message, or no free corridor at all), ``"expansions"`` or ``"time"``.
    """
    plan, _ = lattice_search(
        scenario,
        resolution=resolution,
        weight=weight,
        max_expansions=max_expansions,
        time_limit=time_limit,
        retry=retry,
        analytic_every=analytic_every,
        goal_radius=goal_radius,
        cell=cell,
    )
    return plan


def lattice_search(
    scenario,
    *,
    resolution=None,
    weight=2.0,
    max_expansions=200_000,
    time_limit=10.0,
    retry=True,
    analytic_every=8,
    goal_radius=None,
    cell=None,
    t0=None,
):
    """:func:`plan_lattice`, also returning the :class:`segplan.expansion.Expander` it used."""
    from .expansion import Expander, Workspace
    from .search import NoPathError
    from .world import Scenario

    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    robot = scenario.robot
    L, R = robot.L, robot.min_turning_radius
    resolution = _check(resolution, "resolution", 0.0, allow_none=True)
    if resolution is not None and resolution > L:
        raise ValueError(f"resolution must be at most L={L}, got {resolution!r}")
    weight = _check(weight, "weight", 0.0)
    if weight < 1.0:
        raise ValueError(f"weight must be >= 1 (1: the admissible h'), got {weight!r}")
    max_expansions = _check(max_expansions, "max_expansions", 0, integer=True)
    time_limit = _check(time_limit, "time_limit", 0.0)
    analytic_every = _check(analytic_every, "analytic_every", 0, integer=True)
    goal_radius = _check(goal_radius, "goal_radius", 0.0, allow_none=True)
    cell = _check(cell, "cell", 0.0, allow_none=True)
    if not isinstance(retry, bool):
        raise ValueError(f"retry must be True or False, got {retry!r}")
    res = resolution or 0.25 * L
    tries = [res, 0.5 * res] if retry else [res]
    for r in tries:  # off-line work, outside the planning time: once per robot and resolution
        primitive_set(L, robot.max_steer, r)
    t0 = time.perf_counter() if t0 is None else t0
    deadline = t0 + time_limit
    ws = Workspace(scenario.enlarged, L, scenario.free_bounds, robot.max_curvature)
    ex = Expander(ws)
    start, goal = scenario.start, scenario.goal
    reach = max(
        float(np.abs(p.points).max())
        for t in tries
        for prims in primitive_set(L, robot.max_steer, t).by_heading
        for p in prims
    )
    fine = tries[-1]
    if cell is None:
        fb = scenario.free_bounds
        span = (fb[2] - fb[0]) + (fb[3] - fb[1]) if fb is not None else 40.0 * L
        cell = 0.5 * fine if (span / (0.5 * fine)) ** 2 <= 4.0e6 else fine
    elif abs(round(fine / cell) * cell - fine) > 1e-9 * fine:
        raise ValueError(f"cell must divide the finest resolution {fine:g} m, got {cell!r}")
    pad = int(math.ceil(reach / cell)) + 2
    grid = ClearanceGrid(ws.convex, tuple(start), scenario.free_bounds, cell, pad, goal, 4.0 * L + 4.0 * R)
    gl = grid.to_lattice(np.array([goal[:2]]))[0]
    field = DistanceField(grid, gl, max(cell, 0.25 * L, math.sqrt((grid.nx * grid.ny) / 2e5) * cell))

    def fail(reason, message, expanded, generated, best):
        raise NoPathError(message, reason, expanded, generated, time.perf_counter() - t0, best)

    search = None
    la, lb = grid.component(np.array([[0.0, 0.0], gl])).tolist()
    banned: set = set()
    expanded_total = 0
    for k, r in enumerate(tries):
        search = _LatticeSearch(
            scenario,
            ws,
            ex,
            grid,
            field,
            r,
            weight,
            analytic_every,
            goal_radius if goal_radius is not None else 4.0 * R + 2.0 * L,
            banned,
        )
        if la != lb:
            search.g, search.parent, search.goal_g = {(0, 0, 0): 0.0}, {(0, 0, 0): None}, math.inf
            best = search.make_plan([], None, 0, t0)
            fail(
                "exhausted",
                f"no path from {tuple(start)} to {tuple(goal)}: the goal's free region is not "
                f"connected to the start's (grid of {grid.cell:.3g} m cells); no path exists",
                0,
                1,
                best,
            )
        while True:
            outcome, expanded = search.run(max_expansions - expanded_total, deadline)
            if outcome != "found":
                break
            edges = search.chain(search.goal_parent[0])
            plan = search.make_plan(edges, search.goal_parent[1], expanded_total + expanded, t0)
            # the certified test on every union of the plan (the screen is conservative; this
            # makes the guarantee independent of it)
            bad = [i for i, u in enumerate(plan.unions) if not ws.union_free(u)]
            if not bad:
                return plan, ex
            for i in bad:
                if i < len(edges):
                    banned.add(edges[i])
            if any(i >= len(edges) for i in bad):
                break  # cannot ban a final union; stop this resolution
            expanded_total += expanded
        expanded_total += expanded
        if outcome != "exhausted" or k == len(tries) - 1:
            best = search.make_plan(search.chain(search.best), None, expanded_total, t0)
            what = {
                "exhausted": "every reachable lattice state was expanded at resolution "
                + " and ".join(f"{t:.4g} m" for t in tries[: k + 1]),
                "expansions": f"the expansion limit max_expansions={max_expansions} was reached",
                "time": f"the time limit time_limit={time_limit:g} s was reached",
            }[outcome]
            fail(
                outcome,
                f"no path from {tuple(start)} to {tuple(goal)}: {what}; expanded {expanded_total} states",
                expanded_total,
                len(search.g),
                best,
            )
    raise AssertionError("unreachable")
