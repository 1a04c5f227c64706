"""Floors of the kinds robots drive (issue 25; beyond the paper): warehouses, rooms, parking
lots, clutter, other robots, large sites.

Chapter 9 measures the default planner on random floors (:mod:`segplan.studies.floors`);
this module makes floors that look like the places a forward-only car-like robot is sent
to: aisles between racks, rooms behind doors, a free bay between parked cars. Each kind
of :data:`FLOOR_KINDS` has :data:`N_PER_KIND` = 100 floors in the study
(:func:`kind_floors`); any index makes one more (:func:`kind_floor`). A floor is a
function of its kind and index: its generator is ``numpy.random.default_rng([25,
GENERATOR_VERSION, kind, index])`` (25: the issue's number, a root seed apart from the
random floors' 12; ``kind`` its place in :data:`FLOOR_KINDS`), every coordinate is rounded
to a micrometre and every heading to a microradian, so that a floor, and
:func:`segplan.studies.floors.floor_key`, do not depend on the last bit of the machine's
trigonometry. The layouts, their parameters and ranges are
:mod:`segplan.studies.floor_layouts`; this module places the robot and makes the scenario.

The robot is :data:`segplan.studies.floors.ROBOT` (``L = 1 m``, half-width 0.3 m, 45
degrees: ``R = 1 m``) except in ``"robots"``. Lengths in metres; "model" is the planning
model (obstacles enlarged by the half-width, walls moved in by it).

Kinds: layout, start and goal
-----------------------------
``"warehouse"``
    A 30 x 18 m warehouse (:func:`~segplan.studies.floor_layouts.warehouse_layout`: rack rows,
    aisles 2.0-3.2 m, one cross aisle, end aisles; dead-end aisles in a share
    :data:`DEAD_END_SHARE` of the floors). Start and goal on aisles (between racks, along
    the walls, the cross and end aisles), centred on them within half their spare width,
    heading along them either way, at least :data:`MIN_DISTANCE` = 8 m apart. In a share
    :data:`ACROSS_GOAL_SHARE` of the floors the goal is across an aisle, nose to a rack
    (front wheel 0.1-0.3 L from it in the model), where the aisle leaves room behind to
    arrive on the smallest circle.
``"rooms"``
    A 20 x 12 m flat of six rooms (:func:`~segplan.studies.floor_layouts.rooms_layout`: thin
    walls, one door of 1.2-2.0 m per wall between two rooms, 0-3 pieces of furniture per
    room). Start and goal in two different rooms, at least 4 m apart: the start heading to
    a door of its room, the goal heading away from a door of its room (arriving through
    it), within :data:`DOOR_SPREAD` = 30 degrees, the robot's middle at least ``R + L``
    from that door.
``"parking"``
    A lot of two rows of parked cars with one free bay
    (:func:`~segplan.studies.floor_layouts.parking_layout`). The goal is nose-in in the free
    bay: heading into it, its front wheel 0.1-0.3 L from the back wall (model). The start
    is across the lot, at least a third of the lot's length from the goal: in the third of
    the lot farthest from the free bay, on the drive aisle or in the end zone, heading
    along it within 20 degrees (the end zone: along x or y), either way.
``"clutter"``
    A 20 x 12 m room of 25-45 small obstacles
    (:func:`~segplan.studies.floor_layouts.clutter_layout`). Start and goal at least 8 m
    apart, both headings within :data:`NATURAL_SPREAD` = 60 degrees of the direction from
    start to goal.
``"robots"``
    Other robots: ``L`` in :data:`ROBOT_LENGTH` (0.6-2.0 m, cm), steering limit in
    :data:`ROBOT_STEER_DEG` (30-60 degrees, 0.1 degree), half-width in
    :data:`ROBOT_HALF_WIDTH` (0.25-0.4 ``L``, mm); the clutter floor with every length
    scaled by ``L`` (``20 L x 12 L``, start and goal ``8 L`` apart): what changes is the
    turning radius ``R = L / tan(steer)`` relative to the floor, 0.58-1.73 ``L``.
``"large"``
    A site of 111-185 m by 75-125 m (:func:`~segplan.studies.floor_layouts.site_layout`:
    3-5 by 3-5 blocks, each a warehouse hall or a rooms building, roads between them;
    150-600 obstacles). Start in one block and goal in another whose centre is at least
    :data:`SITE_MIN_DISTANCE` = 30 m away, placed as in the block's kind.

Tight starts
------------
A share :data:`TIGHT_SHARE` (a quarter) of the floors of every kind has a tight start:
the robot faces a wall or an obstacle close ahead (a rack across the aisle in a warehouse,
a wall or a piece of furniture of its room, a parked car across the aisle in the lot, an
obstacle in the clutter), its front wheel ``e + m L`` from it in the model, where ``e``
(:func:`turn_excursion`) is how far the front wheel moves ahead while the robot turns a
quarter circle at its smallest radius and ``m`` is drawn in :data:`TIGHT_MARGIN`
(0.05-0.3); a tight start is kept only if that quarter circle, to the left or to the
right, is free (poses checked every ``pi R / 48`` of A's arc), so it is hard but not a
trap. The floor's description says so.

Feasibility is not proved: OMPL's BIT* is the oracle (:mod:`segplan.studies.kind_study`).
The layouts leave room to drive (aisles and doors wider than the robot, roads between
blocks, tight starts with room for a turn) so that most floors should be feasible for a
forward-only robot. Start and goal are free poses, checked here with the scenario's own
pose test before :func:`segplan.make_scenario` checks them again; a layout where
:data:`POSE_TRIES` draws place none is drawn again, at most :data:`LAYOUT_TRIES` times,
then :func:`kind_floor` raises.

:func:`stress_floor` is the separate stress case: 1000 x 1000 m with 5000 rectangles.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from ..floor.decompose import decompose
from ..floor.scenario import Robot, Scenario, make_scenario
from ..model.pose import TWO_PI, wrap_scalar
from . import floor_layouts as fl
from .floors import ROBOT, _check_index, _FreeTest

__all__ = [
    "ACROSS_GOAL_SHARE",
    "DEAD_END_SHARE",
    "DOOR_SPREAD",
    "FLOOR_KINDS",
    "GENERATOR_VERSION",
    "LAYOUT_TRIES",
    "MIN_DISTANCE",
    "NATURAL_SPREAD",
    "N_PER_KIND",
    "POSE_TRIES",
    "ROBOT_HALF_WIDTH",
    "ROBOT_LENGTH",
    "ROBOT_STEER_DEG",
    "SITE_MIN_DISTANCE",
    "TIGHT_MARGIN",
    "TIGHT_SHARE",
    "kind_floor",
    "kind_floors",
    "stress_floor",
    "turn_excursion",
]

#: Bump when any floor changes (here or in its layout): stored results name the version
#: they were measured on.
GENERATOR_VERSION = 1
#: The kinds, in the order of their seeds.
FLOOR_KINDS = ("warehouse", "rooms", "parking", "clutter", "robots", "large")
#: Floors of each kind in the study.
N_PER_KIND = 100
#: Share of floors with a tight start, and its margin beyond the turn's excursion (in L).
TIGHT_SHARE = 0.25
TIGHT_MARGIN = (0.05, 0.3)
#: Warehouse: share of dead-end layouts, share of goals across an aisle.
DEAD_END_SHARE = 0.25
ACROSS_GOAL_SHARE = 0.15
#: Rooms: a heading within this angle (radians) of the direction to (from) a door.
DOOR_SPREAD = math.radians(30.0)
#: Least distance (m, times L for "robots") between start and goal (warehouse, clutter).
MIN_DISTANCE = 8.0
#: Clutter: headings within this angle (radians) of the start -> goal direction.
NATURAL_SPREAD = math.radians(60.0)
#: Other robots: L (m), steering limit (degrees), half-width (in L).
ROBOT_LENGTH = (0.6, 2.0)
ROBOT_STEER_DEG = (30.0, 60.0)
ROBOT_HALF_WIDTH = (0.25, 0.4)
#: Large sites: least distance (m) between the start's and the goal's blocks' centres.
SITE_MIN_DISTANCE = 30.0
#: Start and goal draws per layout, layouts per floor.
POSE_TRIES = 400
LAYOUT_TRIES = 20

_ROOT_SEED = 25  # the number: every floor of this module descends from it
_DIGITS = fl.DIGITS  # coordinates rounded to a micrometre, headings to a microradian


def _rng(*key: int) -> np.random.Generator:
    return np.random.default_rng([_ROOT_SEED, GENERATOR_VERSION, *key])


def _check_kind(kind) -> str:
    if kind not in FLOOR_KINDS:
        raise ValueError(f"kind must be one of {FLOOR_KINDS}, got {kind!r}")
    return kind


def turn_excursion(robot: Robot) -> float:
    """How far ahead the front wheel B goes while A turns a quarter circle of radius ``R``.

    B circles the turn's centre at ``hypot(L, R)``; it starts ``L`` ahead of the line
    through the centre across the heading, so its largest advance is ``hypot(L, R) - L``
    (``0.414 L`` for ``R = L``). A robot facing a wide wall closer than this in the model
    cannot turn away from it.
    """
    if not isinstance(robot, Robot):
        raise ValueError(f"robot must be a segplan.Robot, got {type(robot).__name__}")
    return math.hypot(robot.L, robot.min_turning_radius) - robot.L


# -- poses -----------------------------------------------------------------------------------
Pose3 = tuple[float, float, float]


def _pose(x: float, y: float, theta: float) -> Pose3:
    return (round(float(x), _DIGITS), round(float(y), _DIGITS), round(wrap_scalar(float(theta)), _DIGITS))


def _shift(pose: Pose3, d: float) -> Pose3:
    """``pose`` moved ``d`` along its heading."""
    x, y, th = pose
    return (x + d * math.cos(th), y + d * math.sin(th), th)


def _toward(rng: np.random.Generator, a, b, spread: float) -> float:
    return math.atan2(b[1] - a[1], b[0] - a[0]) + rng.uniform(-spread, spread)


def _pick(rng: np.random.Generator, items, weights=None):
    if weights is None:
        return items[int(rng.integers(len(items)))]
    w = np.asarray(weights, dtype=float)
    return items[int(rng.choice(len(items), p=w / w.sum()))]


def _free_test(obstacles, bounds, robot: Robot) -> _FreeTest:
    """The scenario's pose test before the scenario exists (non-convex obstacles split as
    :func:`segplan.make_scenario` splits them)."""
    return _FreeTest([q for p in obstacles for q in decompose(p)[1]], bounds, robot)


def _on_lane(rng: np.random.Generator, lane: fl.Lane, robot: Robot) -> Pose3:
    """A pose centred on ``lane`` within half its spare width, heading along it either way."""
    t = rng.random()
    px, py = lane.x0 + t * (lane.x1 - lane.x0), lane.y0 + t * (lane.y1 - lane.y0)
    along = math.atan2(lane.y1 - lane.y0, lane.x1 - lane.x0) + (math.pi if rng.random() < 0.5 else 0.0)
    spare = max(0.0, 0.5 * lane.width - robot.half_width - 0.1)
    off = rng.uniform(-0.5, 0.5) * spare
    px, py = px - off * math.sin(along), py + off * math.cos(along)
    return _pose(px - 0.5 * robot.L * math.cos(along), py - 0.5 * robot.L * math.sin(along), along)


def _facing(rng: np.random.Generator, free, face: fl.Face, robot: Robot, gap: float) -> Pose3 | None:
    """A pose facing ``face``, its front wheel ``gap`` beyond the first free place on the ray
    out of the face (model; found in steps of L / 20 up to 4 L, then bisected to L / 100:
    the pose ``gap + L / 100`` further ahead collides), or None."""
    t = rng.random()
    px, py = face.x0 + t * (face.x1 - face.x0), face.y0 + t * (face.y1 - face.y0)
    phi = rng.uniform(0.0, TWO_PI) if face.phi is None else face.phi
    ux, uy, L = math.cos(phi), math.sin(phi), robot.L

    def at(rho: float) -> Pose3:  # the front wheel rho out of the face
        return (px + (rho + L) * ux, py + (rho + L) * uy, phi + math.pi)

    return _off_face(free, at, L, gap)


def _off_face(free, at: Callable[[float], Pose3], L: float, gap: float) -> Pose3 | None:
    """``at(hi + gap)`` where ``hi`` is the first free place of ``at`` on the ray out of a face
    (steps of L / 20 up to 4 L, then bisected to L / 100; ``at(0)`` touches the face), if that
    pose is free; else None."""
    lo = 0.0
    for i in range(1, 81):
        if free(at(0.05 * i * L)):
            hi = 0.05 * i * L
            break
        lo = 0.05 * i * L
    else:
        return None
    while hi - lo > 0.01 * L:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if free(at(mid)) else (mid, hi)
    pose = _pose(*at(hi + gap))
    return pose if free(pose) else None


def _turns_away(free, pose: Pose3, robot: Robot, steps: int = 24) -> bool:
    """Does a quarter circle of radius ``R`` to the left or to the right from ``pose`` stay
    free (poses every ``pi R / (2 steps)`` of A's arc)?"""
    x, y, th = pose
    R = robot.min_turning_radius
    psi = np.linspace(0.0, 0.5 * math.pi, steps + 1)[1:]
    ux, uy = math.cos(th), math.sin(th)
    for side in (1.0, -1.0):
        ax = x + R * (np.sin(psi) * ux - side * (1.0 - np.cos(psi)) * uy)
        ay = y + R * (np.sin(psi) * uy + side * (1.0 - np.cos(psi)) * ux)
        if all(free((a, b, th + side * p)) for a, b, p in zip(ax, ay, psi, strict=True)):
            return True
    return False


def _tight_start(rng, free, faces, robot: Robot, notes: list[str], what: str) -> Pose3 | None:
    """A start facing one of ``faces`` close ahead, from which a quarter turn at the smallest
    radius to one side stays free (module docstring), or None."""
    if not faces:
        return None
    gap = turn_excursion(robot) + rng.uniform(*TIGHT_MARGIN) * robot.L
    s = _facing(rng, free, _pick(rng, faces), robot, gap)
    if s is None or not _turns_away(free, s, robot):
        return None
    notes.append(f"tight start: facing {what}, front wheel {gap:.2f} m from it (model)")
    return s


def _inside(point, box, margin: float = 0.0) -> bool:
    x0, y0, x1, y1 = box
    return x0 - margin <= point[0] <= x1 + margin and y0 - margin <= point[1] <= y1 + margin


def _in_room(rng: np.random.Generator, room: fl.Room, robot: Robot, arriving: bool) -> Pose3 | None:
    """A pose in ``room``, its middle at least ``R + L`` from a door and heading to it
    (``arriving``: away from it), or None."""
    x0, y0, x1, y1 = room.box
    m = robot.half_width + 0.1
    a = (rng.uniform(x0 + m, x1 - m), rng.uniform(y0 + m, y1 - m))
    door = _pick(rng, room.doors)
    if math.dist(a, door) < robot.min_turning_radius + robot.L:
        return None
    th = _toward(rng, door, a, DOOR_SPREAD) if arriving else _toward(rng, a, door, DOOR_SPREAD)
    return _pose(a[0] - 0.5 * robot.L * math.cos(th), a[1] - 0.5 * robot.L * math.sin(th), th)


# -- start and goal of each kind -------------------------------------------------------------
def _warehouse_pair(rng, free, layout: fl.Layout, robot: Robot, tight: bool, across: bool, notes):
    """A start and a goal among a warehouse's aisles (tight start; goal across an aisle)."""
    lanes = layout.lanes
    weights = [math.hypot(ln.x1 - ln.x0, ln.y1 - ln.y0) for ln in lanes]
    if tight:
        s = _tight_start(rng, free, layout.faces, robot, notes, "a rack across the aisle")
    else:
        s = _on_lane(rng, _pick(rng, lanes, weights), robot)
    if not across:
        return s, _on_lane(rng, _pick(rng, lanes, weights), robot)
    # nose to a rack, with room behind to arrive on the smallest circle (or None: draw again)
    g = _facing(rng, free, _pick(rng, layout.faces), robot, fl.uniform_cm(rng, 0.1, 0.3) * robot.L)
    if g is None or not free(_shift(g, -(robot.min_turning_radius + 0.05 * robot.L))):
        return s, None
    notes.append("goal across an aisle, nose to a rack")
    return s, g


def _rooms_pair(rng, free, layout: fl.Layout, robot: Robot, tight: bool, notes):
    """A start and a goal in two different rooms (tight: facing a wall or furniture of its room)."""
    i, j = rng.choice(len(layout.rooms), 2, replace=False)
    room = layout.rooms[i]
    if tight:
        faces = [
            f for f in layout.faces if _inside((0.5 * (f.x0 + f.x1), 0.5 * (f.y0 + f.y1)), room.box, 0.3)
        ]
        s = _tight_start(rng, free, faces, robot, notes, "a wall or furniture")
        if s is not None and not _inside(s, room.box):
            s = None
    else:
        s = _in_room(rng, room, robot, arriving=False)
    return s, _in_room(rng, layout.rooms[j], robot, arriving=True)


class _Draw(NamedTuple):
    """A kind's floor before it is a scenario."""

    robot: Robot
    bounds: tuple[float, float, float, float]
    obstacles: list[np.ndarray]
    start: Pose3
    goal: Pose3
    notes: list[str]


def _pairs(rng, free, draw_pair: Callable, ok: Callable[[Pose3, Pose3], bool]):
    """Up to :data:`POSE_TRIES` draws of ``draw_pair(notes) -> (start, goal)``: the first
    free pair that ``ok`` accepts and its notes, or None."""
    for _ in range(POSE_TRIES):
        notes: list[str] = []
        s, g = draw_pair(notes)
        if s is not None and g is not None and free(s) and free(g) and ok(s, g):
            return s, g, notes
    return None


def _build_warehouse(rng: np.random.Generator) -> _Draw | None:
    bounds = fl.WAREHOUSE_BOUNDS
    layout = fl.warehouse_layout(rng, bounds, dead_end=rng.random() < DEAD_END_SHARE)
    free = _free_test(layout.obstacles, bounds, ROBOT)
    tight, across = rng.random() < TIGHT_SHARE, rng.random() < ACROSS_GOAL_SHARE
    got = _pairs(
        rng,
        free,
        lambda notes: _warehouse_pair(rng, free, layout, ROBOT, tight, across, notes),
        lambda s, g: math.dist(s[:2], g[:2]) >= MIN_DISTANCE,
    )
    return (
        None if got is None else _Draw(ROBOT, bounds, layout.obstacles, got[0], got[1], layout.notes + got[2])
    )


def _build_rooms(rng: np.random.Generator) -> _Draw | None:
    bounds = fl.ROOMS_BOUNDS
    layout = fl.rooms_layout(rng, bounds)
    free = _free_test(layout.obstacles, bounds, ROBOT)
    tight = rng.random() < TIGHT_SHARE
    got = _pairs(
        rng,
        free,
        lambda notes: _rooms_pair(rng, free, layout, ROBOT, tight, notes),
        lambda s, g: math.dist(s[:2], g[:2]) >= 0.5 * MIN_DISTANCE,
    )
    return (
        None if got is None else _Draw(ROBOT, bounds, layout.obstacles, got[0], got[1], layout.notes + got[2])
    )


def _build_parking(rng: np.random.Generator) -> _Draw | None:
    lot = fl.parking_layout(rng)
    layout, bounds, far = lot.layout, lot.bounds, lot.far
    free = _free_test(layout.obstacles, bounds, ROBOT)
    g = _facing(rng, free, lot.bay, ROBOT, fl.uniform_cm(rng, 0.1, 0.3) * ROBOT.L)
    if g is None:
        return None
    tight = rng.random() < TIGHT_SHARE
    W = bounds[2]
    cars = [f for f in layout.faces if far[0] <= f.x0 <= far[1]]

    def draw_pair(notes):
        if tight:
            return _tight_start(rng, free, cars, ROBOT, notes, "a parked car across the aisle"), g
        return _across_lot(rng, lot, ROBOT), g

    got = _pairs(rng, free, draw_pair, lambda s, g: math.dist(s[:2], g[:2]) >= W / 3)
    if got is None:
        return None
    return _Draw(ROBOT, bounds, layout.obstacles, got[0], got[1], [*layout.notes, "goal nose-in", *got[2]])


def _across_lot(rng: np.random.Generator, lot: fl.Lot, robot: Robot) -> Pose3:
    """A start across a lot from its free bay: in the third of the lot farthest from the bay,
    on the drive aisle or in an end zone, heading along it within 20 degrees, either way."""
    layout, (_, _, W, H), far = lot.layout, lot.bounds, lot.far
    aisle, ends = layout.lanes[0], layout.lanes[1:]
    x = rng.uniform(*far)
    in_end = x < ends[0].width or x > W - ends[1].width
    spare = 0.5 * aisle.width - robot.half_width - 0.1
    y = rng.uniform(0.0, H) if in_end else aisle.y0 + rng.uniform(-0.5, 0.5) * spare
    th = 0.5 * math.pi if in_end and rng.random() < 0.5 else 0.0
    th += (math.pi if rng.random() < 0.5 else 0.0) + rng.uniform(-1.0, 1.0) * math.radians(20.0)
    return _pose(x, y, th)


def _build_clutter(rng: np.random.Generator, robot: Robot = ROBOT, scale: float = 1.0) -> _Draw | None:
    layout = fl.clutter_layout(rng, scale)
    bounds = (0.0, 0.0, round(fl.CLUTTER_BOUNDS[2] * scale, 2), round(fl.CLUTTER_BOUNDS[3] * scale, 2))
    free = _free_test(layout.obstacles, bounds, robot)
    tight = rng.random() < TIGHT_SHARE
    m = robot.half_width + 0.05 * scale

    def draw_pair(notes):
        a = (rng.uniform(m, bounds[2] - m), rng.uniform(m, bounds[3] - m))
        b = (rng.uniform(m, bounds[2] - m), rng.uniform(m, bounds[3] - m))
        if tight:
            s = _tight_start(rng, free, layout.faces, robot, notes, "an obstacle")
            a = s[:2] if s is not None else a
        else:
            s = _pose(*a, _toward(rng, a, b, NATURAL_SPREAD))
        return s, _pose(*b, _toward(rng, a, b, NATURAL_SPREAD))

    got = _pairs(rng, free, draw_pair, lambda s, g: math.dist(s[:2], g[:2]) >= MIN_DISTANCE * scale)
    return (
        None if got is None else _Draw(robot, bounds, layout.obstacles, got[0], got[1], layout.notes + got[2])
    )


def _robot(rng: np.random.Generator) -> Robot:
    L = fl.uniform_cm(rng, *ROBOT_LENGTH)
    steer = round(rng.uniform(*ROBOT_STEER_DEG), 1)
    return Robot(L=L, half_width=round(rng.uniform(*ROBOT_HALF_WIDTH) * L, 3), max_steer=math.radians(steer))


def _build_large(rng: np.random.Generator) -> _Draw | None:
    site = fl.site_layout(rng)
    free = _free_test(site.layout.obstacles, site.bounds, ROBOT)
    tight = rng.random() < TIGHT_SHARE

    def draw_pair(notes):
        i, j = rng.choice(len(site.blocks), 2, replace=False)
        a, b = site.blocks[i], site.blocks[j]
        if math.dist(a.centre, b.centre) < SITE_MIN_DISTANCE:
            return None, None
        notes.append(f"start in a {a.kind} block, goal in a {b.kind} block")
        pair = {"warehouse": _warehouse_pair, "rooms": _rooms_pair}
        if a.kind == "warehouse":
            s, _ = _warehouse_pair(rng, free, a.layout, ROBOT, tight, False, notes)
        else:
            s, _ = _rooms_pair(rng, free, a.layout, ROBOT, tight, notes)
        args = (False, False) if b.kind == "warehouse" else (False,)
        _, g = pair[b.kind](rng, free, b.layout, ROBOT, *args, [])
        return s, g

    got = _pairs(rng, free, draw_pair, lambda s, g: True)
    if got is None:
        return None
    return _Draw(ROBOT, site.bounds, site.layout.obstacles, got[0], got[1], site.layout.notes + got[2])


_BUILDERS: dict[str, Callable[[np.random.Generator], _Draw | None]] = {
    "warehouse": _build_warehouse,
    "rooms": _build_rooms,
    "parking": _build_parking,
    "clutter": _build_clutter,
    "large": _build_large,
}


def kind_floor(kind: str, index: int) -> Scenario:
    """Floor ``index`` of ``kind`` (module docstring).

    Parameters
    ----------
    kind : {"warehouse", "rooms", "parking", "clutter", "robots", "large"}
    index : int
        ``>= 0``; the study uses ``0 .. N_PER_KIND - 1``.

    Returns
    -------
    Scenario
        Named ``f"{kind}-{index:03d}"``; its description names the generator and its
        version and says what was drawn (widths, counts, the robot, a tight start).

    Raises
    ------
    ValueError
        An unknown ``kind``, or an ``index`` that is not an integer >= 0.
    RuntimeError
        If :data:`LAYOUT_TRIES` layouts in a row had no free start and goal.
    """
    kind = _check_kind(kind)
    index = _check_index(index)
    rng = _rng(FLOOR_KINDS.index(kind), index)
    robot = _robot(rng) if kind == "robots" else ROBOT
    for _ in range(LAYOUT_TRIES):
        d = _build_clutter(rng, robot, robot.L) if kind == "robots" else _BUILDERS[kind](rng)
        if d is not None:
            break
    else:
        raise RuntimeError(
            f"{kind} floor {index}: no free start and goal in {LAYOUT_TRIES} layouts "
            f"(segplan.studies.floor_kinds v{GENERATOR_VERSION})"
        )
    notes = d.notes
    if kind == "robots":
        steer = math.degrees(robot.max_steer)
        notes = [
            f"robot L {robot.L:.2f} m, half-width {robot.half_width:.3f} m, steering {steer:.1f} deg",
            *notes,
        ]
    name = f"{kind}-{index:03d}"
    desc = f"{kind.capitalize()} floor {index} (segplan.studies.floor_kinds v{GENERATOR_VERSION}): "
    desc += "; ".join(notes) + "."
    return make_scenario(
        d.robot, d.start, d.goal, d.obstacles, d.bounds, name=name, description=desc, source=name
    )


def kind_floors(kind: str, n: int = N_PER_KIND) -> list[Scenario]:
    """The first ``n`` floors of ``kind`` (:func:`kind_floor`)."""
    kind = _check_kind(kind)
    return [kind_floor(kind, i) for i in range(_check_index(n, "n"))]


def stress_floor(index: int = 0, size: float = 1000.0, n_obstacles: int = 5000) -> Scenario:
    """The stress case: a ``size`` x ``size`` m site with ``n_obstacles`` rectangles, crossed.

    The square is cut into ``k x k`` cells (``k = ceil(sqrt(n))``: 71 cells of 14.1 m for
    the default); ``n`` of them, drawn, each hold an axis-aligned rectangle of sides
    0.2-0.6 of the cell within the cell's middle 80 %, so at least a fifth of a cell (2.8 m
    by default) separates two rectangles. Start in the bottom-left tenth, goal in the
    top-right tenth, each heading within 60 degrees of the direction to the other's A.

    Parameters
    ----------
    index : int
        Which site of that size and count (``>= 0``).
    size : float
        Side of the square (m), at least 50.
    n_obstacles : int
        Rectangles, at least 1 and at most ``(size / 5)^2`` (cells of 5 m or more).

    Returns
    -------
    Scenario
        For :data:`segplan.studies.floors.ROBOT`, named ``f"stress-{size:g}-{n}-{index}"``.
    """
    index = _check_index(index)
    if isinstance(size, bool) or not (isinstance(size, int | float) and math.isfinite(size) and size >= 50.0):
        raise ValueError(f"size must be a number >= 50 (m), got {size!r}")
    n = _check_index(n_obstacles, "n_obstacles")
    if not 1 <= n <= (size / 5.0) ** 2:
        raise ValueError(f"n_obstacles must be in [1, (size / 5)^2 = {(size / 5.0) ** 2:g}], got {n}")
    rng = _rng(len(FLOOR_KINDS), round(size * 1000), n, index)
    k = math.ceil(math.sqrt(n))
    cell = size / k
    obstacles = []
    for c in sorted(rng.choice(k * k, n, replace=False).tolist()):
        i, j = divmod(c, k)
        w, h = rng.uniform(0.2, 0.6, 2) * cell
        x = i * cell + 0.1 * cell + rng.uniform(0.0, 0.8 * cell - w)
        y = j * cell + 0.1 * cell + rng.uniform(0.0, 0.8 * cell - h)
        obstacles.append(fl.rectangle(x, y, x + w, y + h))
    bounds = (0.0, 0.0, float(size), float(size))
    free = _free_test(obstacles, bounds, ROBOT)

    def draw_pair(notes):
        a, b = rng.uniform(0.0, 0.1 * size, 2), size - rng.uniform(0.0, 0.1 * size, 2)
        return _pose(*a, _toward(rng, a, b, NATURAL_SPREAD)), _pose(*b, _toward(rng, a, b, NATURAL_SPREAD))

    got = _pairs(rng, free, draw_pair, lambda s, g: True)
    if got is None:  # pragma: no cover
        raise RuntimeError(f"stress floor {index}: no free start and goal in {POSE_TRIES} draws")
    name = f"stress-{size:g}-{n}-{index}"
    desc = f"Stress floor: {size:g} x {size:g} m, {n} rectangles, crossing {index} "
    desc += f"(segplan.studies.floor_kinds v{GENERATOR_VERSION})."
    return make_scenario(ROBOT, got[0], got[1], obstacles, bounds, name=name, description=desc, source=name)
