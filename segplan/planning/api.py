"""Planning, the library's entry points: :func:`plan` and :func:`plan_scenario`.

Puts the parts together, as section "Results. Graph-search" of Campoy et al. (1989)
does: the validity checker of the enlarged floor (:class:`segplan.planning.validity.Workspace`),
the link model (:class:`segplan.planning.links.LinkModel`: unions in the optimal reference system
and their LONGD), the paper's graph expansion (:class:`segplan.planning.paper.expansion.Expander`), the
problem with its objective (:class:`segplan.planning.paper.problem.Problem`: ``g`` and ``h'`` a/b/c)
and the A* search (:func:`segplan.planning.paper.search.astar`); optionally the refinement beyond the
paper (:func:`segplan.refine`).

The returned ``Plan.cost`` is always the exact LONGD [1] of the plan found (Romberg),
so the paper's two searches (``cost="longd"`` and the baseline ``cost="distance"``)
compare fairly. The time of off-line work (``d_s``, the fitted coefficients of the
heuristic frame and of formula [2], once per process) is not counted in
``Plan.seconds``.
"""

from __future__ import annotations

import dataclasses
import math
import time
import types
import weakref

from ..floor.scenario import Robot, Scenario, make_scenario, with_clearance
from ..model.cost import checked_intrinsic, longd_exact_intrinsic
from ..model.frame import heuristic_coefficients
from .dubins import dubins_length_scalar
from .lattice.search import LATTICE_MAX_EXPANSIONS, lattice_options, lattice_search
from .links import LinkModel
from .paper.expansion import Expander
from .paper.problem import COSTS, HEURISTICS, Problem, characteristic_dimension
from .paper.search import astar
from .plan import PLAN_RTOL, NoPathError, Plan, check_limits, check_option
from .refine import refine_with
from .validity import Workspace

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
]


_DS_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _scenario_ds(scenario: Scenario) -> float:
    """:func:`characteristic_dimension` of a scenario, computed once (the paper's off-line step)."""
    ds = _DS_CACHE.get(scenario)
    if ds is None:
        ds = characteristic_dimension(
            scenario.enlarged, scenario.free_bounds, fallback=scenario.robot.L, groups=scenario.outline_of
        )
        _DS_CACHE[scenario] = ds
    return ds


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
    **options,
) -> Plan:
    """Plan a forward-only path of the segment robot from ``start`` to ``goal``.

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
    obstacles : sequence of (k, 2) arrays or shapely polygons
        Simple polygons (either orientation; shapely ``Polygon`` / ``MultiPolygon``
        objects too, without holes); a non-convex one is split into convex pieces
        (:func:`segplan.floor.decompose.convex_pieces`, beyond the paper); enlarged by
        ``half_width`` off-line.
    L : float
        Robot length A->B (> 0).
    bounds : (xmin, ymin, xmax, ymax), optional
        Walls; the whole swept segment stays strictly inside them shrunk by ``half_width``.
    half_width : float
        Half-width of the robot (>= 0).
    max_steer : float
        Steering limit (radians, in ``(0, pi/2)``): rear-path curvature at most
        ``tan(max_steer) / L`` on every union.
    heuristic, **options
        See :func:`plan_scenario`.
    """
    robot = Robot(L, half_width, max_steer)
    scenario = make_scenario(robot, start, goal, obstacles, bounds, source="plan()")
    return plan_scenario(scenario, heuristic=heuristic, **options)


def _check_choice(value, choices, name):
    if value not in choices:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, choices))}, got {value!r}")
    return value


#: ``planner`` of :func:`plan_scenario`: the lattice planner (beyond the paper, the default)
#: or the paper's search.
PLANNERS = ("lattice", "paper")
#: Share of ``time_limit`` the default planner gives the paper's search before the lattice.
PAPER_SHARE = 0.2
#: Most expansions of the paper's search inside the default planner (the lattice follows).
#: On the 400 random floors of chapter 9 every plan the paper's search found took at most
#: 34 expansions, while its failures ran up to 141 (up to 0.2 s) before the lattice began;
#: the lattice finds the plans such a longer search would. 40 instead of 64: the same plans
#: on those floors, my 100 tight floors and 80 varied robots, and 3 % less time (ABBA).
PAPER_EXPANSIONS = 40
#: Expansions the lattice may spend looking for a shorter plan once the paper's search has
#: found one (a count, not a time share: the plan returned does not depend on the machine).
#: 2000 before the coarse cost-to-go guided the lattice; on the 400 random floors of
#: chapter 9, 400 gives the same lengths in less time.
LATTICE_AFTER_PAPER = 400
#: The default planner skips the lattice when the paper's plan costs at most this factor
#: times a lower bound of any plan's LONGD (the Dubins length of the rear point,
#: :func:`segplan.planning.dubins.dubins_length`). Measured on the 400 random floors of chapter 9
#: (refined plans against BIT*): raising it from 1.05 to 1.3 left the median and the
#: largest length ratio as they were and took a quarter off the median plan time; the
#: refinement wins back what the lattice would have.
NEAR_LOWER_BOUND = 1.3
#: The default planner's refinement (:func:`segplan.refine` options): at most 3 sweeps of
#: local moves per round instead of 6. Measured on the 400 random floors of chapter 9: the
#: median plan time 63 -> 43 ms (the local moves were most of it), the median length ratio
#: to BIT* 0.979 -> 0.982, the largest 1.140 -> 1.141.
LATTICE_REFINE = types.MappingProxyType({"max_sweeps": 3})


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
        ``"lattice"`` (default, beyond the paper): the paper's search first, within
        :data:`PAPER_SHARE` of ``time_limit`` and :data:`PAPER_EXPANSIONS` expansions,
        then the A* over a lattice of cubic-union primitives
        (:func:`segplan.planning.lattice.search.lattice_search`; at most :data:`LATTICE_AFTER_PAPER`
        expansions when the paper's search found a plan, none if that plan is within
        :data:`NEAR_LOWER_BOUND` of a lower bound, else up to ``max_expansions`` and the
        rest of ``time_limit``); the shorter plan found is
        refined. ``"paper"``: the paper's search alone, exactly as the paper describes it
        (the book's reproduction chapters call it so).
    refine : bool or dict, optional
        Beyond the paper: refine the plan found (:func:`segplan.refine`: shortcuts,
        splits, local moves of the nodes), with default options (True; for the lattice
        planner :data:`LATTICE_REFINE`) or these keyword arguments (a dict). ``Plan.seconds``
        then counts search and refinement. Default: True for the lattice planner, False for
        the paper's search.
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
        Optimal reference system method (section "Optimal reference system").
    max_expansions : int, optional
        Expansions before giving up (NoPathError, ``reason="expansions"``); default 3000
        for the paper's search, 200000 for the lattice.
    time_limit : float
        Seconds before giving up (NoPathError, ``reason="time"``).
    max_turn_chain : int
        Longest chain of consecutive turn states of the paper's search (difficult cases):
        four quarter turns make a full circle.
    expander : dict, optional
        Further keyword arguments of :class:`segplan.planning.paper.expansion.Expander`
        (``max_iterations``, ``r0``, ...).
    lattice : dict, optional
        Further keyword arguments of :func:`segplan.planning.lattice.search.lattice_search`
        (``resolution``, ``weight``, ``retry``, ...).

    Returns
    -------
    Plan

    Raises
    ------
    ValueError
        Bad input, naming the argument.
    NoPathError
        No plan within the limits; ``reason="exhausted"`` from the lattice means no path
        exists at the resolutions it names. Carries what was explored (``best``).
    """
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    _check_choice(planner, PLANNERS, "planner")
    _check_choice(heuristic, HEURISTICS, "heuristic")
    _check_choice(cost, COSTS, "cost")
    if refine is None:
        refine = planner == "lattice"
    if not (isinstance(refine, bool) or isinstance(refine, dict)):
        raise ValueError(f"refine must be True, False or a dict of refine() options, got {refine!r}")
    clearance = check_option(clearance, "clearance (m)", 0.0, lo_ok=True)
    max_expansions, time_limit = check_limits(max_expansions, time_limit)
    if clearance > 0:
        scenario = with_clearance(scenario, clearance)
    paper_options = dict(
        cost=cost,
        version=version,
        ds=ds,
        alpha_method=alpha_method,
        max_turn_chain=max_turn_chain,
        expander=expander,
    )
    if planner == "paper":
        return _plan(
            scenario,
            heuristic,
            max_expansions=3000 if max_expansions is None else max_expansions,
            time_limit=time_limit,
            refine=refine,
            **paper_options,
        )
    lattice_options(scenario, **(lattice or {}))  # checked even where the lattice is not run
    t_start = time.perf_counter()
    # the paper's search first (fast where it succeeds), then the lattice; the shorter
    # plan found is refined
    paper = paper_links = None
    # one validity checker of the floor for both searches (built once: on a large floor
    # its set-up is a large share of the planning time)
    robot = scenario.robot
    ws = Workspace(scenario.enlarged, robot.L, scenario.free_bounds, robot.max_curvature)
    try:
        paper, paper_links = _plan(
            scenario,
            heuristic,
            max_expansions=min(PAPER_EXPANSIONS, max_expansions or PAPER_EXPANSIONS),
            time_limit=PAPER_SHARE * float(time_limit),
            refine=False,
            with_links=True,
            workspace=ws,
            **paper_options,
        )
    except NoPathError:
        pass
    left = float(time_limit) - (time.perf_counter() - t_start)
    lattice_expansions = LATTICE_MAX_EXPANSIONS if max_expansions is None else max_expansions
    if paper is not None:
        # a plan exists: the lattice looks for a shorter one within a bounded number of
        # expansions (not a wall-clock share, so the answer does not depend on the machine),
        # unless the plan is already within NEAR_LOWER_BOUND of a lower bound
        lattice_expansions = min(lattice_expansions, LATTICE_AFTER_PAPER)
        s, g = scenario.start, scenario.goal
        bound = dubins_length_scalar(s.x, s.y, s.theta, g.x, g.y, g.theta, scenario.robot.min_turning_radius)
        if paper.cost <= NEAR_LOWER_BOUND * bound:
            lattice_expansions = 0
    found, links = paper, paper_links  # a plan off the lattice (or beyond the lattice's limits)
    if lattice_expansions > 0:
        try:
            found, links = lattice_search(
                scenario,
                max_expansions=lattice_expansions,
                time_limit=max(left, 1e-3),
                workspace=ws,
                **(lattice or {}),
            )
        except NoPathError:
            if paper is None:
                raise
    if paper is not None and paper.cost < found.cost:
        found, links = paper, paper_links
    found = dataclasses.replace(found, seconds=time.perf_counter() - t_start)
    if refine is False:
        return found
    # the refinement reuses the link model (validity checker, unions and costs) of the
    # search whose plan it refines
    return refine_with(found, links, **(LATTICE_REFINE if refine is True else refine))


def plan_scenario_observed(scenario: Scenario, observer, heuristic: str = "a", **options) -> Plan:
    """The paper's search (``planner="paper"``) with an observer of the link costs (for studies).

    ``observer(union, cost)`` is called on every link cost the search asks for (``g`` of
    its links and ``h'`` (a) alike; see :class:`segplan.planning.links.LinkModel`). The plan is the
    same as :func:`plan_scenario`'s: the observer only watches.
    """
    if not callable(observer):
        raise ValueError(f"observer must be callable, got {observer!r}")
    return _plan(scenario, heuristic, observer=observer, **options)


def _plan(
    scenario,
    heuristic,
    *,
    cost="longd",
    version="b",
    ds=None,
    alpha_method="heuristic",
    max_expansions=3000,
    time_limit=10.0,
    max_turn_chain=4,
    expander=None,
    refine=False,
    observer=None,
    with_links=False,
    workspace=None,
) -> Plan | tuple[Plan, LinkModel]:
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    _check_choice(heuristic, HEURISTICS, "heuristic")
    _check_choice(cost, COSTS, "cost")
    if not (isinstance(refine, bool) or isinstance(refine, dict)):
        raise ValueError(f"refine must be True, False or a dict of refine() options, got {refine!r}")
    max_expansions, time_limit = check_limits(max_expansions, time_limit)
    if max_expansions is None:
        max_expansions = 3000
    check_option(max_turn_chain, "max_turn_chain", 0, integer=True, lo_ok=True)
    robot = scenario.robot
    L = robot.L
    # off-line work, outside the planning time (the paper: "the processing of the model of
    # the surroundings ... is performed off-line"): d_s, and the fitted coefficients of the
    # heuristic reference system and of formula [2] (each computed once per process)
    if heuristic == "c":
        if ds is None:
            ds = _scenario_ds(scenario)
        ds_over_L = check_option(ds, "ds", 0.0, lo_ok=True) / L
    else:
        ds_over_L = 0.0
    if alpha_method == "heuristic":
        heuristic_coefficients()
    t0 = time.perf_counter()
    ws = workspace or Workspace(scenario.enlarged, L, scenario.free_bounds, robot.max_curvature)
    options = dict(expander or {})
    links = LinkModel(ws, alpha_method, options.get("steer_fallback", True), observer)
    ex = Expander(ws, version=version, alpha_method=alpha_method, links=links, **options)
    problem = Problem(
        scenario.start, scenario.goal, links, heuristic, cost, ds_over_L, robot.min_turning_radius
    )
    goal = problem.goal

    def successors(pose, turns):
        return ex.successors(pose, goal, turns=turns)

    def finish(nodes, unions, kinds, search_cost, expanded, generated):
        # LONGD [1] of each union (Romberg, rtol 1e-8)
        exact = 0.0
        for u in unions:
            geo = checked_intrinsic(u.p0, u.p1, u.alpha, u.L)
            exact += float(longd_exact_intrinsic(*geo, rtol=PLAN_RTOL))
        st = ex.stats
        return Plan(
            nodes=nodes,
            unions=unions,
            cost=exact,
            search_cost=search_cost,
            expanded=expanded,
            generated=generated,
            seconds=time.perf_counter() - t0,
            heuristic=heuristic,
            cost_kind=cost,
            version=ex.version,
            collision_checks=st.collision_checks,
            exact_checks=st.exact_checks,
            iterations=tuple(it for it, ok, _ in st.iterations if ok),
            kinds=kinds,
        )

    found = astar(
        problem,
        successors,
        finish,
        max_expansions=int(max_expansions),
        time_limit=float(time_limit),
        t0=t0,
        max_turn_chain=max_turn_chain,
    )
    if with_links:  # the default planner's use: the plan and its link model, unrefined
        return found, links
    if refine is False:
        return found
    return refine_with(found, links, **({} if refine is True else refine))
