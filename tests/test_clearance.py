"""The clearance grid's bounds against an independent oracle: shapely's exact distances.

:class:`segplan.planning.lattice.clearance.ClearanceGrid` promises, for every point of a cell that is not
occupied, a distance to the enlarged obstacles and walls of at least ``lower`` of its cell,
and for a blocked cell, that the whole square lies inside an obstacle or beyond a wall.
"""

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from segplan.floor.geometry import ConvexPolygon
from segplan.floor.random_floors import random_convex_polygon
from segplan.planning.lattice.clearance import ClearanceGrid

ROOM = (0.0, 0.0, 6.0, 4.0)
CELL = 0.0625


def _polygon(seed, cx, cy, r):
    """:func:`segplan.floor.random_floors.random_convex_polygon` (3-8 vertices, any rotation and aspect)."""
    return ConvexPolygon(random_convex_polygon(np.random.default_rng(seed), (cx, cy), r, 8))


polygons = st.lists(
    st.builds(
        _polygon, st.integers(0, 2**16), st.floats(0.5, 5.5), st.floats(0.5, 3.5), st.floats(0.15, 1.0)
    ),
    min_size=1,
    max_size=4,
)


@settings(max_examples=30)
@given(
    polys=polygons,
    frame=st.tuples(st.floats(1.0, 5.0), st.floats(1.0, 3.0), st.floats(-math.pi, math.pi)),
    walls=st.booleans(),
    seed=st.integers(0, 2**16),
)
def test_the_grid_bounds_hold(polys, frame, walls, seed):
    bounds = ROOM if walls else None
    grid = ClearanceGrid(polys, frame, bounds, CELL, 4, (3.0, 2.0, 0.0), 1.0)
    h = CELL * math.sqrt(0.5)  # half a cell's diagonal
    rng = np.random.default_rng(seed)
    # random lattice-frame points over the grid
    x0, y0 = grid.i0 * CELL, grid.j0 * CELL
    pts = np.column_stack(
        (rng.uniform(x0, x0 + grid.nx * CELL, 3000), rng.uniform(y0, y0 + grid.ny * CELL, 3000))
    )
    i, j, inside = grid.cells(pts)
    world = pts @ grid.rot.T + frame[:2]
    obstacles = shapely.union_all([shapely.Polygon(p.vertices) for p in polys])
    sp = shapely.points(world)
    d = shapely.distance(obstacles, sp)
    if walls:
        room = shapely.box(*ROOM)
        beyond = ~shapely.contains(room, sp)
        d = np.minimum(d, np.where(beyond, 0.0, shapely.distance(room.exterior, sp)))
    else:
        beyond = np.zeros(len(pts), dtype=bool)
    within = shapely.intersects(obstacles, sp) | beyond
    lower, blocked = grid.lower[i, j], grid.blocked[i, j]
    free = inside & (lower >= 0.0)
    # every point of a cell is at least `lower` from the obstacles and walls
    assert np.all(d[free] >= lower[free] - 1e-9)
    # a blocked cell lies inside an obstacle or beyond a wall
    assert np.all(within[inside & blocked])
    # and the bound is not vacuous: near obstacles within 8 h of the true distance (two h
    # by construction, the rest the distance transform's metric; 5.6 h seen at most on
    # usual polygons, 6.4 h near the sharp vertices of a thin triangle that hypothesis found:
    # polys=[_polygon(65536, 2.0, 2.0, 0.75)], frame=(1.0, 1.0, 0.5), no walls)
    near = free & (d < 0.5)
    assert near.any()
    assert np.all(lower[near] >= d[near] - 8.0 * h)


@pytest.mark.parametrize("walls", [False, True])
def test_the_lattice_reads_the_grid_by_flat_offsets(walls):
    """``lower_blocked_flat`` is ``lower`` with ``-inf`` exactly in the blocked cells (one
    gather answers both of the lattice's questions), and a lattice point's cell (``base``)
    plus the ``offsets`` of points relative to it are the points' cells (``cells``)."""
    rng = np.random.default_rng(3)
    polys = [_polygon(int(s), *rng.uniform((0.5, 0.5), (5.5, 3.5)), 0.8) for s in rng.integers(0, 2**16, 4)]
    grid = ClearanceGrid(polys, (3.0, 2.0, 0.4), ROOM if walls else None, CELL, 4, (3.0, 2.0, 0.0), 1.0)
    lb, blocked = grid.lower_blocked_flat, grid.blocked_flat
    assert blocked.any() and (~blocked).any()
    assert np.array_equal(np.isneginf(lb), blocked) and np.all(np.isfinite(lb[~blocked]))
    assert np.array_equal(lb[~blocked], grid.lower_flat[~blocked])
    a, b = grid.i0 + grid.nx // 2, grid.j0 + grid.ny // 2
    rel = rng.uniform(-grid.pad * CELL, grid.pad * CELL, (200, 2))
    i, j, inside = grid.cells(rel + (a * CELL, b * CELL))
    assert inside.all()
    assert np.array_equal(grid.base(a, b) + grid.offsets(rel), i * grid.ny + j)


def test_obstacles_near_a_box_are_those_whose_bounding_box_meets_it():
    """``obstacles_near`` against shapely's intersection of boxes, with a few obstacles (the
    scalar path) and with many (the array path, above 32)."""
    from segplan.planning.lattice.clearance import obstacles_near
    from segplan.planning.validity import Workspace

    rng = np.random.default_rng(7)
    for n in (5, 60):
        polys = [_polygon(int(s), *rng.uniform(0.0, 20.0, 2), 0.5) for s in rng.integers(0, 2**16, n)]
        ws = Workspace([p.vertices for p in polys], 1.0, None, 1.0)
        boxes = [shapely.box(*shapely.Polygon(p.vertices).bounds) for p in polys]
        hits = 0
        for _ in range(100):
            pts = rng.uniform(0.0, 20.0, (int(rng.integers(1, 6)), 2))
            margin = float(rng.uniform(0.0, 1.0))
            x0, y0 = pts.min(axis=0) - margin
            x1, y1 = pts.max(axis=0) + margin
            truth = [k for k, b in enumerate(boxes) if b.intersects(shapely.box(x0, y0, x1, y1))]
            assert obstacles_near(ws, pts, margin) == truth
            hits += len(truth)
        assert hits > 50
