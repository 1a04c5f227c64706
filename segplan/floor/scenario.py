"""The robot and its world: the segment robot, convex obstacles, bounds, scenario files.

Sections "Mobile robot modelling" and "Results. Graph-search" of Campoy et al. (1989).
The robot is the segment A->B of length ``L`` (A: middle of the rear axle, B: middle of
the front wheel). Its real plan section, the "curved rectangle" of Fig. 2, is modelled
as the set of points within ``half_width`` of that segment; so the segment is planned
among obstacles *enlarged off-line* by ``half_width`` ("the processing of the model of
the surroundings, with obstacles appropriately enlarged, is performed off-line"), and
the walls of a rectangular world move inwards by ``half_width``. Forward motion only (the
paper's AGV; ``Robot(..., reverse=True)`` lets the default planner reverse too, beyond the
paper, issue 26), with the steering angle of the front wheel bounded by ``max_steer``: the rear path's
curvature stays within ``tan(max_steer) / L`` (bicycle model).

Obstacles are simple polygons, ``(k, 2)`` vertex arrays or shapely ``Polygon`` /
``MultiPolygon`` objects (no holes). The planner sees convex polygons, the paper's
obstacles: a non-convex one is split into convex pieces by
:func:`segplan.floor.decompose.convex_pieces` (beyond the paper); ``Scenario.obstacles`` holds
the pieces, ``Scenario.outlines`` the polygons as given (for drawing and files). Convex
polygons are their own single piece, stored counter-clockwise.

Scenario files (JSON)
---------------------
::

    {"name": "...", "description": "...",            (optional strings)
     "L": 1.2, "half_width": 0.35, "max_steer_deg": 45,
     "front_overhang": 0.3, "rear_overhang": 0.5, "rectangle": true,  (optional: the body)
     "reverse": true,                                (optional: may the robot reverse?)
     "start": [x, y, theta_deg], "goal": [x, y, theta_deg],
     "bounds": [xmin, ymin, xmax, ymax],             (or null / absent: no walls)
     "obstacles": [[[x, y], [x, y], [x, y], ...], ...]}

Lengths in metres. **Angles in files are degrees**: ``theta`` of start and goal and
``max_steer_deg``; the Python API (``Pose``, ``Robot.max_steer``) uses radians.
Required keys: ``L``, ``start``, ``goal``, ``obstacles``; defaults: ``half_width`` 0,
``max_steer_deg`` 45, ``bounds`` none, ``front_overhang`` and ``rear_overhang`` 0,
``rectangle`` false (the body, :class:`Robot`) and ``reverse`` false (each written only
when set). Any other key is an error, so is a repeated key.
Polygons may be given in either orientation and are stored counter-clockwise; nothing
else is changed. A polygon may be non-convex (an L-shaped rack, a concave bay: see
``scenarios/beyond_the_paper/l_shaped_rack.json``); it is split into convex pieces. A closing copy of
the first vertex and vertices collinear with their neighbours are dropped (issue 27;
refused before). A vertex repeated elsewhere is an error, as are self-intersecting and
zero-area polygons, NaN/Infinity literals and numbers that overflow to infinity.

A pose collides when its segment A->B (extended by the overhangs, :attr:`Robot.axis`)
touches an enlarged obstacle (closed sets: touching is a collision); it is out of bounds
unless the whole segment lies strictly inside the bounds shrunk by ``half_width``
(:attr:`Scenario.free_bounds`). Scenarios
decide both with :func:`segplan.floor.geometry.pose_conflict`, the planner's own pose test.
Polygons are validated by :func:`segplan.floor.geometry.check_convex_polygon` (the one
validator) and enlarged by :func:`segplan.floor.geometry.enlarge_polygon`. Random floors:
:mod:`segplan.floor.random_floors`.
"""

from __future__ import annotations

import functools
import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from importlib import resources
from pathlib import Path

import numpy as np

from ..model.pose import Pose, as_pose, check_length, show_pose
from .body import RectangleBody
from .geometry import (
    DEFAULT_MAX_ARC,
    check_bounds,
    enlarge_polygon,
    finite_number,
    pose_conflict,
)
from .maps import WORLD_LIMIT, Floor

__all__ = [
    "with_clearance",
    "MIN_LENGTH",
    "OPTIONAL_KEYS",
    "PreparedFloor",
    "FOOTPRINT_KEYS",
    "REQUIRED_KEYS",
    "Robot",
    "Scenario",
    "ScenarioError",
    "WORLD_LIMIT",
    "load_scenario",
    "loads_scenario",
    "make_scenario",
    "prepare_floor",
    "save_scenario",
    "scenario_from_dict",
]
#: Scenario coordinates and lengths must not exceed WORLD_LIMIT (the world's scale, metres
#: in files; defined with the floor, :data:`segplan.floor.maps.WORLD_LIMIT`); L and a nonzero
#: half_width must be at least MIN_LENGTH (a smaller half_width would enlarge polygons by
#: less than the spacing of floats near them).
MIN_LENGTH = 1e-6

REQUIRED_KEYS = ("L", "start", "goal", "obstacles")
#: The body's keys (:class:`Robot`; beyond the paper), optional, saved only when set.
FOOTPRINT_KEYS = ("front_overhang", "rear_overhang", "rectangle")
OPTIONAL_KEYS = ("name", "description", "half_width", "max_steer_deg", "reverse", "bounds", *FOOTPRINT_KEYS)


class ScenarioError(ValueError):
    """A scenario file or scenario description is malformed or infeasible.

    The message names the file (or ``<python>``), and where relevant the key, the
    obstacle index and the vertex index.
    """


# -- the robot ------------------------------------------------------------------------
@dataclass(frozen=True)
class Robot:
    """The oriented-segment robot (section "Mobile robot modelling", Fig. 2).

    Parameters
    ----------
    L : float
        Length of the segment from the rear-axle middle A to the front wheel B (> 0, m).
    half_width : float
        Radius of the robot's plan section around the segment (>= 0, m); obstacles are
        enlarged by it off-line and the walls move inwards by it. 0: the pure segment.
    max_steer : float
        Largest steering angle of the front wheel, radians, in ``(0, pi/2)``.
    front_overhang, rear_overhang : float
        The body's reach beyond the front wheel B and behind the rear axle A along the
        axis (>= 0, m; beyond the paper). The planner checks the *axis segment* from
        ``A - rear_overhang u`` to ``B + front_overhang u`` (``u`` the heading), whose
        points follow the robot's rigid motion, among the obstacles enlarged by
        ``half_width``: :mod:`segplan.floor.collision` sweeps it exactly. 0, 0: the paper's
        segment A->B.
    rectangle : bool
        The body (its footprint, :meth:`footprint`): False (default), the points within
        ``half_width`` of that axis segment, a rectangle with round ends (today's robot,
        the paper's "curved rectangle" when the overhangs are 0), which the planner's test
        sweeps exactly; True, the rectangle ``[-rear_overhang, L + front_overhang] x
        [-half_width, half_width]`` of the robot's frame, which the rounded body contains:
        where the rounded body touches an obstacle or a wall, the rectangle itself is swept
        against the raw one (:mod:`segplan.floor.body`, exact up to the touching tolerance).
    reverse : bool
        May the robot drive backwards (beyond the paper, issue 26)? False: the paper's
        forward-only AGV. True: the default planner may also traverse a union backwards
        (the lattice planner, :mod:`segplan.planning.lattice.astar`), changing direction at nodes.

    Raises
    ------
    ValueError
        Naming the argument, for a non-finite or out-of-range value (a negative overhang:
        the body must contain the segment A->B).

    Notes
    -----
    Both planners honour the body: every union and pose goes through the same checker
    (:class:`segplan.planning.validity.Workspace`). The paper's search places its
    intermediate nodes for the segment A->B (bisectrix of the blocking vertex), so with long
    overhangs it finds fewer plans than the default planner (a ``NoPathError``, never a
    plan that touches).

    Overhangs rather than a ``Footprint`` object or an arbitrary polygon: every body the
    planner can honour exactly is fixed by three numbers (the axis segment's two ends and
    the disk's radius), and the obstacles' off-line enlargement already uses one of them.
    """

    L: float
    half_width: float = 0.0
    max_steer: float = math.radians(45.0)
    front_overhang: float = 0.0
    rear_overhang: float = 0.0
    rectangle: bool = False
    reverse: bool = False

    def __post_init__(self):
        if not isinstance(self.reverse, bool):
            raise ValueError(f"reverse must be True or False, got {self.reverse!r}")
        object.__setattr__(self, "L", check_length(self.L, "L"))
        object.__setattr__(self, "half_width", finite_number(self.half_width, "half_width", minimum=0.0))
        steer = finite_number(self.max_steer, "max_steer")
        if not 0.0 < steer < 0.5 * math.pi:
            raise ValueError(
                f"max_steer must lie in (0, pi/2) radians, got {steer} ({math.degrees(steer)} deg)"
            )
        object.__setattr__(self, "max_steer", steer)
        for name in ("front_overhang", "rear_overhang"):
            value = finite_number(getattr(self, name), name)
            if value < 0.0:
                raise ValueError(f"{name} must be >= 0 (the body must contain the segment A->B), got {value}")
            object.__setattr__(self, name, value)
        if not isinstance(self.rectangle, bool):
            raise ValueError(f"rectangle must be True or False, got {self.rectangle!r}")

    @property
    def axis(self) -> tuple[float, float]:
        """The checked axis segment in the robot's frame: ``(-rear_overhang, L + front_overhang)``
        along the heading from A (``(0, L)``, the segment A->B, by default)."""
        return -self.rear_overhang, self.L + self.front_overhang

    def footprint(self, arc_points: int = 9) -> np.ndarray:
        """Outline ``(k, 2)`` of the body in the robot's frame (A at the origin, heading +x),
        counter-clockwise.

        The rectangle (``rectangle=True``), or the points within ``half_width`` of the axis
        segment (:attr:`axis`) with each round end drawn by ``arc_points`` points (an
        inscribed polygon: for drawing; the planner's test uses the exact round body).
        """
        lo, hi = self.axis
        w = self.half_width
        if self.rectangle:
            return np.array([[lo, -w], [hi, -w], [hi, w], [lo, w]])
        t = np.linspace(-0.5 * math.pi, 0.5 * math.pi, arc_points)
        front = np.column_stack((hi + w * np.cos(t), w * np.sin(t)))
        return np.vstack((front, (hi + lo, 0.0) - front))  # the rear end: the front's turned half way round

    @property
    def max_curvature(self) -> float:
        """Largest curvature of the rear path, ``tan(max_steer) / L`` (bicycle model)."""
        return math.tan(self.max_steer) / self.L

    @property
    def min_turning_radius(self) -> float:
        """Smallest turning radius of the rear point A, ``L / tan(max_steer)``."""
        return self.L / math.tan(self.max_steer)


# -- scenarios ------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Scenario:
    """A validated planning problem (build with :func:`make_scenario` or :func:`load_scenario`).

    Attributes
    ----------
    robot : Robot
    start, goal : Pose
        Rear-axle point and heading, **theta in radians** (files store degrees).
    bounds : tuple (xmin, ymin, xmax, ymax) or None
        The walls, or None for an unbounded world.
    obstacles : tuple of ndarray (k, 2)
        The convex obstacles, counter-clockwise, read-only: the polygons as given, a
        non-convex one replaced by its convex pieces (:func:`segplan.floor.decompose.convex_pieces`).
    enlarged : tuple of ndarray (n, 2)
        ``obstacles`` enlarged by ``robot.half_width`` (:func:`enlarge_polygon`), the
        polygons the segment is planned among; read-only.
    name, description : str
    path : Path or None
        The file it was loaded from.
    outlines : tuple of ndarray (k, 2)
        The obstacles as given (counter-clockwise, read-only), possibly non-convex; the
        same arrays as ``obstacles`` when every obstacle is convex. Drawn and saved.
    outline_of : tuple of int
        ``outline_of[i]``: the index in ``outlines`` of the piece ``obstacles[i]``.
    """

    robot: Robot
    start: Pose
    goal: Pose
    bounds: tuple[float, float, float, float] | None
    obstacles: tuple[np.ndarray, ...]
    enlarged: tuple[np.ndarray, ...]
    name: str = ""
    description: str = ""
    path: Path | None = field(default=None)
    outlines: tuple[np.ndarray, ...] = ()
    outline_of: tuple[int, ...] = ()

    @property
    def L(self) -> float:
        """Robot length."""
        return self.robot.L

    @property
    def free_bounds(self) -> tuple[float, float, float, float] | None:
        """The bounds shrunk by ``half_width``: the segment must stay strictly inside."""
        if self.bounds is None:
            return None
        r = self.robot.half_width
        xmin, ymin, xmax, ymax = self.bounds
        return (xmin + r, ymin + r, xmax - r, ymax - r)

    @functools.cached_property
    def body(self) -> RectangleBody | None:
        """The exact tests of a rectangular body (``robot.rectangle`` and ``half_width > 0``)
        among the raw obstacles and walls (:class:`segplan.floor.body.RectangleBody`), or
        None: the round body, tested through the enlarged obstacles."""
        r = self.robot
        if not (r.rectangle and r.half_width > 0.0):
            return None
        return RectangleBody(
            self.obstacles, r.half_width, self.bounds, r.L, r.rear_overhang, r.front_overhang
        )

    def pose_conflict(self, pose) -> str | None:
        """Why ``pose`` is not free (``"obstacles[i]"`` or ``"bounds"``), or None if it is free.

        Uses :func:`segplan.floor.geometry.pose_conflict`, the planner's own test (separating
        axes; touching, within the relative tolerance ``TOUCH_RTOL`` = 1e-9, counts), so a
        scenario that loads has a start and goal the planner accepts. A rectangular body:
        the rectangle itself against the raw obstacles and walls (:attr:`body`).
        """
        if self.body is not None:
            return self.body.pose_conflict(pose)
        r = self.robot
        return pose_conflict(
            pose, r.L, self.enlarged, self.free_bounds, rear=r.rear_overhang, front=r.front_overhang
        )

    def is_free(self, pose) -> bool:
        """Is the robot at ``pose`` (radians) clear of every enlarged obstacle and wall?"""
        return self.pose_conflict(pose) is None

    def to_dict(self) -> dict:
        """The scenario in file form (plain JSON types; angles in degrees)."""
        out: dict = {}
        if self.name:
            out["name"] = self.name
        if self.description:
            out["description"] = self.description
        out["L"] = self.robot.L
        out["half_width"] = self.robot.half_width
        out["max_steer_deg"] = math.degrees(self.robot.max_steer)
        for key in FOOTPRINT_KEYS:  # written only when set: the paper's robot's files unchanged
            if getattr(self.robot, key):
                out[key] = getattr(self.robot, key)
        if self.robot.reverse:
            out["reverse"] = True
        out["start"] = [self.start.x, self.start.y, math.degrees(self.start.theta)]
        out["goal"] = [self.goal.x, self.goal.y, math.degrees(self.goal.theta)]
        out["bounds"] = None if self.bounds is None else list(self.bounds)
        out["obstacles"] = [p.tolist() for p in self.outlines]
        return out

    def to_json(self) -> str:
        """JSON text of :meth:`to_dict`, one obstacle per line; :func:`load_scenario` reads it back."""
        d = self.to_dict()
        lines = [
            f"  {json.dumps(k)}: {json.dumps(v, allow_nan=False)}" for k, v in d.items() if k != "obstacles"
        ]
        obs = ",\n".join(f"    {json.dumps(p, allow_nan=False)}" for p in d["obstacles"])
        lines.append('  "obstacles": [\n' + obs + "\n  ]" if obs else '  "obstacles": []')
        return "{\n" + ",\n".join(lines) + "\n}\n"


def make_scenario(
    robot: Robot,
    start,
    goal,
    obstacles: Sequence | Floor = (),
    bounds: Sequence[float] | None = None,
    *,
    name: str = "",
    description: str = "",
    path: Path | None = None,
    max_arc: float = DEFAULT_MAX_ARC,
    source: str = "<python>",
) -> Scenario:
    """Validate a planning problem and build a :class:`Scenario` (Python API: radians).

    ``obstacles``: simple polygons (see the module docstring; made into a floor by
    :meth:`segplan.Floor.from_polygons`) or a :class:`segplan.Floor` (a map from
    :func:`segplan.load_ros_map` or :meth:`segplan.Floor.from_occupancy`), whose bounds are
    used when ``bounds`` is None.

    Raises
    ------
    ScenarioError
        Naming ``source``: bad robot parameters, poses, bounds (not a proper rectangle,
        or narrower than the robot), polygons (see :func:`segplan.floor.geometry.check_convex_polygon`), or a
        start or goal that collides with an enlarged obstacle or leaves the free bounds.
    """
    floor = prepare_floor(robot, obstacles, bounds, max_arc=max_arc, source=source)
    return floor.scenario(start, goal, name=name, description=description, path=path, source=source)


@dataclass(frozen=True, eq=False)
class PreparedFloor:
    """A floor made ready for one robot: the off-line half of :func:`make_scenario`.

    The paper's "processing of the model of the surroundings ... performed off-line": the
    polygons checked and split into convex pieces, enlarged by the robot's half-width, the
    bounds checked. Many scenarios (start and goal pairs) share it
    (:meth:`scenario`; :class:`segplan.Planner`). Build with :func:`prepare_floor`.

    Attributes
    ----------
    robot : Robot
    bounds : tuple or None
    floor : segplan.Floor
        The obstacles as given and their convex pieces.
    enlarged : tuple of ndarray
        The pieces enlarged by ``robot.half_width`` (read-only).
    """

    robot: Robot
    bounds: tuple[float, float, float, float] | None
    floor: Floor
    enlarged: tuple[np.ndarray, ...]

    def scenario(
        self,
        start,
        goal,
        *,
        name: str = "",
        description: str = "",
        path: Path | None = None,
        source: str = "<python>",
    ) -> Scenario:
        """The :class:`Scenario` of ``start`` and ``goal`` on this floor (radians).

        Raises
        ------
        ScenarioError
            Naming ``source``: a malformed pose, a heading beyond 2 pi, or a start or goal
            that collides with an enlarged obstacle or leaves the free bounds.
        """
        robot = self.robot
        try:
            start_p = as_pose(start, "start")
            goal_p = as_pose(goal, "goal")
        except ValueError as exc:
            raise ScenarioError(f"{source}: {exc}") from None
        for label, pose in (("start", start_p), ("goal", goal_p)):
            _check_scale(pose[:2], f"{source}: {label}")
            if abs(pose.theta) > 2.0 * math.pi:
                raise ScenarioError(
                    f"{source}: {label} heading theta={pose.theta:g} rad is beyond 2 pi (360 deg): "
                    f"headings are in radians (theta={pose.theta:g} deg would be "
                    f"{math.radians(pose.theta):.6g} rad)"
                )
        floor = self.floor
        sc = Scenario(
            robot, start_p, goal_p, self.bounds, tuple(floor.obstacles), self.enlarged, name, description,
            path, floor.outlines, floor.outline_of,
        )  # fmt: skip
        for label, pose in (("start", start_p), ("goal", goal_p)):
            conflict = sc.pose_conflict(pose)
            if conflict == "bounds" and sc.body is not None:
                raise ScenarioError(
                    f"{source}: {label} pose {_show(pose)} is out of bounds: its {_segment(robot)} "
                    f"must lie strictly inside the bounds {list(sc.bounds)}"
                )
            if conflict == "bounds":
                raise ScenarioError(
                    f"{source}: {label} pose {_show(pose)} is out of bounds: its {_segment(robot)} "
                    f"must lie strictly inside the bounds shrunk by half_width, "
                    f"{list(sc.free_bounds)}"
                )
            if conflict is not None:
                conflict = floor.describe(int(conflict[len("obstacles[") : -1]))  # the obstacle as given
                raise ScenarioError(
                    f"{source}: {label} pose {_show(pose)} collides with {conflict}"
                    + (f" ({_segment(robot)})" if sc.body is not None else
                       f" enlarged by half_width={robot.half_width} ({_segment(robot)})")
                )  # fmt: skip
        return sc


def prepare_floor(
    robot: Robot,
    obstacles: Sequence | Floor = (),
    bounds: Sequence[float] | None = None,
    *,
    max_arc: float = DEFAULT_MAX_ARC,
    source: str = "<python>",
) -> PreparedFloor:
    """The floor half of :func:`make_scenario`, done once for many start and goal pairs
    (:class:`PreparedFloor`; the same arguments and checks, poses apart).

    Raises
    ------
    ScenarioError
        Naming ``source``: bad robot parameters, bounds or polygons.
    """
    if not isinstance(robot, Robot):
        raise ScenarioError(f"{source}: robot must be a Robot, got {type(robot).__name__}")
    if not MIN_LENGTH <= robot.L <= WORLD_LIMIT:
        raise ScenarioError(f"{source}: L={robot.L} is outside [{MIN_LENGTH:g}, {WORLD_LIMIT:g}]")
    if robot.half_width > WORLD_LIMIT or 0.0 < robot.half_width < MIN_LENGTH:
        raise ScenarioError(
            f"{source}: half_width={robot.half_width} must be 0 or within [{MIN_LENGTH:g}, {WORLD_LIMIT:g}]"
        )
    for key in FOOTPRINT_KEYS[:2]:
        if getattr(robot, key) > WORLD_LIMIT:
            raise ScenarioError(f"{source}: {key}={getattr(robot, key)} exceeds {WORLD_LIMIT:g}")
    if bounds is None and isinstance(obstacles, Floor):
        bounds = obstacles.bounds
    if bounds is not None:
        try:
            b = check_bounds(bounds)
        except ValueError as exc:
            raise ScenarioError(f"{source}: {exc}") from None
        if min(b[2] - b[0], b[3] - b[1]) <= 2.0 * robot.half_width:
            raise ScenarioError(f"{source}: bounds {list(b)} leave no room for half_width={robot.half_width}")
        _check_scale(b, f"{source}: bounds")
        bounds = b
    if isinstance(obstacles, Floor):
        floor = obstacles
    else:
        try:
            items = list(obstacles)
        except TypeError:
            raise ScenarioError(
                f"{source}: obstacles must be a sequence of polygons, got {_brief(obstacles)}"
            ) from None
        try:
            floor = Floor.from_polygons(items, source=source)
        except ValueError as exc:
            raise ScenarioError(str(exc)) from None
    enlarged = []
    for p in floor.obstacles:
        e = enlarge_polygon(p, robot.half_width, max_arc)
        e.flags.writeable = False
        enlarged.append(e)
    return PreparedFloor(robot, bounds, floor, tuple(enlarged))


def _check_scale(values, where: str) -> None:
    if any(abs(x) > WORLD_LIMIT for x in values):
        raise ScenarioError(f"{where}: coordinates {list(values)} exceed +-{WORLD_LIMIT:g}")


def _show(p: Pose) -> str:
    return show_pose(p)


def _segment(robot: Robot) -> str:
    """The checked segment (or rectangular body) in words, for error messages."""
    if robot.rectangle and robot.half_width > 0.0:
        text = f"rectangular body [{-robot.rear_overhang:g}, {robot.L + robot.front_overhang:g}] x "
        return text + f"[{-robot.half_width:g}, {robot.half_width:g}] (L={robot.L})"
    text = f"segment of length L={robot.L}"
    if robot.front_overhang or robot.rear_overhang:
        text += f" with overhangs front_overhang={robot.front_overhang}, rear_overhang={robot.rear_overhang}"
    return text


# -- files ----------------------------------------------------------------------------
def _reject_constant(token: str):
    raise _JSONValueError(f"non-finite literal {token} is not allowed (JSON has no NaN or Infinity)")


class _JSONValueError(ValueError):
    pass


def _no_duplicates(pairs):
    seen = {}
    for k, v in pairs:
        if k in seen:
            raise _JSONValueError(f"key {k!r} is repeated")
        seen[k] = v
    return seen


def _number(value, where: str) -> float:
    """A finite float from a JSON number (not a bool, not overflowing)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ScenarioError(f"{where} must be a number, got {_brief(value)}")
    try:
        x = float(value)
    except OverflowError:
        raise ScenarioError(f"{where} is too large for a float") from None
    if not math.isfinite(x):
        raise ScenarioError(f"{where} must be finite, got {x}")
    return x


def _numbers(value, n: int | None, where: str, names: str) -> list[float]:
    if not isinstance(value, list):
        raise ScenarioError(f"{where} must be a list {names}, got {_brief(value)}")
    if n is not None and len(value) != n:
        raise ScenarioError(f"{where} must have {n} numbers {names}, got {len(value)} items")
    return [_number(x, f"{where}[{i}]") for i, x in enumerate(value)]


def _brief(value) -> str:
    """Short description of a JSON value for error messages (no full repr of containers)."""
    if isinstance(value, list):
        return f"a list of {len(value)} items"
    if isinstance(value, dict):
        return f"an object with {len(value)} keys"
    if value is None:
        return "null"
    text = repr(value[:40] if isinstance(value, str) else value)
    return f"{type(value).__name__} {text if len(text) <= 40 else text[:37] + '...'}"


def scenario_from_dict(data, source: str = "<dict>", path: Path | None = None) -> Scenario:
    """Validate a scenario in file form (a dict as parsed from JSON; angles in degrees).

    Raises
    ------
    ScenarioError
        Naming ``source`` and the key, obstacle and vertex at fault.
    """
    if not isinstance(data, dict):
        raise ScenarioError(f"{source}: the top level must be a JSON object, got {_brief(data)}")
    unknown = [k for k in data if k not in REQUIRED_KEYS + OPTIONAL_KEYS]
    if unknown:
        raise ScenarioError(
            f"{source}: unknown key {unknown[0][:40]!r}; "
            f"allowed keys: {', '.join(REQUIRED_KEYS + OPTIONAL_KEYS)}"
        )
    missing = [k for k in REQUIRED_KEYS if k not in data]
    if missing:
        raise ScenarioError(f"{source}: missing key {missing[0]!r} (required: {', '.join(REQUIRED_KEYS)})")
    text = {}
    for key in ("name", "description"):
        value = data.get(key, "")
        if not isinstance(value, str):
            raise ScenarioError(f"{source}: {key} must be a string, got {_brief(value)}")
        text[key] = value
    L = _number(data["L"], f"{source}: L")
    half_width = _number(data.get("half_width", 0.0), f"{source}: half_width")
    steer = _number(data.get("max_steer_deg", 45.0), f"{source}: max_steer_deg")
    if not 0.0 < steer < 90.0:
        raise ScenarioError(f"{source}: max_steer_deg must lie in (0, 90) degrees, got {steer}")
    body = {k: _number(data[k], f"{source}: {k}") for k in FOOTPRINT_KEYS[:2] if k in data}
    if "rectangle" in data:
        if not isinstance(data["rectangle"], bool):
            raise ScenarioError(f"{source}: rectangle must be true or false, got {_brief(data['rectangle'])}")
        body["rectangle"] = data["rectangle"]
    reverse = data.get("reverse", False)
    if not isinstance(reverse, bool):
        raise ScenarioError(f"{source}: reverse must be true or false, got {_brief(reverse)}")
    try:
        robot = Robot(L, half_width, math.radians(steer), **body, reverse=reverse)
    except ValueError as exc:
        raise ScenarioError(f"{source}: {exc}") from None
    poses = {}
    for key in ("start", "goal"):
        x, y, th = _numbers(data[key], 3, f"{source}: {key}", "[x, y, theta_deg]")
        poses[key] = Pose(x, y, math.radians(th))
    bounds = data.get("bounds")
    if bounds is not None:
        bounds = _numbers(bounds, 4, f"{source}: bounds", "[xmin, ymin, xmax, ymax]")
    obstacles = data["obstacles"]
    if not isinstance(obstacles, list):
        raise ScenarioError(f"{source}: obstacles must be a list of polygons, got {_brief(obstacles)}")
    polys = []
    for i, poly in enumerate(obstacles):
        where = f"{source}: obstacles[{i}]"
        if not isinstance(poly, list):
            raise ScenarioError(f"{where} must be a list of [x, y] vertices, got {_brief(poly)}")
        polys.append([_numbers(vtx, 2, f"{where} vertex {j}", "[x, y]") for j, vtx in enumerate(poly)])
    return make_scenario(
        robot,
        poses["start"],
        poses["goal"],
        polys,
        bounds,
        name=text["name"] or (path.stem if path is not None else ""),
        description=text["description"],
        path=path,
        source=source,
    )


def loads_scenario(text: str | bytes, source: str = "<string>", path: Path | None = None) -> Scenario:
    """Parse and validate scenario JSON text (UTF-8 if bytes). See :func:`load_scenario`."""
    if isinstance(text, bytes | bytearray):
        try:
            text = bytes(text).decode("utf-8-sig")
        except UnicodeDecodeError as exc:
            raise ScenarioError(f"{source}: not UTF-8 text ({exc.reason} at byte {exc.start})") from None
    if not text.strip():
        raise ScenarioError(f"{source}: the file is empty")
    try:
        data = json.loads(text, parse_constant=_reject_constant, object_pairs_hook=_no_duplicates)
    except json.JSONDecodeError as exc:
        raise ScenarioError(
            f"{source}: invalid JSON: {exc.msg} (line {exc.lineno}, column {exc.colno})"
        ) from None
    except RecursionError:
        raise ScenarioError(f"{source}: invalid JSON: nested too deeply") from None
    except ValueError as exc:  # our hooks, or an integer literal with too many digits
        raise ScenarioError(f"{source}: invalid JSON: {exc}") from None
    return scenario_from_dict(data, source, path)


def load_scenario(path) -> Scenario:
    """Load and validate a scenario file (JSON; angles in degrees, see the module docstring).

    Parameters
    ----------
    path : str or Path
        A scenario file, or the bare name of a shipped scenario (``"fig5_example1"``, see
        :func:`shipped_scenarios`), read from the installed package with
        :mod:`importlib.resources`.

    Returns
    -------
    Scenario
        Start and goal headings converted to radians; obstacles enlarged off-line.

    Raises
    ------
    ScenarioError
        For any unreadable, malformed or infeasible file; the message names the file and,
        where relevant, the key, obstacle index and vertex index.
    """
    p = Path(path)
    if isinstance(path, str) and not p.suffix and p.name == path and not p.exists():
        shipped = _shipped_files()
        if path not in shipped:
            raise ScenarioError(
                f"{path!r} is neither a file nor a shipped scenario (one of {', '.join(sorted(shipped))})"
            )
        relative, resource = shipped[path]
        return loads_scenario(resource.read_bytes(), source=f"segplan/scenarios/{relative}")
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise ScenarioError(f"{p}: cannot read: {exc.strerror or exc}") from None
    return loads_scenario(raw, source=str(p), path=p)


#: Sub-folder of the shipped scenarios for floors beyond the paper (non-convex obstacles,
#: issue 14): shipped and loadable by name like the others; the paper's chapters, which read
#: the top folder ``scenarios/*.json``, do not see them.
BEYOND_THE_PAPER = "beyond_the_paper"


def _shipped_files() -> dict:
    """``{name: (path relative to scenarios/, resource)}`` of every shipped scenario."""
    folder = resources.files("segplan") / "scenarios"
    out = {}
    for sub, prefix in ((folder, ""), (folder / BEYOND_THE_PAPER, f"{BEYOND_THE_PAPER}/")):
        if sub.is_dir():
            for f in sub.iterdir():
                if f.name.endswith(".json"):
                    out[f.name[: -len(".json")]] = (prefix + f.name, f)
    return out


def shipped_scenarios() -> tuple[str, ...]:
    """Names of the scenarios shipped with segplan (package data), sorted.

    ``load_scenario(name)`` reads one of them; in a clone of the repository they are the
    files of ``scenarios/`` and ``scenarios/beyond_the_paper/`` (non-convex obstacles),
    which ``segplan/scenarios`` links to.
    """
    return tuple(sorted(_shipped_files()))


def save_scenario(scenario: Scenario, path) -> Path:
    """Write ``scenario.to_json()`` to ``path`` and return the path."""
    p = Path(path)
    p.write_text(scenario.to_json(), encoding="utf-8")
    return p


def with_clearance(scenario: Scenario, clearance: float) -> Scenario:
    """The scenario with its robot's ``half_width`` grown by ``clearance`` (m): the safety margin.

    Raises
    ------
    ValueError
        (``segplan.ScenarioError``) If the start or goal is nearer than ``clearance`` to an
        enlarged obstacle or wall.
    """
    robot = scenario.robot
    grown = replace(robot, half_width=robot.half_width + float(clearance))
    try:
        return make_scenario(
            grown, scenario.start, scenario.goal, scenario.outlines, scenario.bounds,
            name=scenario.name, description=scenario.description, path=scenario.path,
            source=f"clearance={clearance:g}",
        )  # fmt: skip
    except ScenarioError as exc:
        raise ScenarioError(f"{exc} (clearance {clearance:g} m beyond half_width)") from None
