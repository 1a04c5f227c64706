"""Plane geometry of the planning model: convex polygons, bounds, segments, enlargement.

The one home of each idea the planner shares (issue 11):

* :func:`check_convex_polygon`, the one polygon validator, and :class:`ConvexPolygon`,
  a polygon validated once with its edge normals and bounding circle (the paper's
  "centre of the polygon" and ``r_max``, section "Collision-detection algorithm");
  :func:`collides <segplan.floor.collision.collides>`, :func:`segplan.make_scenario`,
  :func:`segplan.load_scenario` and :func:`segplan.plan` all validate through it, so they
  accept and reject the same polygons;
* :func:`check_bounds`, the one validator of walls ``(xmin, ymin, xmax, ymax)``;
* :func:`segment_hits_polygon` and :func:`segment_in_bounds`, the one segment-polygon and
  segment-walls predicates, with an explicit tolerance ``tol`` (a length);
  :func:`touch_tolerance` and :func:`pose_collides` / :func:`pose_in_bounds` /
  :func:`pose_conflict` give the robot at one pose the planner's tolerance, and
  :func:`segment_hits_edges` is their scalar fast path (the same decisions);
* :func:`enlarge_polygon`, the off-line enlargement of obstacles by the robot's half-width
  (section "Results": "obstacles appropriately enlarged").

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

Tolerances (stated)
-------------------
Polygons: a turn within ``ANGLE_TOL = 1e-9`` rad of 0 is a collinear vertex (the boundary
goes straight through it), one within ``ANGLE_TOL`` of pi doubles back; an edge shorter
than ``LENGTH_TOL = 1e-12`` times the largest coordinate magnitude repeats a vertex; exact
duplicates anywhere are repeated vertices: every shipped scenario, notebook and test
polygon passes them. Two kinds of vertex are dropped instead of refused (:func:`open_ring`): a
closing copy of the first vertex at the end (GeoJSON and WKT rings, CAD exports) and
collinear vertices (every union of grid cells has them); a polygon that doubles back, a
repeated vertex elsewhere, zero area, a self-intersection and non-finite numbers are still
refused. Touching: ``TOUCH_RTOL = 1e-9`` times the size of the scene (the segment's
length, the polygon's radius, their distance and the coordinates' magnitude) counts as
touching, in every pose test of the planner and of scenarios alike, the tolerance of the
swept-segment test :func:`segplan.floor.collision.collides`: a segment and a polygon are apart
when their bounding boxes are more than ``tol`` apart or a separating axis (an edge normal
or the segment's normal) separates them by more than ``tol``. (Before issue 11 the
planner's own pose test was exact, ``tol = 0``; the scenarios' used this tolerance. No
shipped scenario, notebook or test pose lies within it of an obstacle.)
"""

from __future__ import annotations

import math

import numpy as np

from ..model.pose import TWO_PI, as_pose, check_length

__all__ = [
    "ANGLE_TOL",
    "Bounds",
    "ConvexPolygon",
    "DEFAULT_MAX_ARC",
    "LENGTH_TOL",
    "TOUCH_RTOL",
    "as_polygon",
    "check_bounds",
    "open_ring",
    "check_convex_polygon",
    "edge_list",
    "enlarge_polygon",
    "enlargement_excess",
    "finite_number",
    "polygons_overlap",
    "pose_collides",
    "axis_segment",
    "pose_conflict",
    "pose_in_bounds",
    "pose_segment",
    "segment_hits_edges",
    "segment_hits_polygon",
    "segment_in_bounds",
    "touch_tolerance",
    "bounds_tolerance",
]

#: Largest arc of the enlargement disk replaced by one tangent edge (radians).
DEFAULT_MAX_ARC = math.radians(45.0)
#: Turns within this angle (radians) of 0 or pi count as collinear vertices.
ANGLE_TOL = 1e-9
#: Edges shorter than this times the largest coordinate magnitude count as repeated vertices.
LENGTH_TOL = 1e-12
#: Relative tolerance of touching: separations below ``TOUCH_RTOL`` times the size of the
#: scene count as contact (closed sets, conservative: a near-touch is a collision).
TOUCH_RTOL = 1e-9

#: Walls ``(xmin, ymin, xmax, ymax)``, as returned by :func:`check_bounds`.
Bounds = tuple[float, float, float, float]


# -- numbers and bounds -----------------------------------------------------------
def finite_number(value, name: str, minimum: float | None = None) -> float:
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


def check_bounds(bounds, name: str = "bounds") -> Bounds:
    """Validate walls ``(xmin, ymin, xmax, ymax)``: four finite floats with ``xmin < xmax``, ``ymin < ymax``.

    The one bounds validator (collision, metrics, plots and scenarios call it).

    Raises
    ------
    ValueError
        Naming ``name``: not four numbers, not finite, or not a proper rectangle.
    """
    try:
        b = tuple(float(v) for v in bounds)
    except (TypeError, ValueError, OverflowError) as exc:
        raise ValueError(
            f"{name} must be four finite numbers (xmin, ymin, xmax, ymax), got {bounds!r}"
        ) from exc
    if len(b) != 4:
        raise ValueError(f"{name} must be [xmin, ymin, xmax, ymax], got {len(b)} numbers")
    if not all(math.isfinite(v) for v in b):
        raise ValueError(f"{name} must be four finite numbers (xmin, ymin, xmax, ymax), got {bounds!r}")
    if not (b[0] < b[2] and b[1] < b[3]):
        raise ValueError(f"{name} {list(b)} are not a rectangle: need xmin < xmax and ymin < ymax")
    return b  # type: ignore[return-value]


# -- convex polygons ------------------------------------------------------------------
def open_ring(v: np.ndarray) -> np.ndarray:
    """``v`` without a closing copy of its first vertex (the last vertex, equal up to rounding).

    GeoJSON and WKT rings, shapely's ``exterior.coords`` and many CAD exports repeat the first
    vertex at the end; that copy is no vertex of the polygon and is dropped (issue 27).
    "Equal up to rounding": the closing edge is shorter than ``LENGTH_TOL`` times the largest
    coordinate magnitude, the tolerance of a repeated vertex. ``v`` is a finite ``(k, 2)``
    array; a ring of at most 3 vertices is returned as it is (its repeat is refused later).
    """
    if len(v) <= 3:
        return v
    scale = float(np.abs(v).max())
    w = v / scale if scale > 0.0 else v  # no overflow for huge inputs
    if float(np.hypot(*(w[-1] - w[0]))) <= LENGTH_TOL:
        return v[:-1]
    return v


def _turns(w: np.ndarray) -> np.ndarray:
    """Signed exterior angle at each vertex of the closed ring ``w`` (from edge ``i-1`` to edge ``i``)."""
    edges = _edges(w)  # edge i: w[i] -> w[i+1]
    prev = np.concatenate((edges[-1:], edges[:-1]))  # edge into vertex i
    cross = prev[:, 0] * edges[:, 1] - prev[:, 1] * edges[:, 0]
    dot = np.einsum("ij,ij->i", prev, edges)
    return np.arctan2(cross, dot)


def check_convex_polygon(vertices, where: str = "polygon") -> np.ndarray:
    """Validate a convex simple polygon and return it strictly convex, counter-clockwise.

    Parameters
    ----------
    vertices : array_like, shape (k, 2)
        The vertices in order, either orientation; the ring may be closed (the first vertex
        repeated at the end) and may have collinear vertices: both are dropped.
    where : str
        Names the polygon in error messages (e.g. ``"world.json: obstacles[3]"``).

    Returns
    -------
    ndarray, shape (m, 2)
        A new float array, counter-clockwise, strictly convex: the input's vertices without
        a closing copy of the first one (:func:`open_ring`) and without the vertices the
        boundary goes straight through (turn within ``ANGLE_TOL`` of 0; dropped repeatedly,
        so a straight run of any length leaves its two ends), ``m <= k``. Vertex indices in
        error messages refer to the input order.

    Raises
    ------
    ValueError
        Fewer than 3 vertices, wrong shape, non-finite numbers, a repeated vertex (other
        than a closing copy of the first), a degenerate, zero-area polygon (all vertices
        collinear), an edge doubling back (a turn within ``ANGLE_TOL`` of pi), a non-convex
        polygon (turns of both signs), or a self-intersecting one whose turns all have one
        sign but add up to a multiple of 2 pi other than one (e.g. a star pentagon: 4 pi).

    Notes
    -----
    The turn at vertex ``i`` is the signed angle from edge ``v[i] - v[i-1]`` to edge
    ``v[i+1] - v[i]``. A closed polygon is convex and simple iff all turns are nonzero,
    of one sign, and add up to ``+-2 pi``. Collinear means within ``ANGLE_TOL`` radians.
    Dropping a collinear vertex moves the boundary by at most ``ANGLE_TOL`` times the
    length of its edges (exactly nothing for a vertex on the segment of its neighbours).
    Until issue 27 a collinear vertex and a closing copy were refused.
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
    v = open_ring(v)
    k = len(v)
    # repeated vertices: exact duplicates anywhere, near-duplicates between neighbours
    _, first, inverse = np.unique(v, axis=0, return_index=True, return_inverse=True)
    dup = np.flatnonzero(first[inverse.ravel()] != np.arange(k))
    if dup.size:
        j = int(dup[0])
        i = int(first[inverse.ravel()[j]])
        raise ValueError(f"{where}: vertex {j} repeats vertex {i} {v[j].tolist()}")
    scale = float(np.abs(v).max())
    w = v / scale if scale > 0.0 else v  # turns are scale invariant; no overflow for huge inputs
    edges = _edges(w)  # edge i: v[i] -> v[i+1]
    short = np.flatnonzero(np.hypot(edges[:, 0], edges[:, 1]) <= LENGTH_TOL)
    if short.size:
        i = int(short[0])
        raise ValueError(f"{where}: vertex {(i + 1) % k} repeats vertex {i} up to rounding")
    turn = _turns(w)
    straight = np.abs(turn) <= ANGLE_TOL
    back = np.abs(turn) >= math.pi - ANGLE_TOL
    if np.all(straight | back):
        raise ValueError(f"{where}: degenerate polygon, all vertices are collinear (zero area)")
    if back.any():
        i = int(np.flatnonzero(back)[0])
        raise ValueError(
            f"{where}: vertex {i} {v[i].tolist()} doubles back; "
            "the polygon must be strictly convex (remove it)"
        )
    keep = np.arange(k)  # input indices of the vertices kept
    while straight.any():  # collinear vertices: dropped, then the turns of the rest again
        keep = keep[~straight]
        if len(keep) < 3:
            raise ValueError(f"{where}: degenerate polygon, all vertices are collinear (zero area)")
        turn = _turns(w[keep])
        straight = np.abs(turn) <= ANGLE_TOL
        if np.any(np.abs(turn) >= math.pi - ANGLE_TOL):
            raise ValueError(f"{where}: degenerate polygon, all vertices are collinear (zero area)")
    v, w = v[keep], w[keep]
    total = float(turn.sum())
    sign = math.copysign(1.0, total) if abs(total) > math.pi else math.copysign(1.0, _area2(w))
    wrong = np.flatnonzero(np.sign(turn) != sign)
    if wrong.size:
        right = np.flatnonzero(np.sign(turn) == sign)
        sense = ("counter-clockwise", "clockwise") if sign > 0 else ("clockwise", "counter-clockwise")
        raise ValueError(
            f"{where}: not convex: the boundary turns {sense[1]} at vertex {keep[wrong[0]]} "
            f"{v[wrong[0]].tolist()} but {sense[0]} at vertex {keep[right[0]]} "
            "(non-convex or self-intersecting)"
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


class ConvexPolygon:
    """A validated convex polygon with the data the tests need, computed once (immutable).

    Parameters
    ----------
    vertices : array_like, shape (k, 2)
        Either orientation.
    check : bool
        Validate (:func:`check_convex_polygon`). With ``check=False`` the caller guarantees a
        strictly convex, non-degenerate polygon; only the orientation is normalised.

    Attributes
    ----------
    vertices : ndarray (k, 2)
        Counter-clockwise, read-only.
    normals : ndarray (k, 2)
        Outward unit normal of edge ``i`` (from vertex ``i`` to ``i + 1``).
    offsets : ndarray (k,)
        ``normals[i] . p <= offsets[i]`` for every point of the polygon.
    centre : tuple of float
        Centre of the bounding box (the paper's "centre of the polygon").
    radius : float
        Largest distance from ``centre`` to a vertex (the paper's ``r_max``).
    box : tuple of float
        Bounding box ``(xmin, ymin, xmax, ymax)``.
    """

    __slots__ = ("vertices", "normals", "offsets", "centre", "radius", "box")

    def __init__(self, vertices, check: bool = True):
        if check:
            v = check_convex_polygon(vertices)
        else:
            v = np.array(vertices, dtype=float)
            nxt = np.concatenate((v[1:], v[:1]))  # np.roll(v, -1, axis=0), without its overhead
            area2 = float(np.sum(v[:, 0] * nxt[:, 1] - nxt[:, 0] * v[:, 1]))
            if area2 < 0:
                v = v[::-1].copy()
        e = np.concatenate((v[1:], v[:1])) - v  # v[i+1] - v[i]
        n = np.column_stack((e[:, 1], -e[:, 0])) / np.hypot(e[:, 0], e[:, 1])[:, None]
        h = np.einsum("ij,ij->i", n, v)
        lo, hi = v.min(axis=0), v.max(axis=0)
        c = 0.5 * (lo + hi)
        r = float(np.max(np.hypot(v[:, 0] - c[0], v[:, 1] - c[1])))
        for arr in (v, n, h):
            arr.flags.writeable = False
        box = (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))
        for key, value in zip(self.__slots__, (v, n, h, (float(c[0]), float(c[1])), r, box), strict=True):
            object.__setattr__(self, key, value)

    def __setattr__(self, name, value):
        raise AttributeError("ConvexPolygon is immutable")

    def __repr__(self) -> str:
        return f"ConvexPolygon({self.vertices.tolist()})"

    def __len__(self) -> int:
        return len(self.vertices)


def as_polygon(polygon, check: bool = True, name: str = "polygon") -> ConvexPolygon:
    """Return ``polygon`` as a :class:`ConvexPolygon` (no work if it already is one).

    Validated by :func:`check_convex_polygon` unless ``check=False``. No cache: callers
    that test one polygon often build its :class:`ConvexPolygon` once.
    """
    if isinstance(polygon, ConvexPolygon):
        return polygon
    if check:
        return ConvexPolygon(check_convex_polygon(polygon, name), check=False)
    try:
        v = np.asarray(polygon, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a (k, 2) array of numbers, got {polygon!r}") from exc
    return ConvexPolygon(v, check=False)


# -- enlargement -----------------------------------------------------------------------
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
    r = finite_number(half_width, "half_width", minimum=0.0)
    step = finite_number(max_arc, "max_arc")
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


def segment_hits_polygon(a, b, polygon, tol: float = 0.0) -> bool:
    """Does the closed segment ``a``-``b`` touch the closed convex polygon? (SAT, tolerance ``tol``).

    Separating-axis theorem: two convex sets are disjoint iff some edge normal of one of
    them separates them. The axes are the polygon's outward edge normals (both end points
    strictly outside one edge's half-plane) and the segment's normal (all vertices
    strictly on one side of the segment's line). Touching counts as a hit.

    Parameters
    ----------
    a, b : array_like, shape (2,)
    polygon : ConvexPolygon or array_like, shape (k, 2)
        Counter-clockwise convex polygon (not re-validated).
    tol : float
        Separation (a length, >= 0) below which the sets count as touching: they are
        apart only if their bounding boxes are more than ``tol`` apart or one of the
        axes (unit edge normals, the segment's unit normal) separates them by more than
        ``tol``. ``0``: exact separating axes (the random floors, the shapely tests);
        the planner's pose tests pass :func:`touch_tolerance`.
    """
    if tol != 0.0:
        return _hits_within(
            float(a[0]), float(a[1]), float(b[0]) - float(a[0]), float(b[1]) - float(a[1]),
            as_polygon(polygon, check=False), float(tol),
        )  # fmt: skip
    v = polygon.vertices if isinstance(polygon, ConvexPolygon) else np.asarray(polygon, dtype=float)
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    e = _edges(v)
    n = np.column_stack((e[:, 1], -e[:, 0]))  # outward normals of a CCW polygon (length |e|)
    sa = np.einsum("ij,ij->i", n, a - v)
    sb = np.einsum("ij,ij->i", n, b - v)
    if np.any((sa > 0.0) & (sb > 0.0)):
        return False
    d = b - a
    side = d[0] * (v[:, 1] - a[1]) - d[1] * (v[:, 0] - a[0])
    return not (np.all(side > 0.0) or np.all(side < 0.0))


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


def segment_in_bounds(a, b, bounds, tol: float = 0.0) -> bool:
    """Is the segment more than ``tol`` inside the rectangle ``(xmin, ymin, xmax, ymax)``?

    ``bounds`` as from :func:`check_bounds` (not re-validated); ``tol = 0``: strictly inside.
    """
    xmin, ymin, xmax, ymax = bounds
    xs = (a[0], b[0])
    ys = (a[1], b[1])
    return xmin + tol < min(xs) and max(xs) < xmax - tol and ymin + tol < min(ys) and max(ys) < ymax - tol


# -- the robot at one pose (the planner's touching tolerance) ------------------------
def touch_tolerance(ax: float, ay: float, L: float, centre, radius: float) -> float:
    """Touching tolerance of the segment at ``A = (ax, ay)`` (length ``L``) and a polygon.

    ``TOUCH_RTOL`` times the size of the scene: ``L + r_max + |centre - A| + max(|ax|, |ay|)``.
    """
    return TOUCH_RTOL * (L + radius + math.hypot(centre[0] - ax, centre[1] - ay) + max(abs(ax), abs(ay)))


def bounds_tolerance(ax: float, ay: float, L: float, bounds: Bounds) -> float:
    """Touching tolerance of the segment at ``A`` and the walls: ``TOUCH_RTOL`` times the scene size."""
    xmin, ymin, xmax, ymax = bounds
    return TOUCH_RTOL * (L + (xmax - xmin) + (ymax - ymin) + math.hypot(ax, ay))


def _hits_within(ax: float, ay: float, dx: float, dy: float, poly: ConvexPolygon, tol: float) -> bool:
    """Segment ``A = (ax, ay)``, ``B = A + (dx, dy)`` against ``poly`` with tolerance ``tol`` (arrays)."""
    bx, by = ax + dx, ay + dy
    x0, y0, x1, y1 = poly.box
    if min(ax, bx) > x1 + tol or max(ax, bx) < x0 - tol or min(ay, by) > y1 + tol or max(ay, by) < y0 - tol:
        return False
    N, H, V = poly.normals, poly.offsets, poly.vertices
    gA = N[:, 0] * ax + N[:, 1] * ay - H
    gB = N[:, 0] * bx + N[:, 1] * by - H
    if np.any(np.minimum(gA, gB) > tol):
        return False
    L = math.hypot(dx, dy)
    side = (dx * (V[:, 1] - ay) - dy * (V[:, 0] - ax)) / L
    return not (np.all(side > tol) or np.all(side < -tol))


def edge_list(polygon: ConvexPolygon) -> tuple:
    """``(box, [(x_i, y_i, n_x, n_y, h_i), ...])`` of a polygon as Python floats.

    For :func:`segment_hits_edges`: the bounding box and, per vertex, the unit outward
    normal of the edge leaving it (``h_i = n . v_i``).
    """
    rows = [
        (float(x), float(y), float(nx), float(ny), float(h))
        for (x, y), (nx, ny), h in zip(polygon.vertices, polygon.normals, polygon.offsets, strict=True)
    ]
    return polygon.box, rows


def segment_hits_edges(ax: float, ay: float, dx: float, dy: float, edges, tol: float) -> bool:
    """:func:`segment_hits_polygon` with ``tol > 0`` in scalar arithmetic (the planner's fast path).

    The segment is ``A = (ax, ay)`` to ``B = A + (dx, dy)``; ``edges`` from
    :func:`edge_list`. The same operations in the same order as the array path, so the
    same decisions (checked by ``tests/test_fast_paths.py``).
    """
    (x0, y0, x1, y1), rows = edges
    bx, by = ax + dx, ay + dy
    if min(ax, bx) > x1 + tol or max(ax, bx) < x0 - tol or min(ay, by) > y1 + tol or max(ay, by) < y0 - tol:
        return False
    for _, _, nx, ny, h in rows:
        if nx * ax + ny * ay - h > tol and nx * bx + ny * by - h > tol:
            return False
    L = math.hypot(dx, dy)
    pos = neg = True
    for x, y, _, _, _ in rows:
        side = (dx * (y - ay) - dy * (x - ax)) / L
        pos = pos and side > tol
        neg = neg and side < -tol
    return not (pos or neg)


def axis_segment(x: float, y: float, theta: float, L: float, rear: float = 0.0, front: float = 0.0):
    """The robot's checked axis segment at the pose ``(x, y, theta)``: ``(ax, ay, dx, dy, length)``,
    from ``A - rear u`` to ``A + (L + front) u`` (``u`` the heading; overhangs of
    :class:`segplan.Robot`). ``rear = front = 0``: A->B, with the very floats of
    ``(x, y, L cos theta, L sin theta, L)``."""
    c, s = math.cos(theta), math.sin(theta)
    length = L + rear + front
    return x - rear * c, y - rear * s, length * c, length * s, length


def _pose_segment(pose, L, rear: float = 0.0, front: float = 0.0):
    p = as_pose(pose)
    return axis_segment(p.x, p.y, p.theta, check_length(L), rear, front)


def pose_collides(
    pose, L: float, polygon, *, check: bool = True, rear: float = 0.0, front: float = 0.0
) -> bool:
    """Does the robot's segment at ``pose`` (A and heading, radians) touch ``polygon``?

    :func:`segment_hits_polygon` with the tolerance :func:`touch_tolerance` (that of
    :func:`segplan.floor.collision.collides`): touching counts. ``rear``, ``front``: the
    overhangs (:func:`axis_segment`).
    """
    ax, ay, dx, dy, L = _pose_segment(pose, L, rear, front)
    poly = as_polygon(polygon, check)
    return _hits_within(ax, ay, dx, dy, poly, touch_tolerance(ax, ay, L, poly.centre, poly.radius))


def pose_in_bounds(pose, L: float, bounds, *, rear: float = 0.0, front: float = 0.0) -> bool:
    """Does the robot's segment at ``pose`` lie strictly inside ``bounds`` (walls)?

    Touching a wall, within :func:`bounds_tolerance`, is leaving the bounds. ``rear``,
    ``front``: the overhangs (:func:`axis_segment`).
    """
    ax, ay, dx, dy, L = _pose_segment(pose, L, rear, front)
    b = check_bounds(bounds)
    tol = bounds_tolerance(ax, ay, L, b)
    return segment_in_bounds((ax, ay), (ax + dx, ay + dy), b, tol)


def pose_conflict(
    pose, L: float, polygons, bounds=None, *, rear: float = 0.0, front: float = 0.0
) -> str | None:
    """Why the robot at ``pose`` is not free (``"bounds"`` or ``"obstacles[i]"``), or None.

    The one "is this pose free" predicate: :func:`pose_in_bounds` for the walls, then
    :func:`pose_collides` for each polygon (validated :class:`ConvexPolygon` objects or
    counter-clockwise arrays, not re-validated). :meth:`segplan.Scenario.pose_conflict`
    and the planner's :meth:`segplan.planning.validity.Workspace.pose_free` (its scalar fast path)
    decide with it. ``rear``, ``front``: the robot's overhangs (:func:`axis_segment`).
    """
    if bounds is not None and not pose_in_bounds(pose, L, bounds, rear=rear, front=front):
        return "bounds"
    for i, poly in enumerate(polygons):
        if pose_collides(pose, L, poly, check=False, rear=rear, front=front):
            return f"obstacles[{i}]"
    return None
