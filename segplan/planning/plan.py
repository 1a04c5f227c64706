"""What a search returns: a :class:`Plan`, or a :class:`NoPathError`; and a plan's :class:`Refinement`.

Section "Results. Graph-search" of Campoy et al. (1989) describes the plan: consecutive
nodes joined by cubic unions, its cost the sum of their LONGD [1]. These types sit below
the search (:mod:`segplan.planning.paper.search`) and the refinement
(:mod:`segplan.planning.refine`), so neither imports the other; above the options a plan
records (:mod:`segplan.planning.options`) and the trajectory it offers
(:mod:`segplan.planning.trajectory`: :meth:`Plan.poses`, :meth:`Plan.trajectory`,
:meth:`Plan.facts`).

A plan saved by :meth:`Plan.save` (beyond the paper, issue 27) is a JSON file that
:meth:`Plan.load` turns back into an equal plan, bit for bit (:func:`plan_record`).
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from ..floor.scenario import FOOTPRINT_KEYS, Robot, Scenario
from ..model.cost import chain_longd
from ..model.pose import Pose
from ..model.union import Union
from .checks import check_limits, check_option
from .options import options_from_dict
from .trajectory import (
    DEFAULT_STEP,
    JUMP_TOL,
    PathSamples,
    PlanFacts,
    Trajectory,
    plan_facts,
    sample_path,
    time_law,
)

__all__ = [
    "PLAN_FORMAT",
    "PLAN_FORMAT_VERSION",
    "PLAN_RTOL",
    "NoPathError",
    "Plan",
    "Refinement",
    "check_limits",
    "check_option",
    "direct_plan",
    "lattice_plan",
    "link_ends",
    "plain_directions",
    "plan_from_record",
    "plan_record",
    "saved_robot",
    "union_longd",
    "unions_longd",
]

#: Relative tolerance of the Romberg integration [1] behind a returned plan's ``cost``.
PLAN_RTOL = 1e-8
#: The name and version of the format of a saved plan (:func:`plan_record`).
PLAN_FORMAT = "segplan-plan"
PLAN_FORMAT_VERSION = 1


def union_longd(u) -> float:
    """LONGD of one union by formula [1] (Romberg to :data:`PLAN_RTOL`), from the union's
    own intrinsic parameters (``u.d``, ``u.phi0``, ``u.phi1``, ``u.alpha``, ``u.L``)."""
    return chain_longd((u,), PLAN_RTOL)


def unions_longd(unions: Iterable) -> float:
    """A chain's LONGD: the sum of :func:`union_longd` over ``unions`` (0 for none)."""
    return chain_longd(unions, PLAN_RTOL)


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
        ``"exhausted"`` (every node the search could generate was expanded; the message says
        what is known beyond that: a goal whose free region the start's does not reach, a
        start in a dead end that a forward-only robot cannot turn in),
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
    stopped : str or None
        ``"time"`` where the call's ``time_limit`` cut a stage short and the plan is the best
        found by then (the default planner's lattice search stopped after the paper's search
        had found a plan, or a refinement stopped: ``refinement.stopped``); None otherwise.
    directions : tuple of int
        Beyond the paper (issue 26, a robot that may reverse): ``()`` when every union is
        driven forwards (every plan of a forward-only robot), else one entry per union, ``1``
        forwards or ``-1`` backwards. A backward link ``i`` is the forward union from
        ``nodes[i + 1]`` to ``nodes[i]`` traversed backwards (``unions[i].p0`` is then
        ``nodes[i + 1]``): the same curve, the same front-wheel length LONGD [1]
        (:mod:`segplan.planning.lattice.reverse`). :attr:`link_directions` always has one
        entry per union; :attr:`cusps` lists the nodes where the direction changes.
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
    stopped: str | None = None
    directions: tuple = ()

    @property
    def link_directions(self) -> tuple:
        """The direction of each union: ``1`` forwards, ``-1`` backwards (:attr:`directions`)."""
        return self.directions or (1,) * len(self.unions)

    @property
    def cusps(self) -> tuple:
        """Indices of the nodes where the robot changes direction (stops and shifts gear)."""
        d = self.directions
        return tuple(i for i in range(1, len(d)) if d[i] != d[i - 1])

    def to_dict(self) -> dict:
        """Plain-JSON summary (angles in degrees, like scenario files; ``L`` the robot length of
        the unions, None without any). :meth:`save` writes it with what rebuilds the plan."""
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
            "stopped": self.stopped,
            "L": self.unions[0].L if self.unions else None,
            "directions": list(self.link_directions),
            "cusps": list(self.cusps),
        }

    # -- the plan as a controller reads it (segplan.planning.trajectory) -----------------------
    def poses(self, step: float = DEFAULT_STEP) -> PathSamples:
        """Samples of the plan every ``step`` metres (at most) along the rear point's path.

        Per sample: arc length ``s`` travelled by A, A's ``x``, ``y``, heading ``theta``
        (continuous), the front wheel ``x_front``, ``y_front``, the signed curvature ``kappa``
        of A's path and the steering angle ``steer = arctan(L kappa)``, the ``direction``
        (``-1`` reversing); exact per union from its cubic, every node included (twice where
        two unions meet: each side's curvature), in driving order. See
        :func:`segplan.planning.trajectory.sample_path`.

        Parameters
        ----------
        step : float
            Largest spacing (m) along the rear path, > 0; default 0.05.

        Returns
        -------
        segplan.planning.trajectory.PathSamples
            Read-only arrays (``.x``, ``.y``, ``.theta``, ``.kappa``, ...), ``.to_csv(path)``,
            ``.nav_path()``, ``.save_nav_path(path)``.
        """
        return sample_path(self.unions, step, self.directions)

    def trajectory(
        self,
        v_max: float,
        a_max: float,
        a_lat_max: float,
        steer_rate_max: float,
        *,
        step: float = DEFAULT_STEP,
        jump_tol: float = JUMP_TOL,
    ) -> Trajectory:
        """A time law along the plan that respects every limit, from rest to rest.

        ``v`` (the rear point's speed) at most ``v_max``, ``|dv/dt| <= a_max``,
        ``v^2 |kappa| <= a_lat_max``, ``|d steer / dt| <= steer_rate_max`` everywhere (not
        only at the samples); where the steering jumps at a node (by more than ``jump_tol``)
        the robot stops and re-steers standing, ``|jump| / steer_rate_max`` seconds; at a cusp
        (:attr:`cusps`) it stops and drives on the other way (``v`` negative reversing). A
        forward-backward pass over :meth:`poses` (:func:`segplan.planning.trajectory.time_law`,
        whose module docstring states the models and the discretisation error).

        Parameters
        ----------
        v_max, a_max, a_lat_max : float
            m/s, m/s^2, m/s^2 (> 0).
        steer_rate_max : float
            rad/s (> 0).
        step : float
            Sample spacing (m) along the rear path.
        jump_tol : float
            Steering steps up to this (radians) are driven through (rounding).

        Returns
        -------
        segplan.planning.trajectory.Trajectory
            The samples with ``t``, ``v``, ``a``; ``total_time``, ``jump_time`` (what the
            jumps cost), ``dwell_time``, ``jumps``.
        """
        return time_law(
            self.unions, v_max, a_max, a_lat_max, steer_rate_max, step=step, jump_tol=jump_tol,
            directions=self.directions,
        )  # fmt: skip

    def facts(self, max_steer: float | None = None) -> PlanFacts:
        """The steering angle at each node on each side and its jumps; the largest curvature,
        against ``tan(max_steer) / L`` when the steering limit ``max_steer`` (radians) is given;
        the rear and front path lengths (:func:`segplan.planning.trajectory.plan_facts`).
        The clearance needs the floor: :func:`segplan.plan_clearance`."""
        return plan_facts(self.unions, max_steer, self.directions)

    # -- a file that rebuilds the plan ----------------------------------------------------------
    def save(self, path, scenario: Scenario | None = None) -> Path:
        """Write the plan to ``path`` as JSON (:func:`plan_record`); :meth:`load` reads it back,
        equal bit for bit. With ``scenario`` (the floor it was planned on) the file also
        records the robot (``L``, ``half_width``, ``max_steer`` and the body, which
        :func:`saved_robot` reads back) and the floor's name and file. Returns the path written."""
        path = Path(path)
        text = json.dumps(plan_record(self, scenario), indent=1, allow_nan=False)
        path.write_text(text + "\n", encoding="utf-8")
        return path

    @classmethod
    def load(cls, path) -> Plan:
        """The plan saved at ``path`` by :meth:`save` (:func:`plan_from_record`), its unions and
        every number as they were, its options an options object again
        (``plan_scenario(scenario, options=plan.options)`` plans as it was planned).

        Raises
        ------
        ValueError
            The file is not a saved plan, or a value in it is malformed or inconsistent
            (named).
        """
        return plan_from_record(_read(path))


def _read(path) -> dict:
    """The JSON of the file at ``path`` (ValueError naming it if it is not JSON)."""
    path = Path(path)
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path} is not JSON: {exc}") from None


def link_ends(start, unions, directions=()) -> tuple:
    """The nodes of a chain of ``unions`` from ``start``: each union's far end in its
    direction (``p1`` forwards, ``p0`` backwards; ``directions`` as :attr:`Plan.directions`)."""
    if not directions:
        return (start,) + tuple(u.p1 for u in unions)
    return (start,) + tuple(u.p1 if d > 0 else u.p0 for u, d in zip(unions, directions, strict=True))


def plain_directions(directions) -> tuple:
    """``directions`` as :attr:`Plan.directions` stores them: ``()`` when every link is forwards."""
    directions = tuple(int(d) for d in directions)
    return () if all(d == 1 for d in directions) else directions


def lattice_plan(
    start, unions, kinds, cost, search_cost, expanded, generated, seconds, stats, *, directions=(),
    heuristic="dubins",
) -> Plan:  # fmt: skip
    """A :class:`Plan` of the lattice planner (``version="lattice"``, LONGD cost; ``heuristic``
    the lower bound of its h', ``"dubins"`` or, for a robot that may reverse,
    ``"reeds-shepp"``): the nodes are ``start`` and the unions' far ends (:func:`link_ends`;
    ``directions`` as :attr:`Plan.directions`); ``stats`` the workspace's counters
    (``collision_checks``, ``exact_checks``)."""
    directions = plain_directions(directions)
    return Plan(
        directions=directions,
        nodes=link_ends(start, unions, directions),
        unions=tuple(unions),
        cost=cost,
        search_cost=search_cost,
        expanded=expanded,
        generated=generated,
        seconds=seconds,
        heuristic=heuristic,
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


# -- the saved plan -------------------------------------------------------------------------------
def plan_record(plan: Plan, scenario: Scenario | None = None) -> dict:
    """A plan as plain JSON that :func:`plan_from_record` rebuilds exactly.

    The keys of :meth:`Plan.to_dict` as they are (angles in degrees, for reading), and:
    ``format`` (:data:`PLAN_FORMAT`) and ``format_version``; ``L`` (m); ``max_steer``
    (radians), ``half_width`` (m) and the body (``front_overhang``, ``rear_overhang`` (m),
    ``rectangle``: :class:`segplan.Robot`) of the robot and ``floor`` (``{"name", "path"}``
    of the scenario), each None unless ``scenario`` is given (:func:`saved_robot`);
    ``iterations``; and ``exact``: the nodes ``[x, y, theta]`` in radians and each union's
    :meth:`segplan.Union.state`. Every float is written by ``repr`` (Python's ``json``),
    which reads back as the same double.

    Raises
    ------
    ValueError
        ``scenario`` is not a Scenario, or its robot's ``L`` is not the plan's.
    """
    L = plan.unions[0].L if plan.unions else None
    robot = floor = None
    if scenario is not None:
        if not isinstance(scenario, Scenario):
            raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
        robot = scenario.robot
        if L is not None and robot.L != L:
            raise ValueError(f"the scenario's robot has L={robot.L!r}, the plan's unions L={L!r}")
        L = robot.L
        floor = {"name": scenario.name or None, "path": None if scenario.path is None else str(scenario.path)}
    return {
        "format": PLAN_FORMAT,
        "format_version": PLAN_FORMAT_VERSION,
        **plan.to_dict(),
        "L": L,
        **{
            k: None if robot is None else getattr(robot, k)
            for k in ("max_steer", "half_width", *FOOTPRINT_KEYS)
        },
        "floor": floor,
        "iterations": [int(i) for i in plan.iterations],
        "exact": {
            "nodes": [[float(v) for v in p] for p in plan.nodes],
            "unions": [u.state() for u in plan.unions],
        },
    }


def _field(record: Mapping, name: str, kinds, what: str):
    """``record[name]`` if it is one of ``kinds`` (not a bool), else ValueError naming it."""
    if name not in record:
        raise ValueError(f"the saved plan lacks {name!r}")
    value = record[name]
    if isinstance(value, bool) or not isinstance(value, kinds):  # no field is a flag
        raise ValueError(f"the saved plan's {name!r} must be {what}, got {value!r}")
    return value


def _finite(v) -> bool:
    """A finite number, not a bool."""
    return isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)


def saved_robot(saved) -> Robot | None:
    """The robot a plan was saved with (:meth:`Plan.save` with its scenario), or None (saved
    without one). ``saved``: the file's path or its record (:func:`plan_record`). A record
    made before footprints (no body keys) gives the paper's body, the segment A->B.

    Raises
    ------
    ValueError
        Not JSON, or a robot value out of range (named, as by :class:`segplan.Robot`).
    """
    record = saved if isinstance(saved, Mapping) else _read(saved)
    if record.get("max_steer") is None:
        return None
    body = {k: record[k] for k in FOOTPRINT_KEYS if record.get(k) is not None}
    try:
        return Robot(record.get("L"), record.get("half_width"), record["max_steer"], **body)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"the saved plan's robot: {exc}") from None


def plan_from_record(record: Mapping) -> Plan:
    """The plan of a :func:`plan_record` (read back from JSON): equal to the saved one, bit for bit.

    Raises
    ------
    ValueError
        Not a saved plan of this format, or a missing, malformed or inconsistent value
        (named): the unions must join the nodes, each union's derived values must agree
        with its ends (:meth:`segplan.Union.from_state`).
    """
    if not isinstance(record, Mapping) or record.get("format") != PLAN_FORMAT:
        raise ValueError(f"not a saved segplan plan (no 'format': {PLAN_FORMAT!r})")
    if record.get("format_version") != PLAN_FORMAT_VERSION:
        raise ValueError(
            f"saved plan format version {record.get('format_version')!r}; this segplan reads "
            f"version {PLAN_FORMAT_VERSION}"
        )
    exact = _field(record, "exact", Mapping, "a mapping of nodes and unions")
    nodes = []
    for i, p in enumerate(_field(exact, "nodes", list, "a list")):
        if not (isinstance(p, list) and len(p) == 3 and all(_finite(v) for v in p)):
            raise ValueError(f"the saved plan's node {i} must be [x, y, theta] of finite numbers, got {p!r}")
        nodes.append(Pose(*(float(v) for v in p)))
    unions = tuple(Union.from_state(u) for u in _field(exact, "unions", list, "a list"))
    if len(nodes) != len(unions) + 1:
        raise ValueError(f"the saved plan has {len(nodes)} nodes for {len(unions)} unions")
    directions = record.get("directions", [1] * len(unions))
    if not (
        isinstance(directions, list)
        and len(directions) == len(unions)
        and all(d in (1, -1) and not isinstance(d, bool) for d in directions)
    ):
        raise ValueError(f"the saved plan's 'directions' must be 1 or -1 for each of {len(unions)} unions")
    for i, (u, d) in enumerate(zip(unions, directions, strict=True)):
        ends = (u.p0, u.p1) if d == 1 else (u.p1, u.p0)
        if ends != (nodes[i], nodes[i + 1]):
            raise ValueError(f"the saved plan's union {i} does not join nodes {i} and {i + 1}")
    number, count, text = (int, float), int, str
    iterations = _field(record, "iterations", list, "a list of integers")
    if not all(isinstance(i, int) and not isinstance(i, bool) for i in iterations):
        raise ValueError("the saved plan's 'iterations' must be a list of integers")
    kinds = _field(record, "kinds", list, "a list of node kinds")
    if len(kinds) != len(nodes) or not all(isinstance(k, str) for k in kinds):
        raise ValueError(f"the saved plan's 'kinds' must name each of its {len(nodes)} nodes")
    refinement = record.get("refinement")
    if refinement is not None:
        try:
            refinement = Refinement(**refinement)
        except TypeError as exc:
            raise ValueError(f"the saved plan's 'refinement' is malformed: {exc}") from None
    options = record.get("options")
    planner = record.get("planner")
    if planner is not None and not isinstance(planner, str):
        raise ValueError(f"the saved plan's 'planner' must be a string or null, got {planner!r}")
    stopped = record.get("stopped")
    if stopped not in (None, "time"):
        raise ValueError(f"the saved plan's 'stopped' must be 'time' or null, got {stopped!r}")
    saved_robot(record)  # its robot, if saved, is one
    return Plan(
        nodes=tuple(nodes),
        unions=unions,
        cost=float(_field(record, "cost", number, "a number")),
        search_cost=float(_field(record, "search_cost", number, "a number")),
        expanded=_field(record, "expanded", count, "an integer"),
        generated=_field(record, "generated", count, "an integer"),
        seconds=float(_field(record, "seconds", number, "a number")),
        heuristic=_field(record, "heuristic", text, "a string"),
        cost_kind=_field(record, "cost_kind", text, "a string"),
        version=_field(record, "version", text, "a string"),
        collision_checks=_field(record, "collision_checks", count, "an integer"),
        exact_checks=_field(record, "exact_checks", count, "an integer"),
        iterations=tuple(iterations),
        kinds=tuple(kinds),
        refinement=refinement,
        planner=planner,
        options=None if options is None else options_from_dict(options),
        stopped=stopped,
        directions=plain_directions(directions),
    )
