"""Romberg's work on [1] against formula [2] at the same error (the book's chapter 3).

Section "Approximate computation of cost function" compares the closed approximation [2]
with "Romberg integration with the same maximum error bound". These helpers count the
integrand evaluations Romberg needs for the exact LONGD [1] case by case
(:func:`romberg_work`), find the loosest Romberg tolerance whose measured error matches
[2]'s largest error (:func:`romberg_matched`), and make chapter 3's comparison on its
unions (:func:`matched_cost_study`, shared with ``benchmarks/longd_speed.py`` and the
README), and time both sides of it (:func:`matched_cost_ratios`, the one measurement of
Romberg over [2] that the chapter and the README both quote). The cases and [2]'s errors
come from :mod:`segplan.studies.approx`; nothing here is part of the stable API.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..model.cost import exact_values, longd_approx_intrinsic, longd_integrand
from ..model.romberg import romberg
from .approx import error_study, sample_domain

__all__ = ["MATCH_RTOLS", "matched_cost_ratios", "matched_cost_study", "romberg_matched", "romberg_work"]


def romberg_work(d_over_L, phi0, phi1, alpha, rtol: float, min_levels: int = 1):
    """Integrand evaluations Romberg needs for [1] to meet ``rtol``, case by case (``L = 1``).

    Section "Approximate computation of cost function" compares [2] with "Romberg
    integration with the same maximum error bound". Romberg's stopping rule
    (:func:`segplan.model.romberg.romberg`) is applied to each case alone, from ``min_levels``
    halvings on (level ``k`` uses ``2**k + 1`` points), so the count is the work that
    bound asks for. :func:`segplan.longd_exact` uses at least 4 levels (17 points).

    Returns
    -------
    evaluations : ndarray of int
        Integrand evaluations per case.
    value : ndarray
        Romberg's LONGD per case.
    """

    dl, p0, p1, a = (np.ravel(v).astype(float) for v in np.broadcast_arrays(d_over_L, phi0, phi1, alpha))
    evaluations = np.zeros(dl.size, dtype=int)
    value = np.empty(dl.size)
    for i in range(dl.size):
        count = [0]

        def f(tau, i=i, count=count):
            count[0] += tau.size
            return longd_integrand(tau, dl[i], p0[i], p1[i], a[i], 1.0)

        value[i] = romberg(f, 0.0, 1.0, rtol=rtol, min_levels=min_levels)[0]
        evaluations[i] = count[0]
    return evaluations, value


#: Tolerances tried by :func:`romberg_matched`, loosest first.
MATCH_RTOLS = (2.5e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5)


def romberg_matched(d_over_L, phi0, phi1, alpha, max_error: float, rtols=MATCH_RTOLS, reference=None):
    """Romberg on [1] at "the same maximum error bound" as [2]: the loosest tolerance that meets it.

    Section "Approximate computation of cost function" compares [2] with "Romberg
    integration with the same maximum error bound". Romberg's tolerance is an estimate, not
    a bound, so the matching is measured: for each ``rtol`` in ``rtols`` (loosest first),
    Romberg from level 1 (:func:`romberg_work`) on the given cases, and the first ``rtol``
    whose largest relative error against ``reference`` is at most ``max_error`` (the
    largest error of [2] on the same cases) is kept.

    Parameters
    ----------
    d_over_L, phi0, phi1, alpha : array_like
        Cases (``L = 1``, radians).
    max_error : float
        The maximum ``|relative error|`` to match (> 0).
    rtols : sequence of float
        Tolerances to try, loosest first.
    reference : ndarray, optional
        Exact LONGD of the cases; by default Romberg to ``1e-12``.

    Returns
    -------
    dict
        ``rtol`` (NaN if none of ``rtols`` meets ``max_error``), ``evaluations`` (per case,
        at that ``rtol``), ``mean_evaluations``, ``max_error`` (Romberg's, at that
        ``rtol``), and ``tried``: a list of ``(rtol, mean evaluations, max error)``.
    """
    if not max_error > 0:
        raise ValueError(f"max_error must be positive, got {max_error}")
    dl, p0, p1, a = (np.ravel(v).astype(float) for v in np.broadcast_arrays(d_over_L, phi0, phi1, alpha))
    ref = exact_values(dl, p0, p1, a, 1.0, rtol=1e-12) if reference is None else np.asarray(reference)
    tried = []
    for rtol in rtols:
        evals, value = romberg_work(dl, p0, p1, a, rtol=rtol, min_levels=1)
        err = float(np.max(np.abs(value / ref - 1.0)))
        tried.append((float(rtol), float(evals.mean()), err))
        if err <= max_error:
            return {
                "rtol": float(rtol),
                "evaluations": evals,
                "mean_evaluations": float(evals.mean()),
                "max_error": err,
                "tried": tried,
            }
    return {
        "rtol": math.nan,
        "evaluations": None,
        "mean_evaluations": math.nan,
        "max_error": math.nan,
        "tried": tried,
    }


def matched_cost_study(n: int = 2000, seed: int = 11):
    """Chapter 3's cost comparison, shared with ``benchmarks/longd_speed.py`` (the README).

    ``n`` unions drawn inside the domain of [2] (:func:`segplan.studies.approx.sample_domain`,
    ``seed``); the largest error of segplan's [2] on them
    (:func:`segplan.studies.approx.error_study`); Romberg at the loosest
    tolerance that matches it (:func:`romberg_matched`, reference Romberg to ``1e-12``).

    Returns
    -------
    dict
        ``cases`` (the four arrays), ``reference``, ``approx_max_error`` and the entries of
        :func:`romberg_matched` (``rtol``, ``mean_evaluations``, ``max_error``, ``tried``, ...).
    """
    cases = sample_domain(n, seed=seed)
    reference = exact_values(*cases, 1.0, rtol=1e-12)
    approx_max = float(error_study(*cases)["abs_error"].max())
    out = romberg_matched(*cases, approx_max, reference=reference)
    return {"cases": cases, "reference": reference, "approx_max_error": approx_max, **out}


def _per_call(fn, calls: int, repeats: int) -> float:
    # Best CPU time (process time: the machine is shared) per call of fn(), fn making `calls` calls.
    best = math.inf
    for _ in range(repeats):
        t0 = time.process_time()
        fn()
        best = min(best, time.process_time() - t0)
    return best / calls


def matched_cost_ratios(
    matched: dict, n_scalar: int = 1000, n_vector: int = 200_000, repeats: int = 5
) -> dict:
    """Romberg at [2]'s maximum error over [2]: in integrand evaluations and in time (varies).

    The one measurement of the paper's "2/5 to 1/3 of exact computational cost [...] using
    Romberg integration with the same maximum error bound" that chapter 3 and the README
    (``benchmarks/longd_speed.py``) both quote. On the unions of ``matched``
    (:func:`matched_cost_study`):

    - **in evaluations**: Romberg's mean integrand evaluations at the matched tolerance
      (deterministic) over [2]'s cost counted in integrand evaluations: the CPU time of [2]
      over that of one integrand evaluation, both vectorised over ``n_vector`` unions of the
      same domain (:func:`segplan.studies.approx.sample_domain`, seed 12);
    - **in time**: Romberg from level 1 at the matched tolerance (:func:`romberg_work`)
      against [2] (``longd_approx_intrinsic``), both as scalar calls on the first
      ``n_scalar`` unions.

    Times are the best CPU time of ``repeats`` runs (``time.process_time``), so they vary
    with the machine, less with its load.

    Returns
    -------
    dict
        ``approx_evaluations`` ([2]'s cost in integrand evaluations), ``evaluation_ratio``,
        ``romberg_us`` and ``approx_us`` (scalar, microseconds per union) and
        ``time_ratio_scalar``.

    Raises
    ------
    ValueError
        If ``matched`` found no tolerance (``rtol`` NaN) or the counts are not positive.
    """
    if not math.isfinite(matched.get("rtol", math.nan)):
        raise ValueError("matched must hold a matched tolerance (matched_cost_study found none)")
    for name, v in (("n_scalar", n_scalar), ("n_vector", n_vector), ("repeats", repeats)):
        if isinstance(v, bool) or not isinstance(v, int) or v < 1:
            raise ValueError(f"{name} must be a positive integer, got {v!r}")
    td, tp0, tp1, ta = sample_domain(n_vector, seed=12)
    point = np.array([0.5])
    t_approx_vec = _per_call(lambda: longd_approx_intrinsic(td, tp0, tp1, ta, 1.0), n_vector, repeats)
    t_point = _per_call(lambda: longd_integrand(point, td, tp0, tp1, ta, 1.0), n_vector, repeats)
    cases = tuple(np.asarray(v)[:n_scalar] for v in matched["cases"])
    scalar = [tuple(float(v[i]) for v in cases) for i in range(cases[0].size)]
    n = len(scalar)
    t_romberg = _per_call(lambda: romberg_work(*cases, rtol=matched["rtol"], min_levels=1), n, repeats)
    t_approx = _per_call(
        lambda: [longd_approx_intrinsic(d, p, q, a, 1.0) for d, p, q, a in scalar], n, repeats
    )
    approx_evaluations = t_approx_vec / t_point
    return {
        "approx_evaluations": approx_evaluations,
        "evaluation_ratio": matched["mean_evaluations"] / approx_evaluations,
        "romberg_us": 1e6 * t_romberg,
        "approx_us": 1e6 * t_approx,
        "time_ratio_scalar": t_romberg / t_approx,
    }
