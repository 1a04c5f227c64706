"""Floors that need reverse gear (issue 26; beyond the paper): out of a bay, into a bay
backwards, out of a dead end, a turn in a corridor too narrow for a U-turn.

The paper's AGV drives forward only; so does the default planner unless the robot has a
reverse gear. Every floor here is made so that a forward-only robot cannot, or can only by
a long detour, reach its goal, and that a robot which reverses can: the study's oracle is
OMPL's BIT* on the Reeds-Shepp space (forward and reverse, the same turning radius) at 5 s,
and OMPL's BIT* on the Dubins space (forward only) tells which floors need reverse at all
(:mod:`segplan.studies.kind_study`'s harness, one fresh process per run, at full CPU).

Each kind of :data:`REVERSE_KINDS` has :data:`N_PER_KIND` = 100 floors in the study
(:func:`reverse_floors`); any index makes one more (:func:`reverse_floor`). A floor is a
function of its kind and index: its generator is ``numpy.random.default_rng([26,
GENERATOR_VERSION, kind, index])`` (26: the issue's number), coordinates rounded to a
micrometre and headings to a microradian, as in :mod:`segplan.studies.floor_kinds`, whose
pose helpers this module uses.

Kinds
-----
``"bay-out"``
    A parking lot of :func:`segplan.studies.floor_layouts.parking_layout`; the robot starts
    nose-in in the free bay (front wheel 0.1-0.3 ``L`` from the bay's back wall, in the
    model), the goal is the parking kind's start (across the lot, on the drive aisle or in
    an end zone, heading along it either way).
``"reverse-park"``
    The same lots; start across the lot, goal backed into the free bay: heading out of it,
    the back of the robot's body (``A`` minus the half-width) 0.1-0.3 ``L`` from the back
    wall (model).
``"dead-end"``
    The issue's dead-end bay: a 20 x 12 m floor, robot ``L`` 1.5 m, half-width 0.45 m,
    steering 45 degrees; a bay walled on three sides (thin walls, 0.1-0.2 m) against one of
    the floor's walls, :data:`BAY_SPARE` wider than the robot's body and as deep as the
    robot plus 0.2-1.0 m; 4-10 boxes elsewhere on the floor. Start nose-in in the bay
    (front wheel 0.1-0.3 ``L`` from its back), goal a free pose at least 6 m away, any
    heading.
``"k-turn"``
    A corridor closed at both ends, :data:`CORRIDOR_WIDTH` wide (1.8-3.0 m: narrower than
    the ``2 R + 2 w + `` excursion a U-turn of the default robot needs) and 8-12 m long.
    Start in its first half heading to the far end, goal in its second half heading back:
    a turn on the spot of several cusps (OMPL decides whether the corridor allows it).

The robot is :data:`segplan.studies.floors.ROBOT` (``L = 1 m``, half-width 0.3 m, 45
degrees) but in ``"dead-end"`` (the issue's). Feasibility is not proved: OMPL's
Reeds-Shepp BIT* is the oracle.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..floor.scenario import Robot, Scenario, make_scenario
from . import floor_layouts as fl
from .floor_kinds import _across_lot, _Draw, _facing, _free_test, _off_face, _pairs, _pose
from .floors import ROBOT, _check_index

__all__ = [
    "BAY_SPARE",
    "CORRIDOR_LENGTH",
    "CORRIDOR_WIDTH",
    "DEAD_END_ROBOT",
    "GENERATOR_VERSION",
    "LAYOUT_TRIES",
    "N_PER_KIND",
    "REVERSE_KINDS",
    "reverse_floor",
    "reverse_floors",
]

#: Bump when any floor changes: stored results name the version they were measured on.
GENERATOR_VERSION = 1
#: The kinds, in the order of their seeds.
REVERSE_KINDS = ("bay-out", "reverse-park", "dead-end", "k-turn")
#: Floors of each kind in the study.
N_PER_KIND = 100
#: The issue's robot of the dead-end bay.
DEAD_END_ROBOT = Robot(L=1.5, half_width=0.45, max_steer=math.radians(45.0))
#: Dead-end bay: free width beyond the robot's body (m), drawn.
BAY_SPARE = (0.3, 0.8)
#: Corridor of the k-turn: width and length (m), drawn.
CORRIDOR_WIDTH = (1.8, 3.0)
CORRIDOR_LENGTH = (8.0, 12.0)
#: Layouts drawn before :func:`reverse_floor` gives up.
LAYOUT_TRIES = 20

_ROOT_SEED = 26  # the number
_DEAD_END_BOUNDS = (0.0, 0.0, 20.0, 12.0)


def _rng(*key: int) -> np.random.Generator:
    return np.random.default_rng([_ROOT_SEED, GENERATOR_VERSION, *key])


def _check_kind(kind) -> None:
    if kind not in REVERSE_KINDS:
        raise ValueError(f"kind must be one of {REVERSE_KINDS}, got {kind!r}")


def _backed(rng: np.random.Generator, free, face: fl.Face, robot: Robot, gap: float):
    """A pose backed against ``face``: heading out of it (``face.phi``), the back of its
    body (``A`` minus the half-width; the model's segment starts at ``A``) ``gap`` beyond
    the first free place on the ray out of the face (steps of L / 20 up to 4 L, then
    bisected to L / 100), or None."""
    t = rng.random()
    px, py = face.x0 + t * (face.x1 - face.x0), face.y0 + t * (face.y1 - face.y0)
    phi = face.phi
    ux, uy, L = math.cos(phi), math.sin(phi), robot.L

    def at(rho: float):  # the rear point A rho out of the face, heading out
        return (px + rho * ux, py + rho * uy, phi)

    return _off_face(free, at, L, gap)


def _build_lot(rng: np.random.Generator, backwards: bool) -> _Draw | None:
    """A lot: start nose-in in the free bay, goal across it (``"bay-out"``), or start across
    it and goal backed into the bay (``backwards``: ``"reverse-park"``)."""
    lot = fl.parking_layout(rng)
    layout, bounds = lot.layout, lot.bounds
    free = _free_test(layout.obstacles, bounds, ROBOT)
    gap = fl.uniform_cm(rng, 0.1, 0.3) * ROBOT.L
    bay = (_backed if backwards else _facing)(rng, free, lot.bay, ROBOT, gap)
    if bay is None:
        return None
    far = math.dist

    def draw(notes):
        return (_across_lot(rng, lot, ROBOT), bay) if backwards else (bay, _across_lot(rng, lot, ROBOT))

    got = _pairs(rng, free, draw, lambda s, g: far(s[:2], g[:2]) >= bounds[2] / 3)
    if got is None:
        return None
    what = "goal backed into the free bay" if backwards else "start nose-in in the free bay"
    return _Draw(ROBOT, bounds, layout.obstacles, got[0], got[1], [*layout.notes, what])


def _build_dead_end(rng: np.random.Generator) -> _Draw | None:
    robot, (x0, y0, x1, y1) = DEAD_END_ROBOT, _DEAD_END_BOUNDS
    t = fl.uniform_cm(rng, 0.1, 0.2)
    inner = round(2 * robot.half_width + fl.uniform_cm(rng, *BAY_SPARE), 2)
    depth = round(robot.L + 2 * robot.half_width + fl.uniform_cm(rng, 0.2, 1.0), 2)
    side = int(rng.integers(4))  # the floor wall the bay stands against: bottom, top, left, right
    along = (x1 - x0) if side < 2 else (y1 - y0)
    c = round(rng.uniform(0.2, 0.8) * along, 2)
    a, b = c - 0.5 * inner - t, c + 0.5 * inner + t  # outer faces of the side walls
    if side < 2:
        ys = (y0, y0 + depth) if side == 0 else (y1 - depth, y1)
        walls = [fl.rectangle(a, ys[0], a + t, ys[1]), fl.rectangle(b - t, ys[0], b, ys[1])]
        bay = fl.Face(
            c, ys[0] if side == 0 else ys[1], c, ys[0] if side == 0 else ys[1], 0.5 * math.pi * (1 - 2 * side)
        )
        box = (a, ys[0], b, ys[1])
    else:
        xs = (x0, x0 + depth) if side == 2 else (x1 - depth, x1)
        walls = [fl.rectangle(xs[0], a, xs[1], a + t), fl.rectangle(xs[0], b - t, xs[1], b)]
        bay = fl.Face(
            xs[0] if side == 2 else xs[1], c, xs[0] if side == 2 else xs[1], c, 0.0 if side == 2 else math.pi
        )
        box = (xs[0], a, xs[1], b)
    obstacles = list(walls)
    for _ in range(int(rng.integers(4, 11))):  # boxes elsewhere, 1 m clear of the bay
        w, h = fl.uniform_cm(rng, 0.4, 1.5), fl.uniform_cm(rng, 0.4, 1.5)
        px, py = rng.uniform(x0 + 1.0, x1 - 1.0 - w), rng.uniform(y0 + 1.0, y1 - 1.0 - h)
        if fl._overlaps((px, py, px + w, py + h), box, 1.0):
            continue
        obstacles.append(fl.rectangle(px, py, px + w, py + h))
    free = _free_test(obstacles, _DEAD_END_BOUNDS, robot)
    start = _facing(rng, free, bay, robot, fl.uniform_cm(rng, 0.1, 0.3) * robot.L)
    if start is None:
        return None

    def draw(notes):
        m = robot.half_width + 0.1
        return start, _pose(
            rng.uniform(x0 + m, x1 - m), rng.uniform(y0 + m, y1 - m), rng.uniform(-math.pi, math.pi)
        )

    got = _pairs(rng, free, draw, lambda s, g: math.dist(s[:2], g[:2]) >= 6.0)
    if got is None:
        return None
    notes = [
        f"a bay {inner:.2f} m wide (inside) and {depth:.2f} m deep against the "
        f"{('bottom', 'top', 'left', 'right')[side]} wall, {len(obstacles) - 2} boxes",
        "start nose-in in the bay",
    ]
    return _Draw(robot, _DEAD_END_BOUNDS, obstacles, got[0], got[1], notes)


def _build_k_turn(rng: np.random.Generator) -> _Draw | None:
    w, length = fl.uniform_cm(rng, *CORRIDOR_WIDTH), fl.uniform_cm(rng, *CORRIDOR_LENGTH)
    bounds = (0.0, 0.0, length, w)
    free = _free_test([], bounds, ROBOT)

    def draw(notes):
        ys = rng.uniform(ROBOT.half_width + 0.05, w - ROBOT.half_width - 0.05, size=2)
        s = _pose(rng.uniform(0.5, 0.5 * length - ROBOT.L), ys[0], rng.uniform(-0.2, 0.2))
        g = _pose(rng.uniform(0.5 * length + ROBOT.L, length - 0.5), ys[1], math.pi + rng.uniform(-0.2, 0.2))
        return s, g

    got = _pairs(rng, free, draw, lambda s, g: True)
    if got is None:
        return None
    notes = [f"a corridor {w:.2f} m wide and {length:.2f} m long, closed at both ends", "goal heading back"]
    return _Draw(ROBOT, bounds, [], got[0], got[1], notes)


_BUILDERS: dict[str, Callable[[np.random.Generator], _Draw | None]] = {
    "bay-out": lambda rng: _build_lot(rng, False),
    "reverse-park": lambda rng: _build_lot(rng, True),
    "dead-end": _build_dead_end,
    "k-turn": _build_k_turn,
}


def reverse_floor(kind: str, index: int) -> Scenario:
    """Floor ``index`` of ``kind`` (module docstring).

    Parameters
    ----------
    kind : {"bay-out", "reverse-park", "dead-end", "k-turn"}
    index : int
        ``>= 0``; the study uses ``0 .. N_PER_KIND - 1``.

    Returns
    -------
    Scenario
        Named ``f"{kind}-{index:03d}"``, its description says what was drawn. Its robot is
        forward-only (the study asks for reverse gear where the planner has one).

    Raises
    ------
    ValueError
        An unknown ``kind``, or an ``index`` that is not an integer >= 0.
    RuntimeError
        If :data:`LAYOUT_TRIES` layouts in a row had no free start and goal.
    """
    _check_kind(kind)
    index = _check_index(index)
    rng = _rng(REVERSE_KINDS.index(kind), index)
    for _ in range(LAYOUT_TRIES):
        d = _BUILDERS[kind](rng)
        if d is not None:
            break
    else:
        raise RuntimeError(
            f"{kind} floor {index}: no free start and goal in {LAYOUT_TRIES} layouts "
            f"(segplan.studies.reverse_floors v{GENERATOR_VERSION})"
        )
    name = f"{kind}-{index:03d}"
    desc = f"{kind.capitalize()} floor {index} (segplan.studies.reverse_floors v{GENERATOR_VERSION}): "
    desc += "; ".join(d.notes) + "."
    return make_scenario(
        d.robot, d.start, d.goal, d.obstacles, d.bounds, name=name, description=desc, source=name
    )


def reverse_floors(kind: str, n: int = N_PER_KIND) -> list[Scenario]:
    """The first ``n`` floors of ``kind`` (:func:`reverse_floor`)."""
    _check_kind(kind)
    return [reverse_floor(kind, i) for i in range(_check_index(n, "n"))]
