"""Any simple polygon as obstacles (issue 14 item 5): segplan.floor.decompose, shapely as the oracle."""

import math

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from segplan.floor.decompose import as_outlines, convex_pieces, decompose
from segplan.floor.geometry import check_convex_polygon

L_SHAPE = [[0, 0], [4, 0], [4, 1], [1, 1], [1, 3], [0, 3]]
U_SHAPE = [[0, 0], [3, 0], [3, 3], [2, 3], [2, 1], [1, 1], [1, 3], [0, 3]]


def assert_partition(vertices, pieces, rel=1e-9):
    """Pieces strictly convex, interiors disjoint, union = the polygon (shapely oracle)."""
    poly = shapely.Polygon(vertices)
    shapes = [shapely.Polygon(p) for p in pieces]
    for p, s in zip(pieces, shapes, strict=True):
        check_convex_polygon(p)  # strictly convex, counter-clockwise
        assert shapely.Polygon(p).exterior.is_ccw
        assert s.area == pytest.approx(s.convex_hull.area, rel=rel)
    for i in range(len(shapes)):
        for j in range(i + 1, len(shapes)):
            assert shapes[i].intersection(shapes[j]).area <= rel * poly.area
    union = shapely.union_all(shapes)
    assert sum(s.area for s in shapes) == pytest.approx(poly.area, rel=rel)
    assert union.symmetric_difference(poly).area <= rel * poly.area


def test_convex_polygon_is_its_own_single_piece():
    square = [[0, 0], [0, 1], [1, 1], [1, 0]]  # clockwise
    outline, pieces = decompose(square)
    assert len(pieces) == 1 and pieces[0] is outline
    np.testing.assert_array_equal(outline, check_convex_polygon(square))


@pytest.mark.parametrize(("shape", "count"), [(L_SHAPE, 2), (U_SHAPE, 3)])
def test_l_and_u_shapes_split_into_the_fewest_convex_pieces(shape, count):
    pieces = convex_pieces(shape)
    assert len(pieces) == count
    assert_partition(shape, pieces)
    assert_partition(shape[::-1], convex_pieces(shape[::-1]))


def test_pieces_use_only_input_vertices_and_drop_collinear_ones():
    shape = [[0, 0], [2, 0], [4, 0], [4, 1], [1, 1], [1, 3], [0, 3], [0, 1.5]]  # two collinear vertices
    pieces = convex_pieces(shape)
    assert_partition(shape, pieces)
    given_vertices = {tuple(v) for v in np.asarray(shape, dtype=float)}
    assert all(tuple(v) in given_vertices for p in pieces for v in p)


def star_polygon(radii, gaps):
    """A simple polygon, star-shaped around the origin (often non-convex)."""
    angles = np.cumsum(gaps) / np.sum(gaps) * 2 * math.pi
    return np.column_stack((radii * np.cos(angles), radii * np.sin(angles)))


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.integers(4, 14).flatmap(
        lambda n: st.tuples(
            st.lists(st.floats(0.2, 5.0), min_size=n, max_size=n),
            st.lists(st.floats(0.3, 1.0), min_size=n, max_size=n),
        )
    )
)
def test_property_random_star_polygons_partition_exactly(data):
    radii, gaps = (np.array(x) for x in data)
    v = star_polygon(radii, gaps)
    pieces = convex_pieces(v)
    assert_partition(v, pieces)
    # merging never adds pieces: at most the k - 2 triangles
    assert len(pieces) <= len(v) - 2


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 6), st.integers(1, 4)), min_size=2, max_size=7))
def test_property_orthogonal_skylines_partition_exactly(columns):
    """Skyline polygons: unit-width columns of integer heights (collinear vertices, reflex corners)."""
    top = []
    for x, (_, h) in enumerate(columns):
        top += [[x, h], [x + 1, h]]
    v = np.array([[0, 0], [len(columns), 0], *top[::-1]], dtype=float)
    v = np.array([p for i, p in enumerate(v) if i == 0 or not np.array_equal(p, v[i - 1])])
    if np.array_equal(v[0], v[-1]):
        v = v[:-1]
    assume(shapely.Polygon(v).convex_hull.area > shapely.Polygon(v).area)  # convex ones: validator's call
    pieces = convex_pieces(v)
    assert_partition(v, pieces)


@pytest.mark.parametrize(
    ("vertices", "words"),
    [
        ([[0, 0], [2, 2], [2, 0], [0, 2]], "not a simple polygon"),  # bow tie
        ([[0, 0], [4, 0], [4, 4], [2, 4], [2, -1], [0, 4]], "not a simple polygon"),  # crossing spike
        ([[0, 0], [1, 0], [2, 0]], "collinear"),
        ([[0, 0], [2, 0], [1, 1], [0, 0], [0, 2]], "vertex 3 repeats vertex 0"),  # closing copies are dropped
        ([[0, 0], [1, 0], [1, float("nan")]], "vertex 2"),
        ([[0, 0], [1, 0]], "at least 3 vertices"),
    ],
)
def test_bad_polygons_are_refused_naming_the_polygon_and_vertex(vertices, words):
    with pytest.raises(ValueError, match="obstacles\\[7\\]") as info:
        convex_pieces(vertices, "obstacles[7]")
    assert words in str(info.value)
    if "simple" in words:
        assert "the edges leaving vertex" in str(info.value)


def test_shapely_inputs():
    poly = shapely.Polygon(L_SHAPE)
    (outline,) = as_outlines(poly)
    np.testing.assert_array_equal(outline, np.asarray(L_SHAPE, dtype=float))
    multi = shapely.MultiPolygon([shapely.Polygon(L_SHAPE), shapely.box(10, 10, 11, 11)])
    assert len(as_outlines(multi)) == 2
    holed = shapely.Polygon([[0, 0], [5, 0], [5, 5], [0, 5]], [[[1, 1], [2, 1], [2, 2], [1, 2]]])
    with pytest.raises(ValueError, match="hole"):
        as_outlines(holed, "obstacles[0]")
    with pytest.raises(ValueError, match="LineString"):
        as_outlines(shapely.LineString([[0, 0], [1, 1]]), "obstacles[0]")


def test_pieces_of_one_obstacle_are_not_neighbours_in_d_s():
    """Heuristic (c)'s d_s: the gap between obstacles, not between pieces of one obstacle."""
    from segplan.planning.paper.problem import characteristic_dimension

    left, right = convex_pieces(L_SHAPE)  # touching pieces of the L
    far = np.array([[7.0, 0.0], [8.0, 0.0], [8.0, 1.0], [7.0, 1.0]])  # 3 m right of the L
    assert characteristic_dimension([left, right, far]) == 0.0  # pieces as obstacles: gap 0
    assert characteristic_dimension([left, right, far], groups=[0, 0, 1]) == pytest.approx(3.0)
    assert characteristic_dimension([far, left], groups=[0, 1]) == characteristic_dimension([far, left])
    with pytest.raises(ValueError, match="groups"):
        characteristic_dimension([left, right], groups=[0])
