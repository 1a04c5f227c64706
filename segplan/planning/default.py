"""The default planner (beyond the paper): the paper's search, then the lattice, then the refinement.

1. **The paper's search** (:func:`segplan.planning.stages.paper_search`), within a few
   expansions and a share of the time (:class:`segplan.planning.options.DefaultOptions`:
   ``paper``, ``paper_share``): fast where it succeeds.
2. **The lattice** (:func:`segplan.planning.stages.lattice_stage`; its tight arcs at the
   ends and its shortcuts run inside it): if the paper's search found a plan, a few
   expansions more to look for a shorter one (``lattice_after_paper``), none if that plan is
   already within ``near_lower_bound`` of a lower bound; otherwise up to
   ``lattice.max_expansions`` and the rest of the time.
3. **The refinement** (:func:`segplan.planning.refine.refine_with`) of each plan found
   (the paper's and the lattice's; the one of lower cost first), each with the link model
   of the search that found it, until the call's deadline; the shorter refined plan is
   the answer. So the default plan is never longer than ``segplan.refine`` of the paper's
   plan where the paper's search found that plan within the default's expansions (a
   refinement of the two, not of the shorter alone: a longer plan refines to the shorter
   one about as often as not, see :class:`segplan.planning.options.DefaultOptions`).

Both searches share the context's one validity checker.

A robot that may reverse (``Robot(..., reverse=True)``, issue 26): the paper's search stays
forward-only; the lattice reverses where it pays; plans are compared by the lattice's cost
(:func:`segplan.planning.lattice.reverse.weighted_cost`: reverse links weighted, cusps
penalised) and the lower bound of ``near_lower_bound`` is the Reeds–Shepp length. The
refinement refines each same-direction run of a plan on its own
(:func:`segplan.planning.lattice.reverse.by_runs`), then each cusp tries the local moves
of the refinement on its two links (:func:`segplan.planning.refine.polish_cusps`): the
lattice puts cusps on its coarse headings.
The lattice's improvement by tight arcs and turn-arounds
(:func:`segplan.planning.lattice.escape.improve_with_arcs`) is a third plan refined with the
others rather than a replacement of the lattice's (``alternatives`` of
:func:`segplan.planning.lattice.search.lattice_search`).
"""

from __future__ import annotations

import dataclasses
import math

from ..model.pose import show_pose
from .context import PlanningContext
from .dubins import dubins_length_scalar
from .lattice.reverse import by_runs, weighted_cost
from .options import DefaultOptions
from .plan import NoPathError, Plan, Refinement
from .reeds_shepp import reeds_shepp_length
from .refine import polish_cusps, refine_with
from .stages import lattice_stage, paper_search

__all__ = ["default_pipeline", "lattice_budget"]


def lattice_budget(ctx: PlanningContext, options: DefaultOptions, paper: Plan | None) -> int:
    """Expansions the lattice gets after the paper's search: ``options.lattice.max_expansions``
    without a paper plan; with one, at most ``options.lattice_after_paper`` (a count, not a
    time share, so the plan does not depend on the machine), and 0 if the plan costs at most
    ``options.near_lower_bound`` times a lower bound of any plan's LONGD (the Dubins length
    of the rear point, :func:`segplan.planning.dubins.dubins_length`)."""
    expansions = options.lattice.max_expansions
    if paper is None:
        return expansions
    expansions = min(expansions, options.lattice_after_paper)
    s, g = ctx.scenario.start, ctx.scenario.goal
    robot = ctx.scenario.robot
    length = reeds_shepp_length if robot.reverse else dubins_length_scalar
    bound = length(s.x, s.y, s.theta, g.x, g.y, g.theta, robot.min_turning_radius)
    if paper.cost <= options.near_lower_bound * bound:
        return 0
    return expansions


def default_pipeline(ctx: PlanningContext, options: DefaultOptions) -> Plan:
    """The default planner's plan on the context's floor (module docstring); raises
    :class:`segplan.NoPathError` when neither search finds one (the lattice's failure, its
    time-out naming the call's ``time_limit``)."""
    # 1. the paper's search
    paper = paper_links = None
    try:
        paper, paper_links = paper_search(ctx, options.paper)
    except NoPathError:
        pass
    # 2. the lattice
    found = [] if paper is None else [(paper, paper_links)]
    expansions = lattice_budget(ctx, options, paper)
    if expansions > 0:
        try:
            if ctx.scenario.robot.reverse:  # the improved plan too, both refined (lattice_search)
                more: list = []
                found.append(lattice_stage(ctx, options.lattice, expansions, alternatives=more))
                found += [(plan, found[-1][1]) for plan in more]
            else:
                found.append(lattice_stage(ctx, options.lattice, expansions))
        except NoPathError as exc:
            if paper is None:
                raise _named_limits(exc, ctx, options) from None
            if exc.reason == "time":  # the paper's plan is the best found within the limit
                ctx.counters["stopped_by_time"] += 1
    # the shorter first (the paper's on a tie): it is the answer without refinement, and the
    # one refined first when time is short
    cost = _plan_cost(ctx, options)
    found.sort(key=lambda pair: cost(pair[0]))
    if options.refine is None:
        return found[0][0]
    # 3. the refinement of each, the shorter refined plan kept (the first on a tie)
    ctx.report("refine", "start")
    refined = [_refine(plan, links, options, ctx) for plan, links in found]
    best = min(refined, key=cost)
    ctx.report("refine", "done", cost=best.cost)
    return best


def _plan_cost(ctx: PlanningContext, options: DefaultOptions):
    """How plans are compared: LONGD [1] (``Plan.cost``); for a robot that may reverse, the
    lattice's cost (:func:`segplan.planning.lattice.reverse.weighted_cost`)."""
    if not ctx.scenario.robot.reverse:
        return lambda plan: plan.cost
    factor, penalty = options.lattice.reverse_factor, options.lattice.cusp_penalty * ctx.scenario.robot.L
    return lambda plan: weighted_cost(plan, factor, penalty)


def _refine(plan: Plan, links, options: DefaultOptions, ctx: PlanningContext) -> Plan:
    """:func:`segplan.planning.refine.refine_with` of ``plan``; of each same-direction run of a
    plan with reverse links (:func:`segplan.planning.lattice.reverse.by_runs`), what was done
    summed up in one :class:`segplan.planning.plan.Refinement`."""
    if not plan.directions:
        return refine_with(plan, links, options.refine, deadline=ctx.deadline)
    done: list[Refinement] = []

    def step(part: Plan) -> Plan:
        out = refine_with(part, links, options.refine, deadline=ctx.deadline)
        done.append(out.refinement)
        return out

    out = by_runs(plan, step)
    factor = options.lattice.reverse_factor
    out, cusp_moves = polish_cusps(out, links, options.refine, factor, deadline=ctx.deadline)
    total = {
        f.name: sum(getattr(r, f.name) for r in done)
        for f in dataclasses.fields(Refinement)
        if f.name in ("shortcuts", "splits", "moves", "updates", "checked", "seconds")
    }
    total["moves"] += cusp_moves
    info = Refinement(
        cost_before=plan.cost,
        cost_after=out.cost,
        nodes_before=len(plan.nodes),
        nodes_after=len(out.nodes),
        stopped=any(r.stopped for r in done),
        **total,
    )
    if not out.cost < plan.cost or not math.isfinite(out.cost):  # keep the search's chain
        out, info = plan, dataclasses.replace(info, cost_after=plan.cost, nodes_after=len(plan.nodes))
    return dataclasses.replace(out, refinement=info, seconds=plan.seconds + info.seconds)


def _named_limits(exc: NoPathError, ctx: PlanningContext, options: DefaultOptions) -> NoPathError:
    """The lattice's failure; a time-out names the call's ``time_limit``, not the share the
    lattice had left, and keeps what the lattice said about the floor (its ``note``: a goal
    that looks like the way out of a dead end, :func:`segplan.planning.lattice.dead_end.goal_way_out`)."""
    if exc.reason != "time":
        return exc
    s, g = ctx.scenario.start, ctx.scenario.goal
    note = getattr(exc, "note", None)
    message = (
        f"no path from {show_pose(s)} to {show_pose(g)}: the time limit time_limit={options.time_limit:g} s "
        f"was reached (the paper's search, then the lattice)" + (f"; {note}" if note else "")
        + f"; expanded {exc.expanded} states"
    )  # fmt: skip
    return NoPathError(message, "time", exc.expanded, exc.generated, exc.seconds, exc.best)
