"""The obstacles' bucket grid (issue 25, large floors).

* :class:`segplan.floor.buckets.BoxGrid` against brute force (hypothesis): a query returns
  every box meeting the query box, a point is paired with every box holding it, also at
  cell borders, on degenerate boxes and far outside the grid.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from segplan.floor.buckets import MAX_CELLS, BoxGrid

coord = st.floats(-50.0, 50.0, allow_nan=False)
extent = st.one_of(st.just(0.0), st.floats(0.0, 20.0))


@st.composite
def boxes(draw, max_size=40):
    n = draw(st.integers(0, max_size))
    out = []
    for _ in range(n):
        x, y, w, h = draw(coord), draw(coord), draw(extent), draw(extent)
        out.append((x, y, x + w, y + h))
    return np.array(out, dtype=float).reshape(-1, 4)


def meets(b, x0, y0, x1, y1):
    """Brute force: boxes ``b`` meeting the closed box ``[x0, x1] x [y0, y1]``."""
    return set(np.flatnonzero((b[:, 0] <= x1) & (b[:, 2] >= x0) & (b[:, 1] <= y1) & (b[:, 3] >= y0)).tolist())


@settings(max_examples=300, deadline=None)
@given(boxes(), coord, coord, extent, extent, st.one_of(st.none(), st.floats(0.05, 30.0)))
def test_query_returns_every_box_meeting_the_query(b, x, y, w, h, size):
    grid = BoxGrid(b, size)
    for q in ((x, y, x + w, y + h), *[tuple(r) for r in b[:5]], (-1e9, -1e9, 1e9, 1e9)):
        got = grid.query(*q)
        assert set(got.tolist()) >= meets(b, *q)
        assert np.all(np.diff(got) > 0)  # ascending, unique
    assert set(grid.query(-math.inf, -math.inf, math.inf, math.inf).tolist()) == set(range(len(b)))


@settings(max_examples=300, deadline=None)
@given(boxes(), st.lists(st.tuples(coord, coord), max_size=30), st.one_of(st.none(), st.floats(0.05, 30.0)))
def test_pairs_hold_every_point_in_a_box(b, points, size):
    grid = BoxGrid(b, size)
    # the drawn points, the boxes' corners (on cell borders when the boxes are) and a NaN
    pts = np.array(points + [(r[0], r[1]) for r in b] + [(r[2], r[3]) for r in b], dtype=float).reshape(-1, 2)
    x, y = np.append(pts[:, 0], math.nan), np.append(pts[:, 1], 0.0)
    p, k = grid.pairs(x, y)
    truth = {
        (a, i)
        for a in range(len(pts))
        for i in range(len(b))
        if b[i, 0] <= x[a] <= b[i, 2] and b[i, 1] <= y[a] <= b[i, 3]
    }
    assert set(zip(p.tolist(), k.tolist(), strict=True)) >= truth


def test_default_cells_and_bad_input():
    rng = np.random.default_rng(0)
    c = rng.uniform(0.0, 100.0, (400, 2))
    grid = BoxGrid(np.column_stack((c, c + 2.0)))
    assert 200 <= grid.shape[0] * grid.shape[1] <= 800  # about one cell per box
    assert len(BoxGrid(np.zeros((0, 4))).query(0, 0, 1, 1)) == 0
    assert BoxGrid([(1.0, 1.0, 1.0, 1.0)] * 3).query(0, 0, 2, 2).tolist() == [0, 1, 2]
    with pytest.raises(ValueError, match="finite"):
        BoxGrid([(0.0, 0.0, math.nan, 1.0)])
    with pytest.raises(ValueError, match="min <= max"):
        BoxGrid([(1.0, 0.0, 0.0, 1.0)])
    for size in (0.0, -1.0, math.inf, True):
        with pytest.raises(ValueError, match="size"):
            BoxGrid([(0.0, 0.0, 1.0, 1.0)], size)
    with pytest.raises(ValueError, match="cells"):
        BoxGrid([(0.0, 0.0, 1e6, 1e6)], 1e6 / math.sqrt(MAX_CELLS) / 2)
