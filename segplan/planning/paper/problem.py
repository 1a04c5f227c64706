"""The planning problem: start, goal and the objective (link cost, h' as cost-to-go).

Section "Results. Graph-search" of Campoy et al. (1989): "The evaluation function is
defined as the estimation of the cost of an optimal path conditioned to passing by a
given node ... f = g + h'", with ``g`` the cost (LONGD, the front-wheel path length,
formula [1]/[2]) of the path found so far and ``h'`` an estimate of the remaining cost.
The paper's choices for ``h'``:

(a) "The same function as for g": LONGD of the direct union node->goal in its optimal
    reference system. Not admissible, great "heuristic power".
(b) "Distance between points": admissible (the front wheel's path is at least as long
    as the rear point's, which is at least the chord), weak.
(c) "A weighted average between them, depending on the parameters p ('depth' of the
    node in the graph) and d_s/L, where d_s is a characteristic dimension of the
    surroundings": deep nodes use (a), shallow nodes (b).

Our reconstruction of (c): ``h' = w h_a + (1 - w) h_b`` with ``w = p / (p + d_s / L)``.
A node of depth ``p = d_s / L`` weighs both equally: in cramped surroundings (``d_s``
about ``L``) the robot's size is felt at once and (a) dominates from the first level; in
open ones (``d_s >> L``) distance dominates for longer. By default ``d_s`` is the median,
over the obstacles, of the gap between an enlarged obstacle and its nearest neighbour
(another obstacle or a wall): the typical width of a corridor
(:func:`characteristic_dimension`).

Where the direct union does not exist (no feasible alpha), ``h_a`` falls back to
``d + R (|phi0| + |phi1|)``, the chord plus the arcs of minimum radius ``R`` that turn
the robot onto and off the chord.

The paper's comparison baseline (Figs. 5, 6: "a search algorithm where the cost function
is based upon the distance between points") is ``cost="distance"``: the link cost is the
chord length and every ``h'`` choice becomes the distance.
"""

from __future__ import annotations

import math

import numpy as np

from ...floor.geometry import polygons_overlap
from ...model.pose import Pose, wrap_ieee
from ...model.union import Union
from ..links import LinkModel

__all__ = ["COSTS", "HEURISTICS", "Problem", "characteristic_dimension", "polygon_gap"]

HEURISTICS = ("a", "b", "c")
COSTS = ("longd", "distance")


class Problem:
    """Start, goal and objective of one search (OMPL's problem definition and objective).

    Parameters
    ----------
    start, goal : Pose
    links : LinkModel
        Unions and their LONGD (the link cost ``g`` and ``h'`` (a)).
    heuristic : {"a", "b", "c"}
        The paper's ``h'`` (module docstring).
    cost : {"longd", "distance"}
        Link cost: LONGD (the method) or the chord (the paper's baseline).
    ds_over_L : float
        ``d_s / L`` of heuristic (c).
    min_turning_radius : float
        ``R`` of the fallback of ``h'`` (a) where no union exists.
    """

    def __init__(
        self,
        start: Pose,
        goal: Pose,
        links: LinkModel,
        heuristic: str = "a",
        cost: str = "longd",
        ds_over_L: float = 0.0,
        min_turning_radius: float = 0.0,
    ):
        if heuristic not in HEURISTICS:
            raise ValueError(
                f"heuristic must be one of {', '.join(map(repr, HEURISTICS))}, got {heuristic!r}"
            )
        if cost not in COSTS:
            raise ValueError(f"cost must be one of {', '.join(map(repr, COSTS))}, got {cost!r}")
        self.start = Pose(*start)
        self.goal = Pose(*goal)
        self.links = links
        self.heuristic = heuristic
        self.cost = cost
        self.ds_over_L = float(ds_over_L)
        self.R = float(min_turning_radius)

    def link_cost(self, u: Union) -> float:
        """``g`` of one link: its LONGD, or its chord for the baseline ``cost="distance"``."""
        return u.d if self.cost == "distance" else self.links.link_cost(u)

    def cost_to_go(self, pose: Pose, depth: int) -> float:
        """``h'`` of a node of ``depth`` (module docstring)."""
        goal = self.goal
        d = math.hypot(goal.x - pose.x, goal.y - pose.y)
        if self.cost == "distance" or self.heuristic == "b" or d == 0.0 and pose.theta == goal.theta:
            return d
        ha = self._h_longd(pose, d)
        if self.heuristic == "a":
            return ha
        w = depth / (depth + self.ds_over_L) if depth + self.ds_over_L > 0 else 1.0
        return w * ha + (1.0 - w) * d

    def _h_longd(self, pose: Pose, d: float) -> float:
        u = self.links.union(pose, self.goal)
        if u is not None and self.links.ws.curvature_ok(u):
            return self.links.link_cost(u)
        psi = math.atan2(self.goal.y - pose.y, self.goal.x - pose.x) if d > 0 else pose.theta
        phi0 = abs(wrap_ieee(pose.theta - psi))
        phi1 = abs(wrap_ieee(self.goal.theta - psi))
        return d + self.R * (phi0 + phi1)

    def prepare(self, poses) -> None:
        """Batch the direct unions of new nodes to the goal (their ``h'`` and expansion)."""
        self.links.prefetch([(p, self.goal) for p in poses])


# -- d_s: the characteristic dimension of heuristic (c) -------------------------------
def _segment_point_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distances from points ``p`` (n, 2) to segments ``a``-``b`` (m, 2): ``(n, m)``."""
    ab = b - a
    ap = p[:, None, :] - a[None, :, :]
    t = np.clip(np.einsum("nmk,mk->nm", ap, ab) / np.einsum("mk,mk->m", ab, ab), 0.0, 1.0)
    return np.linalg.norm(ap - t[..., None] * ab[None], axis=-1)


def polygon_gap(p: np.ndarray, q: np.ndarray) -> float:
    """Distance between two disjoint convex polygons (0 if they overlap or touch).

    For disjoint convex polygons the distance is attained at a vertex of one of them, so
    it is the least vertex-to-edge distance both ways.
    """
    if polygons_overlap(p, q):
        return 0.0
    d1 = _segment_point_distance(p, q, np.roll(q, -1, axis=0)).min()
    d2 = _segment_point_distance(q, p, np.roll(p, -1, axis=0)).min()
    return float(min(d1, d2))


def characteristic_dimension(polygons, bounds=None, fallback: float = 1.0, groups=None) -> float:
    """``d_s`` of heuristic (c): the median gap from each obstacle to its nearest neighbour.

    Neighbours are the other obstacles and the walls (``bounds``). Without obstacles the
    shorter side of the bounds, or ``fallback`` without bounds either. Exact gaps
    (:func:`polygon_gap`) are computed only for pairs whose circumscribed circles are
    nearer than the best gap found so far (the circle gap is a lower bound).

    ``groups``: optional, ``groups[i]`` the obstacle that polygon ``i`` is a convex piece of
    (``Scenario.outline_of``, beyond the paper); the pieces of one obstacle are not each
    other's neighbours and an obstacle's gap is the least of its pieces'. None: every
    polygon is an obstacle of its own.
    """
    polys = [np.asarray(p, dtype=float) for p in polygons]
    group = list(range(len(polys))) if groups is None else [int(g) for g in groups]
    if len(group) != len(polys):
        raise ValueError(f"groups must name one obstacle per polygon: {len(group)} for {len(polys)} polygons")
    if not polys:
        if bounds is None:
            return float(fallback)
        return float(min(bounds[2] - bounds[0], bounds[3] - bounds[1]))
    centres = np.array([0.5 * (p.min(axis=0) + p.max(axis=0)) for p in polys])
    radii = np.array([np.max(np.hypot(*(p - c).T)) for p, c in zip(polys, centres, strict=True)])
    circle_gap = np.hypot(*(centres[:, None, :] - centres[None, :, :]).transpose(2, 0, 1))
    circle_gap -= radii[:, None] + radii[None, :]
    gaps: dict[int, float] = {}
    for i, p in enumerate(polys):
        best = math.inf
        if bounds is not None:
            xmin, ymin, xmax, ymax = bounds
            best = min(p[:, 0].min() - xmin, p[:, 1].min() - ymin, xmax - p[:, 0].max(), ymax - p[:, 1].max())
            best = max(best, 0.0)
        for j in np.argsort(circle_gap[i]):
            if group[j] == group[i]:
                continue
            if circle_gap[i, j] >= best:
                break
            best = min(best, polygon_gap(p, polys[j]))
        gaps[group[i]] = min(best, gaps.get(group[i], math.inf))
    finite = [g for g in gaps.values() if math.isfinite(g)]
    return float(np.median(finite)) if finite else float(fallback)
