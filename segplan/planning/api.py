"""Planning, the library's entry points: :func:`plan` and :func:`plan_scenario`.

A call goes through three steps:

1. **The door.** The keyword arguments are checked once and become one options object
   (:mod:`segplan.planning.options`): :class:`PaperOptions` for the paper's search
   (``planner="paper"``), :class:`DefaultOptions` for the default planner; a bad value
   raises a ``ValueError`` naming it.
2. **The context.** The off-line work is done (``d_s``, the fitted coefficients of the
   heuristic frame and of formula [2], once per process; not counted in ``Plan.seconds``),
   then one :class:`segplan.planning.context.PlanningContext` is made: the scenario, its
   one validity checker, the deadline of ``time_limit``.
3. **The planner.** The paper's search (:func:`segplan.planning.stages.paper_search`, as
   section "Results. Graph-search" of Campoy et al. (1989) puts its parts together),
   refined if asked, or the default pipeline (:func:`segplan.planning.default.default_pipeline`:
   the paper's search, the lattice, the refinement). The plan returned records its
   planner and options, and its ``seconds`` is measured here, once, from the context's start.

The returned ``Plan.cost`` is always the exact LONGD [1] of the plan found (Romberg),
so the paper's two searches (``cost="longd"`` and the baseline ``cost="distance"``)
compare fairly.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import types

from ..floor.scenario import Robot, Scenario, make_scenario, with_clearance
from .context import PlanningContext
from .default import default_pipeline
from .lattice.search import lattice_options
from .options import DefaultOptions, LatticeOptions, PaperOptions, check_choice, refine_options
from .plan import NoPathError, Plan, check_limits
from .refine import refine_with
from .stages import paper_offline, paper_search

__all__ = [
    "LATTICE_AFTER_PAPER",
    "LATTICE_REFINE",
    "NEAR_LOWER_BOUND",
    "PAPER_EXPANSIONS",
    "PAPER_SHARE",
    "PLANNERS",
    "plan",
    "plan_scenario",
    "plan_scenario_observed",
    "options_of",
    "planner_options",
]


# -- planning --------------------------------------------------------------------------
def plan(
    start,
    goal,
    obstacles,
    L: float,
    bounds=None,
    half_width: float = 0.0,
    max_steer: float = math.radians(45.0),
    heuristic: str = "a",
    *,
    front_overhang: float = 0.0,
    rear_overhang: float = 0.0,
    rectangle: bool = False,
    reverse: bool = False,
    **options,
) -> Plan:
    """Plan a path of the segment robot from ``start`` to ``goal`` (forward only, as the
    paper's AGV, unless ``reverse``).

    Makes the scenario (:func:`segplan.make_scenario`) and plans on it with
    :func:`plan_scenario`: ``heuristic`` and the keyword ``options`` are that function's,
    and so are the :class:`Plan` returned and the errors raised (:class:`NoPathError`;
    ``ValueError`` naming the argument). Making the scenario adds its own: a malformed
    polygon, or a start or goal in collision or out of bounds, raises
    ``segplan.ScenarioError`` (a ``ValueError``).

    Parameters
    ----------
    start, goal : (x, y, theta)
        Poses: rear-axle point A and heading (radians).
    obstacles : sequence of (k, 2) arrays or shapely polygons, or a Floor
        Simple polygons (either orientation; shapely ``Polygon`` / ``MultiPolygon``
        objects too, without holes); a non-convex one is split into convex pieces
        (:func:`segplan.floor.decompose.convex_pieces`, beyond the paper); enlarged by
        ``half_width`` off-line. Or a :class:`segplan.Floor` (a map:
        :func:`segplan.load_ros_map`, :meth:`segplan.Floor.from_occupancy`), whose bounds
        are used when ``bounds`` is None.
    L : float
        Robot length A->B (> 0).
    bounds : (xmin, ymin, xmax, ymax), optional
        Walls; the whole swept segment stays strictly inside them shrunk by ``half_width``.
    half_width : float
        Half-width of the robot (>= 0).
    max_steer : float
        Steering limit (radians, in ``(0, pi/2)``): rear-path curvature at most
        ``tan(max_steer) / L`` on every union.
    front_overhang, rear_overhang, rectangle
        The robot's body beyond the segment (beyond the paper, :class:`segplan.Robot`): its
        reach ahead of B and behind A (>= 0, m), and a rectangle instead of round ends.
    reverse : bool
        May the robot drive backwards (beyond the paper, :class:`segplan.Robot`; the default
        planner only)? The plan's :attr:`Plan.directions` and :attr:`Plan.cusps` say where.
    heuristic, **options
        See :func:`plan_scenario`.
    """
    robot = Robot(L, half_width, max_steer, front_overhang, rear_overhang, rectangle, reverse)
    scenario = make_scenario(robot, start, goal, obstacles, bounds, source="plan()")
    return plan_scenario(scenario, heuristic=heuristic, **options)


#: ``planner`` of :func:`plan_scenario`: the lattice planner (beyond the paper, the default)
#: or the paper's search.
PLANNERS = ("lattice", "paper")
#: The default planner's values (:class:`DefaultOptions`, where each is documented with
#: the measurement that set it), under their former names.
PAPER_SHARE = DefaultOptions.paper_share
PAPER_EXPANSIONS = DefaultOptions.paper.max_expansions
LATTICE_AFTER_PAPER = DefaultOptions.lattice_after_paper
NEAR_LOWER_BOUND = DefaultOptions.near_lower_bound
LATTICE_REFINE = types.MappingProxyType({"max_sweeps": DefaultOptions.refine.max_sweeps})


def plan_scenario(
    scenario: Scenario,
    heuristic: str = "a",
    *,
    planner: str = "lattice",
    refine: bool | dict | None = None,
    clearance: float = 0.0,
    cost: str = "longd",
    version: str = "b",
    ds: float | None = None,
    alpha_method: str = "heuristic",
    max_expansions: int | None = None,
    time_limit: float = 10.0,
    max_turn_chain: int = 4,
    expander: dict | None = None,
    lattice: dict | None = None,
    options: PaperOptions | DefaultOptions | None = None,
    progress=None,
) -> Plan:
    """Plan on a validated :class:`segplan.Scenario` (see :func:`plan`).

    Parameters
    ----------
    scenario : Scenario
        From :func:`segplan.load_scenario`, :func:`segplan.make_scenario` or
        :func:`segplan.random_world`.
    heuristic : {"a", "b", "c"}
        ``h'`` of the paper's search: (a) LONGD of the direct union, (b) distance, (c)
        their weighted average.
    planner : {"lattice", "paper"}
        ``"lattice"`` (default, beyond the paper): the paper's search first, within a
        share of ``time_limit`` and a few expansions, then the A* over a lattice of
        cubic-union primitives (:func:`segplan.planning.lattice.search.lattice_search`; a
        few hundred expansions when the paper's search found a plan, none if that plan is
        near a lower bound, else up to ``max_expansions`` and the rest of ``time_limit``);
        the shorter plan found is refined (:mod:`segplan.planning.default`; every value in
        :class:`segplan.planning.options.DefaultOptions`). ``"paper"``: the paper's search
        alone, exactly as the paper describes it (the book's reproduction chapters call it
        so; :class:`segplan.planning.options.PaperOptions`).
    refine : bool or dict, optional
        Beyond the paper: refine the plan found (:func:`segplan.refine`: shortcuts,
        splits, local moves of the nodes), with default options (True; for the lattice
        planner ``DefaultOptions().refine``, applied to each plan found) or these keyword arguments
        (a dict, :class:`segplan.planning.options.RefineOptions`' fields). ``Plan.seconds``
        then counts search and refinement, and ``time_limit`` bounds both: past it the
        refinement starts no new work (``Plan.refinement.stopped``). Default: True for the
        lattice planner, False for the paper's search.
    clearance : float
        Safety margin (m, >= 0) beyond ``half_width``: the search and the refinement plan
        around obstacles enlarged by ``half_width + clearance`` and walls moved in as
        much (0: the paper's model). The start and goal must be that far from them.
    cost : {"longd", "distance"}
        Link cost of the paper's search: LONGD (the method) or the distance between node
        points (the paper's baseline).
    version : {"b", "a"}
        Reference systems of intermediate nodes (Fig. 4), see
        :class:`segplan.planning.paper.expansion.Expander`.
    ds : float, optional
        Characteristic dimension of the surroundings for heuristic (c); default
        :func:`segplan.planning.paper.problem.characteristic_dimension` of the enlarged obstacles.
    alpha_method : {"heuristic", "exact"}
        Optimal reference system method (section "Optimal reference system"). "exact" is
        honoured by the paper's search (``planner="paper"``) and refused by the default
        planner (its lattice primitives are built in the heuristic frame).
    max_expansions : int, optional
        Expansions before giving up (NoPathError, ``reason="expansions"``); default 3000
        for the paper's search, 200000 for the lattice.
    time_limit : float
        Seconds before giving up (NoPathError, ``reason="time"``), counted from the start
        of the call (after its off-line work); the refinement stops at it too.
    max_turn_chain : int
        Longest chain of consecutive turn states of the paper's search (difficult cases):
        four quarter turns make a full circle.
    expander : dict, optional
        Further keyword arguments of :class:`segplan.planning.paper.expansion.Expander`
        (``max_iterations``, ``r0``, ...).
    lattice : dict, optional
        Further keyword arguments of :func:`segplan.planning.lattice.search.lattice_search`
        (``resolution``, ``weight``, ``retry``, ...).
    options : PaperOptions or DefaultOptions, optional
        Every option as one checked object instead of the keyword arguments above (which
        must then keep their defaults; ValueError naming any that does not): a
        :class:`segplan.PaperOptions` runs the paper's search, a
        :class:`segplan.DefaultOptions` the default planner. ``plan_scenario(scenario,
        options=p.options)`` plans again as plan ``p`` was planned.
    progress : callable, optional
        Called with a :class:`segplan.planning.context.Progress` (stage, event, seconds,
        expansions, cost) when a stage starts and ends and, in the lattice search, every 64
        expansions: for long calls (large floors), e.g. to show a bar. It only watches (the
        plan does not depend on it); an exception it raises ends the call.

    Returns
    -------
    Plan
        With ``planner`` and ``options`` (the checked options object) recorded.

    Raises
    ------
    ValueError
        Bad input, naming the argument.
    NoPathError
        No plan within the limits; ``reason="exhausted"`` from the lattice means no path
        exists at the resolutions it names. Carries what was explored (``best``).
    """
    scenario, options = planner_options(
        scenario,
        heuristic,
        planner=planner,
        refine=refine,
        clearance=clearance,
        cost=cost,
        version=version,
        ds=ds,
        alpha_method=alpha_method,
        max_expansions=max_expansions,
        time_limit=time_limit,
        max_turn_chain=max_turn_chain,
        expander=expander,
        lattice=lattice,
        options=options,
    )
    return _run(scenario, options, progress=progress)


def planner_options(
    scenario: Scenario, heuristic: str = "a", **options
) -> tuple[Scenario, PaperOptions | DefaultOptions]:
    """The door of :func:`plan_scenario`: its arguments checked once (ValueError naming a
    bad one), as the scenario to plan on (with ``clearance`` applied) and the options object
    of the planner (:func:`options_of`, whose keyword arguments ``options`` are, then the
    checks that need the scenario)."""
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    return _apply(scenario, options_of(heuristic, **options))


def options_of(
    heuristic: str = "a",
    *,
    planner: str = "lattice",
    refine: bool | dict | None = None,
    clearance: float = 0.0,
    cost: str = "longd",
    version: str = "b",
    ds: float | None = None,
    alpha_method: str = "heuristic",
    max_expansions: int | None = None,
    time_limit: float = 10.0,
    max_turn_chain: int = 4,
    expander: dict | None = None,
    lattice: dict | None = None,
    options: PaperOptions | DefaultOptions | None = None,
) -> PaperOptions | DefaultOptions:
    """:func:`plan_scenario`'s keyword arguments (without the scenario) checked once, as the
    options object of the planner: :class:`PaperOptions` or :class:`DefaultOptions`
    (``options`` itself where given, the other arguments then at their defaults); ValueError
    naming a bad one."""
    if options is not None:
        if not isinstance(options, PaperOptions | DefaultOptions):
            raise ValueError(
                "options must be a segplan.PaperOptions or segplan.DefaultOptions, "
                f"got {type(options).__name__}"
            )
        given = dict(
            heuristic=heuristic,
            planner=planner,
            refine=refine,
            clearance=clearance,
            cost=cost,
            version=version,
            ds=ds,
            alpha_method=alpha_method,
            max_expansions=max_expansions,
            time_limit=time_limit,
            max_turn_chain=max_turn_chain,
            expander=expander,
            lattice=lattice,
        )
        defaults = inspect.signature(options_of).parameters
        clash = [name for name, value in given.items() if value != defaults[name].default]
        if clash:
            raise ValueError(f"give either options or {', '.join(clash)}, not both")
        return options
    check_choice(planner, PLANNERS, "planner")
    max_expansions, time_limit = check_limits(max_expansions, time_limit)
    default = planner == "lattice"
    search = dict(
        heuristic=heuristic,
        cost=cost,
        version=version,
        ds=ds,
        alpha_method=alpha_method,
        max_turn_chain=max_turn_chain,
        expander=expander or {},
    )
    if not default:
        options = PaperOptions(
            **search,
            max_expansions=PaperOptions.max_expansions if max_expansions is None else max_expansions,
            time_limit=time_limit,
            refine=refine_options(refine, None),
            clearance=clearance,
        )
    else:
        cap = DefaultOptions.paper.max_expansions
        lattice = dict(lattice or {})
        for name in ("max_expansions", "time_limit"):
            if name in lattice:
                raise ValueError(f"lattice may not set {name}: it is an argument of its own")
        names = {f.name for f in dataclasses.fields(LatticeOptions)} - {"max_expansions"}
        for name in lattice:
            if name not in names:
                raise ValueError(f"lattice has no option {name!r} (its options: {', '.join(sorted(names))})")
        options = DefaultOptions(
            paper=PaperOptions(**search, max_expansions=min(cap, max_expansions or cap)),
            lattice=LatticeOptions(
                **lattice,
                max_expansions=LatticeOptions.max_expansions if max_expansions is None else max_expansions,
            ),
            refine=refine_options(refine, DefaultOptions.refine),
            time_limit=time_limit,
            clearance=clearance,
        )
    return options


Options = PaperOptions | DefaultOptions


def _apply(scenario: Scenario, options: Options) -> tuple[Scenario, Options]:
    """``scenario`` with ``options.clearance`` applied, and ``options``, after the checks that
    need the scenario (the lattice's resolution <= L, even where the lattice is not run)."""
    if options.clearance > 0:
        scenario = with_clearance(scenario, options.clearance)
    if isinstance(options, DefaultOptions):
        lattice_options(scenario, schedule=options.lattice.schedule, **options.lattice.search_options())
    return scenario, options


def _run(
    scenario: Scenario, options: PaperOptions | DefaultOptions, observer=None, workspace=None, progress=None
) -> Plan:
    """Plan with checked ``options`` on ``scenario`` (the module docstring's steps 2 and 3);
    ``workspace``: the scenario's validity checker if one is kept (:class:`segplan.Planner`);
    ``progress``: the call's callback (:class:`segplan.planning.context.Progress`)."""
    if progress is not None and not callable(progress):
        raise ValueError(f"progress must be callable (it is given a segplan Progress), got {progress!r}")
    # the off-line work, before the clock starts
    paper_offline(scenario, options if isinstance(options, PaperOptions) else options.paper)
    ctx = PlanningContext(scenario, options.time_limit, options, workspace, progress)
    try:
        if isinstance(options, PaperOptions):
            found, links = paper_search(ctx, options, observer)
            if options.refine is not None:
                ctx.report("refine", "start")
                found = refine_with(found, links, options.refine, deadline=ctx.deadline)
                ctx.report("refine", "done", cost=found.cost)
        else:
            found = default_pipeline(ctx, options)
    except NoPathError as exc:
        exc.seconds = ctx.deadline.elapsed()
        raise
    planner = "paper" if isinstance(options, PaperOptions) else "lattice"
    cut = ctx.counters["stopped_by_time"] or (found.refinement is not None and found.refinement.stopped)
    return dataclasses.replace(
        found,
        seconds=ctx.deadline.elapsed(),
        planner=planner,
        options=options,
        stopped="time" if cut else None,
    )


def plan_scenario_observed(scenario: Scenario, observer, heuristic: str = "a", **options) -> Plan:
    """The paper's search (``planner="paper"``) with an observer of the link costs (for studies).

    ``observer(union, cost)`` is called on every link cost the search asks for (``g`` of
    its links and ``h'`` (a) alike; see :class:`segplan.planning.links.LinkModel`). The plan is the
    same as :func:`plan_scenario`'s: the observer only watches. ``options``: those of
    :func:`plan_scenario` (``planner`` is ``"paper"``).
    """
    if not callable(observer):
        raise ValueError(f"observer must be callable, got {observer!r}")
    scenario, checked = planner_options(scenario, heuristic, planner="paper", **options)
    return _run(scenario, checked, observer)
