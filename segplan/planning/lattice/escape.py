"""Tight arcs out of the start and into the goal: the lattice planner's way out of a corner.

Beyond the paper (issue 12). The lattice's tightest primitives turn at about ``1.12 R``
(their end points must lie on the lattice, :mod:`segplan.planning.lattice.primitives`); a start facing a
wall a few decimetres away may leave room only for a circle closer to ``R = L /
tan(max_steer)``, and then every lattice state around the start is blocked. A chain of
short symmetric unions along a circle turns much tighter: a union that turns by
``STEP`` (11.25 deg) peaks less than 1 % above the circle's curvature, so the chain keeps
the steering limit on a circle of radius :data:`RADIUS_FACTORS` ``x R``.

:func:`tight_arcs` gives such chains out of a pose (to the left and to the right, every
:data:`TURNS` reached while every union is free) or into it (driving forwards, ending at
the pose). :func:`escape_pairs` orders the combinations of a start arc and a goal arc
(either may be empty) by their cost plus the Dubins length between the inner poses
(:func:`arc_pairs`, for a scenario); the planner (:mod:`segplan.planning.lattice.search`) searches
again (at its first resolution) between the inner poses of each in turn when its search runs
out of states, and puts the arcs around the plan it finds (:func:`join_arcs`).
:func:`improve_with_arcs` joins such arcs by one union where that beats a found plan.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

from ...model.pose import Pose, arc_end, intrinsic_interval, wrap_ieee
from ...model.union import Union
from ..dubins import dubins_length_scalar
from ..links import LinkModel
from ..plan import Plan, link_ends, plain_directions, union_longd, unions_longd
from ..schedule import SCHEDULE, Schedule

__all__ = [
    "RADIUS_FACTORS",
    "STEP",
    "TURNS",
    "Arc",
    "arc_pairs",
    "escape_pairs",
    "improve_with_arcs",
    "join_arcs",
    "tight_arcs",
]

#: Turn of one union of an arc (radians).
STEP = math.radians(11.25)
#: Turns (radians) at which an arc's end is offered, while its unions stay free.
TURNS = tuple(math.radians(d) for d in (45.0, 90.0, 135.0, 180.0, 225.0, 270.0))
#: Radii tried (times ``R``): the smallest whose union keeps the steering limit is used.
RADIUS_FACTORS = (1.01, 1.03, 1.06, 1.1)


@dataclass(frozen=True)
class Arc:
    """A chain of unions along a circle: ``unions`` in driving order, from ``first`` to ``last``.

    ``inner`` is the pose the rest of the plan joins: ``last`` for an arc out of the start,
    ``first`` for an arc into the goal. ``cost``: the unions' exact LONGD [1] (the first's
    times their number: the same to rounding).
    """

    unions: tuple
    first: Pose
    last: Pose
    cost: float
    into: bool

    @property
    def inner(self) -> Pose:
        return self.first if self.into else self.last


def _circle_pose(p: Pose, rho: float, side: int, turn: float) -> Pose:
    """:func:`segplan.model.pose.arc_end` of ``p`` as a Pose, its heading in ``[-pi, pi]``."""
    x, y, th = arc_end(p.x, p.y, p.theta, rho, side, turn)
    return Pose(x, y, wrap_ieee(th))


def tight_arcs(links: LinkModel, pose, R: float, into: bool = False) -> list[Arc]:
    """Free arcs out of ``pose`` (``into=False``) or into it (``into=True``), both sides.

    Parameters
    ----------
    links : segplan.planning.links.LinkModel
        Makes the unions (optimal reference system, steering fallback); its workspace
        (``links.ws``) has the certified tests (free, in bounds, steering limit).
    pose : segplan.Pose
    R : float
        The minimum turning radius.
    into : bool
        Arcs that end at ``pose`` (the goal side) rather than start there.

    Returns
    -------
    list of Arc
        One per side and per turn of :data:`TURNS` reached with every union free.
    """
    ws = links.ws
    p = Pose(*pose)
    out = []
    per = [int(round(t / STEP)) for t in TURNS]
    for side in (1, -1):
        rho = None
        for f in RADIUS_FACTORS:  # the shape is the same all along: the first union decides
            a, b = (
                (_circle_pose(p, f * R, side, -STEP), p) if into else (p, _circle_pose(p, f * R, side, STEP))
            )
            u = links.union(a, b)
            if u is not None and ws.curvature_ok(u):
                rho = f * R
                break
        if rho is None:
            continue
        unions, cost, cur = [], 0.0, p
        u1 = piece = None  # the first union and its LONGD: every later one is congruent
        for k in range(1, per[-1] + 1):
            nxt = _circle_pose(p, rho, side, -k * STEP if into else k * STEP)
            a, b = (nxt, cur) if into else (cur, nxt)
            geo = None if u1 is None else intrinsic_interval(a, b)
            if geo is not None and geo[4] < u1.alpha < geo[5]:  # its frame, moved along
                d, psi, phi0, phi1, _, _ = geo
                u = Union.from_intrinsic(a, b, u1.alpha, u1.L, d, psi, phi0, phi1)
            else:
                u = links.union(a, b)
            if u is None or not ws.union_free(u):
                break
            if u1 is None:
                u1, piece = u, union_longd(u)
            unions.append(u)
            cost += piece
            cur = nxt
            if k in per:
                chain = tuple(reversed(unions)) if into else tuple(unions)
                first, last = (cur, p) if into else (p, cur)
                out.append(Arc(chain, first, last, cost, into))
    return out


def escape_pairs(starts: list[Arc], goals: list[Arc], start, goal, R: float) -> list[tuple]:
    """``(estimate, start_arc or None, goal_arc or None)`` for every combination but the
    empty one, cheapest first by the estimate: the arcs' costs plus the Dubins length
    (radius ``R``) between their inner poses."""
    pairs = []
    for a in (None, *starts):
        for b in (None, *goals):
            if a is None and b is None:
                continue
            p0 = a.inner if a else Pose(*start)
            p1 = b.inner if b else Pose(*goal)
            est = (a.cost if a else 0.0) + (b.cost if b else 0.0) + dubins_length_scalar(*p0, *p1, R)
            pairs.append((est, len(pairs), a, b))
    pairs.sort(key=lambda t: t[:2])
    return [(est, a, b) for est, _, a, b in pairs]


def arc_pairs(scenario, links: LinkModel, ends: str) -> list[tuple]:
    """:func:`escape_pairs` of the scenario's tight arcs: out of the start (if ``ends`` is
    ``"both"``) and into the goal (``"both"`` or ``"goal"``), cheapest first.

    ``ends`` is a failed search's ``NoPathError.escapable`` (:mod:`segplan.planning.lattice.search`):
    ``"both"`` after an exhausted lattice, ``"goal"`` after one whose goal looked enclosed.
    """
    R = scenario.robot.min_turning_radius
    starts = tight_arcs(links, scenario.start, R) if ends == "both" else []
    goals = tight_arcs(links, scenario.goal, R, into=True)
    return escape_pairs(starts, goals, scenario.start, scenario.goal, R)


def improve_with_arcs(
    scenario,
    links: LinkModel,
    plan: Plan,
    t0: float,
    deadline: float = math.inf,
    schedule: Schedule = SCHEDULE,
) -> Plan:
    """A cheaper plan through tight arcs at its ends, or ``plan`` itself.

    The lattice cannot follow a circle tighter than its primitives; where the best route
    turns at nearly ``R`` next to the start or the goal (a tight turn under an obstacle),
    its plan goes the long way round. Arcs (:func:`tight_arcs`) at either end are joined by
    the paper's direct union between their inner poses, for every pair whose estimate
    (:func:`escape_pairs`) beats the plan; the cheapest free plan wins. Tried only when
    ``plan.cost`` exceeds :attr:`Schedule.improve_gap` times the Dubins length of the ends (a
    search between the arcs, tried too, cost more time than it won length). No pair is tried
    once ``deadline`` (a :func:`time.perf_counter` value) has passed: the best plan so far.
    """
    R = scenario.robot.min_turning_radius
    s, g = Pose(*scenario.start), Pose(*scenario.goal)
    if not plan.cost > schedule.improve_gap * dubins_length_scalar(*s, *g, R):
        return plan
    if time.perf_counter() > deadline:
        return plan
    ws = links.ws
    pairs = escape_pairs(tight_arcs(links, s, R), tight_arcs(links, g, R, into=True), s, g, R)
    best = plan
    for est, a, b in pairs:
        if est >= best.cost:
            break  # ordered by this estimate: no later pair can win
        if time.perf_counter() > deadline:
            break
        u = links.union(a.inner if a else s, b.inner if b else g)
        if u is not None and ws.union_free(u):
            cand = join_arcs(scenario, a, (u,), b, plan.expanded, t0, plan)
            if cand.cost < best.cost:
                best = cand
    return best


def join_arcs(
    scenario, a: Arc | None, middle, b: Arc | None, expanded: int, t0: float, template=None
) -> Plan:
    """The plan of arc ``a`` (or None), ``middle`` (a Plan, or a tuple of unions made in
    the frame of ``template``'s plan), arc ``b`` (or None); ``kinds`` ``"arc"`` for the arcs'
    nodes (the start stays ``"start"``, the goal ``"goal"``)."""
    front = a.unions if a else ()
    back = b.unions if b else ()
    direct = isinstance(middle, tuple)
    inner = middle if direct else middle.unions
    kinds = ["start"] + ["arc"] * len(front) + (["goal"] * len(inner) if direct else list(middle.kinds[1:]))
    kinds += ["arc"] * len(back)
    if back:
        kinds[len(front) + len(inner)] = "arc"  # the arc's first node
    kinds[-1] = "goal"
    unions = front + tuple(inner) + back
    ends = (a.cost if a else 0.0) + (b.cost if b else 0.0)
    cost = ends + unions_longd(inner)  # the arcs' LONGD is known
    inner_directions = (1,) * len(inner) if direct else middle.link_directions  # the arcs: forwards
    directions = plain_directions((1,) * len(front) + tuple(inner_directions) + (1,) * len(back))
    return replace(
        template if direct else middle,
        directions=directions,
        nodes=link_ends(Pose(*scenario.start), unions, directions),
        unions=unions,
        cost=cost,
        search_cost=cost if direct else middle.search_cost + ends,
        expanded=expanded,
        seconds=time.perf_counter() - t0,
        kinds=tuple(kinds),
    )
