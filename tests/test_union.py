"""The union of two nodes: interpolation conditions, frames, validation (issue 2)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from segplan import Pose, Union
from segplan.model.pose import alpha_interval, intrinsic, wrap

coord = st.floats(-50, 50)
heading = st.floats(-math.pi, math.pi)
frac = st.floats(0.02, 0.98)


@st.composite
def unions(draw, max_phi_deg=80.0):
    """A random feasible union: start pose, chord, intrinsic headings, alpha, L."""
    max_phi = math.radians(max_phi_deg)
    x, y, psi = draw(coord), draw(coord), draw(heading)
    d = draw(st.floats(0.2, 30))
    phi0, phi1 = draw(st.floats(-max_phi, max_phi)), draw(st.floats(-max_phi, max_phi))
    lo, hi = alpha_interval(phi0, phi1)
    alpha = lo + draw(frac) * (hi - lo)
    L = draw(st.floats(0.05, 5))
    p0 = Pose(x, y, psi + phi0)
    p1 = Pose(x + d * math.cos(psi), y + d * math.sin(psi), psi + phi1)
    return Union(p0, p1, alpha, L)


def angle_diff(a, b):
    return abs(wrap(a - b))


@given(unions())
def test_union_interpolates_both_poses_and_headings(u):
    rear = u.rear(5)
    scale = 1 + max(abs(v) for v in (*u.p0[:2], *u.p1[:2]))
    assert np.allclose(rear[0], u.p0[:2], atol=1e-9 * scale)
    assert np.allclose(rear[-1], u.p1[:2], atol=1e-9 * scale)
    assert angle_diff(u.heading(0.0), u.p0.theta) < 1e-9
    assert angle_diff(u.heading(u.x_end), u.p1.theta) < 1e-9


@given(unions())
def test_front_wheel_is_at_distance_L_along_the_heading(u):
    rear, front = u.rear(33), u.front(33)
    assert np.allclose(np.hypot(*(front - rear).T), u.L, rtol=1e-9)
    # the segment A->B is tangent to the rear path: compare with a finite-difference tangent
    x = u.xs(33)[1:-1]
    h = 1e-6 * u.x_end
    tangent = u.to_world(x + h, u.f(x + h)) - u.to_world(x - h, u.f(x - h))
    seg = (front - rear)[1:-1]
    cross = tangent[:, 0] * seg[:, 1] - tangent[:, 1] * seg[:, 0]
    assert np.all(np.abs(cross) <= 1e-5 * np.hypot(*tangent.T) * u.L)
    assert np.all(np.einsum("ij,ij->i", tangent, seg) > 0)  # forward: B ahead of A


@given(unions(), heading, coord, coord)
def test_union_moves_rigidly_with_the_pose_pair(u, rot, tx, ty):
    c, s = math.cos(rot), math.sin(rot)

    def move(p):
        return Pose(c * p.x - s * p.y + tx, s * p.x + c * p.y + ty, p.theta + rot)

    v = Union(move(u.p0), move(u.p1), u.alpha, u.L)
    R = np.array([[c, -s], [s, c]])
    expected = u.front(17) @ R.T + (tx, ty)
    assert np.allclose(v.front(17), expected, atol=1e-8 * (1 + np.abs(expected).max()))


@given(unions())
def test_max_curvature_bounds_dense_samples(u):
    kmax = u.max_curvature()
    dense = np.abs(u.curvature(np.linspace(0, u.x_end, 4001))).max()
    assert kmax >= dense * (1 - 1e-12)
    assert kmax <= dense * (1 + 1e-3) + 1e-12


def test_union_is_immutable_and_repr():
    u = Union((0, 0, 0.2), (4, 1, 0.0), 0.0, 1.0)
    with pytest.raises(AttributeError):
        u.alpha = 0.3
    assert "Union(" in repr(u)


@pytest.mark.parametrize(
    "args, words",
    [
        (((0, 0, 0), (0, 0, 1), 0.0, 1.0), "coincident"),
        (((0, 0, 0), (1, 0, math.nan), 0.0, 1.0), "finite"),
        (((0, 0, 0), (1, math.inf, 0), 0.0, 1.0), "finite"),
        (((0, 0, 0), (1, 0, 0), 0.0, 0.0), "L must be"),
        (((0, 0, 0), (1, 0, 0), 0.0, -1.0), "L must be"),
        (((0, 0, 0), (1, 0, 0), 0.0, math.nan), "L must be"),
        (((0, 0, 0), (1, 0, 0), math.radians(95), 1.0), "alpha"),
        (((0, 0, 1.0), (1, 0, 0), math.radians(60), 1.0), "alpha"),
        (((0, 0, 0), (1, 0, 0), math.nan, 1.0), "alpha must be finite"),
        (((0, 0, 0), (-1, 0, 0), 0.0, 1.0), "no alpha reference system"),
        (((0, 0), (1, 0, 0), 0.0, 1.0), "three components"),
        ((("a", 0, 0), (1, 0, 0), 0.0, 1.0), "p0"),
    ],
)
def test_bad_input_is_a_clear_value_error(args, words):
    with pytest.raises(ValueError, match=words):
        Union(*args)


def test_goal_behind_the_start_has_no_frame():
    # the goal lies straight behind the start: the start heading opposes the chord
    geo = intrinsic((0, 0, 0), (-5, 0, 0))
    lo, hi = alpha_interval(geo.phi0, geo.phi1)
    assert lo >= hi
    with pytest.raises(ValueError, match="no alpha reference system"):
        Union((0, 0, 0), (-5, 0, 0), 0.0, 1.0)
    # slightly off that line a (hairpin) cubic exists, but only in a sliver of frames
    geo = intrinsic((0, 0, 0), (-5, 0.1, 0))
    lo, hi = alpha_interval(geo.phi0, geo.phi1)
    assert 0 < hi - lo < math.radians(2)


def test_xs_validates_n():
    u = Union((0, 0, 0.2), (4, 1, 0.0), 0.0, 1.0)
    for bad in (1, 0, 2.5, -3):
        with pytest.raises(ValueError, match="n must be"):
            u.rear(bad)


@given(st.floats(-1e4, 1e4))
def test_wrap_lands_in_half_open_interval_and_keeps_the_angle(a):
    w = wrap(a)
    assert -math.pi < w <= math.pi
    assert abs(math.sin(w) - math.sin(a)) < 1e-9 and abs(math.cos(w) - math.cos(a)) < 1e-9


def test_wrap_of_pi_is_pi():
    assert wrap(math.pi) == math.pi and wrap(-math.pi) == math.pi


def test_wrap_convention_is_half_open_at_minus_pi():
    from segplan.model.pose import wrap_fmod, wrap_scalar

    for a, expected in ((-math.pi, math.pi), (math.pi, math.pi), (3 * math.pi, math.pi), (0.5, 0.5)):
        assert wrap(a) == pytest.approx(expected, abs=1e-12)
        assert wrap_scalar(a) == wrap(a)
        assert wrap_fmod(a) == pytest.approx(wrap(a), abs=1e-15)
    for a in np.linspace(-20.0, 20.0, 4001):
        assert -math.pi < wrap_fmod(float(a)) <= math.pi
        assert abs(wrap_fmod(float(a)) - wrap(a)) <= 4e-15
    many = wrap(np.linspace(-10.0, 10.0, 2001))
    assert np.all((many > -math.pi) & (many <= math.pi))
