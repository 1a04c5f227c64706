"""The robot and its world: the segment robot, convex obstacles, bounds, scenario files.

Sections "Mobile robot modelling" and "Results. Graph-search" of Campoy et al. (1989).
The robot is the segment A->B of length ``L`` (A: middle of the rear axle, B: middle of
the front wheel). Its real plan section, the "curved rectangle" of Fig. 2, is modelled
as the set of points within ``half_width`` of that segment; so the segment is planned
among obstacles *enlarged off-line* by ``half_width`` ("the processing of the model of
the surroundings, with obstacles appropriately enlarged, is performed off-line"), and
the walls of a rectangular world move inwards by ``half_width``. Forward motion only,
with the steering angle of the front wheel bounded by ``max_steer``: the rear path's
curvature stays within ``tan(max_steer) / L`` (bicycle model).

Obstacles are convex polygons, ``(k, 2)`` vertex arrays, stored counter-clockwise.

Enlargement (our choice, the paper gives none)
----------------------------------------------
The exact Minkowski sum of a convex polygon with a disk of radius ``r`` is the polygon
with every edge offset outwards by ``r`` joined by circular arcs at the vertices, which
is not a polygon. :func:`enlarge_polygon` keeps every offset edge and replaces the arc at
a vertex of exterior angle ``t`` by ``m = ceil(t / max_arc)`` edges *tangent* to it
(a circumscribed polyline, tangent at the arc's ends and at ``m - 1`` equally spaced
points). The result is convex, contains the exact sum (every edge line supports it), and
exceeds it by at most ``r (1 / cos(t / (2 m)) - 1) <= r (1 / cos(max_arc / 2) - 1)``,
reached at the new vertices. The default ``max_arc = 45 deg`` bounds the excess by
``0.0824 r`` (2.9 cm for ``r = 0.35 m``) and turns a rectangle into an octagon of 8
edges. A plain mitre (offset lines only) would spike at acute corners: the excess at a
corner of interior angle ``beta`` is ``r (1 / sin(beta / 2) - 1)``: 0.41 r at 90 deg,
2.9 r at 30 deg, 6.7 r at 15 deg. Measured (tests, shapely distances): the bound is
attained, 0.0824 r on every rectangle corner; 1.3 % more area than the exact sum on the
shipped industrial floor.

Scenario files (JSON)
---------------------
::

    {"name": "...", "description": "...",            (optional strings)
     "L": 1.2, "half_width": 0.35, "max_steer_deg": 45,
     "start": [x, y, theta_deg], "goal": [x, y, theta_deg],
     "bounds": [xmin, ymin, xmax, ymax],             (or null / absent: no walls)
     "obstacles": [[[x, y], [x, y], [x, y], ...], ...]}

Lengths in metres. **Angles in files are degrees**: ``theta`` of start and goal and
``max_steer_deg``; the Python API (``Pose``, ``Robot.max_steer``) uses radians.
Required keys: ``L``, ``start``, ``goal``, ``obstacles``; defaults: ``half_width`` 0,
``max_steer_deg`` 45, ``bounds`` none. Any other key is an error, so is a repeated key.
Polygons may be given in either orientation and are stored counter-clockwise; nothing
else is changed. A vertex that is repeated (also a closing copy of the first one) or
collinear with its neighbours is an error, as are non-convex and self-intersecting
polygons, NaN/Infinity literals and numbers that overflow to infinity.

A pose collides when its segment A->B touches an enlarged obstacle (closed sets:
touching is a collision); it is out of bounds unless the whole segment lies strictly
inside the bounds shrunk by ``half_width`` (:attr:`Scenario.free_bounds`). Scenarios
decide both with the collision module's pose tests; :func:`segment_hits_polygon` and
:func:`segment_in_bounds` here are the same tests in exact arithmetic (no tolerance).
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import numpy as np

from .pose import Pose, as_pose, check_length

TWO_PI = 2.0 * math.pi
#: Largest arc of the enlargement disk replaced by one tangent edge (radians).
DEFAULT_MAX_ARC = math.radians(45.0)
#: Turns within this angle (radians) of 0 or pi count as collinear vertices.
ANGLE_TOL = 1e-9
#: Edges shorter than this times the largest coordinate magnitude count as repeated vertices.
LENGTH_TOL = 1e-12
#: Scenario coordinates and lengths must not exceed this magnitude (the world's scale,
#: metres in files); L and a nonzero half_width must be at least MIN_LENGTH (a smaller
#: half_width would enlarge polygons by less than the spacing of floats near them).
WORLD_LIMIT = 1e6
MIN_LENGTH = 1e-6

REQUIRED_KEYS = ("L", "start", "goal", "obstacles")
OPTIONAL_KEYS = ("name", "description", "half_width", "max_steer_deg", "bounds")


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

    Raises
    ------
    ValueError
        Naming the argument, for a non-finite or out-of-range value.
    """

    L: float
    half_width: float = 0.0
    max_steer: float = math.radians(45.0)

    def __post_init__(self):
        object.__setattr__(self, "L", check_length(self.L, "L"))
        object.__setattr__(self, "half_width", _finite(self.half_width, "half_width", minimum=0.0))
        steer = _finite(self.max_steer, "max_steer")
        if not 0.0 < steer < 0.5 * math.pi:
            raise ValueError(
                f"max_steer must lie in (0, pi/2) radians, got {steer} ({math.degrees(steer)} deg)"
            )
        object.__setattr__(self, "max_steer", steer)

    @property
    def max_curvature(self) -> float:
        """Largest curvature of the rear path, ``tan(max_steer) / L`` (bicycle model)."""
        return math.tan(self.max_steer) / self.L

    @property
    def min_turning_radius(self) -> float:
        """Smallest turning radius of the rear point A, ``L / tan(max_steer)``."""
        return self.L / math.tan(self.max_steer)


def _finite(value, name: str, minimum: float | None = None) -> float:
    """A finite float (``>= minimum`` if given), else ValueError naming ``name``."""
    if isinstance(value, bool):
        raise ValueError(f"{name} must be a number, got {value!r}")
    try:
        x = float(value)
    except (TypeError, ValueError, OverflowError) as exc:
        raise ValueError(f"{name} must be a finite number, got {value!r}") from exc
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x}")
    if minimum is not None and x < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {x}")
    return x


# -- convex polygons ------------------------------------------------------------------
def check_convex_polygon(vertices, where: str = "polygon") -> np.ndarray:
    """Validate a strictly convex simple polygon and return it counter-clockwise.

    Parameters
    ----------
    vertices : array_like, shape (k, 2)
        The vertices in order, either orientation, without repeating the first one.
    where : str
        Names the polygon in error messages (e.g. ``"world.json: obstacles[3]"``).

    Returns
    -------
    ndarray, shape (k, 2)
        A new float array, counter-clockwise. Vertex indices in error messages refer to
        the input order.

    Raises
    ------
    ValueError
        Fewer than 3 vertices, wrong shape, non-finite numbers, a repeated vertex, a
        vertex collinear with its neighbours (including a degenerate, zero-area polygon
        and an edge doubling back), a non-convex polygon (turns of both signs), or a
        self-intersecting one whose turns all have one sign but add up to a multiple of
        2 pi other than one (e.g. a star pentagon: 4 pi).

    Notes
    -----
    The turn at vertex ``i`` is the signed angle from edge ``v[i] - v[i-1]`` to edge
    ``v[i+1] - v[i]``. A closed polygon is convex and simple iff all turns are nonzero,
    of one sign, and add up to ``+-2 pi``. Collinear means within ``ANGLE_TOL`` radians.
    """
    try:
        v = np.array(vertices, dtype=float)
    except (TypeError, ValueError, OverflowError) as exc:
        raise ValueError(f"{where}: vertices must be a (k, 2) array of numbers") from exc
    if v.ndim != 2 or v.shape[1] != 2:
        raise ValueError(f"{where}: vertices must have shape (k, 2), got shape {v.shape}")
    k = len(v)
    if k < 3:
        raise ValueError(f"{where}: a polygon needs at least 3 vertices, got {k}")
    bad = np.flatnonzero(~np.all(np.isfinite(v), axis=1))
    if bad.size:
        raise ValueError(f"{where}: vertex {bad[0]}: coordinates must be finite, got {v[bad[0]].tolist()}")
    # repeated vertices: exact duplicates anywhere, near-duplicates between neighbours
    _, first, inverse = np.unique(v, axis=0, return_index=True, return_inverse=True)
    dup = np.flatnonzero(first[inverse.ravel()] != np.arange(k))
    if dup.size:
        j = int(dup[0])
        i = int(first[inverse.ravel()[j]])
        hint = " (do not close the ring by repeating the first vertex)" if (i, j) == (0, k - 1) else ""
        raise ValueError(f"{where}: vertex {j} repeats vertex {i} {v[j].tolist()}{hint}")
    scale = float(np.abs(v).max())
    w = v / scale if scale > 0.0 else v  # turns are scale invariant; no overflow for huge inputs
    edges = _edges(w)  # edge i: v[i] -> v[i+1]
    short = np.flatnonzero(np.hypot(edges[:, 0], edges[:, 1]) <= LENGTH_TOL)
    if short.size:
        i = int(short[0])
        raise ValueError(f"{where}: vertex {(i + 1) % k} repeats vertex {i} up to rounding")
    prev = np.concatenate((edges[-1:], edges[:-1]))  # edge into vertex i
    cross = prev[:, 0] * edges[:, 1] - prev[:, 1] * edges[:, 0]
    dot = np.einsum("ij,ij->i", prev, edges)
    turn = np.arctan2(cross, dot)  # signed exterior angle at vertex i
    flat = np.flatnonzero((np.abs(turn) <= ANGLE_TOL) | (np.abs(turn) >= math.pi - ANGLE_TOL))
    if flat.size == k:
        raise ValueError(f"{where}: degenerate polygon, all vertices are collinear (zero area)")
    if flat.size:
        i = int(flat[0])
        how = "doubles back" if abs(turn[i]) > 0.5 * math.pi else "is collinear with its neighbours"
        raise ValueError(
            f"{where}: vertex {i} {v[i].tolist()} {how}; the polygon must be strictly convex (remove it)"
        )
    total = float(turn.sum())
    sign = math.copysign(1.0, total) if abs(total) > math.pi else math.copysign(1.0, _area2(w))
    wrong = np.flatnonzero(np.sign(turn) != sign)
    if wrong.size:
        right = np.flatnonzero(np.sign(turn) == sign)
        sense = ("counter-clockwise", "clockwise") if sign > 0 else ("clockwise", "counter-clockwise")
        raise ValueError(
            f"{where}: not convex: the boundary turns {sense[1]} at vertex {wrong[0]} {v[wrong[0]].tolist()} "
            f"but {sense[0]} at vertex {right[0]} (non-convex or self-intersecting)"
        )
    winding = round(abs(total) / TWO_PI)
    if winding != 1:
        raise ValueError(
            f"{where}: self-intersecting: the boundary turns through {winding} x 360 deg "
            "(a star-like polygon); a convex polygon turns through 360 deg once"
        )
    return np.ascontiguousarray(v if sign > 0 else v[::-1])


def _area2(v: np.ndarray) -> float:
    """Twice the signed area (shoelace), positive for counter-clockwise polygons."""
    x, y = v[:, 0], v[:, 1]
    e = _edges(v)
    return float(np.dot(x, e[:, 1]) - np.dot(e[:, 0], y))  # sum x_i y_i+1 - x_i+1 y_i


def _edges(v: np.ndarray) -> np.ndarray:
    """Edge vectors ``v[i+1] - v[i]`` of a closed polygon (the last one back to ``v[0]``)."""
    e = np.empty_like(v)
    np.subtract(v[1:], v[:-1], out=e[:-1])
    np.subtract(v[0], v[-1], out=e[-1])
    return e


def enlarge_polygon(polygon, half_width: float, max_arc: float = DEFAULT_MAX_ARC) -> np.ndarray:
    """Convex polygon containing the Minkowski sum of ``polygon`` and a disk.

    Parameters
    ----------
    polygon : array_like, shape (k, 2)
        Counter-clockwise strictly convex polygon (as from :func:`check_convex_polygon`;
        not re-validated).
    half_width : float
        Disk radius ``r >= 0``. For ``r == 0`` a copy of the polygon is returned.
    max_arc : float
        Largest arc (radians, in ``(0, pi/2]``) of the disk replaced by one tangent edge.

    Returns
    -------
    ndarray, shape (n, 2)
        Counter-clockwise convex polygon: the edges offset by ``r`` plus, at a vertex of
        exterior angle ``t``, ``m = ceil(t / max_arc)`` edges tangent to the arc there.
        Its new vertex ``j`` at polygon vertex ``p`` is ``p + r / cos(t / 2m) u(a + (j +
        1/2) t / m)``, ``u(a)`` the unit vector of the incoming edge's outward normal.

    Notes
    -----
    Contains the exact sum and exceeds it by at most ``r (1 / cos(max_arc / 2) - 1)``
    (:func:`enlargement_excess`), see the module docstring. The paper enlarges obstacles
    off-line without saying how.
    """
    r = _finite(half_width, "half_width", minimum=0.0)
    step = _finite(max_arc, "max_arc")
    if not 0.0 < step <= 0.5 * math.pi:
        raise ValueError(f"max_arc must lie in (0, pi/2] radians, got {step}")
    v = np.asarray(polygon, dtype=float)
    if r == 0.0:
        return v.copy()
    e = _edges(v)
    a_out = np.arctan2(-e[:, 0], e[:, 1])  # angle of edge i's outward normal (ey, -ex)
    a_in = np.concatenate((a_out[-1:], a_out[:-1]))  # normal of the edge entering vertex i
    t = np.mod(a_out - a_in, TWO_PI)  # exterior angle at vertex i, in (0, pi)
    m = np.maximum(1, np.ceil(t / step - 1e-12)).astype(int)
    phi = t / m  # arc per tangent edge
    idx = np.repeat(np.arange(len(v)), m)
    j = np.arange(idx.size) - np.repeat(np.cumsum(m) - m, m)  # 0..m_i-1 within vertex i
    ang = a_in[idx] + (j + 0.5) * phi[idx]
    rad = r / np.cos(0.5 * phi[idx])  # circumscribed: r / cos(phi / 2)
    return v[idx] + rad[:, None] * np.column_stack((np.cos(ang), np.sin(ang)))


def enlargement_excess(half_width: float, max_arc: float = DEFAULT_MAX_ARC) -> float:
    """Bound on how far :func:`enlarge_polygon` exceeds the exact sum: ``r (sec(max_arc/2) - 1)``."""
    return float(half_width) * (1.0 / math.cos(0.5 * float(max_arc)) - 1.0)


# -- exact segment and polygon tests (separating axes) -----------------------------------
def pose_segment(pose, L: float) -> tuple[np.ndarray, np.ndarray]:
    """End points A (rear axle) and B = A + L (cos theta, sin theta) of the robot at ``pose``."""
    x, y, th = as_pose(pose)
    return np.array([x, y]), np.array([x + L * math.cos(th), y + L * math.sin(th)])


def segment_hits_polygon(a, b, polygon) -> bool:
    """Does the closed segment ``a``-``b`` touch the closed convex polygon? (exact SAT).

    Separating-axis theorem: two convex sets are disjoint iff some edge normal of one of
    them separates them. The axes are the polygon's outward edge normals (both end points
    strictly outside one edge's half-plane) and the segment's normal (all vertices
    strictly on one side of the segment's line). Touching counts as a hit.

    Parameters
    ----------
    a, b : array_like, shape (2,)
    polygon : array_like, shape (k, 2)
        Counter-clockwise convex polygon (not re-validated).
    """
    v = np.asarray(polygon, dtype=float)
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    e = _edges(v)
    n = np.column_stack((e[:, 1], -e[:, 0]))  # outward normals of a CCW polygon
    sa = np.einsum("ij,ij->i", n, a - v)
    sb = np.einsum("ij,ij->i", n, b - v)
    if np.any((sa > 0.0) & (sb > 0.0)):
        return False
    d = b - a
    side = d[0] * (v[:, 1] - a[1]) - d[1] * (v[:, 0] - a[0])
    if np.all(side > 0.0) or np.all(side < 0.0):
        return False
    return True


def polygons_overlap(p, q) -> bool:
    """Do two closed convex polygons (counter-clockwise) touch or overlap? (exact SAT)."""
    p = np.asarray(p, dtype=float)
    q = np.asarray(q, dtype=float)
    for s, t in ((p, q), (q, p)):
        e = _edges(s)
        n = np.column_stack((e[:, 1], -e[:, 0]))
        # dist[i, j]: signed offset of t's vertex j from s's edge i
        dist = n @ t.T - np.einsum("ij,ij->i", n, s)[:, None]
        if np.any(np.all(dist > 0.0, axis=1)):
            return False
    return True


def segment_in_bounds(a, b, bounds) -> bool:
    """Is the segment strictly inside the rectangle ``(xmin, ymin, xmax, ymax)``?"""
    xmin, ymin, xmax, ymax = bounds
    xs = (a[0], b[0])
    ys = (a[1], b[1])
    return xmin < min(xs) and max(xs) < xmax and ymin < min(ys) and max(ys) < ymax


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
        The obstacles as given, counter-clockwise, read-only.
    enlarged : tuple of ndarray (n, 2)
        The obstacles enlarged by ``robot.half_width`` (:func:`enlarge_polygon`), the
        polygons the segment is planned among; read-only.
    name, description : str
    path : Path or None
        The file it was loaded from.
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

    def pose_conflict(self, pose) -> str | None:
        """Why ``pose`` is not free (``"obstacles[i]"`` or ``"bounds"``), or None if it is free.

        Uses :func:`segplan.collision.pose_collides` and :func:`~segplan.collision.pose_in_bounds`,
        the planner's own tests (separating axes; touching, within their relative tolerance
        of 1e-9, counts), so a scenario that loads has a start and goal the planner accepts.
        """
        from .collision import pose_collides, pose_in_bounds  # lazy: collision may import world

        fb = self.free_bounds
        if fb is not None and not pose_in_bounds(pose, self.robot.L, fb):
            return "bounds"
        for i, poly in enumerate(self.enlarged):
            if pose_collides(pose, self.robot.L, poly, check=False):
                return f"obstacles[{i}]"
        return None

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
        out["start"] = [self.start.x, self.start.y, math.degrees(self.start.theta)]
        out["goal"] = [self.goal.x, self.goal.y, math.degrees(self.goal.theta)]
        out["bounds"] = None if self.bounds is None else list(self.bounds)
        out["obstacles"] = [p.tolist() for p in self.obstacles]
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
    obstacles: Sequence = (),
    bounds: Sequence[float] | None = None,
    *,
    name: str = "",
    description: str = "",
    path: Path | None = None,
    max_arc: float = DEFAULT_MAX_ARC,
    source: str = "<python>",
) -> Scenario:
    """Validate a planning problem and build a :class:`Scenario` (Python API: radians).

    Raises
    ------
    ScenarioError
        Naming ``source``: bad robot parameters, poses, bounds (not a proper rectangle,
        or narrower than the robot), polygons (see :func:`check_convex_polygon`), or a
        start or goal that collides with an enlarged obstacle or leaves the free bounds.
    """
    if not isinstance(robot, Robot):
        raise ScenarioError(f"{source}: robot must be a Robot, got {type(robot).__name__}")
    if not MIN_LENGTH <= robot.L <= WORLD_LIMIT:
        raise ScenarioError(f"{source}: L={robot.L} is outside [{MIN_LENGTH:g}, {WORLD_LIMIT:g}]")
    if robot.half_width > WORLD_LIMIT or 0.0 < robot.half_width < MIN_LENGTH:
        raise ScenarioError(
            f"{source}: half_width={robot.half_width} must be 0 or within [{MIN_LENGTH:g}, {WORLD_LIMIT:g}]"
        )
    try:
        start_p = as_pose(start, "start")
        goal_p = as_pose(goal, "goal")
    except ValueError as exc:
        raise ScenarioError(f"{source}: {exc}") from None
    for label, pose in (("start", start_p), ("goal", goal_p)):
        _check_scale(pose[:2], f"{source}: {label}")
    if bounds is not None:
        try:
            b = tuple(_finite(x, "bounds") for x in bounds)
        except (TypeError, ValueError) as exc:
            raise ScenarioError(f"{source}: bounds must be four finite numbers: {exc}") from None
        if len(b) != 4:
            raise ScenarioError(f"{source}: bounds must be [xmin, ymin, xmax, ymax], got {len(b)} numbers")
        if not (b[0] < b[2] and b[1] < b[3]):
            raise ScenarioError(
                f"{source}: bounds {list(b)} are not a rectangle: need xmin < xmax and ymin < ymax"
            )
        if min(b[2] - b[0], b[3] - b[1]) <= 2.0 * robot.half_width:
            raise ScenarioError(f"{source}: bounds {list(b)} leave no room for half_width={robot.half_width}")
        _check_scale(b, f"{source}: bounds")
        bounds = b
    try:
        items = list(obstacles)
    except TypeError:
        raise ScenarioError(
            f"{source}: obstacles must be a sequence of polygons, got {_brief(obstacles)}"
        ) from None
    polys = []
    for i, p in enumerate(items):
        try:
            poly = check_convex_polygon(p, where=f"{source}: obstacles[{i}]")
        except ValueError as exc:
            raise ScenarioError(str(exc)) from None
        if np.abs(poly).max() > WORLD_LIMIT:
            j = int(np.flatnonzero(np.abs(np.asarray(p, dtype=float)).max(axis=1) > WORLD_LIMIT)[0])
            raise ScenarioError(f"{source}: obstacles[{i}] vertex {j}: coordinates exceed +-{WORLD_LIMIT:g}")
        poly.flags.writeable = False
        polys.append(poly)
    enlarged = []
    for p in polys:
        e = enlarge_polygon(p, robot.half_width, max_arc)
        e.flags.writeable = False
        enlarged.append(e)
    sc = Scenario(robot, start_p, goal_p, bounds, tuple(polys), tuple(enlarged), name, description, path)
    for label, pose in (("start", start_p), ("goal", goal_p)):
        conflict = sc.pose_conflict(pose)
        if conflict == "bounds":
            raise ScenarioError(
                f"{source}: {label} pose {_show(pose)} is out of bounds: its segment of length L={robot.L} "
                f"must lie strictly inside the bounds shrunk by half_width, {list(sc.free_bounds)}"
            )
        if conflict is not None:
            raise ScenarioError(
                f"{source}: {label} pose {_show(pose)} collides with {conflict} "
                f"enlarged by half_width={robot.half_width} (segment of length L={robot.L})"
            )
    return sc


def _check_scale(values, where: str) -> None:
    if any(abs(x) > WORLD_LIMIT for x in values):
        raise ScenarioError(f"{where}: coordinates {list(values)} exceed +-{WORLD_LIMIT:g}")


def _show(p: Pose) -> str:
    return f"(x={p.x:g}, y={p.y:g}, theta={math.degrees(p.theta):g} deg)"


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
    try:
        robot = Robot(L, half_width, math.radians(steer))
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
        if path not in shipped_scenarios():
            raise ScenarioError(
                f"{path!r} is neither a file nor a shipped scenario (one of {', '.join(shipped_scenarios())})"
            )
        resource = resources.files("segplan") / "scenarios" / f"{path}.json"
        return loads_scenario(resource.read_bytes(), source=f"segplan/scenarios/{path}.json")
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise ScenarioError(f"{p}: cannot read: {exc.strerror or exc}") from None
    return loads_scenario(raw, source=str(p), path=p)


def shipped_scenarios() -> tuple[str, ...]:
    """Names of the scenarios shipped with segplan (package data), sorted.

    ``load_scenario(name)`` reads one of them; in a clone of the repository they are the
    files of ``scenarios/``, which ``segplan/scenarios`` links to.
    """
    folder = resources.files("segplan") / "scenarios"
    return tuple(sorted(f.name[: -len(".json")] for f in folder.iterdir() if f.name.endswith(".json")))


def save_scenario(scenario: Scenario, path) -> Path:
    """Write ``scenario.to_json()`` to ``path`` and return the path."""
    p = Path(path)
    p.write_text(scenario.to_json(), encoding="utf-8")
    return p


# -- random worlds --------------------------------------------------------------------
def random_convex_polygon(
    rng: np.random.Generator, center, radius: float, max_vertices: int = 6
) -> np.ndarray:
    """A random strictly convex polygon inscribed in an ellipse of semi-axes ``radius``, ``<= radius``.

    ``k`` in ``[3, max_vertices]`` vertices at jittered equally spaced angles (gaps of at
    least 0.4 of ``2 pi / k``), axes ratio in ``[0.35, 1]``, random rotation.
    """
    k = int(rng.integers(3, max_vertices + 1))
    ang = (np.arange(k) + rng.uniform(-0.3, 0.3, k)) * (TWO_PI / k)
    ratio = rng.uniform(0.35, 1.0)
    local = np.column_stack((radius * np.cos(ang), ratio * radius * np.sin(ang)))
    rot = rng.uniform(0.0, TWO_PI)
    c, s = math.cos(rot), math.sin(rot)
    return np.asarray(center, dtype=float) + local @ np.array([[c, s], [-s, c]])


def random_world(
    seed: int,
    n_obstacles: int,
    bounds: Sequence[float] = (0.0, 0.0, 30.0, 20.0),
    robot: Robot | None = None,
    *,
    start=None,
    goal=None,
    radius: tuple[float, float] = (0.5, 2.0),
    max_vertices: int = 6,
    heading_spread: float = 0.5 * math.pi,
    clearance: float | None = None,
    min_gap: float | None = 0.0,
    max_tries: int | None = None,
) -> Scenario:
    """A deterministic random world of convex obstacles with a free start and goal.

    Parameters
    ----------
    seed : int
        Seed of ``numpy.random.default_rng``; the same arguments give the same world.
    n_obstacles : int
        Exactly this many obstacles are placed (or ValueError).
    bounds : (xmin, ymin, xmax, ymax)
    robot : Robot, optional
        Default ``Robot(L=1.2, half_width=0.3)``.
    start, goal : (x, y, theta radians), optional
        Default: start in the left quarter and goal in the right quarter of the free
        bounds, headings uniform in ``[-heading_spread, heading_spread]`` around +x.
    radius : (min, max)
        Range of the obstacles' circumscribed radii; obstacles lie inside the bounds.
    max_vertices : int
        Obstacles have 3 to ``max_vertices`` vertices.
    clearance : float, optional
        Free distance kept between the start and goal segments and every enlarged
        obstacle. Default ``robot.L``.
    min_gap : float or None
        Free gap kept between enlarged obstacles (default 0: they do not overlap); None
        lets obstacles overlap.
    max_tries : int, optional
        Samples before giving up, default ``100 * (n_obstacles + 1)``.

    Raises
    ------
    ValueError
        Bad arguments, or the obstacles do not fit within ``max_tries`` samples.
    """
    robot = Robot(L=1.2, half_width=0.3) if robot is None else robot
    if not isinstance(robot, Robot):
        raise ValueError(f"robot must be a Robot, got {type(robot).__name__}")
    if isinstance(n_obstacles, bool) or not isinstance(n_obstacles, int | np.integer) or n_obstacles < 0:
        raise ValueError(f"n_obstacles must be an integer >= 0, got {n_obstacles!r}")
    if isinstance(max_vertices, bool) or not isinstance(max_vertices, int | np.integer) or max_vertices < 3:
        raise ValueError(f"max_vertices must be an integer >= 3, got {max_vertices!r}")
    try:
        rmin, rmax = (_finite(x, "radius") for x in radius)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"radius must be (min, max) finite numbers, got {radius!r}") from exc
    if not 0.0 < rmin <= rmax:
        raise ValueError(f"radius must be (min, max) with 0 < min <= max, got {radius}")
    spread = _finite(heading_spread, "heading_spread", minimum=0.0)
    clear = robot.L if clearance is None else _finite(clearance, "clearance", minimum=0.0)
    gap = None if min_gap is None else _finite(min_gap, "min_gap", minimum=0.0)
    tries = 100 * (n_obstacles + 1) if max_tries is None else int(max_tries)
    try:
        xmin, ymin, xmax, ymax = (_finite(b, "bounds") for b in bounds)
    except (TypeError, ValueError) as exc:
        raise ValueError(
            f"bounds must be four finite numbers (xmin, ymin, xmax, ymax), got {bounds!r}"
        ) from exc
    if not (xmin < xmax and ymin < ymax) or min(xmax - xmin, ymax - ymin) <= 2.0 * (rmax + robot.half_width):
        raise ValueError(
            f"bounds {bounds!r} are not a rectangle large enough for obstacles of radius up to {rmax}"
        )
    fb = (xmin + robot.half_width, ymin + robot.half_width, xmax - robot.half_width, ymax - robot.half_width)
    rng = np.random.default_rng(seed)

    def sample_pose(x_lo: float, x_hi: float) -> Pose:
        for _ in range(tries):
            p = Pose(rng.uniform(x_lo, x_hi), rng.uniform(fb[1], fb[3]), rng.uniform(-spread, spread))
            a, b = pose_segment(p, robot.L)
            if segment_in_bounds(a, b, fb):
                return p
        raise ValueError(
            f"no pose of length L={robot.L} fits in x in [{x_lo}, {x_hi}] within {tries} samples"
        )

    quarter = 0.25 * (fb[2] - fb[0])
    start_p = as_pose(start, "start") if start is not None else sample_pose(fb[0], fb[0] + quarter)
    goal_p = as_pose(goal, "goal") if goal is not None else sample_pose(fb[2] - quarter, fb[2])
    keep_out = [pose_segment(p, robot.L) for p in (start_p, goal_p)]
    placed: list[np.ndarray] = []
    grown: list[np.ndarray] = []  # placed obstacles enlarged by half_width + min_gap / 2
    boxes = np.empty((n_obstacles, 4))  # their bounding boxes, a cheap first test
    for _ in range(tries):
        if len(placed) == n_obstacles:
            break
        r = rng.uniform(rmin, rmax)
        center = (rng.uniform(xmin + r, xmax - r), rng.uniform(ymin + r, ymax - r))
        poly = random_convex_polygon(rng, center, r, max_vertices)  # convex and CCW by construction
        guard = enlarge_polygon(poly, robot.half_width + clear)
        if any(segment_hits_polygon(a, b, guard) for a, b in keep_out):
            continue
        if gap is not None:
            g = enlarge_polygon(poly, robot.half_width + 0.5 * gap)
            lo, hi = g.min(axis=0), g.max(axis=0)
            n = len(grown)
            near = np.flatnonzero(
                (boxes[:n, 0] <= hi[0])
                & (lo[0] <= boxes[:n, 2])
                & (boxes[:n, 1] <= hi[1])
                & (lo[1] <= boxes[:n, 3])
            )
            if any(polygons_overlap(g, grown[i]) for i in near):
                continue
            boxes[n] = (*lo, *hi)
            grown.append(g)
        placed.append(poly)
    if len(placed) < n_obstacles:
        raise ValueError(
            f"placed only {len(placed)} of {n_obstacles} obstacles within {tries} samples; "
            "use fewer or smaller obstacles, larger bounds, or min_gap=None"
        )
    return make_scenario(
        robot,
        start_p,
        goal_p,
        placed,
        (xmin, ymin, xmax, ymax),
        name=f"random_world(seed={seed}, n_obstacles={n_obstacles})",
        source=f"random_world(seed={seed})",
    )
