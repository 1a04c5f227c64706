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


# -- the one curvature kernel against the five planners' former copies (issue 24) --------------
def _random_cubics(rng, shape):
    """Cubics of random feasible unions (d, headings and alpha drawn wide), each array ``shape``."""
    from segplan.model.union import cubic_coefficients

    phi0 = rng.uniform(-1.5, 1.5, shape)
    phi1 = rng.uniform(-1.5, 1.5, shape)
    lo, hi = alpha_interval(phi0, phi1)
    ok = hi > lo
    phi1 = np.where(ok, phi1, -phi0 * 0.5)
    lo, hi = alpha_interval(phi0, phi1)
    alpha = lo + rng.uniform(0.001, 0.999, shape) * (hi - lo)
    d = np.exp(rng.uniform(-3.0, 4.0, shape))
    return cubic_coefficients(d, phi0, phi1, alpha)


def _same_bits(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def test_peak_curvature_is_each_planners_sampled_peak_bit_for_bit():
    """``curvature_samples`` + ``peak_curvature`` give the very bits of the expressions the
    planners wrote out before issue 24 (literal copies below, each with its caller's shapes):
    the link model's steering fallback (33 abscissae), the lattice's ``steerable`` screen
    (7 frames x 17) and the primitives' ``_peaks`` (49)."""
    from segplan.model.union import curvature_samples, peak_curvature

    rng = np.random.default_rng(24)
    for _ in range(20):
        # planning/links.py LinkModel._steer: n alphas x 33 abscissae
        X, c1, c2, c3 = _random_cubics(rng, (int(rng.integers(1, 40)),))
        tau = np.linspace(0.0, 1.0, 33)
        x = X[:, None] * tau
        fp = c1[:, None] + (2.0 * c2[:, None] + 3.0 * c3[:, None] * x) * x
        fpp = 2.0 * c2[:, None] + 6.0 * c3[:, None] * x
        old = np.max(np.abs(fpp) / (1.0 + fp * fp) ** 1.5, axis=1)
        _, fp, fpp = curvature_samples(X[:, None], c1[:, None], c2[:, None], c3[:, None], tau)
        assert _same_bits(peak_curvature(fp, fpp, axis=1), old)

        # planning/lattice/approach.py steerable: (n, 7, 1) cubics x (1, 1, 17) abscissae
        X, c1, c2, c3 = _random_cubics(rng, (int(rng.integers(1, 30)), 7, 1))
        tau = np.linspace(0.0, 1.0, 17)[None, None, :]
        x = X * tau
        fp = c1 + (2.0 * c2 + 3.0 * c3 * x) * x
        fpp = 2.0 * c2 + 6.0 * c3 * x
        old = np.max(np.abs(fpp) / (1.0 + fp * fp) ** 1.5, axis=2).min(axis=1)
        _, fp, fpp = curvature_samples(X, c1, c2, c3, tau)
        assert _same_bits(peak_curvature(fp, fpp, axis=2).min(axis=1), old)

        # planning/lattice/primitives.py _peaks: (n, k, 1) cubics x 49 abscissae
        X, c1, c2, c3 = _random_cubics(rng, (int(rng.integers(1, 30)), 3, 1))
        s = np.linspace(0.0, 1.0, 49)
        x = X * s
        fp = c1 + (2.0 * c2 + 3.0 * c3 * x) * x
        old = np.max(np.abs(2.0 * c2 + 6.0 * c3 * x) / (1.0 + fp * fp) ** 1.5, axis=-1)
        _, fp, fpp = curvature_samples(X, c1, c2, c3, s)
        assert _same_bits(peak_curvature(fp, fpp), old)


def test_exceeds_curvature_is_each_planners_certain_failure_bit_for_bit():
    """``curvature_samples`` + ``exceeds_curvature`` against the two screens that compared
    without dividing: ``Workspace._curvature_ok`` (one union, 17 abscissae, whose ``x``,
    ``f'`` and ``|f''|`` it reuses) and refine's ``certain_failures`` (n links x 9), with
    limits drawn at the sampled peak itself, where a last-bit difference would show."""
    from segplan.model.union import curvature_samples, exceeds_curvature, peak_curvature

    rng = np.random.default_rng(2024)
    s17 = np.linspace(0.0, 1.0, 17)
    s9 = np.linspace(0.0, 1.0, 9)
    for _ in range(300):
        # planning/validity.py Workspace._curvature_ok: one union, Python floats
        X, c1, c2, c3 = (float(v) for v in _random_cubics(rng, ()))
        _, fp, fpp = curvature_samples(X, c1, c2, c3, s17)
        kmax = float(peak_curvature(fp, fpp)) * float(rng.choice([1.0, 1.0 - 1e-16, 1.0 + 1e-16, 0.5, 2.0]))
        x = X * s17
        fp_old = c1 + (2.0 * c2 + 3.0 * c3 * x) * x
        fpp_old = np.abs(2.0 * c2 + 6.0 * c3 * x)
        old = np.any(fpp_old > kmax * (1.0 + fp_old * fp_old) ** 1.5)
        xk, fp, fpp = curvature_samples(X, c1, c2, c3, s17)
        fpp = np.abs(fpp)
        assert _same_bits(xk, x) and _same_bits(fp, fp_old) and _same_bits(fpp, fpp_old)
        assert exceeds_curvature(fp, fpp, kmax) == old

        # planning/refine.py certain_failures: n links x 9 abscissae, x and f' reused
        X, c1, c2, c3 = _random_cubics(rng, (int(rng.integers(1, 20)),))
        x = X[:, None] * s9
        fp_old = c1[:, None] + (2.0 * c2[:, None] + 3.0 * c3[:, None] * x) * x  # f'
        fpp_old = 2.0 * c2[:, None] + 6.0 * c3[:, None] * x  # f''
        kmax = float(np.median(np.max(np.abs(fpp_old) / (1.0 + fp_old * fp_old) ** 1.5, axis=1)))
        old = np.any(np.abs(fpp_old) > kmax * (1.0 + fp_old * fp_old) ** 1.5, axis=1)
        xk, fp, fpp = curvature_samples(X[:, None], c1[:, None], c2[:, None], c3[:, None], s9)
        assert _same_bits(xk, x) and _same_bits(fp, fp_old) and _same_bits(fpp, fpp_old)
        assert _same_bits(exceeds_curvature(fp, fpp, kmax, axis=1), old)


def test_peak_curvature_is_a_lower_bound_of_the_exact_maximum():
    """Sampled peaks never exceed :meth:`Union.max_curvature` (beyond rounding)."""
    from segplan.model.union import curvature_samples, peak_curvature

    rng = np.random.default_rng(7)
    for _ in range(50):
        phi0, phi1 = rng.uniform(-1.2, 1.2, 2)
        lo, hi = alpha_interval(phi0, phi1)
        if not hi > lo:
            continue
        alpha = lo + rng.uniform(0.05, 0.95) * (hi - lo)
        u = Union(Pose(0.0, 0.0, phi0), Pose(3.0, 0.0, phi1), alpha, 1.0)
        _, c1, c2, c3 = u.coefficients
        _, fp, fpp = curvature_samples(u.x_end, c1, c2, c3, np.linspace(0.0, 1.0, 33))
        assert peak_curvature(fp, fpp) <= u.max_curvature() * (1 + 1e-12)


def test_curvature_stationary_is_numpy_polynomials_bit_for_bit():
    """The quartic ``N`` and its roots on plain arrays give the very bits of the
    ``numpy.polynomial`` objects they replace (literal copy below, as before issue 25): the
    coefficients, their zeros' signs, and the roots, for random cubics and degenerate ones
    (straight, a parabola, no linear or no quadratic term)."""
    from segplan.model.union import _quartic, _roots, curvature_polynomials

    def old(c1, c2, c3):
        p1 = np.polynomial.Polynomial([c1, 2 * c2, 3 * c3])
        p2 = np.polynomial.Polynomial([2 * c2, 6 * c3])
        return 6 * c3 * (1 + p1**2) - 3 * p1 * p2**2

    rng = np.random.default_rng(25)
    _, c1, c2, c3 = _random_cubics(rng, (3000,))
    cases = list(zip(c1.tolist(), c2.tolist(), c3.tolist(), strict=True))
    cases += [(0.0, 0.0, 0.0), (0.7, 0.0, 0.0), (0.0, 1.5, 0.0), (0.5, 0.3, 0.0), (0.0, 0.0, 2.0)]
    cases += [(1.0, 0.0, 1.0), (0.0, -1.0, 1.0), (-0.0, 0.25, -0.0)]
    for c in cases:
        ref = old(*c)
        coef = _quartic(*c)
        assert _same_bits(coef, ref.coef) and _same_bits(np.signbit(coef), np.signbit(ref.coef)), c
        assert _same_bits(curvature_polynomials(*c)[2].coef, ref.coef), c
        if np.any(ref.coef != 0):
            assert _same_bits(_roots(coef), ref.roots()), c
