"""Study helper for the book's optimal-frame chapter: the heuristic against the exact optimum.

Section "Optimal Reference System": the heuristic algorithm (closed forms,
:func:`segplan.frame.heuristic_alpha`) is judged by the LONGD [1] of its frame against the
exact algorithm's (:func:`segplan.frame_exact.exact_alpha_intrinsic`).
"""

from __future__ import annotations

import numpy as np

from ..frame import HeuristicFit, heuristic_alpha, inside
from ..frame_exact import exact_alpha_intrinsic, longd_unit, parabola_alpha
from ..pose import alpha_interval

__all__ = ["heuristic_error_study"]


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
        Case-b coefficients (default: the stored ones, :func:`segplan.frame.heuristic_coefficients`).

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
    v_h = longd_unit(lam, P0, P1, a_h, rtol=1e-10)
    a_p = np.where(case_a, inside(parabola_alpha(P0, P1), P0, P1), np.nan)
    v_p = np.full(P0.shape, np.nan)
    if case_a.any():
        v_p[case_a] = longd_unit(lam[case_a], P0[case_a], P1[case_a], a_p[case_a], rtol=1e-10)
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
