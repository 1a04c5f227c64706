"""The goal's approach tree of the lattice planner (beyond the paper).

The lattice of :mod:`segplan.planning.lattice.search` is laid out in the start's frame, so the goal is
in general off the lattice, and a goal in a pocket may admit no direct union from any
lattice state. :class:`GoalApproaches` grows a small tree backwards from the goal: a
lattice in the goal's own frame, whose states reach the goal exactly by chains of
primitives (every edge screened on the clearance grid and, where unsure, checked by the
certified test when its state is settled: as the search's, :mod:`segplan.planning.lattice.edges`).
Expanded states near the goal then try unions to the most promising of these *approach
states* (``g`` + Dubins length + the approach's cost), and a success
puts the goal in the open list with the whole chain.

**A goal that looks enclosed** (:meth:`GoalApproaches.enclosed`): when the tree runs out
of states, or after :data:`ENCLOSURE_AFTER` expansions without a plan a flood fill over
the grid's screen alone finds at most :data:`ENCLOSURE_LIMIT` states that reach the goal
by primitives (4 times as many at half the cell, and more for a robot that turns wider
than ``L``), and no free union joins the start to one of them, the goal can be reached
neither by that lattice's primitives nor by a union from the start. A union from a state
of the start's lattice might still reach it, so this is no proof: the search goes on for
:data:`ENCLOSED_EXPANSIONS` expansions, then stops with ``reason="expansions"`` and says
why. A goal a few decimetres in front of a wall, facing away from it, looks so (and is).
"""

from __future__ import annotations

import heapq
import math

import numpy as np

from ...model.pose import Pose
from ...model.union import Union, cubic_coefficients
from ..dubins import dubins_length
from .clearance import union_points
from .primitives import heading_angles

__all__ = [
    "APPROACH_CANDIDATES",
    "APPROACH_GROWTH",
    "ENCLOSED_EXPANSIONS",
    "ENCLOSURE_AFTER",
    "ENCLOSURE_LIMIT",
    "GoalApproaches",
    "steerable",
]

_ANGLES = heading_angles()
GOAL = ("goal",)

#: Approach states, the most promising first, that :meth:`GoalApproaches.try_approaches`
#: screens by :func:`steerable` before it builds a union to the first ``tries`` that pass.
APPROACH_CANDIDATES = 8
#: Expansions without a plan after which the goal's enclosure test runs (see
#: :meth:`GoalApproaches.enclosed`), and the approach states it grows to (at ``L / 8``; times
#: 4 per halving of the resolution).
ENCLOSURE_AFTER = 256
ENCLOSURE_LIMIT = 300
#: States the approach tree grows to after :data:`ENCLOSURE_AFTER` expansions without a plan
#: (at ``L / 8``; scaled as ``ENCLOSURE_LIMIT``): more targets for the search's unions. Its
#: edges pass the certified test, so it grows at a cost; the enclosure test counts states
#: by the grid's screen alone (:meth:`GoalApproaches.reach_all`). On the 400 random floors
#: of chapter 9 growing it to ``ENCLOSURE_LIMIT`` found no plan that 120 did not.
APPROACH_GROWTH = 120
#: Expansions the search goes on once the goal looks enclosed (a direct union from a state of
#: the start's lattice may still reach it: not a proof), before it stops. On the 400 random
#: floors of chapter 9, my 100 "walls close ahead" floors and 80 floors of varied robots, the
#: plans found after the goal looked enclosed came 34 and 125 expansions later (any-086,
#: natural-066); 512 before made every such failure about 0.45 s long, 192 about 0.3 s.
ENCLOSED_EXPANSIONS = 192

#: Frames sampled per pose pair by :func:`steerable`, abscissae (fractions of the span).
_FRAMES = (np.arange(1, 8) / 8.0)[None, :, None]
_TAU = np.linspace(0.0, 1.0, 17)[None, None, :]


def steerable(p0, p1: np.ndarray, max_curvature: float, slack: float = 1.1) -> np.ndarray:
    """Which poses ``p1`` (``(n, 3)``) a union from ``p0`` may reach within the steering limit.

    A cheap screen before a union is built (vectorised over the poses): a cubic union
    exists (the feasible interval of alpha is not empty, section "Union of two nodes")
    and, over 7 frames across that interval, the smallest peak curvature of the rear
    path sampled at 17 abscissae is below ``slack * max_curvature`` (a coarser sampling
    than :class:`segplan.planning.links.LinkModel`'s steering fallback; ``slack`` keeps most
    unions the samples misjudge). A heuristic, not a proof: it only orders the tries of
    :meth:`GoalApproaches.try_approaches`, never decides that no plan exists.
    """
    p1 = np.asarray(p1, dtype=float).reshape(-1, 3)
    dx, dy = p1[:, 0] - p0[0], p1[:, 1] - p0[1]
    d = np.hypot(dx, dy)
    psi = np.arctan2(dy, dx)
    phi0 = np.remainder(p0[2] - psi + math.pi, 2.0 * math.pi) - math.pi
    phi1 = np.remainder(p1[:, 2] - psi + math.pi, 2.0 * math.pi) - math.pi
    lo = -0.5 * math.pi - np.minimum(np.minimum(phi0, phi1), 0.0)
    hi = 0.5 * math.pi - np.maximum(np.maximum(phi0, phi1), 0.0)
    ok = (hi > lo) & (d > 1e-9)
    if not ok.any():
        return ok
    d, phi0, phi1, lo, hi = (v[ok, None, None] for v in (d, phi0, phi1, lo, hi))
    alphas = lo + (hi - lo) * _FRAMES
    X, c1, c2, c3 = cubic_coefficients(d, phi0, phi1, alphas)
    x = X * _TAU
    fp = c1 + (2.0 * c2 + 3.0 * c3 * x) * x
    fpp = 2.0 * c2 + 6.0 * c3 * x
    peak = np.max(np.abs(fpp) / (1.0 + fp * fp) ** 1.5, axis=2).min(axis=1)
    ok[ok] = peak < slack * max_curvature
    return ok


class GoalApproaches:
    """Mixin of the lattice search (:mod:`segplan.planning.lattice.search`): the goal's approach tree.

    Uses the search's ``prims``, ``fine``, ``r``, ``L``, ``R``, ``start``, ``goal``, ``grid``,
    ``ex``, ``ws``, ``heap``, ``goal_g``, ``goal_parent`` and :meth:`certified`.
    """

    def goal_pose(self, key):
        """World pose of a state of the lattice laid out in the goal's frame."""
        i, j, h = key
        x, y = i * self.r, j * self.r
        c, s = math.cos(self.goal.theta), math.sin(self.goal.theta)
        return (
            self.goal.x + c * x - s * y,
            self.goal.y + s * x + c * y,
            self.goal.theta + float(_ANGLES[h]),
        )

    def build_approaches(self, budget: float, limit: int):
        """States from which a chain of free primitives ends exactly at the goal (backward Dijkstra).

        The goal is the state ``(0, 0, 0)`` of a lattice laid out in its own frame; the
        predecessors of a state are reached by the primitives backwards. The edges into a
        state are screened at once by the primitives' points on the clearance grid; the
        unsure ones go to :meth:`certified` if and when their state is settled (a failing
        one is replaced by the cheapest passing edge to a settled state,
        :meth:`_approach_repair`). Keeps the states within ``budget`` (LONGD to
        the goal), at most ``limit`` of them. A later call with a larger ``limit`` resumes
        the same search (:meth:`grow_approaches`).
        """
        self.approach_budget_used = float(budget)
        into = [[] for _ in range(len(self.prims))]  # heading -> [(h0, m)] of primitives ending at it
        for h0, prims in enumerate(self.prims):
            for m, p in enumerate(prims):
                into[p.h1].append((h0, m))
        # goal frame -> start (lattice) frame: a rotation by the heading difference and a shift
        dth = self.goal.theta - self.start.theta
        rot = np.array([[math.cos(dth), -math.sin(dth)], [math.sin(dth), math.cos(dth)]])
        self._back = dict(
            into=into,
            rot=rot,
            origin=self.grid.to_lattice(np.array(self.goal[:2])),
            pts_in=[np.stack([self.prims[h0][m].points for h0, m in e]) @ rot.T if e else None for e in into],
            dl_in=[np.array([self.prims[h0][m].delta for h0, m in e]) + 1e-9 if e else None for e in into],
            steps_in=[
                np.array([(self.prims[h0][m].di, self.prims[h0][m].dj, h0) for h0, m in e]).reshape(-1, 3)
                for e in into
            ],
            cost={(0, 0, 0): 0.0},
            done=set(),
            heap=[(0.0, (0, 0, 0))],
            out=[],
            unchecked=set(),  # deferred edge checks, as the search's (segplan.planning.lattice.edges)
            failed=set(),
        )
        self.approach_next = {(0, 0, 0): None}  # key -> (next key, h0, m) of the primitive to it
        self.grow_approaches(limit)

    def _into(self, i: int, j: int, h: int):
        """The primitives into the state ``(i, j, h)`` of the goal's lattice (those of
        ``self._back["into"][h]``): their start points in the lattice frame and the grid's
        screen of their points (certainly free, certainly failing)."""
        b = self._back
        base = self._goal_lattice_point((i, j) - b["steps_in"][h][:, :2])
        free, bad = self.grid.screen(b["pts_in"][h] + base[:, None, :], b["dl_in"][h])
        return base, free, bad

    def _goal_lattice_point(self, ij) -> np.ndarray:
        """Lattice-frame position of the goal's-lattice point(s) ``ij`` (``(..., 2)`` integers)."""
        b = self._back
        return b["origin"] + np.asarray(ij, dtype=float) * self.r @ b["rot"].T

    def _approach_edge_free(self, prev, key, h0: int, m: int) -> bool:
        """The finer screen and, if still unsure, the certified test of primitive ``(h0, m)``
        from goal-frame state ``prev`` to ``key`` (primitives' finer points, as the search's)."""
        fp, fd = self.fine[h0]
        base = self._goal_lattice_point(prev[:2])
        world = (fp[m] @ self._back["rot"].T + base) @ self.grid.rot.T + (self.start.x, self.start.y)
        return self.certified(lambda: self.approach_union(prev, key, h0, m), world, fd[m] + 1e-9)

    def _approach_check(self, key) -> bool:
        """Check the edge of state ``key`` towards the goal, deferred until now; if it fails,
        repair the state (:meth:`_approach_repair`) and return False."""
        b = self._back
        b["unchecked"].discard(key)
        nk, h0, m = self.approach_next[key]
        if self._approach_edge_free(key, nk, h0, m):
            return True
        b["failed"].add((key, h0, m))
        self._approach_repair(key)
        return False

    def _approach_repair(self, key) -> None:
        """State ``key`` of the approach tree lost its edge: give it the cheapest edge to a
        settled state that passes (grid screen, then :meth:`_approach_edge_free`), or forget it."""
        b = self._back
        i, j, h0 = key
        cost, nxt, options = b["cost"], self.approach_next, []
        for m, p in enumerate(self.prims[h0]):
            succ = (i + p.di, j + p.dj, p.h1)
            if succ in b["done"] and (key, h0, m) not in b["failed"]:
                options.append((cost[succ] + p.cost, succ, m))
        del cost[key], nxt[key]
        base = self._goal_lattice_point(key[:2])
        for nc, succ, m in sorted(options):
            p = self.prims[h0][m]
            free, bad = self.grid.screen((p.points @ b["rot"].T + base)[None], p.delta + 1e-9)
            if nc <= self.approach_budget_used and not bad[0]:
                if free[0] or self._approach_edge_free(key, succ, h0, m):
                    cost[key], nxt[key] = nc, (succ, h0, m)
                    heapq.heappush(b["heap"], (nc, key))
                    return
            b["failed"].add((key, h0, m))

    def grow_approaches(self, limit: int):
        """Resume :meth:`build_approaches` until ``limit`` states (or none is left).

        Sets ``approach_exhausted``: the backward search ran out of states, so the states
        found are *all* the states of the goal's lattice from which a chain of free
        primitives reaches the goal (with ``budget`` infinite; see :meth:`start_joins`).
        """
        b = self._back
        into, grid = b["into"], self.grid
        cost, done, heap, out, nxt = b["cost"], b["done"], b["heap"], b["out"], self.approach_next
        budget, goal_key, unchecked = self.approach_budget_used, (0, 0, 0), b["unchecked"]
        while heap and len(out) < limit:
            c, key = heapq.heappop(heap)
            if key in done or c != cost.get(key):
                continue  # settled, or an entry left behind by a repair
            if key in unchecked and not self._approach_check(
                key
            ):  # checked now (segplan.planning.lattice.edges)
                continue
            done.add(key)
            if key != goal_key:
                out.append(key)
            i, j, h = key
            if not into[h]:
                continue
            _, free, bad = self._into(i, j, h)
            for k, (h0, m) in enumerate(into[h]):
                p = self.prims[h0][m]
                prev = (i - p.di, j - p.dj, h0)
                nc = c + p.cost
                if bad[k] or prev in done or nc > budget or not nc < cost.get(prev, math.inf):
                    continue
                # an edge the grid cannot clear is checked if and when prev is settled
                (unchecked.discard if free[k] else unchecked.add)(prev)
                cost[prev], nxt[prev] = nc, (key, h0, m)
                heapq.heappush(heap, (nc, prev))
        while heap:  # exhausted if no state is left that a checked edge joins to the tree
            c, key = heap[0]
            if key in done or c != cost.get(key):
                heapq.heappop(heap)
            elif key in unchecked and not self._approach_check(key):
                continue  # repaired: its entry, if any, is a new one
            else:
                break
        self.approach_exhausted = not heap
        self.approach_keys = list(out)
        self.approach_cost = np.array([cost[k] for k in out])
        poses = np.array([self.goal_pose(k) for k in out]).reshape(-1, 3)
        self.approach_poses = poses
        self.approach_lattice = (
            np.column_stack((grid.to_lattice(poses[:, :2]), poses[:, 2] - self.start.theta))
            if len(out)
            else np.zeros((0, 3))
        )

    def start_joins(self, poses: np.ndarray) -> bool:
        """Does a free union within the steering limit join the start to one of ``poses``?

        ``poses``: every state of the goal's lattice that reaches the goal (the approach
        tree exhausted, or :meth:`reach_all`): if the start joins none of them (nor the
        goal, which the planner tries first), no plan made of a union from the start and a
        chain of primitives in the goal's frame exists, the backward counterpart of an
        exhausted search on the start's lattice.
        """
        if not len(poses):
            return False
        P = tuple(self.start)
        for Q in poses.tolist():  # every one (no screen: this decides a NoPathError)
            u = self.ex.union(Pose(*P), Pose(*Q))
            if u is None or not self.ws.curvature_ok(u):
                continue
            pts, dl = union_points(u)
            free, bad = self.grid.screen(self.grid.to_lattice(pts)[None], dl)
            if not bad[0] and (free[0] or self.certified(u, pts, dl)):
                return True
        return False

    def approach_union(self, prev, key, h0, m) -> Union:
        """The union of primitive ``(h0, m)`` from goal-frame state ``prev`` to ``key``."""

        p = self.prims[h0][m]
        P0, P1 = Pose(*self.goal_pose(prev)), Pose(*self.goal_pose(key))
        psi = math.atan2(P1.y - P0.y, P1.x - P0.x)
        return Union.from_intrinsic(P0, P1, p.alpha, self.L, p.d, psi, p.phi0, p.phi1)

    def approach_chain(self, key) -> list:
        """Unions from an approach state to the goal."""
        out = []
        while self.approach_next[key] is not None:
            nk, h0, m = self.approach_next[key]
            out.append(self.approach_union(key, nk, h0, m))
            key = nk
        return out

    def try_approaches(self, key, P, g, x, y, th, tries: int):
        """Unions from state ``key`` to the ``tries`` most promising approach states."""

        if not len(self.approach_keys) or ("final", key) in self.banned:
            return
        a = self.approach_lattice
        est = g + self.approach_cost + dubins_length(x, y, th, a[:, 0], a[:, 1], a[:, 2], self.R)
        order = np.argsort(est, kind="stable")[:APPROACH_CANDIDATES]
        order = order[est[order] < self.goal_g]
        # the most promising states by Dubins length are often those no single union reaches
        # (a turn tighter than a cubic can make): screen them first
        order = order[steerable(P, self.approach_poses[order], self.ws.max_curvature)][:tries]
        for k in order:
            Q = Pose(*self.approach_poses[k].tolist())
            u = self.ex.union(Pose(*P), Q)
            if u is None or not self.ws.curvature_ok(u):
                continue
            # LONGD before the screen only where it may prune (the link model keeps it per union)
            if self.goal_g < math.inf and not g + self.ex.link_cost(u) + self.approach_cost[k] < self.goal_g:
                continue
            pts, dl = union_points(u)
            free, bad = self.grid.screen(self.grid.to_lattice(pts)[None], dl)
            if bad[0] or not (free[0] or self.certified(u, pts, dl)):
                continue
            self.goal_g = g + self.ex.link_cost(u) + float(self.approach_cost[k])
            self.goal_parent = (key, [u] + self.approach_chain(self.approach_keys[k]))
            heapq.heappush(self.heap, (self.goal_g, -1, GOAL))

    def reach_all(self, limit: int) -> np.ndarray | None:
        """Poses of all the states of the goal's lattice from which a chain of primitives
        reaches the goal, no point of it in a blocked cell of the grid; None if more than
        ``limit``.

        A superset of the states the approach tree can ever hold (its edges also pass the
        certified test), found at a fraction of its cost: a flood fill over the grid's
        screen only (the order of the states does not matter for their number).
        """
        into, steps_in = self._back["into"], self._back["steps_in"]
        seen = {(0, 0, 0)}
        todo = [(0, 0, 0)]
        while todo:
            i, j, h = todo.pop()
            if not into[h]:
                continue
            back = steps_in[h]
            _, _, bad = self._into(i, j, h)
            for k in np.flatnonzero(~bad).tolist():
                prev = (i - int(back[k, 0]), j - int(back[k, 1]), int(back[k, 2]))
                if prev not in seen:
                    if len(seen) > limit:
                        return None
                    seen.add(prev)
                    todo.append(prev)
        seen.discard((0, 0, 0))
        return np.array([self.goal_pose(k) for k in sorted(seen)]).reshape(-1, 3)

    def enclosed(self, expanded: int) -> bool:
        """Grow the goal's approach tree when due; True if the goal looks enclosed.

        The tree (:meth:`build_approaches`) is built after ``approach_after`` expansions.
        If it runs out of states, it holds every state of the goal's lattice that reaches
        the goal by primitives. Otherwise, after :data:`ENCLOSURE_AFTER` expansions without
        a plan, :meth:`reach_all` counts such states (a superset) up to
        ``enclosure_limit``. If they are all known and no union joins the start to any of
        them (:meth:`start_joins`), no plan made of a union and such primitives exists. A
        union from a state of the start's lattice may still reach the goal (not a proof):
        the search goes on for :data:`ENCLOSED_EXPANSIONS` expansions.
        ``enclosure_states`` is then the number of those states.
        """
        if self.approach_keys is None and expanded >= self.approach_after:
            self.build_approaches(self.approach_budget, self.approach_limit)
            poses = self.approach_poses if self.approach_exhausted else None
        elif self.approach_keys is not None and expanded == max(ENCLOSURE_AFTER, self.approach_after):
            if not self.approach_exhausted:  # more targets for the search's unions
                self.grow_approaches(int(round(APPROACH_GROWTH * self.enclosure_limit / ENCLOSURE_LIMIT)))
            poses = self.approach_poses if self.approach_exhausted else self.reach_all(self.enclosure_limit)
        else:
            return False
        if poses is None:
            return False
        self.enclosure_states = len(poses)
        return not self.start_joins(poses)
