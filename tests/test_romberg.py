"""Our Romberg integration against scipy.integrate.quad (issue 2)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.integrate import quad

from segplan.model.romberg import RombergError, romberg


@given(
    st.floats(-3, 3),
    st.floats(0.1, 4),
    st.floats(-2, 2),
    st.floats(0.5, 6),
    st.sampled_from([1e-6, 1e-9, 1e-12]),
)
def test_romberg_matches_quad(a, width, c, w, rtol):
    def f(x):
        return np.sqrt(1 + (c * x) ** 2) * np.cos(w * x) + np.exp(-x * x)

    b = a + width
    value, error = romberg(f, a, b, rtol=rtol, atol=1e-14)
    ref, _ = quad(f, a, b, epsabs=1e-14, epsrel=1e-12, limit=200)
    assert abs(value - ref) <= 10 * max(rtol * abs(value), 1e-13) + 1e-12
    assert error <= max(rtol * abs(value), 1e-14)


def test_romberg_is_vectorised_over_a_batch():
    k = np.linspace(0.5, 3, 7)
    value, error = romberg(lambda x: np.cos(np.multiply.outer(x, k)), 0.0, 1.0, rtol=1e-12)
    assert value.shape == error.shape == (7,)
    assert np.allclose(value, np.sin(k) / k, rtol=1e-11)


def test_romberg_is_exact_for_cubics_after_one_extrapolation():
    value, _ = romberg(lambda x: 4 * x**3 - x, 0.0, 2.0, rtol=1e-15, atol=1e-15)
    assert value == pytest.approx(14.0, rel=1e-15)


def test_romberg_raises_instead_of_a_silent_answer():
    # sqrt(|x - 1/3|) has a kink Romberg cannot resolve to 1e-15 in 8 levels
    with pytest.raises(RombergError, match="did not reach"):
        romberg(lambda x: np.sqrt(np.abs(x - 1 / 3)), 0.0, 1.0, rtol=1e-15, max_levels=8)


@pytest.mark.parametrize(
    "kwargs", [dict(a=0.0, b=math.inf), dict(rtol=0.0, atol=0.0), dict(rtol=-1.0), dict(min_levels=0)]
)
def test_romberg_rejects_bad_arguments(kwargs):
    args = dict(a=0.0, b=1.0) | kwargs
    with pytest.raises(ValueError):
        romberg(np.cos, **args)


def test_each_stops_every_integral_as_a_call_for_it_alone():
    # integrals of different difficulty: alone, each stops at its own level; in one batch with
    # each=True, each gets the value and error of its own call to the last bit (its samples
    # contiguous: the transpose of a (batch, m) array), not those of the level where all stop
    w = np.array([0.5, 3.0, 9.0, 25.0, 1.0, 60.0, 2.0, 14.0, 0.1])
    alone = [romberg(lambda x, v=v: np.cos(v * x) + x * x, 0.0, 1.5, rtol=1e-11) for v in w]

    def f(x):
        return (np.cos(np.multiply.outer(w, x)) + x * x).T

    value, error = romberg(f, 0.0, 1.5, rtol=1e-11, each=True)
    assert value.tolist() == [float(v) for v, _ in alone]
    assert error.tolist() == [float(e) for _, e in alone]
    together, _ = romberg(f, 0.0, 1.5, rtol=1e-11)  # without: every integral at the last level
    assert together.tolist() != value.tolist()
    np.testing.assert_allclose(together, value, rtol=1e-10)


def test_each_raises_for_the_integrals_that_never_meet_the_tolerance():
    with pytest.raises(RombergError, match="worst relative error"):
        romberg(
            lambda x: np.stack((np.cos(x), np.sqrt(np.abs(x - 1 / 3))), axis=-1),
            0.0,
            1.0,
            1e-15,
            max_levels=8,
            each=True,
        )
