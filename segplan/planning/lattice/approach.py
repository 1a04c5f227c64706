"""The goal's approach tree of the lattice planner (beyond the paper).

The lattice of the search (:mod:`segplan.planning.lattice.astar`) is laid out in the start's
frame, so the goal is in general off the lattice, and a goal in a pocket may admit no direct
union from any lattice state. :class:`GoalApproach` grows a small tree backwards from the goal: a
lattice in the goal's own frame, whose states reach the goal exactly by chains of
primitives (every edge screened on the clearance grid and, where unsure, checked by the
certified test when its state is settled: as the search's, :mod:`segplan.planning.lattice.edges`).
Expanded states near the goal then try unions to the most promising of these *approach
states* (``g`` + Dubins length + the approach's cost), and a success
puts the goal in the open list with the whole chain.

**A goal that looks enclosed** (:meth:`GoalApproach.enclosed`): when the tree runs out
of states, or after ``enclosure_after`` expansions without a plan a flood fill over the
grid's screen alone finds at most ``enclosure_limit`` states that reach the goal
by primitives (4 times as many at half the cell, and more for a robot that turns wider
than ``L``), and no free union joins the start to one of them, the goal can be reached
neither by that lattice's primitives nor by a union from the start. A union from a state
of the start's lattice might still reach it, so this is no proof: the search goes on for
``enclosed_expansions`` expansions, then stops with ``reason="expansions"`` and says
why (the counts: :class:`segplan.planning.schedule.Schedule`). A goal a few
decimetres in front of a wall, facing away from it, looks so (and is).
"""

from __future__ import annotations

import heapq
import math

import numpy as np

from ...model.pose import Pose, wrap_floor
from ...model.union import Union, cubic_coefficients, curvature_samples, peak_curvature
from ..dubins import dubins_length, dubins_length_scalar
from ..schedule import Schedule
from .clearance import union_free_near, union_free_screened
from .edges import LazyEdges
from .frame import LatticeFrame

__all__ = ["GoalApproach", "steerable"]

#: Frames sampled per pose pair by :func:`steerable`, abscissae (fractions of the span).
_FRAMES = (np.arange(1, 8) / 8.0)[None, :, None]
_TAU = np.linspace(0.0, 1.0, 17)[None, None, :]
#: States of a front whose primitives :meth:`GoalApproach.reach_all` screens at once.
_FLOOD_CHUNK = 256
#: Approach states up to which :meth:`GoalApproach.connect` takes their Dubins lengths one by one
#: (:func:`segplan.planning.dubins.dubins_length_scalar`) rather than in one vectorised call.
#: Measured on 2026-12-06 (this project's 2-core machine, random poses): the vectorised call
#: costs 185-205 us for 1 to 32 poses (numpy's per-call overhead), the scalar one 4.7 us a
#: pose (177 us for 32, 358 us for 64); enclosed goals have 0-3 approach states and call
#: ``connect`` from every state expanded near them.
_SCALAR_DUBINS = 32


def steerable(p0, p1: np.ndarray, max_curvature: float, slack: float) -> np.ndarray:
    """Which poses ``p1`` (``(n, 3)``) a union from ``p0`` may reach within the steering limit.

    A cheap screen before a union is built (vectorised over the poses): a cubic union
    exists (the feasible interval of alpha is not empty, section "Union of two nodes")
    and, over 7 frames across that interval, the smallest peak curvature of the rear
    path sampled at 17 abscissae is below ``slack * max_curvature`` (a coarser sampling
    than :class:`segplan.planning.links.LinkModel`'s steering fallback; ``slack`` keeps most
    unions the samples misjudge). A heuristic, not a proof: it only orders the tries of
    :meth:`GoalApproach.connect`, never decides that no plan exists
    (:attr:`segplan.planning.schedule.Schedule.steer_slack`).
    """
    p1 = np.asarray(p1, dtype=float).reshape(-1, 3)
    dx, dy = p1[:, 0] - p0[0], p1[:, 1] - p0[1]
    d = np.hypot(dx, dy)
    psi = np.arctan2(dy, dx)
    phi0 = wrap_floor(p0[2] - psi)
    phi1 = wrap_floor(p1[:, 2] - psi)
    lo = -0.5 * math.pi - np.minimum(np.minimum(phi0, phi1), 0.0)
    hi = 0.5 * math.pi - np.maximum(np.maximum(phi0, phi1), 0.0)
    ok = (hi > lo) & (d > 1e-9)
    if not ok.any():
        return ok
    d, phi0, phi1, lo, hi = (v[ok, None, None] for v in (d, phi0, phi1, lo, hi))
    alphas = lo + (hi - lo) * _FRAMES
    X, c1, c2, c3 = cubic_coefficients(d, phi0, phi1, alphas)
    _, fp, fpp = curvature_samples(X, c1, c2, c3, _TAU)
    peak = peak_curvature(fp, fpp, axis=2).min(axis=1)
    ok[ok] = peak < slack * max_curvature
    return ok


class GoalApproach:
    """The goal's approach tree and its enclosure test (module docstring): a part of the lattice search.

    Parameters
    ----------
    robot : segplan.Robot
    start, goal : segplan.Pose
        The search's start (the origin of its lattice and of the clearance grid's frame) and goal.
    resolution : float
        The cell of the search's lattice; the goal's lattice has the same cell and primitives.
    prims : tuple of tuple of Primitive
        The primitives by start heading (:attr:`segplan.planning.lattice.primitives.PrimitiveSet.by_heading`).
    fine : tuple
        Their finer points (:meth:`segplan.planning.lattice.primitives.PrimitiveSet.fine_points`).
    grid : segplan.planning.lattice.clearance.ClearanceGrid
        The search's clearance grid (the start's lattice frame).
    ws : segplan.planning.validity.Workspace
        The certified tests.
    links : segplan.planning.links.LinkModel
        Makes the unions from the search's states (optimal reference system, steering fallback).
    schedule : segplan.planning.schedule.Schedule
        When the tree is built and grown, how much it does.
    budget : float
        The tree keeps the states within this LONGD of the goal (default: all).

    Attributes
    ----------
    keys : list or None
        The approach states (the goal's lattice), nearest the goal first; None until built.
    costs, poses, in_lattice : ndarray
        Their LONGD to the goal, world poses, and poses in the start's lattice frame.
    exhausted : bool
        The tree ran out of states: it holds every state from which a chain of free primitives
        reaches the goal.
    enclosure_limit : int
        States up to which the enclosure test counts (:attr:`Schedule.enclosure_limit` scaled
        to the resolution and to a robot turning wider than ``L``).
    enclosure_states : int
        The states the enclosure test counted when the goal looked enclosed (0 before).
    """

    def __init__(
        self,
        robot,
        start,
        goal,
        resolution,
        prims,
        fine,
        grid,
        ws,
        links,
        schedule: Schedule,
        budget: float = math.inf,
    ):
        self.start, self.goal = start, goal
        self.R = robot.min_turning_radius
        self.frame = LatticeFrame(goal, resolution, robot.L)
        self.prims, self.fine, self.grid, self.ws, self.links = prims, fine, grid, ws, links
        self.schedule, self.budget = schedule, float(budget)
        # the goal's enclosure test: states that reach the goal counted up to this many (more
        # on a finer lattice, and for a robot whose turns, so pockets, are wider than L)
        wider = max(1.0, self.R / robot.L) ** 2
        self.enclosure_limit = int(
            round(schedule.enclosure_limit * (0.125 * robot.L / resolution) ** 2 * wider)
        )
        self.reset()

    def reset(self) -> None:
        """No tree yet (a new search)."""
        self.keys = None
        self.enclosure_states = 0

    def build(self, limit: int) -> None:
        """States from which a chain of free primitives ends exactly at the goal (backward Dijkstra).

        The goal is the state ``(0, 0, 0)`` of a lattice laid out in its own frame; the
        predecessors of a state are reached by the primitives backwards. The edges into a
        state are screened at once by the primitives' points on the clearance grid; the
        unsure ones are checked if and when their state is settled (:class:`LazyEdges`: a
        failing one is replaced by the cheapest passing edge to a settled state). Keeps the
        states within ``budget`` (LONGD to the goal), at most ``limit`` of them. A later
        call of :meth:`grow` with a larger ``limit`` resumes the same search.
        """
        prims = self.prims
        self.into = into = [[] for _ in range(len(prims))]  # heading -> [(h0, m)] of primitives ending at it
        for h0, ps in enumerate(prims):
            for m, p in enumerate(ps):
                into[p.h1].append((h0, m))
        # goal frame -> start (lattice) frame: a rotation by the heading difference and a shift
        dth = self.goal.theta - self.start.theta
        self.rot = rot = np.array([[math.cos(dth), -math.sin(dth)], [math.sin(dth), math.cos(dth)]])
        self.origin = self.grid.to_lattice(np.array(self.goal[:2]))
        self.pts_in = [np.stack([prims[h0][m].points for h0, m in e]) @ rot.T if e else None for e in into]
        self.dl_in = [np.array([prims[h0][m].delta for h0, m in e]) + 1e-9 if e else None for e in into]
        self.steps_in = [
            np.array([(prims[h0][m].di, prims[h0][m].dj, h0) for h0, m in e]).reshape(-1, 3) for e in into
        ]
        self.to_goal = {(0, 0, 0): 0.0}  # key -> LONGD of its chain to the goal
        self.settled: set = set()
        self.open = [(0.0, (0, 0, 0))]
        self.out: list = []
        self.edges = LazyEdges(self.screen_edge, self.check_edge)
        self.next = {(0, 0, 0): None}  # key -> (next key, h0, m) of the primitive to it
        self.grow(limit)

    def _into(self, ij, h: int):
        """The primitives into the states ``ij`` (``(2,)`` or ``(n, 2)`` integers) of heading
        ``h`` of the goal's lattice (those of ``into[h]``): the positions they start from
        (``(..., primitives, 2)``, the goal's lattice) and the grid's screen of their points
        (certainly free, certainly failing; ``(..., primitives)``)."""
        starts = np.asarray(ij)[..., None, :] - self.steps_in[h][:, :2]
        base = self._point(starts)
        free, bad = self.grid.screen(self.pts_in[h] + base[..., None, :], self.dl_in[h])
        return starts, free, bad

    def _point(self, ij) -> np.ndarray:
        """Start-lattice-frame position of the goal's-lattice point(s) ``ij`` (``(..., 2)`` integers)."""
        return self.origin + np.asarray(ij, dtype=float) * self.frame.r @ self.rot.T

    def screen_edge(self, edge) -> tuple[bool, bool]:
        """The grid's screen of primitive ``m`` from goal-frame state ``key`` (``edge = (key, m)``):
        certainly free, certainly failing."""
        key, m = edge
        p = self.prims[key[2]][m]
        free, bad = self.grid.screen((p.points @ self.rot.T + self._point(key[:2]))[None], p.delta + 1e-9)
        return free[0], bad[0]

    def check_edge(self, edge) -> bool:
        """The finer screen and, if still unsure, the certified test of primitive ``m`` from
        goal-frame state ``key`` (``edge = (key, m)``; the primitives' finer points, as the search's)."""
        key, m = edge
        fp, fd = self.fine[key[2]]
        base = self._point(key[:2])
        world = (fp[m] @ self.rot.T + base) @ self.grid.rot.T + (self.start.x, self.start.y)
        return union_free_near(
            self.ws, lambda: self.frame.union(key, self.prims[key[2]][m]), world, fd[m] + 1e-9
        )[0]

    def _check(self, key) -> bool:
        """Check the edge of state ``key`` towards the goal, deferred until now; if it fails,
        repair the state (:meth:`_repair`) and return False."""
        _, _, m = self.next[key]
        if self.edges.check(key, (key, m)):
            return True
        self._repair(key)
        return False

    def _repair(self, key) -> None:
        """State ``key`` of the tree lost its edge: give it the cheapest passing edge to a
        settled state (:meth:`LazyEdges.repair`), or forget it."""
        i, j, h0 = key
        options = []
        for m, p in enumerate(self.prims[h0]):
            succ = (i + p.di, j + p.dj, p.h1)
            if succ in self.settled:
                options.append((self.to_goal[succ] + p.cost, succ, (key, m)))
        del self.to_goal[key], self.next[key]
        found = self.edges.repair(options, self.budget)
        if found is not None:
            nc, succ, (_, m) = found
            self.to_goal[key], self.next[key] = nc, (succ, h0, m)
            heapq.heappush(self.open, (nc, key))

    def grow(self, limit: int) -> None:
        """Resume :meth:`build` until ``limit`` states (or none is left).

        Sets :attr:`exhausted`: the backward search ran out of states, so the states found
        are *all* the states of the goal's lattice from which a chain of free primitives
        reaches the goal (with ``budget`` infinite; see :meth:`start_joins`).
        """
        into, grid = self.into, self.grid
        cost, done, heap, out, nxt = self.to_goal, self.settled, self.open, self.out, self.next
        budget, goal_key, edges = self.budget, (0, 0, 0), self.edges
        while heap and len(out) < limit:
            c, key = heapq.heappop(heap)
            if key in done or c != cost.get(key):
                continue  # settled, or an entry left behind by a repair
            if edges.pending(key) and not self._check(key):  # checked now
                continue
            done.add(key)
            if key != goal_key:
                out.append(key)
            i, j, h = key
            if not into[h]:
                continue
            _, free, bad = self._into((i, j), h)
            for k, (h0, m) in enumerate(into[h]):
                p = self.prims[h0][m]
                prev = (i - p.di, j - p.dj, h0)
                nc = c + p.cost
                if bad[k] or prev in done or nc > budget or not nc < cost.get(prev, math.inf):
                    continue
                # an edge the grid cannot clear is checked if and when prev is settled
                edges.defer(prev, free[k])
                cost[prev], nxt[prev] = nc, (key, h0, m)
                heapq.heappush(heap, (nc, prev))
        while heap:  # exhausted if no state is left that a checked edge joins to the tree
            c, key = heap[0]
            if key in done or c != cost.get(key):
                heapq.heappop(heap)
            elif edges.pending(key) and not self._check(key):
                continue  # repaired: its entry, if any, is a new one
            else:
                break
        self.exhausted = not heap
        self.keys = list(out)
        self.costs = np.array([cost[k] for k in out])
        poses = np.array([self.frame.pose(k) for k in out]).reshape(-1, 3)
        self.poses = poses
        self.in_lattice = (
            np.column_stack((grid.to_lattice(poses[:, :2]), poses[:, 2] - self.start.theta))
            if len(out)
            else np.zeros((0, 3))
        )
        self.in_lattice_rows = self.in_lattice.tolist() if len(out) <= _SCALAR_DUBINS else None

    def start_joins(self, poses: np.ndarray) -> bool:
        """Does a free union within the steering limit join the start to one of ``poses``?

        ``poses``: every state of the goal's lattice that reaches the goal (the tree
        exhausted, or :meth:`reach_all`): if the start joins none of them (nor the goal,
        which the planner tries first), no plan made of a union from the start and a chain
        of primitives in the goal's frame exists, the backward counterpart of an exhausted
        search on the start's lattice.
        """
        if not len(poses):
            return False
        P = tuple(self.start)
        for Q in poses.tolist():  # every one (no screen: this decides a NoPathError)
            u = self.links.union(Pose(*P), Pose(*Q))
            if u is None or not self.ws.curvature_ok(u):
                continue
            if union_free_screened(self.grid, self.ws, u):
                return True
        return False

    def chain(self, key) -> list[Union]:
        """Unions from an approach state to the goal."""
        out = []
        while self.next[key] is not None:
            nk, h0, m = self.next[key]
            out.append(self.frame.union(key, self.prims[h0][m]))
            key = nk
        return out

    def connect(self, P, g: float, x: float, y: float, th: float, goal_g: float):
        """The cheapest union from a state of the search (world pose ``P``, cost ``g``; ``x, y,
        th`` in the start's lattice frame) to one of the most promising approach states, if it
        beats ``goal_g``: ``(cost to the goal, unions to the goal)``, or None.

        The approach states are ranked by ``g`` + their Dubins length + their cost to the goal;
        the first :attr:`Schedule.approach_candidates` are screened by :func:`steerable`, and
        unions are built to the first :attr:`Schedule.approach_tries` that pass.
        """
        if not len(self.keys):
            return None
        s = self.schedule
        a = self.in_lattice
        if len(a) <= _SCALAR_DUBINS:
            rows, R = self.in_lattice_rows, self.R
            dub = np.array([dubins_length_scalar(x, y, th, ax, ay, at, R) for ax, ay, at in rows])
        else:
            dub = dubins_length(x, y, th, a[:, 0], a[:, 1], a[:, 2], self.R)
        est = g + self.costs + dub
        order = np.argsort(est, kind="stable")[: s.approach_candidates]
        order = order[est[order] < goal_g]
        # the most promising states by Dubins length are often those no single union reaches
        # (a turn tighter than a cubic can make): screen them first
        order = order[steerable(P, self.poses[order], self.ws.max_curvature, s.steer_slack)][
            : s.approach_tries
        ]
        found = None
        for k in order:
            Q = Pose(*self.poses[k].tolist())
            u = self.links.union(Pose(*P), Q)
            if u is None or not self.ws.curvature_ok(u):
                continue
            # LONGD before the screen only where it may prune (the link model keeps it per union)
            if goal_g < math.inf and not g + self.links.link_cost(u) + self.costs[k] < goal_g:
                continue
            if not union_free_screened(self.grid, self.ws, u):
                continue
            goal_g = g + self.links.link_cost(u) + float(self.costs[k])
            found = (goal_g, [u] + self.chain(self.keys[k]))
        return found

    def reach_all(self, limit: int) -> np.ndarray | None:
        """Poses of all the states of the goal's lattice from which a chain of primitives
        reaches the goal, no point of it in a blocked cell of the grid; None if more than
        ``limit``.

        A superset of the states the approach tree can ever hold (its edges also pass the
        certified test), found at a fraction of its cost: a flood fill over the grid's
        screen only, breadth first, the primitives into every state of a front that share a
        heading screened at once (the order of the states does not matter for their number,
        nor for the answer: the set is returned sorted).
        """
        seen = {(0, 0, 0)}
        front = [(0, 0, 0)]
        while front:
            by_heading: dict[int, list] = {}
            for i, j, h in front:
                if self.into[h]:
                    by_heading.setdefault(h, []).append((i, j))
            front = []
            for h, ij in by_heading.items():
                back = self.steps_in[h]
                for c in range(0, len(ij), _FLOOD_CHUNK):  # bounded memory on a large front
                    starts, _, bad = self._into(ij[c : c + _FLOOD_CHUNK], h)
                    s, k = np.nonzero(~bad)  # (state of the front, primitive into it) pairs
                    pi, pj = starts[s, k, 0].tolist(), starts[s, k, 1].tolist()
                    for prev in zip(pi, pj, back[k, 2].tolist(), strict=True):
                        if prev not in seen:
                            seen.add(prev)
                            front.append(prev)
                    if len(seen) > limit + 1:  # more than the goal and ``limit`` others
                        return None
        seen.discard((0, 0, 0))
        return np.array([self.frame.pose(k) for k in sorted(seen)]).reshape(-1, 3)

    def enclosed(self, expanded: int) -> bool:
        """Build or grow the tree when due (the search has made ``expanded`` expansions without
        a plan); True if the goal looks enclosed.

        The tree (:meth:`build`) is built after :attr:`Schedule.approach_after` expansions.
        If it runs out of states, it holds every state of the goal's lattice that reaches
        the goal by primitives. Otherwise, after :attr:`Schedule.enclosure_after` expansions,
        the tree grows (:attr:`Schedule.approach_growth`: more targets for the search's
        unions) and :meth:`reach_all` counts such states (a superset) up to
        :attr:`enclosure_limit`. If they are all known and no union joins the start to any of
        them (:meth:`start_joins`), no plan made of a union and such primitives exists. A
        union from a state of the start's lattice may still reach the goal (not a proof):
        the search goes on for :attr:`Schedule.enclosed_expansions` expansions.
        :attr:`enclosure_states` is then the number of those states.
        """
        s = self.schedule
        if self.keys is None and expanded >= s.approach_after:
            self.build(s.approach_limit)
            poses = self.poses if self.exhausted else None
        elif self.keys is not None and expanded == max(s.enclosure_after, s.approach_after):
            if not self.exhausted:  # more targets for the search's unions
                self.grow(int(round(s.approach_growth * self.enclosure_limit / s.enclosure_limit)))
            poses = self.poses if self.exhausted else self.reach_all(self.enclosure_limit)
        else:
            return False
        if poses is None:
            return False
        self.enclosure_states = len(poses)
        return not self.start_joins(poses)
