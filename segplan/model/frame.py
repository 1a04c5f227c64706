"""The optimal reference system: the alpha frame whose cubic minimises LONGD.

Section "Optimal Reference System": every alpha frame gives a different cubic between
the same two nodes; the problem is to find ``alpha_0`` minimising ``LONGD(alpha)`` (the
length [1] of the front-wheel path).

Exact algorithm ("Exact Algorithm"): the paper's safeguarded secant method on
``d LONGD / d tan(alpha) = 0``, global over the feasible interval, in
:mod:`segplan.model.frame_exact` (:func:`segplan.model.frame_exact.exact_alpha_intrinsic`).

Heuristic algorithm ("Heuristic Algorithm"): closed forms, see :func:`heuristic_alpha`.
Case a (intrinsic slopes of opposite signs, a C-shaped union): the frame minimising the
area between trajectory and chord, ``tan(alpha) = (1/m0 + 1/m1) / 2`` in our convention
(chord at ``+alpha``); that frame makes the union a parabola, and it is always a
stationary point of LONGD(alpha) (:func:`segplan.model.frame_exact.parabola_alpha`). Case b
(same signs, an S-shaped union): the paper's formula was never printed; ours is fitted to
exact optima by :func:`segplan.fit.heuristic.fit_heuristic` and its coefficients are read
from the data stored with the package (:data:`HEURISTIC_FIT`, via
:mod:`segplan.model.constants`). :func:`segplan.studies.frames.heuristic_error_study` measures
both against the exact optimum.
"""

from __future__ import annotations

import functools
import itertools
import math
from typing import NamedTuple

import numpy as np

from . import constants
from .frame_exact import exact_alpha_intrinsic, mbar_max, parabola_alpha
from .pose import HALF_PI, alpha_interval, check_length, intrinsic

__all__ = [
    "HEURISTIC_FIT",
    "HeuristicFit",
    "case_b_alpha",
    "heuristic_alpha",
    "heuristic_coefficients",
    "heuristic_features",
    "inside",
    "optimal_alpha",
    "optimal_alpha_intrinsic",
]


# -- the case-b formula's coefficients ------------------------------------------------
class HeuristicFit(NamedTuple):
    """Coefficients of the case-b formula (:func:`case_b_alpha`).

    Attributes
    ----------
    coef : ndarray
        ``c_ijk`` in the order of :meth:`exponents`.
    degree : int
        Total degree of the polynomial in ``(s, q, l)``, ``q`` counting twice.
    phi_max : float
        Largest heading of the fit (radians); headings are clamped to it.
    log_ratio_range : tuple of float
        ``ln(d/L)`` range of the fit; ``ln(d/L)`` is clamped to it.
    n_problems : int
        Number of exact optima fitted.
    rms_z : float
        Weighted RMS residual of the logit.
    """

    coef: np.ndarray
    degree: int
    phi_max: float
    log_ratio_range: tuple[float, float]
    n_problems: int
    rms_z: float

    @classmethod
    def from_values(cls, values) -> HeuristicFit:
        """The fit of a ``"heuristic_frame"`` entry of the constants (the data file's form)."""
        return cls(
            np.array(values["coef"], dtype=float),
            int(values["degree"]),
            float(values["phi_max"]),
            (float(values["log_ratio_range"][0]), float(values["log_ratio_range"][1])),
            int(values["n_problems"]),
            float(values["rms_z"]),
        )

    def exponents(self) -> list[tuple[int, int, int]]:
        """``(i, j, k)`` of the monomials ``s^i q^j l^k``."""
        return _exponents(self.degree)

    def features(self, phi0, phi1, ell):
        """Monomials ``s^i q^j l^k`` (last axis) of ``s = (phi0 + phi1)/2``, ``q = ((phi0 - phi1)/2)^2``."""
        return _features(phi0, phi1, ell, self.degree)


def _exponents(degree):
    return list(_exponent_table(degree)[0])


@functools.cache
def _exponent_table(degree):
    """``(i, j, k)`` tuples and the index arrays of their ``i``, ``j`` and ``k`` (cached)."""
    table = tuple(
        (i, j, k)
        for i, j, k in itertools.product(range(degree + 1), range(degree // 2 + 1), range(degree + 1))
        if i + 2 * j + k <= degree
    )
    index = np.array(table, dtype=np.intp).reshape(-1, 3)
    return table, index[:, 0], index[:, 1], index[:, 2]


def heuristic_features(phi0, phi1, ell, degree):
    """Monomials ``s^i q^j ell^k`` of the case-b formula, ``i + 2 j + k <= degree`` (last axis)."""
    return _features(phi0, phi1, ell, degree)


def _features(phi0, phi1, ell, degree):
    s = 0.5 * (np.asarray(phi0) + np.asarray(phi1))
    q = (0.5 * (np.asarray(phi0) - np.asarray(phi1))) ** 2
    ell = np.asarray(ell)
    # every power once, then the monomials ``s**i * q**j * ell**k`` by indexing: the same
    # products in the same order as one expression per monomial, without its 3 x 34 powers
    # (the powers stacked along a first axis, so that indexing copies whole rows, and the
    # monomials moved to the last axis in one copy at the end: about 1.2x faster)
    _, i, j, k = _exponent_table(degree)
    sp = np.stack([s**n for n in range(degree + 1)])
    qp = np.stack([q**n for n in range(degree // 2 + 1)])
    ep = np.stack([ell**n for n in range(degree + 1)])
    return np.ascontiguousarray(np.moveaxis(sp[i] * qp[j] * ep[k], 0, -1))


# -- heuristic algorithm ----------------------------------------------------------------
def _stored_fit() -> HeuristicFit:
    fit = HeuristicFit.from_values(constants.heuristic_frame())
    fit.coef.flags.writeable = False
    return fit


#: The case-b coefficients stored with the package, read once at import (an immutable value:
#: a read-only array in a tuple). Fitted by :func:`segplan.fit.heuristic.fit_heuristic` with
#: its defaults (396 exact optima) and written to the data file by ``python -m segplan.fit``.
HEURISTIC_FIT = _stored_fit()


def _fit_terms(fit: HeuristicFit) -> tuple[tuple[float, int, int, int], ...]:
    """``(c_ijk, i, j, k)`` of a fit as plain Python numbers (the scalar path's form)."""
    return tuple((c, *e) for c, e in zip(fit.coef.tolist(), fit.exponents(), strict=True))


#: :data:`HEURISTIC_FIT`'s terms, for the scalar path (another fit's are made per call).
_HEURISTIC_TERMS = _fit_terms(HEURISTIC_FIT)


def heuristic_coefficients() -> HeuristicFit:
    """The case-b coefficients stored with the package: :data:`HEURISTIC_FIT`.

    Read from the data file at import (:mod:`segplan.model.constants`); no coefficient is
    typed in, and nothing is fitted at run time.
    """
    return HEURISTIC_FIT


def inside(alpha, phi0, phi1, margin=1e-3):
    """Clip ``alpha`` into the feasible interval, ``margin * (hi - lo)`` away from its ends."""
    lo, hi = alpha_interval(phi0, phi1)
    m = margin * (np.asarray(hi) - np.asarray(lo))
    out = np.clip(alpha, lo + m, hi - m)
    return float(out) if np.ndim(out) == 0 else out


def case_b_alpha(phi0, phi1, d_over_L, fit=None):
    """Our closed formula for case b (slopes of the same sign: an S-shaped union).

    The paper fitted a formula to exact optima but never printed it. Ours places alpha
    in the feasible interval ``(lo, hi)`` through a logistic of a polynomial::

        alpha_b = lo + (hi - lo) / (1 + exp(-z)),
        z = sum_ijk c_ijk s^i q^j l^k   (i + 2 j + k <= degree),

    with ``s = (phi0 + phi1) / 2``, ``q = ((phi0 - phi1) / 2)^2`` (symmetric under the
    swap of the two nodes, which leaves LONGD unchanged) and ``l = ln(d / L)``. Headings of
    negative slopes use the mirror symmetry ``alpha(-phi0, -phi1) = -alpha(phi0, phi1)``.
    The coefficients ``c_ijk`` come from :func:`segplan.fit.heuristic.fit_heuristic`; the
    headings and ``l`` are clamped to the fitted box (by default headings to 80 deg,
    d/L in [0.25, 100]), outside which the formula is a constant extrapolation that
    stays inside the interval.

    Vectorised; requires ``phi0 * phi1 >= 0`` (case b, or a zero slope), not both zero.
    """
    fit = HEURISTIC_FIT if fit is None else fit
    phi0, phi1, d_over_L = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (phi0, phi1, d_over_L)))
    sign = np.where(phi0 + phi1 < 0.0, -1.0, 1.0)  # mirror negative slopes
    a0, a1 = sign * phi0, sign * phi1
    lo, hi = alpha_interval(a0, a1)
    c0 = np.clip(a0, 0.0, fit.phi_max)
    c1 = np.clip(a1, 0.0, fit.phi_max)
    ell = np.clip(np.log(d_over_L), *fit.log_ratio_range)
    z = fit.features(c0, c1, ell) @ fit.coef
    alpha = lo + (hi - lo) / (1.0 + np.exp(-np.clip(z, -700.0, 700.0)))
    return sign * alpha


def heuristic_alpha(d, phi0, phi1, L, fit=None, margin=1e-3):
    """The heuristic optimal frame: closed forms, cheap, vectorised.

    Section "Heuristic Algorithm", extended where the paper's case a falls short.

    * Case b, ``sin(phi0) sin(phi1) >= 0`` (S-shaped union, or a zero slope): our fitted
      closed formula :func:`case_b_alpha`.
    * Case a, ``sin(phi0) sin(phi1) < 0`` (C-shaped union): the paper's minimum-area
      frame :func:`segplan.model.frame_exact.parabola_alpha` is always a stationary point of LONGD(alpha)
      and the
      global optimum for most headings, but when one slope is small (|phi| below about
      10-15 deg of 75) LONGD(alpha) has a second, lower minimum that continues case b
      through the zero slope; there the paper's formula loses up to several per cent
      (and its frame runs into the end of the interval as the small slope goes to
      zero). The second candidate is case b's formula with the small heading set to
      zero. Of the two, the frame where the cubic's chord-relative end slopes
      ``max(|mbar0|, |mbar1|)`` are smaller is kept: a parameter-free closed-form rule
      (comparing LONGD by a cheap quadrature fails exactly there, because the paper's
      frame then lies next to the end of the interval where the integrand is sharp).
    * ``phi0 = phi1 = 0``: ``alpha = 0`` (a straight union; every frame is optimal).

    The result is clipped ``margin * (hi - lo)`` inside the feasible interval.

    Accuracy, LONGD of the heuristic frame over the exact optimum's (measured with
    :func:`segplan.studies.frames.heuristic_error_study` and random samples; see the book):
    headings in [-75, 75] deg and d/L in [1, 20], mean 0.006 %, max 0.17 % (the paper's
    case-a formula alone: mean 0.2 %, max 4.7 % on a 2.5 deg grid, up to 11 % for
    slopes of a hundredth of a degree). Also measured: d/L in [0.25, 1] or [20, 100],
    max 0.23 %; headings to +-90 deg, max 0.15 %; one heading in 90-150 deg, max
    0.6 %; d/L in [100, 1000], max 0.4 %. Below d/L = 0.25 (a robot much longer than
    the link) the fit is extrapolated and errors reach 10 %. Always a valid frame.

    Parameters
    ----------
    d, phi0, phi1, L : float or ndarray
        Chord length, intrinsic headings (radians) and robot length, validated by the
        caller (see :func:`optimal_alpha_intrinsic`).
    fit : HeuristicFit, optional
        Case-b coefficients; default :data:`HEURISTIC_FIT`.
    margin : float
        Relative distance kept from the ends of the interval.
    """
    if type(d) is float and type(phi0) is float and type(phi1) is float and type(L) is float:
        return _heuristic_scalar(d / L, phi0, phi1, fit, margin)  # plain floats: the fast path
    if all(np.ndim(v) == 0 for v in (d, phi0, phi1, L)):
        return _heuristic_scalar(float(d) / float(L), float(phi0), float(phi1), fit, margin)
    d, phi0, phi1, L = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (d, phi0, phi1, L)))
    d_over_L = d / L
    sin_prod = np.sin(phi0) * np.sin(phi1)
    case_a = sin_prod < 0.0
    straight = (phi0 == 0.0) & (phi1 == 0.0)
    alpha = np.zeros(d.shape)
    b = ~case_a & ~straight
    if b.any():
        alpha[b] = case_b_alpha(phi0[b], phi1[b], d_over_L[b], fit)
    if case_a.any():
        p0, p1, dl = phi0[case_a], phi1[case_a], d_over_L[case_a]
        a_par = inside(parabola_alpha(p0, p1), p0, p1, margin)  # the paper's case a
        big0 = np.abs(p0) >= np.abs(p1)  # case b's formula with the small slope set to 0
        a_b = case_b_alpha(np.where(big0, p0, 0.0), np.where(big0, 0.0, p1), dl, fit)
        a_b = inside(a_b, p0, p1, margin)
        # keep the frame whose chord-relative end slopes are smaller (the flatter cubic)
        alpha[case_a] = np.where(mbar_max(p0, p1, a_b) < mbar_max(p0, p1, a_par), a_b, a_par)
    alpha = inside(alpha, phi0, phi1, margin)
    return float(alpha) if np.ndim(alpha) == 0 else alpha


def _interval(phi0, phi1):
    """Scalar :func:`segplan.model.pose.alpha_interval`."""
    return -HALF_PI - min(phi0, phi1, 0.0), HALF_PI - max(phi0, phi1, 0.0)


def _inside_scalar(alpha, phi0, phi1, margin):
    lo, hi = _interval(phi0, phi1)
    m = margin * (hi - lo)
    return min(max(alpha, lo + m), hi - m)


def _mbar_scalar(phi0, phi1, alpha):
    t = math.tan(alpha)
    return max(abs(math.tan(phi0 + alpha) - t), abs(math.tan(phi1 + alpha) - t))


def _terms(fit):
    """``(c_ijk, i, j, k)`` of a fit: the stored fit's, made at import, else made now."""
    return _HEURISTIC_TERMS if fit is HEURISTIC_FIT else _fit_terms(fit)


def _case_b_scalar(phi0, phi1, d_over_L, fit):
    """Scalar :func:`case_b_alpha` in plain floats (the same formula, for speed)."""
    sign = -1.0 if phi0 + phi1 < 0.0 else 1.0
    a0, a1 = sign * phi0, sign * phi1
    lo, hi = _interval(a0, a1)
    c0, c1 = min(max(a0, 0.0), fit.phi_max), min(max(a1, 0.0), fit.phi_max)
    ell = min(max(math.log(d_over_L), fit.log_ratio_range[0]), fit.log_ratio_range[1])
    s, q = 0.5 * (c0 + c1), (0.5 * (c0 - c1)) ** 2
    # each power once (the same values as ``s**i`` etc. in the sum; same order of products)
    sp = [s**n for n in range(fit.degree + 1)]
    qp = [q**n for n in range(fit.degree // 2 + 1)]
    ep = [ell**n for n in range(fit.degree + 1)]
    z = 0.0
    for c, i, j, k in _terms(fit):
        z += c * sp[i] * qp[j] * ep[k]
    return sign * (lo + (hi - lo) / (1.0 + math.exp(-min(max(z, -700.0), 700.0))))


def _heuristic_scalar(d_over_L, phi0, phi1, fit, margin):
    """Scalar :func:`heuristic_alpha` (same rules, plain floats)."""
    fit = HEURISTIC_FIT if fit is None else fit
    if phi0 == 0.0 and phi1 == 0.0:
        return _inside_scalar(0.0, phi0, phi1, margin)
    if math.sin(phi0) * math.sin(phi1) >= 0.0:
        return _inside_scalar(_case_b_scalar(phi0, phi1, d_over_L, fit), phi0, phi1, margin)
    tan_par = math.sin(phi0 + phi1) / (2.0 * math.sin(phi0) * math.sin(phi1))  # case a: den != 0
    a_par = _inside_scalar(math.atan(tan_par), phi0, phi1, margin)
    big0 = abs(phi0) >= abs(phi1)
    a_b = _case_b_scalar(phi0 if big0 else 0.0, 0.0 if big0 else phi1, d_over_L, fit)
    a_b = _inside_scalar(a_b, phi0, phi1, margin)
    best = a_b if _mbar_scalar(phi0, phi1, a_b) < _mbar_scalar(phi0, phi1, a_par) else a_par
    return _inside_scalar(best, phi0, phi1, margin)


# -- public entry points ----------------------------------------------------------------
_METHODS = ("heuristic", "exact", "parabola")


def _check_intrinsic(d, phi0, phi1, L):
    arrays = []
    for name, v in zip(("d", "phi0", "phi1", "L"), (d, phi0, phi1, L), strict=True):
        try:
            arr = np.asarray(v, dtype=float)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{name} must be a number or an array of numbers, got {v!r}") from exc
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"{name} must be finite")
        arrays.append(arr)
    d, phi0, phi1, L = np.broadcast_arrays(*arrays)
    if np.any(d <= 0.0):
        raise ValueError("d (chord length) must be > 0: coincident points have no reference system")
    if L.ndim == 0:
        check_length(float(L))
    elif np.any(L <= 0.0):
        raise ValueError("L must be positive and finite")
    lo, hi = alpha_interval(phi0, phi1)
    empty = ~(np.asarray(hi) - np.asarray(lo) > 1e-9)
    if np.any(empty):
        i = np.flatnonzero(np.ravel(empty))[0]
        raise ValueError(
            "no alpha reference system gives a cubic for intrinsic headings "
            f"phi0={math.degrees(np.ravel(phi0)[i]):.3f} deg, phi1={math.degrees(np.ravel(phi1)[i]):.3f} deg "
            "(the spread of {0, phi0, phi1} must be below 180 deg; a goal behind the start needs an "
            "intermediate node)"
        )
    return d, phi0, phi1, L


def _check_scalars(d, phi0, phi1, L):
    """:func:`_check_intrinsic` for plain Python numbers (same messages)."""
    for name, v in zip(("d", "phi0", "phi1", "L"), (d, phi0, phi1, L), strict=True):
        if not math.isfinite(v):
            raise ValueError(f"{name} must be finite")
    if d <= 0.0:
        raise ValueError("d (chord length) must be > 0: coincident points have no reference system")
    check_length(L)
    lo, hi = _interval(phi0, phi1)
    if not hi - lo > 1e-9:
        _check_intrinsic(d, phi0, phi1, L)  # raises with the full message


def optimal_alpha_intrinsic(d, phi0, phi1, L, method="heuristic", **kwargs):
    """Optimal frame angle alpha in intrinsic parameters (vectorised).

    Parameters
    ----------
    d : float or ndarray
        Chord length (> 0).
    phi0, phi1 : float or ndarray
        Intrinsic headings (radians); the feasible interval
        (:func:`segplan.model.pose.alpha_interval`) must be non-empty.
    L : float or ndarray
        Robot length (> 0).
    method : {"heuristic", "exact", "parabola"}
        ``"exact"``: :func:`segplan.model.frame_exact.exact_alpha_intrinsic` (keyword arguments go to it).
        ``"heuristic"``: :func:`heuristic_alpha`. ``"parabola"``: the paper's case-a
        formula alone (:func:`segplan.model.frame_exact.parabola_alpha`), clipped inside the feasible
        interval -
        for studies; wrong in case b.

    Returns
    -------
    float or ndarray
        Radians, strictly inside the feasible interval.

    Raises
    ------
    ValueError
        Non-finite input, ``d <= 0``, ``L <= 0``, an empty feasible interval, or an
        unknown method.
    """
    if method not in _METHODS:
        raise ValueError(f"method must be one of {_METHODS}, got {method!r}")
    if method == "heuristic" and all(isinstance(v, (int, float)) for v in (d, phi0, phi1, L)):
        _check_scalars(d, phi0, phi1, L)
        return heuristic_alpha(d, phi0, phi1, L, **kwargs)
    d, phi0, phi1, L = _check_intrinsic(d, phi0, phi1, L)
    if method == "exact":
        return exact_alpha_intrinsic(d, phi0, phi1, L, **kwargs)
    if method == "parabola":
        return inside(parabola_alpha(phi0, phi1), phi0, phi1)
    return heuristic_alpha(d, phi0, phi1, L, **kwargs)


def optimal_alpha(p0, p1, L, method="heuristic", **kwargs):
    """The optimal reference system of the union of two nodes.

    Section "Optimal Reference System": the alpha frame whose cubic has the least front-
    wheel length LONGD [1]. ``method="exact"`` runs the paper's exact algorithm (a
    safeguarded secant on ``dLONGD/dtan(alpha) = 0``, global over the feasible
    interval); ``method="heuristic"`` (default) the closed forms of
    :func:`segplan.model.frame.heuristic_alpha` (the paper's case a, our fitted case b).

    Parameters
    ----------
    p0, p1 : Pose or (x, y, theta), or arrays of shape (..., 3)
        Start and end nodes.
    L : float or ndarray
        Robot length (> 0).
    method : {"heuristic", "exact", "parabola"}

    Returns
    -------
    float or ndarray
        ``alpha`` in radians, strictly inside the interval where the cubic exists; use it
        in :class:`segplan.Union` and :func:`segplan.longd_exact`.

    Raises
    ------
    ValueError
        Malformed or non-finite poses, coincident points, ``L <= 0``, or headings for
        which no alpha gives a cubic (e.g. a goal behind the start).
    """
    geo = intrinsic(p0, p1)
    return optimal_alpha_intrinsic(geo.d, geo.phi0, geo.phi1, L, method=method, **kwargs)
