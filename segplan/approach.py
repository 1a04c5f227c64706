"""The goal's approach tree of the lattice planner (beyond the paper).

The lattice of :mod:`segplan.lattice` is laid out in the start's frame, so the goal is
in general off the lattice, and a goal in a pocket may admit no direct union from any
lattice state. :class:`GoalApproaches` grows a small tree backwards from the goal: a
lattice in the goal's own frame, whose states reach the goal exactly by chains of
primitives (every edge screened on the clearance grid and, where unsure, checked by the
certified test). Expanded states near the goal then try unions to the most promising of
these *approach states*.
"""

from __future__ import annotations

import heapq
import math

import numpy as np

from .clearance import union_points
from .dubins import dubins_length
from .pose import Pose
from .primitives import heading_angles
from .union import Union

__all__ = ["GoalApproaches"]

_ANGLES = heading_angles()
GOAL = ("goal",)


class GoalApproaches:
    """Mixin of the lattice search (:mod:`segplan.lattice`): the goal's approach tree.

    Uses the search's ``prims``, ``r``, ``L``, ``R``, ``start``, ``goal``, ``grid``,
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
        unsure ones go to :meth:`certified`. Keeps the states within ``budget`` (LONGD to
        the goal), at most ``limit`` of them.
        """
        into = [[] for _ in range(len(self.prims))]  # heading -> [(h0, m)] of primitives ending at it
        for h0, prims in enumerate(self.prims):
            for m, p in enumerate(prims):
                into[p.h1].append((h0, m))
        # goal frame -> start (lattice) frame: a rotation by the heading difference and a shift
        dth = self.goal.theta - self.start.theta
        rot = np.array([[math.cos(dth), -math.sin(dth)], [math.sin(dth), math.cos(dth)]])
        origin = self.grid.to_lattice(np.array(self.goal[:2]))
        grid = self.grid
        pts_in = [np.stack([self.prims[h0][m].points for h0, m in e]) @ rot.T if e else None for e in into]
        dl_in = [np.array([self.prims[h0][m].delta for h0, m in e]) + 1e-9 if e else None for e in into]
        goal_key = (0, 0, 0)
        cost = {goal_key: 0.0}
        nxt = {goal_key: None}  # key -> (next key, h0, m) of the primitive to it
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
            if not into[h]:
                continue
            starts = (
                np.array([(i - self.prims[h0][m].di, j - self.prims[h0][m].dj) for h0, m in into[h]]) * self.r
            )
            base = origin + starts @ rot.T  # the primitives' start points, lattice frame
            free, bad = grid.screen(pts_in[h] + base[:, None, :], dl_in[h])
            for k, (h0, m) in enumerate(into[h]):
                p = self.prims[h0][m]
                prev = (i - p.di, j - p.dj, h0)
                nc = c + p.cost
                if bad[k] or prev in done or nc > budget or not nc < cost.get(prev, math.inf):
                    continue
                if not free[k]:
                    u = self.approach_union(prev, key, h0, m)
                    world = (pts_in[h][k] + base[k]) @ grid.rot.T + (self.start.x, self.start.y)
                    if not self.certified(u, world, dl_in[h][k]):
                        continue
                cost[prev], nxt[prev] = nc, (key, h0, m)
                heapq.heappush(heap, (nc, prev))
        self.approach_keys = out
        self.approach_cost = np.array([cost[k] for k in out])
        self.approach_next = nxt
        poses = np.array([self.goal_pose(k) for k in out]).reshape(-1, 3)
        self.approach_poses = poses
        self.approach_lattice = (
            np.column_stack((grid.to_lattice(poses[:, :2]), poses[:, 2] - self.start.theta))
            if len(out)
            else np.zeros((0, 3))
        )

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
            pts, dl = union_points(u)
            free, bad = self.grid.screen(self.grid.to_lattice(pts)[None], dl)
            if bad[0] or not (free[0] or self.certified(u, pts, dl)):
                continue
            self.goal_g = total
            self.goal_parent = (key, [u] + self.approach_chain(self.approach_keys[k]))
            heapq.heappush(self.heap, (self.goal_g, -1, GOAL))
