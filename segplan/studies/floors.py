"""Random and hard floors for the robustness study (issue 12; beyond the paper).

The paper shows its planner on two floors (Figs. 5 and 6). The robustness study asks how
often a planner solves a *random* floor, and how it fares on the cases a user meets first:
a start facing a wall, a narrow door, a goal that cannot be reached, a floor eight times
larger. This module makes those floors, deterministically (a floor is a function of its
kind and index; numbers are rounded to a micrometre so that a floor, and
:func:`floor_key`, do not depend on the last bit of the machine's trigonometry).

Every floor is for the same robot, :data:`ROBOT`: ``L = 1 m``, half-width 0.3 m, steering
limit 45 degrees (minimum turning radius of A ``R = L / tan(45 deg) = 1 m``), forward only.

Random floors (:func:`random_floor`)
------------------------------------
A 20 x 12 m room (:data:`SMALL_BOUNDS`) with 4 to 9 convex obstacles, each a rectangle
(sides 0.5-3 m) or a regular polygon (3-8 vertices, circumradius 0.4-1.5 m), at any
rotation, inside the walls, not overlapping one another (they may nearly touch, which
closes passages in the planning model). Then a start and a goal: uniform positions of A in
the free bounds, free poses (the segment clear of every enlarged obstacle and strictly
inside the walls shrunk by the half-width), A at least :data:`MIN_DISTANCE` = 6 m apart.
Headings by *kind* (:data:`KINDS`):

- ``"any"``: start and goal headings uniform over the circle;
- ``"natural"``: each within :data:`NATURAL_SPREAD` = 60 degrees of the direction from
  the start's A to the goal's A (the paper's natural case).

:data:`N_FLOORS` = 200 floors of each kind, indices ``0..199``; names ``"any-007"``.

Large floors (:func:`large_floor`, :func:`sweep_floor`)
-------------------------------------------------------
The same obstacles at the same density on a room scaled by ``s``: ``20 s x 12 s`` m with
``round(8 s^2)`` obstacles (``s = 8``: 160 x 96 m, 512 obstacles), crossed from the left
tenth to the right tenth of the room with natural headings. :func:`large_floor` is the
160 x 96 m room with 512 obstacles; :func:`sweep_floor` any size and obstacle count (the
size sweep of the study).

Hard cases (:func:`hard_cases`)
-------------------------------
Named floors built by hand, each with the reason it is hard in its description: a start
facing a wall with the front wheel 0.5 m from it (in the planning model: from the wall
shrunk by the half-width) and the goal behind; doors and corridors barely wider than the
robot; goals enclosed by obstacles (no plan exists); and the shipped ``turn_around``.
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path

import numpy as np

from ..floor.body import RectangleBody
from ..floor.geometry import axis_segment, enlarge_polygon, pose_collides, pose_in_bounds
from ..floor.random_floors import place_disjoint
from ..floor.scenario import Robot, Scenario, load_scenario, make_scenario
from ..model.pose import TWO_PI, wrap_scalar

__all__ = [
    "GENERATOR_VERSION",
    "KINDS",
    "LARGE_BOUNDS",
    "MIN_DISTANCE",
    "NATURAL_SPREAD",
    "N_FLOORS",
    "ROBOT",
    "SMALL_BOUNDS",
    "floor_key",
    "hard_cases",
    "large_floor",
    "random_floor",
    "random_floors",
    "random_obstacle",
    "sweep_floor",
]

#: Bump when any floor changes: stored results name the version they were measured on.
GENERATOR_VERSION = 1
#: The robot of every floor: L = 1 m, half-width 0.3 m, 45 degrees of steering (R = 1 m).
ROBOT = Robot(L=1.0, half_width=0.3, max_steer=math.radians(45.0))
#: The random floors' room (m).
SMALL_BOUNDS = (0.0, 0.0, 20.0, 12.0)
#: The large room (m): the small one scaled by 8.
LARGE_BOUNDS = (0.0, 0.0, 160.0, 96.0)
#: Heading kinds of the random floors.
KINDS = ("any", "natural")
#: Random floors of each kind.
N_FLOORS = 200
#: Least distance (m) between the start's and the goal's rear point A.
MIN_DISTANCE = 6.0
#: Largest angle (radians) between a natural heading and the start -> goal direction.
NATURAL_SPREAD = math.radians(60.0)
#: Obstacles per small floor (inclusive range) and per square metre on scaled floors.
N_OBSTACLES = (4, 9)
DENSITY = 8.0 / (20.0 * 12.0)
_ROOT_SEED = 12  # the number: every floor's generator descends from it
_DIGITS = 6  # coordinates rounded to a micrometre (and headings to a microradian)
_TRIES = 10_000


def _rng(*key: int) -> np.random.Generator:
    return np.random.default_rng([_ROOT_SEED, GENERATOR_VERSION, *key])


def _check_index(index, name: str = "index", limit: int | None = None) -> int:
    if isinstance(index, bool) or not isinstance(index, int | np.integer) or index < 0:
        raise ValueError(f"{name} must be an integer >= 0, got {index!r}")
    if limit is not None and index >= limit:
        raise ValueError(f"{name} must be below {limit}, got {index}")
    return int(index)


def _check_kind(kind) -> str:
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
    return kind


def random_obstacle(rng: np.random.Generator, center) -> np.ndarray:
    """A rectangle (sides 0.5-3 m) or a regular polygon (3-8 vertices, circumradius
    0.4-1.5 m), equally likely, at a uniform rotation about ``center``; counter-clockwise."""
    c = np.asarray(center, dtype=float)
    rot = rng.uniform(0.0, TWO_PI)
    if rng.random() < 0.5:
        w, h = rng.uniform(0.5, 3.0, 2)
        local = 0.5 * np.array([[-w, -h], [w, -h], [w, h], [-w, h]])
    else:
        k = int(rng.integers(3, 9))
        r = rng.uniform(0.4, 1.5)
        a = np.arange(k) * (TWO_PI / k)
        local = r * np.column_stack((np.cos(a), np.sin(a)))
    cs, sn = math.cos(rot), math.sin(rot)
    return np.round(c + local @ np.array([[cs, sn], [-sn, cs]]), _DIGITS)


def _place_obstacles(rng: np.random.Generator, n: int, bounds) -> list[np.ndarray]:
    """``n`` random obstacles inside ``bounds``, pairwise disjoint (raw polygons)."""
    xmin, ymin, xmax, ymax = bounds

    def draw():
        poly = random_obstacle(rng, (rng.uniform(xmin, xmax), rng.uniform(ymin, ymax)))
        lo, hi = poly.min(axis=0), poly.max(axis=0)
        if lo[0] <= xmin or lo[1] <= ymin or hi[0] >= xmax or hi[1] >= ymax:
            return None
        return poly, poly

    placed = place_disjoint(draw, n, _TRIES * max(1, n))
    if len(placed) < n:  # pragma: no cover
        raise ValueError(f"placed only {len(placed)} of {n} obstacles in {bounds}")
    return placed


class _FreeTest:
    """Is a pose free among the enlarged obstacles and inside the shrunk walls? (the
    scenario's own tests, :meth:`segplan.Scenario.is_free`, before the scenario exists; the
    robot's axis segment with its overhangs, :attr:`segplan.Robot.axis`; a rectangular
    body, :attr:`segplan.Scenario.body`)."""

    def __init__(self, obstacles, bounds, robot: Robot):
        r = robot.half_width
        self.L, self.body = robot.L, {"rear": robot.rear_overhang, "front": robot.front_overhang}
        self.free_bounds = (bounds[0] + r, bounds[1] + r, bounds[2] - r, bounds[3] - r)
        self.polys = [enlarge_polygon(p, r) for p in obstacles]
        self.boxes = np.array([(*p.min(axis=0), *p.max(axis=0)) for p in self.polys]).reshape(-1, 4)
        self.rectangle = (
            RectangleBody(obstacles, r, bounds, robot.L, robot.rear_overhang, robot.front_overhang)
            if robot.rectangle and r > 0.0 else None
        )  # fmt: skip

    def __call__(self, pose) -> bool:
        if self.rectangle is not None:  # a rectangular body: the rectangle itself
            return self.rectangle.pose_conflict(pose) is None
        if not pose_in_bounds(pose, self.L, self.free_bounds, **self.body):
            return False
        x, y, dx, dy, _ = axis_segment(*pose, self.L, self.body["rear"], self.body["front"])
        bx, by = x + dx, y + dy
        b = self.boxes
        near = np.flatnonzero(
            (b[:, 0] <= max(x, bx))
            & (min(x, bx) <= b[:, 2])
            & (b[:, 1] <= max(y, by))
            & (min(y, by) <= b[:, 3])
        )
        return not any(pose_collides(pose, self.L, self.polys[i], check=False, **self.body) for i in near)


def _heading(rng: np.random.Generator, kind: str, direction: float) -> float:
    if kind == "any":
        return rng.uniform(-math.pi, math.pi)
    return direction + rng.uniform(-NATURAL_SPREAD, NATURAL_SPREAD)


def _start_goal(rng, free, kind: str, start_x, goal_x, ylim) -> tuple[tuple, tuple]:
    """Free start and goal: A uniform in the given x ranges and ``ylim``, at least
    :data:`MIN_DISTANCE` apart, headings of ``kind``."""
    for _ in range(_TRIES):
        a = np.round((rng.uniform(*start_x), rng.uniform(*ylim)), _DIGITS)
        b = np.round((rng.uniform(*goal_x), rng.uniform(*ylim)), _DIGITS)
        if math.dist(a, b) < MIN_DISTANCE:
            continue
        direction = math.atan2(b[1] - a[1], b[0] - a[0])
        s = (float(a[0]), float(a[1]), round(wrap_scalar(_heading(rng, kind, direction)), _DIGITS))
        g = (float(b[0]), float(b[1]), round(wrap_scalar(_heading(rng, kind, direction)), _DIGITS))
        if free(s) and free(g):
            return s, g
    raise ValueError("no free start and goal found")  # pragma: no cover


def random_floor(kind: str, index: int) -> Scenario:
    """Random floor ``index`` (``0 <= index < N_FLOORS``) of heading ``kind`` (module docstring).

    Parameters
    ----------
    kind : {"any", "natural"}
    index : int

    Returns
    -------
    Scenario
        Named ``f"{kind}-{index:03d}"``.
    """
    kind = _check_kind(kind)
    index = _check_index(index, limit=N_FLOORS)
    rng = _rng(KINDS.index(kind), index)
    n = int(rng.integers(N_OBSTACLES[0], N_OBSTACLES[1] + 1))
    obstacles = _place_obstacles(rng, n, SMALL_BOUNDS)
    free = _FreeTest(obstacles, SMALL_BOUNDS, ROBOT)
    fb = free.free_bounds
    s, g = _start_goal(rng, free, kind, (fb[0], fb[2]), (fb[0], fb[2]), (fb[1], fb[3]))
    name = f"{kind}-{index:03d}"
    desc = (
        f"Random floor {index} of kind {kind!r} (segplan.studies.floors v{GENERATOR_VERSION}): {n} obstacles."
    )
    return make_scenario(ROBOT, s, g, obstacles, SMALL_BOUNDS, name=name, description=desc, source=name)


def random_floors(kind: str, n: int = N_FLOORS) -> list[Scenario]:
    """The first ``n`` random floors of ``kind``."""
    _check_index(n, "n", N_FLOORS + 1)
    return [random_floor(kind, i) for i in range(n)]


def sweep_floor(scale: float, n_obstacles: int | None = None, index: int = 0) -> Scenario:
    """The small room scaled by ``scale`` (``20 s x 12 s`` m), crossed left to right.

    Parameters
    ----------
    scale : float
        ``s >= 1``.
    n_obstacles : int, optional
        Default ``round(8 s^2)``, the small floors' mean density.
    index : int
        Which floor of that size and count.

    Returns
    -------
    Scenario
        Start A in the left tenth of the free room, goal A in the right tenth, natural
        headings; named ``f"sweep-{20 s:g}x{12 s:g}-{n}-{index}"``.
    """
    if not (isinstance(scale, int | float) and math.isfinite(scale) and scale >= 1.0):
        raise ValueError(f"scale must be a number >= 1, got {scale!r}")
    n = round(DENSITY * 240.0 * scale**2) if n_obstacles is None else _check_index(n_obstacles, "n_obstacles")
    index = _check_index(index)
    w, h = round(20.0 * scale, 3), round(12.0 * scale, 3)
    bounds = (0.0, 0.0, w, h)
    rng = _rng(100, round(1000 * scale), n, index)
    obstacles = _place_obstacles(rng, n, bounds)
    free = _FreeTest(obstacles, bounds, ROBOT)
    fb = free.free_bounds
    tenth = 0.1 * (fb[2] - fb[0])
    s, g = _start_goal(
        rng, free, "natural", (fb[0], fb[0] + tenth), (fb[2] - tenth, fb[2] - ROBOT.L), (fb[1], fb[3])
    )
    name = f"sweep-{w:g}x{h:g}-{n}-{index}"
    desc = f"{w:g} x {h:g} m, {n} obstacles, crossing {index} (segplan.studies.floors v{GENERATOR_VERSION})."
    return make_scenario(ROBOT, s, g, obstacles, bounds, name=name, description=desc, source=name)


def large_floor(index: int) -> Scenario:
    """Large floor ``index``: 160 x 96 m, 512 obstacles, crossed left to right (:func:`sweep_floor`)."""
    return sweep_floor(8.0, 512, index)


# -- hard cases -----------------------------------------------------------------------------
def _rect(x0: float, y0: float, x1: float, y1: float) -> list[list[float]]:
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def _hard(name: str, start, goal, obstacles, description: str, bounds=SMALL_BOUNDS) -> Scenario:
    return make_scenario(
        ROBOT, start, goal, obstacles, bounds, name=name, description=description, source=name
    )


def hard_cases(scenario_dir: str | Path | None = None) -> dict[str, Scenario]:
    """The named hard floors (module docstring), by name.

    Parameters
    ----------
    scenario_dir : path, optional
        Where ``turn_around.json`` is (default: the shipped scenario, ``load_scenario("turn_around")``,
        read from the installed package).

    Returns
    -------
    dict
        ``name -> Scenario``. Names starting ``"enclosed"`` have no plan (the goal is cut
        off in the planning model); ``turn_around`` is the shipped scenario (its own robot,
        L = 1.2 m).
    """
    r = ROBOT.half_width
    xmax = SMALL_BOUNDS[2] - r  # free bounds' right edge
    gap = 0.5  # front wheel to the wall, in the planning model
    ax = xmax - gap - ROBOT.L
    cases = [
        _hard(
            "wall_ahead_back",
            (ax, 6.0, 0.0),
            (ax - 7.0, 6.0, math.pi),
            [],
            "Start facing the right wall, front wheel 0.5 m from it (planning model); goal 7 m behind, "
            "heading back. A circle of radius R = L clears the wall by 8.6 cm.",
        ),
        _hard(
            "wall_ahead_same",
            (ax, 6.0, 0.0),
            (ax - 7.0, 6.0, 0.0),
            [],
            "Start facing the right wall, front wheel 0.5 m from it; goal 7 m behind, heading the same way: "
            "a full loop is needed.",
        ),
        _hard(
            "wall_ahead_low",
            (ax, 1.4, 0.0),
            (ax - 8.0, 4.0, math.pi),
            [],
            "Start facing the right wall 0.5 m away and 1.1 m above the bottom wall: only a left turn fits.",
        ),
        _hard(
            "wall_obstacle",
            (12.0 - r - gap - ROBOT.L, 6.0, 0.0),
            (4.0, 6.0, 0.5 * math.pi),
            [_rect(12.0, 1.5, 12.4, 10.5)],
            "Start facing an interior wall (obstacle), front wheel 0.5 m from its enlargement; goal behind.",
        ),
        _hard(
            "door",
            (3.0, 3.0, 0.0),
            (17.0, 9.0, 0.0),
            [_rect(9.5, 0.0, 10.5, 5.4), _rect(9.5, 6.6, 10.5, 12.0)],
            "A wall across the room with a door 1.2 m wide (0.6 m in the planning model).",
        ),
        _hard(
            "corridor",
            (2.0, 9.0, -0.5 * math.pi),
            (18.0, 3.0, 0.5 * math.pi),
            [_rect(6.0, 0.0, 14.0, 5.3), _rect(6.0, 6.7, 14.0, 12.0)],
            "A corridor 8 m long and 1.4 m wide (0.8 m in the planning model); start and goal face away.",
        ),
        _hard(
            "doors_s",
            (2.0, 2.0, 0.0),
            (18.0, 2.0, 0.0),
            [_rect(6.5, 0.0, 7.0, 10.5), _rect(13.0, 1.5, 13.5, 12.0)],
            "Two walls, a door of 1.5 m at the top of the first and at the bottom of the second: an S.",
        ),
        _hard(
            "enclosed_goal",
            (3.0, 6.0, 0.0),
            (15.0, 6.0, 0.0),
            [
                _rect(12.0, 3.0, 18.0, 3.4),
                _rect(12.0, 8.6, 18.0, 9.0),
                _rect(12.0, 3.0, 12.4, 9.0),
                _rect(17.6, 3.0, 18.0, 9.0),
            ],
            "The goal is inside a closed box of four walls: no plan exists.",
        ),
        _hard(
            "enclosed_slit",
            (3.0, 6.0, 0.0),
            (15.0, 6.0, 0.0),
            [
                _rect(12.0, 3.0, 18.0, 3.4),
                _rect(12.0, 8.6, 18.0, 9.0),
                _rect(12.0, 3.0, 12.4, 5.8),
                _rect(12.0, 6.3, 12.4, 9.0),
                _rect(17.6, 3.0, 18.0, 9.0),
            ],
            "The goal's box has a slit 0.5 m wide, closed by the enlargement (2 x 0.3 m): no plan exists.",
        ),
    ]
    out = {sc.name: sc for sc in cases}
    if scenario_dir is None:
        out["turn_around"] = load_scenario("turn_around")  # shipped with the package
    else:
        out["turn_around"] = load_scenario(Path(scenario_dir) / "turn_around.json")
    return out


def floor_key(scenario: Scenario) -> str:
    """A short hash of a floor's file form (:meth:`segplan.Scenario.to_json`): results
    stored for a floor name the floor they were measured on."""
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    return hashlib.sha256(scenario.to_json().encode()).hexdigest()[:12]
