"""Computed primitive sets are those of the reference: the same selection, the same numbers.

``tests/data/primitive_sets.npz`` holds 28 sets (unit ``L``, steering limits 5-80 deg,
resolutions ``L / 2`` to ``L / 16`` and ``R / 32``) computed by
:func:`segplan.planning.lattice.primitives.compute_primitive_set` as it was at commit 05d743b,
before issue 25 made it faster: ``PYTHONPATH=<that tree> python
benchmarks/primitives_identity.py --write tests/data/primitive_sets.npz --sample test`` (its
docstring: which sets, which fields). On the machine that wrote them the sets computed now
are equal bit for bit; other processors round the last bits differently (primitives module
docstring), hence the tolerance of 1e-12 relative. The other tests hold each faster part to
what it replaced, bit for bit: the screened steering test to the full sampling, the sampler
vectorised over unions and the quarter turns of a heading to literal copies of the
per-union and per-primitive code.
"""

import math

import numpy as np
import pytest
from load_file import ROOT, load_file

from segplan import Union
from segplan.planning.lattice.frame import LatticeFrame, heading_angles
from segplan.planning.lattice.primitives import (
    FINE_S,
    FINE_T,
    SAMPLE_S,
    SAMPLE_T,
    STORED_STEER,
    compute_primitive_set,
    primitive_arrays,
    primitive_set,
)

DATA = ROOT / "tests" / "data" / "primitive_sets.npz"


@pytest.fixture(scope="module")
def identity():
    return load_file(ROOT / "benchmarks" / "primitives_identity.py", "primitives_identity")


def test_computed_sets_equal_the_stored_reference(identity):
    with np.load(DATA) as z:
        old = {k: z[k] for k in z.files}
    pairs = [tuple(map(float, s.split("/"))) for s in identity.sets_of(old)]
    assert len(pairs) == 28
    new = identity.compute(pairs, identity.TEST_FIELDS, identity.TEST_POINTS)
    bad, worst, _ = identity.differences(new, old)
    assert bad == []
    assert set(worst) == {*identity.TEST_FIELDS, "points"}
    assert max(worst.values()) <= 1e-12, worst


@pytest.mark.parametrize(
    ("steer_deg", "cells"),
    [(31.7, 8.0), (44.9, 4.0), (58.3, 16.0), (12.0, 32.0 * math.tan(math.radians(12.0)))],
)
def test_the_screened_selection_is_the_fully_sampled_one(steer_deg, cells):
    # with margins every peak curvature is sampled at all 49 abscissae (the margins need
    # them); without, the unions whose ends already break the limit are not sampled further
    full = primitive_arrays(compute_primitive_set(1.0, math.radians(steer_deg), 1.0 / cells, margins={}))
    fast = primitive_arrays(compute_primitive_set(1.0, math.radians(steer_deg), 1.0 / cells))
    assert full.keys() == fast.keys()
    for key, value in full.items():
        assert np.array_equal(value, fast[key]), key


def _sample_per_union(u, L, S, T):
    """The swept-segment sampler of one union as it was before issue 25 (literal copy): the
    oracle of the vectorised one."""
    x = u.x_end * S
    A = u.to_world(x, u.f(x)) - np.array(u.p0[:2])
    h = u.heading(x)
    U = np.column_stack((np.cos(h), np.sin(h)))
    pts = (A[:, None, :] + L * T[None, :, None] * U[:, None, :]).reshape(-1, 2)
    per = 24
    xd = u.x_end * np.linspace(0.0, 1.0, (len(S) - 1) * per + 1)
    Ad = u.to_world(xd, u.f(xd))
    hd = u.heading(xd)
    Bd = Ad + L * np.column_stack((np.cos(hd), np.sin(hd)))
    la = np.hypot(*np.diff(Ad, axis=0).T)
    lb = np.hypot(*np.diff(Bd, axis=0).T)
    run = max(la.reshape(-1, per).sum(axis=1).max(), lb.reshape(-1, per).sum(axis=1).max())
    delta = 0.5 * run * 1.02 + 0.5 * L * (T[1] - T[0])
    return pts, float(delta)


@pytest.mark.parametrize(("L", "steer_deg", "cells"), [(1.0, 36.2, 8.0), (1.7, 53.0, 2.0), (0.6, 45.0, 16.0)])
def test_points_and_covering_radii_are_the_per_union_samplers_bit_for_bit(L, steer_deg, cells):
    r = L / cells
    ps = compute_primitive_set(L, math.radians(steer_deg), r)
    frame = LatticeFrame((0.0, 0.0, 0.0), r, L)
    angles = heading_angles()
    fine = ps.fine_points()
    for h in range(4):
        for m, p in enumerate(ps.by_heading[h]):
            u = Union((0.0, 0.0, angles[p.h0]), (p.di * r, p.dj * r, angles[p.h1]), p.alpha, L)
            pts, delta = _sample_per_union(u, L, SAMPLE_S, SAMPLE_T)
            assert np.array_equal(pts, p.points) and delta == p.delta, (h, m)
            pts, delta = _sample_per_union(frame.union((0, 0, h), p), L, FINE_S, FINE_T)
            assert np.array_equal(pts, fine[h][0][m]) and delta == fine[h][1][m], (h, m)


def _turned_per_primitive(p, q):
    """A primitive turned by ``q`` quarter turns as before issue 25 (literal copy)."""
    di, dj, pts = p.di, p.dj, p.points
    for _ in range(q):
        di, dj = -dj, di
        pts = np.column_stack((-pts[:, 1], pts[:, 0]))
    return ((p.h0 + 4 * q) % 16, (p.h1 + 4 * q) % 16, di, dj, pts)


@pytest.mark.parametrize("stored", [False, True])
def test_every_heading_holds_the_quarter_turns_bit_for_bit(stored):
    steer = STORED_STEER if stored else math.radians(37.4)
    ps = primitive_set(1.3, steer, 1.3 / 8) if stored else compute_primitive_set(1.3, steer, 1.3 / 8)
    for h in range(16):
        assert len(ps.by_heading[h]) == len(ps.by_heading[h % 4])
        for p, q in zip(ps.by_heading[h % 4], ps.by_heading[h], strict=True):
            h0, h1, di, dj, pts = _turned_per_primitive(p, h // 4)
            assert (q.h0, q.h1, q.di, q.dj) == (h0, h1, di, dj)
            assert q.points.flags.c_contiguous and np.array_equal(q.points, pts)
            assert np.array_equal(np.signbit(q.points), np.signbit(pts))
            for f in ("cost", "alpha", "d", "phi0", "phi1", "peak_curvature", "delta"):
                assert getattr(q, f) == getattr(p, f)
