"""Clearance grids for the lattice planner (beyond the paper): cheap, conservative screens.

:class:`ClearanceGrid` holds, per square cell, a lower bound of the distance to the
enlarged obstacles and walls and whether the cell lies wholly inside one;
:class:`DistanceField` holds a lower bound of the length of the rear point's path to the
goal that knows the obstacles. Both serve the A* (:mod:`segplan.planning.lattice.astar`);
neither decides that a union is free where it is unsure: the package's certified test does
(:meth:`segplan.planning.validity.Workspace.colliding`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import ndimage

from ...floor.geometry import ConvexPolygon
from ...floor.scenario import Scenario

__all__ = [
    "MAX_CELLS",
    "ClearanceGrid",
    "Corridor",
    "DistanceField",
    "grid_resolutions",
    "obstacles_near",
    "union_free_near",
    "union_free_screened",
    "union_points",
]

#: Samples of a union: abscissae (fractions of its frame span) and positions along the segment.
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
    convex : sequence of segplan.floor.collision.ConvexPolygon
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
    overhang : float
        The robot's larger overhang (:attr:`segplan.planning.validity.Workspace.overhang`):
        subtracted from every lower bound, so that the screens of points of the segment
        A->B (the primitives' points, :func:`union_points`) stay conservative for the
        longer checked segment, each of whose points lies within ``overhang`` of A->B.
    depth : float
        How deep inside an obstacle (or beyond a wall) a point of A->B is a certain
        collision (:attr:`segplan.planning.validity.Workspace.depth`): 0 for the round body;
        a rectangular body's cells are blocked only that much deeper.

    Notes
    -----
    A cell is *occupied* when its centre lies within ``h = cell sqrt(2) / 2`` of an
    obstacle (the obstacle's edge lines moved out by ``h``, a superset) or of the walls: the
    occupied squares cover every obstacle and everything outside the walls. For a point
    ``p`` in a free cell ``c``, the distance to any obstacle or wall is at least
    ``edt(c) cell - 2 h``, with ``edt`` the distance between the centres of ``c`` and of
    the nearest occupied cell, here bounded from below by the larger of its chessboard
    distance and its taxicab distance over ``sqrt(2)``
    (:func:`scipy.ndimage.distance_transform_cdt`). A cell is
    *blocked* when its centre lies deeper than ``h + depth`` inside an obstacle or beyond a
    wall: the whole square lies deeper than ``depth``, and the robot's segment cannot touch it.
    """

    def __init__(
        self,
        convex,
        frame,
        bounds,
        cell: float,
        pad: int,
        goal,
        margin: float,
        overhang: float = 0.0,
        depth: float = 0.0,
    ):
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
            self.margin = float(margin) - 1e-9 - overhang
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
            # per row of cells, the centres inside the walls by more than h (occupied: the
            # others) and by more than -h (blocked: the others) form an interval of cy; the
            # margins 1e-9 keep both conservative against rounding
            occ |= ~self._inside_walls(cx, cy, bounds, h + 1e-9)
            blocked |= ~self._inside_walls(cx, cy, bounds, -h - 1e-9 - depth)
        for v in polys:
            poly = ConvexPolygon(v, check=False)
            a = np.floor((v.min(axis=0) - 2 * h) / g).astype(int) - (self.i0, self.j0)
            b = np.ceil((v.max(axis=0) + 2 * h) / g).astype(int) - (self.i0, self.j0) + 1
            i0, j0 = max(int(a[0]), 0), max(int(a[1]), 0)
            i1, j1 = min(int(b[0]), self.nx), min(int(b[1]), self.ny)
            if i0 >= i1 or j0 >= j1:
                continue
            # the signed distance of each centre to the edge lines moved out (the largest over
            # the edges), one edge at a time: the same sums as over an (i, j, edge) array, at
            # a fraction of its cost (no three-dimensional temporaries, no short-axis maximum)
            px, py = cx[i0:i1, None], cy[None, j0:j1]
            sd = None
            for (ux, uy), off in zip(poly.normals.tolist(), poly.offsets.tolist(), strict=True):
                e = px * ux + py * uy - off
                sd = e if sd is None else np.maximum(sd, e, out=sd)
            occ[i0:i1, j0:j1] |= sd <= h
            blocked[i0:i1, j0:j1] |= sd < -h - depth
        if occ.any():
            # a lower bound of the Euclidean distance transform at a third of its cost: the
            # chessboard and the taxicab distances over sqrt(2) never exceed it (nearly equal
            # to it within a few cells of an obstacle, where the screen needs it)
            free = ~occ
            edt = np.maximum(
                ndimage.distance_transform_cdt(free, metric="chessboard"),
                ndimage.distance_transform_cdt(free, metric="taxicab") * math.sqrt(0.5),
            )
        else:
            edt = np.full(occ.shape, 1e9)
        lower = edt * g - 2.0 * h
        if overhang:
            lower -= overhang
        lower[occ] = -1.0
        self.lower, self.blocked = lower, blocked
        self.lower_flat, self.blocked_flat = lower.ravel(), blocked.ravel()
        #: ``lower`` with ``-inf`` in the blocked cells (every other value is finite): one
        #: gather and one minimum answer both of the lattice's questions about a primitive
        self.lower_blocked_flat = np.where(blocked, -math.inf, lower).ravel()

    def _inside_walls(self, cx, cy, bounds, d: float) -> np.ndarray:
        """Cells whose centre lies more than ``d`` inside every wall (lattice-frame centres
        ``cx`` by row, ``cy`` by column): per row an interval of ``cy``."""
        sx, sy, th = self.frame
        c, s = math.cos(th), math.sin(th)
        xmin, ymin, xmax, ymax = bounds
        lo = np.full(cx.shape, -np.inf)
        hi = np.full(cx.shape, np.inf)
        # the walls' distances a + b cy, with a depending on the row
        for a, b in (
            (sx - xmin + c * cx, -s),
            (xmax - sx - c * cx, s),
            (sy - ymin + s * cx, c),
            (ymax - sy - s * cx, -c),
        ):
            if b > 0.0:
                lo = np.maximum(lo, (d - a) / b)
            elif b < 0.0:
                hi = np.minimum(hi, (d - a) / b)
            else:
                hi = np.where(a > d, hi, -np.inf)
        return (cy[None, :] > lo[:, None]) & (cy[None, :] < hi[:, None])

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

        k = max(1, int(round(coarse / grid.cell)))
        self.c = k * grid.cell
        self.x0, self.y0 = grid.i0 * grid.cell, grid.j0 * grid.cell
        nx, ny = -(-grid.nx // k), -(-grid.ny // k)
        padded = np.zeros((nx * k, ny * k), dtype=bool)
        padded[: grid.nx, : grid.ny] = grid.blocked
        # a coarse cell is blocked when its k x k cells all are: the AND of the k^2 strided
        # views (the same booleans as ``all`` over the reshaped axes, 3-30 times faster)
        cells = padded.reshape(nx, k, ny, k)
        all_blocked = cells[:, 0, :, 0].copy()
        for a in range(k):
            for b in range(k):
                if a or b:
                    all_blocked &= cells[:, a, :, b]
        free = ~all_blocked
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
        self._graph, self._free = graph, free
        # octile distances (m) from the goal's cell (zeros where that cell is not free: no
        # information)
        goal = self.octile_from(goal_xy)
        self._goal_known = goal is not None
        self.octile_goal = np.zeros((nx, ny)) if goal is None else goal
        self.table = np.maximum((self.octile_goal - 2.0 * math.sqrt(2.0) * self.c) / 1.0824, 0.0)

    def octile_from(self, xy) -> np.ndarray | None:
        """Octile distances (m) over the free coarse cells from the cell of ``xy`` (``inf``
        where not joined); None if that cell is not free."""
        from scipy.sparse.csgraph import dijkstra

        i, j = self.cell(xy[0], xy[1])
        if 0 <= i < self.nx and 0 <= j < self.ny and self._free[i, j]:
            index = i * self.ny + j
            return dijkstra(self._graph, directed=False, indices=index).reshape(self.nx, self.ny)
        return None

    def corridor(self, start_xy, extra: float, share: float = 0.0) -> Corridor | None:
        """The :class:`Corridor` of the cells through which a route from ``start_xy`` to the
        goal is at most ``extra`` (m) plus ``share`` times the shortest route longer than the
        shortest route over the free cells (the sum of the octile distances from both ends).

        None where either end's cell is not free or the two are not joined.
        """
        from_start = self.octile_from(start_xy)
        if from_start is None or not self._goal_known:
            return None
        total = from_start + self.octile_goal
        best = float(total.min())
        if not math.isfinite(best):
            return None
        # the sums along one shortest route differ in their last bits (other summation
        # orders): a relative 1e-9 keeps every cell of it
        return Corridor(total <= best * (1.0 + share + 1e-9) + extra, self.x0, self.y0, self.c)

    def cell(self, x: float, y: float) -> tuple[int, int]:
        return int(math.floor((x - self.x0) / self.c)), int(math.floor((y - self.y0) / self.c))

    def lower(self, x: float, y: float) -> float:
        """A lower bound of the length of A's path from ``(x, y)`` to the goal (``inf``: none)."""
        i, j = self.cell(x, y)
        if 0 <= i < self.nx and 0 <= j < self.ny:
            return float(self.table[i, j])
        return 0.0


class Corridor:
    """Cells of a :class:`DistanceField` that a route short enough passes through
    (:meth:`DistanceField.corridor`), and their box: where the lattice's guide is built on
    floors too large for a guide over the whole grid (:mod:`segplan.planning.lattice.guide`).

    Parameters
    ----------
    cells : ndarray of bool (nx, ny)
        The field's cells kept (at least one).
    x0, y0, c : float
        The field's corner and cell (m, lattice frame).

    Attributes
    ----------
    box : (xmin, ymin, xmax, ymax)
        The box of the cells kept (lattice frame).
    near : ndarray of bool (nx, ny)
        The cells kept and their neighbours (the cells a guide is built over: a state at the
        corridor's edge keeps the primitives that leave it).
    area : float
        The area of :attr:`near` (m^2).
    """

    def __init__(self, cells: np.ndarray, x0: float, y0: float, c: float):
        ii, jj = np.nonzero(cells)
        self.cells, self.x0, self.y0, self.c = cells, x0, y0, c
        self.box = (
            x0 + float(ii.min()) * c,
            y0 + float(jj.min()) * c,
            x0 + float(ii.max() + 1) * c,
            y0 + float(jj.max() + 1) * c,
        )
        self.near = near = ndimage.binary_dilation(cells, np.ones((3, 3), dtype=bool))
        self.area = float(near.sum()) * c * c

    def covers(self, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
        """``(len(X), len(Y))`` booleans: the point ``(X[i], Y[j])`` lies in :attr:`near`."""
        near = self.near
        i = np.floor((np.asarray(X) - self.x0) / self.c).astype(np.int64)
        j = np.floor((np.asarray(Y) - self.y0) / self.c).astype(np.int64)
        oki, okj = (i >= 0) & (i < near.shape[0]), (j >= 0) & (j < near.shape[1])
        out = near[np.where(oki, i, 0)[:, None], np.where(okj, j, 0)[None, :]]
        return out & oki[:, None] & okj[None, :]

    def __eq__(self, other) -> bool:
        return (
            isinstance(other, Corridor)
            and (self.x0, self.y0, self.c) == (other.x0, other.y0, other.c)
            and np.array_equal(self.cells, other.cells)
        )


def union_points(u) -> tuple[np.ndarray, float]:
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


def obstacles_near(ws, pts: np.ndarray, margin: float) -> list[int]:
    """Obstacles of workspace ``ws`` whose bounding box meets that of points ``pts`` grown by ``margin``."""
    if not len(ws.box_array):
        return []
    # column by column: numpy's reductions along axis 0 of an (n, 2) array are several
    # times slower than over a contiguous column
    x, y = pts[:, 0], pts[:, 1]
    return _boxes_meeting(ws, float(x.min()), float(y.min()), float(x.max()), float(y.max()), margin)


def _boxes_meeting(ws, x0: float, y0: float, x1: float, y1: float, margin: float) -> list[int]:
    """Obstacles of ``ws`` whose bounding box meets the box ``(x0, y0, x1, y1)`` grown by ``margin``."""
    bb = ws.box_array
    if not len(bb):
        return []
    x0, x1, y0, y1 = x0 - margin, x1 + margin, y0 - margin, y1 + margin
    if len(bb) <= 32:  # a few obstacles: Python floats beat numpy's per-call overhead
        return [k for k, b in enumerate(ws.boxes) if b[0] <= x1 and b[2] >= x0 and b[1] <= y1 and b[3] >= y0]
    S = ws.index.query(x0, y0, x1, y1)  # every obstacle whose box meets it, and a few others
    bb = bb[S]
    hit = (bb[:, 0] <= x1) & (bb[:, 2] >= x0) & (bb[:, 1] <= y1) & (bb[:, 3] >= y0)
    return S[hit].tolist()


def union_free_near(ws, u, pts: np.ndarray, delta: float, screen: bool = True) -> tuple[bool, int]:
    """Is union ``u`` free in workspace ``ws``? And how many certified tests it took (0 or 1).

    ``pts`` are world points such that every point of the swept segment lies within
    ``delta`` of one of them (:func:`union_points`, or a primitive's points), the robot's
    overhangs apart (the segment A->B's points: ``ws.overhang`` is added to ``delta`` here). With
    ``screen``, first the signed distances of the points to the edge lines of the
    obstacles near them (their largest over the edges, a lower bound of the distance to a
    convex polygon) and to the walls: all above ``delta``, free; a point strictly inside an
    obstacle or beyond a wall (by more than ``ws.depth``: a rectangular body), not free.
    Otherwise the package's certified test (walls by
    :meth:`~segplan.planning.validity.Workspace.in_bounds`, then
    :meth:`~segplan.planning.validity.Workspace.colliding` on the obstacles near the points).
    ``u`` may be a function without arguments that returns the union (called only then).
    """
    if ws.overhang:
        delta = delta + ws.overhang  # the checked segment reaches that far beyond A->B
    rows = np.ascontiguousarray(pts.T)  # (2, n): the reductions below run along rows
    x, y = rows
    xlo, xhi, ylo, yhi = float(x.min()), float(x.max()), float(y.min()), float(y.max())
    near = _boxes_meeting(ws, xlo, ylo, xhi, yhi, 1.01 * delta + 1e-9)  # as obstacles_near
    if screen:
        lb = math.inf
        for k in near:
            poly = ws.convex[k]
            sd = poly.normals @ rows
            sd -= poly.offsets[:, None]
            m = float(sd.max(axis=0).min())
            if m < -ws.depth:  # a point inside (deeper than a rectangular body's depth)
                return False, 0
            lb = min(lb, m)
        b = ws.bounds
        if b is not None:
            w = min(xlo - b[0], b[2] - xhi)
            w = min(w, ylo - b[1], b[3] - yhi)
            if w <= -ws.depth:
                return False, 0
            lb = min(lb, w)
        if lb > delta:
            return True, 0
    if callable(u):  # made only now: most unions are decided by the screen
        u = u()
    return ws.in_bounds(u) and not ws.colliding(u, only=near), 1


def union_free_screened(grid: ClearanceGrid, ws, u) -> bool:
    """Is union ``u`` free? Its points (:func:`union_points`) screened on ``grid`` first: a point
    in a blocked cell, not free; every point clear of obstacles by its covering radius, free;
    otherwise :func:`union_free_near`."""
    pts, dl = union_points(u)
    free, bad = grid.screen(grid.to_lattice(pts)[None], dl)
    return not bad[0] and bool(free[0] or union_free_near(ws, u, pts, dl)[0])


#: Most cells of a clearance grid (beyond, a coarser grid and lattice: large floors).
MAX_CELLS = 2.0e6


def grid_resolutions(
    scenario: Scenario, tries: list[float], cell: float | None, margin: float, free_resolution: bool
) -> tuple[list[float], float]:
    """Resolutions for the planner (:mod:`segplan.planning.lattice.search`) to try and the
    clearance grid's cell (which must divide each of them).

    By default the cell is half the finest resolution but not below ``L / 16``; where the
    grid would exceed :data:`MAX_CELLS` (an estimate from the floor's size, any rotation), the
    cell grows to the finest resolution, then the retry is dropped, then (only when the
    resolution was not given) the lattice coarsens by halves, up to ``L``.
    """
    L = scenario.robot.L
    fine = tries[-1]
    if cell is not None:
        if any(abs(round(t / cell) * cell - t) > 1e-9 * t for t in tries):
            raise ValueError(f"cell must divide the resolutions {tries}, got {cell!r}")
        return tries, cell
    fb = scenario.free_bounds
    if fb is None:
        pts = np.concatenate([np.array([scenario.start[:2], scenario.goal[:2]])] + list(scenario.enlarged))
        fb = (*(pts.min(axis=0) - margin), *(pts.max(axis=0) + margin))
    area = 0.5 * ((fb[2] - fb[0]) + (fb[3] - fb[1])) ** 2  # the rotated box, at worst
    cell = 0.5 * fine if 0.5 * fine >= L / 16.0 - 1e-12 else fine
    while area / cell**2 > MAX_CELLS:
        if cell < fine:
            cell = fine
        elif len(tries) > 1:
            tries = tries[:1]
            cell = tries[0]
        elif free_resolution and 2.0 * tries[0] <= L:
            tries = [2.0 * tries[0]]
            cell = tries[0]
        else:
            break
    return tries, cell
