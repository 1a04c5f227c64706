"""The lattice planner's A*: weighted A* over a lattice of cubic-union primitives (beyond the paper).

Issue 12. One search at one resolution (the planner around it, its retry, escapes and
shortcuts: :mod:`segplan.planning.lattice.search`), in the shape of Hybrid A* (Dolgov et al.
2008) with the paper's pieces (cubic unions, LONGD costs, the on-line collision test, the
steering limit):

* **States** are those of the lattice (:class:`segplan.planning.lattice.frame.LatticeFrame`)
  laid out at the start: the start is the state ``(0, 0, 0)``; the goal need not be on it.
* **Edges** are the primitives (:mod:`segplan.planning.lattice.primitives`), costs their exact
  LONGD [1]. An expanded state's primitives are screened at once on the clearance grid
  (:class:`segplan.planning.lattice.clearance.ClearanceGrid`, laid out in the lattice's frame so
  that the cells of a primitive's points are integer offsets from its start's cell): one
  whose points are all farther than its covering radius from every obstacle is free; one with
  a point in a blocked cell is not; the others are checked when their state leaves the open
  list (:class:`segplan.planning.lattice.edges.LazyEdges`).
* **Analytic expansion**: from every expanded state near the goal (and from every
  ``analytic_every``-th one, the start first) the paper's direct union to the goal is tried
  in its optimal reference system (section "Optimal Reference System"; with the steering
  fallback of :class:`segplan.planning.links.LinkModel`); if it is free and within the steering
  limit, the goal enters the open list with ``g + LONGD``. The search ends when the goal is
  taken from the open list.
* **Goal region**: near the goal, unions to the goal's approach tree
  (:class:`segplan.planning.lattice.approach.GoalApproach`), which also tells when the goal
  looks enclosed.
* **h'** is ``weight`` times the larger of two lower bounds of LONGD: the Dubins length of the
  rear point to the goal with radius ``R`` (:func:`segplan.planning.dubins.dubins_length_scalar`)
  and a distance over the free cells of a coarse grid
  (:class:`segplan.planning.lattice.clearance.DistanceField`; a state from which the goal's
  region cannot be reached at all is dropped). After :attr:`Schedule.guide_after` expansions
  without a plan, the coarse lattice's cost-to-go joins them
  (:class:`segplan.planning.lattice.guide.Guide`) with the smaller weight
  :attr:`Schedule.guided_weight`.

When each mechanism starts and how much it does: :class:`segplan.planning.schedule.Schedule`.
"""

from __future__ import annotations

import heapq
import math
import time

import numpy as np

from ...model.pose import Pose, wrap_ieee
from ...model.union import Union
from ..dubins import dubins_length_scalar
from ..plan import Plan, lattice_plan, union_longd
from ..schedule import SCHEDULE, Schedule
from .approach import GoalApproach
from .clearance import union_free_near, union_free_screened
from .edges import LazyEdges
from .frame import LatticeFrame, heading_angles
from .guide import Guide
from .primitives import primitive_set

__all__ = ["GOAL", "LatticeAStar"]

#: The goal's entry in the open list.
GOAL = ("goal",)

_ANGLES = heading_angles()


class LatticeAStar:
    """Weighted A* over the lattice laid out at the start (module docstring).

    Parameters
    ----------
    scenario : segplan.Scenario
    ws : segplan.planning.validity.Workspace
        The certified tests.
    links : segplan.planning.links.LinkModel
        The paper's unions (direct union to the goal, unions to the approach tree).
    grid : segplan.planning.lattice.clearance.ClearanceGrid
        Laid out at the start; its cell divides ``resolution``.
    field : segplan.planning.lattice.clearance.DistanceField
        The grid distance to the goal (a bound of ``h'``).
    resolution : float
        The lattice's cell (m).
    weight : float
        Factor on the admissible ``h'`` (>= 1).
    analytic_every : int
        Far from the goal, the direct union is tried every this many expansions.
    goal_radius : float
        Within this distance of the goal every expanded state tries the direct union and
        the approach tree.
    banned : set
        Edges ``(key, m)`` and final unions ``("final", key)`` that the planner's final
        certified check refused (the search runs again without them).
    schedule : Schedule
        When each mechanism starts and how much it does.
    edges, approach, guide : optional
        The parts, if not the default ones: :class:`LazyEdges` of this lattice (its
        :meth:`screen_edge` and :meth:`check_edge`), :class:`GoalApproach`, :class:`Guide`.
    progress : callable, optional
        Called with the expansions so far at every look at the clock (it only watches).
    """

    def __init__(
        self,
        scenario,
        ws,
        links,
        grid,
        field,
        resolution: float,
        *,
        weight: float,
        analytic_every: int,
        goal_radius: float,
        banned: set,
        schedule: Schedule = SCHEDULE,
        edges: LazyEdges | None = None,
        approach: GoalApproach | None = None,
        guide: Guide | None = None,
        progress=None,
    ):
        self.robot = robot = scenario.robot
        self.ws, self.ex, self.grid, self.field = ws, links, grid, field
        self.L, self.R = robot.L, robot.min_turning_radius
        self.r = r = float(resolution)
        self.q = int(round(r / grid.cell))  # grid cells per lattice cell (exact by construction)
        self.start, self.goal = scenario.start, scenario.goal
        self.weight, self.every, self.goal_radius = weight, analytic_every, goal_radius
        self.banned, self.schedule = banned, schedule
        self.progress = progress  # called with the expansions at every look at the clock
        ps = primitive_set(robot.L, robot.max_steer, r)
        self.prims = ps.by_heading
        self.frame = LatticeFrame(self.start, r, self.L)
        gx, gy = grid.to_lattice(np.array(self.goal[:2])).tolist()
        self.goal_l = (
            gx,
            gy,
            wrap_ieee(self.goal.theta - self.start.theta),
        )  # lattice frame
        self.fine = ps.fine_points()  # finer points for primitives close to obstacles
        _, cells, self.delta, self.step, self.cost = ps.heading_tables(grid.cell)
        self.offsets = [i * grid.ny + j for i, j in cells]  # flat-index offsets in this grid
        # per heading h1: (h0, m, di, dj) of the primitives that end at heading h1
        self.into_steps: list = [[] for _ in self.step]
        for h0, steps in enumerate(self.step):
            for m, (di, dj, h1) in enumerate(steps):
                self.into_steps[h1].append((h0, m, di, dj))
        self.edges = LazyEdges(self.screen_edge, self.check_edge) if edges is None else edges
        if guide is None:
            guide = Guide(grid, robot, self.goal_l, lambda k: schedule.guide_box(field, self.L, self.R, k))
        self.guide = guide
        if approach is None:
            approach = GoalApproach(
                robot, self.start, self.goal, r, self.prims, self.fine, grid, ws, links, schedule
            )
        self.approach = approach

    # -- the lattice on the grid ---------------------------------------------------------------
    def union(self, key, m: int) -> Union:
        """The union of primitive ``m`` from state ``key`` (:meth:`LatticeFrame.union`)."""
        return self.frame.union(key, self.prims[key[2]][m])

    def screen_edge(self, edge) -> tuple[bool, bool]:
        """The grid's screen of primitive ``m`` from state ``key`` (``edge = (key, m)``, the
        primitive tables' integer cell offsets): certainly free, certainly failing (a point in
        a blocked cell, or ``key`` at the grid's edge)."""
        (i, j, h), m = edge
        b = self.grid.base(i * self.q, j * self.q)
        if b is None:
            return False, True
        least = self.grid.lower_blocked_flat[self.offsets[h][m] + b].min()
        if least == -math.inf:
            return False, True
        return least > self.delta[h][m], False

    def check_edge(self, edge) -> bool:
        """The finer screen and, if still unsure, the certified test of primitive ``m`` from
        state ``key`` (``edge = (key, m)``)."""
        (i, j, h), m = edge
        fp, fd = self.fine[h]
        world = (fp[m] + (i * self.r, j * self.r)) @ self.grid.rot.T + (self.start.x, self.start.y)
        return union_free_near(self.ws, lambda: self.union((i, j, h), m), world, fd[m] + 1e-9)[0]

    # -- h' ------------------------------------------------------------------------------------
    def h(self, x: float, y: float, hi: int) -> float:
        """``weight`` times the larger of two lower bounds of LONGD, Dubins and the grid
        distance, and of the coarse lattice's cost-to-go once built (lattice frame; ``hi``
        the heading's index)."""
        gx, gy, gth = self.goal_l
        b = max(dubins_length_scalar(x, y, _ANGLES[hi], gx, gy, gth, self.R), self.field.lower(x, y))
        return self.weight * self.guide.raise_bound(x, y, hi, b)

    def h_state(self, key, h_known: dict) -> float:
        """:meth:`h` of lattice state ``key``, computed once (kept in ``h_known``: ``h'`` of a
        state is the same from every parent)."""
        hs = h_known.get(key)
        if hs is None:
            hs = h_known[key] = self.h(key[0] * self.r, key[1] * self.r, key[2])
        return hs

    # -- the goal ------------------------------------------------------------------------------
    def found(self, cost: float, parent: tuple) -> None:
        """A way to the goal for ``cost``: ``parent = (state, unions from it to the goal)``."""
        self.goal_g, self.goal_parent = cost, parent
        heapq.heappush(self.heap, (self.goal_g, -1, GOAL))

    def try_goal(self, key, P, g: float) -> None:
        """Analytic expansion: the direct union from state ``key`` (world pose ``P``) to the goal."""
        if ("final", key) in self.banned:
            return
        u = self.ex.union(Pose(*P), self.goal)
        if u is None or not self.ws.curvature_ok(u):
            return
        # LONGD before the screen only where it may prune (the link model keeps it per union)
        if self.goal_g < math.inf and not g + self.ex.link_cost(u) < self.goal_g:
            return
        if not union_free_screened(self.grid, self.ws, u):
            return
        self.found(g + self.ex.link_cost(u), (key, [u]))

    # -- the search ----------------------------------------------------------------------------
    def run(self, max_expansions: int, deadline: float) -> tuple[str, int]:
        """Search until the goal is taken from the open list or a limit is met.

        Returns ``(outcome, expanded)``: ``"found"`` (then :attr:`goal_parent` and
        :meth:`chain` give the plan), ``"exhausted"`` (every reachable state expanded),
        ``"enclosed"`` (:meth:`GoalApproach.enclosed`), ``"expansions"`` or ``"time"``
        (``deadline``, a :func:`time.perf_counter` value).
        """
        sch = self.schedule
        start = (0, 0, 0)
        self.g = {start: 0.0}
        self.parent = {start: None}
        self.goal_g, self.goal_parent = math.inf, None
        self.approach.reset()
        self.guide.field = None
        self.edges.reset()
        self.heap = [(self.h(0.0, 0.0, 0), 0, start)]
        closed = set()
        counter = 1
        expanded = 0
        gx, gy, _ = self.goal_l
        self.best, best_d = start, math.hypot(gx, gy)
        reason = "exhausted"
        heap, r, q, grid, edges = self.heap, self.r, self.q, self.grid, self.edges
        lower = grid.lower_blocked_flat
        stop_at = math.inf  # set when the goal looks enclosed
        h_known: dict = {}
        reported = 0  # the expansions last handed to progress
        while heap:
            if expanded >= max_expansions:
                reason = "expansions"
                break
            if expanded >= stop_at:
                return ("enclosed", expanded)
            if expanded % sch.deadline_every == 0:
                if time.perf_counter() > deadline:
                    reason = "time"
                    break
                if self.progress is not None and 0 < expanded != reported:
                    self.progress(expanded)
                    reported = expanded
            _, _, key = heapq.heappop(heap)
            if key == GOAL:
                return ("found", expanded)
            if key in closed or key not in self.g:
                continue
            if edges.pending(key) and not edges.check(key, self.parent[key]):  # deferred until now
                counter = self.repair(key, closed, self.h_state(key, h_known), counter)
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
                P = self.frame.pose(key)
                self.try_goal(key, P, g)
            if expanded == sch.guide_after and self.goal_parent is None:
                self.rerank(h_known, closed)
            if self.goal_parent is None and stop_at == math.inf and self.approach.enclosed(expanded):
                stop_at = expanded + sch.enclosed_expansions
            if self.approach.keys and hd <= self.goal_radius and ("final", key) not in self.banned:
                P = P or self.frame.pose(key)
                way = self.approach.connect(P, g, x, y, _ANGLES[h], self.goal_g)
                if way is not None:
                    self.found(way[0], (key, way[1]))
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
                edges.defer(nk, free[m])  # if unsure, checked if and when nk leaves the open list
                self.g[nk] = ng
                self.parent[nk] = (key, m)
                heapq.heappush(heap, (ng + hs, counter, nk))
                counter += 1
        return (reason, expanded)

    def repair(self, key, closed: set, h: float, counter: int) -> int:
        """State ``key``'s edge failed its check: give it the cheapest passing edge from an
        expanded state (in ``closed``) not banned (:meth:`LazyEdges.repair`) and push it again
        with ``h'`` = ``h``; without one, forget its ``g``. Returns the next heap counter."""
        i, j, h1 = key
        options = []
        for h0, m, di, dj in self.into_steps[h1]:
            prev = (i - di, j - dj, h0)
            if prev not in closed or (prev, m) in self.banned:
                continue
            options.append((self.g[prev] + self.cost[h0][m], prev, (prev, m)))
        way = self.edges.repair(options)
        if way is None:
            del self.g[key], self.parent[key]
            return counter
        ng, _, edge = way
        self.g[key], self.parent[key] = ng, edge
        heapq.heappush(self.heap, (ng + h, counter, key))
        return counter + 1

    def rerank(self, h_known: dict, closed: set) -> None:
        """Build the guide (:meth:`Guide.build`) and, if built, lower the weight to
        :attr:`Schedule.guided_weight` and re-rank the open list by the new ``h'`` (computed
        anew, once per state in ``h_known``; the entries of expanded states, in ``closed``, are
        dropped)."""
        if not self.guide.build():
            return
        self.weight = min(self.weight, self.schedule.guided_weight)  # a closer estimate needs less weight
        h_known.clear()
        heap = []
        for f, n, key in self.heap:
            if key != GOAL:
                if key in closed or key not in self.g:
                    continue  # expanded, or its edge failed and no other joins it yet
                f = self.g[key] + self.h_state(key, h_known)
            heap.append((f, n, key))
        heapq.heapify(heap)
        self.heap[:] = heap

    # -- the plan ------------------------------------------------------------------------------
    def reach(self) -> tuple[float, float]:
        """How far the search got from the start: the largest distance (m) of a state it reached
        from the start, and the largest turn (radians, at most pi) of such a state's heading from
        the start's. States generated but not yet expanded count (their unions may be unchecked),
        so both are upper bounds of where the robot can get."""
        keys = np.array(list(self.g), dtype=float)
        distance = self.r * float(np.hypot(keys[:, 0], keys[:, 1]).max())
        turn = float(np.abs(_ANGLES[keys[:, 2].astype(int)]).max())
        return distance, turn

    def chain(self, key) -> list:
        """``[(parent_key, m), ...]``: the lattice edges from the start to ``key``."""
        out = []
        while self.parent[key] is not None:
            out.append(self.parent[key])
            key = out[-1][0]
        out.reverse()
        return out

    def make_plan(self, edges, final, expanded: int, t0: float) -> Plan:
        """A :class:`segplan.planning.plan.Plan` of lattice edges and the final unions to the goal
        (a list, or None): :func:`segplan.planning.plan.lattice_plan`."""
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
