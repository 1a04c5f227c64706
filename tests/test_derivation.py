"""The sympy derivation of formula [2] and its agreement with the library's closed form."""

import numpy as np
import pytest
import sympy as sp

from segplan.model import derivation as dv
from segplan.model.cost import approx_terms, k_alpha, longd_approx_intrinsic
from segplan.model.union import chord_slopes


def test_every_step_is_proved():
    steps = dv.derivation_steps()
    assert len(steps) >= 15
    failed = [s.title for s in steps if not s.holds]
    assert not failed, failed


def test_bump_integrals_by_direct_quadrature():
    # independent of sympy: the Hermite integrals by numpy on a fine grid (Simpson, exact
    # up to rounding for these polynomials)
    rng = np.random.default_rng(0)
    m0, m1 = rng.normal(size=2)
    s = np.linspace(0.0, 1.0, 2001)
    gp = m0 * (3 * s**2 - 4 * s + 1) + m1 * (3 * s**2 - 2 * s)
    gpp = m0 * (6 * s - 4) + m1 * (6 * s - 2)
    w = np.full(s.size, 2.0)
    w[1::2], w[0], w[-1] = 4.0, 1.0, 1.0
    w /= 3.0 * (s.size - 1)
    assert w @ gp**2 == pytest.approx(2 / 15 * (m0**2 + m1**2 - m0 * m1 / 2), rel=1e-12)
    assert w @ gpp**2 == pytest.approx(4 * (m0**2 + m1**2 + m0 * m1), rel=1e-12)
    # the same numbers from segplan.model.derivation's closed forms (unit chord, X = 1)
    steps = {st.title: st for st in dv.bump_integral_steps()}
    values = {dv.X: 1, dv.mbar0: m0, dv.mbar1: m1, dv.t: 0}
    assert float(steps["int g'^2 dx = (2 X / 15) Q1"].rhs.subs(values)) == pytest.approx(w @ gp**2, rel=1e-12)
    assert float(steps["int f''^2 dx = 4 Q2 / X"].rhs.subs(values)) == pytest.approx(w @ gpp**2, rel=1e-12)
    # and from the bump itself, differentiated by sympy and sampled on the grid
    g1 = sp.lambdify(dv.x, sp.diff(dv.bump(), dv.x).subs({dv.X: 1, dv.mbar0: m0, dv.mbar1: m1}))
    assert np.allclose(g1(s), gp, rtol=0, atol=1e-12)


def test_simpson_reproduces_the_ocr_constants_and_nothing_else_does():
    readings = dv.rear_quadrature_readings()
    ocr = sp.Rational(5, 24) * (dv.mbar0**2 + dv.mbar1**2 + sp.Rational(2, 5) * dv.mbar0 * dv.mbar1)
    hits = [name for name, expr in readings.items() if sp.simplify(expr - ocr) == 0]
    assert hits == ["simpson"]
    # Boole's rule is exact for the quartic g'^2; Simpson is not
    assert sp.simplify(readings["boole"] - readings["exact"]) == 0


def test_variants_cover_the_ocr_alternatives():
    v = dv.variants()
    assert len(v) == 18
    assert dv.DERIVED_VARIANT in v
    assert sp.simplify(v[dv.DERIVED_VARIANT] - dv.formula2()) == 0
    for rear in ("exact", "simpson", "second_order"):
        for cross in ("-1/2", "1/2"):
            for exponent in ("-3/2", "-2", "-5/2"):
                assert f"{rear}|cross={cross}|exp={exponent}" in v
    with pytest.raises(ValueError, match="rule"):
        dv.rear_term("trapezoid")


def _random_cases(n, seed):
    rng = np.random.default_rng(seed)
    d = rng.uniform(0.5, 30.0, n)
    L = rng.uniform(0.2, 3.0, n)
    phi0 = rng.uniform(-1.3, 1.3, n)
    phi1 = rng.uniform(-1.3, 1.3, n)
    lo = -np.pi / 2 - np.minimum(np.minimum(phi0, phi1), 0.0)
    hi = np.pi / 2 - np.maximum(np.maximum(phi0, phi1), 0.0)
    keep = hi - lo > 0.05
    alpha = lo + (hi - lo) * rng.uniform(0.02, 0.98, n)
    return d[keep], phi0[keep], phi1[keep], alpha[keep], L[keep]


def test_longd_approx_equals_the_sympy_expression():
    d, phi0, phi1, alpha, L = _random_cases(4000, seed=7)
    f = dv.lambdified()
    m0, m1 = chord_slopes(phi0, phi1, alpha)
    expected = f(d, alpha, m0, m1, L, k_alpha(alpha))
    got = longd_approx_intrinsic(d, phi0, phi1, alpha, L)
    np.testing.assert_allclose(got, expected, rtol=1e-12)
    # and the scalar path (math module) agrees too
    for i in range(0, d.size, 97):
        assert longd_approx_intrinsic(d[i], phi0[i], phi1[i], alpha[i], L[i]) == pytest.approx(
            expected[i], rel=1e-12
        )


def test_approx_terms_are_the_two_terms_of_the_sympy_expression():
    d, phi0, phi1, alpha, L = _random_cases(2000, seed=8)
    f = dv.lambdified()
    m0, m1 = chord_slopes(phi0, phi1, alpha)
    rear, front = approx_terms(d, phi0, phi1, alpha, L)
    np.testing.assert_allclose(d + front, f(d, alpha, m0, m1, L, 0.0), rtol=1e-12)
    np.testing.assert_allclose(d * rear, f(d, alpha, m0, m1, L, 1.0) - f(d, alpha, m0, m1, L, 0.0), rtol=1e-9)


def test_explicit_k_is_used():
    d, phi0, phi1, alpha, L = _random_cases(500, seed=9)
    f = dv.lambdified()
    m0, m1 = chord_slopes(phi0, phi1, alpha)
    np.testing.assert_allclose(
        longd_approx_intrinsic(d, phi0, phi1, alpha, L, k=0.5), f(d, alpha, m0, m1, L, 0.5), rtol=1e-12
    )


def test_term_functions_are_the_terms_of_the_formula():
    d, phi0, phi1, alpha, L = _random_cases(1000, seed=10)
    m0, m1 = chord_slopes(phi0, phi1, alpha)
    rear, front = approx_terms(d, phi0, phi1, alpha, L)
    np.testing.assert_allclose(dv.rear_lambdified()(alpha, m0, m1), rear, rtol=1e-12)
    np.testing.assert_allclose(dv.front_lambdified()(d, alpha, m0, m1, L), front, rtol=1e-12)
    # every variant is d (1 + k rear) + front with its own rule, cross and exponent
    for name in ("simpson|cross=1/2|exp=-3/2", "second_order|cross=-1/2|exp=-2"):
        rule, cross, exponent = (part.split("=")[-1] for part in name.split("|"))
        r = dv.rear_lambdified(rule)(alpha, m0, m1)
        f = dv.front_lambdified(cross, exponent)(d, alpha, m0, m1, L)
        np.testing.assert_allclose(
            d * (1 + 0.7 * r) + f, dv.lambdified(name)(d, alpha, m0, m1, L, 0.7), rtol=1e-12
        )
    # the OCR-literal Simpson rear term at one point, by hand
    a, b, c = 0.3, 0.2, -0.1
    hand = 5 / 48 * np.cos(a) ** 2 * (b**2 + c**2 + 2 / 5 * b * c)
    assert dv.rear_lambdified("simpson")(a, b, c) == pytest.approx(hand, rel=1e-14)
    # a general rational exponent
    e = dv.front_lambdified("-1/2", "-11/4")(2.0, a, b, c, 1.0)
    q1, q2 = b * b + c * c - b * c / 2, b * b + c * c + b * c
    assert e == pytest.approx(
        2 / (2.0 * np.cos(a)) * (1 / np.cos(a) ** 2 + 2 * q1 / 15) ** -2.75 * q2, rel=1e-14
    )


def test_displayed_statements_are_checked_too():
    steps = dv.derivation_steps()
    assert all(s.shown is not None for s in steps if "sec^2(alpha) (1 + u)" not in s.title)
    assert {s.relation for s in steps} == {"=", "~"}
    for s in steps:
        tex = s.latex()
        assert (r"\approx" in tex) == (s.relation == "~")
    # a wrong statement for a right lhs = rhs is caught
    g = dv.bump()
    lhs = sp.integrate(sp.diff(g, dv.x) ** 2, (dv.x, 0, dv.X))
    wrong = sp.Integral(sp.Derivative(dv.g_fn(dv.x), dv.x), (dv.x, 0, dv.X))  # g', not g'^2
    right = sp.Integral(sp.Derivative(dv.g_fn(dv.x), dv.x) ** 2, (dv.x, 0, dv.X))
    assert dv._step("t", lhs, 2 * dv.X * dv.Q1 / 15, shown=right).holds
    assert not dv._step("t", lhs, 2 * dv.X * dv.Q1 / 15, shown=wrong).holds
