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

from .cost import longd_exact_intrinsic
from .dubins import dubins_length_scalar
from .primitives import heading_angles, primitive_set
from .union import Union

__all__ = ["ClearanceGrid", "DistanceField", "lattice_search", "plan_lattice"]

_ANGLES = heading_angles()
#: Samples of a union screened by the grid: abscissae and positions along the segment.
_U_S = np.linspace(0.0, 1.0, 33)
_U_T = np.linspace(0.0, 1.0, 9)


class ClearanceGrid:
    """Lower bounds of the distance to the enlarged obstacles and walls, on a square grid.

    Parameters
    ----------
    convex : sequence of segplan.collision.ConvexPolygon
        The enlarged obstacles.
    box : (xmin, ymin, xmax, ymax)
        Area covered (the free bounds, or a box around everything when there are none).
    cell : float
        Cell size (m).
    walls : bool
        Whether the box is a wall (the free bounds): points outside it fail.

    Notes
    -----
    A cell is *occupied* when its centre lies within ``h = cell sqrt(2) / 2`` of an
    obstacle (the obstacle's edge lines moved out by ``h``, a superset) or of the walls: the
    occupied squares cover every obstacle. For a point ``p`` in a free cell ``c``, the
    distance to any obstacle is at least ``edt(c) cell - 2 h``, with ``edt`` the distance
    between the centres of ``c`` and of the nearest occupied cell. A cell is *blocked*
    when its centre lies deeper than ``h`` inside an obstacle: the whole square is inside.
    """

    def __init__(self, convex, box, cell: float, walls: bool):
        self.x0, self.y0 = float(box[0]), float(box[1])
        self.cell = float(cell)
        self.walls = bool(walls)
        self.nx = max(1, int(math.ceil((box[2] - box[0]) / cell)))
        self.ny = max(1, int(math.ceil((box[3] - box[1]) / cell)))
        h = self.cell * math.sqrt(0.5)
        cx = self.x0 + (np.arange(self.nx) + 0.5) * cell
        cy = self.y0 + (np.arange(self.ny) + 0.5) * cell
        occ = np.zeros((self.nx, self.ny), dtype=bool)
        blocked = np.zeros_like(occ)
        if walls:
            wx = np.minimum(cx - box[0], box[2] - cx)
            wy = np.minimum(cy - box[1], box[3] - cy)
            occ |= np.minimum.outer(wx, wy) <= h
        for poly in convex:
            lo = poly.vertices.min(axis=0) - 2 * h
            hi = poly.vertices.max(axis=0) + 2 * h
            i0, i1 = self._index(lo[0], self.x0, self.nx), self._index(hi[0], self.x0, self.nx) + 1
            j0, j1 = self._index(lo[1], self.y0, self.ny), self._index(hi[1], self.y0, self.ny) + 1
            if i0 >= i1 or j0 >= j1:
                continue
            px = cx[i0:i1, None, None]
            py = cy[None, j0:j1, None]
            s = np.max(px * poly.normals[:, 0] + py * poly.normals[:, 1] - poly.offsets, axis=-1)
            occ[i0:i1, j0:j1] |= s <= h
            blocked[i0:i1, j0:j1] |= s < -h
        self.occupied = occ
        self.blocked = blocked
        edt = ndimage.distance_transform_edt(~occ) if occ.any() else np.full(occ.shape, 1e9)
        lb = edt * cell - 2.0 * h
        lb[occ] = -1.0
        self.lower = lb
        self.margin = math.inf  # lower bound outside the box (set by the planner without walls)

    def _index(self, v: float, origin: float, n: int) -> int:
        return min(max(int(math.floor((v - origin) / self.cell)), 0), n)

    def cells(self, pts: np.ndarray):
        """Cell indices of points ``(..., 2)`` and whether they lie inside the grid."""
        i = np.floor((pts[..., 0] - self.x0) / self.cell).astype(np.int64)
        j = np.floor((pts[..., 1] - self.y0) / self.cell).astype(np.int64)
        inside = (i >= 0) & (i < self.nx) & (j >= 0) & (j < self.ny)
        return np.where(inside, i, 0), np.where(inside, j, 0), inside

    def screen(self, pts: np.ndarray, delta) -> tuple[np.ndarray, np.ndarray]:
        """Certainly free / certainly failing, for sets of points ``(m, n, 2)`` with radii ``delta``.

        Returns two boolean arrays ``(m,)``: all points farther than ``delta`` from every
        obstacle and wall; some point inside a blocked cell (or outside the walls).
        """
        i, j, inside = self.cells(pts)
        lb = np.where(inside, self.lower[i, j], -1.0 if self.walls else self.margin)
        bad = inside & self.blocked[i, j]
        if self.walls:
            bad |= ~inside
        return np.min(lb, axis=-1) > delta, np.any(bad, axis=-1)

    def label_of(self, x: float, y: float, labels: np.ndarray) -> int:
        i, j, inside = self.cells(np.array([x, y]))
        return int(labels[int(i), int(j)]) if inside else -1


def _grid(ws, start, goal, L: float, R: float, cell: float | None) -> ClearanceGrid:
    """The clearance grid of a workspace (the free bounds, or a box around everything)."""
    if ws.bounds is not None:
        box, walls = ws.bounds, True
        margin = math.inf
    else:
        pts = [np.array([start[:2], goal[:2]])] + list(ws.polygons)
        allp = np.concatenate(pts)
        margin = 4.0 * L + 4.0 * R
        box = (*(allp.min(axis=0) - margin), *(allp.max(axis=0) + margin))
        walls = False
    if cell is None:
        area = (box[2] - box[0]) * (box[3] - box[1])
        cell = max(L / 20.0, math.sqrt(area / 4.0e5))
    grid = ClearanceGrid(ws.convex, box, cell, walls)
    if not walls:
        grid.margin = margin - 1e-9
    return grid


class DistanceField:
    """Shortest distances to the goal over the free cells of a coarse grid: a dead-end aware ``h'``.

    A coarse cell (``k x k`` cells of a :class:`ClearanceGrid`) is blocked when all its
    cells are blocked (wholly inside obstacles), so the free coarse cells contain every
    position of the rear point A. Distances run between cell centres over the 8-connected
    free cells (Dijkstra, :func:`scipy.sparse.csgraph.dijkstra`). A path of A of length
    ``l`` visits a chain of such cells whose octile length is at most
    ``1.0824 l + 2 sqrt(2) c`` (``c`` the coarse cell), so :meth:`lower` =
    ``(D - 2 sqrt(2) c) / 1.0824`` never exceeds the length of A's path, nor LONGD. A cell
    the goal's cell cannot be reached from cannot reach the goal at all (``inf``).
    """

    def __init__(self, grid: ClearanceGrid, goal, coarse: float):
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import dijkstra

        k = max(1, int(round(coarse / grid.cell)))
        self.k, self.c = k, k * grid.cell
        self.x0, self.y0 = grid.x0, grid.y0
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
        gi, gj = self.cell(goal[0], goal[1])
        if 0 <= gi < nx and 0 <= gj < ny and free[gi, gj]:
            dist = dijkstra(graph, directed=False, indices=int(ids[gi, gj]))
        else:
            dist = np.zeros(nx * ny)
        self.lower_table = np.maximum((dist.reshape(nx, ny) - 2.0 * math.sqrt(2.0) * self.c) / 1.0824, 0.0)

    def cell(self, x: float, y: float) -> tuple[int, int]:
        return int(math.floor((x - self.x0) / self.c)), int(math.floor((y - self.y0) / self.c))

    def lower(self, x: float, y: float) -> float:
        """A lower bound of the length of A's path from ``(x, y)`` to the goal (``inf``: none)."""
        i, j = self.cell(x, y)
        if 0 <= i < self.nx and 0 <= j < self.ny:
            return float(self.lower_table[i, j])
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
        self.r = float(resolution)
        self.start, self.goal = scenario.start, scenario.goal
        self.weight, self.every, self.goal_radius = weight, analytic_every, goal_radius
        self.banned = banned
        ps = primitive_set(robot.L, robot.max_steer, self.r)
        self.prims = ps.by_heading
        th = self.start.theta
        self.c, self.s = math.cos(th), math.sin(th)
        rot = np.array([[self.c, -self.s], [self.s, self.c]])
        self.points, self.delta, self.step, self.cost, self.end = [], [], [], [], []
        for prims in ps.by_heading:
            self.points.append(np.stack([p.points @ rot.T for p in prims]))
            self.delta.append(np.array([p.delta for p in prims]))
            self.step.append([(p.di, p.dj, p.h1) for p in prims])
            self.cost.append([p.cost for p in prims])
            ends = np.array([[p.di * self.r, p.dj * self.r] for p in prims]) @ rot.T
            self.end.append(
                [
                    (float(e[0]), float(e[1]), th + float(_ANGLES[p.h1]))
                    for e, p in zip(ends, prims, strict=True)
                ]
            )

    def pose(self, key):
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

    def near(self, pts: np.ndarray) -> list[int]:
        """Obstacles whose bounding box meets the bounding box of ``pts``."""
        bb = self.ws._bbox
        if not len(bb):
            return []
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        hit = (bb[:, 0] <= hi[0]) & (bb[:, 2] >= lo[0]) & (bb[:, 1] <= hi[1]) & (bb[:, 3] >= lo[1])
        return np.flatnonzero(hit).tolist()

    def certified(self, u: Union, pts: np.ndarray) -> bool:
        """The package's certified test of a union (walls, then the obstacles near it)."""
        self.certified_calls += 1
        return self.ws.in_bounds(u) and not self.ws.colliding(u, only=self.near(pts))

    def h(self, x, y, th):
        """``weight`` times the larger of two lower bounds of LONGD: Dubins, and the grid distance."""
        g = self.goal
        return self.weight * max(
            dubins_length_scalar(x, y, th, g.x, g.y, g.theta, self.R), self.field.lower(x, y)
        )

    def try_goal(self, key, P, g):
        """Analytic expansion: the direct union from state ``key`` to the goal."""
        from .pose import Pose

        u = self.ex.union(Pose(*P), self.goal)
        if u is None or not self.ws.curvature_ok(u):
            return
        c = self.ex.link_cost(u)
        if not g + c < self.goal_g:
            return
        pts, dl = _union_points(u)
        free, bad = self.grid.screen(pts[None], dl)
        if bad[0] or not (free[0] or self.certified(u, pts)):
            return
        self.goal_g, self.goal_parent = g + c, (key, u)
        heapq.heappush(self.heap, (self.goal_g, -1, GOAL))

    def run(self, max_expansions: int, deadline: float):
        start = (0, 0, 0)
        self.g = {start: 0.0}
        self.parent = {start: None}
        self.goal_g, self.goal_parent = math.inf, None
        self.certified_calls = 0
        sx, sy, sth = self.start
        self.heap = [(float(self.h(sx, sy, sth)), 0, start)]
        closed = set()
        counter = 1
        expanded = 0
        best, best_d = start, math.hypot(self.goal.x - sx, self.goal.y - sy)
        reason = "exhausted"
        heap = self.heap
        while heap:
            if expanded >= max_expansions:
                reason = "expansions"
                break
            if expanded % 64 == 0 and time.perf_counter() > deadline:
                reason = "time"
                break
            f, _, key = heapq.heappop(heap)
            if key == GOAL:
                return ("found", expanded)
            if key in closed:
                continue
            closed.add(key)
            expanded += 1
            g = self.g[key]
            P = self.pose(key)
            hd = math.hypot(self.goal.x - P[0], self.goal.y - P[1])
            if hd < best_d:
                best, best_d = key, hd
            if expanded == 1 or hd <= self.goal_radius or expanded % self.every == 0:
                self.try_goal(key, P, g)
            h = key[2]
            pts = self.points[h] + np.array(P[:2])
            free, bad = self.grid.screen(pts, self.delta[h])
            ends = self.end[h]
            for m, (di, dj, h1) in enumerate(self.step[h]):
                if bad[m]:
                    continue
                nk = (key[0] + di, key[1] + dj, h1)
                if nk in closed:
                    continue
                ng = g + self.cost[h][m]
                if not ng < self.g.get(nk, math.inf):
                    continue
                if (key, m) in self.banned:
                    continue
                ex_, ey_, eth = ends[m]
                hs = self.h(P[0] + ex_, P[1] + ey_, eth)
                if hs == math.inf:
                    continue  # the goal's region cannot be reached from there
                if not free[m] and not self.certified(self.union(key, m, P), pts[m]):
                    continue
                self.g[nk] = ng
                self.parent[nk] = (key, m)
                heapq.heappush(heap, (ng + hs, counter, nk))
                counter += 1
        self.best = best
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
        """A :class:`segplan.search.Plan` of lattice edges and an optional final union."""
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
        if final is not None:
            unions.append(final)
            nodes.append(final.p1)
            cost += float(
                longd_exact_intrinsic(final.d, final.phi0, final.phi1, final.alpha, final.L, rtol=1e-8)
            )
            kinds.append("goal")
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
    grid = _grid(ws, scenario.start, scenario.goal, L, R, cell)
    start, goal = scenario.start, scenario.goal

    def fail(reason, message, expanded, generated, best):
        raise NoPathError(message, reason, expanded, generated, time.perf_counter() - t0, best)

    search = None
    field = DistanceField(
        grid, goal, max(grid.cell, 0.25 * L, math.sqrt((grid.nx * grid.ny) / 2e5) * grid.cell)
    )
    labels, _ = ndimage.label(~grid.blocked, structure=np.ones((3, 3), dtype=int))
    la, lb = grid.label_of(start.x, start.y, labels), grid.label_of(goal.x, goal.y, labels)
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
            if len(plan.unions) - 1 in bad:
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
