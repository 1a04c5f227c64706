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
Where no pair of arcs joins, a forward robot's planner tries its hops last (:func:`hop_pairs`:
single forward unions to poses off the lattice's headings and offsets, below).
The arcs and the turn-arounds are made of legs along tight circles
(:class:`segplan.planning.lattice.legs.Legs`: a planning call drives each leg once).

**A robot that may reverse** (issue 26; :mod:`segplan.planning.lattice.reverse`) also has
the arcs driven backwards (:func:`reversed_arc`: the same unions, the other direction) and
**hops** (:func:`hops`): single free unions, either way, to poses within a few ``L`` of the
start or the goal with headings off the lattice's (every :data:`HOP_TURNS` from the end's
heading, :data:`HOP_AHEAD` along it and :data:`HOP_ASIDE` across it). A robot nose-in in a
bay barely wider than itself cannot tilt by the lattice's smallest heading step (26.6 deg)
inside it, and no circle fits: every lattice state it reaches lies on the bay's axis
(``benchmarks/reverse_floors.py``'s dead-end floors: 10 of 100 exhausted so). One
union backwards that leaves the bay askew, then a search from there, gets it out. The pairs
of a reversing robot are ordered by the arcs' search cost (LONGD, times ``reverse_factor``
when driven backwards) plus the Reeds-Shepp length between the inner poses.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

from ...model.pose import Pose, wrap_ieee
from ..dubins import dubins_length_scalar
from ..links import LinkModel
from ..plan import Plan, link_ends, plain_directions, union_longd, unions_longd
from ..reeds_shepp import reeds_shepp_length
from ..schedule import SCHEDULE, Schedule
from .legs import LEG_STEPS, RADIUS_FACTORS, STEP, Legs
from .reverse import weighted_cost

__all__ = [
    "BOTH_ENDS",
    "HOP_AHEAD",
    "HOP_ASIDE",
    "HOP_TURNS",
    "LEG_STEPS",
    "RADIUS_FACTORS",
    "STEP",
    "TURNS",
    "IMPROVE_NEAR",
    "IMPROVE_SHARES",
    "MULTI_POINT",
    "IMPROVE_TRIES",
    "TURN_AROUND_FROM",
    "TURN_LEGS",
    "TURN_SHARES",
    "TURN_SHIFTS",
    "WHOLE_TURN",
    "Arc",
    "arc_pairs",
    "escape_pairs",
    "hop_pairs",
    "hops",
    "improve_with_arcs",
    "join_arcs",
    "reversed_arc",
    "tight_arcs",
    "turn_arounds",
]

#: Turns (radians) at which an arc's end is offered, while its unions stay free.
TURNS = tuple(math.radians(d) for d in (45.0, 90.0, 135.0, 180.0, 225.0, 270.0))
#: A hop's other pose: distances along the end's heading (times ``L``), ...
HOP_AHEAD = (0.5, 1.0, 1.5, 2.0, 2.5)
#: ... offsets across it (times ``L``; positive to the left) ...
HOP_ASIDE = (-0.6, -0.3, 0.0, 0.3, 0.6)
#: ... and turns from it (radians). The grid (170 poses, the straight ones left out: the
#: lattice has them) was set by hand on the dead-end floors' bays (about ``L`` wider than
#: the robot; ``segplan.studies.reverse_floors``), not tuned: on dead-end-010 14 of its
#: hops are free and 13 of those lead to a plan.
HOP_TURNS = tuple(math.radians(d) for d in (-45.0, -30.0, -15.0, 0.0, 15.0, 30.0, 45.0))


@dataclass(frozen=True)
class Arc:
    """A chain of unions along a circle (or one union, a hop): driven from ``first`` to ``last``.

    ``unions`` as a plan stores its links (:attr:`segplan.Plan.directions`): in driving
    order, each the forward union between its two nodes, from the far one to the near one
    where it is driven backwards (``directions``, one per union, ``()`` when all are driven
    forwards). ``inner`` is the pose the rest of the plan joins: ``last`` for an arc out of
    the start, ``first`` for an arc into the goal. ``cost``: the unions' exact LONGD [1] (the
    first's times their number for an arc along one circle: the same to rounding);
    ``search``: the search's cost of it (LONGD times ``reverse_factor`` where driven
    backwards, plus ``cusp_penalty`` per change of direction; None: ``cost``); ``longds``:
    each union's LONGD, in the order of ``unions``, where known (None: computed when needed).
    """

    unions: tuple
    first: Pose
    last: Pose
    cost: float
    into: bool
    directions: tuple = ()
    search: float | None = None
    longds: tuple | None = None

    @property
    def link_directions(self) -> tuple:
        """The direction of each union (1 forwards, -1 backwards)."""
        return self.directions or (1,) * len(self.unions)

    @property
    def search_cost(self) -> float:
        return self.cost if self.search is None else self.search

    @property
    def inner(self) -> Pose:
        return self.first if self.into else self.last


def tight_arcs(links: LinkModel, pose, R: float, into: bool = False, legs: Legs | None = None) -> list[Arc]:
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
    legs : Legs, optional
        The legs driven so far in this planning call (of ``links`` and ``R``), to reuse;
        None: a new one (the same arcs).

    Returns
    -------
    list of Arc
        One per side and per turn of :data:`TURNS` reached with every union free.
    """
    p = Pose(*pose)
    legs = Legs.checked(legs, links, R)
    out = []
    per = [int(round(t / STEP)) for t in TURNS]
    for side in (1, -1):
        # into the pose: the circle behind it, driven forwards to it (a leg out of it, backwards)
        got = legs.leg(p, side, -1 if into else 1, _never, per[-1])
        unions, cost = [], 0.0
        piece = legs.piece(p, side, -1 if into else 1)  # every later union is congruent
        for k, (u, cur) in enumerate(got, 1):
            unions.append(u)
            cost += piece
            if k in per:
                chain = tuple(reversed(unions)) if into else tuple(unions)
                first, last = (cur, p) if into else (p, cur)
                out.append(Arc(chain, first, last, cost, into))
    return out


def _search_cost(
    unions, directions, cost: float, reverse_factor: float, cusp_penalty: float, longds=None
) -> float:
    """The search's cost of links ``unions`` (LONGD [1] ``cost`` in all; ``longds``, each
    link's, if known) driven ``directions``."""
    if all(d > 0 for d in directions):
        return cost
    if all(d < 0 for d in directions):
        return reverse_factor * cost
    if longds is None:
        longds = [union_longd(u) for u in unions]
    back = math.fsum(x for x, d in zip(longds, directions, strict=True) if d < 0)
    cusps = sum(a != b for a, b in zip(directions[:-1], directions[1:], strict=True))
    return cost + (reverse_factor - 1.0) * back + cusp_penalty * cusps


def reversed_arc(arc: Arc, reverse_factor: float = 1.0, cusp_penalty: float = 0.0) -> Arc:
    """``arc`` driven the other way: an arc into a pose becomes an arc out of it, and the
    other way round, each union driven in the other direction (the same unions, in the other
    order: a reverse link is stored as the forward union from its far node to its near one);
    its search cost with ``reverse_factor`` and ``cusp_penalty`` (m)."""
    unions = tuple(reversed(arc.unions))
    directions = tuple(-d for d in reversed(arc.link_directions))
    longds = None if arc.longds is None else tuple(reversed(arc.longds))
    search = _search_cost(unions, directions, arc.cost, reverse_factor, cusp_penalty, longds)
    directions = plain_directions(directions)
    return Arc(unions, arc.last, arc.first, arc.cost, not arc.into, directions, search, longds)


def hops(
    links: LinkModel, pose, L: float, into: bool, direction: int, reverse_factor: float = 1.0
) -> list[Arc]:
    """Single free unions within the steering limit out of ``pose`` (``into=False``) or into
    it (``into=True``), driven forwards (``direction`` 1) or backwards (-1): one
    :class:`Arc` per free one, its other pose on the grid :data:`HOP_AHEAD` x
    :data:`HOP_ASIDE` x :data:`HOP_TURNS` in ``pose``'s frame (module docstring), ahead of
    ``pose`` when the forward union runs from ``pose`` to it (out forwards, into backwards),
    else behind. The straight hops (no offset, no turn) are left out. A hop driven
    backwards has the search cost ``reverse_factor`` times its LONGD."""
    ws = links.ws
    p = Pose(*pose)
    ahead = (direction > 0) != into  # the forward union runs from p to the other pose
    sign = 1.0 if ahead else -1.0
    c, s = math.cos(p.theta), math.sin(p.theta)
    out = []
    for d in HOP_AHEAD:
        for e in HOP_ASIDE:
            for turn in HOP_TURNS:
                if e == 0.0 and turn == 0.0:
                    continue
                along, across = sign * d * L, e * L
                x, y = p.x + along * c - across * s, p.y + along * s + across * c
                q = Pose(x, y, wrap_ieee(p.theta + turn))
                if not ws.pose_free(q):
                    continue
                u = links.union(p, q) if ahead else links.union(q, p)
                if u is None or not ws.union_free(u):  # the steering limit included
                    continue
                first, last = (q, p) if into else (p, q)
                cost = union_longd(u)
                search = _search_cost((u,), (direction,), cost, reverse_factor, 0.0)
                out.append(Arc((u,), first, last, cost, into, plain_directions((direction,)), search))
    return out


#: A reversing robot's escape pairs with arcs at both ends: those of this many cheapest arcs
#: of each end (:func:`escape_pairs`). Set by hand; not tuned.
BOTH_ENDS = 8
#: Turn-arounds are offered where the start's and the goal's headings differ by more than
#: this (radians): a quarter turn, within a lattice's reach without one.
TURN_AROUND_FROM = 0.5 * math.pi
#: Pairs tried at most by a reversing robot's improvement (:func:`_improve_reversing`), the
#: cheapest estimates first; as many again for each tolerance of :data:`IMPROVE_NEAR` beyond
#: the first where those turn-arounds are offered. Set by hand (the bay-out floors'
#: improvement took 40-85 ms without a cap); not tuned.
IMPROVE_TRIES = 32
#: Straight moves before a turn-around (times ``R``; :func:`turn_arounds`). Set by hand; not tuned.
TURN_SHIFTS = (0.5, 1.0, 2.0, 3.0)
#: Shares of its free unions a turn-around's leg drives, tried in turn while none gets there
#: (:func:`turn_arounds`): the whole leg, then half (k-turn-079: a full leg left no room for
#: the next). Set by hand; not tuned.
TURN_SHARES = (1.0, 0.5)
#: Shares of their free unions the legs of the improvement's turn-arounds drive
#: (:func:`_improve_reversing`): every one offered, from every start of :data:`TURN_SHIFTS`
#: (``every`` of :func:`turn_arounds`: a search over the legs' lengths and the turn's
#: position). Measured on 2026-12-03 on the reverse study's k-turn floors
#: (``segplan.studies.reverse_floors``, OMPL's stored Reeds-Shepp BIT* 5 s the reference;
#: shares and starts chosen on the 46 even floors OMPL solved, checked on the 48 odd ones):
#: whole legs from the nearest start only (before) gave front-wheel lengths of median 1.069
#: and worst 1.387 times OMPL's on the even floors, 1.084 and 1.376 on the odd ones; every
#: share of (1, 0.75, 0.5, 0.33) or of (1, 0.67, 0.33) from the nearest start 1.048-1.049
#: and 1.210 on the even floors but 1.078 and 1.376 on the odd ones; (1, 0.67, 0.33) from
#: every start 1.046 and 1.210 (even), 1.037 and 1.200 (odd; floors over 1.15 times: 12 to
#: 6). With :data:`MULTI_POINT`, on all 400 floors of the study: k-turn median 1.082 to
#: 1.049 and worst 1.387 to 1.210 (46 plans shorter, 8 longer by 0.1-9 %, where the
#: search's cost took a plan with fewer cusps or less reversing); bay-out and reverse-park
#: plans the same, dead-end one shorter and one 4 % longer. Set so; not tuned further.
IMPROVE_SHARES = (1.0, 0.67, 0.33)
#: The improvement's turn-arounds search the legs' lengths and the turn's position
#: (:data:`IMPROVE_SHARES`) only for a plan with at least this many changes of direction (a
#: multi-point turn, which it may shorten). Searched for every plan (2026-12-03, every fourth
#: bay-out and reverse-park floor of the reverse study, whose answers have at most one cusp),
#: it made 5 of the 25 bay-out plans 0.6-2.8 % longer (for a lower search cost) and one
#: 0.01 % shorter, left the reverse-park plans as they were and took up to 4 times the CPU
#: time of a call; with this gate their plans are those of before.
MULTI_POINT = 2
#: How close to the other end's heading the improvement's turn-arounds turn (radians,
#: ``near`` of :func:`turn_arounds`, with ``every``): all the way (within ``STEP / 2``), and
#: stopped short by up to 30 and 60 degrees, the union to the other end turning the rest.
#: Chosen on 2026-12-03 on the reverse study's k-turn-014 (``segplan.studies.reverse_floors``;
#: OMPL's stored Reeds-Shepp BIT* 5 s turns round near the start and reverses 4 m into the
#: goal, turning on the way: whole turn-arounds joined by one union cost 1.210 times its
#: length, 60 degrees short 1.065; 90 joined nothing). Measured on all 400 floors, each half
#: against the stored run of the code before: k-turn front-wheel length median 1.049 to 1.035
#: and worst 1.210 to 1.176 on the 46 even floors OMPL solved, 1.040 to 1.033 and 1.200 to
#: 1.165 on the 48 odd ones; floors over 1.15 times 4 to 1 and 6 to 1; 33 k-turn plans
#: shorter, 10 longer (the worst, k-turn-042, 1.002 to 1.176: the search's cost took a plan
#: reversing 1.4 m instead of 8.7 m, with a cusp fewer); bay-out and reverse-park plans the
#: same, two dead-end plans shorter. A first run with :data:`IMPROVE_TRIES` pairs in all,
#: not per tolerance, lost the odd floors' k-turn-069 (1.117 to 1.242: the winning pair fell
#: beyond the cap); the cap per tolerance was set after it, on that floor.
IMPROVE_NEAR = (0.5 * STEP, math.radians(30.0), math.radians(60.0))
#: A turn-around all the way round (``near`` of :func:`turn_arounds`: within ``STEP / 2``).
WHOLE_TURN = IMPROVE_NEAR[:1]
#: Legs of a turn-around at most (:func:`turn_arounds`).
TURN_LEGS = 12


def _never(pose: Pose) -> bool:
    """A leg's ``stop`` that never stops it (:meth:`segplan.planning.lattice.legs.Legs.leg`)."""
    return False


def turn_arounds(
    links: LinkModel,
    pose,
    target: float,
    R: float,
    reverse_factor: float = 1.0,
    cusp_penalty: float = 0.0,
    shares: tuple = TURN_SHARES,
    every: bool = False,
    budget: float = math.inf,
    toward=None,
    near: tuple = WHOLE_TURN,
    legs: Legs | None = None,
) -> list[Arc]:
    """Multi-point turns out of ``pose`` until its heading is within ``STEP / 2`` of
    ``target`` (radians; or each of ``near``, see below): legs along tight circles, forwards
    and backwards in turn, each turning the same way (forwards on the left circle, backwards
    on the right one, or the mirror image) as far as its unions stay free, at most
    :data:`TURN_LEGS` legs. A K-turn
    (a three-point turn and its longer kin) in a corridor narrower than two turning radii,
    which the lattice's coarse headings and longer primitives cannot make
    (``segplan.studies.reverse_floors``' k-turn floors: 15 of 94 failed without it).

    The turn starts at ``pose`` or, if it gets stuck there (a start near the corridor's
    closed end: k-turn-037), after one straight union along the heading, forwards or
    backwards by :data:`TURN_SHIFTS` times ``R`` (the nearest that works). If no turn gets
    there with whole legs, legs of half their free length are tried (``shares``, by default
    :data:`TURN_SHARES`). One
    :class:`Arc` (``into=False``, its search cost with ``reverse_factor`` and
    ``cusp_penalty``, m) per turning sense and first direction that gets there; none where
    the heading is already there.

    ``every`` (the improvement of a found plan, :data:`IMPROVE_SHARES`): the turn-arounds of
    every share in ``shares`` from every start (the pose and its shifts) that gets there,
    instead of the first share and the nearest start; a turn is given up once a lower bound
    of the search cost of a plan through it, driven either way, exceeds ``budget`` (m): no
    such plan could cost less. The bound: ``min(1, reverse_factor)`` times its LONGD so far
    and the straight distance from where it got to ``toward`` (the plan's other end, a
    pose; none if None: the front wheel's path is at least as long as the rear point's, and
    that at least the distance), plus ``cusp_penalty`` per change of direction so far.

    ``near``: how close to ``target`` a turn's heading must get (radians, each at least
    ``STEP / 2``), the turns of each in turn (:data:`IMPROVE_NEAR`): a turn stopped short of
    the target leaves the rest of the turn to the union that joins it to the other end, as a
    peer's plan turns while it drives down the corridor.

    ``legs``: the legs driven so far in this planning call (:class:`Legs`, of ``links`` and
    ``R``), to reuse; None: a new one, shared by the turns of every tolerance (the same arcs)."""
    p = Pose(*pose)
    legs = Legs.checked(legs, links, R)
    out: list = []
    for tolerance in near:
        out += _turn_arounds_near(
            links,
            p,
            target,
            R,
            max(0.5 * STEP, tolerance),
            (reverse_factor, cusp_penalty, budget, toward),
            shares,
            every,
            legs,
        )
    return out


def _turn_arounds_near(links, p: Pose, target: float, R: float, tolerance: float, costs, shares, every, legs):
    """:func:`turn_arounds` with one tolerance: the turns whose heading ends within
    ``tolerance`` (radians) of ``target`` (``costs``: :func:`_turn_arounds`'; ``legs``: a
    :class:`Legs`)."""
    ws = links.ws

    def there(q: Pose) -> bool:
        return abs(wrap_ieee(q.theta - target)) < tolerance

    if there(p):
        return []
    c, s = math.cos(p.theta), math.sin(p.theta)

    def ways():  # (unions, directions, pose, LONGDs) to start the legs from, the nearest first
        yield (), (), p, ()
        for shift in TURN_SHIFTS:
            for sign in (1, -1):
                q = Pose(p.x + sign * shift * R * c, p.y + sign * shift * R * s, p.theta)
                u = links.union(p, q) if sign > 0 else links.union(q, p)
                if u is not None and ws.union_free(u):
                    yield (u,), (sign,), q, (union_longd(u),)

    made: list = []  # the ways made so far (each made once, when first needed, for every turn)
    more = ways()

    def starts():  # the ways made, then the next ones
        yield from made
        for way in more:
            made.append(way)
            yield way

    out: list = []
    for share in shares:
        if not out or every:
            out += _turn_arounds(links, p, R, there, starts, share, costs, every, legs)
    return out


def _turn_arounds(links, p, R, there, starts, share, costs: tuple, every: bool, legs: Legs) -> list[Arc]:
    """:func:`turn_arounds` with legs driving ``share`` of their free unions; ``starts()``
    yields the ways to start from, the nearest first; ``costs``: ``(reverse_factor,
    cusp_penalty, budget, toward)``; ``every``: from every start, not only the nearest that
    works; ``legs``: :func:`_turn`'s."""
    reverse_factor, cusp_penalty, budget, toward = costs
    least = min(1.0, reverse_factor)
    out = []
    for turn in (1, -1):
        for first in (1, -1):
            for lead, lead_dirs, p0, lead_longds in starts():
                bound = (least, cusp_penalty, budget - least * math.fsum(lead_longds), toward)
                arc = _turn(links, p0, R, turn, first, there, share, bound, legs)
                if arc is None:
                    continue
                unions, directions = lead + arc[0], lead_dirs + arc[1]
                longds = lead_longds + arc[3]
                cost = math.fsum(longds)
                search = _search_cost(unions, directions, cost, reverse_factor, cusp_penalty, longds)
                directions = plain_directions(directions)
                out.append(Arc(unions, p, arc[2], cost, False, directions, search, longds))
                if not every:
                    break  # the nearest start that works
    return out


def _turn(
    links: LinkModel,
    p: Pose,
    R: float,
    turn: int,
    first: int,
    there,
    share: float = 1.0,
    bound: tuple = (1.0, 0.0, math.inf, None),
    legs: Legs | None = None,
) -> tuple | None:
    """The legs of one turn-around from ``p`` (:func:`turn_arounds`): ``(unions, directions,
    end, longds)``, or None if it gets stuck or runs out of legs. Each leg drives the
    ``share`` of its free unions (rounded up; all of them to reach the target). The unions of
    a leg are congruent: each leg's first LONGD [1] stands for the others (as
    :func:`tight_arcs`). ``bound = (factor, penalty, budget, toward)``: None as soon as
    ``factor`` times the LONGD so far and the distance to ``toward`` (a pose, or None) plus
    ``penalty`` per change of direction exceeds ``budget`` (:func:`turn_arounds`' ``every``).
    ``legs``: the :class:`Legs` driven so far (the same leg starts several turns: every
    share's first); None: a new one."""
    legs = Legs.checked(legs, links, R)
    factor, penalty, budget, toward = bound
    unions: list = []
    directions: list = []
    longds: list = []
    cur, stuck = p, 0
    so_far, cusps = 0.0, 0  # LONGD and changes of direction of the legs so far
    for leg in range(TURN_LEGS):
        d = first if leg % 2 == 0 else -first
        side = turn if d > 0 else -turn  # both legs turn the heading the same way
        got = legs.leg(cur, side, d, there)
        piece = legs.piece(cur, side, d)
        if share < 1.0 and got and not there(got[-1][1]):
            got = got[: max(1, math.ceil(share * len(got)))]
        stuck = stuck + 1 if not got else 0
        if stuck == 2:
            return None
        if got and directions and directions[-1] != d:
            cusps += 1
        so_far += piece * len(got)
        for u, q in got:
            unions.append(u)
            directions.append(d)
            longds.append(piece)
            cur = q
        rest = 0.0 if toward is None else math.hypot(toward.x - cur.x, toward.y - cur.y)
        if factor * (so_far + rest) + penalty * cusps > budget * (1.0 + 1e-9):
            return None  # dearer than the budget, driven either way
        if there(cur):
            return tuple(unions), tuple(directions), cur, tuple(longds)
    return None


def escape_pairs(
    starts: list[Arc], goals: list[Arc], start, goal, R: float, reverse: bool = False
) -> list[tuple]:
    """``(estimate, start_arc or None, goal_arc or None)`` for every combination but the
    empty one, cheapest first by the estimate: the arcs' search costs
    (:attr:`Arc.search_cost`) plus the Dubins length (radius ``R``) between their inner
    poses; for a robot that may reverse (``reverse`` true), the Reeds-Shepp length, and of
    the combinations of two arcs only those of the :data:`BOTH_ENDS` cheapest of each end
    (by their estimate alone; its hops make hundreds of arcs per end, and the estimates of
    all their combinations took 0.3 s on k-turn-003)."""
    pairs = []
    bound = reeds_shepp_length if reverse else dubins_length_scalar

    def cost(arc: Arc | None) -> float:
        return 0.0 if arc is None else arc.search_cost

    if reverse:
        s0, g0 = Pose(*start), Pose(*goal)
        starts = sorted(starts, key=lambda a: cost(a) + bound(*a.inner, *g0, R))
        goals = sorted(goals, key=lambda b: cost(b) + bound(*s0, *b.inner, R))
    for i, a in enumerate((None, *starts)):
        for k, b in enumerate((None, *goals)):
            if a is None and b is None:
                continue
            if reverse and i and k and max(i, k) > BOTH_ENDS:
                continue  # (index 0 is None)
            p0 = a.inner if a else Pose(*start)
            p1 = b.inner if b else Pose(*goal)
            est = cost(a) + cost(b) + bound(*p0, *p1, R)
            pairs.append((est, len(pairs), a, b))
    pairs.sort(key=lambda t: t[:2])
    return [(est, a, b) for est, _, a, b in pairs]


def arc_pairs(
    scenario,
    links: LinkModel,
    ends: str,
    reverse_factor: float = 1.0,
    cusp_penalty: float = 0.0,
    escaping: bool = True,
    budget: float = math.inf,
    every: bool = False,
    legs: Legs | None = None,
) -> list[tuple]:
    """:func:`escape_pairs` of the scenario's tight arcs: out of the start (if ``ends`` is
    ``"both"``) and into the goal (``"both"`` or ``"goal"``), cheapest first; for a robot
    that may reverse (``scenario.robot.reverse``) also the arcs driven backwards
    (:func:`reversed_arc`), the hops (:func:`hops`) both ways and, where the goal's heading
    is more than :data:`TURN_AROUND_FROM` from the start's, the turn-arounds
    (:func:`turn_arounds`), ordered with ``reverse_factor`` and ``cusp_penalty`` (m).

    ``ends`` is a failed search's ``NoPathError.escapable`` (:mod:`segplan.planning.lattice.search`):
    ``"both"`` after an exhausted lattice, ``"goal"`` after one whose goal looked enclosed.
    For an escape (``escaping``), a reversing robot's pairs are interleaved
    (:func:`_interleaved`) and its turn-arounds may have half legs (:data:`TURN_SHARES`);
    otherwise (the improvement of a found plan, :func:`improve_with_arcs`) they are in the
    order of their estimates, without hops (they are for traps: their hundreds of pairs took
    seconds), its turn-arounds with whole legs from the nearest start, or if ``every``, those
    of every share of :data:`IMPROVE_SHARES` from every start (``every`` of
    :func:`turn_arounds`), none through which a plan would cost more than ``budget`` (m: the
    found plan's). ``legs``: the :class:`Legs` driven so far in this planning call, to reuse
    (None: a new one; the same pairs).
    """
    robot = scenario.robot
    R = robot.min_turning_radius
    legs = Legs.checked(legs, links, R)
    starts = tight_arcs(links, scenario.start, R, legs=legs) if ends == "both" else []
    goals = tight_arcs(links, scenario.goal, R, into=True, legs=legs)
    if not robot.reverse:
        return escape_pairs(starts, goals, scenario.start, scenario.goal, R)
    rf, cp = reverse_factor, cusp_penalty
    start, goal = Pose(*scenario.start), Pose(*scenario.goal)
    if ends == "both":
        starts += [reversed_arc(a, rf, cp) for a in tight_arcs(links, start, R, into=True, legs=legs)]
        starts += [h for d in (1, -1) if escaping for h in hops(links, start, robot.L, False, d, rf)]
    turning = abs(wrap_ieee(goal.theta - start.theta)) > TURN_AROUND_FROM
    if escaping:
        shares, every = TURN_SHARES, False
    else:
        shares = IMPROVE_SHARES if every else TURN_SHARES[:1]
    near = IMPROVE_NEAR if every else WHOLE_TURN
    if ends == "both" and turning:
        starts += turn_arounds(links, start, goal.theta, R, rf, cp, shares, every, budget, goal, near, legs)
    goals += [reversed_arc(a, rf, cp) for a in tight_arcs(links, goal, R, legs=legs)]
    goals += [h for d in (1, -1) if escaping for h in hops(links, goal, robot.L, True, d, rf)]
    if turning:
        back = turn_arounds(links, goal, start.theta, R, rf, cp, shares, every, budget, start, near, legs)
        goals += [reversed_arc(a, rf, cp) for a in back]
    pairs = escape_pairs(starts, goals, start, goal, R, True)
    return _interleaved(pairs) if escaping else pairs


def hop_pairs(scenario, links: LinkModel) -> list[tuple]:
    """A forward robot's last escape: :func:`escape_pairs` of its forward hops (:func:`hops`)
    out of the start and into the goal, cheapest first.

    Tried only where every pair of tight arcs failed (:func:`segplan.planning.lattice.search._escape`),
    at both ends whatever the failed search's ``escapable``: a hop ends at a pose whose heading or
    offset the lattice laid out at the start does not have, and the search from it lays its
    lattice there. Found on the floor-kinds study (``segplan.studies.floor_kinds``, floors OMPL's
    BIT* solves): clutter-097's start runs along a wall past an obstacle in a gap that only a
    heading off the lattice's threads (exhausted after 29 expansions; a hop aside joins), and
    robots-086's goal looked enclosed to the start's lattice (3 states reach it), where a hop
    out of the start, turned 30 deg, joins it."""
    L = scenario.robot.L
    starts = hops(links, scenario.start, L, False, 1)
    goals = hops(links, scenario.goal, L, True, 1)
    pairs = escape_pairs(starts, goals, scenario.start, scenario.goal, scenario.robot.min_turning_radius)
    return [p for p in pairs if p[1] is None or p[2] is None]


def _interleaved(pairs: list[tuple]) -> list[tuple]:
    """``pairs`` taken in turn from four queues, each in its order: a turn-around
    (:func:`turn_arounds`) at one end, a start arc only, a goal arc only, both. A reversing
    robot's hops make hundreds of pairs, and where the start is the trap the cheapest
    estimates are all goal-side (dead-end-010: the first 16 were), so one order by the
    estimate would try none that leaves the start; a turn-around's many unions put it
    after every hop (k-turn-008: 1291 pairs)."""

    def turning(arc) -> bool:
        return arc is not None and len(set(arc.link_directions)) > 1

    turns = [p for p in pairs if (p[1] is None or p[2] is None) and (turning(p[1]) or turning(p[2]))]
    taken = {id(p) for p in turns}
    rest = [p for p in pairs if id(p) not in taken]
    queues = [turns]
    queues += [[p for p in rest if (p[1] is None, p[2] is None) == k] for k in ((False, True), (True, False))]
    queues.append([p for p in rest if p[1] is not None and p[2] is not None])
    out = []
    for k in range(max(map(len, queues))):
        out += [q[k] for q in queues if k < len(q)]
    return out


def improve_with_arcs(
    scenario,
    links: LinkModel,
    plan: Plan,
    t0: float,
    deadline: float = math.inf,
    schedule: Schedule = SCHEDULE,
    reverse_factor: float | None = None,
    cusp_penalty: float = 0.0,
    legs: Legs | None = None,
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

    A robot that may reverse (``scenario.robot.reverse``, ``reverse_factor`` given):
    :func:`_improve_reversing`. ``legs``: the :class:`Legs` driven so far in this planning
    call, to reuse (None: a new one; the same plan).
    """
    if scenario.robot.reverse and reverse_factor is not None:
        args = (schedule, reverse_factor, cusp_penalty, legs)
        return _improve_reversing(scenario, links, plan, t0, deadline, *args)
    R = scenario.robot.min_turning_radius
    s, g = Pose(*scenario.start), Pose(*scenario.goal)
    if not plan.cost > schedule.improve_gap * dubins_length_scalar(*s, *g, R):
        return plan
    if time.perf_counter() > deadline:
        return plan
    ws = links.ws
    legs = Legs.checked(legs, links, R)
    pairs = escape_pairs(tight_arcs(links, s, R, legs=legs), tight_arcs(links, g, R, True, legs), s, g, R)
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


def _improve_reversing(
    scenario,
    links: LinkModel,
    plan: Plan,
    t0: float,
    deadline: float,
    schedule: Schedule,
    rf: float,
    cp: float,
    legs: Legs | None = None,
) -> Plan:
    """:func:`improve_with_arcs` for a robot that may reverse: the arcs of :func:`arc_pairs`
    (tight arcs either way, hops, turn-arounds) at both ends, joined by the paper's direct
    union driven either way, plans compared by the search's cost
    (:func:`segplan.planning.lattice.reverse.weighted_cost` with ``rf`` and ``cp``, m: the
    default planner's comparison; the hops left out: they are for traps, and their hundreds
    of pairs took seconds), tried when that cost exceeds :attr:`Schedule.improve_gap`
    times the Reeds-Shepp length of the ends. The lattice's K-turns, whose primitives turn
    at ``1.12 R`` with headings 26.6 deg apart, cost 1.10 times OMPL's in the median on the
    reverse study's k-turn floors; a turn-around on tight circles and one union down the
    corridor is often shorter. For a plan with :data:`MULTI_POINT` changes of direction or
    more, the turn-arounds are searched over the legs' lengths and the turn's position
    (:data:`IMPROVE_SHARES`), none through which a plan would cost more than the plan."""
    R = scenario.robot.min_turning_radius
    s, g = Pose(*scenario.start), Pose(*scenario.goal)
    best, best_w = plan, weighted_cost(plan, rf, cp)
    if not best_w > schedule.improve_gap * reeds_shepp_length(*s, *g, R):
        return plan
    if time.perf_counter() > deadline:
        return plan
    ws = links.ws
    every = len(plan.cusps) >= MULTI_POINT
    pairs = arc_pairs(scenario, links, "both", rf, cp, escaping=False, budget=best_w, every=every, legs=legs)
    tries = IMPROVE_TRIES * (len(IMPROVE_NEAR) if every else 1)  # as many per tolerance
    for est, a, b in pairs[:tries]:
        if est >= best_w:
            break  # ordered by this estimate: no later pair can win
        if time.perf_counter() > deadline:
            break
        p0, p1 = a.inner if a else s, b.inner if b else g
        for d in (1, -1):
            u = links.union(p0, p1) if d > 0 else links.union(p1, p0)
            if u is None or not ws.union_free(u):
                continue
            # the search's cost of the joined plan from its parts (the arcs' are known): the
            # union's, and a cusp where it meets an arc driven the other way
            w = (a.search_cost if a else 0.0) + (b.search_cost if b else 0.0)
            w += union_longd(u) * (rf if d < 0 else 1.0)
            w += cp * (
                (a is not None and a.link_directions[-1] != d) + (b is not None and b.link_directions[0] != d)
            )
            if w < best_w:
                best, best_w = join_arcs(scenario, a, (u,), b, plan.expanded, t0, plan, middle_direction=d), w
    return best


def join_arcs(
    scenario,
    a: Arc | None,
    middle,
    b: Arc | None,
    expanded: int,
    t0: float,
    template=None,
    middle_direction: int = 1,
) -> Plan:
    """The plan of arc ``a`` (or None), ``middle`` (a Plan, or a tuple of unions made in
    the frame of ``template``'s plan, driven ``middle_direction``), arc ``b`` (or None); ``kinds``
    ``"arc"`` for the arcs' nodes (the start stays ``"start"``, the goal ``"goal"``). Its
    ``search_cost`` adds the arcs' :attr:`Arc.search_cost` (a change of direction where an
    arc meets ``middle`` is not charged)."""
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
    weighted = sum(x.search_cost for x in (a, b) if x)
    inner_directions = (middle_direction,) * len(inner) if direct else middle.link_directions
    outer = (a.link_directions if a else (), b.link_directions if b else ())
    directions = plain_directions(outer[0] + tuple(inner_directions) + outer[1])
    return replace(
        template if direct else middle,
        directions=directions,
        nodes=link_ends(Pose(*scenario.start), unions, directions),
        unions=unions,
        cost=cost,
        search_cost=cost if direct else middle.search_cost + weighted,
        expanded=expanded,
        seconds=time.perf_counter() - t0,
        kinds=tuple(kinds),
    )
