"""Angle wrapping has one home, segplan.model.pose (issue 24): each form against the literal
expression its callers wrote before, bit for bit, and the conventions that tell them apart."""

import math

import numpy as np

from segplan.model.pose import TWO_PI, wrap, wrap_floor, wrap_fmod, wrap_ieee, wrap_scalar


def _angles():
    rng = np.random.default_rng(24)
    edge = [math.pi, -math.pi, 0.0, -0.0, 1e-300, -1e-20, 3 * math.pi, -3 * math.pi, 1e17, -1e17]
    edge += [math.nextafter(math.pi, 0.0), math.nextafter(-math.pi, 0.0), math.nextafter(math.pi, 4.0)]
    near = list(-math.pi + rng.uniform(-1e-15, 1e-15, 200)) + list(math.pi + rng.uniform(-1e-15, 1e-15, 200))
    return [
        float(v) for v in (*rng.uniform(-40.0, 40.0, 20000), *rng.uniform(-1e-15, 1e-15, 200), *edge, *near)
    ]


def test_two_pi_is_the_constant_every_caller_typed():
    assert TWO_PI.hex() == (2.0 * math.pi).hex() == (2 * math.pi).hex()


def test_wrap_ieee_is_math_remainder():
    """The lattice planner's ``math.remainder(a, 2 * math.pi)`` (escape, search) and the paper
    problem's LONGD fallback bound."""
    for a in _angles():
        assert wrap_ieee(a).hex() == math.remainder(a, 2 * math.pi).hex()


def test_wrap_floor_is_the_numpy_remainder_form():
    """The lattice's ``steerable`` screen and its guide: ``np.remainder(a + pi, 2 pi) - pi``,
    on arrays; and ``ompl_heading``'s ``(a + pi) % (2 pi) - pi`` on floats."""
    a = np.array(_angles())
    old = np.remainder(a + math.pi, 2.0 * math.pi) - math.pi
    assert wrap_floor(a).tobytes() == old.tobytes()
    b = a.reshape(1, -1)[:, ::3]  # strided, as a caller's slice
    assert wrap_floor(b).tobytes() == (np.remainder(b + math.pi, 2 * math.pi) - math.pi).tobytes()
    for v in _angles():
        assert float(wrap_floor(v)).hex() == ((v + math.pi) % (2.0 * math.pi) - math.pi).hex()


def test_the_forms_are_different_ideas():
    """Why they were not merged: intervals differ at +-pi, and roundings in the last bit."""
    assert wrap(-math.pi) == math.pi and wrap_scalar(-math.pi) == math.pi and wrap_fmod(-math.pi) == math.pi
    assert wrap_ieee(-math.pi) == -math.pi and wrap_ieee(math.pi) == math.pi
    assert wrap_floor(math.pi) == -math.pi
    angles = _angles()
    assert any(wrap_fmod(a) != wrap_scalar(a) for a in angles)  # fmod is exact, round is not
    assert all(wrap_scalar(a) == wrap(a) for a in angles)  # the fast path: the same operations
