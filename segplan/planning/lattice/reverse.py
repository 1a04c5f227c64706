"""Reverse links of the lattice: the paper's cubic union traversed backwards (beyond the paper).

Issue 26. A robot that may reverse (``Robot(..., reverse=True)``) drives a union either way.

**The formulation.** Driving backwards from pose ``p`` to pose ``q`` (rear point A, heading
``theta`` pointing from A to the front wheel B, as always) means moving A with negative
speed: the configurations the robot passes through are those of the **forward union from
q to p** (the paper's cubic, section "Union of two nodes", in its optimal reference
system), visited in the opposite order. At every point of it the robot has the same
position and heading as on the forward union, so the rear path of A, the path of the
front wheel ``B = A + L (cos theta, sin theta)``, the swept segment, the curvature (the
steering angle) and LONGD [1], the front wheel's path length, are the same; only the
direction of travel differs. So a reverse link is stored as that forward union
(:attr:`segplan.Plan.directions` ``-1``: ``unions[i]`` runs from ``nodes[i + 1]`` to
``nodes[i]``), and everything the planner checks of a union (collision, steering limit,
LONGD) carries over unchanged.

The other formulation that comes to mind, the forward union from ``p`` to ``q`` with both
headings turned by ``pi``, has the same rear path (a cubic through the same two points
with the same tangent lines, in a frame turned by ``pi``), but it is the path of a robot
whose front wheel is *behind* A: its "front wheel" traces ``A - L (cos theta, sin
theta)``, a different curve (of the same length, as it happens: the points ``A + L t`` and
``A - L t`` both move at ``sqrt(1 + (L kappa)^2)`` times A's speed, so formula [1] cannot
tell them apart), and its swept segment lies behind A: the collision test would check the
wrong area. It is not the robot's motion. ``tests/test_reverse_lattice.py`` checks these
statements numerically: the bicycle model integrated backwards (negative speed, the
steering of the union at each point; RK4) from ``p`` follows the forward union from ``q``
to ``p`` and ends at ``q``, its front wheel on the union's front-wheel path, which is as
long as LONGD [1]; the turned-headings union's rear path is the same, its "front wheel"
path is not (its length is).

**In the lattice** (:class:`segplan.planning.lattice.astar.LatticeAStar`): the reverse
primitives of a heading ``h`` are the forward primitives that *end* at ``h``, traversed
backwards (from ``(i, j, h)`` to ``(i - di, j - dj, h0)``), with the same swept points
shifted to the reverse link's start. A search state carries its last direction in its
heading index: ``h`` (``0 <= h < NH``) after a forward link, ``h + NH`` after a reverse
one; the start is both. An edge costs its LONGD, times ``reverse_factor`` if reverse,
plus ``cusp_penalty`` where its direction differs from the state's last
(:class:`DirectionTables`). The heuristic is then the Reeds–Shepp length
(:func:`segplan.planning.reeds_shepp.reeds_shepp_length`) instead of Dubins', times
``min(1, reverse_factor)``: a lower bound of every such cost (module
:mod:`segplan.planning.reeds_shepp`: LONGD is at least the Reeds–Shepp length, and each
link's cost at least ``min(1, reverse_factor)`` times its LONGD).

:func:`by_runs` applies a plan-to-plan step made for forward plans (the shortcuts, the
refinement) to each same-direction run of a plan, a reverse run as the forward plan from
its last node to its first: cusps stay where the search put them.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np

from ..plan import Plan, link_ends, plain_directions, union_longd
from .frame import NH

__all__ = ["DirectionTables", "by_runs", "runs", "weighted_cost"]


@dataclasses.dataclass(frozen=True)
class DirectionTables:
    """The lattice search's per-heading tables with reverse links (module docstring).

    Indexed by the direction-extended heading ``s`` (``0 <= s < 2 NH``: heading ``s % NH``,
    last link reverse if ``s >= NH``); edge ``m`` of ``s``: forward primitives of ``s % NH``
    first (in :attr:`segplan.planning.lattice.primitives.PrimitiveSet.by_heading` order), then
    the reverse ones.

    Attributes
    ----------
    edges : list of list of (Primitive, bool)
        The primitive of each edge and whether it is traversed backwards.
    step : list of list of (di, dj, s1)
        The edge's end state, relative (``s1`` direction-extended).
    cost : list of list of float
        Search cost: LONGD [1], times ``reverse_factor`` if reverse, plus ``cusp_penalty`` if
        the direction changes.
    length : list of list of float
        LONGD [1] of each edge.
    cells, delta : list
        The swept points' grid cells relative to the start's cell and covering radii (plus
        1e-9), as :meth:`segplan.planning.lattice.primitives.PrimitiveSet.heading_tables`.
    fine : list of (ndarray, ndarray)
        Finer points and their radii, as :meth:`segplan.planning.lattice.primitives.PrimitiveSet.fine_points`.
    """

    edges: list
    step: list
    cost: list
    length: list
    cells: list
    delta: list
    fine: list

    @classmethod
    def build(
        cls, ps, cell: float, reverse_factor: float, cusp_penalty: float, reach: float
    ) -> DirectionTables:
        """The tables of primitive set ``ps`` on a grid of ``cell`` (m); ``cusp_penalty`` in
        metres; ``reach`` the bound of every swept point's coordinates that the clearance
        grid's padding allows (:func:`segplan.planning.lattice.primitives.max_reach`). Made
        once per set and arguments (kept with the set, as its own tables)."""
        key = ("reverse", float(cell), float(reverse_factor), float(cusp_penalty), float(reach))
        out = ps._derived.get(key)
        if out is None:
            out = ps._derived[key] = cls._build(ps, cell, reverse_factor, cusp_penalty, reach)
        return out

    @classmethod
    def _build(cls, ps, cell, reverse_factor, cusp_penalty, reach) -> DirectionTables:
        r = ps.resolution
        points, cells, delta, step, cost = ps.heading_tables(cell)
        fine = ps.fine_points()
        into: list[list[int]] = [[] for _ in range(NH)]  # (h0, m) of the primitives ending at h
        for h0, prims in enumerate(ps.by_heading):
            for m, p in enumerate(prims):
                into[p.h1].append((h0, m))
        out = cls([], [], [], [], [], [], [])
        for s in range(2 * NH):
            h, back = s % NH, s >= NH
            fwd = ps.by_heading[h]
            rev = [(h0, m, ps.by_heading[h0][m]) for h0, m in into[h]]
            shift = [np.array([p.di * r, p.dj * r]) for _, _, p in rev]
            rev_points = [points[h0][m] - d for (h0, m, _), d in zip(rev, shift, strict=True)]
            if rev_points and max(np.abs(q).max() for q in rev_points) > reach:
                raise AssertionError("a reverse primitive's points exceed the clearance grid's padding")
            out.edges.append([(p, False) for p in fwd] + [(p, True) for _, _, p in rev])
            out.step.append(step[h] + [(-p.di, -p.dj, p.h0 + NH) for _, _, p in rev])
            change_f, change_r = (cusp_penalty, 0.0) if back else (0.0, cusp_penalty)
            out.cost.append(
                [c + change_f for c in cost[h]] + [reverse_factor * p.cost + change_r for _, _, p in rev]
            )
            out.length.append(list(cost[h]) + [p.cost for _, _, p in rev])
            rc = [np.floor(q / cell).astype(np.int64) for q in rev_points]
            out.cells.append(
                tuple(np.concatenate([cells[h][k]] + [c[None, :, k] for c in rc]) for k in (0, 1))
            )
            out.delta.append(np.concatenate([delta[h], [delta[h0][m] for h0, m, _ in rev]]))
            fp, fd = fine[h]
            rfp = [fine[h0][0][m] - d for (h0, m, _), d in zip(rev, shift, strict=True)]
            rfd = [fine[h0][1][m] for h0, m, _ in rev]
            rfp = np.concatenate([fp, np.array(rfp)]) if rfp else fp
            out.fine.append((np.ascontiguousarray(rfp), np.concatenate([fd, rfd])))
        return out


def runs(directions) -> list[tuple[int, int, int]]:
    """``(first, stop, direction)`` of each same-direction run of links ``first .. stop - 1``."""
    out: list = []
    for i, d in enumerate(directions):
        if out and out[-1][2] == d:
            out[-1] = (out[-1][0], i + 1, d)
        else:
            out.append((i, i + 1, d))
    return out


def _forward_part(plan: Plan, first: int, stop: int, d: int, longds: list[float]) -> Plan:
    """Links ``first .. stop - 1`` of ``plan`` (direction ``d``; LONGD [1] of each link
    ``longds``) as a forward plan (a reverse run from its last node to its first)."""
    nodes, kinds, unions = plan.nodes[first : stop + 1], plan.kinds[first : stop + 1], plan.unions[first:stop]
    if d < 0:
        nodes, kinds, unions = nodes[::-1], kinds[::-1], unions[::-1]
    cost = math.fsum(longds[first:stop])
    part = {"nodes": nodes, "unions": unions, "kinds": kinds, "directions": ()}
    return dataclasses.replace(plan, **part, cost=cost, search_cost=cost, refinement=None)


def by_runs(plan: Plan, step: Callable[[Plan], Plan]) -> Plan:
    """``step`` (a forward plan to a forward plan with the same ends) applied to each
    same-direction run of ``plan``, a reverse run as the forward plan from its last node to its
    first (module docstring); ``plan`` itself if it has no reverse link. The result's ``cost``
    is the sum of the runs' (LONGD [1]); every other field but the nodes, unions, kinds and
    directions is ``plan``'s."""
    if not plan.directions:
        return step(plan)
    nodes, unions, kinds, directions = [plan.nodes[0]], [], [plan.kinds[0]], []
    cost = 0.0
    longds = [union_longd(u) for u in plan.unions]
    for first, stop, d in runs(plan.directions):
        part = step(_forward_part(plan, first, stop, d, longds))
        pn, pu, pk = part.nodes, part.unions, part.kinds
        if d < 0:
            pn, pu, pk = pn[::-1], pu[::-1], pk[::-1]
        nodes += pn[1:]
        kinds += pk[1:]
        unions += pu
        directions += [d] * len(pu)
        cost += part.cost
    kinds[0], kinds[-1] = plan.kinds[0], plan.kinds[-1]
    directions = plain_directions(directions)
    assert link_ends(nodes[0], unions, directions) == tuple(nodes)
    return dataclasses.replace(
        plan, nodes=tuple(nodes), unions=tuple(unions), kinds=tuple(kinds), directions=directions, cost=cost
    )


def weighted_cost(plan: Plan, reverse_factor: float, cusp_penalty: float) -> float:
    """The search's cost of ``plan``: LONGD [1] of each link, times ``reverse_factor`` if
    reverse, plus ``cusp_penalty`` (m) per cusp; ``plan.cost`` for a forward plan."""
    if not plan.directions:
        return plan.cost
    total = math.fsum(
        union_longd(u) * (reverse_factor if d < 0 else 1.0)
        for u, d in zip(plan.unions, plan.directions, strict=True)
    )
    return total + cusp_penalty * len(plan.cusps)
