"""A resolution-complete planner: A* over a lattice of cubic-union primitives (beyond the paper).

Issue 12. The paper's search (:mod:`segplan.planning.paper.search`) expands few successors per node and
gives up when they run out (an enclosed goal, but also many floors a sampling planner
solves). This planner keeps the paper's pieces (cubic unions, LONGD costs, the on-line
collision test, the steering limit) and makes the search complete on a lattice, in the
shape of Hybrid A* (Dolgov et al. 2008):

* **States** are the lattice states of :mod:`segplan.planning.lattice.primitives` laid out in the start's
  frame: the start is the state ``(0, 0, 0)``, a state ``(i, j, h)`` is the rear point
  ``start + rot(theta_s) (i r, j r)`` heading ``theta_s + angle(h)``. The start is thus
  exactly on the lattice; the goal need not be.
* **Edges** are the primitives (short unions, tight turns near the minimum radius),
  costs their exact LONGD [1].
* **Analytic expansion**: from every expanded state near the goal (and from every
  ``analytic_every``-th one, the start first) the paper's direct union to the goal is
  tried, in its optimal reference system (with the steering fallback of
  :class:`segplan.planning.links.LinkModel`); if it is free and within the steering limit, the
  goal enters the open list with ``g + LONGD``. The search ends when the goal is taken
  from the open list.
* **Goal region**: a goal in a pocket may admit no direct union from any lattice state:
  the goal's approach tree and its enclosure test (:mod:`segplan.planning.lattice.approach`).
* **h'** is ``weight`` times the larger of two lower bounds of LONGD: the Dubins length
  of the rear point to the goal with radius ``R`` (:func:`segplan.planning.dubins.dubins_length`)
  and a distance over the free cells of a coarse grid (:class:`DistanceField`: it knows
  the obstacles, so dead ends do not trap the search; a state from which the goal's
  region cannot be reached at all is dropped). With ``weight = 1`` the plan is the
  cheapest over the lattice and the final unions; the default ``weight = 2`` trades
  length (which the refinement wins back in part) for far fewer expansions. After
  :data:`segplan.planning.lattice.guide.GUIDE_AFTER` expansions without a plan (a loop around
  obstacles, which neither bound sees), the coarse lattice's cost-to-go joins them
  (:mod:`segplan.planning.lattice.guide`) with a smaller weight.
* **Collision**: a per-plan grid of lower bounds of the distance to the enlarged
  obstacles and walls (a conservative rasterisation and a Euclidean distance transform,
  :class:`ClearanceGrid`, laid out in the lattice's frame so that the cells of a
  primitive's points are integer offsets from its start's cell) screens all primitives
  of a node at once by their sampled points (:attr:`segplan.planning.lattice.primitives.Primitive.points`):
  a primitive whose points are all farther than its covering radius from every obstacle
  is free; one with a point in a cell lying wholly inside an obstacle is not. The others
  get a finer screen (signed distances of the points to the edge lines of the obstacles
  near them) and, if still unsure, the package's certified test
  (:meth:`segplan.planning.validity.Workspace.colliding`, walls by
  :meth:`~segplan.planning.validity.Workspace.in_bounds`), deferred until their state leaves the
  open list (:mod:`segplan.planning.lattice.edges`: most never do). Every union of the returned plan is
  checked again by the certified test.
* **Completeness**: the search expands every reachable lattice state before it says
  ``NoPathError(reason="exhausted")``, and says at which resolution; by default it then
  tries once more at half the cell size. Before searching, the grid's free cells
  (8-connected) must join the start's rear point to the goal's: if they do not, no path
  exists at all and the error comes at once (an enclosed goal).
* **Tight corners** (:mod:`segplan.planning.lattice.escape`): when the lattice runs out of states (or the
  goal looks enclosed), the search runs again from the ends of tight arcs of short unions
  out of the start and into the goal, which turn closer to ``R`` than any primitive; a
  plan far above the Dubins length tries the direct union between such arcs' ends.

:func:`plan_lattice` returns a :class:`segplan.planning.paper.search.Plan` (``version="lattice"``);
:func:`segplan.plan_scenario` calls it (``planner="lattice"``, the default) and refines
the plan (:mod:`segplan.planning.refine`).
"""

from __future__ import annotations

import heapq
import math
import time

import numpy as np

from ...floor.scenario import Scenario
from ...model.frame import heuristic_coefficients
from ...model.pose import Pose
from ...model.union import Union
from ..dubins import dubins_length_scalar
from ..links import LinkModel
from ..plan import NoPathError, check_limits, check_option, direct_plan, lattice_plan, union_longd
from ..validity import Workspace
from .approach import ENCLOSED_EXPANSIONS, ENCLOSURE_AFTER, ENCLOSURE_LIMIT, GOAL, GoalApproaches
from .clearance import ClearanceGrid, DistanceField, grid_resolutions, union_free_near, union_points
from .edges import DeferredChecks
from .escape import escape_search, improve_with_arcs
from .guide import GUIDE_AFTER, Guided
from .primitives import fine_points, heading_angles, heading_tables, max_reach, primitive_set
from .shortcut import shortcut_plan

__all__ = [
    "ENCLOSED_EXPANSIONS",
    "ENCLOSURE_AFTER",
    "ENCLOSURE_LIMIT",
    "GOAL_RADIUS",
    "LATTICE_MAX_EXPANSIONS",
    "lattice_options",
    "lattice_search",
    "plan_lattice",
]

_ANGLES = heading_angles()


class _LatticeSearch(GoalApproaches, Guided, DeferredChecks):
    """A* over the lattice laid out in the start's frame (module docstring)."""

    def __init__(
        self, scenario, ws, ex, grid, field, resolution, weight, analytic_every, goal_radius, banned
    ):
        self.robot = robot = scenario.robot
        self.ws, self.ex, self.grid, self.field = ws, ex, grid, field
        self.L, self.R = robot.L, robot.min_turning_radius
        self.r = r = float(resolution)
        self.q = int(round(r / grid.cell))  # grid cells per lattice cell (exact by construction)
        self.start, self.goal = scenario.start, scenario.goal
        self.weight, self.every, self.goal_radius = weight, analytic_every, goal_radius
        self.banned = banned
        self.approach_after, self.approach_tries, self.approach_limit = 32, 2, 60
        self.approach_budget = math.inf  # the nearest approach_limit states (all, if fewer)
        # the goal's enclosure test: states that reach the goal counted up to this many (more
        # on a finer lattice, and for a robot whose turns, so pockets, are wider than L)
        wider = max(1.0, self.R / self.L) ** 2
        self.enclosure_limit = int(round(ENCLOSURE_LIMIT * (0.125 * self.L / r) ** 2 * wider))
        ps = primitive_set(robot.L, robot.max_steer, r)
        self.prims = ps.by_heading
        th = self.start.theta
        self.c, self.s = math.cos(th), math.sin(th)
        gx, gy = grid.to_lattice(np.array(self.goal[:2])).tolist()
        self.goal_l = (gx, gy, math.remainder(self.goal.theta - th, 2 * math.pi))  # lattice frame
        self.fine = fine_points(ps)  # finer points for primitives close to obstacles
        self.points, cells, self.delta, self.step, self.cost = heading_tables(ps, grid.cell)
        self.offsets = [i * grid.ny + j for i, j in cells]  # flat-index offsets in this grid
        self.into_steps = self.into_tables()

    def pose(self, key):
        """World pose of a lattice state."""
        i, j, h = key
        x, y = i * self.r, j * self.r
        sx, sy, th = self.start
        return (
            sx + self.c * x - self.s * y,
            sy + self.s * x + self.c * y,
            th + float(_ANGLES[h]),
        )

    def union(self, key, m, P0=None) -> Union:
        """The union of primitive ``m`` from state ``key``, between the two states' world poses."""

        p = self.prims[key[2]][m]
        di, dj, h1 = self.step[key[2]][m]
        P0 = Pose(*(P0 or self.pose(key)))
        P1 = Pose(*self.pose((key[0] + di, key[1] + dj, h1)))
        psi = math.atan2(P1.y - P0.y, P1.x - P0.x)
        return Union.from_intrinsic(P0, P1, p.alpha, self.L, p.d, psi, p.phi0, p.phi1)

    def certified(self, u, pts: np.ndarray, delta: float | None = None) -> bool:
        """:func:`segplan.planning.lattice.clearance.union_free_near` (counts the certified tests); ``u`` a
        :class:`~segplan.model.union.Union` or a function making it (made only if the screen cannot
        decide)."""
        free, certified = union_free_near(
            self.ws, u, pts, self.L if delta is None else delta, delta is not None
        )
        self.certified_calls += certified
        return free

    def h(self, x, y, hi):
        """``weight`` times the larger of two lower bounds of LONGD, Dubins and the grid
        distance, and of the coarse lattice's cost-to-go once built (lattice frame; ``hi``
        the heading's index)."""
        gx, gy, gth = self.goal_l
        b = max(dubins_length_scalar(x, y, _ANGLES[hi], gx, gy, gth, self.R), self.field.lower(x, y))
        return self.weight * self.guided(x, y, hi, b)

    def h_state(self, key, h_known: dict) -> float:
        """:meth:`h` of lattice state ``key``, computed once (kept in ``h_known``: ``h'`` of a
        state is the same from every parent)."""
        hs = h_known.get(key)
        if hs is None:
            hs = h_known[key] = self.h(key[0] * self.r, key[1] * self.r, key[2])
        return hs

    def try_goal(self, key, P, g):
        """Analytic expansion: the direct union from state ``key`` (world pose ``P``) to the goal."""

        if ("final", key) in self.banned:
            return
        u = self.ex.union(Pose(*P), self.goal)
        if u is None or not self.ws.curvature_ok(u):
            return
        # LONGD before the screen only where it may prune (the link model keeps it per union)
        if self.goal_g < math.inf and not g + self.ex.link_cost(u) < self.goal_g:
            return
        pts, dl = union_points(u)
        free, bad = self.grid.screen(self.grid.to_lattice(pts)[None], dl)
        if bad[0] or not (free[0] or self.certified(u, pts, dl)):
            return
        self.goal_g, self.goal_parent = g + self.ex.link_cost(u), (key, [u])
        heapq.heappush(self.heap, (self.goal_g, -1, GOAL))

    def run(self, max_expansions: int, deadline: float):
        start = (0, 0, 0)
        self.g = {start: 0.0}
        self.parent = {start: None}
        self.goal_g, self.goal_parent = math.inf, None
        self.certified_calls = 0
        self.approach_keys = None
        self.enclosure_states = 0  # set by the enclosure test (GoalApproaches.enclosed)
        self.ctg = None
        self.heap = [(self.h(0.0, 0.0, 0), 0, start)]
        closed = set()
        counter = 1
        expanded = 0
        gx, gy, _ = self.goal_l
        self.best, best_d = start, math.hypot(gx, gy)
        reason = "exhausted"
        heap, r, q, grid = self.heap, self.r, self.q, self.grid
        lower = grid.lower_blocked_flat
        stop_at = math.inf  # set when the goal looks enclosed
        h_known: dict = {}
        unchecked: set = set()  # states whose edge from their parent awaits its check
        failed: set = set()  # edges (key, m) that failed it
        while heap:
            if expanded >= max_expansions:
                reason = "expansions"
                break
            if expanded >= stop_at:
                return ("enclosed", expanded)
            if expanded % 64 == 0 and time.perf_counter() > deadline:
                reason = "time"
                break
            _, _, key = heapq.heappop(heap)
            if key == GOAL:
                return ("found", expanded)
            if key in closed or key not in self.g:
                continue
            if key in unchecked:  # the edge into it is checked now (deferred.py)
                unchecked.discard(key)
                if not self.edge_free(*self.parent[key]):
                    failed.add(self.parent[key])
                    counter = self.repair(key, closed, failed, self.h_state(key, h_known), counter)
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
            if expanded == GUIDE_AFTER and self.goal_parent is None:
                self.guide(h_known, closed)
            if self.goal_parent is None and stop_at == math.inf and self.enclosed(expanded):
                stop_at = expanded + ENCLOSED_EXPANSIONS
            if self.approach_keys and hd <= self.goal_radius:
                P = P or self.pose(key)
                self.try_approaches(key, P, g, x, y, _ANGLES[h], self.approach_tries)
            b = grid.base(i * q, j * q)
            if b is None:
                continue  # at the edge of the grid (no walls): the lattice ends there
            idx = self.offsets[h] + b
            least = lower[idx].min(axis=1)
            free = least > self.delta[h]
            bad = least == -math.inf  # a blocked cell
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
                hs = self.h_state(nk, h_known)
                if hs == math.inf:
                    continue  # the goal's region cannot be reached from there
                if free[m]:
                    unchecked.discard(nk)
                else:
                    unchecked.add(nk)  # checked if and when nk leaves the open list
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
        """A :class:`segplan.planning.paper.search.Plan` of lattice edges and the final unions to the goal (a
        list): :func:`segplan.planning.plan.lattice_plan`."""

        unions = []
        cost = 0.0
        for key, m in edges:
            unions.append(self.union(key, m))
            cost += self.cost[key[2]][m]
        kinds = ["start"] + ["lattice"] * len(edges)
        for k, u in enumerate(final or []):
            unions.append(u)
            cost += union_longd(u)
            kinds.append("goal" if k == len(final) - 1 else "approach")
        search_cost = self.goal_g if final is not None else cost
        seconds = time.perf_counter() - t0
        return lattice_plan(
            Pose(*self.start), unions, kinds, cost, search_cost, expanded, len(self.g), seconds, self.ws.stats
        )


#: Default ``max_expansions`` of the lattice search.
LATTICE_MAX_EXPANSIONS = 200_000

#: Default ``goal_radius`` of :func:`plan_lattice`: ``a R + b L`` with ``(a, b)`` these.
GOAL_RADIUS = (2.0, 1.0)


def plan_lattice(
    scenario,
    *,
    resolution: float | None = None,
    weight: float = 2.0,
    max_expansions: int | None = None,
    time_limit: float = 10.0,
    retry: bool = True,
    analytic_every: int = 8,
    goal_radius: float | None = None,
    cell: float | None = None,
    escapes: bool = True,
):
    """Plan on the lattice of cubic-union primitives (module docstring).

    Parameters
    ----------
    scenario : segplan.Scenario
    resolution : float, optional
        Lattice cell size (m); default ``L / 8`` (then ``L / 16`` if ``retry``).
    weight : float
        Factor on the admissible ``h'`` (>= 1; 1: the cheapest plan over the lattice).
    max_expansions, time_limit : int, float
        Limits (NoPathError with ``reason="expansions"`` or ``"time"``); ``max_expansions``
        None: :data:`LATTICE_MAX_EXPANSIONS`.
    retry : bool
        After an exhausted lattice, search once more at half the cell size.
    analytic_every : int
        Far from the goal, try the direct union every this many expansions.
    goal_radius : float, optional
        Within this distance of the goal every expanded state tries the direct union;
        default ``2 R + L`` (:data:`GOAL_RADIUS`: every state tried costs a union, its
        steering check and LONGD; a wider radius mostly adds time, see
        ``benchmarks/plan_speed.py``).
    cell : float, optional
        Cell size of the clearance grid (m; it must divide every resolution tried); by
        default half the finest resolution, not below ``L / 16``, coarser on large floors
        (:data:`segplan.planning.lattice.clearance.MAX_CELLS`, where the lattice coarsens too unless
        ``resolution`` is given).
    escapes : bool
        Tight arcs at the ends (:mod:`segplan.planning.lattice.escape`; see :func:`lattice_search`).

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
        escapes=escapes,
    )
    return plan


def lattice_options(
    scenario, *, resolution=None, weight=2.0, retry=True, analytic_every=8, goal_radius=None, cell=None,
    escapes=True,
):  # fmt: skip
    """The options of :func:`lattice_search` checked (ValueError naming a bad one), as a
    dict without ``escapes``; :func:`segplan.plan_scenario` checks them even where it
    does not run the lattice."""
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    L = scenario.robot.L
    resolution = check_option(resolution, "resolution", 0.0, allow_none=True)
    if resolution is not None and resolution > L:
        raise ValueError(f"resolution must be at most L={L}, got {resolution!r}")
    for name, flag in (("retry", retry), ("escapes", escapes)):
        if not isinstance(flag, bool):
            raise ValueError(f"{name} must be True or False, got {flag!r}")
    return {
        "resolution": resolution,
        "weight": check_option(weight, "weight", 1.0, lo_ok=True),  # 1: the admissible h'
        "retry": retry,
        "analytic_every": check_option(analytic_every, "analytic_every", 1, integer=True, lo_ok=True),
        "goal_radius": check_option(goal_radius, "goal_radius", 0.0, allow_none=True),
        "cell": check_option(cell, "cell", 0.0, allow_none=True),
    }


def _lattice_search(
    scenario, *, resolution, weight, retry, analytic_every, goal_radius, cell, max_expansions, time_limit, t0,
    workspace,
):  # fmt: skip
    """:func:`lattice_search` without the escapes (one lattice search, its retry); the
    options checked by :func:`lattice_options`."""

    robot = scenario.robot
    L, R = robot.L, robot.min_turning_radius
    max_expansions, time_limit = check_limits(max_expansions, time_limit)
    if max_expansions is None:
        max_expansions = LATTICE_MAX_EXPANSIONS
    res = resolution or 0.125 * L
    tries = [res, 0.5 * res] if retry else [res]
    tries, cell = grid_resolutions(scenario, tries, cell, 4.0 * L + 4.0 * R, resolution is None)
    # off-line work, outside the planning time (as the paper's search): the primitives (once
    # per robot and resolution; those of the retry when it comes), the fitted coefficients of
    # the heuristic frame and of [2]
    primitive_set(L, robot.max_steer, tries[0])
    heuristic_coefficients()
    t0 = time.perf_counter() if t0 is None else t0
    deadline = t0 + time_limit
    ws = workspace or Workspace(scenario.enlarged, L, scenario.free_bounds, robot.max_curvature)
    ex = LinkModel(ws)
    start, goal = scenario.start, scenario.goal
    # the paper's direct union first: where it is free, it is the plan (no grid to build)
    direct = None if start == goal else ex.union(start, goal)
    if start == goal or (direct is not None and ws.union_free(direct)):
        return direct_plan(start, direct, time.perf_counter() - t0, ws.stats), ex
    reach = max(max_reach(L, robot.max_steer, t) for t in tries)
    pad = int(math.ceil(reach / cell)) + 2
    grid = ClearanceGrid(ws.convex, tuple(start), scenario.free_bounds, cell, pad, goal, 4.0 * L + 4.0 * R)
    gl = grid.to_lattice(np.array([goal[:2]]))[0]
    field = DistanceField(grid, gl, max(cell, 0.25 * L, math.sqrt((grid.nx * grid.ny) / 5e4) * cell))

    escapable = ""  # may tight arcs at the start or goal help? (not after a proof)

    def fail(reason, message, expanded, generated, best):
        exc = NoPathError(message, reason, expanded, generated, time.perf_counter() - t0, best)
        exc.escapable = escapable
        raise exc

    search = None
    la, lb = grid.component(np.array([[0.0, 0.0], gl])).tolist()
    banned: set = set()
    expanded_total = 0
    proofs: list = []  # (resolution, "exhausted" or "enclosed", approach states) per try
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
            goal_radius if goal_radius is not None else GOAL_RADIUS[0] * R + GOAL_RADIUS[1] * L,
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
                return shortcut_plan(plan, ex, grid, t0), ex
            for i in bad:  # never seen in our tests; the search runs again without them
                banned.add(edges[i] if i < len(edges) else ("final", search.goal_parent[0]))
            expanded_total += expanded
        expanded_total += expanded
        proofs.append((r, outcome, search.enclosure_states))
        if outcome != "exhausted" or k == len(tries) - 1:
            best = search.make_plan(search.chain(search.best), None, expanded_total, t0)
            if outcome == "exhausted":
                what = "every reachable lattice state was expanded at resolution " + " and ".join(
                    f"{t:.4g} m" for t, _, _ in proofs
                )
            elif outcome == "enclosed":
                what = (
                    f"the goal looks enclosed: only {proofs[-1][2]} states of the lattice laid out "
                    f"in the goal's frame (resolution {r:.4g} m) reach it by primitives and no union "
                    f"from the start reaches one of them; the search stopped {ENCLOSED_EXPANSIONS} "
                    "expansions later (a limit, not a proof)"
                )
                outcome = "expansions"
            else:
                what = {
                    "expansions": f"the expansion limit max_expansions={max_expansions} was reached",
                    "time": f"the time limit time_limit={time_limit:g} s was reached",
                }[outcome]
            # tight arcs may help: out of the start and into the goal after an exhausted
            # lattice, into the goal after one that looks enclosed (not after a proof)
            escapable = "both" if outcome == "exhausted" else "goal" if proofs[-1][1] == "enclosed" else ""
            fail(
                outcome,
                f"no path from {tuple(start)} to {tuple(goal)}: {what}; expanded {expanded_total} states",
                expanded_total,
                len(search.g),
                best,
            )
    raise AssertionError("unreachable")


def lattice_search(
    scenario,
    *,
    resolution=None,
    weight=2.0,
    max_expansions=None,
    time_limit=10.0,
    retry=True,
    analytic_every=8,
    goal_radius=None,
    cell=None,
    t0=None,
    workspace=None,
    escapes=True,
):
    """:func:`plan_lattice`, also returning the :class:`segplan.planning.links.LinkModel` it used.

    ``workspace``: a :class:`segplan.planning.validity.Workspace` of this scenario to reuse (the
    default planner passes the paper's search's; its counters then add up).
    ``escapes``: tight arcs out of the start and into the goal (:mod:`segplan.planning.lattice.escape`):
    when the lattice runs out of states (or the goal looks enclosed), search again between
    their ends while the limits allow, at the first resolution only (the retry's finer
    lattice, tried once between the start and the goal, would multiply the time of every
    pair); when its plan costs far more than the Dubins length, try the paper's direct
    union between their ends.
    """
    options = lattice_options(
        scenario, resolution=resolution, weight=weight, retry=retry, analytic_every=analytic_every,
        goal_radius=goal_radius, cell=cell, escapes=escapes,
    )  # fmt: skip
    t0 = time.perf_counter() if t0 is None else t0
    if workspace is None:
        robot = scenario.robot
        workspace = Workspace(scenario.enlarged, robot.L, scenario.free_bounds, robot.max_curvature)

    def search(sub, expansions, seconds, start_time=None, retry=options["retry"]):
        kw = dict(max_expansions=expansions, time_limit=seconds, t0=start_time, workspace=workspace)
        return _lattice_search(sub, **kw, **{**options, "retry": retry})

    try:
        plan, links = search(scenario, max_expansions, time_limit, t0)
    except NoPathError as exc:
        if not (escapes and getattr(exc, "escapable", "")):
            raise
        limit = LATTICE_MAX_EXPANSIONS if max_expansions is None else max_expansions
        deadline = t0 + float(time_limit)
        once = lambda *a: search(*a, retry=False)[0]  # noqa: E731 (one resolution per pair)
        plan = escape_search(scenario, workspace, exc, once, limit, deadline, t0)
        links = LinkModel(workspace)
    if escapes:
        plan = improve_with_arcs(scenario, workspace, plan, t0)
    return plan, links
