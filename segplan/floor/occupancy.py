"""Occupancy grids as convex obstacles: which cells block, and convex pieces that cover them.

Beyond the paper (issue 27): robots' maps are occupancy grids (ROS ``map_server`` images,
``nav_msgs/OccupancyGrid``), while the planner sees convex polygons (section
"Collision-detection algorithm"). This module turns the one into the other; the floor
(:class:`segplan.floor.maps.Floor`) puts the pieces in metres.

Cells
-----
:func:`classify` reads a grid as the ROS message does: a boolean grid is True where
occupied; a numeric grid holds occupancy in percent (0 free .. 100 occupied), negative
values and NaN are unknown. A cell is *blocked* (an obstacle for the planner) if occupied,
or unknown when unknown cells count as occupied (the default everywhere).

Coordinates here are in cells: the grid's row 0 is its bottom row (lowest y, as in
``nav_msgs/OccupancyGrid``; an image's row 0 is its top row, the caller flips it), cell
``(r, c)`` is the unit square ``[c, c + 1] x [r, r + 1]``, and a piece is a
counter-clockwise strictly convex polygon with integer vertices (cell corners).

The cover (:func:`cover_cells`)
-------------------------------
**Every blocked cell is covered** (conservative: a simplification only grows obstacles),
and a piece touches a free cell only if that cell is *near* a blocked one: within ``k``
cells in the Chebyshev distance between cell centres (``max(|dr|, |dc|) <= k``; the
``tolerance`` of :meth:`segplan.Floor.from_occupancy`, in cells). "Touches" means the open
cell meets the piece (a shared edge or corner does not count): :func:`touched_cells`.
``tests/test_maps.py`` checks both with shapely, cell by cell.

``k = 0``: the exact partition into rectangles (:func:`rectangles`): the runs of blocked
cells of each row, merged with identical runs of the rows above; no free cell is touched.

``k >= 1``: the 8-connected components of blocked cells are covered one by one:

1. a component whose bounding box holds no far cell (farther than ``k`` from every blocked
   cell) is covered by that box (vectorised over every component at once: specks, blobs,
   ragged straight walls);
2. otherwise (a region of it, starting with the whole component): its tight bounding box
   if that holds no far cell; else the convex hull of its cells if the hull touches no far
   cell (a slanted wall, a rasterised polygon: one piece); else its exact rectangles if
   they are at most :data:`FEW_RECTANGLES` (an L, a U); else the region is cut in two
   halves across its longer side and each half is covered the same way. A single cell is
   its own box, so the recursion ends.

The hull test is exact: the hull has integer vertices, its x-extent over the band of each
row is computed in integer arithmetic (floor and ceiling of rational numbers), and the far
cells of a row between two columns are counted from the row's prefix sums, so a test costs
one operation per row.

What the tolerance costs the robot: every point of a piece lies within ``k sqrt(2)`` cell
sizes of a blocked cell (it is in a blocked cell or in a touched one, whose centre is within
``k`` cells of a blocked cell's centre in both x and y, so each of its points is within ``k``
cells of that blocked square in x and in y), so the robot is kept at most that much farther
from the blocked cells than the exact cover keeps it. Much of what is
covered it could not reach anyway: its body, of half-width ``r``, does not fit into a notch
narrower than ``2 r`` between ragged cells (closing a set with a disk and then dilating it by
the disk is dilating it, ``(A . B) + B = A + B``); a hull over a ragged wall is close to that
closing.

Measured (the free space lost, and the pieces)
----------------------------------------------
The loss is the fraction of the free cells that some piece touches,
:meth:`segplan.Floor.free_space_loss` (``touched_cells(pieces) & free``, counted)::

    floor = segplan.load_ros_map("office.yaml")  # or Floor.from_occupancy(grid, ...)
    floor.free_space_loss(), len(floor.obstacles)

On the 2000 x 3000-cell synthetic office map of ``benchmarks/maps.py`` (5 cm cells; ragged
and slanted walls, furniture, specks, unknown pockets; stored in
``benchmarks/results/maps.json``, commit d650fa3): tolerance 0 cells, 21489 pieces and no
free cell touched; 1 cell, 1926 pieces and 0.94 % of the free cells touched; 2 cells (the
default), 1447 pieces and 1.02 %; 3 cells, 1326 pieces and 1.07 %. ``load_ros_map`` took
0.44 s (median of 7 loads, 2 shared cores, load average 2.5; target 2 s). The shipped
floors rasterised at 5 cm (``tests/test_maps.py``): fig. 5 and fig. 6 give back 10 pieces
(156 exact rectangles) touching 0.3 % of the free cells, ``l_shaped_rack`` its 6 pieces.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "DEFAULT_OCCUPIED",
    "FEW_RECTANGLES",
    "FEW_RECTANGLES_AREA",
    "blocked_cells",
    "classify",
    "cover_cells",
    "rectangles",
    "touched_cells",
]

#: Occupancy (percent) at or above which a cell of a numeric grid is occupied: ROS
#: ``map_server``'s default ``occupied_thresh`` 0.65.
DEFAULT_OCCUPIED = 65.0

FREE, OCCUPIED, UNKNOWN = 0, 1, -1

#: A region of the cover whose box and hull reach too far is covered by its exact rectangles
#: (:func:`rectangles`) when they are at most this many, else cut in two: an L-shaped rack
#: (2 rectangles) or a U-shaped bay (3) stays as few pieces as its exact partition. On
#: ``l_shaped_rack`` rasterised at 5 cm: 22 pieces with 1 cell of tolerance without this
#: step, 6 with it (the exact partition: 6).
FEW_RECTANGLES = 3
#: ... tried on regions of at most this many cells (a larger one is cut first: its halves
#: are tried), so that the big regions of a map cost no partition each.
FEW_RECTANGLES_AREA = 256 * 256


def classify(grid, occupied: float | None = None, free: float | None = None) -> np.ndarray:
    """Cell classes of an occupancy grid: 1 occupied, 0 free, -1 unknown (int8, same shape).

    Parameters
    ----------
    grid : array_like, 2-D
        Booleans (True: occupied; no unknown cell) or numbers in the ``nav_msgs/OccupancyGrid``
        convention: occupancy in percent, 0 free .. 100 occupied, negative or NaN unknown.
    occupied : float, optional
        Numeric grids: a cell is occupied when its value is ``>= occupied`` (default
        :data:`DEFAULT_OCCUPIED` = 65). Refused for a boolean grid.
    free : float, optional
        Numeric grids: a cell is free when ``0 <= value <= free``; values between ``free`` and
        ``occupied`` are unknown. Default: every value ``0 <= value < occupied`` is free.

    Raises
    ------
    ValueError
        Not a 2-D grid, an empty one, non-numeric values, ``free >= occupied``, thresholds on
        a boolean grid, or (thresholds not given) a numeric grid whose values all lie in
        ``[0, 1]`` with some above 0: a 0..1 scale read as percent would be all free, so the
        scale must be said (``occupied=0.65``, or a boolean grid).
    """
    try:
        g = np.asarray(grid)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"grid must be a 2-D array, got {type(grid).__name__}") from exc
    if g.ndim != 2:
        raise ValueError(f"grid must be a 2-D array (rows, columns), got shape {g.shape}")
    if g.size == 0:
        raise ValueError(f"grid has no cell (shape {g.shape})")
    if g.dtype == bool:
        if occupied is not None or free is not None:
            raise ValueError(
                "occupied= and free= apply to numeric grids; a boolean grid is True where occupied"
            )
        return g.astype(np.int8)
    if not (np.issubdtype(g.dtype, np.integer) or np.issubdtype(g.dtype, np.floating)):
        raise ValueError(f"grid must hold booleans or numbers, got dtype {g.dtype}")
    known = ~np.isnan(g) & (g >= 0) if g.dtype.kind == "f" else g >= 0
    if occupied is None and free is None:
        values = g[known]
        if values.size and float(values.max()) <= 1.0 and float(values.max()) > 0.0:
            raise ValueError(
                "grid values lie in [0, 1]: give the scale, occupied=0.65 (and free=0.196) for "
                "probabilities, or a boolean grid (True: occupied); percent (0..100) is the default"
            )
    hi = DEFAULT_OCCUPIED if occupied is None else _threshold(occupied, "occupied")
    lo = None if free is None else _threshold(free, "free")
    if lo is not None and not lo < hi:
        raise ValueError(f"free={lo:g} must be below occupied={hi:g}")
    out = np.full(g.shape, UNKNOWN, dtype=np.int8)
    with np.errstate(invalid="ignore"):
        out[known & (g < hi if lo is None else g <= lo)] = FREE
        out[known & (g >= hi)] = OCCUPIED
    return out


def _threshold(value, name: str) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a number, got {value!r}") from exc
    if not math.isfinite(x) or x < 0.0:
        raise ValueError(f"{name} must be a finite number >= 0, got {value!r}")
    return x


def blocked_cells(classes: np.ndarray, unknown_is_occupied: bool = True) -> np.ndarray:
    """Blocked cells (bool): occupied ones, and unknown ones if ``unknown_is_occupied``."""
    if unknown_is_occupied:
        return classes != FREE
    return classes == OCCUPIED


# -- the exact partition ------------------------------------------------------------------
def rectangles(blocked: np.ndarray) -> np.ndarray:
    """The blocked cells as disjoint rectangles: ``(n, 4)`` int64 rows ``(r0, c0, r1, c1)``.

    Cells ``r0 <= r < r1``, ``c0 <= c < c1``. The runs of blocked cells of each row are
    merged with identical runs (same first and last column) of the next rows: a wall
    along a row or a column is one rectangle. Vectorised; the union is exactly the
    blocked cells.
    """
    b = np.asarray(blocked, dtype=bool)
    h, w = b.shape
    pad = np.zeros((h, w + 2), dtype=np.int8)
    pad[:, 1:-1] = b
    step = np.diff(pad, axis=1)  # +1 where a run starts, -1 one past its end
    rs, cs = np.nonzero(step == 1)
    _, ce = np.nonzero(step == -1)  # row-major: paired with the starts
    if not rs.size:
        return np.zeros((0, 4), dtype=np.int64)
    key = cs.astype(np.int64) * (w + 1) + ce
    order = np.lexsort((rs, key))  # by span, then row
    k, r = key[order], rs[order]
    new = np.ones(len(k), dtype=bool)
    new[1:] = (k[1:] != k[:-1]) | (r[1:] != r[:-1] + 1)
    first = np.flatnonzero(new)
    last = np.append(first[1:], len(k)) - 1
    a, z = order[first], order[last]
    return np.column_stack((rs[a], cs[a], rs[z] + 1, ce[a])).astype(np.int64)


def _box(r0: int, c0: int, r1: int, c1: int) -> np.ndarray:
    return np.array([[c0, r0], [c1, r0], [c1, r1], [c0, r1]], dtype=np.int64)


# -- the cover with a tolerance ------------------------------------------------------------
def cover_cells(blocked: np.ndarray, k: int) -> list[np.ndarray]:
    """Convex pieces covering every blocked cell, touching free cells only within ``k`` of one.

    Parameters
    ----------
    blocked : ndarray of bool, shape (rows, columns)
        Row 0 the bottom row (lowest y).
    k : int
        Tolerance in cells (Chebyshev distance between cell centres), ``>= 0``. 0: the
        exact partition into rectangles (:func:`rectangles`).

    Returns
    -------
    list of ndarray (m, 2), int64
        Counter-clockwise strictly convex polygons, vertices ``(x, y) = (column, row)`` at
        cell corners. Deterministic. The method is in the module docstring.
    """
    from scipy import ndimage

    b = np.ascontiguousarray(blocked, dtype=bool)
    k = int(k)
    if k < 0:
        raise ValueError(f"k must be >= 0 cells, got {k}")
    if k == 0:
        return [_box(*row) for row in rectangles(b).tolist()]
    h, w = b.shape
    near = ndimage.maximum_filter(b, size=2 * k + 1, mode="constant", cval=False)
    far = ~near
    P = np.zeros((h, w + 1), dtype=np.int32)  # P[r, c]: far cells of row r left of column c
    np.cumsum(far, axis=1, out=P[:, 1:])
    F = np.zeros((h + 1, w + 1), dtype=np.int32)  # F[r, c]: far cells below row r, left of c
    np.cumsum(P, axis=0, out=F[1:])
    labels, n = ndimage.label(b, structure=np.ones((3, 3), dtype=bool))
    slices = ndimage.find_objects(labels)
    boxes = np.array([(s[0].start, s[1].start, s[0].stop, s[1].stop) for s in slices], dtype=np.int64)
    boxes = boxes.reshape(-1, 4)
    r0, c0, r1, c1 = boxes.T
    far_in_box = F[r1, c1] - F[r0, c1] - F[r1, c0] + F[r0, c0]
    out: list[np.ndarray] = []
    for i in range(n):
        if far_in_box[i] == 0:
            out.append(_box(*boxes[i].tolist()))
        else:
            _cover_region(labels[slices[i]] == i + 1, int(r0[i]), int(c0[i]), P, F, out)
    return out


def _cover_region(S: np.ndarray, r0: int, c0: int, P: np.ndarray, F: np.ndarray, out: list) -> None:
    """Cover the True cells of ``S`` (its cell (0, 0) is the grid's ``(r0, c0)``); step 2 of the method."""
    stack = [(S, r0, c0)]
    while stack:
        S, r0, c0 = stack.pop()
        rows = np.flatnonzero(S.any(axis=1))
        if not rows.size:
            continue
        cols = np.flatnonzero(S.any(axis=0))
        ra, rb, ca, cb = int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1
        S = S[ra:rb, ca:cb]
        r0, c0 = r0 + ra, c0 + ca
        h, w = S.shape
        r1, c1 = r0 + h, c0 + w
        if F[r1, c1] - F[r0, c1] - F[r1, c0] + F[r0, c0] == 0:
            out.append(_box(r0, c0, r1, c1))
            continue
        if h > 1 and w > 1:
            hull = _cells_hull(S)
            lo, hi = _band_columns(hull, h)
            rr = np.arange(r0, r1)
            if not np.any(P[rr, c0 + hi] - P[rr, c0 + lo]):
                out.append(hull + np.array([c0, r0], dtype=np.int64))
                continue
        # rows differing from the row below each end or start a rectangle: too many, no partition
        if (
            h * w <= FEW_RECTANGLES_AREA
            and np.count_nonzero(np.any(S[1:] != S[:-1], axis=1)) < 2 * FEW_RECTANGLES
        ):
            exact = rectangles(S)
            if len(exact) <= FEW_RECTANGLES:  # an L, a U, a step: its exact rectangles, no loss
                out.extend(_box(r0 + a, c0 + b, r0 + c, c0 + d) for a, b, c, d in exact.tolist())
                continue
        if h >= w:
            m = h // 2
            stack += [(S[m:], r0 + m, c0), (S[:m], r0, c0)]
        else:
            m = w // 2
            stack += [(S[:, m:], r0, c0 + m), (S[:, :m], r0, c0)]


def _cells_hull(S: np.ndarray) -> np.ndarray:
    """Convex hull (counter-clockwise, int64 corners, strictly convex) of the True cells of ``S``.

    At each integer height ``y`` the cells of rows ``y - 1`` and ``y`` reach from ``xl(y)``
    (the least left corner) to ``xr(y)`` (the greatest right corner); the hull is the convex
    chain of the ``(xr(y), y)`` going up followed by that of the ``(xl(y), y)`` coming down
    (Andrew's monotone chain, exact in integers). A point no farther out than one below and
    one above it is no vertex and is dropped first (prefix and suffix maxima, :func:`_extreme`).
    """
    w = S.shape[1]
    rr = np.flatnonzero(S.any(axis=1))
    left = S.argmax(axis=1)[rr]
    right = w - S[:, ::-1].argmax(axis=1)[rr]
    ys = np.concatenate((rr, rr + 1))
    order = np.argsort(ys, kind="stable")
    ys = ys[order]
    heights, first = np.unique(ys, return_index=True)
    xl = np.minimum.reduceat(np.concatenate((left, left))[order], first)
    xr = np.maximum.reduceat(np.concatenate((right, right))[order], first)
    up = _monotone_chain(xr, heights, _extreme(xr))
    down = _monotone_chain(xl[::-1], heights[::-1], _extreme(-xl[::-1]))
    return _strict_ccw(np.array(up + down, dtype=np.int64))


def _extreme(x: np.ndarray) -> np.ndarray:
    """Points that may be hull vertices of a side pushed towards +x: the two ends, and those
    strictly beyond every point before them or every point after them (another lies on or
    inside the segment between a point at least as far out before it and one after it)."""
    n = len(x)
    keep = np.ones(n, dtype=bool)
    if n > 2:
        before = np.maximum.accumulate(x)[:-2]  # before[i]: the max of x[:i + 1]
        after = np.maximum.accumulate(x[::-1])[::-1][2:]  # after[i]: the max of x[i + 2:]
        keep[1:-1] = (x[1:-1] > before) | (x[1:-1] > after)
    return keep


def _monotone_chain(x: np.ndarray, y: np.ndarray, keep: np.ndarray) -> list:
    """The counter-clockwise convex chain through the kept points ``(x, y)`` in their order."""
    out: list = []
    for px, py in zip(x[keep].tolist(), y[keep].tolist(), strict=True):
        while len(out) >= 2:
            (ax, ay), (bx, by) = out[-2], out[-1]
            if (bx - ax) * (py - by) - (by - ay) * (px - bx) > 0:  # a left turn at b: keep b
                break
            out.pop()
        out.append((px, py))
    return out


def _strict_ccw(v: np.ndarray) -> np.ndarray:
    """``v`` counter-clockwise without collinear vertices (exact: integer coordinates)."""
    nxt = np.concatenate((v[1:], v[:1]))
    if int(np.sum(v[:, 0] * nxt[:, 1] - nxt[:, 0] * v[:, 1])) < 0:
        v = v[::-1]
        nxt = np.concatenate((v[1:], v[:1]))
    e = nxt - v  # edge out of vertex i
    p = np.concatenate((e[-1:], e[:-1]))  # edge into vertex i
    return np.ascontiguousarray(v[p[:, 0] * e[:, 1] - p[:, 1] * e[:, 0] != 0])


def _band_columns(hull: np.ndarray, h: int) -> tuple[np.ndarray, np.ndarray]:
    """Columns ``[lo[r], hi[r])`` of the cells of row ``r`` that the hull touches, for ``0 <= r < h``.

    ``hull`` counter-clockwise with integer vertices spanning rows ``0 .. h`` exactly. The
    hull meets row ``r``'s band ``r <= y <= r + 1`` over ``x`` between the least of its
    left edges at ``y = r`` and ``y = r + 1`` and the greatest of its right edges there (a
    convex set's extent over a band is reached at the band's lines when no vertex lies
    strictly inside: the vertices are integers). Exact: floors and ceilings of rationals.
    """
    x, y = hull[:, 0], hull[:, 1]
    n = len(hull)
    ys = np.arange(h + 1, dtype=np.int64)
    bottom, top = y.min(), y.max()
    i_br = int(np.flatnonzero(y == bottom)[np.argmax(x[y == bottom])])  # bottom right
    i_tr = int(np.flatnonzero(y == top)[np.argmax(x[y == top])])  # top right
    i_tl = int(np.flatnonzero(y == top)[np.argmin(x[y == top])])  # top left
    i_bl = int(np.flatnonzero(y == bottom)[np.argmin(x[y == bottom])])  # bottom left
    right = [(i_br + j) % n for j in range((i_tr - i_br) % n + 1)]  # y strictly increasing
    left = [(i_tl + j) % n for j in range((i_bl - i_tl) % n + 1)][::-1]  # reversed: increasing
    xr = _chain_at(ys, y[right], x[right], ceil=True)
    xl = _chain_at(ys, y[left], x[left], ceil=False)
    return np.minimum(xl[:-1], xl[1:]), np.maximum(xr[:-1], xr[1:])


def _chain_at(ys: np.ndarray, cy: np.ndarray, cx: np.ndarray, ceil: bool) -> np.ndarray:
    """Ceiling (or floor) of the x of the chain ``(cx, cy)`` (``cy`` increasing) at the integers ``ys``."""
    if len(cy) == 1:  # a single vertex: cannot happen for a hull spanning >= 1 row; kept total
        return np.full(len(ys), cx[0], dtype=np.int64)
    j = np.clip(np.searchsorted(cy, ys, side="right") - 1, 0, len(cy) - 2)
    y0, y1, x0, x1 = cy[j], cy[j + 1], cx[j], cx[j + 1]
    den = y1 - y0
    num = x0 * den + (ys - y0) * (x1 - x0)  # x * den
    return -((-num) // den) if ceil else num // den


# -- measuring ---------------------------------------------------------------------------
def touched_cells(pieces, shape: tuple[int, int]) -> np.ndarray:
    """Cells (bool, ``shape``, row 0 the bottom row) whose open square meets some piece.

    ``pieces`` as from :func:`cover_cells` (integer corners, counter-clockwise, strictly
    convex, inside the grid). The measure of the free space a cover loses: the free
    cells it touches.
    """
    out = np.zeros(shape, dtype=bool)
    for p in pieces:
        p = np.asarray(p, dtype=np.int64)
        r0, r1 = int(p[:, 1].min()), int(p[:, 1].max())
        lo, hi = _band_columns(p - np.array([0, r0]), r1 - r0)
        for r, a, z in zip(range(r0, r1), lo.tolist(), hi.tolist(), strict=True):
            out[r, a:z] = True
    return out
