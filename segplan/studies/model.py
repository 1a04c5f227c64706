"""Study helper for the book's first chapter: the oriented segment against the enclosing circle.

Section "Introduction" and Figs. 1-2: a robot "enclosed in a suitable circle" with "the
obstacles ... enlarged accordingly" loses "most of the limited free space of an industrial
environment", while the segment model sacrifices "only a small portion of collision-free
space". :func:`free_space_comparison` measures both on a floor with shapely.

Fig. 2: the segment model's own "wasted area", "related to the difference between the
apparent and real edge of the robot [...] only significant at the rear part, which is a
negligible fact, if considering that the robot is allowed to move only forward".
:func:`wasted_space` measures it in pose space against a reconstructed real outline.
"""

from __future__ import annotations

import itertools

import numpy as np

__all__ = ["free_space_comparison", "wasted_space"]


def free_space_comparison(scenario, resolution: int = 32):
    """Free area and passages of a floor for the segment model and for the enclosing circle.

    The segment model (section "Mobile robot modelling") plans the segment A-B among the
    obstacles enlarged by the robot's half-width (:attr:`segplan.Scenario.enlarged`,
    walls moved in by it); the circle model plans the centre of the circle that encloses
    the robot, of radius ``R = L / 2 + half_width``, among the obstacles enlarged by ``R``
    (walls moved in by ``R``). Both enlargements are exact buffers (shapely, ``resolution``
    segments per quarter circle).

    Returns
    -------
    dict
        ``floor_free`` (floor minus obstacles, m^2), ``segment_free`` and ``circle_free``
        (free area left to each model's reference, m^2), ``R`` and ``half_width``;
        ``passages``: a list of ``(name_a, name_b, width)`` for every pair of obstacles
        (and obstacle-wall pair) closer than ``2 R`` (the circle cannot pass between
        them), ``segment_passes``: for each, whether it is wider than ``2 half_width``
        (the segment, heading through it, fits).

    Raises
    ------
    ValueError
        If the scenario has no walls (``bounds`` is None): its free area is infinite.
    """
    import shapely

    if scenario.bounds is None:
        raise ValueError("scenario must have bounds (walls) to measure free area")
    hw = scenario.robot.half_width
    R = 0.5 * scenario.L + hw
    xmin, ymin, xmax, ymax = scenario.bounds
    room = shapely.box(xmin, ymin, xmax, ymax)
    obstacles = [shapely.Polygon(o) for o in scenario.obstacles]
    blocked = shapely.union_all(obstacles) if obstacles else shapely.Polygon()

    def free(r):
        inner = (
            shapely.box(xmin + r, ymin + r, xmax - r, ymax - r)
            if 2 * r < min(xmax - xmin, ymax - ymin)
            else None
        )
        if inner is None:
            return 0.0
        grown = (
            shapely.union_all([o.buffer(r, quad_segs=resolution) for o in obstacles]) if obstacles else None
        )
        return float(inner.area if grown is None else inner.difference(grown).area)

    walls = {
        "wall x-": shapely.LineString([(xmin, ymin), (xmin, ymax)]),
        "wall x+": shapely.LineString([(xmax, ymin), (xmax, ymax)]),
        "wall y-": shapely.LineString([(xmin, ymin), (xmax, ymin)]),
        "wall y+": shapely.LineString([(xmin, ymax), (xmax, ymax)]),
    }
    named = {f"obstacle {i}": o for i, o in enumerate(obstacles)}
    passages = []
    for (na, a), (nb, b) in itertools.combinations(named.items(), 2):
        w = float(a.distance(b))
        if 0.0 < w < 2 * R:
            passages.append((na, nb, w))
    for (na, a), (nb, b) in itertools.product(named.items(), walls.items()):
        w = float(a.distance(b))
        if 0.0 < w < 2 * R:
            passages.append((na, nb, w))
    return {
        "floor_free": float(room.difference(blocked).area),
        "segment_free": free(hw),
        "circle_free": free(R),
        "R": R,
        "half_width": hw,
        "passages": passages,
        "segment_passes": [bool(w > 2 * hw) for _, _, w in passages],
    }


def wasted_space(scenario, n: int = 20_000, seed: int = 0) -> dict:
    """The collision-free poses the segment model gives up against the robot's real outline (Fig. 2).

    The model's apparent edge is the "curved rectangle" of Fig. 2: every point within
    ``half_width`` of the segment A-B (a rectangle with a half-disc at A and one at B), the
    set whose clearance segplan plans with. The real outline is our reconstruction (Fig. 2
    is lost in the scan): the rectangle from A to B of width ``2 half_width``, the largest
    rectangle of that width inside the curved rectangle, so every loss lies in the two
    end caps.

    ``n`` poses are drawn uniformly (rear point A in the walls, heading in ``[-pi, pi)``;
    ``seed``). A pose is *free for the real robot* when its rectangle lies inside the walls
    and touches no obstacle, and *sacrificed* when it is free for the real robot but the
    curved rectangle touches an obstacle or a wall (shapely, exact polygons; caps with 16
    segments per quarter circle). A sacrificed pose is charged to the *rear* cap if the
    disc at A touches, else to the *front* cap; a front-cap loss is *passed anyway* when
    the real rectangle moved straight forward by ``half_width`` touches too: a robot that
    moves only forward (the paper's argument) would meet that obstacle a moment later.

    Returns
    -------
    dict
        ``poses`` (drawn), ``real_free`` (poses free for the real outline),
        ``sacrificed`` (share of ``real_free`` given up by the model), ``rear`` and
        ``front`` (shares of the sacrificed poses charged to each cap),
        ``front_passed_anyway`` (share of the front-cap losses a forward move meets
        anyway), ``forward_relevant`` (share of ``real_free`` sacrificed by the rear cap
        or by a front-cap loss not passed anyway) and ``model_area_wasted`` (the caps'
        share of the curved rectangle's area, ``pi w^2 / (2 w L + pi w^2)``).

    Raises
    ------
    ValueError
        If the scenario has no walls, ``half_width`` is 0 (no outline), or ``n`` < 1.
    """
    import shapely

    if scenario.bounds is None:
        raise ValueError("scenario must have bounds (walls) to draw poses in")
    w, L = scenario.robot.half_width, scenario.L
    if not w > 0:
        raise ValueError("scenario.robot.half_width must be positive: the segment has no outline")
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ValueError(f"n must be a positive integer, got {n!r}")
    xmin, ymin, xmax, ymax = scenario.bounds
    rng = np.random.default_rng(seed)
    a = np.column_stack((rng.uniform(xmin, xmax, n), rng.uniform(ymin, ymax, n)))
    th = rng.uniform(-np.pi, np.pi, n)
    h = np.column_stack((np.cos(th), np.sin(th)))  # heading
    nrm = np.column_stack((-h[:, 1], h[:, 0]))  # left normal
    b = a + L * h
    blocked = shapely.union_all([shapely.Polygon(o) for o in scenario.obstacles] or [shapely.Polygon()])
    room = shapely.box(xmin, ymin, xmax, ymax)
    shapely.prepare(blocked)

    def hits(geoms):
        return shapely.intersects(geoms, blocked) | ~shapely.within(geoms, room)

    def rectangles(p, q):
        corners = np.stack((p - w * nrm, q - w * nrm, q + w * nrm, p + w * nrm), axis=1)
        return shapely.polygons(corners)

    real_hit = hits(rectangles(a, b))
    model_hit = hits(shapely.buffer(shapely.linestrings(np.stack((a, b), axis=1)), w, quad_segs=16))
    sacrificed = ~real_hit & model_hit
    rear = sacrificed & hits(shapely.buffer(shapely.points(a), w, quad_segs=16))
    front = sacrificed & ~rear
    passed = front & hits(rectangles(a + w * h, b + w * h))
    real_free = int((~real_hit).sum())
    n_sac = int(sacrificed.sum())
    return {
        "poses": n,
        "real_free": real_free,
        "sacrificed": n_sac / real_free if real_free else float("nan"),
        "rear": int(rear.sum()) / n_sac if n_sac else float("nan"),
        "front": int(front.sum()) / n_sac if n_sac else float("nan"),
        "front_passed_anyway": int(passed.sum()) / int(front.sum()) if front.any() else float("nan"),
        "forward_relevant": int((rear | (front & ~passed)).sum()) / real_free if real_free else float("nan"),
        "model_area_wasted": np.pi * w**2 / (2 * w * L + np.pi * w**2),
    }
