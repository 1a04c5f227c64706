"""The A*-type search on the graph built on-line (section "Results. Graph-search").

"The evaluation function is defined as the estimation of the cost of an optimal path
conditioned to passing by a given node ... f = g + h'". This module is the search
alone: it knows nothing of obstacles, unions or LONGD. It asks a
:class:`segplan.planning.paper.problem.Problem` for ``g`` of a link
(:meth:`~segplan.planning.paper.problem.Problem.link_cost`)
and ``h'`` of a node (:meth:`~segplan.planning.paper.problem.Problem.cost_to_go`), and a ``successors``
function (in the planner, :meth:`segplan.planning.paper.expansion.Expander.successors`) for the graph.

Search details (ours): nodes that are equivalent for the search (the successors' ``key``:
the same obstacle vertex passed on the same side with a similar heading, or turn states
in the same cell of a ``L/4`` and 22.5 deg grid) are expanded once (the closed set).
Chains of consecutive turn states are limited (``max_turn_chain``), and the search stops
after ``max_expansions`` expansions or ``time_limit`` seconds with
:class:`segplan.NoPathError`, which carries what was explored (the explored node
closest to the goal); so does an exhausted graph (the node generation found no new
successor: the graph is sparse, so this says nothing of the floor, and the message says no more).
"""

from __future__ import annotations

import heapq
import math
import time
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from ...model.pose import Pose, show_pose
from ..plan import NoPathError, Plan

if TYPE_CHECKING:  # the search needs only the problem's link_cost, cost_to_go and prepare
    from .problem import Problem

__all__ = ["Finish", "Successors", "astar"]

#: ``successors(pose, turns)``: the successors of a node (objects with ``pose``, ``union``,
#: ``kind`` and ``key``; ``turns``: whether turn states may be generated).
Successors = Callable[[Pose, bool], Sequence]
#: ``finish(nodes, unions, kinds, search_cost, expanded, generated)``: the plan of a path.
Finish = Callable[[tuple, tuple, tuple, float, int, int], Plan]


def astar(
    problem: Problem,
    successors: Successors,
    finish: Finish,
    *,
    max_expansions: int,
    time_limit: float,
    t0: float,
    max_turn_chain: int = 4,
) -> Plan:
    """A* from ``problem.start`` to ``problem.goal`` over ``successors``.

    Parameters
    ----------
    problem : Problem
        ``g`` (:meth:`~segplan.planning.paper.problem.Problem.link_cost`), ``h'``
        (:meth:`~segplan.planning.paper.problem.Problem.cost_to_go`).
    successors : callable
        ``successors(pose, turns)``, see :data:`Successors`.
    finish : callable
        Builds the :class:`segplan.Plan` of a path, see :data:`Finish`.
    max_expansions, time_limit : int, float
        Limits (``NoPathError`` with ``reason="expansions"`` or ``"time"``).
    t0 : float
        ``time.perf_counter()`` at the start of planning (the time limit counts from it).
    max_turn_chain : int
        Longest chain of consecutive successors of kind ``"turn"``.

    Raises
    ------
    NoPathError
        With the plan to the explored node closest to the goal as ``best``.
    """
    search = _Search(problem, successors, finish, max_turn_chain)
    return search.run(int(max_expansions), float(time_limit), t0)


class _Search:
    """A* bookkeeping: parallel lists indexed by node id."""

    def __init__(self, problem: Problem, successors: Successors, finish: Finish, max_turn_chain: int = 4):
        self.problem = problem
        self.successors = successors
        self.finish = finish
        self.start = problem.start
        self.goal = problem.goal
        self.poses: list[Pose] = []
        self.parent: list[int] = []
        self.union: list = []  # the link (a union, for the planner) that reached each node
        self.g: list[float] = []
        self.depth: list[int] = []
        self.kind: list[str] = []
        self.dist: list[float] = []
        self.chain: list[int] = []  # consecutive turn states ending at the node
        self.max_turn_chain = max_turn_chain

    def add(self, pose, parent, union, g, depth, kind) -> int:
        self.poses.append(pose)
        self.parent.append(parent)
        self.union.append(union)
        self.g.append(g)
        self.depth.append(depth)
        self.kind.append(kind)
        self.dist.append(math.hypot(self.goal.x - pose.x, self.goal.y - pose.y))
        self.chain.append(self.chain[parent] + 1 if kind == "turn" else 0)
        return len(self.poses) - 1

    def path(self, i: int):
        ids = []
        while i >= 0:
            ids.append(i)
            i = self.parent[i]
        ids.reverse()
        return ids

    def make_plan(self, i: int, expanded: int):
        ids = self.path(i)
        return self.finish(
            tuple(self.poses[j] for j in ids),
            tuple(self.union[j] for j in ids[1:]),
            tuple(self.kind[j] for j in ids),
            self.g[i],
            expanded,
            len(self.poses),
        )

    def run(self, max_expansions: int, time_limit: float, t0: float) -> Plan:
        start, goal = Pose(*self.start), Pose(*self.goal)
        s = self.add(start, -1, None, 0.0, 0, "start")
        if start == goal:
            return self.make_plan(s, 0)
        heap = [(self.problem.cost_to_go(start, 0), 0, s)]
        closed: set = set()
        best_g: dict = {("start",): 0.0}
        keys = {s: ("start",)}
        expanded = 0
        counter = 1
        reason = "exhausted"
        while heap:
            if expanded >= max_expansions:
                reason = "expansions"
                break
            if time.perf_counter() - t0 > time_limit:
                reason = "time"
                break
            _, _, i = heapq.heappop(heap)
            if self.kind[i] == "goal":
                return self.make_plan(i, expanded)
            key = keys[i]
            if key in closed:
                continue
            closed.add(key)
            expanded += 1
            succs = self.successors(self.poses[i], self.chain[i] < self.max_turn_chain)
            # the direct unions of the new nodes to the goal (h' and their expansion), batched
            self.problem.prepare([s.pose for s in succs if s.kind != "goal" and s.key not in closed])
            for succ in succs:
                if succ.key in closed:
                    continue
                g = self.g[i] + self.problem.link_cost(succ.union)
                if g >= best_g.get(succ.key, math.inf):
                    continue
                best_g[succ.key] = g
                depth = self.depth[i] + 1
                j = self.add(succ.pose, i, succ.union, g, depth, succ.kind)
                keys[j] = succ.key
                f = g + (0.0 if succ.kind == "goal" else self.problem.cost_to_go(succ.pose, depth))
                heapq.heappush(heap, (f, counter, j))
                counter += 1
        seconds = time.perf_counter() - t0
        best = min(range(len(self.poses)), key=lambda k: (self.dist[k], self.g[k]))
        partial = self.make_plan(best, expanded)
        what = {
            "exhausted": _exhausted(expanded, len(self.poses)),
            "expansions": f"the expansion limit max_expansions={max_expansions} was reached",
            "time": f"the time limit time_limit={time_limit:g} s was reached",
        }[reason]
        raise NoPathError(
            f"no path from {show_pose(start)} to {show_pose(goal)}: {what}; expanded {expanded} nodes, "
            f"generated {len(self.poses)}; the closest node explored is {self.dist[best]:.3g} from the goal",
            reason,
            expanded,
            len(self.poses),
            seconds,
            partial,
        )


def _exhausted(expanded: int, generated: int) -> str:
    """What an exhausted search says: the paper's node generation (direct union, intermediate
    nodes at an obstacle's vertices, approach and turn states) found no new collision-free
    successor. It knows nothing of the floor beyond its graph, so it says no more: not that the
    goal is enclosed, nor that no path exists."""
    if generated == 1:
        found = "found no collision-free successor of the start"
    else:
        found = f"found no new collision-free successor after {expanded} expansions"
    return (
        f"the paper's node generation (the direct union, intermediate nodes at the vertices of the "
        f"obstacle in its way, approach and turn states) {found}; its graph is sparse, so this is "
        "not a proof that no path exists (the default planner's lattice searches a denser one)"
    )
