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
  :attr:`Schedule.guided_weight`; at each :attr:`Schedule.escalate_every` expansions
  without a plan after that, the weight grows by :attr:`Schedule.escalate_factor` (the open
  list re-ranked; :attr:`LatticeAStar.boost`).
* **Reverse** (a robot that may reverse, issue 26; :mod:`segplan.planning.lattice.reverse`):
  every state also has the reverse links of its heading, a state's heading index says its
  last direction (``h + NH`` after a reverse link), edges cost ``reverse_factor`` times
  their LONGD backwards and ``cusp_penalty`` more at a change of direction, the direct
  union to the goal is tried both ways, and ``h'`` uses the Reeds–Shepp length instead of
  Dubins'. The goal's approach tree (forward) still joins states near the goal, but its
  enclosure test, which knows forward approaches only, does not stop the search, and the
  coarse lattice's cost-to-go (forward) does not guide it.

  Tried on 2026-12-07 and not kept: a second approach tree of *backward* arrivals (the
  states reached from the goal by forward primitives, joined by a reverse union and driven
  backwards to the goal). On the reverse study's 400 floors it changed 29 plans (12 shorter,
  17 longer, mostly reverse parkings), left every kind's median and worst length as they
  were (dead-end-022 still 1.200 times OMPL's: with the weight 2 its better route, two
  cusps and a reverse arrival, is never expanded) and made the k-turns' median time about
  a third longer (1.06 -> 1.42 s, one run each).

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
from ..reeds_shepp import reeds_shepp_length
from ..schedule import SCHEDULE, Schedule
from .approach import GoalApproach
from .clearance import union_free_near, union_free_screened
from .edges import LazyEdges
from .frame import NH, LatticeFrame, heading_angles
from .guide import Guide
from .primitives import max_reach, primitive_set
from .reverse import DirectionTables

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
    reverse_factor, cusp_penalty : float
        For a robot that may reverse (``scenario.robot.reverse``): the factor on a reverse
        link's LONGD and the cost of a change of direction (m); unused otherwise.
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
        reverse_factor: float = 1.0,
        cusp_penalty: float = 0.0,
    ):
        self.robot = robot = scenario.robot
        self.ws, self.ex, self.grid, self.field = ws, links, grid, field
        self.L, self.R = robot.L, robot.min_turning_radius
        self.r = r = float(resolution)
        self.q = int(round(r / grid.cell))  # grid cells per lattice cell (exact by construction)
        self.start, self.goal = scenario.start, scenario.goal
        self.weight, self.every, self.goal_radius = weight, analytic_every, goal_radius
        #: a forward search's factor on ``weight``, 1 at each :meth:`run`'s start, times
        #: ``schedule.escalate_factor`` at each ``escalate_every`` expansions without a plan
        #: once the guide is built (:class:`segplan.planning.schedule.Schedule`)
        self.boost = 1.0
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
        self.reverse = robot.reverse
        self.reverse_factor, self.cusp_penalty = reverse_factor, cusp_penalty
        self.bound_factor = min(1.0, reverse_factor)  # h' stays a lower bound of every link's cost
        if self.reverse:
            reach = max_reach(robot.L, robot.max_steer, r)
            t = DirectionTables.build(ps, grid.cell, reverse_factor, cusp_penalty, reach)
            self.edge_prims, self.fine, self.delta, self.step = t.edges, t.fine, t.delta, t.step
            self.cost, self.length, cells = t.cost, t.length, t.cells
        else:
            self.fine = ps.fine_points()  # finer points for primitives close to obstacles
            _, cells, self.delta, self.step, self.cost = ps.heading_tables(grid.cell)
            self.edge_prims = [[(p, False) for p in prims] for prims in self.prims]
            self.length = self.cost
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
        """The union of edge ``m`` from state ``key`` (:meth:`LatticeFrame.union`): its
        primitive's, from the far end for a reverse edge (:mod:`segplan.planning.lattice.reverse`)."""
        p, back = self.edge_prims[key[2]][m]
        if back:
            return self.frame.union((key[0] - p.di, key[1] - p.dj, p.h0), p)
        return self.frame.union(key, p)

    def backed(self, key) -> bool:
        """Was state ``key`` reached by a reverse link?"""
        return key[2] >= NH

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
        if self.reverse:
            return self.weight * self.bound_of(x, y, hi % NH, hi >= NH, {})
        b = max(dubins_length_scalar(x, y, _ANGLES[hi], gx, gy, gth, self.R), self.field.lower(x, y))
        return self.weight * self.boost * self.guide.raise_bound(x, y, hi, b)

    def bound_of(self, x: float, y: float, hi: int, back: bool, rs_known: dict) -> float:
        """A robot that may reverse: a lower bound of the cost to the goal from ``(x, y)``,
        heading index ``hi`` (lattice frame), after a reverse link if ``back``, else after a
        forward one; ``rs_known`` keeps the Reeds–Shepp lengths computed, by ``(x, y, hi)``.

        A plan from there either keeps the last direction to the goal, or changes it at least
        once. Kept forwards, its cost is at least the Dubins length to the goal; kept
        backwards, ``reverse_factor`` times the Dubins length from the goal back to the pose
        (a reverse path is a forward path driven backwards in time); with a change, at least
        ``cusp_penalty`` plus ``min(1, reverse_factor)`` times the Reeds–Shepp length. Each
        length is at least the grid distance
        (:class:`segplan.planning.lattice.clearance.DistanceField`), and each bounds LONGD
        [1] from below (:mod:`segplan.planning.dubins`, :mod:`segplan.planning.reeds_shepp`);
        the bound is the smaller of the kept direction's and the change's. The Reeds–Shepp
        length, the dearest to compute, only where the change's bound with the straight-line
        distance in its place is below the kept direction's. (Computing it only when a state
        leaves the open list, the straight-line bound until then, expanded 18 % more states
        on a K-turn and took longer: measured on ``benchmarks/reverse_defaults.py``'s turn-1
        and the bay.)"""
        kept, rough = self._kept_and_rough(x, y, hi, back)
        if not rough < kept:
            return kept
        gx, gy, gth = self.goal_l
        rs = rs_known.get((x, y, hi))
        if rs is None:
            rs = rs_known[x, y, hi] = reeds_shepp_length(x, y, _ANGLES[hi], gx, gy, gth, self.R)
        return min(kept, self.cusp_penalty + self.bound_factor * max(rs, self.field.lower(x, y)))

    def _kept_and_rough(self, x: float, y: float, hi: int, back: bool) -> tuple[float, float]:
        """:meth:`bound_of`'s bound of the kept direction, and of a change with the straight-line
        distance for the Reeds–Shepp length."""
        gx, gy, gth = self.goal_l
        th, R = _ANGLES[hi], self.R
        lower = self.field.lower(x, y)
        if back:
            kept = self.reverse_factor * max(dubins_length_scalar(gx, gy, gth, x, y, th, R), lower)
        else:
            kept = max(dubins_length_scalar(x, y, th, gx, gy, gth, R), lower)
        return kept, self.cusp_penalty + self.bound_factor * max(math.hypot(gx - x, gy - y), lower)

    def h_state(self, key, h_known: dict) -> float:
        """:meth:`h` of lattice state ``key``, computed once (kept in ``h_known``: ``h'`` of a
        state is the same from every parent)."""
        hs = h_known.get(key)
        if hs is None and self.reverse:  # the two directions of a state share its Reeds-Shepp length
            i, j, h = key
            rs_known = h_known.setdefault("reeds_shepp", {})
            hs = h_known[key] = self.weight * self.bound_of(i * self.r, j * self.r, h % NH, h >= NH, rs_known)
            return hs
        if hs is None:
            hs = h_known[key] = self.h(key[0] * self.r, key[1] * self.r, key[2])
        return hs

    # -- the goal ------------------------------------------------------------------------------
    def found(self, cost: float, parent: tuple, directions: tuple = ()) -> None:
        """A way to the goal for ``cost``: ``parent = (state, unions from it to the goal)``,
        ``directions`` those of the unions (``()``: forwards)."""
        self.goal_g, self.goal_parent = cost, parent
        self.goal_directions = directions
        heapq.heappush(self.heap, (self.goal_g, -1, GOAL))

    def try_goal(self, key, P, g: float) -> None:
        """Analytic expansion: the direct union from state ``key`` (world pose ``P``) to the
        goal; for a robot that may reverse, also the union from the goal to ``P`` driven
        backwards, each with the cost of its direction (:mod:`segplan.planning.lattice.reverse`)."""
        if ("final", key) in self.banned:
            return
        if not self.reverse:
            self.try_final(key, self.ex.union(Pose(*P), self.goal), g, 1.0)
            return
        back = self.backed(key)
        self.try_final(key, self.ex.union(Pose(*P), self.goal), g + back * self.cusp_penalty, 1.0)
        rf, turn = self.reverse_factor, (not back) * self.cusp_penalty
        self.try_final(key, self.ex.union(self.goal, Pose(*P)), g + turn, rf, -1)

    def try_final(self, key, u, g: float, factor: float, direction: int = 1) -> None:
        """The final union ``u`` (or None) from state ``key``, of cost ``g`` plus ``factor`` times
        its LONGD, into the open list if it is free and keeps the steering limit."""
        if u is None or not self.ws.curvature_ok(u):
            return
        # LONGD before the screen only where it may prune (the link model keeps it per union)
        if self.goal_g < math.inf and not g + factor * self.ex.link_cost(u) < self.goal_g:
            return
        if not union_free_screened(self.grid, self.ws, u):
            return
        self.found(g + factor * self.ex.link_cost(u), (key, [u]), () if direction == 1 else (direction,))

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
        self.goal_directions: tuple = ()
        self.approach.reset()
        self.guide.field = None
        self.boost = 1.0
        self.edges.reset()
        self.heap = [(self.h(0.0, 0.0, 0), 0, start)]
        counter = 1
        if self.reverse:  # the start is reached both ways: no cusp for a first reverse link
            back = (0, 0, NH)
            self.g[back], self.parent[back] = 0.0, None
            self.heap.append((self.h(0.0, 0.0, NH), 1, back))
            counter = 2
        closed = set()
        expanded = 0
        gx, gy, _ = self.goal_l
        self.best, best_d = start, math.hypot(gx, gy)
        reason = "exhausted"
        heap, r, q, grid, edges = self.heap, self.r, self.q, self.grid, self.edges
        lower = grid.lower_blocked_flat
        stop_at = math.inf  # set when the goal looks enclosed
        h_known: dict = {"reeds_shepp": {}}  # and h' by state
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
            if expanded == sch.guide_after and self.goal_parent is None and not self.reverse:
                self.rerank(h_known, closed)
            elif expanded % sch.escalate_every == 0 and self.goal_parent is None:
                if self.guide.field is not None:  # a flood despite the guide: more weight
                    self.boost *= sch.escalate_factor
                    self.reweigh(h_known, closed)
            if (
                self.goal_parent is None
                and stop_at == math.inf
                and self.approach.enclosed(expanded)  # builds the approach tree when due
                and not self.reverse  # it knows forward approaches only
            ):
                stop_at = expanded + sch.enclosed_expansions
            if self.approach.keys and hd <= self.goal_radius and ("final", key) not in self.banned:
                P = P or self.frame.pose(key)
                gc = g + self.cusp_penalty if h >= NH else g  # the approach tree drives forwards
                way = self.approach.connect(P, gc, x, y, _ANGLES[h % NH], self.goal_g)
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
        :attr:`Schedule.guided_weight` (:meth:`reweigh`)."""
        if self.guide.build():
            self.weight = min(self.weight, self.schedule.guided_weight)  # a closer estimate needs less weight
            self.reweigh(h_known, closed)

    def reweigh(self, h_known: dict, closed: set) -> None:
        """Re-rank the open list by ``h'`` computed anew (once per state in ``h_known``; the
        entries of expanded states, in ``closed``, are dropped): after the guide is built
        (:meth:`rerank`), and when :attr:`boost` grows."""
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
        turn = float(np.abs(_ANGLES[keys[:, 2].astype(int) % NH]).max())
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
        unions, directions = [], []
        cost = 0.0
        for key, m in edges:
            unions.append(self.union(key, m))
            directions.append(-1 if self.edge_prims[key[2]][m][1] else 1)
            cost += self.length[key[2]][m]
        kinds = ["start"] + ["lattice"] * len(edges)
        for k, u in enumerate(final or []):
            unions.append(u)
            cost += union_longd(u)
            kinds.append("goal" if k == len(final) - 1 else "approach")
        if final:
            directions += list(self.goal_directions) or [1] * len(final)
        search_cost = self.goal_g if final is not None else cost
        seconds = time.perf_counter() - t0
        start, generated, stats = Pose(*self.start), len(self.g), self.ws.stats
        heuristic = "reeds-shepp" if self.reverse else "dubins"
        return lattice_plan(
            start, unions, kinds, cost, search_cost, expanded, generated, seconds, stats,
            directions=directions, heuristic=heuristic,
        )  # fmt: skip
