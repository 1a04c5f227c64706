"""Greedy shortcuts of a lattice plan (beyond the paper): fewer, longer unions, same corridor.

A plan of the lattice's A* (:mod:`segplan.planning.lattice.astar`) has a node every few
tenths of a metre (its motion primitives are short unions). :func:`shortcut_plan` replaces
runs of them by single unions of the paper's kind (formula [1] cost, optimal frame, steering limit) where one
is free and no longer, before :mod:`segplan.planning.refine` polishes the plan.
"""

from __future__ import annotations

import dataclasses
import math
import time

from ..links import LinkModel
from ..plan import Plan, unions_longd
from .clearance import ClearanceGrid, union_free_near, union_points

__all__ = ["shortcut_plan"]


def shortcut_plan(
    plan: Plan, ex: LinkModel, grid: ClearanceGrid, t0: float, window: int, deadline: float = math.inf
) -> Plan:
    """Greedy shortcuts of a found plan: from each node, the farthest node within ``window``
    (:attr:`segplan.planning.schedule.Schedule.shortcut_window`) that one free union
    reaches for no more LONGD than the chain.

    A lattice plan has a node every few tenths of a metre; this keeps its shape with far
    fewer nodes, so the refinement (whose shortcut step is quadratic in the nodes) stays
    fast on long plans. Every new union keeps the steering limit and is free: screened on
    the clearance grid, then :func:`segplan.planning.lattice.clearance.union_free_near` where unsure, and
    finally the certified test (the plan's own unions, kept, passed it already). Once
    ``deadline`` (a :func:`time.perf_counter` value) has passed, no further shortcut is tried:
    the rest of the plan is kept as it is.
    """
    nodes, unions, kinds = list(plan.nodes), list(plan.unions), list(plan.kinds)
    if len(unions) < 3:
        return plan
    cost = [ex.link_cost(u) for u in unions]
    out_n, out_u, out_k = [nodes[0]], [], [kinds[0]]
    new = []  # the shortcut unions (not yet through the certified test)
    i = 0
    while i < len(unions):
        best = None
        late = time.perf_counter() > deadline
        for j in range(min(len(unions), i + window), i + 1, -1):
            if late:
                break
            u = ex.union(nodes[i], nodes[j])
            if u is None or not ex.ws.curvature_ok(u):
                continue
            # the grid's screen before LONGD: it rejects most candidates, at a fraction of the cost
            pts, dl = union_points(u)
            free, bad = grid.screen(grid.to_lattice(pts)[None], dl)
            if bad[0] or not ex.link_cost(u) <= sum(cost[i:j]):
                continue
            if not (free[0] or union_free_near(ex.ws, u, pts, dl)[0]):
                continue
            best = (j, u)
            break
        j, u = best if best is not None else (i + 1, unions[i])
        if best is not None:
            new.append(u)
        out_n.append(nodes[j])
        out_u.append(u)
        out_k.append(kinds[j])
        i = j
    total = unions_longd(out_u)
    if not total <= plan.cost or not all(ex.ws.union_free(u) for u in new):  # the certified test
        return plan
    return dataclasses.replace(
        plan,
        nodes=tuple(out_n),
        unions=tuple(out_u),
        kinds=tuple(out_k),
        cost=total,
        seconds=time.perf_counter() - t0,
    )
