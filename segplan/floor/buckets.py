"""Boxes filed by the cells of a uniform grid: which boxes may meet a region (beyond the paper).

A floor of thousands of obstacles is asked about small regions: the obstacles near one
union, those that may hold a sample point of a link. :class:`BoxGrid` files every box
``(xmin, ymin, xmax, ymax)`` under each square cell of a uniform grid that its extent
meets, once, and answers a question by the cells the region meets. Plain numpy (the
planner never builds shapely geometry).

Conservative by construction
----------------------------
The cell of a coordinate ``v`` along an axis is ``k(v) = floor(clip((v - origin) / size,
0, n - 1))``; each step (subtracting a constant, dividing by a positive constant,
clipping, ``floor``) is monotone in IEEE arithmetic, so ``k`` is. A box ``[a, b]`` is filed
under the cells ``k(a) .. k(b)`` and a query ``[p, q]`` reads the cells ``k(p) .. k(q)``;
if the intervals meet (``a <= q`` and ``p <= b``), then ``k(a) <= k(q)`` and ``k(p) <=
k(b)``: the ranges of cells meet, in both axes. So :meth:`BoxGrid.query` returns every box
meeting the query box (closed boxes, no tolerance needed), and :meth:`BoxGrid.pairs` pairs
each point with every box holding it, plus some boxes that do not: the caller's own exact
test then decides, and decides as it would over all the boxes.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["CELLS_PER_BOX", "MAX_CELLS", "BoxGrid"]

#: Cells of the grid per box filed: the cell's side is ``sqrt(area / (CELLS_PER_BOX * n))``
#: for ``n`` boxes over the area they span, and no smaller than the boxes' median side nor
#: than the extent's longer side over ``CELLS_PER_BOX * n`` (so about that many cells).
#: The grid changes no decision of its callers, only their speed. 1: measured on 2026-12-03
#: with ``benchmarks/stress_floor.py --cells-per-box 0.25 0.5 1 2 4 --floors 0 1`` (the 1 km
#: stress floors of 5000 obstacles), three passes, the last two in opposite orders, on a
#: shared 2-core machine (CPU share of the plans 0.3-1.0): the default plan's CPU time was
#: 2.3-3.7 s for every value, no trend above that noise, and every value gave the same
#: plans, bit for bit; 1 keeps about one cell per box.
CELLS_PER_BOX = 1.0
#: Most cells of a grid (a given ``size`` must not make more; the default makes about one per box).
MAX_CELLS = 10**7


class BoxGrid:
    """Boxes filed under the square cells of a uniform grid (module docstring).

    Parameters
    ----------
    boxes : array_like, shape (n, 4)
        ``(xmin, ymin, xmax, ymax)`` per box, finite, ``xmin <= xmax`` and ``ymin <= ymax``.
    size : float, optional
        Side of a cell; default from :data:`CELLS_PER_BOX`.

    Attributes
    ----------
    origin : (float, float)
        Lower-left corner of the grid (that of the boxes' extent).
    size : float
        Side of a cell.
    shape : (int, int)
        Cells along x and along y (boxes and points beyond the grid fall in its edge cells).
    """

    def __init__(self, boxes, size: float | None = None):
        b = np.asarray(boxes, dtype=float).reshape(-1, 4)
        if not np.all(np.isfinite(b)) or np.any(b[:, 0] > b[:, 2]) or np.any(b[:, 1] > b[:, 3]):
            raise ValueError("boxes must be finite (xmin, ymin, xmax, ymax) rows with min <= max")
        self.n = len(b)
        if self.n:
            lo, hi = b[:, :2].min(axis=0), b[:, 2:].max(axis=0)
        else:
            lo = hi = np.zeros(2)
        span = hi - lo
        if size is None:
            side = float(np.median(np.maximum(b[:, 2] - b[:, 0], b[:, 3] - b[:, 1]))) if self.n else 0.0
            area = float(max(span[0], side) * max(span[1], side))
            m = CELLS_PER_BOX * max(self.n, 1)
            # about m cells over the area; and at most m + 1 along a side (boxes along a line)
            size = max(math.sqrt(area / m), side, float(span.max()) / m)
            if size <= 0.0:  # every box a point, all at one place: one cell holds them
                size = 1.0
        elif isinstance(size, bool) or not (
            isinstance(size, int | float) and math.isfinite(size) and size > 0
        ):
            raise ValueError(f"size must be a positive number, got {size!r}")
        self.origin = (float(lo[0]), float(lo[1]))
        self.size = float(size)
        nx, ny = (int(v) + 1 for v in span / self.size)
        if nx * ny > MAX_CELLS:
            raise ValueError(f"size {size!r} makes {nx} x {ny} cells, more than {MAX_CELLS:.0e}")
        self.shape = (nx, ny)
        i0, i1 = self._cells(b[:, 0], 0), self._cells(b[:, 2], 0)
        j0, j1 = self._cells(b[:, 1], 1), self._cells(b[:, 3], 1)
        # one (cell, box) row per cell a box meets, sorted by cell (then by box: stable)
        wj = j1 - j0 + 1
        count = (i1 - i0 + 1) * wj
        box, k = _ranges(count)
        cell = (i0[box] + k // wj[box]) * ny + j0[box] + k % wj[box]
        order = np.argsort(cell, kind="stable")
        #: Box ids, cell by cell (those of cell ``c``: ``ids[start[c]:start[c + 1]]``).
        self.ids = box[order]
        self.ids.flags.writeable = False
        self.start = np.concatenate(([0], np.cumsum(np.bincount(cell, minlength=nx * ny))))

    def _cells(self, v, axis: int) -> np.ndarray:
        """Cell indices of coordinates ``v`` along ``axis`` (0: x, 1: y), clipped to the grid."""
        t = (np.asarray(v, dtype=float) - self.origin[axis]) / self.size
        t = np.nan_to_num(t, nan=0.0)  # a NaN point meets no box in any exact test: any cell does
        return np.floor(np.clip(t, 0.0, self.shape[axis] - 1)).astype(np.int64)

    def _cell(self, v: float, axis: int) -> int:
        """:meth:`_cells` of one coordinate, in Python floats (the same IEEE operations)."""
        t = (float(v) - self.origin[axis]) / self.size
        return math.floor(min(max(t, 0.0), self.shape[axis] - 1)) if t == t else 0

    def query(self, x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
        """Ids (ascending, unique) of the boxes filed under the cells that the closed box
        ``[x0, x1] x [y0, y1]`` meets: every box meeting it, and perhaps others."""
        i0, i1, j0, j1 = self._cell(x0, 0), self._cell(x1, 0), self._cell(y0, 1), self._cell(y1, 1)
        ny, start = self.shape[1], self.start
        if i0 == i1 and j0 == j1:  # one cell: its ids are unique and ascending already
            return self.ids[start[i0 * ny + j0] : start[i0 * ny + j0 + 1]]
        parts = [self.ids[start[i * ny + j0] : start[i * ny + j1 + 1]] for i in range(i0, i1 + 1)]
        return np.unique(np.concatenate(parts)) if parts else np.zeros(0, dtype=np.int64)

    def pairs(self, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(point, box)`` index pairs: each point of ``(x, y)`` (flat arrays) with every box
        filed under its cell, so with every box that holds it (and perhaps others)."""
        cell = self._cells(x, 0) * self.shape[1] + self._cells(y, 1)
        first = self.start[cell]
        point, k = _ranges(self.start[cell + 1] - first)
        return point, self.ids[first[point] + k]


def _ranges(count: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For counts ``c_r``: the row ``r`` repeated ``c_r`` times and ``0 .. c_r - 1`` beside it."""
    row = np.repeat(np.arange(len(count)), count)
    return row, np.arange(len(row)) - (np.cumsum(count) - count)[row]
