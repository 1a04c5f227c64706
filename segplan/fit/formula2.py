"""The fit of formula [2]: ``k_alpha`` and its validated domain, computed on a grid.

Section "Approximate computation of cost function": ``k_alpha`` is a "constant depending
on alpha and verifying 0 < k_alpha < 1, optimized empirically to adjust best to exact cost
function", and a "statistical study of errors" with "an absolute value of relative error
less than 2,5 %" and "average of relative errors ... 0,5 %" fixed the "ranges of alpha and
slope relative to intrinsic reference system" where [2] is used; "out of the evaluated
range for formula [2], the Romberg algorithm is used".

Nothing here is typed: :func:`run_calibration` computes, on a fixed grid and with exact
LONGD (Romberg, :func:`segplan.model.cost.exact_values`),

* ``k_alpha = c0 + c1 sin^2(alpha)`` by linear least squares of the relative error of
  [2] (the relative error is linear in ``k_alpha``), with ``sin^2`` held at its value at
  the grid's largest ``|alpha|`` (45 deg) beyond it, so ``k_alpha`` stays in (0, 1);
* the domain: for each band of ``d / L`` the box ``|alpha| <= alpha_max``,
  ``|phi_i| <= phi_max`` (``phi_i`` the intrinsic headings) of largest volume whose
  maximum relative error on the grid stays under ``design_max`` (default 2.25 %, a margin
  under the paper's 2.5 % for off-grid points) and whose mean stays under 0.5 %;

iterating fit and domain until the domain no longer changes (a few tenths of a second
once the grid's exact values are computed). The planner does not run this: it reads the
result stored with the package (:mod:`segplan.model.constants`, written by
``python -m segplan.fit``).

Why ``d / L`` matters: the rear excess's relative error does not depend on ``d / L``, but
the front-wheel excess comes from a binomial expansion in ``L f''``, which fails when
``d / L`` is small (at ``d / L = 1`` the front term can be wrong by tens of percent).
Why ``c0 + c1 sin^2``: LONGD is unchanged by the reflection ``(phi0, phi1, alpha) ->
-(...)``, so ``k_alpha`` is even in alpha; the expansion consistent to second order in the
bump scales the rear excess by ``cos^2(alpha) = 1 - sin^2(alpha)`` (see
:mod:`segplan.model.derivation`), so ``k_alpha`` should fall with ``sin^2`` at first order. By
measurement (:func:`segplan.studies.approx.k_basis_comparison`), this two-parameter form
fits as well as a separate ``k`` for each grid value of alpha
(:func:`segplan.studies.approx.k_by_alpha`) and better than a constant or
``c cos^2(alpha)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np

from ..model.cost import Domain, approx_terms, exact_values, k_from_coef

__all__ = [
    "ALPHA_GRID_DEG",
    "PHI_GRID_DEG",
    "BAND_LOWER",
    "DL_GRID",
    "FRAME_CAP_DEG",
    "BOUND_MAX",
    "BOUND_MEAN",
    "DESIGN_MAX",
    "EXACT_RTOL",
    "S2_CAP",
    "Calibration",
    "calibration_grid",
    "k_basis",
    "fit_k",
    "fit_domain",
    "grid_inside",
    "run_calibration",
]

#: Grid of the calibration (degrees; reflection symmetry lets alpha run over >= 0 only).
ALPHA_GRID_DEG = tuple(range(0, 46, 5))
PHI_GRID_DEG = tuple(range(-60, 61, 5))
#: Bands of d / L: lower bounds. Grid values of d / L (1e6 stands for d / L -> infinity).
BAND_LOWER = (1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 10.0)
DL_GRID = (1.0, 1.25, 1.5, 1.75, 2.0, 2.5, 3.0, 3.5, 4.0, 5.0, 6.0, 8.0, 10.0, 20.0, 50.0, 1e6)
#: Frame headings |phi_i + alpha| up to this (degrees) are sampled; boxes must stay inside.
FRAME_CAP_DEG = 75
BOUND_MAX = 0.025  # the paper's bound on |relative error|
BOUND_MEAN = 0.005  # the paper's mean |relative error|
DESIGN_MAX = 0.0225  # bound used on the grid (margin for off-grid points)
EXACT_RTOL = 1e-6  # Romberg tolerance of the reference values (errors of interest are >= 1e-4)
#: ``sin^2`` of the largest grid alpha: ``k_alpha`` is held constant beyond it.
S2_CAP = math.sin(math.radians(ALPHA_GRID_DEG[-1])) ** 2


@dataclass(frozen=True)
class Calibration:
    """Result of :func:`run_calibration`.

    Attributes
    ----------
    k_coef : tuple of float
        ``(c0, c1)``: ``k_alpha = c0 + c1 min(sin^2(alpha), sin^2(45 deg))``.
    domain : Domain
    max_error, mean_error : float
        Maximum and mean ``|relative error|`` of [2] on the grid points inside the domain.
    n_inside, n_grid : int
        Grid points inside the domain, grid points in all.
    iterations : int
        Fit/domain iterations until the domain stopped changing.
    """

    k_coef: tuple[float, float]
    domain: Domain
    max_error: float
    mean_error: float
    n_inside: int
    n_grid: int
    iterations: int


@cache
def calibration_grid():
    """The fixed grid of the calibration with exact LONGD (cached).

    Returns
    -------
    dict of ndarray
        ``alpha_deg, phi0_deg, phi1_deg`` (integers), ``d_over_L``, ``exact`` (with
        ``L = 1``), ``rear`` and ``front`` (the terms of [2] before ``k_alpha``).
    """
    a, p0, p1, dl = np.meshgrid(ALPHA_GRID_DEG, PHI_GRID_DEG, PHI_GRID_DEG, DL_GRID, indexing="ij")
    a, p0, p1, dl = (v.ravel() for v in (a, p0, p1, dl))
    keep = (np.abs(p0 + a) <= FRAME_CAP_DEG) & (np.abs(p1 + a) <= FRAME_CAP_DEG)
    a, p0, p1, dl = a[keep], p0[keep], p1[keep], dl[keep]
    al, ph0, ph1 = np.radians(a), np.radians(p0), np.radians(p1)
    exact = exact_values(dl, ph0, ph1, al, 1.0)
    rear, front = approx_terms(dl, ph0, ph1, al, 1.0)
    grid = {
        "alpha_deg": a,
        "phi0_deg": p0,
        "phi1_deg": p1,
        "d_over_L": dl,
        "exact": exact,
        "rear": rear,
        "front": front,
    }
    for v in grid.values():
        v.flags.writeable = False
    return grid


# -- the fit of k_alpha ----------------------------------------------------------------
def k_basis(alpha) -> np.ndarray:
    """Basis of ``k_alpha``: ``(1, min(sin^2 alpha, S2_CAP))`` along the last axis."""
    s2 = np.minimum(np.sin(alpha) ** 2, S2_CAP)
    return np.stack((np.ones_like(s2), s2), axis=-1)


def fit_k(d, alpha, exact, rear, front, basis=k_basis) -> np.ndarray:
    """Least-squares coefficients of ``k_alpha`` for [2] written as ``d (1 + k rear) + front``.

    The relative error ``(d + k d rear + front - exact) / exact`` is linear in the
    coefficients, so the fit is one ``lstsq``.
    """
    design = basis(alpha) * (d * rear / exact)[:, None]
    target = (exact - d - front) / exact
    return np.linalg.lstsq(design, target, rcond=None)[0]


# -- the domain ------------------------------------------------------------------------
def _select_box(a_idx, p_idx, err, n_a, n_p, volume, design_max, mean_max, a_deg, p_deg):
    """Largest-volume box (alpha_max, phi_max) whose grid error bounds hold, or None."""
    cell_max = np.zeros((n_a, n_p))
    cell_sum = np.zeros((n_a, n_p))
    cell_n = np.zeros((n_a, n_p))
    np.maximum.at(cell_max, (a_idx, p_idx), err)
    np.add.at(cell_sum, (a_idx, p_idx), err)
    np.add.at(cell_n, (a_idx, p_idx), 1.0)
    box_max = np.maximum.accumulate(np.maximum.accumulate(cell_max, axis=0), axis=1)
    box_n = cell_n.cumsum(0).cumsum(1)
    box_mean = cell_sum.cumsum(0).cumsum(1) / np.maximum(box_n, 1.0)
    ok = (box_max <= design_max) & (box_mean <= mean_max) & (box_n > 0)
    ok &= (a_deg[:, None] + p_deg[None, :]) <= FRAME_CAP_DEG
    if not np.any(ok):
        return None
    score = np.where(ok, volume, -1.0)
    i, j = np.unravel_index(np.argmax(score), score.shape)
    return float(a_deg[i]), float(p_deg[j])


def fit_domain(grid, err, design_max: float = DESIGN_MAX, mean_max: float = BOUND_MEAN) -> Domain:
    """Per band of ``d / L``, the largest box in (|alpha|, |phi_i|) meeting the bounds on the grid.

    The volume of a box is the number of grid points ``(alpha >= 0, phi0, phi1)`` it holds.
    """
    a_deg = np.asarray(ALPHA_GRID_DEG, dtype=float)
    p_deg = np.asarray([p for p in PHI_GRID_DEG if p >= 0], dtype=float)
    a_idx = np.searchsorted(a_deg, grid["alpha_deg"])
    pmax = np.maximum(np.abs(grid["phi0_deg"]), np.abs(grid["phi1_deg"]))
    p_idx = np.searchsorted(p_deg, pmax)
    first = grid["d_over_L"] == DL_GRID[0]  # one d / L value: the (alpha, phi0, phi1) grid
    vol = np.zeros((a_deg.size, p_deg.size))
    np.add.at(vol, (a_idx[first], p_idx[first]), 1.0)
    volume = vol.cumsum(0).cumsum(1)
    upper = (*BAND_LOWER[1:], math.inf)
    alpha_max, phi_max = [], []
    for lo, hi in zip(BAND_LOWER, upper, strict=True):
        band = (grid["d_over_L"] >= lo) & (grid["d_over_L"] < hi)
        box = _select_box(
            a_idx[band],
            p_idx[band],
            err[band],
            a_deg.size,
            p_deg.size,
            volume,
            design_max,
            mean_max,
            a_deg,
            p_deg,
        )
        a_max, p_max = box if box is not None else (0.0, 0.0)
        alpha_max.append(math.radians(a_max))
        phi_max.append(math.radians(p_max))
    return Domain(tuple(BAND_LOWER), tuple(alpha_max), tuple(phi_max))


def grid_inside(grid, domain: Domain) -> np.ndarray:
    """Which points of :func:`calibration_grid` lie inside ``domain`` (boolean array)."""
    return domain.contains(
        grid["d_over_L"],
        np.radians(grid["phi0_deg"]),
        np.radians(grid["phi1_deg"]),
        np.radians(grid["alpha_deg"]),
        1.0,
    )


def run_calibration(
    design_max: float = DESIGN_MAX,
    mean_max: float = BOUND_MEAN,
    max_iter: int = 10,
    terms: tuple[np.ndarray, np.ndarray] | None = None,
) -> Calibration:
    """Fit ``k_alpha`` and the domain on the grid, alternating until the domain is stable.

    Starts from ``k_alpha`` fitted on ``|phi_i| <= 30 deg``, ``d / L >= 3``. Deterministic.
    ``terms``: optional ``(rear, front)`` arrays on :func:`calibration_grid` replacing the
    terms of the derived [2] (``LONGD ~ d (1 + k rear) + front``), to calibrate a variant
    (see :func:`segplan.studies.approx.variant_domains`).
    """
    g = calibration_grid()
    d, alpha = g["d_over_L"], np.radians(g["alpha_deg"])
    rear, front = (g["rear"], g["front"]) if terms is None else terms
    inside = (np.maximum(np.abs(g["phi0_deg"]), np.abs(g["phi1_deg"])) <= 30) & (d >= 3)
    domain, iterations = None, 0
    while iterations < max_iter:
        iterations += 1
        coef = fit_k(d[inside], alpha[inside], g["exact"][inside], rear[inside], front[inside])
        err = np.abs((d * (1.0 + k_from_coef(coef, alpha, S2_CAP) * rear) + front - g["exact"]) / g["exact"])
        new = fit_domain(g, err, design_max, mean_max)
        inside = grid_inside(g, new)
        if new == domain:
            break
        domain = new
    if not np.any(inside):
        raise RuntimeError("calibration found no domain where [2] meets the bounds")
    return Calibration(
        k_coef=tuple(float(c) for c in coef),
        domain=domain,
        max_error=float(err[inside].max()),
        mean_error=float(err[inside].mean()),
        n_inside=int(inside.sum()),
        n_grid=int(inside.size),
        iterations=iterations,
    )
