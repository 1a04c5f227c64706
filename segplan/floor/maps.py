"""The floor: obstacles as given and as convex pieces, and the walls; from polygons or a map.

A :class:`Floor` is what a robot's world is before a robot is put in it: the obstacles
(simple polygons as given, their convex pieces for the paper's collision test) and the
bounds. It goes wherever obstacles go: :func:`segplan.make_scenario` and
:func:`segplan.plan` take one in place of a list of polygons (the floor's bounds are used
when none are given).

Two ways to make one:

* :meth:`Floor.from_polygons`: simple polygons (vertex lists, shapely ``Polygon`` /
  ``MultiPolygon``), each split into convex pieces by :func:`segplan.floor.decompose.decompose`;
  what :func:`segplan.make_scenario` does with its ``obstacles``;
* :meth:`Floor.from_occupancy` (beyond the paper, issue 27): an occupancy grid in metres,
  its blocked cells covered by convex pieces (:mod:`segplan.floor.occupancy`: every blocked
  cell covered, free cells touched only within ``tolerance`` of a blocked one). ROS
  ``map_server`` files: :func:`segplan.load_ros_map` (:mod:`segplan.floor.ros_map`).

Map coordinates follow ROS ``map_server``: the grid's bottom-left cell has its lower-left
corner at ``origin``; x grows along a row, y upwards; an image's row 0 is its *top* row
(``first_row="top"``, the default; ``"bottom"`` for ``nav_msgs/OccupancyGrid`` data, whose
row 0 is at the origin). The bounds are the grid's extent: outside the map is unknown, so
it is a wall.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .decompose import as_outlines, decompose
from .geometry import Bounds, check_bounds, finite_number
from .occupancy import blocked_cells, classify, cover_cells, touched_cells

__all__ = ["DEFAULT_TOLERANCE_CELLS", "Floor", "WORLD_LIMIT"]

#: Coordinates and lengths of a floor or scenario must not exceed this magnitude (the
#: world's scale, metres in files).
WORLD_LIMIT = 1e6

#: Default ``tolerance`` of :meth:`Floor.from_occupancy`, in cells: a piece may touch a
#: free cell within two cells of a blocked one. On the 2000 x 3000-cell synthetic office map
#: of ``benchmarks/maps.py`` (``benchmarks/results/maps.json``): 1447 pieces touching 1.02 %
#: of the free cells, against 21489 exact rectangles (0 cells) and 1926 pieces, 0.94 %
#: (1 cell); 3 cells saves 8 % more pieces for 1.07 %.
DEFAULT_TOLERANCE_CELLS = 2


@dataclass(frozen=True, eq=False)
class Floor:
    """Obstacles, as given and as convex pieces, and walls (build with a ``from_`` method).

    Attributes
    ----------
    obstacles : tuple of ndarray (k, 2)
        Convex pieces, counter-clockwise, strictly convex, read-only: what the collision test
        sees (as :attr:`segplan.Scenario.obstacles`).
    outlines : tuple of ndarray (k, 2)
        The obstacles as given (simple polygons, counter-clockwise, read-only); for a map, the
        pieces themselves (a map has no polygons of its own).
    outline_of : tuple of int
        ``outline_of[i]``: the index in ``outlines`` of the piece ``obstacles[i]``.
    bounds : (xmin, ymin, xmax, ymax) or None
        The walls; a map's extent.
    labels : tuple of str
        How error messages name each piece (``"obstacles[2] (its convex piece 1)"``); empty
        for a map (see :meth:`describe`).
    source : str
        Where the floor came from (a file name, ``"<python>"``, ``"<grid>"``).
    cells : ndarray of int8 (rows, columns) or None
        A map's cells, row 0 the top row (image order): 1 occupied, 0 free, -1 unknown.
    resolution : float or None
        A map's cell size (m).
    origin : (x, y) or None
        A map's lower-left corner (m).
    unknown_is_occupied : bool
        Whether a map's unknown cells are obstacles.
    tolerance : float or None
        A map's tolerance (m): how far beyond its blocked cells a piece may reach.
    """

    obstacles: tuple[np.ndarray, ...]
    outlines: tuple[np.ndarray, ...]
    outline_of: tuple[int, ...]
    bounds: Bounds | None = None
    labels: tuple[str, ...] = ()
    source: str = "<python>"
    cells: np.ndarray | None = None
    resolution: float | None = None
    origin: tuple[float, float] | None = None
    unknown_is_occupied: bool = True
    tolerance: float | None = None

    def __repr__(self) -> str:
        where = "" if self.cells is None else f", map {self.cells.shape[1]} x {self.cells.shape[0]} cells"
        n, m = len(self.obstacles), len(self.outlines)
        return (
            f"Floor({n} convex piece{'' if n == 1 else 's'} of {m} obstacle{'' if m == 1 else 's'}, "
            f"bounds={None if self.bounds is None else list(self.bounds)}{where}, source={self.source!r})"
        )

    # -- from polygons -------------------------------------------------------------------
    @classmethod
    def from_polygons(cls, obstacles: Sequence = (), bounds=None, *, source: str = "<python>") -> Floor:
        """A floor of simple polygons, each split into convex pieces.

        Parameters
        ----------
        obstacles : sequence
            Simple polygons: ``(k, 2)`` vertex lists (either orientation; a closing copy of
            the first vertex and collinear vertices are dropped) or shapely ``Polygon`` /
            ``MultiPolygon`` objects without holes. A non-convex one is split by
            :func:`segplan.floor.decompose.decompose`.
        bounds : (xmin, ymin, xmax, ymax), optional
            The walls.
        source : str
            Prefix of error messages (a file name).

        Raises
        ------
        ValueError
            Naming ``source``, the obstacle and the vertex: a malformed polygon (see
            :func:`segplan.floor.geometry.check_convex_polygon` and
            :func:`segplan.floor.decompose.decompose`), coordinates beyond
            :data:`WORLD_LIMIT`, bad bounds.
        """
        if bounds is not None:
            bounds = check_bounds(bounds, f"{source}: bounds")
        try:
            items = list(obstacles)
        except TypeError:
            raise ValueError(
                f"{source}: obstacles must be a sequence of polygons, got {type(obstacles).__name__}"
            ) from None
        polys, outlines, outline_of, labels = [], [], [], []
        for i, item in enumerate(items):
            where = f"{source}: obstacles[{i}]"
            given = as_outlines(item, where)
            for j, p in enumerate(given):
                at = where if len(given) == 1 else f"{where} part {j}"
                outline, pieces = decompose(p, where=at)
                if np.abs(outline).max() > WORLD_LIMIT:  # the pieces' vertices are the outline's
                    k = int(np.flatnonzero(np.abs(np.asarray(p, dtype=float)).max(axis=1) > WORLD_LIMIT)[0])
                    raise ValueError(f"{at} vertex {k}: coordinates exceed +-{WORLD_LIMIT:g}")
                for q in (outline, *pieces):  # a convex outline is its own piece, the same array
                    q.flags.writeable = False
                outline_of.extend([len(outlines)] * len(pieces))
                label = f"obstacles[{i}]" + ("" if len(given) == 1 else f" part {j}")
                one = len(pieces) == 1
                labels.extend(label if one else f"{label} (its convex piece {n})" for n in range(len(pieces)))
                outlines.append(outline)
                polys.extend(pieces)
        return cls(tuple(polys), tuple(outlines), tuple(outline_of), bounds, tuple(labels), source)

    # -- from an occupancy grid --------------------------------------------------------------
    @classmethod
    def from_occupancy(
        cls,
        grid,
        resolution: float,
        origin: Sequence[float] = (0.0, 0.0),
        *,
        occupied: float | None = None,
        free: float | None = None,
        unknown_is_occupied: bool = True,
        first_row: str = "top",
        tolerance: float | None = None,
        source: str = "<grid>",
    ) -> Floor:
        """A floor from an occupancy grid: its blocked cells covered by convex pieces.

        Parameters
        ----------
        grid : array_like, 2-D
            Booleans (True: occupied) or occupancy in percent as ``nav_msgs/OccupancyGrid``
            (0 free .. 100 occupied; negative or NaN unknown), see
            :func:`segplan.floor.occupancy.classify`.
        resolution : float
            Cell size (m, > 0).
        origin : (x, y) or (x, y, yaw)
            The lower-left corner of the bottom-left cell (m); a yaw must be 0 (a rotated map
            is refused: rotate the grid).
        occupied, free : float, optional
            Thresholds of a numeric grid (:func:`segplan.floor.occupancy.classify`; default:
            occupied at >= 65, free below it).
        unknown_is_occupied : bool
            Unknown cells are obstacles (default, conservative) or free space.
        first_row : {"top", "bottom"}
            Where the grid's row 0 lies: ``"top"`` for an image (the default), ``"bottom"``
            for ``nav_msgs/OccupancyGrid`` data reshaped to ``(height, width)``.
        tolerance : float, optional
            How far (m) a piece may reach beyond the blocked cells to make fewer, larger
            pieces: a piece touches a free cell only if that cell's centre is within
            ``tolerance`` of a blocked cell's centre in both x and y (Chebyshev distance,
            counted in whole cells). Default :data:`DEFAULT_TOLERANCE_CELLS` cells; 0: the
            exact cover (rectangles of blocked cells, no free cell touched).
        source : str
            Names the grid in error messages.

        Returns
        -------
        Floor
            ``obstacles``: the pieces in metres, each covering blocked cells only or cells
            within ``tolerance`` of them; **every blocked cell is covered**. ``bounds``: the
            grid's extent. ``cells``: the cell classes, row 0 the top row.

        Raises
        ------
        ValueError
            Naming ``source``: a malformed grid or threshold, a bad resolution, origin or
            tolerance, coordinates beyond :data:`WORLD_LIMIT`, or no free cell.
        """
        try:
            classes = classify(grid, occupied, free)
            res = finite_number(resolution, "resolution")
            if res <= 0.0:
                raise ValueError(f"resolution must be > 0 m, got {res}")
            ox, oy = _origin(origin)
            if first_row not in ("top", "bottom"):
                raise ValueError(f"first_row must be 'top' or 'bottom', got {first_row!r}")
            if tolerance is None:
                k = DEFAULT_TOLERANCE_CELLS
            else:
                k = int(math.floor(finite_number(tolerance, "tolerance", minimum=0.0) / res + 1e-9))
        except ValueError as exc:
            raise ValueError(f"{source}: {exc}") from None
        image = classes if first_row == "top" else classes[::-1]
        h, w = image.shape
        bounds = (ox, oy, ox + res * w, oy + res * h)
        if max(abs(v) for v in bounds) > WORLD_LIMIT:
            raise ValueError(f"{source}: the map's extent {list(bounds)} exceeds +-{WORLD_LIMIT:g}")
        blocked = blocked_cells(image[::-1], unknown_is_occupied)  # row 0 the bottom row
        if blocked.all():
            unknown = "occupied or unknown" if unknown_is_occupied else "occupied"
            raise ValueError(f"{source}: the map has no free cell (every cell is {unknown})")
        pieces = []
        for p in cover_cells(blocked, k):
            q = np.empty(p.shape, dtype=float)
            q[:, 0] = ox + res * p[:, 0]
            q[:, 1] = oy + res * p[:, 1]
            q.flags.writeable = False
            pieces.append(q)
        cells = np.ascontiguousarray(image)
        cells.flags.writeable = False
        n = len(pieces)
        return cls(
            tuple(pieces), tuple(pieces), tuple(range(n)), bounds, (), source, cells, res,
            (ox, oy), bool(unknown_is_occupied), k * res,
        )  # fmt: skip

    # -- questions ---------------------------------------------------------------------------
    def describe(self, i: int) -> str:
        """How error messages name the piece ``obstacles[i]``."""
        if self.labels:
            return self.labels[i]
        p = self.obstacles[i]
        (x0, y0), (x1, y1) = p.min(axis=0), p.max(axis=0)
        return (
            f"the blocked cells of {self.source} (convex piece {i} of {len(self.obstacles)}, "
            f"x {x0:g}..{x1:g} m, y {y0:g}..{y1:g} m)"
        )

    @property
    def blocked(self) -> np.ndarray | None:
        """A map's blocked cells (bool, row 0 the top row): occupied, and unknown if they count."""
        if self.cells is None:
            return None
        return blocked_cells(self.cells, self.unknown_is_occupied)

    def cell(self, x: float, y: float) -> tuple[int, int] | None:
        """``(row, column)`` of a map's cell holding the point ``(x, y)`` (row 0 the top row), or None."""
        if self.cells is None:
            return None
        ox, oy = self.origin
        h, w = self.cells.shape
        c = math.floor((x - ox) / self.resolution)
        r = h - 1 - math.floor((y - oy) / self.resolution)
        return (r, c) if 0 <= r < h and 0 <= c < w else None

    def free_space_loss(self) -> float:
        """Fraction of a map's free cells that its pieces touch (0 with ``tolerance=0``).

        The price of fewer pieces: the free cells whose open square meets a piece
        (:func:`segplan.floor.occupancy.touched_cells`), over the free cells; every one of
        them lies within ``tolerance`` of a blocked cell.
        """
        if self.cells is None:
            raise ValueError("free_space_loss: this floor is not a map")
        blocked = self.blocked[::-1]  # row 0 the bottom row
        free = ~blocked
        ox, oy = self.origin
        corners = [np.rint((p - (ox, oy)) / self.resolution).astype(np.int64) for p in self.obstacles]
        touched = touched_cells(corners, blocked.shape)
        return float(np.count_nonzero(touched & free)) / max(int(np.count_nonzero(free)), 1)


def _origin(origin) -> tuple[float, float]:
    """``(x, y)`` of an origin ``(x, y)`` or ``(x, y, yaw)`` with yaw 0."""
    try:
        values = [float(v) for v in origin]
    except (TypeError, ValueError) as exc:
        raise ValueError(f"origin must be (x, y) or (x, y, yaw) numbers, got {origin!r}") from exc
    if len(values) not in (2, 3) or not all(math.isfinite(v) for v in values):
        raise ValueError(f"origin must be (x, y) or (x, y, yaw), finite numbers, got {origin!r}")
    if len(values) == 3 and values[2] != 0.0:
        raise ValueError(
            f"origin yaw {values[2]:g} rad is not supported: the map would be rotated and its "
            "walls not parallel to the axes; rotate the image and set yaw to 0"
        )
    return values[0], values[1]
