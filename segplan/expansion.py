"""Graph expansion: the successors of a node toward the goal, with intermediate nodes.

Section "Graph expansion method. Generation of intermediate nodes" of Campoy et al.
(1989). The search graph is built on-line: a node (a pose) is joined to the goal by the
cubic union of section III in its optimal reference system. If that union is free, the
goal is the node's only successor. If it collides with an obstacle, "a suitable
intermediate state near the vertex is chosen ... along the bisectrix of the
correspondent angle of the polygon. ... The slope is a weighted average between the one
at right angles with the bisectrix and the one that would appear naturally using clamped
spline interpolation for the three points involved. Though the algorithm is iterative,
until no collision appears, two or three iterates at the most are normally needed."

Our reconstruction (the paper gives no formulas for this section)
-----------------------------------------------------------------
*Which obstacles, which vertex.* The first obstacle along the direct union that it
touches gets candidates (the paper's single-obstacle setting; ``all_obstacles=True``:
every obstacle it touches, slower and in our tests no more successful). The path can pass
a convex polygon on either side, so each side gives one candidate: two successors per
obstacle. On side ``s`` (``+1``: the
obstacle stays on the robot's right, ``-1``: on its left) the vertex is the *tangent
vertex seen from the node*: the polygon's extreme vertex in the direction of ``s`` as
seen from the node's rear point (the first vertex a shortest path around the obstacle
touches, :func:`tangent_vertices`). If the tangent vertex seen backwards from the goal
is the same vertex, one intermediate node passes the obstacle and we iterate, as the
paper does, until *both* new unions are free of it (a "complete" candidate). Otherwise
(a long obstacle, such as a rack) one node cannot pass it: only the first union must be
free of it, and the next expansion, from the new node, passes the next vertex.

*First estimate.* Position ``P = v + r0 b`` with ``v`` the vertex, ``b`` the outward
unit bisectrix of its angle (:func:`outward_bisectors`) and ``r0 = 0.3 L``. Heading
``theta = theta_perp + w wrap(theta_spline - theta_perp)``: ``theta_perp`` at right
angles with the bisectrix, oriented in the direction of travel (clockwise around the
obstacle on side ``+1``); ``theta_spline`` the tangent at ``P`` of the parametric clamped
cubic spline through start, ``P`` and goal (:func:`clamped_spline_tangent`); ``w = 0.5``.

*Iterates* (at most ``max_iterations = 4``; the paper: "two or three iterates at the most
are normally needed"), by the reason the last one failed:

* the robot at ``P`` touches an obstacle or a wall: first "readjust the orientation"
  (the paper's words for difficult cases) to the direction of the obstacle's edge that
  leaves ``v`` in the direction of travel (``w = 0``: the robot lies along that edge, a
  *tight spot* such as a doorway); then move ``P`` closer to the vertex
  (``r /= growth``). In a tight spot every other failure slides ``P`` along the edge by
  ``0.5 L``, deeper into the passage, keeping the edge's direction;
* a new union touches the offending obstacle: move ``P`` outward (``r *= growth``,
  ``growth = 1.7``);
* the union from the node does not exist or breaks the steering limit (too sharp a
  turn, ``P`` too close): slide ``P`` along that edge by ``0.5 L`` and take the edge
  direction with more spline weight (``w = (1 + w) / 2``);
* the union to the goal (complete candidates only) does not exist or is too curved:
  ``w = (1 + w) / 2`` and ``r *= growth``;
* the union from the node is free of the offending obstacle but hits another one or a
  wall: slide along the edge (deeper into a passage). If no later iterate succeeds, the
  first such iterate is returned and :meth:`Expander.successors` generates intermediate
  nodes for the obstacle in its way (``recursion`` levels), aiming at that iterate as a
  subgoal (without the requirement on the union from it).

Every candidate records its iterate count (``ExpansionStats.iterations``).

*Reference systems* (Fig. 4). ``version="b"`` (the paper's choice): each piece gets its
own optimal reference system (:func:`segplan.frame.optimal_alpha_intrinsic`).
``version="a"``: both pieces of an intermediate node share one frame, "estimated as close
to the optimum": the optimal frame of the direct union node->goal (its chord's frame if
that union does not exist).

*Steering limit* (not in the paper). Every union must keep the rear path's curvature
within ``tan(max_steer) / L``. When the optimal frame's cubic breaks it, version "b"
tries the frame of least peak curvature instead (:meth:`Expander._steer`).

*Difficult cases* (section III: "great changes of slope, or even orientations opposing
the direction in which a natural trajectory would be traversed ... can be solved ... by
using a suitable intermediate state"). When the direct union does not exist (no
feasible alpha, e.g. a goal behind the start), breaks the steering limit or leaves the
bounds, or when no vertex candidate works, the successors are *turn states*
(:meth:`Expander.turn_states`): poses reached from the node along circular arcs of
radius ``turn_radius = 1.6`` times the minimum turning radius, turning by 90 and 45
degrees to either side (a quarter-circle cubic has a peak curvature of about 1.4 / radius,
below the limit at 1.6 radii), and the goal's *approach states*
(:meth:`Expander.approach_states`), the mirror image: poses from which such an arc (or a
straight run of ``2 L``) ends at the goal. A chain of them lets a forward-only robot turn
around; the search bounds the length of such chains.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import collision, cost
from .cost import in_domain
from .frame import heuristic_alpha, optimal_alpha_intrinsic
from .pose import Pose
from .romberg import RombergError
from .union import Union, cubic_coefficients
from .world import segment_in_bounds

HALF_PI = 0.5 * math.pi
TWO_PI = 2.0 * math.pi
#: Margin (radians) kept from the ends of the interval where the cubic exists.
ALPHA_MARGIN = 1e-9
#: Romberg tolerance of link costs outside the domain of formula [2] (the paper uses Romberg
#: with the same error bound as [2], 2.5 %; we keep far below it).
LONGD_RTOL = 1e-5
#: Alphas tried by the steering fallback of :meth:`Expander.union`.
STEER_SAMPLES = 15
_TAU = np.linspace(0.0, 1.0, 33)
_CURV_S = np.linspace(0.0, 1.0, 17)
#: Fewest pose pairs that :meth:`Expander.prefetch` sends to the array path of the
#: heuristic optimal frame (fewer: the scalar path, pair by pair, is faster).
PREFETCH_MIN_HEURISTIC = 12
#: Positions (fractions of the union's span) sampled by the certain-hit test.
HIT_SAMPLES = 9
_HIT_S = np.linspace(0.0, 1.0, HIT_SAMPLES)


def _wrap(a: float) -> float:
    """Scalar wrap to ``(-pi, pi]`` (fast path of :func:`segplan.pose.wrap`)."""
    a = math.fmod(a + math.pi, TWO_PI)
    if a <= 0.0:
        a += TWO_PI
    return a - math.pi


def _geometry(p0, p1):
    """Chord length and angle, intrinsic headings and the feasible alpha interval, or None.

    Scalar fast path of :func:`segplan.pose.intrinsic` and
    :func:`segplan.pose.alpha_interval` (interval shrunk by ``ALPHA_MARGIN``); None for
    coincident points or an empty interval (no cubic joins the poses).
    """
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    d = math.hypot(dx, dy)
    if d <= 1e-9 * max(1.0, abs(p0[0]), abs(p0[1]), abs(p1[0]), abs(p1[1])):
        return None
    psi = math.atan2(dy, dx)
    phi0, phi1 = _wrap(p0[2] - psi), _wrap(p1[2] - psi)
    lo = -HALF_PI - min(phi0, phi1, 0.0) + ALPHA_MARGIN
    hi = HALF_PI - max(phi0, phi1, 0.0) - ALPHA_MARGIN
    if not hi > lo:
        return None
    return d, psi, phi0, phi1, lo, hi


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


def _iterate_pose(start, goal, px: float, py: float, base: float, w: float) -> Pose:
    """An iterate at ``(px, py)``: heading ``base + w wrap(theta_spline - base)``."""
    px, py = float(px), float(py)
    try:
        theta_s = clamped_spline_tangent(start, (px, py), goal)
    except ValueError:
        theta_s = base
    return Pose(px, py, _wrap(base + w * _wrap(theta_s - base)))


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


def max_curvature(u: Union) -> float:
    """Largest ``|curvature|`` of a union's rear path, as :meth:`Union.max_curvature`, faster.

    Interior extrema of ``kappa = f'' / (1 + f'^2)^(3/2)`` solve
    ``f''' (1 + f'^2) - 3 f' f''^2 = 0``; with ``f = c1 x + c2 x^2 + c3 x^3`` that is the
    quartic (expanded by hand, checked against the polynomial product in the tests)::

        -270 c3^3 x^4 - 360 c2 c3^2 x^3 - (156 c2^2 c3 + 72 c1 c3^2) x^2
        - (48 c1 c2 c3 + 24 c2^3) x + 6 c3 (1 + c1^2) - 12 c1 c2^2 = 0.
    """
    _, c1, c2, c3 = u.coefficients
    X = u.x_end
    xs = [0.0, X]
    coef = (
        -270.0 * c3**3,
        -360.0 * c2 * c3**2,
        -(156.0 * c2 * c2 * c3 + 72.0 * c1 * c3 * c3),
        -(48.0 * c1 * c2 * c3 + 24.0 * c2**3),
        6.0 * c3 * (1.0 + c1 * c1) - 12.0 * c1 * c2 * c2,
    )
    if any(coef):
        for r in np.roots(coef):
            if abs(r.imag) < 1e-9 and 0.0 < r.real < X:
                xs.append(float(r.real))
    x = np.array(xs)
    fp = c1 + (2.0 * c2 + 3.0 * c3 * x) * x
    return float(np.max(np.abs(2.0 * c2 + 6.0 * c3 * x) / (1.0 + fp * fp) ** 1.5))


@dataclass
class ExpansionStats:
    """Counters of one expansion engine (reset with :meth:`Expander.reset_stats`).

    Attributes
    ----------
    iterations : list of (int, bool, bool)
        For every vertex candidate: iterates used, success, whether it was "complete"
        (one node passes the obstacle, both new unions free of it).
    unions : int
        Unions built (optimal reference system or shared one).
    infeasible : int
        Pose pairs for which no cubic exists (no feasible alpha, coincident points).
    exact_checks : int
        Calls of the exact test :func:`segplan.collision.collides`.
    broad_rejections : int
        Union-polygon pairs rejected by the bounding-box test alone.
    certain_hits : int
        Union-polygon pairs found colliding by a sample inside the polygon.
    batched : int
        Optimal reference systems computed in vectorised batches (:meth:`Expander.prefetch`).
    curvature_exact : int
        Unions whose curvature needed :meth:`Union.max_curvature` (the cheap bound failed).

    Notes
    -----
    The workspace keeps its answers per union (:meth:`Workspace.facts`), so the collision
    counters count distinct union-polygon pairs: a pair asked about again is not tested,
    nor counted, again.
    """

    iterations: list = field(default_factory=list)
    unions: int = 0
    infeasible: int = 0
    exact_checks: int = 0
    broad_rejections: int = 0
    certain_hits: int = 0
    batched: int = 0
    curvature_exact: int = 0

    @property
    def collision_checks(self) -> int:
        """Union-polygon pairs decided (by the bounding box or the exact test)."""
        return self.exact_checks + self.broad_rejections


@dataclass(frozen=True)
class Candidate:
    """An intermediate node generated near a vertex (or a failed attempt).

    Attributes
    ----------
    pose : Pose
        The last iterate.
    polygon, vertex : int
        Obstacle index and vertex index.
    side : int
        ``+1``: the obstacle stays on the robot's right; ``-1``: on its left.
    iterations : int
        Iterates used (1 = the first estimate was accepted).
    ok : bool
        Whether the iteration converged.
    complete : bool
        Whether both new unions were required (and found) free of the obstacle.
    union_in, union_out : Union or None
        start->pose and pose->goal of the last iterate.
    reason : str
        Why the last iterate failed ("" when ok).
    """

    pose: Pose
    polygon: int
    vertex: int
    side: int
    iterations: int
    ok: bool
    complete: bool
    union_in: Union | None
    union_out: Union | None
    reason: str = ""


@dataclass(frozen=True)
class Successor:
    """A successor of a node: the new pose and the free union that reaches it.

    Attributes
    ----------
    pose : Pose
    union : Union
        Collision-free, in bounds, within the steering limit.
    kind : str
        ``"goal"``, ``"vertex"`` (intermediate node near an obstacle vertex), ``"turn"``
        or ``"approach"`` (intermediate states of a difficult case, see
        :meth:`Expander.turn_states` and :meth:`Expander.approach_states`).
    key : tuple
        Identifies equivalent nodes for the search's closed set.
    candidate : Candidate or None
        The vertex candidate that produced it.
    """

    pose: Pose
    union: Union
    kind: str
    key: tuple
    candidate: Candidate | None = None


def _longd_scalar(d: float, phi0: float, phi1: float, alpha: float, L: float, rtol: float) -> float:
    """:func:`segplan.cost.longd_intrinsic` of one union in floats (the same value, faster).

    Formula [2] inside its domain, else Romberg on [1].
    """
    if in_domain(d, phi0, phi1, alpha, L):
        return float(cost.longd_approx_intrinsic(d, phi0, phi1, alpha, L))
    return float(cost.longd_exact_intrinsic(d, phi0, phi1, alpha, L, rtol=rtol))


def _edge_list(vertices) -> list[tuple[float, float, float, float]]:
    """``(x_i, y_i, n_x, n_y)`` per vertex of a counter-clockwise polygon (Python floats).

    ``n = (e_y, -e_x)`` is the outward normal of the edge ``e = v_{i+1} - v_i``, as in
    :func:`segplan.world.segment_hits_polygon`.
    """
    out = []
    for i, (x, y) in enumerate(vertices):
        nx_, ny_ = vertices[(i + 1) % len(vertices)]
        out.append((x, y, ny_ - y, -(nx_ - x)))
    return out


def _segment_hits(a, b, edges) -> bool:
    """:func:`segplan.world.segment_hits_polygon` in scalar arithmetic (the same operations).

    ``edges`` from :func:`_edge_list`; touching counts as a hit (separating axes).
    """
    ax, ay = a
    bx, by = b
    for x, y, nx, ny in edges:
        if nx * (ax - x) + ny * (ay - y) > 0.0 and nx * (bx - x) + ny * (by - y) > 0.0:
            return False
    dx, dy = bx - ax, by - ay
    pos = neg = True
    for x, y, _, _ in edges:
        side = dx * (y - ay) - dy * (x - ax)
        pos = pos and side > 0.0
        neg = neg and side < 0.0
    return not (pos or neg)


class _Facts:
    """What a :class:`Workspace` has established about one union (kept per union object).

    Every test of a union is a deterministic function of the union (and of the fixed
    workspace), so its answer is computed once: the search meets the same union several
    times (the direct union of a node as its ``h'`` and at its expansion; a candidate's
    union against the offending obstacle, the others, then all of them).
    """

    __slots__ = ("union", "sweep", "curvature", "in_bounds", "near", "hits", "samples", "cost")

    def __init__(self, union: Union):
        self.union = union  # keeps the union alive, so its id is not reused while cached
        self.sweep = None
        self.curvature = None
        self.in_bounds = None
        self.near: dict = {}  # polygon -> frame abscissa of its nearest vertex, None if rejected
        self.hits: dict = {}  # polygon -> touched
        self.samples = None
        self.cost = None


class Workspace:
    """Enlarged convex obstacles, bounds and robot limits, with cheap tests first.

    Parameters
    ----------
    obstacles : sequence of (k, 2) arrays
        Enlarged obstacles, strictly convex (as :attr:`segplan.Scenario.enlarged`,
        already validated: they are wrapped as
        :class:`segplan.collision.ConvexPolygon` without re-validation).
    L : float
        Robot length.
    bounds : (xmin, ymin, xmax, ymax) or None
        Free bounds (walls already moved inwards by the half-width).
    max_curvature : float
        Steering limit of the rear path, ``tan(max_steer) / L``.

    Notes
    -----
    Order of the tests on a union (the paper's "quick checkings ... If it is not so the
    more time-consuming routines are executed"):

    1. all obstacles at once: the frame bounding box of each polygon against the frame
       box of the swept segment (:class:`segplan.collision.Sweep`), one vectorised step;
    2. a *certain hit*: a sample of the swept segment (rear point, front wheel and
       middle of the robot at ``HIT_SAMPLES`` positions) strictly inside the polygon;
    3. :func:`segplan.collision.collides` (the paper's ``d_c`` rejection, then the exact
       event test) on the polygons left.
    """

    def __init__(self, obstacles, L: float, bounds=None, max_curvature: float = math.inf):
        self.polygons = [np.ascontiguousarray(p, dtype=float) for p in obstacles]
        self.convex = [collision.ConvexPolygon(p, check=False) for p in self.polygons]
        self.polygons = [c.vertices for c in self.convex]  # counter-clockwise
        self.L = float(L)
        self.bounds = None if bounds is None else tuple(float(b) for b in bounds)
        self.max_curvature = float(max_curvature)
        self.stats = ExpansionStats()
        self.collision_stats = collision.CollisionStats()
        self._facts: dict = {}
        self._checked_bounds = None
        # circumscribed circles (centre of the bounding box, largest vertex distance), inflated
        # by a relative margin so the broad phase never rejects a touching polygon
        self._circles = [(c.centre[0], c.centre[1], c.radius * (1.0 + 1e-9) + 1e-9) for c in self.convex]
        self._bbox = np.array([[*p.min(axis=0), *p.max(axis=0)] for p in self.polygons]).reshape(-1, 4)
        self._bisectors = [outward_bisectors(p) for p in self.polygons]
        # vertices as Python floats, for the scalar broad phase of :meth:`colliding`
        self._vertex_lists = [[(float(x), float(y)) for x, y in p] for p in self.polygons]
        # and with the (unnormalised) outward normal of the edge leaving each vertex, and the
        # bounding boxes, for the scalar :meth:`pose_free`
        self._edge_lists = [_edge_list(v) for v in self._vertex_lists]
        self._bbox_list = [tuple(float(b) for b in row) for row in self._bbox]

    # -- poses -------------------------------------------------------------------------
    def pose_free(self, pose) -> bool:
        """Is the robot's segment at ``pose`` clear of every obstacle and inside the bounds?"""
        x, y, th = pose
        bx, by = x + self.L * math.cos(th), y + self.L * math.sin(th)
        a, b = (x, y), (bx, by)
        if self.bounds is not None and not segment_in_bounds(a, b, self.bounds):
            return False
        if not self.polygons:
            return True
        lo_x, hi_x, lo_y, hi_y = min(x, bx), max(x, bx), min(y, by), max(y, by)
        for i, (b0, b1, b2, b3) in enumerate(self._bbox_list):
            near = b0 <= hi_x and b2 >= lo_x and b1 <= hi_y and b3 >= lo_y
            if near and _segment_hits(a, b, self._edge_lists[i]):
                return False
        return True

    # -- unions ------------------------------------------------------------------------
    def curvature_ok(self, u: Union) -> bool:
        """Is the rear path's curvature within the steering limit everywhere?

        Cached per union; see :meth:`_curvature_ok`.
        """
        if not math.isfinite(self.max_curvature):
            return True
        f = self.facts(u)
        if f.curvature is None:
            f.curvature = self._curvature_ok(u)
        return f.curvature

    def _curvature_ok(self, u: Union) -> bool:
        """:meth:`curvature_ok` without the cache.

        Cheap sufficient bound first: ``|kappa| <= |f''|`` and ``f''`` is linear, so
        ``max(|f''(0)|, |f''(X)|) <= kappa_max`` suffices; then a certain failure (the
        curvature sampled at 17 abscissae exceeds the limit); then the same bound piece by
        piece between the samples; otherwise the exact maximum (:func:`max_curvature`).
        """
        if not math.isfinite(self.max_curvature):
            return True
        _, _, c2, c3 = u.coefficients
        X = u.x_end
        if max(abs(2.0 * c2), abs(2.0 * c2 + 6.0 * c3 * X)) <= self.max_curvature:
            return True
        # a sampled curvature above the limit is a certain failure
        c1 = u.coefficients[1]
        x = X * _CURV_S
        fp = c1 + (2.0 * c2 + 3.0 * c3 * x) * x
        fpp = np.abs(2.0 * c2 + 6.0 * c3 * x)
        if np.any(fpp > self.max_curvature * (1.0 + fp * fp) ** 1.5):
            return False
        # a certain pass: on each piece between samples |kappa| <= max|f''| / (1 + min f'^2)^1.5
        # (f'' is linear, f' a parabola: its least |f'| is at an end, at its vertex or 0)
        a, b = fp[:-1], fp[1:]
        m = np.where(a * b <= 0.0, 0.0, np.minimum(np.abs(a), np.abs(b)))
        if c3 != 0.0:
            xv = -c2 / (3.0 * c3)
            k = np.searchsorted(x, xv) - 1
            if 0 <= k < len(m) and x[k] < xv < x[k + 1]:
                m[k] = min(m[k], abs(c1 + (2.0 * c2 + 3.0 * c3 * xv) * xv))
        if np.all(np.maximum(fpp[:-1], fpp[1:]) <= self.max_curvature * (1.0 + m * m) ** 1.5):
            return True
        self.stats.curvature_exact += 1
        return max_curvature(u) <= self.max_curvature

    def facts(self, u: Union) -> _Facts:
        """The cached answers about union ``u`` (kept on the union's identity)."""
        f = self._facts.get(id(u))
        if f is None or f.union is not u:
            if len(self._facts) > 4096:
                self._facts.clear()
            f = _Facts(u)
            self._facts[id(u)] = f
        return f

    def sweep(self, u: Union) -> collision.Sweep:
        """The per-union data of the collision tests (cached on the union's identity)."""
        f = self.facts(u)
        if f.sweep is None:
            f.sweep = collision.Sweep(u)
        return f.sweep

    def in_bounds(self, u: Union) -> bool:
        """Does the swept segment stay strictly inside the bounds? (cached per union)"""
        if self.bounds is None:
            return True
        f = self.facts(u)
        if f.in_bounds is None:
            if self._checked_bounds is None:
                self._checked_bounds = collision._bounds(self.bounds)  # validated once
            f.in_bounds = collision._union_in_bounds(self.sweep(u), self._checked_bounds)
        return f.in_bounds

    def _samples(self, sw: collision.Sweep) -> tuple[np.ndarray, np.ndarray]:
        """World points of the swept segment: rear, middle and front at ``HIT_SAMPLES`` positions."""
        x, fx, ux, uy = sw.segment(_HIT_S)
        L = sw.L
        fr = np.concatenate((x, x + 0.5 * L * ux, x + L * ux))
        fy = np.concatenate((fx, fx + 0.5 * L * uy, fx + L * uy))
        return sw.x0 + sw.cos * fr - sw.sin * fy, sw.y0 + sw.sin * fr + sw.cos * fy

    def _certain_hit(self, wx: np.ndarray, wy: np.ndarray, i: int) -> bool:
        """A sample point strictly inside polygon ``i``: a collision for certain."""
        c = self.convex[i]
        g = np.multiply.outer(wx, c.normals[:, 0]) + np.multiply.outer(wy, c.normals[:, 1]) - c.offsets
        return bool(np.any(np.all(g < 0.0, axis=1)))

    def colliding(self, u: Union, first: bool = True, only=None) -> list[int]:
        """Obstacles that the union's swept segment touches, in order along the path.

        Parameters
        ----------
        u : Union
        first : bool
            Stop at the first colliding obstacle (the one met first along the path,
            ordered by the frame abscissa of its nearest vertex).
        only : iterable of int, optional
            Test only these obstacles.
        """
        if not self.polygons:
            return []
        facts = self.facts(u)
        sw = self.sweep(u)
        known, hits = facts.near, facts.hits
        x0, x1, y0, y1 = sw.box
        c, s, ox, oy = sw.cos, sw.sin, sw.x0, sw.y0
        candidates = range(len(self.polygons)) if only is None else only
        near = []
        for i in candidates:
            if i in known:  # decided by the broad phase before (pairs are counted once)
                if known[i] is not None:
                    near.append((known[i], i))
                continue
            known[i] = None
            # the polygon's circumscribed circle against the frame box of the swept segment
            gx, gy, r = self._circles[i]
            dx, dy = gx - ox, gy - oy
            fx, fy = c * dx + s * dy, c * dy - s * dx
            ex = max(x0 - fx, 0.0, fx - x1)
            ey = max(y0 - fy, 0.0, fy - y1)
            if ex * ex + ey * ey > r * r:
                self.stats.broad_rejections += 1
                continue
            # the polygon's frame bounding box against the same box (scalar arithmetic:
            # a handful of vertices)
            px, py = [], []
            for x, y in self._vertex_lists[i]:
                vx, vy = x - ox, y - oy
                px.append(c * vx + s * vy)
                py.append(c * vy - s * vx)
            px_min = min(px)
            if max(px) < x0 or px_min > x1 or max(py) < y0 or min(py) > y1:
                self.stats.broad_rejections += 1
                continue
            known[i] = px_min
            near.append((px_min, i))
        if not near:
            return []
        near.sort()
        idx = [i for _, i in near]
        out = []
        for i in idx:
            hit = hits.get(i)
            if hit is None:
                if facts.samples is None:
                    facts.samples = self._samples(sw)
                wx, wy = facts.samples
                hit = self._certain_hit(wx, wy, i)
                if hit:
                    self.stats.certain_hits += 1
                else:
                    self.stats.exact_checks += 1
                    hit = collision.collides(sw, self.convex[i], check=False, stats=self.collision_stats)
                hits[i] = hit
            if hit:
                out.append(int(i))
                if first:
                    break
        return out

    def union_free(self, u: Union) -> bool:
        """Free of every obstacle, inside the bounds and within the steering limit."""
        return self.curvature_ok(u) and self.in_bounds(u) and not self.colliding(u)


class Expander:
    """Successors of nodes toward a goal (section "Generation of intermediate nodes").

    Parameters
    ----------
    workspace : Workspace
    version : {"b", "a"}
        Fig. 4: ``"b"`` an optimal reference system per piece (the paper's choice), ``"a"``
        one reference system shared by the two pieces of an intermediate node.
    alpha_method : {"heuristic", "exact"}
        Passed to :func:`segplan.frame.optimal_alpha_intrinsic`.
    max_iterations : int
        Iterates per vertex candidate.
    r0 : float
        First distance of a candidate from its vertex along the bisectrix, in units of ``L``.
    growth : float
        Factor applied to the distance when an iterate fails.
    spline_weight : float
        First weight ``w`` of the clamped-spline heading, in ``[0, 1]``.
    turn_radius : float
        Radius of the arcs to turn states, in units of the minimum turning radius (> 1).
    turn_angles : tuple of float
        Arc angles (radians, in ``(0, pi/2]``) of the turn states, on each side.
    recursion : int
        Levels of intermediate nodes generated for a candidate's own union when that
        union hits another obstacle.
    steer_fallback : bool
        When the optimal reference system's cubic breaks the steering limit, use the
        frame of least peak curvature instead (see :meth:`_steer`).
    slide : float
        Step along the obstacle's edge (units of ``L``) of the sliding iterates.
    all_obstacles : bool
        Candidates for every obstacle the direct union touches, not only the first.

    Notes
    -----
    All lengths scale with ``L``. The paper gives no values; the defaults were chosen by
    trials on the shipped scenarios and on random worlds.
    """

    def __init__(
        self,
        workspace: Workspace,
        version: str = "b",
        alpha_method: str = "heuristic",
        max_iterations: int = 4,
        r0: float = 0.3,
        growth: float = 1.7,
        spline_weight: float = 0.5,
        turn_radius: float = 1.6,
        turn_angles: tuple[float, ...] = (HALF_PI, 0.25 * math.pi),
        recursion: int = 1,
        steer_fallback: bool = True,
        slide: float = 0.5,
        all_obstacles: bool = False,
    ):
        if version not in ("a", "b"):
            raise ValueError(
                f"version must be 'a' (one shared reference system) or 'b' (one per piece), got {version!r}"
            )
        if alpha_method not in ("heuristic", "exact"):
            raise ValueError(f"alpha_method must be 'heuristic' or 'exact', got {alpha_method!r}")
        if isinstance(max_iterations, bool) or int(max_iterations) != max_iterations or max_iterations < 1:
            raise ValueError(f"max_iterations must be an integer >= 1, got {max_iterations!r}")
        for name, value, lo in (("r0", r0, 0.0), ("growth", growth, 1.0), ("turn_radius", turn_radius, 1.0)):
            if not (math.isfinite(value) and value > lo):
                raise ValueError(f"{name} must be a finite number > {lo}, got {value!r}")
        if not 0.0 <= spline_weight <= 1.0:
            raise ValueError(f"spline_weight must lie in [0, 1], got {spline_weight!r}")
        if not turn_angles or not all(0.0 < a <= HALF_PI for a in turn_angles):
            raise ValueError(f"turn_angles must be angles in (0, pi/2] radians, got {turn_angles!r}")
        self.ws = workspace
        self.version = version
        self.alpha_method = alpha_method
        self.max_iterations = int(max_iterations)
        self.r0 = float(r0) * workspace.L
        self.growth = float(growth)
        self.spline_weight = float(spline_weight)
        kappa = workspace.max_curvature
        R = 1.0 / kappa if 0.0 < kappa < math.inf else workspace.L  # minimum turning radius
        self.turn_radius = float(turn_radius) * R
        self.turn_angles = tuple(float(a) for a in turn_angles)
        self.recursion = int(recursion)
        self.steer_fallback = bool(steer_fallback)
        self.slide = float(slide) * workspace.L
        self.all_obstacles = bool(all_obstacles)
        self._cache: dict = {}
        self._alphas: dict = {}
        self._setup_cache: dict = {}
        self._tangent_cache: dict = {}
        self._approach: tuple | None = None

    @property
    def stats(self) -> ExpansionStats:
        return self.ws.stats

    def reset_stats(self) -> None:
        self.ws.stats = ExpansionStats()

    # -- unions ------------------------------------------------------------------------
    def union(self, p0: Pose, p1: Pose, frame_angle: float | None = None) -> Union | None:
        """The cubic union p0 -> p1, or None if no cubic exists.

        Parameters
        ----------
        frame_angle : float, optional
            World angle of the reference system's x-axis (version "a"); by default the
            optimal reference system (section "Optimal reference system"), cached per
            pose pair.
        """
        key = (p0, p1, frame_angle)
        if key in self._cache:
            return self._cache[key]
        u = self._make_union(p0, p1, frame_angle)
        if len(self._cache) > 200_000:
            self._cache.clear()
        self._cache[key] = u
        return u

    def prefetch(self, pairs) -> None:
        """Optimal reference systems of several pose pairs in one vectorised call.

        :func:`segplan.frame.optimal_alpha_intrinsic` costs far less per pair on arrays
        than on scalars for the exact method; the alphas are kept until :meth:`union` asks
        for them. Pairs without a cubic or already known are skipped. The heuristic
        method's scalar path is the faster one for fewer than
        :data:`PREFETCH_MIN_HEURISTIC` pairs (about 20 us a pair against 0.25-0.4 ms a
        call on arrays), so such batches are left to :meth:`union`, pair by pair. The two
        paths agree to rounding (a few 1e-15 rad).
        """
        if self.alpha_method == "heuristic" and len(pairs) < PREFETCH_MIN_HEURISTIC:
            return
        keys, geos = [], []
        for p0, p1 in pairs:
            if (p0, p1, None) in self._cache or (p0, p1) in self._alphas:
                continue
            geo = _geometry(p0, p1)
            if geo is not None:
                keys.append((p0, p1))
                geos.append(geo)
        if len(keys) < 2:
            return
        d, _, phi0, phi1, _, _ = (np.array(v) for v in zip(*geos, strict=True))
        try:
            alphas = self._optimal_alpha(d, phi0, phi1)
        except ValueError:
            return
        self.stats.batched += len(keys)
        if len(self._alphas) > 10_000:
            self._alphas.clear()
        for key, a in zip(keys, np.atleast_1d(alphas), strict=True):
            self._alphas[key] = float(a)

    def _optimal_alpha(self, d, phi0, phi1):
        """:func:`segplan.frame.optimal_alpha_intrinsic` of pairs from :func:`_geometry`.

        Those are valid by construction (``d > 0``, finite, a feasible interval wider than
        ``2 ALPHA_MARGIN``), so the heuristic method skips the re-validation (the same
        values: :func:`segplan.frame.heuristic_alpha` is what the method calls).
        """
        if self.alpha_method == "heuristic" and 0.0 < self.ws.L < math.inf:
            return heuristic_alpha(d, phi0, phi1, self.ws.L)
        return optimal_alpha_intrinsic(d, phi0, phi1, self.ws.L, method=self.alpha_method)

    def _make_union(self, p0, p1, frame_angle):
        geo = _geometry(p0, p1)
        if geo is None:
            self.stats.infeasible += 1
            return None
        d, psi, phi0, phi1, lo, hi = geo
        if frame_angle is None:
            alpha = self._alphas.pop((p0, p1), None)
            if alpha is None:
                try:
                    alpha = float(self._optimal_alpha(d, phi0, phi1))
                except ValueError:
                    self.stats.infeasible += 1
                    return None
        else:
            alpha = _wrap(psi - frame_angle)
        if not lo < alpha < hi:
            self.stats.infeasible += 1
            return None
        self.stats.unions += 1
        u = Union.from_intrinsic(p0, p1, alpha, self.ws.L, d, psi, phi0, phi1)
        if frame_angle is None and self.steer_fallback and not self.ws.curvature_ok(u):
            u = self._steer(p0, p1, d, psi, phi0, phi1, lo, hi) or u
        return u

    def _steer(self, p0, p1, d, psi, phi0, phi1, lo, hi) -> Union | None:
        """Steering fallback: the frame of least sampled peak curvature, if it keeps the limit.

        The optimal reference system minimises LONGD, not curvature; when its cubic breaks
        the steering limit another alpha may keep it (our addition: the paper has no
        steering limit). ``STEER_SAMPLES`` alphas across the feasible interval are scored by
        their largest curvature on 33 abscissae (one vectorised evaluation); the best is
        checked exactly.
        """
        alphas = lo + (hi - lo) * (np.arange(1, STEER_SAMPLES + 1) / (STEER_SAMPLES + 1))
        X, c1, c2, c3 = cubic_coefficients(d, phi0, phi1, alphas)
        x = X[:, None] * _TAU
        fp = c1[:, None] + (2.0 * c2[:, None] + 3.0 * c3[:, None] * x) * x
        fpp = 2.0 * c2[:, None] + 6.0 * c3[:, None] * x
        peak = np.max(np.abs(fpp) / (1.0 + fp * fp) ** 1.5, axis=1)
        k = int(np.argmin(peak))
        if not peak[k] < self.ws.max_curvature:
            return None
        self.stats.unions += 1
        u = Union.from_intrinsic(p0, p1, float(alphas[k]), self.ws.L, d, psi, phi0, phi1)
        return u if self.ws.curvature_ok(u) else None

    def link_cost(self, u: Union) -> float:
        """LONGD of a union (formula [2] inside its domain, [1] outside: :func:`segplan.cost.longd`).

        ``inf`` for a near-singular cubic whose integral [1] cannot be brought to the
        error bound (such a union also breaks the steering limit). Cached per union.
        """
        f = self.ws.facts(u)
        if f.cost is None:
            try:
                f.cost = _longd_scalar(u.d, u.phi0, u.phi1, u.alpha, u.L, LONGD_RTOL)
            except RombergError:
                f.cost = math.inf
        return f.cost

    # -- intermediate nodes --------------------------------------------------------------
    def shared_frame(self, start: Pose, goal: Pose) -> float:
        """Version "a": the optimal frame of the direct union, else its chord's angle."""
        u = self.union(start, goal)
        if u is not None:
            return u.frame_angle
        return math.atan2(goal[1] - start[1], goal[0] - start[0])

    def _tangents(self, polygon: int, point) -> tuple[int, int]:
        """:func:`tangent_vertices` of obstacle ``polygon`` seen from ``point`` (cached)."""
        key = (polygon, point[0], point[1])
        out = self._tangent_cache.get(key)
        if out is None:
            if len(self._tangent_cache) > 100_000:
                self._tangent_cache.clear()
            out = self._tangent_cache[key] = tangent_vertices(self.ws.polygons[polygon], point)
        return out

    def _setup(self, start: Pose, goal: Pose, polygon: int, side: int, subgoal: bool):
        """Vertex, completeness, bisectrix and reference headings of a candidate (cached:
        :meth:`first_estimate` and :meth:`intermediate` ask for the same one)."""
        key = (start, goal, polygon, side, subgoal)
        out = self._setup_cache.get(key)
        if out is None:
            if len(self._setup_cache) > 100_000:
                self._setup_cache.clear()
            out = self._setup_cache[key] = self._make_setup(start, goal, polygon, side, subgoal)
        return out

    def _make_setup(self, start: Pose, goal: Pose, polygon: int, side: int, subgoal: bool):
        poly = self.ws.polygons[polygon]
        ccw_s, cw_s = self._tangents(polygon, start)
        ccw_g, cw_g = self._tangents(polygon, goal)
        vertex = ccw_s if side > 0 else cw_s
        complete = not subgoal and vertex == (cw_g if side > 0 else ccw_g)
        v = poly[vertex]
        bx, by = self.ws._bisectors[polygon][vertex]
        # perpendicular to the bisectrix, clockwise around the obstacle for side +1
        theta_perp = math.atan2(-bx, by) if side > 0 else math.atan2(bx, -by)
        # direction of the edge that leaves the vertex in the direction of travel
        nxt = poly[(vertex - 1) % len(poly)] if side > 0 else poly[(vertex + 1) % len(poly)]
        theta_edge = math.atan2(nxt[1] - v[1], nxt[0] - v[0])
        return vertex, complete, v, (float(bx), float(by)), theta_perp, theta_edge

    def first_estimate(self, start: Pose, goal: Pose, polygon: int, side: int, subgoal: bool = False) -> Pose:
        """The first iterate of :meth:`intermediate` (the paper's "good initial estimate")."""
        _, _, v, (bx, by), theta_perp, _ = self._setup(start, goal, polygon, side, subgoal)
        return _iterate_pose(
            start, goal, v[0] + self.r0 * bx, v[1] + self.r0 * by, theta_perp, self.spline_weight
        )

    def intermediate(
        self, start: Pose, goal: Pose, polygon: int, side: int, subgoal: bool = False
    ) -> Candidate:
        """Generate an intermediate node passing obstacle ``polygon`` on ``side``.

        Iterates (at most ``max_iterations``) until the union start->P is free of the
        obstacle, exists and keeps the steering limit, and so does P->goal (free of the
        obstacle too when one node passes it, see the module docstring).

        Parameters
        ----------
        start, goal : Pose
        polygon : int
            Index of the offending obstacle.
        side : {+1, -1}
            ``+1``: pass with the obstacle on the robot's right.
        subgoal : bool
            ``goal`` is an intermediate node that another obstacle blocks (recursion),
            not the goal of the search: P->goal is then not required, since the next
            expansion from P aims at the search's goal.
        """
        vertex, complete, v, (bx, by), theta_perp, theta_edge = self._setup(
            start, goal, polygon, side, subgoal
        )
        frame = self.shared_frame(start, goal) if self.version == "a" else None
        ex, ey = math.cos(theta_edge), math.sin(theta_edge)
        r, w, base, slide, tight = self.r0, self.spline_weight, theta_perp, 0.0, False
        pose, u_in, u_out, reason = start, None, None, ""
        fallback = None
        for it in range(1, self.max_iterations + 1):
            pose = _iterate_pose(start, goal, v[0] + r * bx + slide * ex, v[1] + r * by + slide * ey, base, w)
            u_in = u_out = None
            reason = self._check_candidate(start, goal, pose, polygon, complete, frame)
            if isinstance(reason, tuple):
                u_in, u_out, blocked = reason
                if not blocked:
                    self.stats.iterations.append((it, True, complete))
                    return Candidate(pose, polygon, vertex, side, it, True, complete, u_in, u_out)
                if fallback is None:
                    fallback = Candidate(
                        pose, polygon, vertex, side, it, True, complete, u_in, u_out, "blocked"
                    )
                reason = "blocked"
            if reason == "pose" and not tight:
                # readjust an unreasonable orientation: along the next edge (a tight spot)
                base, w, tight = theta_edge, 0.0, True
            elif reason == "pose":
                # the robot at P still touches something (a narrow gap): closer to the vertex
                r /= self.growth
            elif tight:
                # the robot fits only along the edge: slide along it, deeper into the passage
                slide += self.slide
            elif reason == "collision":
                r *= self.growth
            elif reason in ("infeasible_in", "curvature_in", "blocked"):
                # too sharp a turn from the start, or another obstacle on the way in: slide
                # along the next edge, with a smoother heading
                slide += self.slide
                if reason != "blocked":
                    base, w = theta_edge, 0.5 * (1.0 + w)
            else:  # the union to the goal does not exist or is too curved
                w = 0.5 * (1.0 + w)
                r *= self.growth
        if fallback is not None:
            # free of the offending obstacle but blocked by another: the caller generates
            # intermediate nodes for that one (recursion)
            self.stats.iterations.append((fallback.iterations, True, complete))
            return fallback
        self.stats.iterations.append((self.max_iterations, False, complete))
        return Candidate(
            pose, polygon, vertex, side, self.max_iterations, False, complete, u_in, u_out, reason
        )

    def _check_candidate(self, start, goal, pose, polygon, complete, frame):
        """Check one iterate.

        Returns ``(u_in, u_out, blocked)`` if start->pose exists, keeps the steering limit
        and is free of the offending obstacle, and, for a complete candidate, so is
        pose->goal (``u_out`` is None otherwise: the next expansion deals with it);
        ``blocked`` tells whether start->pose hits another obstacle or a wall. Otherwise a
        reason string: ``"pose"``, ``"infeasible_in"``, ``"curvature_in"``,
        ``"collision"``, ``"infeasible_out"``, ``"curvature_out"``.
        """
        if not self.ws.pose_free(pose):
            return "pose"
        u_in = self.union(start, pose, frame)
        if u_in is None:
            return "infeasible_in"
        if not self.ws.curvature_ok(u_in):
            return "curvature_in"
        if self.ws.colliding(u_in, only=(polygon,)):
            return "collision"
        u_out = None
        if complete:
            u_out = self.union(pose, goal, frame)
            if u_out is None:
                return "infeasible_out"
            if not self.ws.curvature_ok(u_out):
                return "curvature_out"
            if self.ws.colliding(u_out, only=(polygon,)):
                return "collision"
        others = [i for i in range(len(self.ws.polygons)) if i != polygon]
        blocked = not self.ws.in_bounds(u_in) or bool(self.ws.colliding(u_in, only=others))
        return u_in, u_out, blocked

    def turn_states(self, node: Pose) -> list[Pose]:
        """Turn states of a difficult case: ends of arcs of radius ``turn_radius`` from ``node``."""
        x, y, th = node
        R = self.turn_radius
        out = []
        for beta in self.turn_angles:
            for side in (1.0, -1.0):
                # centre at the side, point after turning by beta
                cx, cy = x - side * R * math.sin(th), y + side * R * math.cos(th)
                t = th + side * beta
                out.append(Pose(cx + side * R * math.sin(t), cy - side * R * math.cos(t), _wrap(t)))
        return out

    def approach_states(self, goal: Pose) -> list[tuple[Pose, Union]]:
        """Approach states of the goal, with their free unions to it (cached per goal).

        The mirror image of :meth:`turn_states`: poses from which the robot reaches the
        goal along an arc of radius ``turn_radius`` turning by ``turn_angles`` to either
        side, or straight along the goal's heading from ``2 L`` behind it. They are the
        "suitable intermediate states" of a difficult final approach (a goal near a wall
        or heading against the direction of arrival).
        """
        if self._approach is not None and self._approach[0] == goal:
            return self._approach[1]
        back = Pose(goal.x, goal.y, _wrap(goal.theta + math.pi))
        poses = [Pose(p.x, p.y, _wrap(p.theta + math.pi)) for p in self.turn_states(back)]
        c, s = math.cos(goal.theta), math.sin(goal.theta)
        poses.append(Pose(goal.x - 2.0 * self.ws.L * c, goal.y - 2.0 * self.ws.L * s, goal.theta))
        out = []
        self.prefetch([(p, goal) for p in poses])
        for pose in poses:
            if not self.ws.pose_free(pose):
                continue
            u = self.union(pose, goal)
            if u is not None and self.ws.union_free(u):
                out.append((pose, u))
        self._approach = (goal, out)
        return out

    # -- successors --------------------------------------------------------------------
    def direct(self, node: Pose, goal: Pose) -> Union | None:
        """The direct union node->goal in its optimal reference system (cached)."""
        return self.union(node, goal)

    def successors(self, node: Pose, goal: Pose, turns: bool = True) -> list[Successor]:
        """Successors of ``node`` in the on-line graph, toward ``goal``.

        The goal itself if the direct union is free; otherwise intermediate nodes near the
        first offending obstacle (both sides); turn states for the difficult cases.
        Every returned union is free, in bounds and within the steering limit.
        """
        u = self.direct(node, goal)
        out: list[Successor] = []
        if u is not None and self.ws.curvature_ok(u):
            hit = self.ws.colliding(u, first=not self.all_obstacles)
            inside = self.ws.in_bounds(u)
            if not hit and inside:
                return [Successor(goal, u, "goal", ("goal",))]
            if hit:
                # obstacles: intermediate nodes near their vertices; turn states only if
                # none works
                seen = set()
                for polygon in hit:
                    for succ in self._around(node, goal, polygon, self.recursion):
                        if succ.key not in seen:
                            seen.add(succ.key)
                            out.append(succ)
                if out:
                    return out
        # a difficult case: approach states of the goal, and turn states of the node
        return self._approaches(node, goal) + (self._turns(node) if turns else [])

    def _around(self, node: Pose, target: Pose, polygon: int, depth: int, subgoal=False) -> list[Successor]:
        if self.version == "b":
            # both sides' first estimates (usually accepted) in one vectorised batch
            firsts = [self.first_estimate(node, target, polygon, side, subgoal) for side in (1, -1)]
            self.prefetch([(node, p) for p in firsts] + [(p, target) for p in firsts])
        out = []
        for side in (1, -1):
            cand = self.intermediate(node, target, polygon, side, subgoal)
            if not cand.ok:
                continue
            u = cand.union_in
            if not self.ws.in_bounds(u):
                continue
            hit = self.ws.colliding(u)
            if not hit:
                key = ("vertex", polygon, cand.vertex, side, round(cand.pose.theta / (math.pi / 6)))
                out.append(Successor(cand.pose, u, "vertex", key, cand))
            elif depth > 0:
                out += self._around(node, cand.pose, hit[0], depth - 1, subgoal=True)
        return out

    def _approaches(self, node: Pose, goal: Pose) -> list[Successor]:
        out = []
        states = self.approach_states(goal)
        self.prefetch([(node, p) for p, _ in states])
        for i, (pose, _) in enumerate(states):
            if pose == node:
                continue
            u = self.union(node, pose)
            if u is not None and self.ws.union_free(u):
                out.append(Successor(pose, u, "approach", ("approach", i)))
        return out

    def _turns(self, node: Pose) -> list[Successor]:
        out = []
        q = 0.25 * self.ws.L
        states = self.turn_states(node)
        self.prefetch([(node, p) for p in states])
        for pose in states:
            if not self.ws.pose_free(pose):
                continue
            u = self.union(node, pose)
            if u is None or not self.ws.union_free(u):
                continue
            key = ("turn", round(pose.x / q), round(pose.y / q), round(pose.theta / (math.pi / 8)))
            out.append(Successor(pose, u, "turn", key))
        return out
