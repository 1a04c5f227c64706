"""The obstacles' bucket grid (issue 25, large floors) and the workspace's tests that read it.

* :class:`segplan.floor.buckets.BoxGrid` against brute force (hypothesis): a query returns
  every box meeting the query box, a point is paired with every box holding it, also at
  cell borders, on degenerate boxes and far outside the grid.
* The workspace's answers through it are those of brute force over every obstacle, bit for
  bit: :meth:`Workspace.inside` against a loop over every polygon, the refinement's
  :func:`certain_failures` against its former loop (every obstacle whose box meets the
  samples), :meth:`Workspace.pose_free` against the pose predicate over every obstacle,
  the broad phase against the scalar loop (counts included), in either order of the
  questions.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from segplan.floor.buckets import MAX_CELLS, BoxGrid
from segplan.floor.geometry import pose_conflict
from segplan.model.frame import heuristic_alpha
from segplan.model.pose import Pose, alpha_interval, wrap
from segplan.model.union import cubic_coefficients
from segplan.planning import validity
from segplan.planning.links import LinkModel
from segplan.planning.refine import certain_failures
from segplan.planning.validity import Workspace
from segplan.studies.floor_kinds import stress_floor
from segplan.studies.floors import sweep_floor

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


# -- the workspace's tests through the index, against brute force ---------------------------
def big_workspace(cell=None):
    """A 300 x 300 m stress floor of 1000 obstacles; with ``cell``, its index of cells of
    that side (fine cells: the query boxes' own margins decide what the tests see)."""
    sc = stress_floor(0, size=300.0, n_obstacles=1000)
    r = sc.robot
    original = validity.BoxGrid
    try:
        if cell is not None:
            validity.BoxGrid = lambda boxes: original(boxes, cell)
        ws = Workspace(sc.enlarged, r.L, sc.free_bounds, r.max_curvature)
        ws.index  # noqa: B018 (the grid is built at its first use: here, patched)
    finally:
        validity.BoxGrid = original
    assert cell is None or ws.index.size == cell
    return sc, ws


def inside_brute(ws, x, y):
    """Every polygon in turn: strictly inside its box, then every edge (the former loop)."""
    out = np.zeros(x.shape, dtype=bool)
    for poly, (x0, y0, x1, y1) in zip(ws.convex, ws.boxes, strict=True):
        near = (x > x0) & (x < x1) & (y > y0) & (y < y1)
        if near.any():
            k = np.flatnonzero(near)
            g = np.multiply.outer(x[k], poly.normals[:, 0]) + np.multiply.outer(y[k], poly.normals[:, 1])
            out[k[np.all(g - poly.offsets < 0.0, axis=1)]] = True
    return out


def test_inside_is_brute_force():
    sc, ws = big_workspace()
    rng = np.random.default_rng(1)
    x, y = rng.uniform(-5.0, 305.0, 20000), rng.uniform(-5.0, 305.0, 20000)
    # and points on the obstacles' vertices and boxes (on the boundary: not strictly inside)
    v = np.concatenate([p.vertices for p in ws.convex[:200]])
    x, y = np.concatenate((x, v[:, 0], ws.box_array[:, 0])), np.concatenate((y, v[:, 1], ws.box_array[:, 1]))
    got = ws.inside(x, y)
    assert np.array_equal(got, inside_brute(ws, x, y)) and 1000 < got.sum() < 10000
    assert ws.inside(x.reshape(2, -1), y.reshape(2, -1)).shape == (2, len(x) // 2)


@pytest.mark.parametrize("cell", [None, 0.25])
def test_pose_free_is_the_pose_predicate_over_every_obstacle(cell):
    """Poses whose rear point, middle or front wheel lies near an obstacle's vertex (within
    the reach of the screen, L / 10 beyond the segment's ends): the pose predicate over every
    obstacle decides as the workspace through its index."""
    sc, ws = big_workspace(cell)
    rng = np.random.default_rng(4)
    L, n = ws.L, 3000
    v = np.concatenate([p.vertices for p in ws.convex])[rng.integers(0, 8000, n)]
    th = rng.uniform(-np.pi, np.pi, n)
    along = rng.choice([-0.1, 0.0, 0.5, 1.0, 1.1], n) + rng.normal(0.0, 0.03, n)  # point of the segment
    side = rng.normal(0.0, 0.05, n)
    x = v[:, 0] - along * L * np.cos(th) + side * np.sin(th)
    y = v[:, 1] - along * L * np.sin(th) - side * np.cos(th)
    got = [ws.pose_free((a, b, t)) for a, b, t in zip(x, y, th, strict=True)]
    truth = [
        pose_conflict((a, b, t), L, ws.convex, ws.bounds) is None for a, b, t in zip(x, y, th, strict=True)
    ]
    assert got == truth and 0.2 < np.mean(got) < 0.8


def certain_failures_brute(ws, A, frame, X, c1, c2, c3):
    """The refinement's screen as it was: every obstacle whose box meets the samples' box."""
    from segplan.model.union import curvature_samples, exceeds_curvature
    from segplan.planning.refine import SAMPLES

    x, fp, fpp = curvature_samples(X[:, None], c1[:, None], c2[:, None], c3[:, None], SAMPLES)
    bad = exceeds_curvature(fp, fpp, ws.max_curvature, axis=1)
    fx = ((c3[:, None] * x + c2[:, None]) * x + c1[:, None]) * x
    h = frame[:, None] + np.arctan(fp)
    cf, sf = np.cos(frame)[:, None], np.sin(frame)[:, None]
    rx, ry = A[:, :1] + cf * x - sf * fx, A[:, 1:2] + sf * x + cf * fx
    ux, uy = np.cos(h), np.sin(h)
    L = ws.L
    wx = np.concatenate((rx, rx + 0.5 * L * ux, rx + L * ux), axis=1)
    wy = np.concatenate((ry, ry + 0.5 * L * uy, ry + L * uy), axis=1)
    xmin, ymin, xmax, ymax = ws.bounds
    bad |= np.any((wx <= xmin) | (wx >= xmax) | (wy <= ymin) | (wy >= ymax), axis=1)
    return bad | np.any(inside_brute(ws, wx.ravel(), wy.ravel()).reshape(wx.shape), axis=1)


def test_certain_failures_are_those_of_every_obstacle():
    sc, ws = big_workspace()
    rng = np.random.default_rng(2)
    n = 3000
    A = np.column_stack((rng.uniform(0, 300, n), rng.uniform(0, 300, n), rng.uniform(-np.pi, np.pi, n)))
    step, ang = rng.uniform(0.5, 40.0, n), A[:, 2] + rng.uniform(-0.6, 0.6, n)
    B = np.column_stack(
        (A[:, 0] + step * np.cos(ang), A[:, 1] + step * np.sin(ang), A[:, 2] + rng.uniform(-0.6, 0.6, n))
    )
    psi = np.arctan2(B[:, 1] - A[:, 1], B[:, 0] - A[:, 0])
    phi0, phi1 = wrap(A[:, 2] - psi), wrap(B[:, 2] - psi)
    lo, hi = alpha_interval(phi0, phi1)
    ok = hi - lo > 0.02
    A, B, psi, phi0, phi1 = A[ok], B[ok], psi[ok], phi0[ok], phi1[ok]
    d = np.hypot(B[:, 0] - A[:, 0], B[:, 1] - A[:, 1])
    alpha = np.atleast_1d(heuristic_alpha(d, phi0, phi1, sc.robot.L))
    args = (A, psi - alpha, *cubic_coefficients(d, phi0, phi1, alpha))
    got = certain_failures(ws, *args)
    assert np.array_equal(got, certain_failures_brute(ws, *args))
    assert 0.1 < got.mean() < 0.9


def test_broad_phase_through_the_index_decides_as_the_scalar_loop(monkeypatch):
    """A floor whose index leaves most obstacles unexamined: the same collisions, obstacles
    kept and counts as the scalar loop over every obstacle, whether the whole floor or a
    subset is asked about first."""
    sc = sweep_floor(6.0, 400, 1)
    fb = sc.free_bounds
    rng = np.random.default_rng(3)
    poses = [
        Pose(rng.uniform(fb[0], fb[2]), rng.uniform(fb[1], fb[3]), rng.uniform(-math.pi, math.pi))
        for _ in range(150)
    ]
    subset = list(range(0, 400, 7))

    def run(order):
        ws = Workspace(sc.enlarged, sc.robot.L, fb, sc.robot.max_curvature)
        links = LinkModel(ws)
        out = []
        for a, b in zip(poses[:-1], poses[1:], strict=True):
            u = links.union(a, Pose(a.x + (b.x - a.x) * 0.3, a.y + (b.y - a.y) * 0.3, b.theta))
            if u is None:
                continue
            for only in order:
                out.append(ws.colliding(u, first=False, only=only))
            kept = sorted((i, v) for i, v in ws.facts(u).near.items() if v is not None)
            out.append((kept, ws.pose_free(a)))
        s = ws.stats
        return out, (s.broad_rejections, s.exact_checks, s.certain_hits)

    runs = [run((None, subset)), run((subset, None))]
    assert runs[0][1][0] > 0 and any(isinstance(x, list) and x for x in runs[0][0])
    monkeypatch.setattr(validity, "VECTOR_SCREEN_MIN", 10**9)
    assert runs == [run((None, subset)), run((subset, None))]
