"""Study helper for the book's optimal-frame chapter: the heuristic against the exact optimum.

Section "Optimal Reference System": the heuristic algorithm (closed forms,
:func:`segplan.model.frame.heuristic_alpha`) is judged by the LONGD [1] of its frame against the
exact algorithm's (:func:`segplan.model.frame_exact.exact_alpha_intrinsic`).
"""

from __future__ import annotations

import numpy as np

from ..model.frame import HeuristicFit, heuristic_alpha, inside
from ..model.frame_exact import exact_alpha_intrinsic, longd_unit, parabola_alpha
from ..model.pose import alpha_interval

__all__ = ["case_a_boundary", "paper_case_a_excess", "heuristic_error_study"]


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
        Case-b coefficients (default: the stored ones, :func:`segplan.model.frame.heuristic_coefficients`).

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


def paper_case_a_excess(d_over_L, phi0, phi1):
    """Relative LONGD excess of the paper's case-a frame over the exact optimum (``L = 1``).

    Section "Optimal Reference System", case a: ``tan a0 = (1/m0 + 1/m1) / 2``
    (:func:`segplan.model.frame_exact.parabola_alpha`, clipped just inside the interval) against
    :func:`segplan.model.frame_exact.exact_alpha_intrinsic`; both costs are LONGD [1] by Romberg.
    Inputs broadcast; headings of opposite signs (case a).
    """
    shape = np.broadcast_shapes(np.shape(d_over_L), np.shape(phi0), np.shape(phi1))
    dl, p0, p1 = (np.ravel(np.asarray(v, dtype=float)) for v in np.broadcast_arrays(d_over_L, phi0, phi1))
    if np.any(np.sin(p0) * np.sin(p1) >= 0.0):
        raise ValueError("phi0 and phi1 must have opposite signs (case a)")
    _, v_ex, _ = exact_alpha_intrinsic(dl, p0, p1, 1.0, full_output=True)
    a_p = inside(parabola_alpha(p0, p1), p0, p1)
    v_p = longd_unit(1.0 / dl, p0, p1, a_p, rtol=1e-10)
    out = (v_p / (v_ex / dl) - 1.0).reshape(shape)
    return float(out) if out.ndim == 0 else out


def case_a_boundary(phi_large, d_over_L, iterations: int = 11, exact_tol: float = 1e-8, lowest=1e-3):
    """Where the paper's case-a formula stops being exact: a root-find of the boundary.

    For every larger slope ``phi_large`` (radians, > 0) and ``d_over_L``, on both sides
    (the small slope is ``phi1 = -s`` with ``phi0 = phi_large``, or ``phi0 = -s`` with
    ``phi1 = phi_large``; the reflection ``(phi0, phi1, alpha) -> -(...)`` covers the
    other quadrant), the smaller slope ``s`` in ``(lowest, phi_large]`` where the paper's
    excess (:func:`paper_case_a_excess`) crosses ``exact_tol`` is found by bisection
    (``iterations`` halvings). Bisection assumes one crossing: the formula fails below the
    threshold and is exact above it; check it against a grid.

    Returns
    -------
    pandas.DataFrame
        One row per ``(side, phi_large, d_over_L)``: ``side`` ("phi1 small", "phi0 small"),
        ``phi_large_deg``, ``d_over_L``, ``threshold_deg`` (an upper bound of the failing
        smaller slopes, to ``phi_large / 2**iterations``; 0 when the formula is exact
        down to ``lowest``), ``fails_at_lowest`` and ``excess_at_lowest`` (the excess
        with the smaller slope at ``lowest``, the limit of the failure).
    """
    import pandas as pd

    if iterations < 1:
        raise ValueError(f"iterations must be >= 1, got {iterations}")
    big, dl = (np.ravel(v) for v in np.meshgrid(np.ravel(phi_large), np.ravel(d_over_L), indexing="ij"))
    big, dl = np.asarray(big, dtype=float), np.asarray(dl, dtype=float)
    if np.any(big <= lowest) or np.any(dl <= 0):
        raise ValueError("phi_large must exceed lowest and d_over_L must be positive")
    frames = []
    for side in ("phi1 small", "phi0 small"):

        def excess(s, at, side=side):  # the excess at smaller slope s, on the problems `at`
            if side == "phi1 small":
                return paper_case_a_excess(dl[at], big[at], -s)
            return paper_case_a_excess(dl[at], -s, big[at])

        everywhere = np.arange(big.size)
        e_low = excess(np.full(big.shape, lowest), everywhere)
        fails_low = e_low > exact_tol
        # only where the formula fails at `lowest` is there a threshold; where it fails at
        # phi_large too, the threshold is phi_large: bisect the rest (the same result as
        # bisecting every problem, at a fraction of the exact-optimum searches)
        fails_hi = np.zeros(big.shape, dtype=bool)
        at = everywhere[fails_low]
        fails_hi[at] = excess(big[at], at) > exact_tol
        at = everywhere[fails_low & ~fails_hi]
        lo, hi = np.full(at.shape, lowest), big[at].copy()
        for _ in range(iterations):
            mid = 0.5 * (lo + hi)
            f = excess(mid, at) > exact_tol
            lo, hi = np.where(f, mid, lo), np.where(f, hi, mid)
        threshold = np.where(fails_hi, big, 0.0)
        threshold[at] = hi
        frames.append(
            pd.DataFrame(
                {
                    "side": side,
                    "phi_large_deg": np.degrees(big),
                    "d_over_L": dl,
                    "threshold_deg": np.degrees(threshold),
                    "fails_at_lowest": fails_low,
                    "excess_at_lowest": e_low,
                }
            )
        )
    return pd.concat(frames, ignore_index=True)
