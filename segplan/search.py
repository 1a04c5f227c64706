"""The A*-type search on the graph built on-line (section "Results. Graph-search").

:func:`plan` and :func:`plan_scenario` run, by default, the resolution-complete lattice
planner (:mod:`segplan.lattice`, beyond the paper) and refine its plan; the paper's search
described below is ``planner="paper"``, exactly as before.

"The evaluation function is defined as the estimation of the cost of an optimal path
conditioned to passing by a given node ... f = g + h'", with ``g`` the cost (LONGD, the
front-wheel path length, formula [1]/[2]) of the path found so far and ``h'`` an
estimate of the remaining cost. The paper's choices for ``h'``:

(a) "The same function as for g": LONGD of the direct union node->goal in its optimal
    reference system. Not admissible, great "heuristic power".
(b) "Distance between points": admissible (the front wheel's path is at least as long
    as the rear point's, which is at least the chord), weak.
(c) "A weighted average between them, depending on the parameters p ('depth' of the
    node in the graph) and d_s/L, where d_s is a characteristic dimension of the
    surroundings": deep nodes use (a), shallow nodes (b).

Our reconstruction of (c): ``h' = w h_a + (1 - w) h_b`` with ``w = p / (p + d_s / L)``.
A node of depth ``p = d_s / L`` weighs both equally: in cramped surroundings (``d_s``
about ``L``) the robot's size is felt at once and (a) dominates from the first level; in
open ones (``d_s >> L``) distance dominates for longer. By default ``d_s`` is the median,
over the obstacles, of the gap between an enlarged obstacle and its nearest neighbour
(another obstacle or a wall): the typical width of a corridor
(:func:`characteristic_dimension`).

Where the direct union does not exist (no feasible alpha), ``h_a`` falls back to
``d + R (|phi0| + |phi1|)``, the chord plus the arcs of minimum radius ``R`` that turn
the robot onto and off the chord.

The paper's comparison baseline (Figs. 5, 6: "a search algorithm where the cost function
is based upon the distance between points") is ``cost="distance"``: the link cost is the
chord length and every ``h'`` choice becomes the distance. The returned ``Plan.cost`` is
always the exact LONGD [1] of the plan found, so both searches compare fairly.

Search details (ours): the successors of a node come from
:meth:`segplan.expansion.Expander.successors`; nodes that are equivalent for the search
(the same obstacle vertex passed on the same side with a similar heading, or turn states
in the same cell of a ``L/4`` and 22.5 deg grid) share a key, and a key is expanded once
(the closed set). Chains of consecutive turn states are limited (``max_turn_chain``), and
the search stops after ``max_expansions`` expansions or ``time_limit`` seconds with
:class:`NoPathError`, which carries what was explored; so does an exhausted graph (an
enclosed goal). The time of off-line work (``d_s``, the fitted coefficients of the
heuristic frame and of formula [2], once per process) is not counted in
``Plan.seconds``.
"""

from __future__ import annotations

import dataclasses
import heapq
import math
import time
import weakref
from dataclasses import dataclass

import numpy as np

from .calibration import calibration
from .cost import checked_intrinsic, longd_exact_intrinsic
from .expansion import Expander, Workspace
from .frame import heuristic_coefficients
from .pose import Pose
from .refine import refine_with
from .union import Union
from .world import Robot, Scenario, make_scenario

HEURISTICS = ("a", "b", "c")
COSTS = ("longd", "distance")
#: ``planner`` of :func:`plan_scenario`: the lattice planner (beyond the paper, the default)
#: or the paper's search.
PLANNERS = ("lattice", "paper")
#: Share of ``time_limit`` given to the paper's search that runs before the lattice planner
#: (``planner="lattice"``); the lattice gets the rest, or this share too when the paper's
#: search has found a plan already.
PAPER_SHARE = 0.2


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
        Wall-clock planning time.
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
        Kind of each node: ``"start"``, ``"vertex"``, ``"turn"``, ``"goal"`` (and
        ``"refined"`` for a node added or moved by :func:`segplan.refine`).
    refinement : segplan.refine.Refinement or None
        What :func:`segplan.refine` changed (None: the search's plan as found).
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
    refinement: object = None

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
        }


# -- d_s -------------------------------------------------------------------------------
def _segment_point_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distances from points ``p`` (n, 2) to segments ``a``-``b`` (m, 2): ``(n, m)``."""
    ab = b - a
    ap = p[:, None, :] - a[None, :, :]
    t = np.clip(np.einsum("nmk,mk->nm", ap, ab) / np.einsum("mk,mk->m", ab, ab), 0.0, 1.0)
    return np.linalg.norm(ap - t[..., None] * ab[None], axis=-1)


def polygon_gap(p: np.ndarray, q: np.ndarray) -> float:
    """Distance between two disjoint convex polygons (0 if they overlap or touch).

    For disjoint convex polygons the distance is attained at a vertex of one of them, so
    it is the least vertex-to-edge distance both ways.
    """
    from .world import polygons_overlap

    if polygons_overlap(p, q):
        return 0.0
    d1 = _segment_point_distance(p, q, np.roll(q, -1, axis=0)).min()
    d2 = _segment_point_distance(q, p, np.roll(p, -1, axis=0)).min()
    return float(min(d1, d2))


def characteristic_dimension(polygons, bounds=None, fallback: float = 1.0) -> float:
    """``d_s`` of heuristic (c): the median gap from each obstacle to its nearest neighbour.

    Neighbours are the other obstacles and the walls (``bounds``). Without obstacles the
    shorter side of the bounds, or ``fallback`` without bounds either. Exact gaps
    (:func:`polygon_gap`) are computed only for pairs whose circumscribed circles are
    nearer than the best gap found so far (the circle gap is a lower bound).
    """
    polys = [np.asarray(p, dtype=float) for p in polygons]
    if not polys:
        if bounds is None:
            return float(fallback)
        return float(min(bounds[2] - bounds[0], bounds[3] - bounds[1]))
    centres = np.array([0.5 * (p.min(axis=0) + p.max(axis=0)) for p in polys])
    radii = np.array([np.max(np.hypot(*(p - c).T)) for p, c in zip(polys, centres, strict=True)])
    circle_gap = np.hypot(*(centres[:, None, :] - centres[None, :, :]).transpose(2, 0, 1))
    circle_gap -= radii[:, None] + radii[None, :]
    gaps = []
    for i, p in enumerate(polys):
        best = math.inf
        if bounds is not None:
            xmin, ymin, xmax, ymax = bounds
            best = min(p[:, 0].min() - xmin, p[:, 1].min() - ymin, xmax - p[:, 0].max(), ymax - p[:, 1].max())
            best = max(best, 0.0)
        for j in np.argsort(circle_gap[i]):
            if j == i:
                continue
            if circle_gap[i, j] >= best:
                break
            best = min(best, polygon_gap(p, polys[j]))
        if math.isfinite(best):
            gaps.append(best)
    return float(np.median(gaps)) if gaps else float(fallback)


_DS_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _scenario_ds(scenario: Scenario) -> float:
    """:func:`characteristic_dimension` of a scenario, computed once (the paper's off-line step)."""
    ds = _DS_CACHE.get(scenario)
    if ds is None:
        ds = characteristic_dimension(scenario.enlarged, scenario.free_bounds, fallback=scenario.robot.L)
        _DS_CACHE[scenario] = ds
    return ds


# -- the search ------------------------------------------------------------------------
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

    Parameters
    ----------
    start, goal : (x, y, theta)
        Poses: rear-axle point A and heading (radians).
    obstacles : sequence of (k, 2) arrays
        Convex polygons (either orientation); enlarged by ``half_width`` off-line.
    L : float
        Robot length A->B (> 0).
    bounds : (xmin, ymin, xmax, ymax), optional
        Walls; the whole swept segment stays strictly inside them shrunk by ``half_width``.
    half_width : float
        Half-width of the robot (>= 0).
    max_steer : float
        Steering limit (radians, in ``(0, pi/2)``): rear-path curvature at most
        ``tan(max_steer) / L`` on every union.
    heuristic : {"a", "b", "c"}
        The paper's ``h'`` (see the module docstring).
    **options
        Passed to :func:`plan_scenario` (``planner``, ``refine``, ``clearance``, ``cost``,
        ``version``, ``ds``, ``alpha_method``, ``max_expansions``, ``time_limit``,
        ``expander``, ``lattice``).

    Returns
    -------
    Plan

    Raises
    ------
    ValueError
        Bad input, naming the argument (``segplan.ScenarioError``, a ValueError, for a
        malformed polygon or a start/goal in collision or out of bounds).
    NoPathError
        No plan within the search limits; carries what was explored.
    """
    robot = Robot(L, half_width, max_steer)
    scenario = make_scenario(robot, start, goal, obstacles, bounds, source="plan()")
    return plan_scenario(scenario, heuristic=heuristic, **options)


def _check_choice(value, choices, name):
    if value not in choices:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, choices))}, got {value!r}")
    return value


def plan_scenario(
    scenario: Scenario,
    heuristic: str = "a",
    *,
    cost: str = "longd",
    version: str = "b",
    ds: float | None = None,
    alpha_method: str = "heuristic",
    max_expansions: int | None = None,
    time_limit: float = 10.0,
    max_turn_chain: int = 4,
    expander: dict | None = None,
    refine: bool | dict | None = None,
    planner: str = "lattice",
    clearance: float = 0.0,
    lattice: dict | None = None,
) -> Plan:
    """Plan on a validated :class:`segplan.Scenario` (see :func:`plan`).

    Parameters
    ----------
    scenario : Scenario
        From :func:`segplan.load_scenario`, :func:`segplan.make_scenario` or
        :func:`segplan.random_world`.
    heuristic : {"a", "b", "c"}
        ``h'``: (a) LONGD of the direct union, (b) distance, (c) their weighted average.
    cost : {"longd", "distance"}
        Link cost: LONGD (the method) or the distance between node points (the paper's
        baseline).
    version : {"b", "a"}
        Reference systems of intermediate nodes (Fig. 4), see :class:`Expander`.
    ds : float, optional
        Characteristic dimension of the surroundings for heuristic (c); default
        :func:`characteristic_dimension` of the enlarged obstacles.
    alpha_method : {"heuristic", "exact"}
        Optimal reference system method (section "Optimal reference system").
    max_expansions : int, optional
        Expansions before giving up (NoPathError, ``reason="expansions"``); default 3000
        for the paper's search, 200000 for the lattice.
    time_limit : float
        Seconds before giving up (NoPathError, ``reason="time"``).
    max_turn_chain : int
        Longest chain of consecutive turn states (difficult cases): four quarter turns
        make a full circle. Bounds the part of the graph built from turn states.
    expander : dict, optional
        Further keyword arguments of :class:`Expander` (``max_iterations``, ``r0``, ...).
    refine : bool or dict, optional
        Beyond the paper: refine the plan found (:func:`segplan.refine`: shortcuts,
        splits, local moves of the nodes), with default options (True) or these
        keyword arguments (a dict). ``Plan.seconds`` then counts search and refinement.
        Default: True for the lattice planner, False for the paper's search.
    planner : {"lattice", "paper"}
        ``"lattice"`` (default, beyond the paper): the resolution-complete A* over a
        lattice of cubic-union primitives (:mod:`segplan.lattice`); ``heuristic``,
        ``cost``, ``version``, ``ds``, ``alpha_method``, ``max_turn_chain`` and
        ``expander`` then do not apply. The paper's search (default options) runs first,
        within :data:`PAPER_SHARE` of ``time_limit``, then the lattice; the shorter plan
        found is refined (the paper's alone if the lattice stops at a limit).
        ``"paper"``: the paper's search (this module).
    clearance : float
        Safety margin (m, >= 0) beyond ``half_width``: the search and the refinement plan
        around obstacles enlarged by ``half_width + clearance`` and walls moved in as
        much (0: the paper's model). The start and goal must be that far from them.
    lattice : dict, optional
        Further keyword arguments of :func:`segplan.lattice.lattice_search`
        (``resolution``, ``weight``, ``retry``, ...).

    Returns
    -------
    Plan
    """
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    _check_choice(heuristic, HEURISTICS, "heuristic")
    _check_choice(cost, COSTS, "cost")
    _check_choice(planner, PLANNERS, "planner")
    _check_choice(version, ("b", "a"), "version")
    _check_choice(alpha_method, ("heuristic", "exact"), "alpha_method")
    if refine is None:
        refine = planner == "lattice"
    if not (isinstance(refine, bool) or isinstance(refine, dict)):
        raise ValueError(f"refine must be True, False or a dict of refine() options, got {refine!r}")
    given_expansions = max_expansions
    if max_expansions is None:
        max_expansions = 3000 if planner == "paper" else 200_000
    if (
        isinstance(clearance, bool)
        or not isinstance(clearance, int | float)
        or not (math.isfinite(clearance) and clearance >= 0)
    ):
        raise ValueError(f"clearance must be a finite number of metres >= 0, got {clearance!r}")
    if clearance > 0:
        scenario = with_clearance(scenario, clearance)
    if isinstance(max_expansions, bool) or int(max_expansions) != max_expansions or max_expansions < 1:
        raise ValueError(f"max_expansions must be an integer >= 1, got {max_expansions!r}")
    if isinstance(max_turn_chain, bool) or int(max_turn_chain) != max_turn_chain or max_turn_chain < 0:
        raise ValueError(f"max_turn_chain must be an integer >= 0, got {max_turn_chain!r}")
    if not (isinstance(time_limit, int | float) and math.isfinite(time_limit) and time_limit > 0):
        raise ValueError(f"time_limit must be a positive number of seconds, got {time_limit!r}")
    if planner == "lattice":
        from .lattice import lattice_search

        t_start = time.perf_counter()
        # the paper's search first (fast where it succeeds), then the lattice; the shorter
        # plan found is refined
        paper = None
        try:
            paper = plan_scenario(
                scenario,
                planner="paper",
                refine=False,
                time_limit=PAPER_SHARE * float(time_limit),
                max_expansions=given_expansions,
            )
        except NoPathError:
            pass
        try:
            found, ex = lattice_search(
                scenario,
                max_expansions=int(max_expansions),
                time_limit=max(
                    min(
                        float(time_limit) - (time.perf_counter() - t_start),
                        math.inf if paper is None else PAPER_SHARE * float(time_limit),
                    ),
                    1e-3,
                ),
                **(lattice or {}),
            )
        except NoPathError:
            if paper is None:
                raise
            found, ex = paper, None  # a plan off the lattice (or beyond the lattice's limits)
        if paper is not None and paper.cost < found.cost:
            found, ex = paper, None
        found = dataclasses.replace(found, seconds=time.perf_counter() - t_start)
        if refine is False:
            return found
        options = {} if refine is True else refine
        if ex is None:  # the paper's plan: a fresh expansion engine (the refinement's own)
            from .refine import refine as refine_plan

            return refine_plan(found, scenario, **options)
        return refine_with(found, ex, **options)
    robot = scenario.robot
    L = robot.L
    # off-line work, outside the planning time (the paper: "the processing of the model of
    # the surroundings ... is performed off-line"): d_s, and the fitted coefficients of the
    # heuristic reference system and of formula [2] (each computed once per process)
    if heuristic == "c":
        if ds is None:
            ds = _scenario_ds(scenario)
        if not (isinstance(ds, int | float) and math.isfinite(ds) and ds >= 0):
            raise ValueError(f"ds must be a finite number >= 0, got {ds!r}")
        ds_over_L = float(ds) / L
    else:
        ds_over_L = 0.0
    if alpha_method == "heuristic":
        heuristic_coefficients()
    calibration()
    t0 = time.perf_counter()
    ws = Workspace(scenario.enlarged, L, scenario.free_bounds, robot.max_curvature)
    ex = Expander(ws, version=version, alpha_method=alpha_method, **(expander or {}))
    search = _Search(ex, scenario.start, scenario.goal, heuristic, cost, ds_over_L, robot, max_turn_chain)
    found = search.run(int(max_expansions), float(time_limit), t0)
    if refine is False:
        return found
    return refine_with(found, ex, **({} if refine is True else refine))


def with_clearance(scenario: Scenario, clearance: float) -> Scenario:
    """The scenario with its robot's ``half_width`` grown by ``clearance`` (m): the safety margin.

    Raises
    ------
    ValueError
        (``segplan.ScenarioError``) If the start or goal is nearer than ``clearance`` to an
        enlarged obstacle or wall.
    """
    from .world import ScenarioError

    robot = scenario.robot
    grown = Robot(robot.L, robot.half_width + float(clearance), robot.max_steer)
    try:
        return make_scenario(
            grown, scenario.start, scenario.goal, scenario.obstacles, scenario.bounds,
            name=scenario.name, description=scenario.description, path=scenario.path,
            source=f"clearance={clearance:g}",
        )  # fmt: skip
    except ScenarioError as exc:
        raise ScenarioError(f"{exc} (clearance {clearance:g} m beyond half_width)") from None


class _Search:
    """A* bookkeeping: parallel lists indexed by node id."""

    def __init__(
        self,
        ex: Expander,
        start: Pose,
        goal: Pose,
        heuristic,
        cost,
        ds_over_L,
        robot: Robot,
        max_turn_chain=4,
    ):
        self.ex = ex
        self.start = start
        self.goal = goal
        self.heuristic = heuristic
        self.cost = cost
        self.ds_over_L = ds_over_L
        self.R = robot.min_turning_radius
        self.poses: list[Pose] = []
        self.parent: list[int] = []
        self.union: list[Union | None] = []
        self.g: list[float] = []
        self.depth: list[int] = []
        self.kind: list[str] = []
        self.dist: list[float] = []
        self.chain: list[int] = []  # consecutive turn states ending at the node
        self.max_turn_chain = max_turn_chain

    def h(self, pose: Pose, depth: int) -> float:
        """``h'`` of a node (module docstring)."""
        goal = self.goal
        d = math.hypot(goal.x - pose.x, goal.y - pose.y)
        if self.cost == "distance" or self.heuristic == "b" or d == 0.0 and pose.theta == goal.theta:
            return d
        ha = self._h_longd(pose, d)
        if self.heuristic == "a":
            return ha
        w = depth / (depth + self.ds_over_L) if depth + self.ds_over_L > 0 else 1.0
        return w * ha + (1.0 - w) * d

    def _h_longd(self, pose: Pose, d: float) -> float:
        u = self.ex.direct(pose, self.goal)
        if u is not None and self.ex.ws.curvature_ok(u):
            return self.ex.link_cost(u)
        psi = math.atan2(self.goal.y - pose.y, self.goal.x - pose.x) if d > 0 else pose.theta
        phi0 = abs(math.remainder(pose.theta - psi, 2 * math.pi))
        phi1 = abs(math.remainder(self.goal.theta - psi, 2 * math.pi))
        return d + self.R * (phi0 + phi1)

    def link(self, u: Union) -> float:
        return u.d if self.cost == "distance" else self.ex.link_cost(u)

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

    def make_plan(self, i: int, expanded: int, t0: float) -> Plan:
        ids = self.path(i)
        unions = tuple(self.union[j] for j in ids[1:])
        # LONGD [1] of each union (Romberg, rtol 1e-8)
        exact = 0.0
        for u in unions:
            exact += float(longd_exact_intrinsic(*checked_intrinsic(u.p0, u.p1, u.alpha, u.L), rtol=1e-8))
        st = self.ex.stats
        return Plan(
            nodes=tuple(self.poses[j] for j in ids),
            unions=unions,
            cost=exact,
            search_cost=self.g[i],
            expanded=expanded,
            generated=len(self.poses),
            seconds=time.perf_counter() - t0,
            heuristic=self.heuristic,
            cost_kind=self.cost,
            version=self.ex.version,
            collision_checks=st.collision_checks,
            exact_checks=st.exact_checks,
            iterations=tuple(it for it, ok, _ in st.iterations if ok),
            kinds=tuple(self.kind[j] for j in ids),
        )

    def run(self, max_expansions: int, time_limit: float, t0: float) -> Plan:
        start, goal = Pose(*self.start), Pose(*self.goal)
        s = self.add(start, -1, None, 0.0, 0, "start")
        if start == goal:
            return self.make_plan(s, 0, t0)
        heap = [(self.h(start, 0), 0, s)]
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
                return self.make_plan(i, expanded, t0)
            key = keys[i]
            if key in closed:
                continue
            closed.add(key)
            expanded += 1
            succs = self.ex.successors(self.poses[i], goal, turns=self.chain[i] < self.max_turn_chain)
            # the direct unions of the new nodes to the goal (h' and their expansion), batched
            self.ex.prefetch([(s.pose, goal) for s in succs if s.kind != "goal" and s.key not in closed])
            for succ in succs:
                if succ.key in closed:
                    continue
                g = self.g[i] + self.link(succ.union)
                if g >= best_g.get(succ.key, math.inf):
                    continue
                best_g[succ.key] = g
                depth = self.depth[i] + 1
                j = self.add(succ.pose, i, succ.union, g, depth, succ.kind)
                keys[j] = succ.key
                f = g + (0.0 if succ.kind == "goal" else self.h(succ.pose, depth))
                heapq.heappush(heap, (f, counter, j))
                counter += 1
        seconds = time.perf_counter() - t0
        best = min(range(len(self.poses)), key=lambda k: (self.dist[k], self.g[k]))
        partial = self.make_plan(best, expanded, t0)
        what = {
            "exhausted": "every reachable node was expanded (is the goal enclosed?)",
            "expansions": f"the expansion limit max_expansions={max_expansions} was reached",
            "time": f"the time limit time_limit={time_limit:g} s was reached",
        }[reason]
        raise NoPathError(
            f"no path from {tuple(start)} to {tuple(goal)}: {what}; expanded {expanded} nodes, "
            f"generated {len(self.poses)}; the closest node explored is {self.dist[best]:.3g} from the goal",
            reason,
            expanded,
            len(self.poses),
            seconds,
            partial,
        )
