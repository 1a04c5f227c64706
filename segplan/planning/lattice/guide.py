"""A heading-aware cost-to-go over a coarse lattice: the lattice planner's guide on hard floors.

Beyond the paper (issue 12). The lattice search's ``h'`` (:mod:`segplan.planning.lattice.astar`) is the
larger of two bounds: the Dubins length (knows the heading, not the obstacles) and the
:class:`segplan.planning.lattice.clearance.DistanceField` (knows the obstacles, not the heading). Where the
goal must be reached by a loop around obstacles, both lie far below the true cost, and A*
floods every state whose ``g + h'`` is below it: thousands of expansions on a floor a
Dubins car crosses easily.

:class:`HeadingField` is the cost-to-go of the coarser lattice (cell ``L / 2``, the same 16
headings and the same frame as the search's lattice, so that every search state has a
coarse twin): Dijkstra (:func:`scipy.sparse.csgraph.dijkstra`) from the goal over the
coarse primitives run backwards, with their exact LONGD [1] as costs. It is optimistic
about obstacles: a coarse primitive is dropped only if one of a few of its swept points
lies in a cell wholly inside an obstacle or beyond a wall
(:attr:`segplan.planning.lattice.clearance.ClearanceGrid.blocked`). The goal is seeded by the coarse states
near it, each with its distance to the goal (the paper's final union is not on the lattice).
It is an estimate, not a bound (the coarse lattice rounds), which the weighted search does
not need. Where it is infinite (no coarse route) the state is ranked after the states that
have one: its ``h'`` is its two bounds plus the field's largest finite cost-to-go
(:attr:`HeadingField.worst`). It stays in the open list, so completeness on the search's
lattice is not touched. (Falling back to the bounds alone ranked such states *first*, as the
bounds lie below the estimates: for robots that turn widely, whose coarse primitives leave
most coarse states without a route, the search flooded them.) Where the start itself has no
coarse route and the finer lattice of ``L / FINER_CELLS`` turns tighter (its tightest turning
primitive more than :data:`FINER_TURN` times less wide: robots whose steering limit the
coarse cells round badly, e.g. 25 or 60 deg, not the default 45 deg), the field is built
again on that lattice and kept if the start has a route there.
"""

from __future__ import annotations

import math

import numpy as np

from ...model.pose import wrap_floor
from .frame import NH, heading_angles
from .primitives import primitive_set

__all__ = [
    "COARSE_CELLS",
    "FINER_CELLS",
    "FINER_TURN",
    "MAX_BOX_STATES",
    "MAX_STATES",
    "SEED_RADIUS",
    "Guide",
    "HeadingField",
    "turns_tighter",
]

#: The coarse lattice's cell: ``L / COARSE_CELLS`` (a stored primitive set).
COARSE_CELLS = 2
#: The finer coarse lattice (``L / FINER_CELLS``) tried where the start has no coarse route.
FINER_CELLS = 4
#: ... if its tightest turning primitive is this many times less wide than the coarse one's.
FINER_TURN = 1.05
#: Coarse lattices larger than this many states are not built (the search keeps its bounds).
MAX_STATES = 400_000
#: ... nor those whose window's box (:class:`HeadingField`'s ``window``) would hold more than
#: this many states: the cost-to-go table and the primitives' tests span the box, the graph
#: only the corridor's cells. Set by hand (issue 25; 13 MB of table), not measured: the
#: corridors of the "large" sites of :mod:`segplan.studies.floor_kinds` whose guide it lets
#: be built have boxes of 0.4-0.6 million states.
MAX_BOX_STATES = 1_600_000
#: Coarse states within this many coarse cells of the goal, at most one heading step from
#: its heading, seed the Dijkstra.
SEED_RADIUS = 3.0

#: Swept points of a coarse primitive tested against the blocked cells: abscissae and
#: positions along the segment (indices into the primitives' 13 x 7 samples).
_S_IDX = (0, 3, 6, 9, 12)
_T_IDX = (0, 3, 6)

_ANGLES = heading_angles()


class HeadingField:
    """Cost-to-go of the coarse lattice from every coarse state to the goal (module docstring).

    Parameters
    ----------
    grid : segplan.planning.lattice.clearance.ClearanceGrid
        The search's clearance grid (lattice frame).
    robot : segplan.Robot
    goal : (x, y, theta)
        The goal in the lattice frame.
    resolution : float
        Coarse cell (m); a multiple of ``grid.cell``.
    window : segplan.planning.lattice.clearance.Corridor or None
        Build the coarse lattice only over the corridor's cells
        (:attr:`segplan.planning.lattice.clearance.Corridor.near`, within its box; lattice
        frame; :meth:`Guide.build`): elsewhere the cost-to-go is ``inf``. None: the whole grid.

    Attributes
    ----------
    table : ndarray (nx, ny, 16)
        The cost-to-go (m of front-wheel path; ``inf``: no coarse route).
    worst : float
        The largest finite value of ``table`` (0 if there is none).
    """

    worst: float = 0.0

    def __init__(self, grid, robot, goal, resolution: float, window=None):
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import dijkstra

        L = robot.L
        self.rc = rc = float(resolution)
        q = int(round(rc / grid.cell))
        ps = primitive_set(L, robot.max_steer, rc)
        points, _, _, step, cost = ps.heading_tables(grid.cell)
        # coarse points whose grid cell (and a margin of one coarse primitive) lies in the grid
        reach = max(float(np.abs(p).max()) for p in points)
        m = int(math.ceil(reach / grid.cell)) + 1
        I0 = -(-(grid.i0 + m) // q)
        I1 = (grid.i0 + grid.nx - m) // q
        J0 = -(-(grid.j0 + m) // q)
        J1 = (grid.j0 + grid.ny - m) // q
        if window is not None:
            box = window.box
            I0, J0 = max(I0, math.floor(box[0] / rc)), max(J0, math.floor(box[1] / rc))
            I1, J1 = min(I1, math.ceil(box[2] / rc)), min(J1, math.ceil(box[3] / rc))
        self.I0, self.J0 = I0, J0
        self.nx, self.ny = nx, ny = max(I1 - I0 + 1, 0), max(J1 - J0 + 1, 0)
        n = nx * ny * NH
        self.table = np.full((nx, ny, NH), np.inf)
        if n == 0:
            return
        X = (np.arange(nx) + I0) * rc
        Y = (np.arange(ny) + J0) * rc
        # the coarse cells of the window's corridor (None: every cell)
        inside = None if window is None else window.covers(X, Y)
        # a primitive's sample at cell offset (di, dj) from its start, over every coarse state:
        # the grid's blocked cells on a strided slice (every q-th cell from the lattice's corner)
        blocked = grid.blocked
        ci, cj = I0 * q - grid.i0, J0 * q - grid.j0

        def hit(cells, out):
            for di, dj in cells:
                out |= blocked[ci + di : ci + di + q * nx : q, cj + dj : cj + dj + q * ny : q]
            return out

        ii, jj = np.arange(nx)[None, :, None], np.arange(ny)[None, None, :]
        rows, cols, w = [], [], []
        sel = (np.array(_S_IDX[1:])[:, None] * 7 + np.array(_T_IDX)[None, :]).ravel()
        for h in range(NH):
            at = np.floor(points[h][:, sel, :] / grid.cell).astype(np.int64).tolist()
            at0 = np.floor(points[h][0, np.array(_T_IDX), :] / grid.cell).astype(np.int64).tolist()
            at_start = hit(at0, np.zeros((nx, ny), dtype=bool))  # the segment at the start
            bad = np.empty((len(at), nx, ny), dtype=bool)
            for k, cells in enumerate(at):
                bad[k] = at_start
                hit(cells, bad[k])
            di, dj, h1 = (np.array(v)[:, None, None] for v in zip(*step[h], strict=True))
            # the end state on the coarse lattice, and the primitive free of blocked cells
            ok = (ii + di >= 0) & (ii + di < nx) & (jj + dj >= 0) & (jj + dj < ny) & ~bad
            k, si, sj = np.nonzero(ok)
            if inside is not None:  # both ends in the corridor
                di_k, dj_k = di.ravel()[k], dj.ravel()[k]
                both = inside[si, sj] & inside[si + di_k, sj + dj_k]
                k, si, sj = k[both], si[both], sj[both]
            start = (si * ny + sj) * NH
            # reversed edges: from the end state to the start state
            rows.append(start + ((di * ny + dj) * NH + h1).ravel()[k])
            cols.append(start + h)
            w.append(np.asarray(cost[h])[k])
        # the seeds: coarse states near the goal, joined to a virtual node n by the Dubins
        # length to the goal (the final union)
        gx, gy, gth = goal
        rad = SEED_RADIUS * rc
        near_x = np.abs(X - gx) <= rad
        near_y = np.abs(Y - gy) <= rad
        si, sj, sh = np.meshgrid(np.nonzero(near_x)[0], np.nonzero(near_y)[0], np.arange(NH), indexing="ij")
        si, sj, sh = si.ravel(), sj.ravel(), sh.ravel()
        dh = np.abs(wrap_floor(_ANGLES[sh] - gth))
        # the goal ahead of the seed (within a cone), as a final union needs it
        ex, ey = gx - X[si], gy - Y[sj]
        ahead = ex * np.cos(_ANGLES[sh]) + ey * np.sin(_ANGLES[sh])
        side = np.abs(-ex * np.sin(_ANGLES[sh]) + ey * np.cos(_ANGLES[sh]))
        keep = (np.hypot(ex, ey) <= rad) & (dh <= 2 * math.pi / NH + 1e-9)
        keep &= (ahead >= -0.5 * rc) & (side <= 0.5 * rc + 0.6 * np.maximum(ahead, 0.0))
        si, sj, sh = si[keep], sj[keep], sh[keep]
        if si.size:
            seed = np.hypot(X[si] - gx, Y[sj] - gy)
            rows.append(np.full(si.size, n))
            cols.append((si * ny + sj) * NH + sh)
            w.append(np.asarray(seed, dtype=float) + 1e-9)
        r = np.concatenate(rows) if rows else np.zeros(0, dtype=np.int64)
        c = np.concatenate(cols) if cols else np.zeros(0, dtype=np.int64)
        graph = coo_matrix((np.concatenate(w), (r, c)), shape=(n + 1, n + 1)).tocsr()
        dist = dijkstra(graph, directed=True, indices=n)
        self.table = dist[:n].reshape(nx, ny, NH)
        finite = dist[:n][np.isfinite(dist[:n])]
        self.worst = float(finite.max()) if finite.size else 0.0

    def estimate(self, x: float, y: float, h: int) -> float:
        """The least cost-to-go of the (up to four) coarse states around ``(x, y)`` at heading ``h``.

        ``x, y`` in the lattice frame (m); ``inf`` if none has a coarse route.
        """
        fi, fj = x / self.rc - self.I0, y / self.rc - self.J0
        i, j = int(math.floor(fi)), int(math.floor(fj))
        best = math.inf
        t = self.table
        for a in (i, i + 1):
            if 0 <= a < self.nx:
                for b in (j, j + 1):
                    if 0 <= b < self.ny:
                        v = t[a, b, h]
                        if v < best:
                            best = v
        return float(best)

    @staticmethod
    def resolution(grid, L: float, cells: int = COARSE_CELLS, window=None) -> float | None:
        """The coarse cell for ``grid`` (``L / cells``), or None if that is not a
        multiple of the grid's cell or the coarse lattice (over ``window`` if given, a
        corridor as in :class:`HeadingField`) would exceed :data:`MAX_STATES` states, or its
        window's box :data:`MAX_BOX_STATES`."""
        rc = L / cells
        q = rc / grid.cell
        if abs(q - round(q)) > 1e-9 or round(q) < 1:
            return None
        area = grid.nx * grid.ny * grid.cell**2
        if window is not None:
            box = window.box
            if (box[2] - box[0] + 2 * rc) * (box[3] - box[1] + 2 * rc) / (rc * rc) * NH > MAX_BOX_STATES:
                return None
            area = min(area, window.area)
        if area / (rc * rc) * NH > MAX_STATES:
            return None
        return rc


def turns_tighter(robot, coarse: float, fine: float) -> bool:
    """Does the lattice of cell ``fine`` turn tighter than that of ``coarse`` (:data:`FINER_TURN`)?"""
    L, steer = robot.L, robot.max_steer
    wide = primitive_set(L, steer, coarse).turning_radii().min()
    return bool(wide > FINER_TURN * primitive_set(L, steer, fine).turning_radii().min())


class Guide:
    """The lattice search's guide: the coarse cost-to-go once built, and ``h'`` raised to it.

    Parameters
    ----------
    grid : segplan.planning.lattice.clearance.ClearanceGrid
        The search's clearance grid (lattice frame).
    robot : segplan.Robot
    goal : (x, y, theta)
        The goal in the lattice frame.
    window : callable or None
        Called where the whole grid's coarse lattice would exceed :data:`MAX_STATES`, with a
        scale of its slack (1, then doubled while the start has no coarse route in it): a
        :class:`segplan.planning.lattice.clearance.Corridor` (lattice frame) to build the
        lattice over instead, or None. The search hands the corridor of its distance field
        (:meth:`segplan.planning.lattice.clearance.DistanceField.corridor`).

    Attributes
    ----------
    field : HeadingField or None
        The cost-to-go, once :meth:`build` made it.
    """

    def __init__(self, grid, robot, goal, window=None):
        self.grid, self.robot, self.goal = grid, robot, goal
        self.window = window
        self.field: HeadingField | None = None

    def raise_bound(self, x: float, y: float, hi: int, bound: float) -> float:
        """``bound`` raised to the coarse cost-to-go at ``(x, y)``, heading ``hi``, once built;
        where that is infinite, ``bound`` plus the field's largest finite value (module docstring)."""
        if self.field is not None:
            e = self.field.estimate(x, y, hi)
            if e == math.inf:
                return bound + self.field.worst
            if bound < e:
                return e
        return bound

    def build(self) -> bool:
        """Build the coarse cost-to-go (:class:`HeadingField`; again at ``L / FINER_CELLS`` if the
        start has no coarse route and that lattice turns tighter, :func:`turns_tighter`), over
        the :attr:`window` where the whole grid's would be too large. False if the grid admits
        no coarse lattice (:meth:`HeadingField.resolution`)."""
        L = self.robot.L
        box = None
        rc = HeadingField.resolution(self.grid, L)
        if rc is None and self.window is not None:  # too large: a window only
            return self._build_windowed()
        if rc is None:
            return False
        self.field = HeadingField(self.grid, self.robot, self.goal, rc, box)
        if self.field.estimate(0.0, 0.0, 0) == math.inf:  # the start (lattice origin) has no route
            fine = HeadingField.resolution(self.grid, L, FINER_CELLS, box)
            if fine is not None and turns_tighter(self.robot, rc, fine):
                field = HeadingField(self.grid, self.robot, self.goal, fine, box)
                if field.estimate(0.0, 0.0, 0) < math.inf:
                    self.field = field
        return True

    def _build_windowed(self) -> bool:
        """The coarse cost-to-go over the window (:attr:`window`), grown by doubling its slack
        while the start has no coarse route in it and the grown window stays within
        :data:`MAX_STATES` (the largest one built is kept). False if none could be built."""
        L = self.robot.L
        scale, tried = 1.0, None
        while True:
            corridor = self.window(scale)
            if corridor is None or corridor == tried:
                break
            rc = HeadingField.resolution(self.grid, L, window=corridor)
            if rc is None:
                break
            self.field = HeadingField(self.grid, self.robot, self.goal, rc, corridor)
            if self.field.estimate(0.0, 0.0, 0) < math.inf:
                break
            scale, tried = 2.0 * scale, corridor
        return self.field is not None
