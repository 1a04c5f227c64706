"""What a search returns: a :class:`Plan`, or a :class:`NoPathError`; and a plan's :class:`Refinement`.

Types only (section "Results. Graph-search" of Campoy et al. (1989) describes the plan:
consecutive nodes joined by cubic unions, its cost the sum of their LONGD [1]). They sit
below the search (:mod:`segplan.planning.paper.search`) and the refinement
(:mod:`segplan.planning.refine`), so
neither imports the other.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable
from dataclasses import dataclass, field

from ..model.cost import chain_longd

__all__ = [
    "PLAN_RTOL",
    "NoPathError",
    "Plan",
    "Refinement",
    "check_limits",
    "check_option",
    "direct_plan",
    "lattice_plan",
    "union_longd",
    "unions_longd",
]

#: Relative tolerance of the Romberg integration [1] behind a returned plan's ``cost``.
PLAN_RTOL = 1e-8


def union_longd(u) -> float:
    """LONGD of one union by formula [1] (Romberg to :data:`PLAN_RTOL`), from the union's
    own intrinsic parameters (``u.d``, ``u.phi0``, ``u.phi1``, ``u.alpha``, ``u.L``)."""
    return chain_longd((u,), PLAN_RTOL)


def unions_longd(unions: Iterable) -> float:
    """A chain's LONGD: the sum of :func:`union_longd` over ``unions`` (0 for none)."""
    return chain_longd(unions, PLAN_RTOL)


def check_option(
    value, name: str, lo: float, *, integer: bool = False, allow_none: bool = False, lo_ok: bool = False
):
    """A search option: a finite number above ``lo`` (at least ``lo`` with ``lo_ok``),
    an integer if ``integer``, or None if ``allow_none``. Returns it as int or float.

    The one validator of the planners' numeric options (:func:`segplan.plan_scenario`,
    :func:`segplan.planning.lattice.search.lattice_search`). Raises ValueError naming ``name``.
    """
    if value is None and allow_none:
        return None
    ok = not isinstance(value, bool) and isinstance(value, int | float) and math.isfinite(value)
    ok = ok and (value >= lo if lo_ok else value > lo)
    if ok and integer:
        ok = int(value) == value
    if not ok:
        kind = "an integer" if integer else "a finite number"
        raise ValueError(f"{name} must be {kind} {'>=' if lo_ok else '>'} {lo}, got {value!r}")
    return int(value) if integer else float(value)


def check_limits(max_expansions, time_limit) -> tuple[int | None, float]:
    """The search limits of every planner: ``max_expansions`` an integer >= 1 (or None: the
    planner's default), ``time_limit`` a positive number of seconds. Raises ValueError
    naming the argument (:func:`check_option`)."""
    return (
        check_option(max_expansions, "max_expansions", 1, integer=True, allow_none=True, lo_ok=True),
        check_option(time_limit, "time_limit", 0.0),
    )


@dataclass(frozen=True)
class Refinement:
    """What :func:`refine` did.

    Attributes
    ----------
    cost_before, cost_after : float
        Exact LONGD [1] of the plan before and after.
    nodes_before, nodes_after : int
        Number of nodes (start and goal included).
    shortcuts, splits, moves : int
        Nodes removed by shortcuts, nodes added by splits, accepted local moves.
    updates : int
        Node updates tried by the local search.
    checked : int
        Unions checked exactly (steering limit, walls, obstacles).
    seconds : float
        Wall time of the refinement alone.
    stopped : bool
        The deadline passed during the refinement (:func:`segplan.plan_scenario`'s
        ``time_limit``): it stopped early and returned the chain so far.
    """

    cost_before: float
    cost_after: float
    nodes_before: int
    nodes_after: int
    shortcuts: int
    splits: int
    moves: int
    updates: int
    checked: int
    seconds: float
    stopped: bool = False


class NoPathError(RuntimeError):
    """No plan was found: the reachable graph was exhausted or a search limit was hit.

    Attributes
    ----------
    reason : str
        ``"exhausted"`` (every reachable node expanded: e.g. the goal is enclosed),
        ``"expansions"`` or ``"time"`` (a limit was reached).
    expanded, generated : int
        Nodes expanded and generated.
    seconds : float
        Time spent.
    best : Plan
        The explored path that came closest to the goal (a partial plan that does not
        end at the goal; ``best.nodes[-1]`` is where it stops).
    """

    def __init__(self, message: str, reason: str, expanded: int, generated: int, seconds: float, best):
        super().__init__(message)
        self.reason = reason
        self.expanded = expanded
        self.generated = generated
        self.seconds = seconds
        self.best = best


@dataclass(frozen=True)
class Plan:
    """A plan: consecutive nodes joined by collision-free cubic unions.

    Attributes
    ----------
    nodes : tuple of Pose
        Start, intermediate nodes, goal (``len(unions) + 1`` poses).
    unions : tuple of Union
        ``unions[i]`` joins ``nodes[i]`` to ``nodes[i + 1]``.
    cost : float
        Sum of the exact LONGD [1] of the unions (front-wheel path length).
    search_cost : float
        The ``g`` of the search at the last node (LONGD [2]/[1], or distances for the
        baseline ``cost="distance"``).
    expanded, generated : int
        Nodes expanded and generated by the search.
    seconds : float
        Wall-clock planning time (through :func:`segplan.plan_scenario`: the whole call's,
        measured once from its start, off-line work excluded).
    heuristic, cost_kind, version : str
        The search's settings.
    collision_checks : int
        Distinct union-obstacle pairs decided (broad phase or exact test; a pair asked
        about again is answered from the workspace's cache and not counted again).
    exact_checks : int
        Calls of the exact collision test.
    iterations : tuple of int
        Iterates used by every successful vertex candidate generated during the search.
    kinds : tuple of str
        Kind of each node: ``"start"``, ``"vertex"``, ``"turn"``, ``"goal"``; the lattice
        planner's ``"lattice"``, ``"approach"`` and ``"arc"`` (:mod:`segplan.planning.lattice.escape`) (and
        ``"refined"`` for a node added or moved by :func:`segplan.refine`).
    refinement : Refinement or None
        What :func:`segplan.refine` changed (None: the search's plan as found).
    planner : str or None
        The planner that made the plan: :func:`segplan.plan_scenario`'s ``planner``
        (``"lattice"``, the default planner, or ``"paper"``); None for a stage called
        alone (e.g. :func:`segplan.planning.lattice.search.plan_lattice`).
    options : PaperOptions or DefaultOptions or None
        Every value that made it (:mod:`segplan.planning.options`); None as ``planner``.
    """

    nodes: tuple
    unions: tuple
    cost: float
    search_cost: float
    expanded: int
    generated: int
    seconds: float
    heuristic: str
    cost_kind: str
    version: str
    collision_checks: int
    exact_checks: int
    iterations: tuple
    kinds: tuple
    refinement: Refinement | None = None
    planner: str | None = None
    options: object = field(default=None, compare=False)

    def to_dict(self) -> dict:
        """Plain-JSON summary (angles in degrees, like scenario files)."""
        return {
            "cost": self.cost,
            "search_cost": self.search_cost,
            "nodes": [[p.x, p.y, math.degrees(p.theta)] for p in self.nodes],
            "kinds": list(self.kinds),
            "alphas_deg": [math.degrees(u.alpha) for u in self.unions],
            "expanded": self.expanded,
            "generated": self.generated,
            "seconds": self.seconds,
            "heuristic": self.heuristic,
            "cost_kind": self.cost_kind,
            "version": self.version,
            "collision_checks": self.collision_checks,
            "exact_checks": self.exact_checks,
            "refinement": None if self.refinement is None else dataclasses.asdict(self.refinement),
            "planner": self.planner,
            "options": None if self.options is None else self.options.to_dict(),
        }


def lattice_plan(start, unions, kinds, cost, search_cost, expanded, generated, seconds, stats) -> Plan:
    """A :class:`Plan` of the lattice planner (``version="lattice"``, Dubins h', LONGD cost):
    the nodes are ``start`` and the unions' ends; ``stats`` the workspace's counters
    (``collision_checks``, ``exact_checks``)."""
    return Plan(
        nodes=(start,) + tuple(u.p1 for u in unions),
        unions=tuple(unions),
        cost=cost,
        search_cost=search_cost,
        expanded=expanded,
        generated=generated,
        seconds=seconds,
        heuristic="dubins",
        cost_kind="longd",
        version="lattice",
        collision_checks=stats.collision_checks,
        exact_checks=stats.exact_checks,
        iterations=(),
        kinds=tuple(kinds),
    )


def direct_plan(start, u, seconds: float, stats) -> Plan:
    """The lattice planner's plan of one free union ``u`` from ``start`` (or of none: the
    start is the goal): :func:`lattice_plan`."""
    unions = () if u is None else (u,)
    cost = unions_longd(unions)
    return lattice_plan(
        start,
        unions,
        ("start",) + ("goal",) * len(unions),
        cost,
        cost,
        len(unions),
        1 + len(unions),
        seconds,
        stats,
    )
