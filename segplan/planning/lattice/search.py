"""The lattice planner: a lattice A*, its retry, escapes and shortcuts (beyond the paper).

Issue 12. The paper's search (:mod:`segplan.planning.paper.search`) expands few successors per
node and gives up when they run out (an enclosed goal, but also many floors a sampling planner
solves). This planner keeps the paper's pieces (cubic unions, LONGD costs, the on-line
collision test, the steering limit) and makes the search complete on a lattice, in the shape
of Hybrid A* (Dolgov et al. 2008). Its house:

* :mod:`~segplan.planning.lattice.frame`: lattice states and world poses, a primitive's union
  from a state; :mod:`~segplan.planning.lattice.primitives`: the motion primitives;
  :mod:`~segplan.planning.lattice.clearance`: the clearance grid and the distance field;
  :mod:`~segplan.planning.schedule`: when each mechanism starts and how much it does.
* :mod:`~segplan.planning.lattice.astar`: the A* at one resolution, composed of its parts:
  the lazy edges (:mod:`~segplan.planning.lattice.edges`), the goal's approach tree
  (:mod:`~segplan.planning.lattice.approach`) and the guide (:mod:`~segplan.planning.lattice.guide`).
* This module, the planner: the paper's direct union first; the clearance grid (laid out in the
  start's frame) and the distance field; the A* at the default resolution and, after an
  exhausted lattice, once more at half the cell; every union of a found plan checked again by
  the certified test (:meth:`segplan.planning.validity.Workspace.union_free`: the search runs
  again without a refused one); greedy shortcuts of the plan (:mod:`~segplan.planning.lattice.shortcut`).
* **Completeness**: the search expands every reachable lattice state before it says
  ``NoPathError(reason="exhausted")``, and says at which resolution. Before searching, the
  grid's free cells (8-connected) must join the start's rear point to the goal's: if they do
  not, no path exists at all and the error comes at once (an enclosed goal).
* **Tight corners** (:mod:`~segplan.planning.lattice.escape`): when the lattice runs out of
  states (or the goal looks enclosed), the planner asks for the tight arcs of short unions out
  of the start and into the goal, which turn closer to ``R`` than any primitive, and searches
  again between their ends, each pair first probed with :data:`PROBE_EXPANSIONS` (the pairs
  cut short are then searched in full); a plan far above the Dubins length tries the direct union
  between such arcs' ends. Where no pair of arcs joins, a forward robot's last tries start
  or end with a hop (a single union to a pose off the lattice's headings and offsets,
  :func:`~segplan.planning.lattice.escape.hop_pairs`), each probed with :data:`HOP_PROBE`.
* **Reverse** (a robot that may reverse, issue 26: :mod:`~segplan.planning.lattice.reverse`):
  reverse links in the A*, its costs ``reverse_factor`` and ``cusp_penalty``; the shortcuts
  work within each run of one direction, so the cusps stay where the search put them. Its
  search is staged (:func:`_quick_then_escape`: :data:`QUICK_EXPANSIONS` first, then the
  escapes, then the rest); its escapes also drive the tight arcs backwards and add hops
  (single unions either way to poses off the lattice's headings) and turn-arounds, probed
  with :data:`PROBE_EXPANSIONS` first, the cheapest plan of them kept (:func:`_escape`).

:func:`plan_lattice` returns a :class:`segplan.planning.plan.Plan` (``version="lattice"``);
:func:`segplan.plan_scenario` calls it (``planner="lattice"``, the default) and refines the plan
(:mod:`segplan.planning.refine`).
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import replace

import numpy as np

from ...floor.scenario import Scenario
from ...model.pose import Pose, show_pose, wrap_ieee
from ..context import workspace_of
from ..dubins import dubins_length_scalar
from ..links import LinkModel
from ..plan import NoPathError, Plan, check_limits, check_option, direct_plan, lattice_plan
from ..schedule import SCHEDULE, Schedule
from ..validity import Workspace
from .astar import LatticeAStar
from .clearance import ClearanceGrid, DistanceField, grid_resolutions
from .dead_end import DEAD_END_TURN, goal_way_out, start_dead_end
from .escape import arc_pairs, hop_pairs, improve_with_arcs, join_arcs
from .legs import Legs
from .primitives import max_reach, primitive_set
from .reverse import by_runs
from .shortcut import shortcut_plan

__all__ = [
    "DEAD_END_TURN",
    "CUSP_PENALTY",
    "GOAL_RADIUS",
    "LATTICE_MAX_EXPANSIONS",
    "REVERSE_FACTOR",
    "HOP_ESCAPES",
    "HOP_PROBE",
    "PROBE_EXPANSIONS",
    "QUICK_EXPANSIONS",
    "lattice_options",
    "lattice_search",
    "plan_lattice",
]


#: Default ``max_expansions`` of the lattice search (measured: see
#: :class:`segplan.planning.options.LatticeOptions`' ``max_expansions``).
LATTICE_MAX_EXPANSIONS = 200_000

#: Default ``goal_radius`` of :func:`plan_lattice`: ``a R + b L`` with ``(a, b)`` these.
GOAL_RADIUS = (2.0, 1.0)
#: Defaults of ``reverse_factor`` and ``cusp_penalty`` (units of ``L``) of a robot that may
#: reverse (:class:`segplan.planning.options.LatticeOptions`, where the measurement is).
REVERSE_FACTOR = 1.15
CUSP_PENALTY = 0.5


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
    reverse_factor: float = REVERSE_FACTOR,
    cusp_penalty: float = CUSP_PENALTY,
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
    reverse_factor, cusp_penalty : float
        A robot that may reverse (``scenario.robot.reverse``, issue 26): the factor (> 0) on a
        reverse link's LONGD and the cost (>= 0, units of ``L``) of a change of direction, in
        the search (:mod:`segplan.planning.lattice.reverse`); unused for a forward-only robot.

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
        reverse_factor=reverse_factor,
        cusp_penalty=cusp_penalty,
    )
    return plan


def lattice_options(
    scenario,
    *,
    resolution=None,
    weight=2.0,
    retry=True,
    analytic_every=8,
    goal_radius=None,
    cell=None,
    escapes=True,
    schedule: Schedule = SCHEDULE,
    reverse_factor=REVERSE_FACTOR,
    cusp_penalty=CUSP_PENALTY,
):
    """The options of :func:`lattice_search` checked (ValueError naming a bad one), as a
    dict without ``escapes``; :func:`segplan.plan_scenario` checks them even where it
    does not run the lattice.

    Also refused: a robot whose turns are far wider than the floor (its turning
    primitives at the first resolution reach more than twice across the floor: the
    bounds, or without walls the box of the start, the goal and the obstacles). No turn
    of the lattice fits there; computing its primitives would take minutes and gigabytes
    (issue 25: a 1e-6 deg steering limit on Fig. 5's floor took 10 GB).
    """
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    L = scenario.robot.L
    resolution = check_option(resolution, "resolution", 0.0, allow_none=True)
    if resolution is not None and resolution > L:
        raise ValueError(f"resolution must be at most L={L}, got {resolution!r}")
    for name, flag in (("retry", retry), ("escapes", escapes)):
        if not isinstance(flag, bool):
            raise ValueError(f"{name} must be True or False, got {flag!r}")
    if not isinstance(schedule, Schedule):
        raise ValueError(f"schedule must be a Schedule, got {type(schedule).__name__}")
    _check_turns_fit(scenario, resolution, schedule)
    return {
        "resolution": resolution,
        "weight": check_option(weight, "weight", 1.0, lo_ok=True),  # 1: the admissible h'
        "retry": retry,
        "analytic_every": check_option(analytic_every, "analytic_every", 1, integer=True, lo_ok=True),
        "goal_radius": check_option(goal_radius, "goal_radius", 0.0, allow_none=True),
        "cell": check_option(cell, "cell", 0.0, allow_none=True),
        "reverse_factor": check_option(reverse_factor, "reverse_factor", 0.0),
        "cusp_penalty": check_option(cusp_penalty, "cusp_penalty", 0.0, lo_ok=True),
    }


def _check_turns_fit(scenario, resolution, schedule: Schedule) -> None:
    """ValueError if the robot's turning primitives reach more than twice across the floor
    (:func:`lattice_options`)."""
    robot = scenario.robot
    res = resolution or _default_resolution(robot.L, robot.min_turning_radius, schedule)
    reach = max_reach(robot.L, robot.max_steer, res)
    fb = scenario.free_bounds
    if fb is None:
        pts = np.concatenate([np.array([scenario.start[:2], scenario.goal[:2]])] + list(scenario.enlarged))
        fb = (*pts.min(axis=0), *pts.max(axis=0))
    across = math.hypot(fb[2] - fb[0], fb[3] - fb[1])
    if not reach <= 2.0 * across:
        raise ValueError(
            f"max_steer={math.degrees(robot.max_steer):.3g} deg: the robot turns far wider than the "
            f"floor (minimum turning radius R={robot.min_turning_radius:.3g} m; the lattice's turns "
            f"reach {reach:.3g} m, the floor is {across:.3g} m across): the default planner cannot "
            "turn on it; planner='paper' joins the poses by the paper's unions alone"
        )


def _default_resolution(L: float, R: float, schedule: Schedule) -> float:
    """The lattice's first resolution by default: ``L / 8``, or ``R / wide_turn_cells`` for a
    robot turning wider (at most ``L``; :attr:`segplan.planning.schedule.Schedule.wide_turn_cells`)."""
    return min(L, max(0.125 * L, R / schedule.wide_turn_cells))


def lattice_floor(scenario, ws: Workspace, tries: list[float], cell: float, schedule=SCHEDULE):
    """The clearance grid (laid out at the start, room for the primitives of every resolution
    in ``tries``) and the distance field to the goal of a scenario: ``(grid, field)``."""
    robot = scenario.robot
    L, R = robot.L, robot.min_turning_radius
    reach = max(max_reach(L, robot.max_steer, t) for t in tries)
    pad = int(math.ceil(reach / cell)) + 2
    grid = ClearanceGrid(
        ws.convex,
        tuple(scenario.start),
        scenario.free_bounds,
        cell,
        pad,
        scenario.goal,
        schedule.margin(L, R),
        ws.overhang,
        ws.depth,
    )
    gl = grid.to_lattice(np.array([scenario.goal[:2]]))[0]
    field = DistanceField(grid, gl, max(cell, 0.25 * L, math.sqrt((grid.nx * grid.ny) / 5e4) * cell))
    return grid, field


def lattice_resolutions(
    scenario, resolution, retry: bool, cell, schedule=SCHEDULE
) -> tuple[list[float], float]:
    """The resolutions to try (``resolution``, default ``L / 8`` or coarser for a robot that
    turns wide (:func:`_default_resolution`), then half of it if ``retry``) and the clearance
    grid's cell (:func:`segplan.planning.lattice.clearance.grid_resolutions`)."""
    robot = scenario.robot
    L, R = robot.L, robot.min_turning_radius
    res = resolution or _default_resolution(L, R, schedule)
    tries = [res, 0.5 * res] if retry else [res]
    return grid_resolutions(scenario, tries, cell, schedule.margin(L, R), resolution is None)


def _lattice_search(
    scenario,
    *,
    resolution,
    weight,
    retry,
    analytic_every,
    goal_radius,
    cell,
    max_expansions,
    time_limit,
    t0,
    links: LinkModel,
    schedule=SCHEDULE,
    progress=None,
    reverse_factor=REVERSE_FACTOR,
    cusp_penalty=CUSP_PENALTY,
    diagnose=False,
):
    """:func:`lattice_search` without the escapes (one lattice search, its retry), its
    unions made by ``links`` (on ``links.ws``); the options checked by :func:`lattice_options`.
    ``diagnose``: a forward robot's search that stops at a limit says whether its goal looks
    like the way out of a dead end (:func:`segplan.planning.lattice.dead_end.goal_way_out`;
    the call's own search only, not the sub-searches of its escapes and repairs, whose
    failures are not reported)."""
    robot = scenario.robot
    L, R = robot.L, robot.min_turning_radius
    max_expansions, time_limit = check_limits(max_expansions, time_limit)
    if max_expansions is None:
        max_expansions = LATTICE_MAX_EXPANSIONS
    tries, cell = lattice_resolutions(scenario, resolution, retry, cell, schedule)
    # off-line work, outside the planning time (as the paper's search): the primitives (once
    # per robot and resolution; those of the retry when it comes), the fitted coefficients of
    # the heuristic frame and of [2]
    primitive_set(L, robot.max_steer, tries[0])
    t0 = time.perf_counter() if t0 is None else t0
    deadline = t0 + time_limit
    ws = links.ws
    start, goal = scenario.start, scenario.goal
    # the paper's direct union first: where it is free, it is the plan (no grid to build)
    direct = None if start == goal else links.union(start, goal)
    if start == goal or (direct is not None and ws.union_free(direct)):
        return direct_plan(start, direct, time.perf_counter() - t0, ws.stats), links
    grid, field = lattice_floor(scenario, ws, tries, cell, schedule)
    gl = grid.to_lattice(np.array([goal[:2]]))[0]

    escapable = ""  # may tight arcs at the start or goal help? (not after a proof)

    def fail(reason, head, expanded, generated, best, note=None):
        exc = NoPathError(f"{head}; expanded {expanded} states", reason, expanded, generated, 0.0, best)
        exc.seconds = time.perf_counter() - t0
        exc.escapable = escapable
        exc.head = head  # the message without its count (the escapes add to both)
        exc.note = note  # what the message says about the floor beyond the limit, if anything
        raise exc

    la, lb = grid.component(np.array([[0.0, 0.0], gl])).tolist()
    if la != lb:
        best = lattice_plan(Pose(*start), [], ["start"], 0.0, 0.0, 0, 1, time.perf_counter() - t0, ws.stats)
        fail(
            "exhausted",
            f"no path from {show_pose(start)} to {show_pose(goal)}: the goal's free region is not "
            f"connected to the start's (grid of {grid.cell:.3g} m cells); no path exists",
            0,
            1,
            best,
        )
    radius = goal_radius if goal_radius is not None else GOAL_RADIUS[0] * R + GOAL_RADIUS[1] * L
    banned: set = set()
    shortcut = functools.partial(
        shortcut_plan, ex=links, grid=grid, t0=t0, window=schedule.shortcut_window, deadline=deadline
    )
    expanded_total = 0
    proofs: list = []  # (resolution, "exhausted" or "enclosed", approach states, reach) per try
    for k, r in enumerate(tries):
        search = LatticeAStar(
            scenario,
            ws,
            links,
            grid,
            field,
            r,
            weight=weight,
            analytic_every=analytic_every,
            goal_radius=radius,
            banned=banned,
            schedule=schedule,
            progress=progress,
            reverse_factor=reverse_factor,
            cusp_penalty=cusp_penalty * L,
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
            if not bad:  # shortcuts within each run of one direction: the cusps stay
                return by_runs(plan, shortcut), links
            for i in bad:  # never seen in our tests; the search runs again without them
                banned.add(edges[i] if i < len(edges) else ("final", search.goal_parent[0]))
            expanded_total += expanded
        expanded_total += expanded
        proofs.append((r, outcome, search.approach.enclosure_states, search.reach()))
        if outcome != "exhausted" or k == len(tries) - 1:
            best = search.make_plan(search.chain(search.best), None, expanded_total, t0)
            note = None  # what a limit's message says about the floor (below)
            if outcome == "exhausted":
                what = (
                    "every lattice state reachable from the start was expanded at resolution "
                    + " and ".join(f"{p[0]:.4g} m" for p in proofs)
                    + ": no chain of the lattice's unions reaches the goal (not a proof that no "
                    "path exists: one may need turns tighter than the lattice's, e.g. a start or "
                    "a goal facing an obstacle close by)"
                )
                dead_end = None if robot.reverse else start_dead_end(proofs)
                if dead_end:
                    what = f"{dead_end}; {what}"
            elif outcome == "enclosed":
                what = (
                    f"the goal looks enclosed: only {proofs[-1][2]} states of the lattice laid out "
                    f"in the goal's frame (resolution {r:.4g} m) reach it by primitives and no union "
                    f"from the start reaches one of them; the search stopped {schedule.enclosed_expansions} "
                    "expansions later (a limit, not a proof)"
                )
                outcome = "expansions"
            else:
                what = {
                    "expansions": f"the expansion limit max_expansions={max_expansions} was reached",
                    "time": f"the time limit time_limit={time_limit:g} s was reached",
                }[outcome]
                note = goal_way_out(search.approach) if diagnose and not robot.reverse else None
                if note:
                    what = f"{what}; {note}"
            # tight arcs may help: out of the start and into the goal after an exhausted
            # lattice, into the goal after one that looks enclosed (not after a proof)
            escapable = "both" if outcome == "exhausted" else "goal" if proofs[-1][1] == "enclosed" else ""
            fail(
                outcome,
                f"no path from {show_pose(start)} to {show_pose(goal)}: {what}",
                expanded_total,
                len(search.g),
                best,
                note,
            )
    raise AssertionError("unreachable")


def _reverse_costs(options: dict, scenario) -> tuple[float, float]:
    """``(reverse_factor, cusp_penalty in metres)`` of the checked ``options`` (the penalty is
    given in units of ``L``)."""
    return options["reverse_factor"], options["cusp_penalty"] * scenario.robot.L


#: The expansions of a probing search between escape pairs (:func:`_escape`). Set by hand
#: from dead-end-010 (its one-cusp escapes took 37-160 expansions, its three-cusp ones
#: 400-1900; ``segplan.studies.reverse_floors``), not tuned; a forward robot's pairs are
#: probed with it too since issue 25's warehouse-020 (its joining pair took 8).
PROBE_EXPANSIONS = 256
#: A forward robot's hop pairs (:func:`segplan.planning.lattice.escape.hop_pairs`) searched
#: between at most, each for at most :data:`HOP_PROBE` expansions, after its arcs' pairs failed
#: (:func:`_escape`). Set by hand: on the two floors they were made for (clutter-097,
#: robots-086) the 7th and the 2nd pair joined, in 8 and 79 expansions. A call that fails
#: pays for them: measured on 2026-12-06 on a forward robot on every 4th of the first 40
#: floors of the reverse study's dead-end, k-turn and bay-out kinds
#: (``segplan.studies.reverse_floors``, which a forward robot cannot leave), CPU time to the
#: ``NoPathError`` 0.01-0.13 s -> 0.01-0.24 s in the bays, 0.04-0.08 s -> 0.36-0.57 s on the
#: k-turns that failed fast (the others took 0.4-8 s before and about as long after). Not tuned.
HOP_ESCAPES = 8
#: Expansions of one search from or to a hop (:data:`HOP_ESCAPES`).
HOP_PROBE = 128


def _search_between(
    scenario, links: LinkModel, a, b, options: dict, budget: int, left: float, schedule, progress
):
    """One lattice search (no retry) from arc ``a``'s inner pose (or the start, ``a`` None) to
    arc ``b``'s (or the goal), at most ``budget`` expansions and ``left`` seconds: its plan,
    or the :class:`NoPathError` it raises (the escapes' and the loop repair's sub-search)."""
    ends = {"start": a.inner if a else scenario.start, "goal": b.inner if b else scenario.goal}
    inner, _ = _lattice_search(
        replace(scenario, **ends), max_expansions=budget, time_limit=left, t0=None, links=links,
        schedule=schedule, progress=progress, **{**options, "retry": False},
    )  # fmt: skip
    return inner


def _escape(
    scenario,
    links: LinkModel,
    exc: NoPathError,
    options: dict,
    max_expansions: int,
    deadline: float,
    t0: float,
    schedule=SCHEDULE,
    progress=None,
    legs: Legs | None = None,
) -> Plan:
    """Search again between the inner poses of tight arcs
    (:func:`segplan.planning.lattice.escape.arc_pairs` of ``exc.escapable``), the cheapest
    pairs first, at most
    :attr:`~segplan.planning.schedule.Schedule.max_escapes` of them, at the first
    resolution only, while the limits of the whole call allow (``max_expansions``, counted
    from ``exc.expanded``; ``deadline``). Returns the arcs around the first plan found;
    re-raises ``exc`` (with the expansions and the time of every try added) if none.

    A robot that may reverse has many more pairs (hops, arcs either way), and the cheapest
    estimate often leads to a plan with extra cusps (dead-end-010: 20.9 m and 4 cusps
    against 11-13 m with one from other hops, found in 37-160 expansions against 400-1900).
    Its pairs are first *probed*: each search gets at most :data:`PROBE_EXPANSIONS`; then,
    only if no probe found a plan, the pairs a probe cut short are searched in full. Its
    tries go on after a plan is found, for as many expansions again as the escapes took to
    find it (an anytime doubling, counted in expansions so that the answer is the same on
    any machine; k-turn-008's turn-around joins at once, after which its hops would have
    taken 0.3 s each), while a pair's estimate is below the best plan's search cost, and the
    cheapest plan (search cost) is returned. A forward robot's pairs are probed in the same
    way (warehouse-020 of :mod:`segplan.studies.floor_kinds`: the search towards its first
    pair's arc ran to the 10 s time limit, while the fourth pair's joined in 8 expansions),
    and its escapes return the first plan; if no pair of its arcs joins (and no limit cut the tries
    short), the first :data:`HOP_ESCAPES` of its hop pairs
    (:func:`segplan.planning.lattice.escape.hop_pairs`) are tried, each for at most
    :data:`HOP_PROBE` expansions, and the first plan is returned (only calls that failed
    before get there: every plan found before is found as before).
    ``legs``: the call's :class:`segplan.planning.lattice.legs.Legs` (None: a new one; the
    same pairs).
    """
    pairs = arc_pairs(scenario, links, exc.escapable, *_reverse_costs(options, scenario), legs=legs)
    pairs = pairs[: schedule.max_escapes]
    used = exc.expanded
    tries = 0
    cut = None  # the limit that stopped the tries, if one did
    best = None
    until = math.inf  # after the first plan: as many expansions again as it took (below)
    pending = pairs
    hopped = []  # a forward robot's hop pairs, once its arcs' pairs failed
    forward = not scenario.robot.reverse
    # the arcs' pairs probed, those a probe cut short searched in full, then a forward robot's hops
    caps = (PROBE_EXPANSIONS, None, HOP_PROBE) if forward else (PROBE_EXPANSIONS, None)
    for stage, cap in enumerate(caps):
        again = []  # the pairs a probe cut short
        for est, a, b in pending:
            if best is not None and not est < best.search_cost:
                continue  # this pair cannot win
            if best is not None and used >= until:
                break
            left = deadline - time.perf_counter()
            if used >= max_expansions or left <= 0:
                cut = "expansions" if used >= max_expansions else "time"
                break
            tries += int(stage != 1)  # a pair searched in full after its probe is one try
            budget = max_expansions - used if cap is None else min(cap, max_expansions - used)
            try:
                inner = _search_between(scenario, links, a, b, options, budget, left, schedule, progress)
            except NoPathError as e:
                used += e.expanded
                if cap is not None and e.reason == "expansions" and budget == cap:
                    again.append((est, a, b))
                    continue
                cut = e.reason if e.reason in ("expansions", "time") else None
                continue
            used += inner.expanded
            plan = join_arcs(scenario, a, inner, b, used, t0)
            if forward:
                return plan
            if best is None:
                until = used + (used - exc.expanded)
            if best is None or plan.search_cost < best.search_cost:
                best = plan
        if best is not None or stage == len(caps) - 1:
            break
        # a limit of the call ends the tries; so does a search whose goal looked enclosed,
        # except after a forward robot's probes (its pairs cut short are searched in full)
        enclosed = cut == "expansions" and used < max_expansions
        if cut is not None and not (forward and stage == 0 and enclosed):
            break
        if stage == 0:
            pending = again
        else:
            pending = hopped = hop_pairs(scenario, links)[:HOP_ESCAPES]
    if best is not None:
        return replace(best, expanded=used, seconds=time.perf_counter() - t0)
    exc.expanded = used
    exc.seconds = time.perf_counter() - t0
    offered = len(pairs) + len(hopped)
    tried = f"searches between tight arcs at the ends: {tries} of {offered} tried, none joined"
    if hopped:
        tried += f" ({len(hopped)} of them from or to hops)"
    if cut is not None:  # the tries were cut short: not a result about the floor
        if cut == "time" or used >= max_expansions:
            limit = f"max_expansions={max_expansions}" if cut == "expansions" else "the time limit"
            tried += f"; {limit} was reached before the rest were tried (more may join: raise it)"
        else:  # a search between arcs stopped where its goal looked enclosed, below the call's limit
            own = f"Schedule.enclosed_expansions={schedule.enclosed_expansions}"
            tried += "; a search between them stopped at the lattice's own limit"
            tried += f" (its goal looked enclosed: {own}; a limit, not a proof)"
        exc.reason = cut
    exc.args = (f"{exc.head}; {tried}; expanded {used} states",)
    raise exc


#: The expansions of a reversing robot's first, quick lattice search (:func:`_quick_then_escape`).
#: Set by hand: the reverse study's bay-out, reverse-park and dead-end floors took at most 784
#: expansions (every fourth floor, 75 in all; ``segplan.studies.reverse_floors``), and its
#: k-turns took 1-3 s or failed at the time limit; not tuned. Lower values measured on
#: 2026-12-07 on all 400 floors of the reverse study (``reverse_study.run_segplan``, the
#: default costs; lengths over OMPL's stored Reeds-Shepp BIT*, which do not depend on the
#: machine): 500 changes 8 plans (3 shorter, 5 longer), every kind's median and worst as at
#: 1000; 250 changes 21 (13 shorter, 8 longer) but k-turn-095 goes to 1.159 times OMPL's,
#: over issue 26's 1.15 (k-turn worst 1.132 at 1000). Neither is kept (250 saved about a
#: tenth of the k-turns' median time, with both runs sharing the machine: no timing result).
QUICK_EXPANSIONS = 1000


def _quick_then_escape(
    search, scenario, links, options, limit, deadline, t0, schedule, progress, legs
) -> Plan:
    """A reversing robot's lattice search in stages: ``search(QUICK_EXPANSIONS)``; if that is
    cut by the expansions, the escapes (:func:`_escape`: hops, arcs either way and
    turn-arounds, :mod:`segplan.planning.lattice.escape`), whose multi-point turns the
    lattice's primitives cannot make in a corridor narrower than two turning radii (it
    searched such floors for seconds and failed on 15 of 94); if none joins, the search
    again with the rest of ``limit``. A search that ends otherwise is the answer (a failure
    raised as it was). ``legs``: the call's :class:`segplan.planning.lattice.legs.Legs`."""
    try:
        return search(QUICK_EXPANSIONS)
    except NoPathError as exc:
        if exc.reason != "expansions":
            raise
        exc.escapable = "both"
        try:
            return _escape(scenario, links, exc, options, limit, deadline, t0, schedule, progress, legs)
        except NoPathError as again:
            if again.reason == "time" or again.expanded >= limit:
                raise
            return search(limit - again.expanded)


#: A forward plan longer than this many times the Dubins length of its ends is searched
#: again towards the tight loops at its ends (:func:`_repair_loops`). Set by hand on
#: chapter 11's worst warehouse floors (warehouse-013: 2.5 times, warehouse-061: 3.4 times,
#: both plans going round a rack where the best path loops in an aisle crossing); not tuned.
LOOP_GAP = 2.0
#: A tight arc (:func:`segplan.planning.lattice.escape.tight_arcs`) turning at least this much
#: (radians) is a loop the lattice's primitives (turning at ``1.12 R``) cannot make.
LOOP_TURN = 0.75 * math.pi
#: Pairs of arcs with a loop searched between at most (:func:`_repair_loops`), each for at
#: most :data:`LOOP_EXPANSIONS` expansions (warehouse-013's loop joined in 37-42). Measured
#: on 2026-12-03 on the floor-kinds study's first 100 floors of warehouse, rooms, parking,
#: clutter and robots (``segplan.studies.floor_kinds``, OMPL's stored BIT* 5 s as the
#: reference): 11 plans changed, every one shorter (warehouse worst 2.07 to 1.22 times
#: BIT*'s); 4 tries of 256 expansions cost 150-550 ms more on those floors, 2 tries 50-300 ms
#: and kept all but one gain (rooms-055, already 0.94 times BIT*'s), 128 expansions lost
#: warehouse-061's (back to 1.83). With 2 tries the repair ran on 15 of the 100 warehouse and
#: 16 of the 100 rooms floors and shortened 5 and 6 of them; where it found nothing it cost
#: 5-430 ms (the price of the gains; the Dubins gap does not tell the two apart, nor does the
#: distance field's bound, which is weaker than Dubins' on these floors).
LOOP_TRIES = 2
LOOP_EXPANSIONS = 256


def _repair_loops(
    scenario,
    links: LinkModel,
    plan: Plan,
    options: dict,
    deadline: float,
    t0: float,
    schedule,
    progress,
    legs=None,
) -> Plan:
    """A shorter forward plan through a tight loop at an end, or ``plan`` itself.

    Where the best path turns round in a crossing of aisles (a loop on a circle of radius
    about ``R``), the lattice, whose tightest primitive turns at ``1.12 R``, goes round a
    whole rack instead (chapter 11's warehouse-013: 32.9 m against BIT*'s 15.9 m). When the
    plan costs more than :data:`LOOP_GAP` times the Dubins length of its ends, the pairs of
    tight arcs (:func:`segplan.planning.lattice.escape.arc_pairs`) of which one turns by at
    least :data:`LOOP_TURN` are searched between, the cheapest estimates first, at most
    :data:`LOOP_TRIES` of them and :data:`LOOP_EXPANSIONS` expansions each (counted, so the
    answer is the same on any machine), within ``deadline``; the cheapest plan (LONGD [1])
    is kept. A robot that may reverse makes its loops with a cusp (its turn-arounds). ``legs``:
    the call's :class:`segplan.planning.lattice.legs.Legs` (None: a new one)."""
    s, g = Pose(*scenario.start), Pose(*scenario.goal)
    R = scenario.robot.min_turning_radius
    if scenario.robot.reverse or not plan.cost > LOOP_GAP * dubins_length_scalar(*s, *g, R):
        return plan

    def loops(arc, end: Pose) -> bool:
        return arc is not None and abs(wrap_ieee(arc.inner.theta - end.theta)) >= LOOP_TURN

    pairs = [p for p in arc_pairs(scenario, links, "both", legs=legs) if loops(p[1], s) or loops(p[2], g)]
    best, used = plan, plan.expanded
    for est, a, b in pairs[:LOOP_TRIES]:
        left = deadline - time.perf_counter()
        if not est < best.cost or left <= 0:
            break
        try:
            inner = _search_between(scenario, links, a, b, options, LOOP_EXPANSIONS, left, schedule, progress)
        except NoPathError as e:
            used += e.expanded
            continue
        used += inner.expanded
        cand = join_arcs(scenario, a, inner, b, used, t0)
        if cand.cost < best.cost:
            best = cand
    return best if best is plan else replace(best, expanded=used, seconds=time.perf_counter() - t0)


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
    schedule: Schedule = SCHEDULE,
    progress=None,
    reverse_factor=REVERSE_FACTOR,
    cusp_penalty=CUSP_PENALTY,
    alternatives: list | None = None,
):
    """:func:`plan_lattice`, also returning the :class:`segplan.planning.links.LinkModel` it used.

    ``workspace``: a :class:`segplan.planning.validity.Workspace` of this scenario to reuse (the
    default planner passes the paper's search's; its counters then add up).
    ``escapes``: tight arcs out of the start and into the goal (:mod:`segplan.planning.lattice.escape`):
    when the lattice runs out of states (or the goal looks enclosed), search again between
    their ends while the limits allow, at the first resolution only (the retry's finer
    lattice, tried once between the start and the goal, would multiply the time of every
    pair); when its plan costs far more than the Dubins length, try the paper's direct
    union between their ends (within ``time_limit``).
    ``schedule``: when each mechanism starts and how much it does
    (:class:`segplan.planning.schedule.Schedule`; default
    :data:`segplan.planning.schedule.SCHEDULE`, the one every plan of the package is made with).
    ``progress``: called with the expansions of the current search every
    :attr:`~segplan.planning.schedule.Schedule.deadline_every` expansions (it only watches).
    ``alternatives``: for a robot that may reverse, a list that receives the plan of its
    improvement by arcs either way and turn-arounds
    (:func:`segplan.planning.lattice.escape.improve_with_arcs` with ``reverse_factor``)
    where it differs from the plan (after the forward arcs' improvement, which every robot
    gets), instead of its replacing the plan: its cost is compared before refinement, and
    the lattice's plan refines better on some floors (the reverse study's bay-out-050: 1.00
    times OMPL's length refined, 1.13 through the improvement), so the default planner
    refines both and keeps the cheaper.
    """
    options = lattice_options(
        scenario,
        resolution=resolution,
        weight=weight,
        retry=retry,
        analytic_every=analytic_every,
        goal_radius=goal_radius,
        cell=cell,
        escapes=escapes,
        schedule=schedule,
        reverse_factor=reverse_factor,
        cusp_penalty=cusp_penalty,
    )
    t0 = time.perf_counter() if t0 is None else t0
    links = LinkModel(workspace_of(scenario) if workspace is None else workspace)
    limit = LATTICE_MAX_EXPANSIONS if max_expansions is None else max_expansions
    deadline = t0 + float(time_limit)

    def search(expansions):
        plan, _ = _lattice_search(
            scenario,
            max_expansions=expansions,
            time_limit=time_limit,
            t0=t0,
            links=links,
            schedule=schedule,
            progress=progress,
            diagnose=True,
            **options,
        )
        return plan

    legs = Legs(links, scenario.robot.min_turning_radius)  # the tight circles' legs, each driven once
    try:
        if scenario.robot.reverse and escapes and limit > QUICK_EXPANSIONS:
            args = (scenario, links, options, limit, deadline, t0, schedule, progress, legs)
            plan = _quick_then_escape(search, *args)
        else:
            plan = search(max_expansions)
    except NoPathError as exc:
        if not (escapes and getattr(exc, "escapable", "")):
            raise
        plan = _escape(scenario, links, exc, options, limit, deadline, t0, schedule, progress, legs)
    if escapes:
        plan = improve_with_arcs(scenario, links, plan, t0, deadline, schedule, legs=legs)
        plan = _repair_loops(scenario, links, plan, options, deadline, t0, schedule, progress, legs)
        if alternatives is not None and scenario.robot.reverse:
            costs = _reverse_costs(options, scenario)
            better = improve_with_arcs(scenario, links, plan, t0, deadline, schedule, *costs, legs)
            if better is not plan:
                alternatives.append(better)
    return plan, links
