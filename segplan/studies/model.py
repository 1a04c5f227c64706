"""Study helper for the book's first chapter: the oriented segment against the enclosing circle.

Section "Introduction" and Figs. 1-2: a robot "enclosed in a suitable circle" with "the
obstacles ... enlarged accordingly" loses "most of the limited free space of an industrial
environment", while the segment model sacrifices "only a small portion of collision-free
space". :func:`free_space_comparison` measures both on a floor with shapely.
"""

from __future__ import annotations

import itertools

__all__ = ["free_space_comparison"]


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
