"""Fitting and measuring the heuristic optimal reference system.

Section "Optimal Reference System", "Heuristic Algorithm", case b: "A simple closed
formula has been developed, which interpolates optimal values computed exactly." The
paper never printed it; :func:`fit_heuristic` builds ours from exact optima
(:func:`segplan.frame.exact_alpha_intrinsic`) by weighted least squares, and
:func:`heuristic_error_study` measures any heuristic against the exact optimum.
"""

from __future__ import annotations

import functools
import itertools
import math
from typing import NamedTuple

import numpy as np

from .pose import alpha_interval

__all__ = ["HeuristicFit", "fit_heuristic", "heuristic_error_study"]


class HeuristicFit(NamedTuple):
    """Coefficients of the case-b formula (:func:`segplan.frame.case_b_alpha`).

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


def _features(phi0, phi1, ell, degree):
    s = 0.5 * (np.asarray(phi0) + np.asarray(phi1))
    q = (0.5 * (np.asarray(phi0) - np.asarray(phi1))) ** 2
    ell = np.asarray(ell)
    # every power once, then the monomials ``s**i * q**j * ell**k`` by indexing: the same
    # products in the same order as one expression per monomial, without its 3 x 34 powers
    _, i, j, k = _exponent_table(degree)
    sp = np.stack([s**n for n in range(degree + 1)], axis=-1)
    qp = np.stack([q**n for n in range(degree // 2 + 1)], axis=-1)
    ep = np.stack([ell**n for n in range(degree + 1)], axis=-1)
    return np.take(sp, i, axis=-1) * np.take(qp, j, axis=-1) * np.take(ep, k, axis=-1)


def fit_heuristic(
    step_deg: float = 10.0,
    phi_max_deg: float = 80.0,
    d_over_L=(0.25, 100.0),
    n_d_over_L: int = 9,
    degree: int = 5,
    n_scan: int = 12,
) -> HeuristicFit:
    """Fit the case-b formula to exact optima (deterministic).

    The grid covers case b with ``phi0 >= phi1 >= 0`` (the other orderings and signs
    follow by symmetry): headings ``0, step, 2 step, ..., phi_max`` (both zero excluded)
    times ``n_d_over_L`` values of d/L evenly spaced in ``ln(d/L)``. At each point the
    exact optimum ``alpha*`` and the curvature ``k = LONGD''(alpha*) / LONGD`` (central
    difference) are computed; the target is the logit of the position of ``alpha*`` in
    the feasible interval, ``z = ln(u / (1 - u))`` with ``u = (alpha* - lo)/(hi - lo)``.
    Weighted least squares with weights ``sqrt(k) (hi - lo) u (1 - u)`` (the first-order
    change of alpha per unit of z) makes the residuals approximate
    ``sqrt(2 * relative LONGD error)``: the fit minimises the LONGD excess, not the
    error in alpha, as the paper's criterion asks.

    Parameters
    ----------
    step_deg, phi_max_deg : float
        Heading grid (degrees).
    d_over_L : (float, float)
        Range of d/L.
    n_d_over_L : int
        Number of d/L values.
    degree : int
        Total degree of the polynomial (5: 34 coefficients).
    n_scan : int
        Scan points of the exact algorithm (case b has a single minimum).

    Returns
    -------
    HeuristicFit
    """
    from .frame import _longd_unit, exact_alpha_intrinsic

    if not (0 < step_deg <= phi_max_deg < 90.0):
        raise ValueError(f"need 0 < step_deg <= phi_max_deg < 90, got {step_deg}, {phi_max_deg}")
    lo_dl, hi_dl = (float(v) for v in d_over_L)
    if not (0 < lo_dl < hi_dl and n_d_over_L >= 2):
        raise ValueError(
            f"need 0 < d_over_L[0] < d_over_L[1] and n_d_over_L >= 2, got {d_over_L}, {n_d_over_L}"
        )
    heads = np.radians(np.arange(0.0, phi_max_deg + 1e-9, step_deg))
    dls = np.geomspace(lo_dl, hi_dl, n_d_over_L)
    grid = np.array([(a, b, dl) for dl in dls for a in heads for b in heads if b <= a and a > 0.0])
    p0, p1, dl = grid.T
    lam = 1.0 / dl
    alpha, longd, _ = exact_alpha_intrinsic(dl, p0, p1, 1.0, rtol=1e-8, n_scan=n_scan, full_output=True)
    lo, hi = alpha_interval(p0, p1)
    h = 2e-3  # k = LONGD'' / LONGD by a central difference
    v0 = longd / dl
    vp = _longd_unit(lam, p0, p1, np.minimum(alpha + h, hi - 1e-9), rtol=1e-10)
    vm = _longd_unit(lam, p0, p1, np.maximum(alpha - h, lo + 1e-9), rtol=1e-10)
    k = np.maximum((vp + vm - 2.0 * v0) / (h * h * v0), 1e-9)
    u = (alpha - lo) / (hi - lo)
    z = np.log(u / (1.0 - u))
    w = np.sqrt(k) * (hi - lo) * u * (1.0 - u)  # d alpha / dz, scaled by sqrt(k)
    X = _features(p0, p1, np.log(dl), degree)
    coef, *_ = np.linalg.lstsq(X * w[:, None], z * w, rcond=None)
    rms = float(np.sqrt(np.mean((w * (X @ coef - z)) ** 2)))
    return HeuristicFit(
        coef, degree, math.radians(phi_max_deg), (math.log(lo_dl), math.log(hi_dl)), len(grid), rms
    )


def heuristic_error_study(phi0, phi1, d_over_L, L: float = 1.0, fit: HeuristicFit | None = None):
    """Heuristic and paper's case-a frames against the exact optimum, on a grid.

    Every combination of the given ``phi0``, ``phi1`` (radians) and ``d_over_L`` is a
    problem with ``d = d_over_L * L``; pairs with an empty feasible interval and the
    straight pair ``(0, 0)`` are dropped.

    Parameters
    ----------
    phi0, phi1 : array_like
        Intrinsic headings (radians).
    d_over_L : array_like
        Chord length over robot length.
    L : float
        Robot length.
    fit : HeuristicFit, optional
        Case-b coefficients (default: the cached fit).

    Returns
    -------
    pandas.DataFrame
        One row per problem: ``phi0, phi1`` (radians), ``d_over_L``, ``case`` ("a": slopes
        of opposite signs, "b": same signs or a zero slope), ``alpha_exact``,
        ``alpha_heuristic``, ``alpha_paper`` (the paper's case-a formula clipped inside
        the interval; NaN in case b, where the paper printed no formula),
        ``longd_exact_opt``, ``longd_heuristic``, ``longd_paper`` (LONGD [1] by Romberg,
        ``rtol = 1e-10``), ``rel_err`` and ``rel_err_paper`` (relative LONGD excess over
        the exact optimum; tiny negative values are the exact algorithm's tolerance).
    """
    import pandas as pd

    from .frame import _longd_unit, exact_alpha_intrinsic, heuristic_alpha, inside, parabola_alpha

    P0, P1, DL = (
        np.ravel(v) for v in np.meshgrid(np.ravel(phi0), np.ravel(phi1), np.ravel(d_over_L), indexing="ij")
    )
    P0, P1, DL = (np.asarray(v, dtype=float) for v in (P0, P1, DL))
    lo, hi = alpha_interval(P0, P1)
    keep = (np.asarray(hi) - np.asarray(lo) > 1e-9) & ~((P0 == 0.0) & (P1 == 0.0))
    P0, P1, DL = P0[keep], P1[keep], DL[keep]
    if np.any(DL <= 0) or not np.all(np.isfinite(DL)):
        raise ValueError("d_over_L must be positive and finite")
    lam = 1.0 / DL
    case_a = np.sin(P0) * np.sin(P1) < 0.0
    a_ex, v_ex, _ = exact_alpha_intrinsic(DL, P0, P1, 1.0, full_output=True)
    a_h = heuristic_alpha(DL, P0, P1, 1.0, fit=fit)
    v_h = _longd_unit(lam, P0, P1, a_h, rtol=1e-10)
    a_p = np.where(case_a, inside(parabola_alpha(P0, P1), P0, P1), np.nan)
    v_p = np.full(P0.shape, np.nan)
    if case_a.any():
        v_p[case_a] = _longd_unit(lam[case_a], P0[case_a], P1[case_a], a_p[case_a], rtol=1e-10)
    v_ex = v_ex / DL  # LONGD / d
    return pd.DataFrame(
        {
            "phi0": P0,
            "phi1": P1,
            "d_over_L": DL,
            "case": np.where(case_a, "a", "b"),
            "alpha_exact": a_ex,
            "alpha_heuristic": a_h,
            "alpha_paper": a_p,
            "longd_exact_opt": v_ex * DL * L,
            "longd_heuristic": v_h * DL * L,
            "longd_paper": v_p * DL * L,
            "rel_err": (v_h - v_ex) / v_ex,
            "rel_err_paper": (v_p - v_ex) / v_ex,
        }
    )
