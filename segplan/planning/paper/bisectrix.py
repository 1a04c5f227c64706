"""The geometry of an intermediate node near an obstacle vertex.

Section "Graph expansion method. Generation of intermediate nodes" of Campoy et al.
(1989): "a suitable intermediate state near the vertex is chosen ... along the bisectrix
of the correspondent angle of the polygon. ... The slope is a weighted average between
the one at right angles with the bisectrix and the one that would appear naturally using
clamped spline interpolation for the three points involved." The pieces of that sentence:
the outward bisectrices of a convex polygon's vertex angles (:func:`outward_bisectors`),
the vertices a path around the polygon touches first (:func:`tangent_vertices`), the
clamped spline's tangent (:func:`clamped_spline_tangent`) and the weighted heading
(:func:`iterate_pose`). How the expansion chooses and iterates them is
:mod:`segplan.planning.paper.expansion`.
"""

from __future__ import annotations

import math

import numpy as np

from ...model.pose import Pose, wrap_fmod

__all__ = ["clamped_spline_tangent", "iterate_pose", "outward_bisectors", "tangent_vertices"]


def clamped_spline_tangent(p0, point, p1) -> float:
    """Heading at ``point`` of the clamped cubic spline through three poses' points.

    The spline is parametric, ``(x(t), y(t))`` with chord-length knots ``0, h1, h1 + h2``
    and clamped end derivatives equal to the unit heading vectors of ``p0`` and ``p1``.
    Continuity of the second derivative at the middle knot gives its derivative ``D1``::

        h2 D0 + 2 (h1 + h2) D1 + h1 D2 = 3 [h2 (P1 - P0) / h1 + h1 (P2 - P1) / h2]

    Parameters
    ----------
    p0, p1 : (x, y, theta)
        Start and goal poses (their headings clamp the spline).
    point : (x, y)
        The middle point.

    Returns
    -------
    float
        World angle of ``D1`` (radians).
    """
    x0, y0, t0 = p0[0], p0[1], p0[2]
    x2, y2, t2 = p1[0], p1[1], p1[2]
    x1, y1 = point[0], point[1]
    h1 = math.hypot(x1 - x0, y1 - y0)
    h2 = math.hypot(x2 - x1, y2 - y1)
    if h1 <= 0.0 or h2 <= 0.0:
        raise ValueError("point must differ from both end points")
    rx = 3.0 * (h2 * (x1 - x0) / h1 + h1 * (x2 - x1) / h2) - h2 * math.cos(t0) - h1 * math.cos(t2)
    ry = 3.0 * (h2 * (y1 - y0) / h1 + h1 * (y2 - y1) / h2) - h2 * math.sin(t0) - h1 * math.sin(t2)
    return math.atan2(ry, rx)  # the factor 1 / (2 (h1 + h2)) does not change the angle


def iterate_pose(start, goal, px: float, py: float, base: float, w: float) -> Pose:
    """An intermediate node at ``(px, py)``: heading ``base + w wrap(theta_spline - base)``.

    The paper's "weighted average" of two slopes: ``base`` (in the expansion, the heading
    at right angles with the bisectrix) and ``theta_spline``, the tangent at ``(px, py)``
    of the clamped spline through ``start`` and ``goal`` (:func:`clamped_spline_tangent`;
    ``base`` if the point coincides with either), with weight ``w`` on the spline.
    """
    px, py = float(px), float(py)
    try:
        theta_s = clamped_spline_tangent(start, (px, py), goal)
    except ValueError:
        theta_s = base
    return Pose(px, py, wrap_fmod(base + w * wrap_fmod(theta_s - base)))


def outward_bisectors(polygon: np.ndarray) -> np.ndarray:
    """Unit outward bisectrices of the vertex angles of a convex polygon, ``(k, 2)``.

    ``b_i = unit(unit(v_i - v_{i-1}) + unit(v_i - v_{i+1}))``: for an interior angle below
    pi the two unit vectors from the neighbours to the vertex add up to a vector along the
    bisectrix, pointing away from the polygon.
    """
    v = np.asarray(polygon, dtype=float)
    a = v - np.concatenate((v[-1:], v[:-1]))  # v[i] - v[i-1] (np.roll, without its overhead)
    c = v - np.concatenate((v[1:], v[:1]))  # v[i] - v[i+1]
    a /= np.hypot(a[:, 0], a[:, 1])[:, None]
    c /= np.hypot(c[:, 0], c[:, 1])[:, None]
    b = a + c
    return b / np.hypot(b[:, 0], b[:, 1])[:, None]


def tangent_vertices(polygon, point) -> tuple[int, int]:
    """Indices of the polygon's extreme vertices seen from ``point`` (outside it).

    Returns
    -------
    ccw, cw : int
        The vertex of largest and of smallest direction angle seen from ``point``,
        measured from the direction of the polygon's centroid. A convex polygon not
        containing the point is seen within a cone narrower than pi that contains that
        direction, so these angles never wrap.
    """
    px, py = float(point[0]), float(point[1])
    pts = [(float(x) - px, float(y) - py) for x, y in polygon]
    cx = sum(p[0] for p in pts) / len(pts)
    cy = sum(p[1] for p in pts) / len(pts)
    rel = [math.atan2(cx * y - cy * x, cx * x + cy * y) for x, y in pts]
    return max(range(len(rel)), key=rel.__getitem__), min(range(len(rel)), key=rel.__getitem__)
