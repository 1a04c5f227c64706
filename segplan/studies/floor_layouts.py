"""The layouts of the floor kinds (issue 25; beyond the paper): where the racks, walls,
doors, furniture, parked cars and clutter of :mod:`segplan.studies.floor_kinds` stand.

A layout is obstacles and the places a robot is put among them: drive lanes
(:class:`Lane`: aisles, the parking lot's drive aisle), rooms with their doors
(:class:`Room`) and faces a robot can be made to face close ahead (:class:`Face`: a rack's
long side, a wall, a parked car's tail, a piece of clutter). Each function draws one
layout from the generator it is given; :mod:`segplan.studies.floor_kinds` seeds it, places
the robot and makes the scenario. Lengths in metres, drawn in whole centimetres
(:func:`uniform_cm`); polygon vertices rounded to a micrometre (:data:`DIGITS`).

Warehouse (:func:`warehouse_layout`, in a 30 x 18 m hall)
    Rack rows along x, each a back-to-back rack of depth :data:`RACK_DEPTH` (1.0-2.2 m),
    stacked from the bottom wall: a wall aisle, then rack, aisle, rack, ... while one more
    rack and a 2 m aisle fit (3-4 rows); the aisles between racks are :data:`AISLE_WIDTH`
    (2.0-3.2 m) wide, the aisle along the top wall takes what is left (2.0 m to about 7 m:
    a staging area). One straight cross aisle (:data:`CROSS_AISLE_WIDTH`, 2.6-3.6 m,
    centred in the middle 30-70 % of the racks) cuts every row in two; end aisles
    (:data:`END_AISLE_WIDTH`, 2.6-3.6 m) at both ends, or, for a dead-end layout, the racks
    reach one end wall.
    Lanes: every aisle, between racks and along the walls, the cross aisle, the end aisles.
    Faces: the racks' long sides.
Rooms (:func:`rooms_layout`, in a 20 x 12 m building)
    Six rooms (3 x 2) behind thin walls (:data:`WALL_THICKNESS`, 0.10-0.20 m; the inner
    walls within 1 m of the thirds and of the half). Each of the seven walls between two
    rooms has one door of :data:`DOOR_WIDTH` (1.2-2.0 m, at least ``2 * half_width +``
    :data:`DOOR_MARGIN` for the book's robot), at least :data:`DOOR_CORNER` = 1 m from the
    wall's ends. Each room holds :data:`FURNITURE` (0-3) axis-aligned pieces: tables and
    shelves (sides 0.4-2.0 m, three in five against a wall, the others at least 0.9 m from
    every wall) and, one in five, an L-shaped counter in a corner (arms 1.0-2.2 m, 0.5-0.7
    m deep; non-convex: segplan splits it); none within :data:`DOOR_CLEAR` = 1.2 m of a door
    (0.2 m to its sides), none closer than :data:`FURNITURE_GAP` = 0.1 m to another. Rooms:
    the six, with their doors. Faces: both sides of every wall part, every piece of furniture.
Parking lot (:func:`parking_layout`)
    Two rows of :data:`BAYS_PER_ROW` (10-16) bays of pitch :data:`BAY_PITCH` (1.0-1.3 m)
    along the bottom and top walls, a drive aisle (:data:`PARKING_AISLE`, 3.0-4.2 m) between
    them and end zones (:data:`END_ZONE`, 3.0-4.5 m) at both ends: 16-30 x 6.4-8.6 m.
    Every bay but one holds a parked car (:data:`CAR_LENGTH` 1.5-1.8 m by :data:`CAR_WIDTH`
    0.6-0.72 m, nose 0.05-0.25 m from the wall, shifted up to 4 cm along the row and turned
    up to 3 degrees, but never within 5 cm of its bay's sides), so the free bay is at least
    ``pitch + 0.1`` m wide between its neighbours. Lanes: the drive aisle and the end zones.
    Faces: the cars' tails (out into the aisle) and the wall at the back of the free bay.
Clutter (:func:`clutter_layout`, 20 x 12 m times a scale)
    :data:`CLUTTER_COUNT` (25-45) small obstacles at least :data:`CLUTTER_GAP` = 0.1 m apart
    (times the scale), strictly inside the walls: boxes (sides 0.3-1.0 m, any rotation; three
    in seven), cylinders (regular 6-8-gons of radius 0.15-0.5 m; three in seven) and small
    L-shapes (arms 0.6-1.2 m, 0.25-0.4 m thick; one in seven). Faces: every obstacle's
    centre, any direction out.
Large site (:func:`site_layout`)
    :data:`SITE_BLOCKS` x :data:`SITE_BLOCKS` (3-5 by 3-5) cells of :data:`SITE_CELL` (37 x
    25 m), so 111-185 m by 75-125 m, each holding, equally likely, a warehouse hall (the
    warehouse layout, no dead ends, inside walls 0.2 m thick with gates as wide as the
    aisles they open: one or two on each end wall, and each end of the cross aisle open
    half the time) or a rooms building (the rooms layout inside walls 0.2 m thick, with
    entrance doors of 1.6-2.0 m into two of its rooms), placed at random in its cell with
    roads of at least 6 m between the blocks' walls.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ..floor.geometry import enlarge_polygon
from ..floor.random_floors import place_disjoint
from ..model.pose import TWO_PI

__all__ = [
    "AISLE_WIDTH",
    "BAYS_PER_ROW",
    "BAY_PITCH",
    "Block",
    "CAR_LENGTH",
    "CAR_WIDTH",
    "CLUTTER_BOUNDS",
    "CLUTTER_COUNT",
    "CLUTTER_GAP",
    "CROSS_AISLE_WIDTH",
    "DIGITS",
    "DOOR_CLEAR",
    "DOOR_CORNER",
    "DOOR_MARGIN",
    "DOOR_WIDTH",
    "END_AISLE_WIDTH",
    "END_ZONE",
    "ENTRANCE_WIDTH",
    "FURNITURE",
    "FURNITURE_GAP",
    "Face",
    "Layout",
    "Lane",
    "Lot",
    "PARKING_AISLE",
    "RACK_DEPTH",
    "ROOMS_BOUNDS",
    "Room",
    "SITE_BLOCKS",
    "SITE_CELL",
    "SITE_WALL",
    "Site",
    "WALL_THICKNESS",
    "WAREHOUSE_BOUNDS",
    "clutter_layout",
    "parking_layout",
    "rectangle",
    "rooms_layout",
    "site_layout",
    "uniform_cm",
    "warehouse_layout",
]

#: Coordinates are rounded to this many decimals (a micrometre).
DIGITS = 6
#: Warehouse (m).
WAREHOUSE_BOUNDS = (0.0, 0.0, 30.0, 18.0)
AISLE_WIDTH = (2.0, 3.2)
RACK_DEPTH = (1.0, 2.2)
CROSS_AISLE_WIDTH = (2.6, 3.6)
END_AISLE_WIDTH = (2.6, 3.6)
#: Rooms (m). DOOR_MARGIN: a door is at least 2 * half_width + DOOR_MARGIN wide for the book's robot.
ROOMS_BOUNDS = (0.0, 0.0, 20.0, 12.0)
WALL_THICKNESS = (0.1, 0.2)
DOOR_WIDTH = (1.2, 2.0)
DOOR_MARGIN = 0.6
DOOR_CORNER = 1.0
DOOR_CLEAR = 1.2
FURNITURE = (0, 3)
FURNITURE_GAP = 0.1
#: Parking lot (m).
BAY_PITCH = (1.0, 1.3)
BAYS_PER_ROW = (10, 16)
CAR_LENGTH = (1.5, 1.8)
CAR_WIDTH = (0.6, 0.72)
PARKING_AISLE = (3.0, 4.2)
END_ZONE = (3.0, 4.5)
#: Clutter (m, at scale 1).
CLUTTER_BOUNDS = (0.0, 0.0, 20.0, 12.0)
CLUTTER_COUNT = (25, 45)
CLUTTER_GAP = 0.1
#: Large sites: blocks per side, a block's cell (m), its walls' thickness and entrance doors (m).
SITE_BLOCKS = (3, 5)
SITE_CELL = (37.0, 25.0)
SITE_WALL = 0.2
ENTRANCE_WIDTH = (1.6, 2.0)
_ROAD = 6.0  # least road between two blocks' walls (m)


def uniform_cm(rng: np.random.Generator, lo: float, hi: float) -> float:
    """A length uniform in ``[lo, hi]``, rounded to whole centimetres (so still in the range
    when its ends are)."""
    return round(rng.uniform(lo, hi), 2)


# -- the pieces of a layout ------------------------------------------------------------------
class Lane(NamedTuple):
    """An axis-aligned drive lane: its centre line from (x0, y0) to (x1, y1) and its width."""

    x0: float
    y0: float
    x1: float
    y1: float
    width: float


class Face(NamedTuple):
    """Where a robot may face an obstacle: a segment on it (a point where both ends agree)
    and the direction out of it (radians; None: any)."""

    x0: float
    y0: float
    x1: float
    y1: float
    phi: float | None


@dataclass
class Room:
    """A room's free box (between its walls' faces) and its doors' centres."""

    box: tuple[float, float, float, float]
    doors: list[tuple[float, float]] = field(default_factory=list)


@dataclass
class Layout:
    """Obstacles (``(k, 2)`` arrays, counter-clockwise or not) and the places among them;
    ``notes``: what was drawn, in words."""

    obstacles: list[np.ndarray] = field(default_factory=list)
    lanes: list[Lane] = field(default_factory=list)
    rooms: list[Room] = field(default_factory=list)
    faces: list[Face] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    def add(self, other: Layout) -> None:
        """Take in ``other``'s obstacles, lanes, rooms and faces (not its notes)."""
        for name in ("obstacles", "lanes", "rooms", "faces"):
            getattr(self, name).extend(getattr(other, name))


class Lot(NamedTuple):
    """A parking lot: its layout, bounds, the free bay's back wall (a :class:`Face`) and the
    x range of the third of the lot farthest from the free bay."""

    layout: Layout
    bounds: tuple[float, float, float, float]
    bay: Face
    far: tuple[float, float]


class Block(NamedTuple):
    """A block of a large site: ``"warehouse"`` or ``"rooms"``, its layout and its centre."""

    kind: str
    layout: Layout
    centre: tuple[float, float]


class Site(NamedTuple):
    """A large site: every block's obstacles in ``layout``, its bounds and its blocks."""

    layout: Layout
    bounds: tuple[float, float, float, float]
    blocks: list[Block]


def rectangle(x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
    """The axis-aligned rectangle ``[x0, x1] x [y0, y1]``, counter-clockwise, rounded."""
    return np.round(np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float), DIGITS)


def _wall(vertical: bool, at: float, t: float, lo: float, hi: float, openings=()) -> list[np.ndarray]:
    """The solid parts of a wall of thickness ``t`` centred on ``at`` (x if ``vertical``,
    else y) from ``lo`` to ``hi``, with ``openings`` ``(a, b)`` along it."""
    parts, cur = [], lo
    for a, b in sorted(openings):
        if a > cur:
            parts.append((cur, a))
        cur = max(cur, b)
    if hi > cur:
        parts.append((cur, hi))
    h = 0.5 * t
    return [
        rectangle(at - h, p, at + h, q) if vertical else rectangle(p, at - h, q, at + h) for p, q in parts
    ]


def _long_faces(box, inset: float) -> list[Face]:
    """The two long faces of a thin box (a wall part, a rack), ``inset`` from its ends."""
    x0, y0, x1, y1 = box
    if x1 - x0 >= y1 - y0:
        if x1 - x0 <= 2 * inset:
            return []
        return [
            Face(x0 + inset, y0, x1 - inset, y0, -0.5 * math.pi),
            Face(x0 + inset, y1, x1 - inset, y1, 0.5 * math.pi),
        ]
    if y1 - y0 <= 2 * inset:
        return []
    return [Face(x0, y0 + inset, x0, y1 - inset, math.pi), Face(x1, y0 + inset, x1, y1 - inset, 0.0)]


def _bbox(p: np.ndarray) -> tuple[float, float, float, float]:
    return (*p.min(axis=0).tolist(), *p.max(axis=0).tolist())


# -- warehouse -------------------------------------------------------------------------------
def warehouse_layout(rng: np.random.Generator, box, dead_end: bool) -> Layout:
    """Racks, aisles and a cross aisle filling ``box`` (module docstring).

    ``dead_end``: the racks reach the left or the right end of ``box`` (drawn), so their
    aisles are closed there. Lanes: every horizontal aisle piece beside the racks, the
    cross aisle, the end aisles; faces: the racks' long sides.
    """
    x0, y0, x1, y1 = box
    out = Layout()
    rows, y = [], y0 + uniform_cm(rng, *AISLE_WIDTH)  # the bottom wall aisle
    while True:
        d = uniform_cm(rng, *RACK_DEPTH)
        if y + d + AISLE_WIDTH[0] > y1:
            break
        rows.append((round(y, 2), round(y + d, 2)))
        y += d + uniform_cm(rng, *AISLE_WIDTH)
    left, right = uniform_cm(rng, *END_AISLE_WIDTH), uniform_cm(rng, *END_AISLE_WIDTH)
    side = "none"
    if dead_end:
        side = "left" if rng.random() < 0.5 else "right"
        left, right = (0.0, right) if side == "left" else (left, 0.0)
    rx0, rx1 = round(x0 + left, 2), round(x1 - right, 2)
    cw = uniform_cm(rng, *CROSS_AISLE_WIDTH)
    c = round(rx0 + rng.uniform(0.3, 0.7) * (rx1 - rx0), 2)
    spans = [(rx0, round(c - 0.5 * cw, 2)), (round(c + 0.5 * cw, 2), rx1)]
    for ra, rb in rows:
        for sa, sb in spans:
            out.obstacles.append(rectangle(sa, ra, sb, rb))
            out.faces += _long_faces((sa, ra, sb, rb), 0.5)
    edges = [y0, *[v for r in rows for v in r], y1]  # aisle bands: (edges[2k], edges[2k + 1])
    for k in range(0, len(edges), 2):
        a, b = edges[k], edges[k + 1]
        for sa, sb in spans:
            out.lanes.append(Lane(sa, 0.5 * (a + b), sb, 0.5 * (a + b), b - a))
    out.lanes.append(Lane(c, y0, c, y1, cw))
    for w, x in ((left, x0 + 0.5 * left), (right, x1 - 0.5 * right)):
        if w > 0:
            out.lanes.append(Lane(x, y0, x, y1, w))
    widths = [edges[k + 1] - edges[k] for k in range(2, len(edges) - 2, 2)]
    out.notes.append(
        f"{len(rows)} rack rows, aisles {min(widths, default=0):.2f}-{max(widths, default=0):.2f} m, "
        f"cross aisle {cw:.2f} m" + ("" if side == "none" else f", racks against the {side} wall")
    )
    return out


# -- rooms -----------------------------------------------------------------------------------
def _door(rng: np.random.Generator, lo: float, hi: float, width=DOOR_WIDTH) -> tuple[float, float]:
    w = uniform_cm(rng, *width)
    a = round(rng.uniform(lo + DOOR_CORNER, hi - DOOR_CORNER - w), 2)
    return a, round(a + w, 2)


def _overlaps(a, b, gap: float = 0.0) -> bool:
    return a[0] < b[2] + gap and b[0] < a[2] + gap and a[1] < b[3] + gap and b[1] < a[3] + gap


def _furniture(rng: np.random.Generator, room, keep_out: list) -> tuple[list[np.ndarray], list]:
    """0-3 axis-aligned pieces in ``room`` (its free box), clear of the ``keep_out`` boxes."""
    x0, y0, x1, y1 = room
    placed, boxes = [], []
    for _ in range(int(rng.integers(FURNITURE[0], FURNITURE[1] + 1))):
        for _ in range(50):
            if rng.random() < 0.2:  # an L-shaped counter in a corner
                a, b, d = uniform_cm(rng, 1.2, 2.2), uniform_cm(rng, 1.0, 1.8), uniform_cm(rng, 0.5, 0.7)
                sx, sy = (1, 1) if rng.random() < 0.5 else (-1, 1)
                sy = sy if rng.random() < 0.5 else -sy
                cx = x0 + 0.02 if sx > 0 else x1 - 0.02
                cy = y0 + 0.02 if sy > 0 else y1 - 0.02
                local = [(0, 0), (a, 0), (a, d), (d, d), (d, b), (0, b)]
                poly = np.array([(cx + sx * u, cy + sy * v) for u, v in local])
                if sx * sy < 0:
                    poly = poly[::-1]
                parts = [_bbox(np.array([(cx, cy), (cx + sx * a, cy + sy * d)])),
                         _bbox(np.array([(cx, cy), (cx + sx * d, cy + sy * b)]))]  # fmt: skip
            else:
                w, h = uniform_cm(rng, 0.6, 2.0), uniform_cm(rng, 0.4, 1.2)
                if rng.random() < 0.5:
                    w, h = h, w
                if rng.random() < 0.6:  # against a wall
                    side = int(rng.integers(4))
                    px = rng.uniform(x0, x1 - w) if side < 2 else (x0 + 0.02 if side == 2 else x1 - 0.02 - w)
                    py = rng.uniform(y0, y1 - h) if side >= 2 else (y0 + 0.02 if side == 0 else y1 - 0.02 - h)
                else:
                    px, py = rng.uniform(x0 + 0.9, x1 - 0.9 - w), rng.uniform(y0 + 0.9, y1 - 0.9 - h)
                px, py = round(px, 2), round(py, 2)
                parts = [(px, py, px + w, py + h)]
                poly = rectangle(*parts[0])
            if any(
                p[0] < x0 or p[1] < y0 or p[2] > x1 or p[3] > y1 or any(_overlaps(p, k) for k in keep_out)
                for p in parts
            ):
                continue
            if any(_overlaps(p, q, FURNITURE_GAP) for p in parts for q in boxes):
                continue
            placed.append(np.round(poly, DIGITS))
            boxes.extend(parts)
            break
    return placed, boxes


def rooms_layout(rng: np.random.Generator, box) -> Layout:
    """Six rooms with doors and furniture filling ``box`` (module docstring); ``box``'s
    edges are the outer walls' inner faces (the floor's bounds, or a building's walls)."""
    x0, y0, x1, y1 = box
    W, H = x1 - x0, y1 - y0
    out = Layout()
    t = uniform_cm(rng, *WALL_THICKNESS)
    xs = [round(x0 + W / 3 + rng.uniform(-1, 1), 2), round(x0 + 2 * W / 3 + rng.uniform(-1, 1), 2)]
    ym = round(y0 + H / 2 + rng.uniform(-1, 1), 2)
    h = 0.5 * t
    cols = [(x0, xs[0] - h), (xs[0] + h, xs[1] - h), (xs[1] + h, x1)]
    rows = [(y0, ym - h), (ym + h, y1)]
    rooms = {
        (r, c): Room((cols[c][0], rows[r][0], cols[c][1], rows[r][1])) for r in range(2) for c in range(3)
    }
    zones: list[tuple] = []
    widths = []
    for j, x in enumerate(xs):  # the two vertical walls: a door to each row's next room
        doors = [_door(rng, *rows[r]) for r in range(2)]
        out.obstacles += _wall(True, x, t, y0, y1, doors)
        for r, (a, b) in enumerate(doors):
            for c in (j, j + 1):
                rooms[r, c].doors.append((x, 0.5 * (a + b)))
            zones.append((x - h - DOOR_CLEAR, a - 0.2, x + h + DOOR_CLEAR, b + 0.2))
            widths.append(b - a)
    for c, (ca, cb) in enumerate(cols):  # the horizontal wall: a door per column
        a, b = _door(rng, ca, cb)
        out.obstacles += _wall(False, ym, t, ca, cb, [(a, b)])
        for r in range(2):
            rooms[r, c].doors.append((0.5 * (a + b), ym))
        zones.append((a - 0.2, ym - h - DOOR_CLEAR, b + 0.2, ym + h + DOOR_CLEAR))
        widths.append(b - a)
    for p in out.obstacles:
        out.faces += _long_faces(_bbox(p), 0.6)
    n = 0
    for room in rooms.values():
        pieces, boxes = _furniture(rng, room.box, zones)
        out.obstacles += pieces
        n += len(pieces)
        out.faces += [
            Face(0.5 * (b[0] + b[2]), 0.5 * (b[1] + b[3]), 0.5 * (b[0] + b[2]), 0.5 * (b[1] + b[3]), None)
            for b in boxes
        ]
    out.rooms = list(rooms.values())
    out.notes.append(f"walls {t:.2f} m, doors {min(widths):.2f}-{max(widths):.2f} m, {n} pieces of furniture")
    return out


# -- parking ---------------------------------------------------------------------------------
def parking_layout(rng: np.random.Generator) -> Lot:
    """A parking lot with one free bay (module docstring).

    Returns
    -------
    Lot
        Its bounds are the lot's walls, ``(0, 0, W, H)``; ``bay`` is the point of the
        wall at the back of the free bay (5 cm or less off the bay's centre line) with the
        direction into the lot.
    """
    out = Layout()
    pitch, n = uniform_cm(rng, *BAY_PITCH), int(rng.integers(BAYS_PER_ROW[0], BAYS_PER_ROW[1] + 1))
    cl, cw = uniform_cm(rng, *CAR_LENGTH), uniform_cm(rng, *CAR_WIDTH)
    depth = round(cl + uniform_cm(rng, 0.2, 0.4), 2)
    aisle, ez = uniform_cm(rng, *PARKING_AISLE), uniform_cm(rng, *END_ZONE)
    W, H = round(2 * ez + n * pitch, 2), round(2 * depth + aisle, 2)
    free_row, free_bay = int(rng.integers(2)), int(rng.integers(n))
    for row in range(2):
        for k in range(n):
            if (row, k) == (free_row, free_bay):
                continue
            nose = uniform_cm(rng, 0.05, 0.25)
            cx = ez + (k + 0.5) * pitch + rng.uniform(-0.04, 0.04)
            cy = nose + 0.5 * cl if row == 0 else H - nose - 0.5 * cl
            a = math.radians(rng.uniform(-3.0, 3.0))
            if 0.5 * cw * math.cos(a) + 0.5 * cl * abs(math.sin(a)) + 0.04 > 0.5 * pitch - 0.05:
                a = 0.0  # keep neighbours apart
            cs, sn = math.cos(a), math.sin(a)
            local = 0.5 * np.array([[-cw, -cl], [cw, -cl], [cw, cl], [-cw, cl]])
            out.obstacles.append(np.round((cx, cy) + local @ np.array([[cs, sn], [-sn, cs]]), DIGITS))
            out.faces.append(Face(cx, cy, cx, cy, 0.5 * math.pi if row == 0 else -0.5 * math.pi))
    bx = ez + (free_bay + 0.5) * pitch + rng.uniform(-0.05, 0.05)
    wall = (bx, 0.0, bx, 0.0, 0.5 * math.pi) if free_row == 0 else (bx, H, bx, H, -0.5 * math.pi)
    out.lanes = [Lane(0.0, depth + 0.5 * aisle, W, depth + 0.5 * aisle, aisle)]
    out.lanes += [Lane(0.5 * ez, 0.0, 0.5 * ez, H, ez), Lane(W - 0.5 * ez, 0.0, W - 0.5 * ez, H, ez)]
    far = (round(W * 2 / 3, 2), W) if bx < 0.5 * W else (0.0, round(W / 3, 2))
    out.notes.append(
        f"{n} bays of {pitch:.2f} m a row, cars {cl:.2f} x {cw:.2f} m, aisle {aisle:.2f} m, "
        f"free bay {free_bay} of the {'bottom' if free_row == 0 else 'top'} row"
    )
    return Lot(out, (0.0, 0.0, W, H), Face(*wall), far)


# -- clutter ---------------------------------------------------------------------------------
def clutter_layout(rng: np.random.Generator, scale: float = 1.0) -> Layout:
    """25-45 small obstacles in ``(0, 0, 20 scale, 12 scale)`` (module docstring), every
    length times ``scale``."""
    out = Layout()
    W, H = CLUTTER_BOUNDS[2] * scale, CLUTTER_BOUNDS[3] * scale
    n = int(rng.integers(CLUTTER_COUNT[0], CLUTTER_COUNT[1] + 1))

    def draw():
        c = np.array((rng.uniform(0, W), rng.uniform(0, H)))
        rot = rng.uniform(0.0, TWO_PI)
        u = rng.random()
        if u < 1 / 7:  # a small L
            a, b, d = rng.uniform(0.6, 1.2), rng.uniform(0.6, 1.2), rng.uniform(0.25, 0.4)
            local = np.array([(0, 0), (a, 0), (a, d), (d, d), (d, b), (0, b)]) - (0.5 * a, 0.5 * b)
            hull = np.array([(0, 0), (a, 0), (a, b), (0, b)]) - (0.5 * a, 0.5 * b)
        elif u < 4 / 7:  # a box
            w, h = rng.uniform(0.3, 1.0, 2)
            local = hull = 0.5 * np.array([[-w, -h], [w, -h], [w, h], [-w, h]])
        else:  # a cylinder
            k = int(rng.integers(6, 9))
            ang = np.arange(k) * (TWO_PI / k)
            local = hull = rng.uniform(0.15, 0.5) * np.column_stack((np.cos(ang), np.sin(ang)))
        turn = np.array([[math.cos(rot), math.sin(rot)], [-math.sin(rot), math.cos(rot)]])
        poly = np.round(scale * (c + local @ turn), DIGITS)
        lo, hi = poly.min(axis=0), poly.max(axis=0)
        if lo[0] <= 0 or lo[1] <= 0 or hi[0] >= W or hi[1] >= H:
            return None
        return poly, enlarge_polygon(scale * (c + hull @ turn), 0.5 * CLUTTER_GAP * scale)

    out.obstacles = place_disjoint(draw, n, 200 * n)
    if len(out.obstacles) < n:  # pragma: no cover
        raise RuntimeError(f"placed only {len(out.obstacles)} of {n} obstacles")
    out.faces = [Face(*p.mean(axis=0), *p.mean(axis=0), None) for p in out.obstacles]
    out.notes.append(f"{n} obstacles")
    return out


# -- large sites -----------------------------------------------------------------------------
def site_layout(rng: np.random.Generator) -> Site:
    """A large site of warehouse halls and rooms buildings (module docstring).

    Returns
    -------
    Site
        ``layout`` holds every block's obstacles (walls included), lanes, rooms and faces;
        each :class:`Block` its own, to place a start in one block and a goal in another.
    """
    nx, ny = (int(rng.integers(SITE_BLOCKS[0], SITE_BLOCKS[1] + 1)) for _ in range(2))
    cx, cy = SITE_CELL
    site, blocks = Layout(), []
    t = SITE_WALL
    for i in range(nx):
        for j in range(ny):
            kind = "warehouse" if rng.random() < 0.5 else "rooms"
            size = WAREHOUSE_BOUNDS[2:] if kind == "warehouse" else ROOMS_BOUNDS[2:]
            slack = (cx - size[0] - 2 * t - _ROAD, cy - size[1] - 2 * t - _ROAD)
            ox = round(i * cx + 0.5 * _ROAD + t + rng.uniform(0, slack[0]), 2)
            oy = round(j * cy + 0.5 * _ROAD + t + rng.uniform(0, slack[1]), 2)
            box = (ox, oy, ox + size[0], oy + size[1])
            if kind == "warehouse":
                block = warehouse_layout(rng, box, dead_end=False)
                bands = sorted(
                    {(ln.y0 - 0.5 * ln.width, ln.y0 + 0.5 * ln.width) for ln in block.lanes if ln.y0 == ln.y1}
                )
                gates: dict[str, list] = {"left": [], "right": [], "bottom": [], "top": []}
                for side in ("left", "right"):  # one or two aisles open on each end wall
                    for k in rng.choice(len(bands), int(rng.integers(1, 3)), replace=False):
                        gates[side].append(bands[k])
                cross = next(ln for ln in block.lanes if ln.x0 == ln.x1)
                for side in ("bottom", "top"):
                    if rng.random() < 0.5:
                        gates[side].append((cross.x0 - 0.5 * cross.width, cross.x0 + 0.5 * cross.width))
            else:
                block = rooms_layout(rng, box)
                gates = {"left": [], "right": [], "bottom": [], "top": []}
                for k in rng.choice(len(block.rooms), 2, replace=False):
                    room = block.rooms[k]
                    rx0, ry0, rx1, ry1 = room.box
                    sides = [
                        s
                        for s, ok in (
                            ("left", rx0 == ox),
                            ("right", rx1 == box[2]),
                            ("bottom", ry0 == oy),
                            ("top", ry1 == box[3]),
                        )
                        if ok
                    ]
                    side = sides[int(rng.integers(len(sides)))]
                    lo, hi = (ry0, ry1) if side in ("left", "right") else (rx0, rx1)
                    a, b = _door(rng, lo, hi, ENTRANCE_WIDTH)
                    gates[side].append((a, b))
                    at = {"left": ox, "right": box[2], "bottom": oy, "top": box[3]}[side]
                    room.doors.append(
                        (at, 0.5 * (a + b)) if side in ("left", "right") else (0.5 * (a + b), at)
                    )
            walls = _wall(True, ox - 0.5 * t, t, oy - t, box[3] + t, gates["left"])
            walls += _wall(True, box[2] + 0.5 * t, t, oy - t, box[3] + t, gates["right"])
            walls += _wall(False, oy - 0.5 * t, t, ox, box[2], gates["bottom"])
            walls += _wall(False, box[3] + 0.5 * t, t, ox, box[2], gates["top"])
            block.obstacles += walls
            site.add(block)
            blocks.append(Block(kind, block, (0.5 * (ox + box[2]), 0.5 * (oy + box[3]))))
    site.notes.append(f"{nx} x {ny} blocks, {len(site.obstacles)} obstacles")
    return Site(site, (0.0, 0.0, round(nx * cx, 2), round(ny * cy, 2)), blocks)
