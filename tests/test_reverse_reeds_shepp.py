"""Issue 26, reverse motion, step 2: the Reeds–Shepp length, the lower bound of a robot that may reverse.

Oracles: OMPL's ``ReedsSheppStateSpace.distance`` (an independent implementation) on
thousands of random pose pairs; and properties: at most the Dubins length (a forward path
is one of the car's), at least the rear points' distance, the same both ways (a path
driven backwards in time) and with both headings turned by pi (the same path in the other
gear), and at most the length of any path of the car drawn at random (arcs of radius at
least R and straight pieces, each forwards or backwards).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from ompl_distance import ompl_distance
from test_lattice_oracles import _drive as drive

from segplan.planning import reeds_shepp
from segplan.planning.dubins import dubins_length_scalar
from segplan.planning.reeds_shepp import reeds_shepp_length


def _ompl_reeds_shepp(R):
    return ompl_distance("reedsshepp", R)


def _poses(seed, n, spread=5.0):
    rng = np.random.default_rng(seed)
    X = rng.uniform(-spread, spread, (n, 6))
    X[:, 2] = rng.uniform(-math.pi, math.pi, n)
    X[:, 5] = rng.uniform(-math.pi, math.pi, n)
    X[: n // 3, 3:5] = X[: n // 3, 0:2] + rng.uniform(-1.5, 1.5, (n // 3, 2))  # close pairs: CCCC words
    return X


def _against_ompl(R, n, seed=7):
    ompl = _ompl_reeds_shepp(R)
    X = _poses(seed, n)
    ours = np.array([reeds_shepp_length(*x, R) for x in X])
    theirs = np.array([ompl(x[:3], x[3:]) for x in X])
    return ours, theirs


@pytest.mark.parametrize("R", [0.4, 1.3, 3.0])
def test_reeds_shepp_length_equals_ompl(R):
    ours, theirs = _against_ompl(R, 3000)
    assert np.allclose(ours, theirs, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("k", range(8))
def test_a_missing_base_word_is_caught_by_ompl(monkeypatch, k):
    words = reeds_shepp._SYMMETRIC + reeds_shepp._ASYMMETRIC
    drop = words[k]
    monkeypatch.setattr(reeds_shepp, "_SYMMETRIC", tuple(w for w in reeds_shepp._SYMMETRIC if w is not drop))
    monkeypatch.setattr(
        reeds_shepp, "_ASYMMETRIC", tuple(w for w in reeds_shepp._ASYMMETRIC if w is not drop)
    )
    ours, theirs = _against_ompl(1.0, 3000, seed=11)
    assert np.any(ours > theirs + 1e-6), drop.__name__


def test_the_backwards_symmetry_is_needed(monkeypatch):
    monkeypatch.setattr(reeds_shepp, "_BACKWARDS", ())  # the asymmetric words in their plain forms only
    ours, theirs = _against_ompl(1.0, 1500, seed=3)
    assert np.any(ours > theirs + 1e-6)


_pose = st.tuples(st.floats(-6, 6), st.floats(-6, 6), st.floats(-math.pi, math.pi, allow_nan=False))


@settings(max_examples=400, deadline=None)
@given(_pose, _pose, st.floats(0.2, 4.0))
def test_reeds_shepp_between_euclid_and_dubins(p, q, R):
    rs = reeds_shepp_length(*p, *q, R)
    assert math.hypot(q[0] - p[0], q[1] - p[1]) <= rs * (1 + 1e-9) + 1e-9
    assert rs <= dubins_length_scalar(*p, *q, R) * (1 + 1e-9) + 1e-9


@settings(max_examples=400, deadline=None)
@given(_pose, _pose, st.floats(0.2, 4.0))
def test_reeds_shepp_symmetric_under_reversal(p, q, R):
    rs = reeds_shepp_length(*p, *q, R)
    assert reeds_shepp_length(*q, *p, R) == pytest.approx(rs, rel=1e-9, abs=1e-9)  # driven back
    flipped = (p[0], p[1], p[2] + math.pi), (q[0], q[1], q[2] + math.pi)  # the other gear
    assert reeds_shepp_length(*flipped[0], *flipped[1], R) == pytest.approx(rs, rel=1e-9, abs=1e-9)


def _drive(pose, pieces, R):
    """End pose and length of a path of pieces ``(signed length, curvature in units of 1/R)``
    (the oracles' integration, :func:`test_lattice_oracles._drive`: a negative length drives
    the piece backwards)."""
    return drive(pose, pieces, R), sum(abs(s) for s, _ in pieces)


@settings(max_examples=400, deadline=None)
@given(
    _pose,
    st.lists(
        st.tuples(st.floats(-3, 3), st.sampled_from([-1.0, -0.5, 0.0, 0.7, 1.0])), min_size=1, max_size=6
    ),
    st.floats(0.3, 3.0),
)
def test_reeds_shepp_at_most_any_car_path(p, pieces, R):
    q, length = _drive(p, pieces, R)
    assert reeds_shepp_length(*p, *q, R) <= length * (1 + 1e-9) + 1e-9


@pytest.mark.parametrize("R", [0, -1.0, math.inf, math.nan, True, "1"])
def test_bad_radius(R):
    with pytest.raises(ValueError, match="R must be"):
        reeds_shepp_length(0, 0, 0, 1, 1, 0, R)
