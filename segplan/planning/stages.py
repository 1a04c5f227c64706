"""The two searches as stages of a planning call: each takes the call's context and its options.

:func:`paper_search` puts the paper's pieces together, as section "Results. Graph-search"
of Campoy et al. (1989) does: the validity checker of the enlarged floor (the context's
:class:`segplan.planning.validity.Workspace`), the link model
(:class:`segplan.planning.links.LinkModel`: unions in the optimal reference system and their
LONGD), the graph expansion (:class:`segplan.planning.paper.expansion.Expander`), the problem
with its objective (:class:`segplan.planning.paper.problem.Problem`: ``g`` and ``h'`` a/b/c)
and the A* search (:func:`segplan.planning.paper.search.astar`). :func:`lattice_stage` runs
the lattice (:func:`segplan.planning.lattice.search.lattice_search`) on the context's
workspace until the context's deadline.

Each returns the plan found and the link model that made it (the refinement reuses its
caches), or raises :class:`segplan.NoPathError`. The returned ``Plan.cost`` is always the
exact LONGD [1] of the plan (Romberg), so the paper's two searches (``cost="longd"`` and the
baseline ``cost="distance"``) compare fairly.
"""

from __future__ import annotations

import time

from ..floor.scenario import Scenario
from ..model.cost import chain_longd
from .context import PlanningContext
from .lattice.search import lattice_search
from .links import LinkModel
from .options import LatticeOptions, PaperOptions
from .paper.expansion import Expander
from .paper.problem import Problem, characteristic_dimension
from .paper.search import astar
from .plan import PLAN_RTOL, NoPathError, Plan

__all__ = ["lattice_stage", "paper_offline", "paper_search"]


def _scenario_ds(scenario: Scenario) -> float:
    """:func:`characteristic_dimension` of a scenario (the paper's off-line step, outside the
    planning time; a few milliseconds on the book's floors, so no cache keeps it)."""
    return characteristic_dimension(
        scenario.enlarged, scenario.free_bounds, fallback=scenario.robot.L, groups=scenario.outline_of
    )


def paper_offline(scenario: Scenario, options: PaperOptions) -> float:
    """The paper's off-line work, outside the planning time: ``d_s / L`` for heuristic (c)
    (0 otherwise). (The fitted coefficients of the heuristic reference system are computed
    once, when :mod:`segplan.model.frame` is imported.) Returns ``d_s / L``."""
    if options.heuristic == "c":
        ds = float(_scenario_ds(scenario)) if options.ds is None else options.ds
        ds_over_L = ds / scenario.robot.L
    else:
        ds_over_L = 0.0
    return ds_over_L


def paper_search(ctx: PlanningContext, options: PaperOptions, observer=None) -> tuple[Plan, LinkModel]:
    """The paper's A* search on the context's floor, within ``options``' limits (its time
    counted from the context's start); ``observer(union, cost)`` watches every link cost
    (:class:`LinkModel`). Returns the plan (unrefined) and its link model."""
    scenario = ctx.scenario
    robot = scenario.robot
    ds_over_L = paper_offline(scenario, options)  # done before the context's clock; cached
    t0 = ctx.deadline.start
    expander = options.expander_options
    links = ctx.link_model(options.alpha_method, expander.get("steer_fallback", True), observer)
    ex = Expander(
        ctx.workspace, version=options.version, alpha_method=options.alpha_method, links=links, **expander
    )
    problem = Problem(
        scenario.start,
        scenario.goal,
        links,
        options.heuristic,
        options.cost,
        ds_over_L,
        robot.min_turning_radius,
    )
    goal = problem.goal

    def successors(pose, turns):
        return ex.successors(pose, goal, turns=turns)

    def finish(nodes, unions, kinds, search_cost, expanded, generated):
        # LONGD [1] of each union (Romberg, rtol 1e-8)
        exact = chain_longd(unions, PLAN_RTOL, from_poses=True)
        st = ex.stats
        return Plan(
            nodes=nodes,
            unions=unions,
            cost=exact,
            search_cost=search_cost,
            expanded=expanded,
            generated=generated,
            seconds=time.perf_counter() - t0,
            heuristic=options.heuristic,
            cost_kind=options.cost,
            version=ex.version,
            collision_checks=st.collision_checks,
            exact_checks=st.exact_checks,
            iterations=tuple(it for it, ok, _ in st.iterations if ok),
            kinds=kinds,
        )

    ctx.report("paper", "start")
    try:
        found = astar(
            problem,
            successors,
            finish,
            max_expansions=options.max_expansions,
            time_limit=options.time_limit,
            t0=t0,
            max_turn_chain=options.max_turn_chain,
        )
    except NoPathError as exc:
        ctx.count("paper", None, exc.expanded)
        ctx.report("paper", "done", exc.expanded)
        raise
    ctx.count("paper", found, found.expanded)
    ctx.report("paper", "done", found.expanded, found.cost)
    return found, links


def lattice_stage(
    ctx: PlanningContext, options: LatticeOptions, max_expansions: int, alternatives: list | None = None
) -> tuple[Plan, LinkModel]:
    """The lattice search on the context's floor and workspace, within ``max_expansions``
    and the context's deadline, with ``options``' schedule; ``alternatives`` as
    :func:`segplan.planning.lattice.search.lattice_search`'s."""
    ctx.report("lattice", "start")
    watch = None if ctx.progress is None else (lambda n: ctx.report("lattice", "expanded", n))
    try:
        found, links = lattice_search(
            ctx.scenario,
            max_expansions=max_expansions,
            time_limit=ctx.deadline.limit,
            t0=ctx.deadline.start,
            workspace=ctx.workspace,
            schedule=options.schedule,
            progress=watch,
            alternatives=alternatives,
            **options.search_options(),
        )
    except NoPathError as exc:
        ctx.count("lattice", None, exc.expanded)
        ctx.report("lattice", "done", exc.expanded)
        raise
    ctx.count("lattice", found, found.expanded)
    ctx.report("lattice", "done", found.expanded, found.cost)
    return found, links
