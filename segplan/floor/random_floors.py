"""Random floors: deterministic random worlds of convex obstacles (tests, studies, benchmarks).

Not in the paper (its floors are Figs. 5 and 6, ``scenarios/``): worlds drawn from a
seed, with a free start and goal, to measure the planner beyond the paper's two examples.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..model.pose import TWO_PI, Pose, as_pose
from .geometry import (
    axis_segment,
    check_bounds,
    enlarge_polygon,
    finite_number,
    polygons_overlap,
    segment_hits_polygon,
    segment_in_bounds,
)
from .scenario import Robot, Scenario, make_scenario

__all__ = ["place_disjoint", "random_convex_polygon", "random_world"]


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


def place_disjoint(draw, n: int, tries: int) -> list[np.ndarray]:
    """Up to ``n`` obstacles from ``draw()``, each kept only if it stays clear of those kept.

    ``draw()`` is called at most ``tries`` times, never once ``n`` are kept; it returns
    ``None`` (the draw is rejected) or ``(polygon, grown)``: ``polygon`` is kept iff
    ``grown`` overlaps (:func:`segplan.floor.geometry.polygons_overlap`) no kept obstacle's
    ``grown``, after a bounding-box filter; ``grown=None`` keeps it without that test.
    Deterministic given ``draw``; the caller reports too few (the list may be shorter than
    ``n``). Both floor generators place their obstacles with it (:func:`random_world`,
    :mod:`segplan.studies.floors`).
    """
    placed: list[np.ndarray] = []
    grown: list[np.ndarray] = []
    boxes = np.empty((n, 4))  # the grown polygons' bounding boxes, a cheap first test
    for _ in range(tries):
        if len(placed) == n:
            break
        drawn = draw()
        if drawn is None:
            continue
        poly, g = drawn
        if g is not None:
            lo, hi = g.min(axis=0), g.max(axis=0)
            k = len(grown)
            near = np.flatnonzero(
                (boxes[:k, 0] <= hi[0])
                & (lo[0] <= boxes[:k, 2])
                & (boxes[:k, 1] <= hi[1])
                & (lo[1] <= boxes[:k, 3])
            )
            if any(polygons_overlap(g, grown[i]) for i in near):
                continue
            boxes[k] = (*lo, *hi)
            grown.append(g)
        placed.append(poly)
    return placed


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
        rmin, rmax = (finite_number(x, "radius") for x in radius)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"radius must be (min, max) finite numbers, got {radius!r}") from exc
    if not 0.0 < rmin <= rmax:
        raise ValueError(f"radius must be (min, max) with 0 < min <= max, got {radius}")
    spread = finite_number(heading_spread, "heading_spread", minimum=0.0)
    clear = robot.L if clearance is None else finite_number(clearance, "clearance", minimum=0.0)
    gap = None if min_gap is None else finite_number(min_gap, "min_gap", minimum=0.0)
    tries = 100 * (n_obstacles + 1) if max_tries is None else int(max_tries)
    xmin, ymin, xmax, ymax = check_bounds(bounds)
    if min(xmax - xmin, ymax - ymin) <= 2.0 * (rmax + robot.half_width):
        raise ValueError(
            f"bounds {bounds!r} are not a rectangle large enough for obstacles of radius up to {rmax}"
        )
    fb = (xmin + robot.half_width, ymin + robot.half_width, xmax - robot.half_width, ymax - robot.half_width)
    rng = np.random.default_rng(seed)

    def ends(p: Pose) -> tuple[np.ndarray, np.ndarray]:  # the checked segment, overhangs included
        r = robot
        ax, ay, dx, dy, _ = axis_segment(p.x, p.y, p.theta, r.L, r.rear_overhang, r.front_overhang)
        return np.array([ax, ay]), np.array([ax + dx, ay + dy])

    def sample_pose(x_lo: float, x_hi: float) -> Pose:
        for _ in range(tries):
            p = Pose(rng.uniform(x_lo, x_hi), rng.uniform(fb[1], fb[3]), rng.uniform(-spread, spread))
            a, b = ends(p)
            if segment_in_bounds(a, b, fb):
                return p
        raise ValueError(
            f"no pose of length L={robot.L} fits in x in [{x_lo}, {x_hi}] within {tries} samples"
        )

    quarter = 0.25 * (fb[2] - fb[0])
    start_p = as_pose(start, "start") if start is not None else sample_pose(fb[0], fb[0] + quarter)
    goal_p = as_pose(goal, "goal") if goal is not None else sample_pose(fb[2] - quarter, fb[2])
    keep_out = [ends(p) for p in (start_p, goal_p)]

    def draw():
        r = rng.uniform(rmin, rmax)
        center = (rng.uniform(xmin + r, xmax - r), rng.uniform(ymin + r, ymax - r))
        poly = random_convex_polygon(rng, center, r, max_vertices)  # convex and CCW by construction
        guard = enlarge_polygon(poly, robot.half_width + clear)
        if any(segment_hits_polygon(a, b, guard) for a, b in keep_out):
            return None
        # kept apart: enlarged by half_width + min_gap / 2, they do not overlap
        return poly, None if gap is None else enlarge_polygon(poly, robot.half_width + 0.5 * gap)

    placed = place_disjoint(draw, n_obstacles, tries)
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
