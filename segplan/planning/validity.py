"""The validity checker: is a pose, a union, free? (the planner's view of the world).

What the search may use of the obstacles and walls (OMPL's "state validity checker"):
:class:`Workspace` holds the enlarged obstacles as :class:`segplan.floor.geometry.ConvexPolygon`,
the free bounds and the steering limit, and answers, cheap tests first (the paper's
"quick checkings ... If it is not so the more time-consuming routines are executed",
section "Collision-detection algorithm"):

* :meth:`Workspace.pose_free`: the robot at one pose (:func:`segplan.floor.geometry.pose_conflict`);
* :meth:`Workspace.curvature_ok`: the union's rear-path curvature within the steering limit
  (through :meth:`segplan.Union.max_curvature`, the one exact maximum);
* :meth:`Workspace.in_bounds`, :meth:`Workspace.colliding`: the swept segment against the
  walls and the obstacles (:mod:`segplan.floor.collision`);
* :meth:`Workspace.union_free`: all of these;
* :meth:`Workspace.inside`: which sample points lie strictly inside an obstacle (the
  refinement's screen).

On large floors only the obstacles near the region asked about are examined: the workspace
files them in a grid of buckets (:class:`segplan.floor.buckets.BoxGrid`, :attr:`Workspace.index`),
which returns every obstacle a test could keep, so the tests decide as they would over all.

Answers about a union are kept per union only when the caller asks (``cache=True``, an
instance's own store; no module-level cache).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from ..floor.body import RectangleBody
from ..floor.buckets import BoxGrid
from ..floor.collision import CollisionStats, collides, sweep_in_bounds
from ..floor.geometry import (
    ConvexPolygon,
    axis_segment,
    bounds_tolerance,
    check_bounds,
    edge_list,
    segment_hits_edges,
    segment_in_bounds,
    touch_tolerance,
)
from ..floor.sweep import Sweep
from ..model.union import Union, curvature_samples, exceeds_curvature

__all__ = ["HIT_SAMPLES", "ExpansionStats", "Workspace"]

_CURV_S = np.linspace(0.0, 1.0, 17)
#: Positions (fractions of the union's span) sampled by the certain-hit test.
HIT_SAMPLES = 9
_HIT_S = np.linspace(0.0, 1.0, HIT_SAMPLES)


@dataclass
class ExpansionStats:
    """Counters of one expansion engine (reset with
    :meth:`segplan.planning.paper.expansion.Expander.reset_stats`).

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
        Calls of the exact test :func:`segplan.floor.collision.collides`.
    broad_rejections : int
        Union-polygon pairs rejected by the bounding-box test alone.
    certain_hits : int
        Union-polygon pairs found colliding by a sample inside the polygon.
    batched : int
        Optimal reference systems computed in vectorised batches
        (:meth:`segplan.planning.links.LinkModel.prefetch`).
    curvature_exact : int
        Unions whose curvature needed :meth:`Union.max_curvature` (the cheap bound failed).
    body_checks : int
        Union-polygon pairs the round body touches, asked again about a rectangular body
        (:attr:`Workspace.body`).

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
    body_checks: int = 0

    @property
    def collision_checks(self) -> int:
        """Union-polygon pairs decided (by the bounding box or the exact test)."""
        return self.exact_checks + self.broad_rejections


class _Facts:
    """What a :class:`Workspace` has established about one union (kept per union object).

    Every test of a union is a deterministic function of the union (and of the fixed
    workspace), so its answer is computed once: the search meets the same union several
    times (the direct union of a node as its ``h'`` and at its expansion; a candidate's
    union against the offending obstacle, the others, then all of them). Kept only when
    the caller asks (``Workspace(..., cache=True)``, the default of the planner).
    """

    __slots__ = ("union", "sweep", "curvature", "in_bounds", "near", "swept", "hits", "samples")

    def __init__(self, union: Union):
        self.union = union  # keeps the union alive, so its id is not reused while cached
        self.sweep = None
        self.curvature = None
        self.in_bounds = None
        # the broad phase's decisions: polygon -> frame abscissa of its nearest vertex if kept,
        # None if rejected; once ``swept``, every polygon is decided and those absent are rejected
        self.near: dict = {}
        self.swept = False
        self.hits: dict = {}  # polygon -> touched
        self.samples = None


#: Margin of the index's queries (:attr:`Workspace.index`) relative to the coordinates'
#: magnitude: far above the rounding of the tests they stand for (a few ulps, ~1e-15), so a
#: query returns every obstacle those tests could keep.
_ROUNDING = 1e-9

#: Obstacles above which :meth:`Workspace.colliding` and :meth:`Workspace.pose_free` pre-screen
#: them with arrays (large floors; below, the scalar loops alone, as before).
VECTOR_SCREEN_MIN = 64


def _padded(rows: list, k: int, *tail: int) -> np.ndarray:
    """Arrays of shape ``(m, *tail)``, ``m <= k``, stacked as ``(len(rows), k, *tail)``, each
    padded with copies of its first row."""
    out = np.empty((len(rows), k, *tail), dtype=float)
    for i, a in enumerate(rows):
        out[i, : len(a)] = a
        out[i, len(a) :] = a[0]
    return out


class Workspace:
    """Enlarged convex obstacles, bounds and robot limits, with cheap tests first.

    Parameters
    ----------
    obstacles : sequence of (k, 2) arrays
        Enlarged obstacles, strictly convex (as :attr:`segplan.Scenario.enlarged`,
        already validated: they are wrapped as
        :class:`segplan.floor.geometry.ConvexPolygon` without re-validation).
    L : float
        Robot length.
    bounds : (xmin, ymin, xmax, ymax) or None
        Free bounds (walls already moved inwards by the half-width).
    max_curvature : float
        Steering limit of the rear path, ``tan(max_steer) / L``.
    cache : bool
        Keep the answers about each union (:meth:`facts`, at most 4096 unions); False:
        every question is answered afresh.
    rear, front : float
        The robot's overhangs (:class:`segplan.Robot`, beyond the paper): every test is of
        the axis segment from ``A - rear u`` to ``B + front u``
        (:class:`segplan.floor.sweep.Sweep`, :func:`segplan.floor.geometry.axis_segment`);
        :attr:`overhang`, the larger, is the distance from A->B of its farthest point, which
        the lattice's point screens add to their covering radii. 0: the segment A->B.
    body : segplan.floor.body.RectangleBody, optional
        A rectangular body (:class:`segplan.Robot` with ``rectangle=True``, beyond the
        paper): a union or pose the tests below find touching an enlarged obstacle or the
        moved walls (the round body, which contains the rectangle) is asked again about the
        rectangle itself against the raw obstacle or walls (:mod:`segplan.floor.body`),
        which decides. None: the round body (the paper's, with overhangs) is the robot.

    Notes
    -----
    Order of the tests on a union (the paper's "quick checkings ... If it is not so the
    more time-consuming routines are executed"):

    1. all obstacles at once: the frame bounding box of each polygon against the frame
       box of the swept segment (:class:`segplan.floor.sweep.Sweep`), one vectorised step
       over the obstacles filed near it (:attr:`index`; above ``VECTOR_SCREEN_MIN``
       obstacles);
    2. a *certain hit*: a sample of the swept segment (rear point, front wheel and
       middle of the robot at ``HIT_SAMPLES`` positions) strictly inside the polygon;
    3. :func:`segplan.floor.collision.collides` (the paper's ``d_c`` rejection, then the exact
       event test) on the polygons left;
    4. with a rectangular ``body``, on the polygons found touching: the rectangle's exact
       sweep against the raw obstacle (:func:`segplan.floor.body.rectangle_collides`).

    The screens that only *reject* with the enlarged obstacles (a point of A->B inside one or
    beyond a moved wall, the lattice's blocked cells, :meth:`inside`) reject a point only
    deeper than :attr:`depth`: 0 for the round body; for a rectangle the depth at which the
    rectangle itself must touch (:attr:`segplan.floor.body.RectangleBody.depth`), so they
    stay sound for it.
    """

    def __init__(
        self,
        obstacles,
        L: float,
        bounds=None,
        max_curvature: float = math.inf,
        *,
        cache: bool = True,
        rear: float = 0.0,
        front: float = 0.0,
        body: RectangleBody | None = None,
    ):
        self.convex = [ConvexPolygon(p, check=False) for p in obstacles]
        if body is not None and len(body.convex) != len(self.convex):
            raise ValueError(
                f"body has {len(body.convex)} raw obstacles for {len(self.convex)} enlarged ones"
            )
        #: The rectangular body's exact tests (:class:`segplan.floor.body.RectangleBody`) or None.
        self.body = body
        #: How deep inside an enlarged obstacle or beyond a moved wall a point of A->B is a
        #: certain collision (m): 0 for the round body, :attr:`RectangleBody.depth` for a rectangle.
        self.depth = 0.0 if body is None else body.depth
        self.rear, self.front = float(rear), float(front)
        #: The farthest a point of the checked segment lies from A->B (m; 0 without overhangs).
        self.overhang = max(self.rear, self.front)
        self.polygons = [c.vertices for c in self.convex]  # counter-clockwise
        self.L = float(L)
        self.bounds = None if bounds is None else check_bounds(bounds)
        self.max_curvature = float(max_curvature)
        self.cache = bool(cache)
        self.stats = ExpansionStats()
        self.collision_stats = CollisionStats()
        self._facts: dict = {}
        # circumscribed circles (centre of the bounding box, largest vertex distance), inflated
        # by a relative margin so the broad phase never rejects a touching polygon
        self._circles = [(c.centre[0], c.centre[1], c.radius * (1.0 + 1e-9) + 1e-9) for c in self.convex]
        # the same circles, and the vertices padded to a common count (the first repeated),
        # as arrays: the broad phase of floors of many obstacles, vectorised (the same
        # floating-point operations as the scalar loop, so the same decisions)
        self._circle_array = np.array(self._circles, dtype=float).reshape(-1, 3)
        k = max((len(p) for p in self.polygons), default=1)
        self._vertex_array = _padded(self.polygons, k, 2)
        #: Bounding boxes ``(xmin, ymin, xmax, ymax)`` of the obstacles (Python floats).
        self.boxes = [c.box for c in self.convex]
        #: The same bounding boxes as an ``(n, 4)`` array (for vectorised screens).
        self.box_array = np.array(self.boxes, dtype=float).reshape(-1, 4)
        # the edges' normals and offsets padded the same way (the first edge repeated), for
        # :meth:`inside`
        self._normal_array = _padded([c.normals for c in self.convex], k, 2)
        self._offset_array = _padded([c.offsets for c in self.convex], k)
        # vertices as Python floats, for the scalar broad phase of :meth:`colliding`
        self._vertex_lists = [[(float(x), float(y)) for x, y in p] for p in self.polygons]
        # boxes and unit edge normals as Python floats, for the scalar :meth:`pose_free`
        self._edge_lists = [edge_list(c) for c in self.convex]

    def reset(self) -> None:
        """Forget the counters and the answers kept about unions: a new planning call on the
        same floor (:class:`segplan.Planner`) counts its own work, and the unions of earlier
        calls are not asked about again (the answers are kept on union identities)."""
        self.stats = ExpansionStats()
        self.collision_stats = CollisionStats()
        self._facts.clear()

    @functools.cached_property
    def index(self) -> BoxGrid:
        """The obstacles filed by the cells of a grid (:class:`segplan.floor.buckets.BoxGrid`),
        each under the box that holds its bounding box and its circle: a query returns every
        obstacle whose polygon or circle may meet the region asked about. Built at its first
        use (floors of more than ``VECTOR_SCREEN_MIN`` obstacles; a few hundred microseconds
        that a small floor's plan would not use)."""
        C, B = self._circle_array, self.box_array
        lo = np.minimum(C[:, :2] - C[:, 2:], B[:, :2])
        hi = np.maximum(C[:, :2] + C[:, 2:], B[:, 2:])
        return BoxGrid(np.column_stack((lo, hi)))

    # -- poses -------------------------------------------------------------------------
    def pose_free(self, pose) -> bool:
        """Is the robot's segment at ``pose`` (overhangs included) clear of every obstacle and in the bounds?

        :func:`segplan.floor.geometry.pose_conflict` (the one pose predicate, touching within
        ``TOUCH_RTOL``) in scalar arithmetic: the same decisions, faster for a handful of
        polygons (checked by ``tests/test_fast_paths.py``).
        """
        if self.body is not None:  # the rectangle itself (a pose test is cheap)
            return self.body.pose_conflict(pose) is None
        x, y, dx, dy, L = axis_segment(*pose, self.L, self.rear, self.front)
        if self.bounds is not None:
            tol = bounds_tolerance(x, y, L, self.bounds)
            if not segment_in_bounds((x, y), (x + dx, y + dy), self.bounds, tol):
                return False
        if len(self.convex) > VECTOR_SCREEN_MIN:
            # an obstacle whose circle is farther than the segment's half-length + L / 10
            # from its middle is left out: the scalar test could not find it touching (its
            # tolerance is ~1e-9 of the scene; a separating axis leaves a gap of at least
            # L / 10 times the sine of half the polygon's sharpest angle); only obstacles filed
            # near the middle can be that close (the index; its margin covers the rounding)
            mx, my = x + 0.5 * dx, y + 0.5 * dy
            a = 0.6 * L + 1e-6 + _ROUNDING * (1.0 + abs(mx) + abs(my) + L)
            S = self.index.query(mx - a, my - a, mx + a, my + a)
            C = self._circle_array[S]
            reach = C[:, 2] + 0.6 * L + 1e-6
            near = S[(C[:, 0] - mx) ** 2 + (C[:, 1] - my) ** 2 <= reach * reach].tolist()
        else:
            near = range(len(self.convex))
        for i in near:
            c = self.convex[i]
            tol = touch_tolerance(x, y, L, c.centre, c.radius)
            if segment_hits_edges(x, y, dx, dy, self._edge_lists[i], tol):
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
        piece between the samples; otherwise the exact maximum (:meth:`Union.max_curvature`).
        """
        if not math.isfinite(self.max_curvature):
            return True
        _, _, c2, c3 = u.coefficients
        X = u.x_end
        if max(abs(2.0 * c2), abs(2.0 * c2 + 6.0 * c3 * X)) <= self.max_curvature:
            return True
        # a sampled curvature above the limit is a certain failure
        c1 = u.coefficients[1]
        x, fp, fpp = curvature_samples(X, c1, c2, c3, _CURV_S)
        fpp = np.abs(fpp)
        if exceeds_curvature(fp, fpp, self.max_curvature):
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
        return u.max_curvature() <= self.max_curvature

    def facts(self, u: Union) -> _Facts:
        """The answers about union ``u`` (kept on the union's identity if ``cache``)."""
        if not self.cache:
            return _Facts(u)
        f = self._facts.get(id(u))
        if f is None or f.union is not u:
            if len(self._facts) > 4096:
                self._facts.clear()
            f = _Facts(u)
            self._facts[id(u)] = f
        return f

    def sweep(self, u: Union) -> Sweep:
        """The per-union data of the collision tests (cached on the union's identity)."""
        f = self.facts(u)
        if f.sweep is None:
            f.sweep = Sweep(u, self.rear, self.front)
        return f.sweep

    def in_bounds(self, u: Union) -> bool:
        """Does the swept segment stay strictly inside the bounds? (cached per union)"""
        if self.bounds is None:
            return True
        f = self.facts(u)
        if f.in_bounds is None:
            sw = self.sweep(u)
            f.in_bounds = sweep_in_bounds(sw, self.bounds) or (
                self.body is not None and self.body.in_bounds(sw)
            )
        return f.in_bounds

    def _samples(self, sw: Sweep) -> tuple[np.ndarray, np.ndarray]:
        """World points of the swept segment: rear, middle and front at ``HIT_SAMPLES`` positions."""
        x, fx, ux, uy = sw.segment(_HIT_S)
        L = sw.L
        fr = np.concatenate((x, x + 0.5 * L * ux, x + L * ux))
        fy = np.concatenate((fx, fx + 0.5 * L * uy, fx + L * uy))
        return sw.x0 + sw.cos * fr - sw.sin * fy, sw.y0 + sw.sin * fr + sw.cos * fy

    def inside(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Which points lie strictly inside an obstacle, deeper than :attr:`depth` (vectorised).

        Each point against the obstacles filed under its cell (:attr:`index`: every one
        whose bounding box holds it; up to ``VECTOR_SCREEN_MIN`` obstacles, against every
        one): strictly inside the box, then strictly inside every edge by more than the
        depth (``n . p - h < -depth``; 0 for the round body).

        Parameters
        ----------
        x, y : ndarray
            Coordinates of the points (one shape).

        Returns
        -------
        ndarray of bool
            Of that shape.
        """
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        out = np.zeros(x.size, dtype=bool)
        px, py = x.ravel(), y.ravel()
        if len(self.convex) > VECTOR_SCREEN_MIN:
            p, i = self.index.pairs(px, py)
            px, py, bb = px[p], py[p], self.box_array[i]
            box = (px > bb[:, 0]) & (px < bb[:, 2]) & (py > bb[:, 1]) & (py < bb[:, 3])
            p, i, px, py = p[box], i[box], px[box], py[box]
        else:  # a few obstacles: the same box test on every pair, without the index's bookkeeping
            bb, qx, qy = self.box_array, px[:, None], py[:, None]
            p, i = np.nonzero((qx > bb[:, 0]) & (qx < bb[:, 2]) & (qy > bb[:, 1]) & (qy < bb[:, 3]))
            px, py = px[p], py[p]
        N = self._normal_array[i]
        g = px[:, None] * N[:, :, 0] + py[:, None] * N[:, :, 1] - self._offset_array[i]
        out[p[np.all(g < -self.depth, axis=1)]] = True
        return out.reshape(x.shape)

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
        if only is None and len(self.polygons) > VECTOR_SCREEN_MIN:
            near = self._broad_phase(facts, sw)
            candidates = ()
        else:
            near = []
        for i in candidates:
            if i in known or facts.swept:  # decided by the broad phase before (counted once)
                if known.get(i) is not None:
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
                    hit = collides(sw, self.convex[i], check=False, stats=self.collision_stats)
                if hit and self.body is not None:  # the round body touches: the rectangle?
                    self.stats.body_checks += 1
                    hit = self.body.collides(sw, i)
                hits[i] = hit
            if hit:
                out.append(int(i))
                if first:
                    break
        return out

    def _broad_phase(self, facts: _Facts, sw) -> list:
        """The scalar broad phase of :meth:`colliding` over every obstacle, vectorised.

        Only the obstacles filed (:attr:`index`) near the world box of the swept segment's
        frame box are examined: an obstacle whose circle meets that frame box has its
        circle's box meeting the frame box's world box, so every other one would fail the
        circle test. On those, the scalar loop's floating-point operations on arrays (circle
        against the frame box, then the polygon's frame box): the same decisions and counts.
        Afterwards every obstacle is decided (``facts.swept``); the kept ones are stored,
        the rejected ones are not.
        """
        known = facts.near
        near = [(v, i) for i, v in known.items() if v is not None]
        if facts.swept:
            return near
        x0, x1, y0, y1 = sw.box
        c, s, ox, oy = sw.cos, sw.sin, sw.x0, sw.y0
        # the frame box's corners in the world, and their box grown by the rounding margin
        wx = [ox + c * fx - s * fy for fx in (x0, x1) for fy in (y0, y1)]
        wy = [oy + s * fx + c * fy for fx in (x0, x1) for fy in (y0, y1)]
        m = _ROUNDING * (1.0 + max(map(abs, wx + wy)))
        U = self.index.query(min(wx) - m, min(wy) - m, max(wx) + m, max(wy) + m)
        if known:
            U = U[[i not in known for i in U.tolist()]]
        C = self._circle_array[U]
        dx, dy = C[:, 0] - ox, C[:, 1] - oy
        fx, fy = c * dx + s * dy, c * dy - s * dx
        ex = np.maximum(np.maximum(x0 - fx, 0.0), fx - x1)
        ey = np.maximum(np.maximum(y0 - fy, 0.0), fy - y1)
        inside = ~(ex * ex + ey * ey > C[:, 2] * C[:, 2])
        S = U[inside]
        V = self._vertex_array[S]
        vx, vy = V[:, :, 0] - ox, V[:, :, 1] - oy
        px, py = c * vx + s * vy, c * vy - s * vx
        px_min = px.min(axis=1)
        keep = ~((px.max(axis=1) < x0) | (px_min > x1) | (py.max(axis=1) < y0) | (py.min(axis=1) > y1))
        # the undecided obstacles, less those kept, are rejected (most without being examined)
        self.stats.broad_rejections += len(self.polygons) - len(known) - int(keep.sum())
        facts.swept = True
        for i, v in zip(S[keep].tolist(), px_min[keep].tolist(), strict=True):
            known[i] = v
            near.append((v, i))
        return near

    def union_free(self, u: Union) -> bool:
        """Free of every obstacle, inside the bounds and within the steering limit."""
        return self.curvature_ok(u) and self.in_bounds(u) and not self.colliding(u)
