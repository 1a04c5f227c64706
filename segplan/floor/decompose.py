"""Any simple polygon as obstacles: its split into convex pieces (beyond the paper).

The paper's collision test (section "Collision-detection algorithm") takes convex
polygons. A floor plan's racks and bays are not convex; :func:`convex_pieces` splits a
simple polygon into convex pieces with disjoint interiors whose union is the polygon, so
that the planner and the swept-segment test see only convex polygons and their
guarantees hold piece by piece (a segment misses the polygon iff it misses every piece).
Enlarging the pieces one by one (:func:`segplan.floor.geometry.enlarge_polygon`) covers the
Minkowski sum of the whole polygon with the disk, which is the union of the pieces' sums.

Method
------
1. A polygon that :func:`segplan.floor.geometry.check_convex_polygon` accepts is returned as
   the single piece, without a closing copy of its first vertex and without collinear
   vertices (issue 27: dropped, no longer refused; convex input that was accepted before
   gives exactly the scenario it always gave).
2. Otherwise the vertices are checked (shape, finite, no repeated vertex other than a
   closing copy of the first one, which is dropped), then the ring
   must be *simple* (shapely's ``is_valid``; a self-intersection is reported with the
   vertices whose edges meet there) with nonzero area.
3. shapely's constrained Delaunay triangulation (``shapely.constrained_delaunay_triangles``,
   GEOS >= 3.10, shapely >= 2.1) splits it into triangles on the input vertices (no new
   points, so every piece's vertices are input vertices, bit for bit).
4. Greedy merging: in a fixed order, two pieces that share an edge are replaced by their
   union while the union, without its collinear vertices, passes
   :func:`check_convex_polygon`; repeated until no pair merges. Deterministic.

Holes (interior rings of a shapely ``Polygon``) are refused with a ``ValueError``: give
the ring around a hole as several polygons.
"""

from __future__ import annotations

import numpy as np

from .geometry import ANGLE_TOL, LENGTH_TOL, _area2, check_convex_polygon, open_ring

__all__ = ["as_outlines", "convex_pieces", "decompose"]


def as_outlines(obstacle, where: str = "polygon") -> list[np.ndarray]:
    """The vertex lists of one obstacle given as vertices or a shapely geometry.

    Parameters
    ----------
    obstacle : array_like (k, 2), shapely Polygon or MultiPolygon
        A polygon's vertices in order (not closed), or a shapely polygon (its exterior
        ring without the closing vertex) or multipolygon (one outline per part).
    where : str
        Names the obstacle in error messages.

    Raises
    ------
    ValueError
        A shapely polygon with holes, an empty geometry or another geometry type.
    """
    kind = getattr(obstacle, "geom_type", None)
    if kind is None:
        return [obstacle]
    if kind == "MultiPolygon":
        parts = list(obstacle.geoms)
        if not parts:
            raise ValueError(f"{where}: an empty MultiPolygon")
        out = []
        for j, part in enumerate(parts):
            out.extend(as_outlines(part, f"{where} part {j}"))
        return out
    if kind != "Polygon":
        raise ValueError(f"{where}: a {kind} is not an obstacle; give a Polygon, a MultiPolygon or vertices")
    if obstacle.is_empty:
        raise ValueError(f"{where}: an empty Polygon")
    if len(obstacle.interiors):
        raise ValueError(
            f"{where}: a polygon with {len(obstacle.interiors)} hole(s) is not supported; "
            "give the ring around a hole as several polygons"
        )
    return [np.asarray(obstacle.exterior.coords, dtype=float)[:-1]]


def convex_pieces(vertices, where: str = "polygon") -> list[np.ndarray]:
    """Split a simple polygon into strictly convex pieces (beyond the paper).

    The paper's collision test (section "Collision-detection algorithm") takes convex
    polygons; this is how a non-convex obstacle (an L-shaped rack, a U-shaped bay) reaches
    it: shapely's constrained Delaunay triangulation on the polygon's own vertices, then
    triangles merged greedily while their union stays convex (the module docstring gives
    the method). A segment misses the polygon iff it misses every piece.
    ``decompose(vertices, where)[1]``.

    Parameters
    ----------
    vertices : array_like, shape (k, 2)
        The polygon's vertices in order, either orientation; a closing copy of the first
        vertex and collinear vertices are dropped.
    where : str
        Names the polygon in error messages (e.g. ``"obstacles[3]"``).

    Returns
    -------
    list of ndarray (n, 2)
        Counter-clockwise strictly convex pieces with disjoint interiors whose union is the
        polygon, every vertex an input vertex; a convex polygon gives one piece, itself.

    Raises
    ------
    ValueError
        Naming ``where`` and the vertex: wrong shape, fewer than 3 vertices, non-finite
        coordinates, a repeated vertex, a self-intersecting boundary, zero area.

    Examples
    --------
    >>> from segplan import convex_pieces
    >>> L = [(0, 0), (4, 0), (4, 1), (1, 1), (1, 3), (0, 3)]
    >>> len(convex_pieces(L))
    2
    """
    return decompose(vertices, where)[1]


def decompose(vertices, where: str = "polygon") -> tuple[np.ndarray, list[np.ndarray]]:
    """Validate a simple polygon and split it into strictly convex pieces (module docstring).

    Parameters
    ----------
    vertices : array_like, shape (k, 2)
        The polygon's vertices in order, either orientation; a closing copy of the first
        vertex at the end is dropped. Collinear vertices are allowed (they vanish from
        the pieces; a non-convex outline keeps them); a polygon whose boundary turns one
        way only (convex, or a star) is decided by :func:`check_convex_polygon`, which
        drops its collinear vertices.
    where : str
        Names the polygon in error messages.

    Returns
    -------
    outline : ndarray (k, 2)
        The polygon, counter-clockwise (a new array), without a closing copy of the first
        vertex (and, if convex, without collinear vertices).
    pieces : list of ndarray (n, 2)
        Counter-clockwise strictly convex pieces with disjoint interiors whose union is
        the polygon; if the polygon is convex, one piece: ``outline`` itself.

    Raises
    ------
    ValueError
        Naming ``where`` and the vertex: wrong shape, fewer than 3 vertices, non-finite
        coordinates, a repeated vertex, a self-intersecting boundary, zero area.
    """
    try:
        convex = check_convex_polygon(vertices, where)
        return convex, [convex]
    except ValueError as exc:
        refusal = exc
    v = _check_vertices(vertices, where)
    if v is None:  # the convex validator's message is the right one (shape, finite, repeats)
        raise refusal
    if not _has_reflex_vertex(v):  # convex up to collinear vertices, or a star: refused as always
        raise refusal
    scale = float(np.abs(v).max()) or 1.0
    d = v - v[0]
    far = d[np.argmax(np.hypot(d[:, 0], d[:, 1]))]  # collinear iff every d is parallel to it
    if not np.any(np.abs(far[0] * d[:, 1] - far[1] * d[:, 0]) > LENGTH_TOL * scale**2):
        raise ValueError(f"{where}: degenerate polygon, all vertices are collinear (zero area)")
    import shapely  # beyond the paper: shapely decomposes, the planner never calls it

    poly = shapely.Polygon(v)
    if not poly.is_valid:
        reason = shapely.is_valid_reason(poly)
        raise ValueError(
            f"{where}: not a simple polygon ({reason.split('[')[0].strip().lower()}) at "
            f"{_where_it_crosses(v, reason)}; the boundary must not cross or touch itself"
        )
    if poly.area <= LENGTH_TOL * scale * scale:
        raise ValueError(f"{where}: degenerate polygon of zero area")
    triangulation = shapely.constrained_delaunay_triangles(poly)
    triangles = [np.asarray(t.exterior.coords)[:-1] for t in triangulation.geoms]
    pieces = [_ccw(t) for t in triangles if abs(_area2(t)) > 0.0]
    return _ccw(v), _merge(pieces, where)


def _check_vertices(vertices, where: str) -> np.ndarray | None:
    """``(k, 2)`` finite floats, k >= 3, no repeated vertex (a closing copy of the first dropped).

    None where the convex check said why.
    """
    try:
        v = np.array(vertices, dtype=float)
    except (TypeError, ValueError, OverflowError):
        return None
    if v.ndim != 2 or v.shape[1] != 2 or len(v) < 3 or not np.all(np.isfinite(v)):
        return None
    v = open_ring(v)
    if len(np.unique(v, axis=0)) != len(v):
        return None
    scale = float(np.abs(v).max()) or 1.0
    e = np.roll(v, -1, axis=0) - v
    if np.any(np.hypot(e[:, 0], e[:, 1]) <= LENGTH_TOL * scale):
        return None
    return v


def _has_reflex_vertex(v: np.ndarray) -> bool:
    """Does the boundary turn against its orientation (by more than ``ANGLE_TOL``) somewhere?"""
    a = v - np.roll(v, 1, axis=0)
    b = np.roll(v, -1, axis=0) - v
    turn = np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.einsum("ij,ij->i", a, b))
    big = np.abs(turn) > ANGLE_TOL
    return bool(np.any(big & (turn > 0))) and bool(np.any(big & (turn < 0)))


def _where_it_crosses(v: np.ndarray, reason: str) -> str:
    """Name the vertices whose edges meet at the point of shapely's validity reason (``"... [x y]"``)."""
    try:
        x, y = (float(t) for t in reason.split("[", 1)[1].rstrip("]").split()[:2])
    except (IndexError, ValueError):
        return "vertex 0"
    p = np.array([x, y])
    w = np.roll(v, -1, axis=0)
    e = w - v
    t = np.clip(np.einsum("ij,ij->i", p - v, e) / np.einsum("ij,ij->i", e, e), 0.0, 1.0)
    d = np.hypot(*(v + t[:, None] * e - p).T)
    scale = max(float(np.abs(v).max()), 1.0)
    near = np.flatnonzero(d <= 1e-9 * scale)
    j = int(np.argmin(np.hypot(v[:, 0] - x, v[:, 1] - y)))
    if len(near) >= 2:
        i, k = int(near[0]), int(near[1])
        meet = f"the edges leaving vertex {i} and vertex {k} meet at ({x:g}, {y:g})"
        return f"vertex {j} {v[j].tolist()}: {meet}"
    return f"vertex {j} {v[j].tolist()} (near ({x:g}, {y:g}))"


def _ccw(v: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(v if _area2(v) > 0 else v[::-1], dtype=float)


def _drop_collinear(v: np.ndarray) -> np.ndarray:
    """``v`` without vertices whose turn is within ``ANGLE_TOL`` of 0 (straight through)."""
    while len(v) > 3:
        a = v - np.roll(v, 1, axis=0)  # edge into vertex i
        b = np.roll(v, -1, axis=0) - v  # edge out of vertex i
        turn = np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.einsum("ij,ij->i", a, b))
        flat = np.flatnonzero(np.abs(turn) <= ANGLE_TOL)
        if not flat.size:
            break
        v = np.delete(v, flat[0], axis=0)
    return v


def _glue(p: np.ndarray, q: np.ndarray, i: int, j: int) -> np.ndarray:
    """The ring of ``p`` and ``q`` glued along their shared edge (``p[i]->p[i+1]`` = ``q[j+1]->q[j]``)."""
    n, m = len(p), len(q)
    # walk p from p[i+1] round to p[i], then q from q[j+1]... : q's vertices after p[i] = q[j+1]
    ring_p = [p[(i + 1 + k) % n] for k in range(n)]  # p[i+1], ..., p[i]
    ring_q = [q[(j + 2 + k) % m] for k in range(m - 2)]  # q[j+2], ..., q[j-1]
    return np.array(ring_p + ring_q, dtype=float)


def _merge(pieces: list[np.ndarray], where: str) -> list[np.ndarray]:
    """Greedily merge neighbours (sharing an edge) while the union stays strictly convex.

    One pass in a fixed order: each piece, edge by edge, is merged with the piece across
    the edge if their union is strictly convex, and scans its edges again after every
    merge, so that in the end no two neighbours can merge. Pieces share exact vertex
    coordinates (the triangulation adds no points): a shared edge is found by its two end
    points.
    """
    alive = dict(enumerate(pieces))
    owner: dict = {}  # directed edge (a, b) -> (piece, index of a)

    def ring(k):
        return [tuple(x) for x in alive[k].tolist()]

    def edges(k, add):
        r = ring(k)
        for i in range(len(r)):
            key = (r[i], r[(i + 1) % len(r)])
            if add:
                owner[key] = (k, i)
            else:
                owner.pop(key, None)

    for k in alive:
        edges(k, True)
    for a in range(len(pieces)):
        if a not in alive:
            continue
        i = 0
        while i < len(alive[a]):
            r = ring(a)
            across = owner.get((r[(i + 1) % len(r)], r[i]))  # the same edge, reversed
            if across is not None and across[0] != a:
                b, j = across
                try:
                    union = check_convex_polygon(_drop_collinear(_glue(alive[a], alive[b], i, j)))
                except ValueError:
                    union = None
                if union is not None:
                    edges(a, False)
                    edges(b, False)
                    del alive[b]
                    alive[a] = union
                    edges(a, True)
                    i = 0  # a changed: try every edge again
                    continue
            i += 1
    return [
        check_convex_polygon(_drop_collinear(p), f"{where} convex piece {n}")
        for n, p in enumerate(alive.values())
    ]
