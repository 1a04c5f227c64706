"""Maps in (issue 27): occupancy grids and ROS map_server maps as a segplan.Floor.

Independent oracles: shapely decides coverage cell by cell (every blocked cell's box lies in
the union of the convex pieces, within 1e-9 of a cell's area) and which free cells a piece
touches (positive area of intersection); the Chebyshev distance to the nearest blocked cell
is brute force; the map_server pixel rules are written out per pixel. Timing is measured by
``benchmarks/maps.py``, not here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from load_file import ROOT, load_file
from PIL import Image

import segplan
from segplan.cli import EXIT_BAD_INPUT, main
from segplan.floor.geometry import check_convex_polygon
from segplan.floor.occupancy import classify, cover_cells, rectangles, touched_cells

OCC, FREE, UNK = 100, 0, -1


# -- grids ---------------------------------------------------------------------------------
@st.composite
def grids(draw):
    """Occupancy grids (``nav_msgs`` values 100 / 0 / -1, row 0 the top row) of one of the kinds
    the issue lists: noise, unknown regions, thin one-cell walls, diagonal walls, fully free,
    fully occupied, or all of them at once."""
    rows, cols = draw(st.integers(1, 18)), draw(st.integers(1, 18))
    kind = draw(st.sampled_from(["noise", "unknown", "thin", "diagonal", "free", "occupied", "mixed"]))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    g = np.zeros((rows, cols), dtype=np.int8)
    if kind == "occupied":
        g[:] = OCC
    if kind in ("noise", "mixed"):
        g[rng.random((rows, cols)) < draw(st.floats(0.05, 0.6))] = OCC
    if kind in ("unknown", "mixed"):
        r0, c0 = rng.integers(0, rows), rng.integers(0, cols)
        g[r0 : r0 + rng.integers(1, rows + 1), c0 : c0 + rng.integers(1, cols + 1)] = UNK
        g[rng.random((rows, cols)) < 0.1] = UNK
    if kind in ("thin", "mixed"):
        for _ in range(rng.integers(1, 4)):
            if rng.random() < 0.5:
                g[rng.integers(0, rows), rng.integers(0, cols) :] = OCC
            else:
                g[rng.integers(0, rows) :, rng.integers(0, cols)] = OCC
    if kind in ("diagonal", "mixed"):
        for _ in range(rng.integers(1, 3)):
            r, c, dc = rng.integers(0, rows), rng.integers(0, cols), rng.choice([-1, 1])
            while 0 <= r < rows and 0 <= c < cols:
                g[r, c] = OCC
                r, c = r + 1, c + dc * rng.integers(1, 3)  # slopes 1 and 1/2
    return g


def cell_boxes(shape, resolution, origin):
    """shapely boxes of every cell, row 0 the top row, as an array of the grid's shape."""
    rows, cols = shape
    ox, oy = origin
    r, c = np.mgrid[0:rows, 0:cols]
    y0 = oy + resolution * (rows - 1 - r)
    x0 = ox + resolution * c
    return shapely.box(x0, y0, x0 + resolution, y0 + resolution)


def chebyshev_to_blocked(blocked: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Brute force: each of ``cells``' (a mask) Chebyshev distance, in cells, to the nearest blocked cell."""
    rr, cc = np.nonzero(blocked)
    r, c = np.nonzero(cells)
    if not rr.size:
        return np.full(r.size, np.inf)
    out = np.empty(r.size)
    for i in range(0, r.size, 256):  # in chunks: cells x blocked cells
        d = np.maximum(np.abs(r[i : i + 256, None] - rr), np.abs(c[i : i + 256, None] - cc))
        out[i : i + 256] = d.min(axis=1)
    return out


@settings(max_examples=150)
@given(
    grids(),
    st.integers(0, 3),
    st.booleans(),
    st.sampled_from([0.05, 0.1, 0.37, 1.0, 2.5]),
    st.tuples(st.floats(-60.0, 60.0), st.floats(-60.0, 60.0)),
)
def test_every_blocked_cell_is_covered_and_free_cells_only_near_blocked_ones(
    grid, k, unknown_occ, res, origin
):
    blocked = (grid == OCC) | ((grid == UNK) & unknown_occ)
    if blocked.all():
        with pytest.raises(ValueError, match="no free cell"):
            segplan.Floor.from_occupancy(
                grid, res, origin, unknown_is_occupied=unknown_occ, tolerance=k * res
            )
        return
    floor = segplan.Floor.from_occupancy(
        grid, res, origin, unknown_is_occupied=unknown_occ, tolerance=k * res
    )
    rows, cols = grid.shape
    ox, oy = origin
    assert floor.bounds == pytest.approx((ox, oy, ox + res * cols, oy + res * rows))
    np.testing.assert_array_equal(floor.blocked, blocked)
    for p in floor.obstacles:
        q = check_convex_polygon(p)  # strictly convex, counter-clockwise: the validator keeps it
        np.testing.assert_array_equal(q, p)
        assert not p.flags.writeable
        lo, hi = p.min(axis=0), p.max(axis=0)
        assert lo[0] >= ox - 1e-9 and lo[1] >= oy - 1e-9
        assert hi[0] <= ox + res * cols + 1e-9 and hi[1] <= oy + res * rows + 1e-9
    union = shapely.union_all([shapely.Polygon(p) for p in floor.obstacles])
    boxes = cell_boxes(grid.shape, res, origin)
    cell_area = res * res
    # every blocked cell's box is covered (cell by cell)
    uncovered = shapely.area(shapely.difference(boxes[blocked], union))
    assert np.all(uncovered <= 1e-9 * cell_area), f"uncovered blocked cells: {np.flatnonzero(uncovered)}"
    # a free cell is touched only within k cells (Chebyshev) of a blocked cell
    touched = shapely.area(shapely.intersection(boxes, union)) > 1e-9 * cell_area
    assert np.all(chebyshev_to_blocked(blocked, touched & ~blocked) <= k)
    if k == 0:
        assert not np.any(touched & ~blocked)  # the exact cover
    # the floor's own measure of the loss agrees with shapely's
    free = ~blocked
    assert floor.free_space_loss() == pytest.approx(np.count_nonzero(touched & free) / np.count_nonzero(free))


@settings(max_examples=100)
@given(grids(), st.integers(0, 3))
def test_cover_cells_and_touched_cells_against_shapely_in_cell_units(grid, k):
    """The cover in cell units (row 0 the bottom row): integer corners, coverage, the touched cells."""
    blocked = (grid != FREE)[::-1]
    pieces = cover_cells(blocked, k)
    union = shapely.union_all([shapely.Polygon(p) for p in pieces])
    rows, cols = blocked.shape
    r, c = np.mgrid[0:rows, 0:cols]
    boxes = shapely.box(c, r, c + 1, r + 1)
    assert np.all(shapely.area(shapely.difference(boxes[blocked], union)) <= 1e-9)
    want = np.array(
        [[any(shapely.Polygon(p).intersection(b).area > 1e-12 for p in pieces) for b in row] for row in boxes]
    )
    np.testing.assert_array_equal(touched_cells(pieces, blocked.shape), want.reshape(blocked.shape))
    for p in pieces:
        assert p.dtype == np.int64 and shapely.Polygon(p).exterior.is_ccw


@pytest.mark.parametrize("seed", [0, 1])
def test_the_benchmark_office_map_at_a_small_size_against_shapely(tmp_path, seed):
    """The benchmark's office map (ragged walls, slanted walls, furniture, specks, unknown
    pockets) at 120 x 180 cells, through the map file: coverage cell by cell, the loss bound."""
    bench = load_file(ROOT / "benchmarks" / "maps.py", "maps_benchmark")
    img = bench.office_map(120, 180, seed)
    floor = segplan.load_ros_map(bench.write_map(tmp_path, img))
    blocked = img != 254
    np.testing.assert_array_equal(floor.blocked, blocked)
    union = shapely.union_all([shapely.Polygon(p) for p in floor.obstacles])
    boxes = cell_boxes(img.shape, bench.RESOLUTION, bench.ORIGIN)
    cell_area = bench.RESOLUTION**2
    assert np.all(shapely.area(shapely.difference(boxes[blocked], union)) <= 1e-9 * cell_area)
    touched = shapely.area(shapely.intersection(boxes, union)) > 1e-9 * cell_area
    assert np.all(chebyshev_to_blocked(blocked, touched & ~blocked) <= 2)  # the default: two cells
    assert len(floor.obstacles) < len(rectangles(blocked)) / 3  # far fewer than the exact partition


def test_rectangles_are_an_exact_partition():
    rng = np.random.default_rng(3)
    b = rng.random((40, 50)) < 0.4
    R = rectangles(b)
    cover = np.zeros(b.shape, dtype=int)
    for r0, c0, r1, c1 in R:
        cover[r0:r1, c0:c1] += 1
    np.testing.assert_array_equal(cover, b.astype(int))  # every blocked cell exactly once
    walls = np.zeros((30, 30), dtype=bool)
    walls[5, 2:28] = walls[2:28, 20] = True
    assert len(rectangles(walls)) == 3  # a wall along a row or a column is one rectangle per run


def test_a_slanted_rasterised_obstacle_is_one_piece_with_little_loss():
    """A rasterised slanted rectangle: the tolerance makes it one piece (the hull of its cells)."""
    poly = shapely.Polygon([(4.551, 9.644), (7.149, 11.144), (6.449, 12.356), (3.851, 10.856)])  # fig. 5
    res = 0.05
    boxes = cell_boxes((300, 300), res, (0.0, 5.0))
    grid = np.where(shapely.area(shapely.intersection(boxes, poly)) > 0, OCC, FREE)
    exact = segplan.Floor.from_occupancy(grid, res, (0.0, 5.0), tolerance=0.0)
    simple = segplan.Floor.from_occupancy(grid, res, (0.0, 5.0))
    assert len(exact.obstacles) > 40 and len(simple.obstacles) == 1
    assert exact.free_space_loss() == 0.0
    assert simple.free_space_loss() < 0.01
    piece = shapely.Polygon(simple.obstacles[0])
    assert poly.difference(piece).area < 1e-12  # the polygon is inside its cover
    # the cells meeting the polygon lie within a cell's diagonal of it, and so does their hull
    assert piece.difference(poly.buffer(math.sqrt(2) * res + 1e-9)).area < 1e-12


# -- classification ------------------------------------------------------------------------
def test_classify_follows_the_occupancy_grid_convention():
    g = np.array([[-1, 0, 10, 64, 65, 100], [-5, 0, 0, 0, 0, 0]], dtype=np.int16)
    np.testing.assert_array_equal(classify(g)[0], [-1, 0, 0, 0, 1, 1])
    np.testing.assert_array_equal(classify(g, free=19.6)[0], [-1, 0, 0, -1, 1, 1])
    np.testing.assert_array_equal(classify(g, occupied=50)[0], [-1, 0, 0, 1, 1, 1])
    f = np.array([[np.nan, 0.1, 0.9]])
    np.testing.assert_array_equal(classify(f, occupied=0.65, free=0.196), [[-1, 0, 1]])
    np.testing.assert_array_equal(classify(np.array([[True, False]])), [[1, 0]])
    with pytest.raises(ValueError, match=r"\[0, 1\].*occupied=0.65"):
        classify(f)  # a 0..1 grid read as percent would be all free
    with pytest.raises(ValueError, match=r"\[0, 1\]"):
        classify(np.array([[0, 1, 1]]))
    with pytest.raises(ValueError, match="free=70 must be below occupied=65"):
        classify(g, free=70)
    with pytest.raises(ValueError, match="boolean grid"):
        classify(np.array([[True]]), occupied=1)
    with pytest.raises(ValueError, match="2-D"):
        classify(np.zeros(5))
    with pytest.raises(ValueError, match="booleans or numbers"):
        classify(np.array([["a"]]))


def test_first_row_bottom_is_the_occupancy_grid_message_order():
    g = np.zeros((4, 5), dtype=np.int8)
    g[0, 0] = OCC  # the image's top-left cell
    top = segplan.Floor.from_occupancy(g, 1.0, (10.0, 20.0), tolerance=0)
    bottom = segplan.Floor.from_occupancy(g[::-1], 1.0, (10.0, 20.0), first_row="bottom", tolerance=0)
    np.testing.assert_array_equal(top.obstacles[0], bottom.obstacles[0])
    assert shapely.Polygon(top.obstacles[0]).equals(shapely.box(10, 23, 11, 24))  # top-left: high y
    assert top.cell(10.5, 23.5) == (0, 0) and top.cell(9.9, 23.5) is None


def test_bad_arguments_are_refused_naming_them():
    g = np.zeros((3, 3), dtype=np.int8)
    for kwargs, words in [
        ({"resolution": 0.0}, "resolution must be > 0"),
        ({"resolution": math.nan}, "resolution must be finite"),
        ({"origin": (0.0, 0.0, 0.3)}, "origin yaw 0.3 rad is not supported"),
        ({"origin": (0.0,)}, "origin must be"),
        ({"tolerance": -1.0}, "tolerance must be >= 0"),
        ({"first_row": "left"}, "first_row"),
    ]:
        args = {"resolution": 0.1, **kwargs}
        with pytest.raises(ValueError, match=words) as info:
            segplan.Floor.from_occupancy(g, **args, source="lab.pgm")
        assert str(info.value).startswith("lab.pgm: ")


# -- polygons with collinear and closing vertices ----------------------------------------------
def test_a_union_of_grid_cells_is_accepted_as_an_obstacle():
    """The issue's report: shapely's union of cell boxes (closed ring, collinear vertices) was refused."""
    cells = [shapely.box(x, y, x + 0.5, y + 0.5) for x in (2.0, 2.5, 3.0) for y in (1.0, 1.5)]
    cells += [shapely.box(3.0, 2.0, 3.5, 2.5)]  # an L: non-convex
    union = shapely.union_all(cells)
    ring = np.asarray(union.exterior.coords)  # closed: the first vertex repeated
    assert np.array_equal(ring[0], ring[-1]) and len(ring) > 7
    robot = segplan.Robot(1.0, 0.1)
    for obstacle in (union, ring, ring[::-1]):
        sc = segplan.make_scenario(robot, (0.0, 0.5, 0.0), (6.0, 0.5, 0.0), [obstacle], (-1, -1, 8, 5))
        assert shapely.union_all([shapely.Polygon(p) for p in sc.obstacles]).equals(union)
        assert len(sc.outlines[0]) == len(ring) - 1 or len(sc.outlines[0]) == 6  # closing copy dropped
    box_ring = np.asarray(shapely.union_all(cells[:6]).exterior.coords)  # a rectangle of six cells
    sc = segplan.make_scenario(robot, (0.0, 0.5, 0.0), (6.0, 0.5, 0.0), [box_ring])
    assert len(sc.obstacles) == 1 and len(sc.obstacles[0]) == 4  # collinear vertices dropped


def test_floor_from_polygons_is_what_make_scenario_builds():
    sc = segplan.load_scenario("l_shaped_rack")
    floor = segplan.Floor.from_polygons(sc.outlines, sc.bounds)
    again = segplan.make_scenario(sc.robot, sc.start, sc.goal, floor)
    assert again.bounds == sc.bounds  # the floor's bounds
    for a, b in zip(again.obstacles, sc.obstacles, strict=True):
        np.testing.assert_array_equal(a, b)
    assert again.outline_of == sc.outline_of
    with pytest.raises(ValueError, match=r"<python>: obstacles\[0\]: vertex 2 repeats vertex 1"):
        segplan.Floor.from_polygons([[[0, 0], [1, 0], [1, 0], [0, 1]]])


# -- the floor where obstacles go --------------------------------------------------------------
def small_map() -> np.ndarray:
    """A 6 x 10 m room at 0.1 m with a wall in the middle and a 2 m gap in it (row 0 the top)."""
    g = np.zeros((60, 100), dtype=np.int8)
    g[:, :2] = g[:, -2:] = g[:2, :] = g[-2:, :] = OCC
    g[20:, 49:51] = OCC  # the wall, from the bottom up to y = 4 m
    return g


def test_plan_and_make_scenario_take_a_floor():
    floor = segplan.Floor.from_occupancy(small_map(), 0.1)
    start, goal = (1.0, 1.0, 0.0), (8.5, 1.0, 0.0)
    p = segplan.plan(start, goal, floor, 0.8, half_width=0.2, max_steer=math.radians(45))
    on_map = segplan.make_scenario(segplan.Robot(0.8, 0.2), start, goal, floor)
    assert not segplan.measure_scenario_path(segplan.plan_poses(p), on_map).collides
    assert on_map.bounds == (0.0, 0.0, 10.0, 6.0)  # the floor's bounds
    assert max(y for _, y, _ in segplan.plan_poses(p)) > 4.2  # over the wall, through the gap
    with pytest.raises(
        segplan.ScenarioError, match=r"start pose .* collides with the blocked cells of <grid>"
    ):
        segplan.make_scenario(segplan.Robot(0.8, 0.2), (4.6, 1.0, 0.0), goal, floor)
    with pytest.raises(segplan.ScenarioError, match="out of bounds"):
        segplan.make_scenario(segplan.Robot(0.8, 0.2), (-3.0, 1.0, 0.0), goal, floor)
    narrow = segplan.make_scenario(segplan.Robot(0.8, 0.2), start, goal, floor, (0, 0, 10, 5))
    assert narrow.bounds == (0.0, 0.0, 10.0, 5.0)  # given bounds win


def rasterise(polygons, bounds, res):
    """Cells (row 0 the top row) that a polygon meets with positive area (shapely)."""
    xmin, ymin, xmax, ymax = bounds
    rows, cols = round((ymax - ymin) / res), round((xmax - xmin) / res)
    grid = np.zeros((rows, cols), dtype=np.int8)
    for p in polygons:
        (x0, y0), (x1, y1) = np.min(p, axis=0), np.max(p, axis=0)
        c0, c1 = max(int((x0 - xmin) / res) - 1, 0), min(int((x1 - xmin) / res) + 2, cols)
        b0, b1 = max(int((y0 - ymin) / res) - 1, 0), min(int((y1 - ymin) / res) + 2, rows)  # from the bottom
        b, c = np.mgrid[b0:b1, c0:c1]
        boxes = shapely.box(xmin + res * c, ymin + res * b, xmin + res * (c + 1), ymin + res * (b + 1))
        hit = shapely.area(shapely.intersection(boxes, shapely.Polygon(p))) > 0
        grid[rows - 1 - b[hit], c[hit]] = OCC
    return grid


@pytest.mark.parametrize("name", ["fig5_example1", "fig6_example2", "l_shaped_rack"])
def test_round_trip_of_a_shipped_floor_covers_every_obstacle(name):
    sc = segplan.load_scenario(name)
    res = 0.05
    floor = segplan.Floor.from_occupancy(rasterise(sc.outlines, sc.bounds, res), res, sc.bounds[:2])
    union = shapely.union_all([shapely.Polygon(p) for p in floor.obstacles])
    for p in sc.outlines:
        assert shapely.Polygon(p).difference(union).area <= 1e-9
    # the tolerance keeps each slanted obstacle whole, a non-convex one as few pieces as given
    assert len(floor.obstacles) == len(sc.obstacles)
    assert floor.free_space_loss() < 0.005


def test_round_trip_plans_on_the_rasterised_fig5():
    sc = segplan.load_scenario("fig5_example1")
    res = 0.05
    floor = segplan.Floor.from_occupancy(rasterise(sc.outlines, sc.bounds, res), res, sc.bounds[:2])
    r = sc.robot
    p = segplan.plan(sc.start, sc.goal, floor, r.L, half_width=r.half_width, max_steer=r.max_steer)
    on_map = segplan.make_scenario(r, sc.start, sc.goal, floor)
    assert not segplan.measure_scenario_path(segplan.plan_poses(p), on_map).collides
    assert not segplan.measure_scenario_path(segplan.plan_poses(p), sc).collides  # the real floor too


# -- ROS map_server files ----------------------------------------------------------------------
def write_yaml(folder, image="map.pgm", **keys):
    lines = {"image": image, "resolution": 0.1, "origin": "[-1.0, -2.0, 0.0]", "negate": 0}
    lines.update({"occupied_thresh": 0.65, "free_thresh": 0.196})
    lines.update(keys)
    text = "".join(f"{k}: {v}\n" for k, v in lines.items() if v is not None)
    path = folder / "map.yaml"
    path.write_text(text, encoding="utf-8")
    return path


def write_pgm(path, img: np.ndarray, plain=False, maxval=255):
    rows, cols = img.shape
    if plain:
        body = "\n".join(" ".join(str(int(v)) for v in row) for row in img)
        path.write_text(f"P2\n# a comment\n{cols} {rows}\n{maxval}\n{body}\n")
    else:
        dtype = np.uint8 if maxval < 256 else ">u2"
        path.write_bytes(b"P5\n# a comment\n%d %d\n%d\n" % (cols, rows, maxval) + img.astype(dtype).tobytes())


#: Grey levels and their cells under the default thresholds (occ = 1 - p: > 0.65 occupied,
#: < 0.196 free): 254 free, 0 occupied, 205 unknown (occ = 50/255 = 0.19608), 90 occupied
#: (occ = 0.647 is not > 0.65: unknown), 88 occupied (0.655).
LEVELS = np.array([[254, 0, 205, 90, 88, 205, 205, 254]], dtype=np.uint8)


def expected(levels, maxval=255, negate=False, lo=0.196, hi=0.65):
    """map_server's rule, pixel by pixel."""
    out = []
    for v in levels.ravel().tolist():
        p = v / maxval
        occ = p if negate else 1.0 - p
        out.append(1 if occ > hi else 0 if occ < lo else -1)
    return np.array(out, dtype=np.int8).reshape(levels.shape)


def rows_of(img):
    return np.vstack([img, np.full((2, img.shape[1]), 254, dtype=img.dtype)])  # free rows: a free cell


@pytest.mark.parametrize("fmt", ["P5", "P2", "P5-16", "png-L", "png-RGB", "png-RGBA", "png-P"])
def test_load_ros_map_reads_pgm_and_png_as_map_server_does(tmp_path, fmt):
    img = rows_of(np.tile(LEVELS, (2, 1)))
    if fmt == "P5":
        write_pgm(tmp_path / "map.pgm", img)
    elif fmt == "P2":
        write_pgm(tmp_path / "map.pgm", img, plain=True)
    elif fmt == "P5-16":
        write_pgm(tmp_path / "map.pgm", img.astype(np.uint32) * 257, maxval=65535)
    else:
        mode = fmt.split("-")[1]
        im = Image.fromarray(img, "L")
        im = im.convert(mode) if mode != "P" else im.convert("P")
        im.save(tmp_path / "map.png")
    yaml = write_yaml(tmp_path, "map.png" if fmt.startswith("png") else "map.pgm")
    floor = segplan.load_ros_map(yaml, tolerance=0.0)
    np.testing.assert_array_equal(floor.cells, expected(img))
    assert floor.bounds == pytest.approx((-1.0, -2.0, -1.0 + 0.1 * img.shape[1], -2.0 + 0.1 * img.shape[0]))
    assert floor.source == str(yaml)
    # the occupied pixel at row 0, column 1 (the top row) is the cell at x -0.9..-0.8, y top
    top = -2.0 + 0.1 * img.shape[0]
    assert any(shapely.Polygon(p).contains(shapely.Point(-0.85, top - 0.05)) for p in floor.obstacles)


def test_negate_thresholds_modes_and_unknown(tmp_path):
    img = rows_of(np.tile(LEVELS, (2, 1)))
    write_pgm(tmp_path / "map.pgm", img)
    yaml = write_yaml(tmp_path, negate=1)
    np.testing.assert_array_equal(segplan.load_ros_map(yaml).cells[:2], expected(img, negate=True)[:2])
    yaml = write_yaml(tmp_path, occupied_thresh=0.5, free_thresh=0.1)
    np.testing.assert_array_equal(segplan.load_ros_map(yaml).cells, expected(img, lo=0.1, hi=0.5))
    yaml = write_yaml(tmp_path, mode="scale")  # no alpha: as trinary in the binary view
    np.testing.assert_array_equal(segplan.load_ros_map(yaml).cells, expected(img))
    raw = np.array([[0, 50, 100, 255], [0, 0, 0, 0]], dtype=np.uint8)  # raw: percent, > 100 unknown
    write_pgm(tmp_path / "map.pgm", raw)
    yaml = write_yaml(tmp_path, mode="raw")
    np.testing.assert_array_equal(segplan.load_ros_map(yaml).cells, [[0, -1, 1, -1], [0, 0, 0, 0]])
    # unknown cells: obstacles by default, free space when told
    write_pgm(tmp_path / "map.pgm", np.array([[205, 205], [254, 254]], dtype=np.uint8))
    yaml = write_yaml(tmp_path)
    assert len(segplan.load_ros_map(yaml).obstacles) == 1
    assert len(segplan.load_ros_map(yaml, unknown_is_occupied=False).obstacles) == 0


def test_scale_mode_transparent_pixels_are_unknown(tmp_path):
    rgba = np.zeros((2, 2, 4), dtype=np.uint8)
    rgba[..., :3] = 254
    rgba[..., 3] = [[255, 0], [255, 255]]
    Image.fromarray(rgba, "RGBA").save(tmp_path / "map.png")
    np.testing.assert_array_equal(
        segplan.load_ros_map(write_yaml(tmp_path, "map.png")).cells, [[0, 0], [0, 0]]
    )
    scaled = segplan.load_ros_map(write_yaml(tmp_path, "map.png", mode="scale"))
    np.testing.assert_array_equal(scaled.cells, [[0, -1], [0, 0]])


@pytest.mark.parametrize(
    ("change", "words"),
    [
        ({"resolution": "[0.1"}, "invalid YAML"),
        ({"occupied_tresh": 0.7}, "unknown key 'occupied_tresh'; did you mean 'occupied_thresh'"),
        ({"resolution": None}, "missing key 'resolution'"),
        ({"resolution": -0.1}, "resolution must be > 0"),
        ({"resolution": "abc"}, "resolution must be a number"),
        ({"origin": "[1, 2, 0.5]"}, "origin yaw 0.5 rad is not supported"),
        ({"origin": "[1]"}, "origin must be"),
        ({"negate": 2}, "negate must be 0 or 1"),
        ({"occupied_thresh": 0.1}, "0 <= free_thresh < occupied_thresh <= 1"),
        ({"free_thresh": -0.1}, "0 <= free_thresh < occupied_thresh <= 1"),
        ({"occupied_thresh": 1.5}, "0 <= free_thresh < occupied_thresh <= 1"),
        ({"mode": "binary"}, "mode must be one of trinary, scale, raw"),
        ({"image": "nowhere.pgm"}, "image 'nowhere.pgm': cannot read"),
        ({"image": "junk.png"}, "image 'junk.png': not an image"),
        ({"image": "short.pgm"}, "image 'short.pgm': PGM holds 3 bytes of pixels, 4 x 2 need 8"),
        ({"image": "full.pgm"}, "no free cell"),
    ],
)
def test_bad_map_files_are_one_clear_line(tmp_path, change, words):
    write_pgm(tmp_path / "map.pgm", rows_of(LEVELS))
    write_pgm(tmp_path / "full.pgm", np.zeros((2, 2), dtype=np.uint8))
    (tmp_path / "junk.png").write_bytes(b"\x89PNG not really")
    (tmp_path / "short.pgm").write_bytes(b"P5\n4 2\n255\n\x00\x00\x00")
    yaml = write_yaml(tmp_path, **change)
    with pytest.raises(ValueError, match=words) as info:
        segplan.load_ros_map(yaml)
    assert str(info.value).startswith(str(yaml)) and "\n" not in str(info.value)


def test_a_missing_yaml_and_a_list_are_refused(tmp_path):
    with pytest.raises(ValueError, match="cannot read"):
        segplan.load_ros_map(tmp_path / "none.yaml")
    (tmp_path / "list.yaml").write_text("- image\n- map.pgm\n")
    with pytest.raises(ValueError, match="'key: value' lines"):
        segplan.load_ros_map(tmp_path / "list.yaml")


# -- the command line -----------------------------------------------------------------------
@pytest.fixture
def room_yaml(tmp_path):
    """small_map() as a map_server map (grey levels: 0 occupied, 254 free, 205 unknown)."""
    g = small_map()
    img = np.where(g == OCC, 0, 254).astype(np.uint8)
    img[5:15, 60:70] = 205  # an unknown patch: x 6..7 m, y 4.5..5.5 m
    write_pgm(tmp_path / "room.pgm", img)
    path = tmp_path / "room.yaml"
    path.write_text(
        "image: room.pgm\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n", encoding="utf-8"
    )
    return path


ROBOT = ["--L", "0.8", "--half-width", "0.2"]


def test_cli_plans_on_a_map(room_yaml, capsys):
    code = main(
        ["plan", str(room_yaml), "--start", "1", "1", "0", "--goal", "8.5", "1", "0", *ROBOT, "--json"]
    )
    out = capsys.readouterr()
    assert code == 0, out.err
    import json

    data = json.loads(out.out)
    assert data["found"] is True and data["scenario"] == "room"
    assert data["nodes"][0] == [1.0, 1.0, 0.0] and data["nodes"][-1] == [8.5, 1.0, 0.0]


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (
            ["--start", "4.6", "1", "0", "--goal", "8.5", "1", "0", *ROBOT],
            "start pose .* collides with the blocked",
        ),
        (["--start", "-5", "1", "0", "--goal", "8.5", "1", "0", *ROBOT], "start pose .* out of bounds"),
        (
            ["--start", "6.1", "5.0", "0", "--goal", "8.5", "1", "0", *ROBOT],
            "start pose .* collides",
        ),  # unknown
        (["--goal", "8.5", "1", "0", *ROBOT], "a map needs --start"),
        (["--start", "1", "1", "0", "--goal", "8.5", "1", "0"], "a map needs --L"),
        (["--start", "1", "1", "0", "--goal", "8.5", "1", "0", "--L", "-1"], "L must be"),
        (["--start", "1", "1", "0", "--goal", "8.5", "1", "0", *ROBOT, "--max-steer-deg", "95"], "max_steer"),
    ],
)
def test_cli_map_errors_are_one_line_exit_2(room_yaml, capsys, args, words):
    assert main(["plan", str(room_yaml), *args]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert err.startswith("segplan: error: ") and err.count("\n") == 1 and "Traceback" not in err
    import re

    assert re.search(words, err), err


def test_cli_bad_map_files_are_one_line_exit_2(tmp_path, room_yaml, capsys):
    poses = ["--start", "1", "1", "0", "--goal", "8.5", "1", "0", *ROBOT]
    cases = {
        "bad.yaml": ("image: room.pgm\nresolution: [0.1\n", "invalid YAML"),
        "missing.yaml": ("image: gone.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n", "cannot read"),
        "thresh.yaml": (
            "image: room.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nfree_thresh: 0.9\n",
            "free_thresh < occupied_thresh",
        ),
        "full.yaml": ("image: full.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n", "no free cell"),
    }
    write_pgm(tmp_path / "full.pgm", np.zeros((3, 3), dtype=np.uint8))
    for name, (text, words) in cases.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
        assert main(["plan", str(tmp_path / name), *poses]) == EXIT_BAD_INPUT
        err = capsys.readouterr().err
        assert err.startswith(f"segplan: error: {tmp_path / name}") and words in err, err
        assert err.count("\n") == 1 and "Traceback" not in err
    assert main(["plan", "fig5_example1", "--start", "1", "1", "0"]) == EXIT_BAD_INPUT
    assert "--start applies to a map" in capsys.readouterr().err
