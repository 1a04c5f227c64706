"""Plot helpers shared by the book's notebooks and the command line.

This is the only module of :mod:`segplan` that imports matplotlib; the algorithms never
do (import it as ``segplan.viz.plot``; ``import segplan`` does not load it). Every function
draws on a given :class:`matplotlib.axes.Axes` (a new figure and axes when ``ax`` is
``None``) and returns the axes. Plane plots carry ``x [m]``, ``y [m]`` labels and an equal
aspect ratio.

What is drawn follows the paper's model (section "Mobile robot modelling"): the robot is
the oriented segment from A (middle of the rear axle) to B (middle of the front wheel); a
union between two nodes is the cubic followed by A, and its cost, formula [1], is the
length of the path followed by B.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.patches import Polygon as PolygonPatch
from matplotlib.patches import Rectangle

from ..floor.geometry import check_bounds
from ..floor.maps import Floor
from ..floor.scenario import Robot, Scenario
from ..model.cost import longd_exact
from ..model.pose import Pose, as_pose, check_length, feasible_alpha_interval, intrinsic
from ..model.union import Union

__all__ = [
    "FRONT_LABEL",
    "FRONT_STYLE",
    "REAR_LABEL",
    "REAR_STYLE",
    "REVERSE_COLOR",
    "ROBOT_STYLE",
    "has_body",
    "legend_beside",
    "plot_body",
    "plan_figure",
    "plot_bounds",
    "plot_floor",
    "plot_longd",
    "plot_plan",
    "plot_polygons",
    "plot_pose",
    "plot_union",
]

REAR_STYLE = {"linestyle": "-", "linewidth": 1.8}
FRONT_STYLE = {"linestyle": "--", "linewidth": 1.4}
ROBOT_STYLE = {"color": "0.35", "linewidth": 1.0}
#: Legend labels of the two paths of a plan: the rear-axle point A's and the front wheel B's
#: (whose length is LONGD, formula [1]).
REAR_LABEL = "rear path A"
FRONT_LABEL = "front-wheel path B"


# -- helpers ---------------------------------------------------------------------------
def _axes(ax: Axes | None, figsize: tuple[float, float] = (7.0, 4.5)) -> Axes:
    """Return ``ax``, or the axes of a new figure when it is ``None``."""
    if ax is None:
        _, ax = plt.subplots(figsize=figsize)
    elif not isinstance(ax, Axes):
        raise ValueError(f"ax must be a matplotlib Axes or None, got {type(ax).__name__}")
    return ax


def _plane(ax: Axes) -> Axes:
    """Label a world-plane plot in metres with an equal aspect ratio."""
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_aspect("equal", adjustable="datalim")
    return ax


def _check_count(value: int, name: str, minimum: int) -> int:
    if isinstance(value, bool) or int(value) != value or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def _vertices(polygon, name: str) -> np.ndarray:
    """Vertices ``(k, 2)`` of a polygon given as an array-like or a shapely-like polygon."""
    exterior = getattr(polygon, "exterior", None)
    coords = exterior.coords if exterior is not None else polygon
    try:
        xy = np.asarray(coords, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a (k, 2) array of vertices or a polygon, got {polygon!r}") from exc
    if xy.ndim != 2 or xy.shape[1] != 2 or xy.shape[0] < 3:
        raise ValueError(f"{name} must have at least 3 vertices of shape (k, 2), got shape {xy.shape}")
    if not np.all(np.isfinite(xy)):
        raise ValueError(f"{name} must have finite vertices")
    return xy


# -- the robot, a union, a plan --------------------------------------------------------
def plot_pose(
    pose: Sequence[float] | Pose,
    L: float,
    ax: Axes | None = None,
    *,
    color: str = "0.2",
    label: str | None = None,
    linewidth: float = 2.0,
) -> Axes:
    """Draw the robot at ``pose`` as the oriented segment A->B of length ``L``.

    A (rear axle, the pose's point) is marked with a dot, B (front wheel) with an arrow
    head (section "Mobile robot modelling", Fig. 2).

    Raises
    ------
    ValueError
        Malformed ``pose`` or ``L <= 0``.
    """
    p = as_pose(pose, "pose")
    L = check_length(L)
    ax = _axes(ax)
    b = (p.x + L * math.cos(p.theta), p.y + L * math.sin(p.theta))
    ax.plot([p.x, b[0]], [p.y, b[1]], color=color, linewidth=linewidth, label=label, solid_capstyle="butt")
    ax.plot([p.x], [p.y], "o", color=color, markersize=4)
    ax.annotate(
        "",
        xy=b,
        xytext=(p.x + 0.6 * L * math.cos(p.theta), p.y + 0.6 * L * math.sin(p.theta)),
        arrowprops={"arrowstyle": "-|>", "color": color, "linewidth": linewidth, "shrinkA": 0, "shrinkB": 0},
    )
    return _plane(ax)


def plot_body(
    pose: Sequence[float] | Pose,
    robot: Robot,
    ax: Axes | None = None,
    *,
    color: str = "0.2",
    alpha: float = 0.3,
    label: str | None = None,
) -> Axes:
    """Draw the robot's body at ``pose``: its footprint (:meth:`segplan.Robot.footprint`, the
    round body or the rectangle, overhangs included), filled, over the segment A->B
    (:func:`plot_pose`).

    Raises
    ------
    ValueError
        Malformed ``pose``, or ``robot`` not a :class:`segplan.Robot`.
    """
    _check_robot(robot)
    p = as_pose(pose, "pose")
    ax = _axes(ax)
    _add_body(ax, robot, p.x, p.y, p.theta, facecolor=color, edgecolor=color, alpha=alpha)
    return plot_pose(p, robot.L, ax, color=color, label=label)


def _check_robot(robot) -> Robot:
    if not isinstance(robot, Robot):
        raise ValueError(f"robot must be a segplan.Robot, got {type(robot).__name__}")
    return robot


def has_body(robot: Robot | None) -> bool:
    """Has ``robot`` a body beyond the paper's (overhangs or a rectangle)? Drawings show such a
    body (:func:`plot_body`); the paper's robot keeps its segments."""
    return robot is not None and (robot.axis != (0.0, robot.L) or robot.rectangle)


def _add_body(ax: Axes, robot: Robot, x: float, y: float, theta: float, **style) -> None:
    """The footprint (:meth:`segplan.Robot.footprint`) placed at the pose, as a patch."""
    c, s = math.cos(theta), math.sin(theta)
    outline = robot.footprint() @ np.array([[c, s], [-s, c]]) + (x, y)
    ax.add_patch(PolygonPatch(outline, closed=True, **style))


def plot_union(
    union: Union,
    ax: Axes | None = None,
    *,
    n: int = 201,
    robots: int = 7,
    rear: bool = True,
    front: bool = True,
    ends: bool = True,
    color: str | None = None,
    label: str | None = None,
    legend: bool = True,
    robot: Robot | None = None,
) -> Axes:
    """Draw a union: the rear path (A, solid), the front-wheel path (B, dashed) and the robot.

    Parameters
    ----------
    union : Union
        The cubic union of two nodes in its alpha reference system.
    ax : Axes, optional
        Where to draw; a new figure when ``None``.
    n : int
        Samples per path (>= 2).
    robots : int
        Number of robot segments A->B drawn at equally spaced frame abscissae, ends
        included (0 for none, otherwise >= 2).
    rear, front : bool
        Draw the rear-axle path and the front-wheel path (whose length is LONGD, [1]).
    ends : bool
        Draw the two nodes as oriented segments.
    color : str, optional
        Colour of both paths (the next colour of the cycle when ``None``).
    label : str, optional
        Legend label of the rear path (the front-wheel path, same colour, dashed, then stays
        out of the legend); without one the paths are labelled :data:`REAR_LABEL` and
        :data:`FRONT_LABEL`.
    legend : bool
        Give the paths legend labels (``False`` keeps them out of the legend).
    robot : Robot, optional
        The robot (its ``L`` the union's): with a body beyond the paper's (:func:`has_body`),
        its footprint is drawn, unfilled, at every robot pose drawn (the ends included);
        otherwise (None, the paper's robot) the segments alone.

    Raises
    ------
    ValueError
        ``union`` is not a :class:`segplan.Union`, bad ``n`` / ``robots``, or ``robot`` not a
        :class:`segplan.Robot`.
    """
    if not isinstance(union, Union):
        raise ValueError(f"union must be a segplan.Union, got {type(union).__name__}")
    if robot is not None:
        _check_robot(robot)
    n = _check_count(n, "n", 2)
    robots = _check_count(robots, "robots", 0)
    if robots == 1:
        raise ValueError("robots must be 0 or >= 2 (the ends are always included), got 1")
    ax = _axes(ax)
    rear_label = (label or REAR_LABEL) if legend else "_nolegend_"
    front_label = FRONT_LABEL if legend and not label else "_nolegend_"
    if rear:
        a = union.rear(n)
        (line,) = ax.plot(a[:, 0], a[:, 1], color=color, label=rear_label, **REAR_STYLE)
        color = line.get_color()  # the next colour of the cycle when none was given
    if front:
        b = union.front(n)
        ax.plot(b[:, 0], b[:, 1], color=color, label=front_label, **FRONT_STYLE)
    if robots:
        a, b = union.rear(robots), union.front(robots)
        segs = np.stack((a, b), axis=1)  # (robots, 2 points, 2 coordinates)
        for s in segs[1:-1] if ends else segs:
            ax.plot(s[:, 0], s[:, 1], **ROBOT_STYLE)
        if has_body(robot):
            for (x, y), (bx, by) in segs:
                _add_body(ax, robot, x, y, math.atan2(by - y, bx - x), fill=False, **ROBOT_STYLE)
    if ends:
        for p in (union.p0, union.p1):
            plot_pose(p, union.L, ax, color="0.15", linewidth=1.6)
    return _plane(ax)


def plot_plan(
    unions: Iterable[Union],
    ax: Axes | None = None,
    *,
    obstacles: Iterable | None = None,
    bounds: Sequence[float] | None = None,
    robots: int = 3,
    color: str = "C0",
    label: str | None = None,
    robot: Robot | None = None,
) -> Axes:
    """Draw a plan, a sequence of unions joined at their nodes, over obstacles and bounds.

    Parameters
    ----------
    unions : iterable of Union
        Consecutive unions of the plan (search result, section "Results. Graph-search").
    obstacles : iterable of polygons, optional
        Passed to :func:`plot_polygons`.
    bounds : (xmin, ymin, xmax, ymax), optional
        Passed to :func:`plot_bounds`.
    robots : int
        Robot segments drawn per union (0 or >= 2).
    color : str
        Colour of the paths.
    label : str, optional
        Legend label of the plan's rear path, given once (the front-wheel path then stays out
        of the legend, as in :func:`plot_union`); without one both paths get a legend entry,
        :data:`REAR_LABEL` and :data:`FRONT_LABEL`.
    robot : Robot, optional
        With a body beyond the paper's, drawn at the robot poses (:func:`plot_union`).

    Raises
    ------
    ValueError
        An item is not a Union, the plan is empty, or ``robot`` is not a Robot.
    """
    unions = list(unions)
    if not unions:
        raise ValueError("unions must hold at least one segplan.Union")
    for i, u in enumerate(unions):
        if not isinstance(u, Union):
            raise ValueError(f"unions[{i}] must be a segplan.Union, got {type(u).__name__}")
    ax = _axes(ax)
    if bounds is not None:
        plot_bounds(bounds, ax)
    if obstacles is not None:
        plot_polygons(obstacles, ax)
    for i, u in enumerate(unions):
        plot_union(u, ax, robots=robots, color=color, label=label, legend=i == 0, robot=robot)
    return _plane(ax)


def legend_beside(ax: Axes, **kwargs):
    """The axes' legend outside them, on their right, top-aligned: never over a wall or an obstacle.

    A figure saved with ``bbox_inches="tight"``, or laid out by matplotlib's constrained
    layout, makes room for it. ``kwargs`` go to :meth:`matplotlib.axes.Axes.legend`.
    """
    options = {"loc": "upper left", "bbox_to_anchor": (1.02, 1.0), "borderaxespad": 0.0, "fontsize": "small"}
    return ax.legend(**(options | kwargs))


# -- the world -------------------------------------------------------------------------
def plot_polygons(
    polygons: Iterable,
    ax: Axes | None = None,
    *,
    facecolor: str = "0.75",
    edgecolor: str = "0.25",
    label: str | None = "obstacle",
) -> Axes:
    """Fill polygons (obstacles, section "Collision-detection algorithm").

    Parameters
    ----------
    polygons : iterable
        Each a ``(k, 2)`` array-like of vertices (k >= 3) or an object with
        ``.exterior.coords`` (a shapely Polygon).
    label : str, optional
        Legend label, given to the first polygon only.

    Raises
    ------
    ValueError
        A polygon with fewer than 3 vertices, a wrong shape or non-finite vertices.
    """
    ax = _axes(ax)
    for i, poly in enumerate(polygons):
        xy = _vertices(poly, f"polygons[{i}]")
        ax.add_patch(
            PolygonPatch(
                xy,
                closed=True,
                facecolor=facecolor,
                edgecolor=edgecolor,
                linewidth=1.0,
                label=label if i == 0 else None,
            )
        )
    ax.autoscale_view()
    return _plane(ax)


def plot_bounds(bounds: Sequence[float], ax: Axes | None = None, *, color: str = "0.1") -> Axes:
    """Outline the rectangular workspace ``(xmin, ymin, xmax, ymax)`` in metres.

    Raises
    ------
    ValueError
        Not four finite numbers with ``xmin < xmax`` and ``ymin < ymax``.
    """
    b = check_bounds(bounds)
    ax = _axes(ax)
    width, height = b[2] - b[0], b[3] - b[1]
    ax.add_patch(Rectangle((b[0], b[1]), width, height, fill=False, edgecolor=color, linewidth=1.5))
    ax.autoscale_view()
    return _plane(ax)


def plot_floor(
    scenario: Scenario | Floor,
    ax: Axes | None = None,
    *,
    enlarged: tuple[str, str] = ("0.85", "0.25"),
    obstacles: tuple[str, str] = ("0.55", "0.25"),
    bounds: bool = True,
    poses: bool = True,
    pose_color: str = "0.2",
) -> Axes:
    """Draw a scenario's floor: walls, enlarged obstacles, obstacles, start and goal.

    The planning model of section "Results. Graph-search": the obstacles (darker) inside
    their enlargement by the robot's half-width (lighter), in which the segment A->B is
    planned, and the robot at start and goal (:func:`plot_pose`). A :class:`segplan.Floor`
    (a map before a robot is put in it) has walls and obstacles only.

    Parameters
    ----------
    scenario : segplan.Scenario or segplan.Floor
    enlarged, obstacles : (facecolor, edgecolor)
        Colours of the enlarged and of the given obstacles (legend labels "enlarged
        obstacle" and "obstacle"); the enlargement is drawn for a robot of positive
        half-width only.
    bounds : bool
        Outline the walls (if the scenario has any, :func:`plot_bounds`).
    poses : bool
        Draw the robot at start and goal, in ``pose_color``.

    Raises
    ------
    ValueError
        ``scenario`` is neither a :class:`segplan.Scenario` nor a :class:`segplan.Floor`.
    """
    if not isinstance(scenario, Scenario | Floor):
        raise ValueError(
            f"scenario must be a segplan.Scenario or a segplan.Floor, got {type(scenario).__name__}"
        )
    ax = _axes(ax)
    if bounds and scenario.bounds is not None:
        plot_bounds(scenario.bounds, ax)
    is_scenario = isinstance(scenario, Scenario)
    if is_scenario and scenario.robot.half_width > 0:
        plot_polygons(
            scenario.enlarged, ax, facecolor=enlarged[0], edgecolor=enlarged[1], label="enlarged obstacle"
        )
    plot_polygons(scenario.outlines, ax, facecolor=obstacles[0], edgecolor=obstacles[1], label="obstacle")
    if poses and is_scenario:
        for pose in (scenario.start, scenario.goal):
            plot_pose(pose, scenario.L, ax, color=pose_color)
    return _plane(ax)


def plan_figure(
    floor: Scenario | Floor,
    unions: Iterable[Union] = (),
    title: str = "",
    directions: Sequence[int] = (),
    *,
    figsize=(10.0, 7.0),
):
    """A figure of a floor and a plan on it, to save to a file (the command line's ``--out``).

    The floor (:func:`plot_floor`), the plan's unions if any (:func:`plot_plan`: the rear path
    A, the dashed front-wheel path B, the robot at intervals, with its body if it has one
    beyond the paper's, :func:`has_body`), a scenario's start (green) and goal (red) (with
    that body, :func:`plot_body`),
    every one in the legend and the legend beside the floor (:func:`legend_beside`).
    ``directions``: a plan's :attr:`segplan.Plan.directions` (``()``: all forwards); the
    links driven backwards are drawn in :data:`REVERSE_COLOR` under their own legend
    entries and each cusp (a change of direction) is marked by a cross.
    Returns the :class:`matplotlib.figure.Figure`; the caller saves and closes it.

    Raises
    ------
    ValueError
        ``directions`` given and not one 1 or -1 per union.
    """
    unions = list(unions)
    directions = [int(d) for d in directions] if len(directions) else []
    if directions and (len(directions) != len(unions) or any(d not in (1, -1) for d in directions)):
        n = len(unions)
        raise ValueError(f"directions must hold 1 or -1 for each of the {n} unions, got {directions}")
    fig, ax = plt.subplots(figsize=figsize)
    plot_floor(floor, ax, poses=False)
    r = floor.robot if isinstance(floor, Scenario) else None
    if unions and -1 in directions:
        for d, colour, what in ((1, "C0", "forward"), (-1, REVERSE_COLOR, "reverse")):
            part = [u for u, x in zip(unions, directions, strict=True) if x == d]
            if part:
                plot_plan(part, ax, robots=4, robot=r, color=colour, label=f"rear path A, {what}")
        links = zip(unions[:-1], directions[:-1], directions[1:], strict=True)
        cusps = [u.p0 if d < 0 else u.p1 for u, d, e in links if d != e]
        ax.plot([p.x for p in cusps], [p.y for p in cusps], "kx", ms=9, mew=2, label="cusp", zorder=5)
    elif unions:
        plot_plan(unions, ax, robots=4, robot=r)
    if r is not None:
        if has_body(r):
            plot_body(floor.start, r, ax, color="tab:green", label="start")
            plot_body(floor.goal, r, ax, color="tab:red", label="goal")
        else:
            plot_pose(floor.start, floor.L, ax, color="tab:green", label="start")
            plot_pose(floor.goal, floor.L, ax, color="tab:red", label="goal")
    ax.set_title(title)
    legend_beside(ax)
    return fig


#: Colour of the links a plan drives backwards (:func:`plan_figure`).
REVERSE_COLOR = "C1"


# -- the cost --------------------------------------------------------------------------
def plot_longd(
    p0: Sequence[float] | Pose,
    p1: Sequence[float] | Pose,
    L: float,
    ax: Axes | None = None,
    *,
    alphas=None,
    n: int = 201,
    margin: float = 0.05,
    ymax: float | None = None,
    color: str = "C0",
    label: str | None = "LONGD, formula [1]",
    mark_min: bool = True,
    chord: bool = True,
) -> Axes:
    """Plot LONGD(alpha), formula [1] by Romberg integration, over the feasible interval.

    LONGD grows without bound at both ends of the interval where the cubic exists (an
    end slope becomes vertical), so by default the curve covers the interval shrunk by
    ``margin`` of its width at each end.

    Parameters
    ----------
    p0, p1 : Pose or (x, y, theta)
        The two nodes.
    L : float
        Robot length (> 0).
    alphas : array-like, optional
        Angles (radians) at which to evaluate; overrides ``n`` and ``margin``.
    n : int
        Number of angles (>= 2).
    margin : float
        Fraction of the interval width left out at each end, in ``[0, 0.5)``.
    ymax : float, optional
        Upper limit of the y-axis [m]; default 1.5 times the smallest value plotted (the
        lower limit is just under the smaller of ``d`` and that value).
    mark_min : bool
        Mark the smallest sampled value.
    chord : bool
        Draw the chord length ``d`` for reference.

    Raises
    ------
    ValueError
        Invalid poses or ``L``, no feasible alpha, bad ``n`` or ``margin``, or an
        ``alpha`` outside the feasible interval.
    """
    geo = intrinsic(p0, p1)
    if alphas is None:
        n = _check_count(n, "n", 2)
        if not 0.0 <= margin < 0.5:
            raise ValueError(f"margin must lie in [0, 0.5), got {margin!r}")
        lo, hi = feasible_alpha_interval(geo.phi0, geo.phi1)
        w = hi - lo
        eps = max(margin * w, 1e-6 * w)  # the ends themselves are excluded
        alphas = np.linspace(lo + eps, hi - eps, n)
    alphas = np.asarray(alphas, dtype=float)
    if alphas.ndim != 1 or alphas.size < 2:
        raise ValueError(f"alphas must be a 1-D array of at least 2 angles, got shape {alphas.shape}")
    values = np.asarray(longd_exact(p0, p1, alphas, L), dtype=float)
    ax = _axes(ax)
    deg = np.degrees(alphas)
    ax.plot(deg, values, color=color, label=label)
    if chord:
        ax.axhline(geo.d, color="0.5", linestyle=":", linewidth=1.0, label="chord length d")
    if mark_min:
        i = int(np.argmin(values))
        ax.plot(deg[i], values[i], "o", color=color, markersize=5, label="smallest sampled LONGD")
    vmin = float(np.min(values))
    bottom = 0.95 * min(vmin, geo.d)
    top = 1.5 * vmin if ymax is None else float(ymax)
    if not top > bottom:
        raise ValueError(f"ymax must exceed {bottom:.6g} m, got {ymax!r}")
    ax.set_ylim(bottom, top)
    ax.set_xlabel("alpha [deg]")
    ax.set_ylabel("LONGD [m]")
    return ax
