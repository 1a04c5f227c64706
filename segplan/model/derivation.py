"""Formula [2] derived from formula [1] with sympy, step by step, each step checked.

Section "Approximate computation of cost function": "After algebraic manipulations in [1]
(first order binomial Taylor series; average value of integral with a positive weight
function) the cost function can be approximated by [2]". The OCR of [2] is garbled; this
module rebuilds it from [1] and also builds the literal OCR readings, so that the book can
measure every alternative against the exact LONGD.

The route (all in the alpha frame, ``X = d cos(alpha)``, ``t = tan(alpha)``, ``s = x / X``):

1. The cubic is the chord plus a Hermite bump, ``f = t x + g``,
   ``g = X [mbar0 h10(s) + mbar1 h11(s)]``, which vanishes at both ends.
2. Integrals of the bump: ``int g' = 0``, ``int g'^2 = (2 X / 15) Q1`` and
   ``int f''^2 = 4 Q2 / X``, with ``Q1 = mbar0^2 + mbar1^2 - mbar0 mbar1 / 2`` and
   ``Q2 = mbar0^2 + mbar1^2 + mbar0 mbar1``; the mean of ``1 + f'^2`` over the span is
   ``1 / cos^2(alpha) + (2 / 15) Q1``.
3. Rear path: ``1 + f'^2 = sec^2(alpha) (1 + u)``, ``u = cos^2(alpha) (2 t g' + g'^2)``; the
   first-order binomial ``sqrt(1 + u) ~ 1 + u / 2`` gives ``d [1 + cos^2(alpha) Q1 / 15]``.
4. Front excess: the first-order binomial in ``B = L^2 f''^2 / (1 + f'^2)^2`` gives
   ``(L^2 / 2) int f''^2 (1 + f'^2)^(-5/2)``.
5. Mean value with the positive weight ``f''^2``: ``(1 + f'^2)^(-5/2)`` leaves the integral
   at an intermediate value, taken as its value at the mean of ``1 + f'^2`` (step 2).
6. Formula [2]: ``d [1 + k_alpha cos^2(alpha) Q1 / 15]
   + 2 L^2 / (d cos(alpha)) [1 / cos^2(alpha) + (2 / 15) Q1]^(-5/2) Q2``, ``k_alpha`` the
   paper's empirical factor on the rear excess.

Where the OCR's ``5/48`` and ``2/5`` come from: Simpson's rule applied to ``int_0^1 g'^2 ds``
gives exactly ``(5/24) (mbar0^2 + mbar1^2 + (2/5) mbar0 mbar1)``, so the OCR's first term
``d [1 + k 5/48 cos^2(alpha) (mbar0^2 + mbar1^2 + 2/5 mbar0 mbar1)]`` is step 3 with that
integral estimated by Simpson's rule instead of computed exactly (see
:func:`rear_quadrature_readings`; no other classic rule reproduces both numbers).

The OCR's front bracket prints ``+ 1/2 mbar0 mbar1``; step 2 gives ``- 1/2`` (the mean of
``1 + f'^2`` is ``1/cos^2(alpha) + (2/15) Q1``), so we read the ``+`` as a misprint and
keep both signs in :func:`variants` for the measurement. The exponent, illegible in the
OCR, is ``-5/2`` by step 4.

Every public function returns sympy objects and is fast (whole module well under a second).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import sympy as sp

__all__ = [
    "DERIVED_VARIANT",
    "Q1",
    "Q2",
    "Step",
    "alpha",
    "bump",
    "bump_integral_steps",
    "cubic",
    "cubic_steps",
    "d",
    "derivation_steps",
    "formula2",
    "formula2_steps",
    "front_lambdified",
    "front_steps",
    "front_term",
    "hermite_basis",
    "k",
    "L",
    "lambdified",
    "mbar0",
    "mbar1",
    "ocr_steps",
    "rear_lambdified",
    "rear_quadrature_readings",
    "rear_second_order_steps",
    "rear_steps",
    "rear_term",
    "variants",
    "X",
    "x",
]

# -- symbols ---------------------------------------------------------------------------
d, L, X = sp.symbols("d L X", positive=True)
alpha = sp.Symbol("alpha", real=True)
mbar0, mbar1 = sp.symbols("mbar0 mbar1", real=True)
k = sp.Symbol("k_alpha", positive=True)
x, s, t, u, eps = sp.symbols("x s t u epsilon", real=True)
A_, w_ = sp.symbols("A w", positive=True)  # 1 + f'^2 and |f''| as plain symbols
gp_ = sp.Symbol("g'", real=True)  # g'(x) as a plain symbol
#: Undefined functions that *state* a step for display (:attr:`Step.shown`); evaluated by
#: :func:`_concrete` (``f`` the cubic, ``g`` the bump, ``u`` of step 3, ``g'`` of the unit bump).
f_fn, g_fn, u_fn, gp_fn = sp.Function("f"), sp.Function("g"), sp.Function("u"), sp.Function("g'")

#: Quadratic forms of the chord-relative slopes.
Q1 = mbar0**2 + mbar1**2 - sp.Rational(1, 2) * mbar0 * mbar1
Q2 = mbar0**2 + mbar1**2 + mbar0 * mbar1


@dataclass(frozen=True)
class Step:
    """One step of the derivation: ``lhs = rhs``, proved by sympy (``holds``).

    ``lhs`` is what sympy computed (an integral done, a series expanded, ...), ``rhs`` the
    closed form. ``shown``, when given, states the left side with unevaluated operators
    (integrals, derivatives of the undefined ``f``, ``g``) for display; ``relation`` is
    ``"="`` or ``"~"`` (an approximation: a truncated series or a mean value). For ``"="``
    steps ``holds`` also requires that ``shown``, evaluated with the concrete ``f``, ``g``
    (:func:`_concrete`), equals ``lhs``: the displayed statement is checked too. For
    ``"~"`` steps ``holds`` checks the algebra after the approximation (``lhs = rhs``).
    """

    title: str
    lhs: sp.Expr
    rhs: sp.Expr
    holds: bool
    note: str = ""
    shown: sp.Expr | None = None
    relation: str = "="

    def equation(self) -> sp.Eq:
        """The step as an unevaluated ``sympy.Eq`` (for display)."""
        return sp.Eq(self.lhs, self.rhs, evaluate=False)

    def latex(self) -> str:
        """LaTeX of the step as stated: ``shown`` (or ``lhs``), ``=`` or ``\\approx``, ``rhs``."""
        left = self.lhs if self.shown is None else self.shown
        return sp.latex(left) + (r" \approx " if self.relation == "~" else " = ") + sp.latex(self.rhs)


def _proved(lhs, rhs) -> bool:
    diff = sp.expand(lhs - rhs)
    return diff == 0 or sp.cancel(diff) == 0 or sp.simplify(diff) == 0


def _concrete(expr) -> sp.Expr:
    """Evaluate a stated step: the undefined ``f``, ``g``, ``u``, ``g'`` replaced and ``doit``."""
    g1 = sp.diff(bump(), x)
    h10, h11 = hermite_basis()
    unit = mbar0 * sp.diff(h10, s) + mbar1 * sp.diff(h11, s)
    out = sp.sympify(expr).replace(f_fn, sp.Lambda(x, cubic())).replace(g_fn, sp.Lambda(x, bump()))
    out = out.replace(u_fn, sp.Lambda(x, (2 * t * g1 + g1**2) / (1 + t**2)))  # u = cos^2 (2 t g' + g'^2)
    return _in_t(out.replace(gp_fn, sp.Lambda(s, unit)), keep_x=True).doit()


def _in_t(expr, keep_x: bool = False) -> sp.Expr:
    """Trigonometric functions of alpha in ``t = tan(alpha)``, and ``X = d cos(alpha)``."""
    sec = sp.sqrt(1 + t**2)
    out = sp.sympify(expr).subs({sp.sec(alpha): sec, sp.cos(alpha): 1 / sec, sp.tan(alpha): t})
    return out if keep_x else out.subs(X, d / sec)


def _step(title: str, lhs, rhs, note: str = "", shown=None, relation: str = "=") -> Step:
    holds = _proved(lhs, rhs)
    if holds and shown is not None and relation == "=":
        holds = _proved(_in_t(_concrete(shown)), _in_t(lhs))
    return Step(title, lhs, rhs, holds, note, shown, relation)


# -- step 1: the cubic -----------------------------------------------------------------
def hermite_basis() -> tuple[sp.Expr, sp.Expr]:
    """Hermite basis on ``s`` in ``[0, 1]`` with zero end values: ``h10``, ``h11``."""
    return s**3 - 2 * s**2 + s, s**3 - s**2


def bump() -> sp.Expr:
    """The bump ``g(x) = X [mbar0 h10(x/X) + mbar1 h11(x/X)]`` over the chord."""
    h10, h11 = hermite_basis()
    return sp.expand(X * (mbar0 * h10 + mbar1 * h11).subs(s, x / X))


def cubic() -> sp.Expr:
    """The union's cubic in the alpha frame, ``f(x) = t x + g(x)``, ``t = tan(alpha)``."""
    return t * x + bump()


def cubic_steps() -> list[Step]:
    """The cubic joins ``(0, 0)`` to ``(X, X t)`` with end slopes ``t + mbar_i``."""
    f = cubic()
    fp = sp.diff(f, x)
    return [
        _step("f(0) = 0", f.subs(x, 0), sp.S.Zero, shown=f_fn(0)),
        _step("f(X) = X tan(alpha) = d sin(alpha)", f.subs(x, X), X * t, shown=f_fn(X)),
        _step(
            "f'(0) = tan(alpha) + mbar0",
            fp.subs(x, 0),
            t + mbar0,
            shown=sp.Subs(sp.Derivative(f_fn(x), x), x, 0),
        ),
        _step(
            "f'(X) = tan(alpha) + mbar1",
            fp.subs(x, X),
            t + mbar1,
            shown=sp.Subs(sp.Derivative(f_fn(x), x), x, X),
        ),
    ]


# -- step 2: integrals of the bump -----------------------------------------------------
def bump_integral_steps() -> list[Step]:
    """The Hermite integrals used by [2], each computed by sympy over ``[0, X]``."""
    g = bump()
    gp, gpp = sp.diff(g, x), sp.diff(g, x, 2)
    fp = t + gp
    return [
        _step(
            "int g' dx = 0 (the bump vanishes at both ends)",
            sp.integrate(gp, (x, 0, X)),
            sp.S.Zero,
            shown=sp.Integral(sp.Derivative(g_fn(x), x), (x, 0, X)),
        ),
        _step(
            "int g'^2 dx = (2 X / 15) Q1",
            sp.integrate(gp**2, (x, 0, X)),
            2 * X * Q1 / 15,
            shown=sp.Integral(sp.Derivative(g_fn(x), x) ** 2, (x, 0, X)),
        ),
        _step(
            "int f''^2 dx = 4 Q2 / X",
            sp.integrate(gpp**2, (x, 0, X)),
            4 * Q2 / X,
            shown=sp.Integral(sp.Derivative(f_fn(x), (x, 2)) ** 2, (x, 0, X)),
        ),
        _step(
            "mean of 1 + f'^2 = 1 + tan^2(alpha) + (2/15) Q1",
            1 + sp.integrate(fp**2, (x, 0, X)) / X,
            1 + t**2 + 2 * Q1 / 15,
            shown=sp.Mul(1 / X, sp.Integral(1 + sp.Derivative(f_fn(x), x) ** 2, (x, 0, X)), evaluate=False),
        ),
    ]


# -- step 3: the rear path (first-order binomial) --------------------------------------
def rear_steps() -> list[Step]:
    """First-order binomial expansion of ``sqrt(1 + f'^2)`` about the chord's slope."""
    gp = gp_  # g'(x) as a plain symbol
    c2 = 1 / (1 + t**2)  # cos^2(alpha)
    sec = sp.sqrt(1 + t**2)
    series = sp.series(sp.sqrt(1 + u), u, 0, 2).removeO()
    g1 = sp.diff(bump(), x)
    u_of_x = c2 * (2 * t * g1 + g1**2)
    rear = sp.integrate(sp.expand(sec * (1 + u_of_x / 2)), (x, 0, X)).subs(X, d / sec)  # X = d cos(alpha)
    return [
        _step(
            "1 + f'^2 = sec^2(alpha) (1 + u), u = cos^2(alpha) (2 t g' + g'^2)",
            1 + (t + gp) ** 2,
            (1 + c2 * (2 * t * gp + gp**2)) / c2,
        ),
        _step(
            "sqrt(1 + u) = 1 + u/2 + O(u^2)  (first-order binomial)",
            series,
            1 + u / 2,
            shown=sp.sqrt(1 + u),
            relation="~",
        ),
        _step(
            "int sec(alpha) (1 + u/2) dx = d [1 + cos^2(alpha) Q1 / 15]",
            rear,
            d * (1 + c2 * Q1 / 15),
            "integrated by sympy with the bump's g'; X sec(alpha) = d",
            shown=sp.Integral(sp.sec(alpha) * (1 + u_fn(x) / 2), (x, 0, X)),
        ),
    ]


def rear_second_order_steps() -> list[Step]:
    """The expansion consistent to second order in the bump gives ``cos^4`` instead of ``cos^2``.

    The first-order binomial drops the ``u^2 / 8`` term, which holds ``4 t^2 g'^2``, of the
    same order as ``g'^2``. The Taylor series of ``sqrt(1 + (t + eps g')^2)`` in ``eps`` has
    the quadratic coefficient ``cos^3(alpha) / 2``, so the rear path becomes
    ``d [1 + cos^4(alpha) Q1 / 15]``: the binomial form overestimates the rear excess by
    the factor ``1 / cos^2(alpha)``, which the paper's ``k_alpha < 1`` (depending on alpha)
    compensates.
    """
    gp = gp_
    sec = sp.sqrt(1 + t**2)
    series = sp.series(sp.sqrt(1 + (t + eps * gp) ** 2), eps, 0, 3).removeO()
    expected = sec + eps * t * gp / sec + eps**2 * gp**2 / (2 * sec**3)
    g1 = sp.diff(bump(), x)
    rear = sp.integrate(sp.expand(expected.subs({eps: 1, gp: g1})), (x, 0, X)).subs(X, d / sec)
    return [
        _step(
            "sqrt(1 + (t + eps g')^2) to O(eps^2)",
            series,
            expected,
            shown=sp.sqrt(1 + (t + eps * gp) ** 2),
            relation="~",
        ),
        _step(
            "int sqrt(1 + f'^2) dx ~ d [1 + cos^4(alpha) Q1 / 15]",
            rear,
            d * (1 + Q1 / (15 * (1 + t**2) ** 2)),
            shown=sp.Integral(sp.sqrt(1 + sp.Derivative(f_fn(x), x) ** 2), (x, 0, X)),
            relation="~",
        ),
    ]


# -- steps 4-5: the front-wheel excess ---------------------------------------------------
def front_steps() -> list[Step]:
    """First-order binomial in ``B = L^2 f''^2 / A^2``, then the weighted mean value."""
    integrand = sp.sqrt(A_ + L**2 * w_**2 / A_**2)  # A = 1 + f'^2, w = |f''|
    series = sp.series(integrand, L, 0, 3).removeO()
    abar = 1 + t**2 + 2 * Q1 / 15  # mean of A (step 2)
    int_fpp2 = sp.integrate(sp.diff(bump(), x, 2) ** 2, (x, 0, X))
    sec = sp.sqrt(1 + t**2)
    front = (L**2 / 2 * abar ** sp.Rational(-5, 2) * int_fpp2).subs(X, d / sec)
    closed = 2 * L**2 / (d / sec) * (1 + t**2 + 2 * Q1 / 15) ** sp.Rational(-5, 2) * Q2
    return [
        _step(
            "sqrt(A + L^2 f''^2 / A^2) = sqrt(A) + (L^2 / 2) f''^2 A^(-5/2) + O(L^4)",
            series,
            sp.sqrt(A_) + L**2 * w_**2 / (2 * A_ ** sp.Rational(5, 2)),
            shown=integrand,
            relation="~",
        ),
        _step(
            "(L^2/2) int f''^2 A^(-5/2) dx ~ (L^2/2) mean(A)^(-5/2) int f''^2 dx = "
            "2 L^2 / (d cos(alpha)) [1/cos^2(alpha) + (2/15) Q1]^(-5/2) Q2",
            front.subs(X, d / sec),
            closed,
            "mean-value theorem with the positive weight f''^2; the intermediate value of A "
            "is taken at its mean over the span",
            shown=L**2
            / 2
            * sp.Integral(
                sp.Derivative(f_fn(x), (x, 2)) ** 2
                * (1 + sp.Derivative(f_fn(x), x) ** 2) ** sp.Rational(-5, 2),
                (x, 0, X),
            ),
            relation="~",
        ),
    ]


# -- step 6: formula [2] ----------------------------------------------------------------
def rear_term(rule: str = "exact") -> sp.Expr:
    """The rear excess over ``d`` in [2], before ``k_alpha``, in (alpha, mbar0, mbar1).

    ``rule="exact"``: ``cos^2(alpha) Q1 / 15`` (step 3). ``rule="simpson"``: the OCR's
    ``(5/48) cos^2(alpha) (mbar0^2 + mbar1^2 + (2/5) mbar0 mbar1)``.
    ``rule="second_order"``: ``cos^4(alpha) Q1 / 15``.
    """
    c = sp.cos(alpha)
    if rule == "exact":
        return c**2 * Q1 / 15
    if rule == "simpson":
        return sp.Rational(5, 48) * c**2 * (mbar0**2 + mbar1**2 + sp.Rational(2, 5) * mbar0 * mbar1)
    if rule == "second_order":
        return c**4 * Q1 / 15
    raise ValueError(f"rule must be 'exact', 'simpson' or 'second_order', got {rule!r}")


def front_term(cross: sp.Expr | str = "-1/2", exponent: sp.Expr | str = "-5/2") -> sp.Expr:
    """The front excess of [2] with a chosen cross coefficient and exponent.

    ``2 L^2 / (d cos a) [1/cos^2 a + (2/15)(mbar0^2 + mbar1^2 + cross mbar0 mbar1)]^exponent Q2``;
    the derivation gives ``cross = -1/2``, ``exponent = -5/2``; the OCR prints ``+1/2`` and
    an illegible exponent.
    """
    c = sp.cos(alpha)
    q = mbar0**2 + mbar1**2 + sp.Rational(cross) * mbar0 * mbar1
    return 2 * L**2 / (d * c) * (1 / c**2 + sp.Rational(2, 15) * q) ** sp.Rational(exponent) * Q2


def formula2(rule: str = "exact", cross: sp.Expr | str = "-1/2", exponent: sp.Expr | str = "-5/2") -> sp.Expr:
    """Formula [2] as a sympy expression in (d, alpha, mbar0, mbar1, L, k_alpha).

    The defaults give the derived closed form; other arguments give the OCR-literal
    alternatives (see :func:`variants`).
    """
    return d * (1 + k * rear_term(rule)) + front_term(cross, exponent)


def formula2_steps() -> list[Step]:
    """The derived [2] equals rear (step 3, rear excess scaled by k) plus front (steps 4-5)."""
    c2 = 1 / (1 + t**2)
    sec = sp.sqrt(1 + t**2)
    assembled = (
        d * (1 + k * c2 * Q1 / 15) + 2 * L**2 * sec / d * (1 / c2 + 2 * Q1 / 15) ** sp.Rational(-5, 2) * Q2
    )
    in_alpha = formula2().subs(sp.cos(alpha), 1 / sec)  # cos(alpha) = 1 / sqrt(1 + tan^2)
    return [
        _step(
            "formula [2] (derived)",
            in_alpha,
            assembled,
            "k_alpha scales the rear excess",
            shown=sp.Symbol("LONGD"),
            relation="~",
        )
    ]


# -- the OCR's 5/48 and 2/5 -----------------------------------------------------------
def rear_quadrature_readings() -> dict[str, sp.Expr]:
    """``int_0^1 g'(s)^2 ds`` (``g'`` of the unit bump) exactly and by classic quadrature rules.

    Only Simpson's rule gives ``(5/24)(mbar0^2 + mbar1^2 + (2/5) mbar0 mbar1)``, whose half
    is the OCR's ``5/48 (mbar0^2 + mbar1^2 + 2/5 mbar0 mbar1)``.
    """
    h10, h11 = hermite_basis()
    gp = mbar0 * sp.diff(h10, s) + mbar1 * sp.diff(h11, s)
    G = sp.Lambda(s, gp**2)
    half, third, quarter = sp.Rational(1, 2), sp.Rational(1, 3), sp.Rational(1, 4)
    r = sp.sqrt(3) / 6
    rules = {
        "exact": sp.integrate(gp**2, (s, 0, 1)),
        "trapezoid": (G(0) + G(1)) / 2,
        "midpoint": G(half),
        "simpson": (G(0) + 4 * G(half) + G(1)) / 6,
        "simpson_3_8": (G(0) + 3 * G(third) + 3 * G(2 * third) + G(1)) / 8,
        "gauss_legendre_2": (G(half - r) + G(half + r)) / 2,
        "boole": (7 * G(0) + 32 * G(quarter) + 12 * G(half) + 32 * G(3 * quarter) + 7 * G(1)) / 90,
    }
    return {name: sp.factor(sp.expand(v)) for name, v in rules.items()}


def ocr_steps() -> list[Step]:
    """Simpson's rule on ``int g'^2`` reproduces the OCR's 5/48 and 2/5 exactly."""
    readings = rear_quadrature_readings()
    ocr = sp.Rational(5, 24) * (mbar0**2 + mbar1**2 + sp.Rational(2, 5) * mbar0 * mbar1)
    c2 = sp.cos(alpha) ** 2
    half = sp.Rational(1, 2)
    simpson = sp.Mul(
        sp.Rational(1, 6), gp_fn(0) ** 2 + 4 * gp_fn(half) ** 2 + gp_fn(1) ** 2, evaluate=False
    )  # Simpson's rule on int_0^1 g'(s)^2 ds
    return [
        _step(
            "Simpson: int_0^1 g'^2 ds ~ (5/24)(mbar0^2 + mbar1^2 + (2/5) mbar0 mbar1)",
            readings["simpson"],
            ocr,
            shown=simpson,
        ),
        _step(
            "rear excess (cos^2(alpha)/2) x Simpson = OCR's 5/48 cos^2(alpha)(...)",
            c2 / 2 * readings["simpson"],
            rear_term("simpson"),
            shown=sp.Mul(c2 / 2, simpson, evaluate=False),
        ),
        _step(
            "Simpson - exact = (3/40)(mbar0 + mbar1)^2 >= 0 (g'^2 is a quartic: Simpson is not exact)",
            readings["simpson"] - readings["exact"],
            sp.Rational(3, 40) * (mbar0 + mbar1) ** 2,
            "the OCR's first term overestimates the binomial rear excess unless mbar0 = -mbar1",
            shown=simpson - sp.Integral(gp_fn(s) ** 2, (s, 0, 1)),
        ),
    ]


def variants() -> dict[str, sp.Expr]:
    """Formula [2] and the OCR-literal alternatives, keyed by a short name.

    Names are ``"<rear>|cross=<c>|exp=<e>"``: rear rule ``exact`` (derived), ``simpson``
    (OCR's 5/48, 2/5) or ``second_order``; cross coefficient ``-1/2`` (derived) or ``+1/2``
    (OCR); exponent ``-3/2``, ``-2`` or ``-5/2`` (derived).
    """
    out = {}
    for rule in ("exact", "simpson", "second_order"):
        for cross in (sp.Rational(-1, 2), sp.Rational(1, 2)):
            for exponent in (sp.Rational(-3, 2), sp.Integer(-2), sp.Rational(-5, 2)):
                out[f"{rule}|cross={cross}|exp={exponent}"] = formula2(rule, cross, exponent)
    return out


DERIVED_VARIANT = "exact|cross=-1/2|exp=-5/2"


@cache
def derivation_steps() -> tuple[Step, ...]:
    """Every step of the derivation in order (cubic, integrals, rear, front, [2], OCR); cached."""
    return (
        *cubic_steps(),
        *bump_integral_steps(),
        *rear_steps(),
        *rear_second_order_steps(),
        *front_steps(),
        *formula2_steps(),
        *ocr_steps(),
    )


@cache
def lambdified(name: str = DERIVED_VARIANT):
    """A numpy function ``(d, alpha, mbar0, mbar1, L, k_alpha) -> LONGD`` of a variant."""
    expr = variants()[name]
    return sp.lambdify((d, alpha, mbar0, mbar1, L, k), expr, modules="numpy")


@cache
def rear_lambdified(rule: str = "exact"):
    """A numpy function ``(alpha, mbar0, mbar1) -> rear excess`` of [2] before ``k_alpha``.

    See :func:`rear_term` for the rules (``"exact"``, ``"simpson"``, ``"second_order"``).
    """
    return sp.lambdify((alpha, mbar0, mbar1), rear_term(rule), modules="numpy")


@cache
def front_lambdified(cross: str = "-1/2", exponent: str = "-5/2"):
    """A numpy function ``(d, alpha, mbar0, mbar1, L) -> front excess`` of [2].

    ``cross`` and ``exponent`` are rationals written as strings (e.g. ``"1/2"``,
    ``"-11/4"``); see :func:`front_term`.
    """
    return sp.lambdify((d, alpha, mbar0, mbar1, L), front_term(cross, exponent), modules="numpy")
