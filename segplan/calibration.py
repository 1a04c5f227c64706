"""The empirical side of formula [2]: ``k_alpha`` and the validated domain, fitted by code.

Section "Approximate computation of cost function": ``k_alpha`` is a "constant depending
on alpha and verifying 0 < k_alpha < 1, optimized empirically to adjust best to exact cost
function", and a "statistical study of errors" with "an absolute value of relative error
less than 2,5 %" and "average of relative errors ... 0,5 %" fixed the "ranges of alpha and
slope relative to intrinsic reference system" where [2] is used; "out of the evaluated
range for formula [2], the Romberg algorithm is used".

Nothing here is typed: :func:`calibration` computes, on a fixed grid and with exact LONGD
(Romberg, :func:`segplan.cost.longd_exact_intrinsic`),

* ``k_alpha = c0 + c1 sin^2(alpha)`` by linear least squares of the relative error of
  [2] (the relative error is linear in ``k_alpha``), with ``sin^2`` held at its value at
  the grid's largest ``|alpha|`` (45 deg) beyond it, so ``k_alpha`` stays in (0, 1);
* the domain: for each band of ``d / L`` the box ``|alpha| <= alpha_max``,
  ``|phi_i| <= phi_max`` (``phi_i`` the intrinsic headings) of largest volume whose
  maximum relative error on the grid stays under ``design_max`` (default 2.25 %, a margin
  under the paper's 2.5 % for off-grid points) and whose mean stays under 0.5 %;

iterating fit and domain until the domain no longer changes. The result is cached in
memory; the first call takes a few tenths of a second.

Why ``d / L`` matters: the rear excess's relative error does not depend on ``d / L``, but
the front-wheel excess comes from a binomial expansion in ``L f''``, which fails when
``d / L`` is small (at ``d / L = 1`` the front term can be wrong by tens of percent).
Why ``c0 + c1 sin^2``: LONGD is unchanged by the reflection ``(phi0, phi1, alpha) ->
-(...)``, so ``k_alpha`` is even in alpha; the expansion consistent to second order in the
bump scales the rear excess by ``cos^2(alpha) = 1 - sin^2(alpha)`` (see
:mod:`segplan.derivation`), so ``k_alpha`` should fall with ``sin^2`` at first order. By
measurement (:func:`k_basis_comparison`), this two-parameter form fits as well as a
separate ``k`` for each grid value of alpha (:func:`k_by_alpha`) and better than a
constant or ``c cos^2(alpha)``.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from functools import cache

import numpy as np

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


@dataclass(frozen=True)
class Domain:
    """The validated domain of [2]: per band of ``d / L``, a box in alpha and the headings.

    Attributes
    ----------
    band_lower : tuple of float
        Lower bounds of the ``d / L`` bands (ascending; the last band is unbounded).
    alpha_max, phi_max : tuple of float
        Radians, per band; ``phi_max = 0`` marks an empty band.
    """

    band_lower: tuple[float, ...]
    alpha_max: tuple[float, ...]
    phi_max: tuple[float, ...]

    def contains(self, d, phi0, phi1, alpha, L):
        """Vectorised membership test (see :func:`in_domain`)."""
        if all(isinstance(v, float | int | np.floating) for v in (d, phi0, phi1, alpha, L)):
            j = bisect.bisect_right(self.band_lower, d / L) - 1  # scalar fast path
            if j < 0 or self.phi_max[j] <= 0:
                return False
            p_max = self.phi_max[j]
            return abs(alpha) <= self.alpha_max[j] and abs(phi0) <= p_max and abs(phi1) <= p_max
        lower = np.asarray(self.band_lower)
        j = np.searchsorted(lower, np.divide(d, L), side="right") - 1
        jj = np.maximum(j, 0)
        a_max = np.asarray(self.alpha_max)[jj]
        p_max = np.asarray(self.phi_max)[jj]
        inside = (j >= 0) & (p_max > 0) & (np.abs(alpha) <= a_max)
        inside &= (np.abs(phi0) <= p_max) & (np.abs(phi1) <= p_max)
        return inside

    def table(self):
        """The domain as a pandas DataFrame in degrees (one row per band)."""
        import pandas as pd

        upper = (*self.band_lower[1:], math.inf)
        return pd.DataFrame(
            {
                "d/L from": self.band_lower,
                "d/L to": upper,
                "|alpha| max (deg)": np.round(np.degrees(self.alpha_max), 6),
                "|phi_i| max (deg)": np.round(np.degrees(self.phi_max), 6),
            }
        )


@dataclass(frozen=True)
class Calibration:
    """Result of :func:`calibration`.

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


# -- exact reference values ------------------------------------------------------------
def exact_values(d, phi0, phi1, alpha, L, rtol: float = EXACT_RTOL, chunk: int = 1024) -> np.ndarray:
    """Exact LONGD [1] of many cases, in chunks of similar difficulty.

    Romberg on a batch runs until its hardest member converges; sorting by the steepest
    frame heading ``max |phi_i + alpha|`` keeps easy cases in cheap batches.
    """
    from .cost import longd_exact_intrinsic

    d, phi0, phi1, alpha, L = (np.ravel(v) for v in np.broadcast_arrays(d, phi0, phi1, alpha, L))
    key = np.maximum(np.abs(phi0 + alpha), np.abs(phi1 + alpha))
    order = np.argsort(key, kind="stable")
    out = np.empty(d.shape)
    for part in np.array_split(order, max(1, -(-d.size // chunk))):
        out[part] = longd_exact_intrinsic(d[part], phi0[part], phi1[part], alpha[part], L[part], rtol=rtol)
    return out


@cache
def calibration_grid():
    """The fixed grid of the calibration with exact LONGD (cached).

    Returns
    -------
    dict of ndarray
        ``alpha_deg, phi0_deg, phi1_deg`` (integers), ``d_over_L``, ``exact`` (with
        ``L = 1``), ``rear`` and ``front`` (the terms of [2] before ``k_alpha``).
    """
    from .cost import approx_terms

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
#: ``sin^2`` of the largest grid alpha: ``k_alpha`` is held constant beyond it.
S2_CAP = math.sin(math.radians(ALPHA_GRID_DEG[-1])) ** 2


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


def k_from_coef(coef, alpha):
    """``k_alpha`` from its coefficients (vectorised): ``c0 + c1 min(sin^2 alpha, S2_CAP)``."""
    return coef[0] + coef[1] * np.minimum(np.sin(alpha) ** 2, S2_CAP)


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


def _grid_inside(grid, domain: Domain) -> np.ndarray:
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
    (see :func:`variant_domains`).
    """
    g = calibration_grid()
    d, alpha = g["d_over_L"], np.radians(g["alpha_deg"])
    rear, front = (g["rear"], g["front"]) if terms is None else terms
    inside = (np.maximum(np.abs(g["phi0_deg"]), np.abs(g["phi1_deg"])) <= 30) & (d >= 3)
    domain, iterations = None, 0
    while iterations < max_iter:
        iterations += 1
        coef = fit_k(d[inside], alpha[inside], g["exact"][inside], rear[inside], front[inside])
        err = np.abs((d * (1.0 + k_from_coef(coef, alpha) * rear) + front - g["exact"]) / g["exact"])
        new = fit_domain(g, err, design_max, mean_max)
        inside = _grid_inside(g, new)
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


@cache
def calibration() -> Calibration:
    """The calibration used by :func:`segplan.longd_approx` and :func:`segplan.longd` (cached)."""
    return run_calibration()


def k_alpha(alpha):
    """The fitted ``k_alpha`` of formula [2] (vectorised; radians)."""
    return k_from_coef(calibration().k_coef, alpha)


def in_domain(d, phi0, phi1, alpha, L):
    """Whether [2] is used: inside the validated domain (vectorised, intrinsic parameters).

    Parameters
    ----------
    d : float or ndarray
        Chord length.
    phi0, phi1 : float or ndarray
        Intrinsic headings (radians).
    alpha : float or ndarray
        Reference-system angle (radians).
    L : float or ndarray
        Robot length.

    Returns
    -------
    bool or ndarray of bool
        True where ``|alpha| <= alpha_max`` and ``|phi_i| <= phi_max`` of the band of ``d / L``
        (see :func:`calibration`), False elsewhere.
    """
    inside = calibration().domain.contains(d, phi0, phi1, alpha, L)
    return bool(inside) if np.ndim(inside) == 0 else inside


# -- studies (used by the book's notebooks) ------------------------------------------
def sample_domain(n: int, seed: int = 0, domain: Domain | None = None, d_over_L_max: float = 100.0):
    """``n`` cases drawn uniformly inside the domain (deterministic).

    ``d / L`` is log-uniform over the non-empty bands (the last band up to
    ``d_over_L_max``); alpha and the headings are uniform in the band's box.

    Returns
    -------
    d_over_L, phi0, phi1, alpha : ndarray
        Radians; ``L = 1``.
    """
    dom = calibration().domain if domain is None else domain
    rng = np.random.default_rng(seed)
    lower = np.asarray(dom.band_lower)
    upper = np.append(lower[1:], d_over_L_max)
    live = np.asarray(dom.phi_max) > 0
    lo, hi = np.log(lower[live]), np.log(upper[live])
    widths = hi - lo
    band = rng.choice(widths.size, size=n, p=widths / widths.sum())
    dl = np.exp(lo[band] + widths[band] * rng.random(n))
    a_max = np.asarray(dom.alpha_max)[live][band]
    p_max = np.asarray(dom.phi_max)[live][band]
    alpha = a_max * rng.uniform(-1.0, 1.0, n)
    phi0 = p_max * rng.uniform(-1.0, 1.0, n)
    phi1 = p_max * rng.uniform(-1.0, 1.0, n)
    return dl, phi0, phi1, alpha


def sample_wide(
    n: int,
    seed: int = 0,
    alpha_max_deg: float = 60.0,
    phi_max_deg: float = 75.0,
    d_over_L: tuple[float, float] = (1.0, 20.0),
    frame_cap_deg: float = 80.0,
):
    """``n`` cases drawn uniformly over a wide range (deterministic, rejection sampling).

    Alpha and the headings are uniform, ``d / L`` log-uniform; cases with a frame heading
    ``|phi_i + alpha|`` above ``frame_cap_deg`` (near-vertical end slopes, where the cubic
    barely exists) are redrawn.

    Returns
    -------
    d_over_L, phi0, phi1, alpha : ndarray
        Radians; ``L = 1``.
    """
    rng = np.random.default_rng(seed)
    cap = math.radians(frame_cap_deg)
    parts, have = [], 0
    while have < n:
        m = 2 * (n - have) + 16
        alpha = math.radians(alpha_max_deg) * rng.uniform(-1.0, 1.0, m)
        phi0 = math.radians(phi_max_deg) * rng.uniform(-1.0, 1.0, m)
        phi1 = math.radians(phi_max_deg) * rng.uniform(-1.0, 1.0, m)
        dl = np.exp(rng.uniform(math.log(d_over_L[0]), math.log(d_over_L[1]), m))
        ok = (np.abs(phi0 + alpha) <= cap) & (np.abs(phi1 + alpha) <= cap)
        parts.append(np.stack((dl, phi0, phi1, alpha))[:, ok])
        have += int(ok.sum())
    dl, phi0, phi1, alpha = np.concatenate(parts, axis=1)[:, :n]
    return dl, phi0, phi1, alpha


def error_study(d_over_L, phi0, phi1, alpha, k=None):
    """Exact [1] against [2] case by case, as a pandas DataFrame.

    Parameters
    ----------
    d_over_L, phi0, phi1, alpha : array_like
        Cases with ``L = 1`` (radians), e.g. from :func:`sample_wide` or
        :func:`sample_domain`.
    k : float or ndarray, optional
        ``k_alpha``; the fitted one by default.

    Returns
    -------
    pandas.DataFrame
        Columns ``d_over_L, alpha_deg, phi0_deg, phi1_deg, mbar0, mbar1, exact, approx,
        rel_error`` (signed, ``approx / exact - 1``), ``abs_error`` and ``in_domain``.
    """
    import pandas as pd

    from .cost import longd_approx_intrinsic
    from .union import chord_slopes

    dl, phi0, phi1, alpha = (
        np.ravel(v).astype(float) for v in np.broadcast_arrays(d_over_L, phi0, phi1, alpha)
    )
    exact = exact_values(dl, phi0, phi1, alpha, 1.0)
    approx = longd_approx_intrinsic(dl, phi0, phi1, alpha, 1.0, k=k)
    m0, m1 = chord_slopes(phi0, phi1, alpha)
    rel = approx / exact - 1.0
    return pd.DataFrame(
        {
            "d_over_L": dl,
            "alpha_deg": np.degrees(alpha),
            "phi0_deg": np.degrees(phi0),
            "phi1_deg": np.degrees(phi1),
            "mbar0": m0,
            "mbar1": m1,
            "exact": exact,
            "approx": approx,
            "rel_error": rel,
            "abs_error": np.abs(rel),
            "in_domain": calibration().domain.contains(dl, phi0, phi1, alpha, 1.0),
        }
    )


def k_by_alpha():
    """``k`` fitted separately on each grid value of ``|alpha|`` (inside the domain) vs the smooth fit.

    Returns
    -------
    pandas.DataFrame
        Columns ``alpha_deg, n, k_bin, k_alpha``.
    """
    import pandas as pd

    g, cal = calibration_grid(), calibration()
    inside = _grid_inside(g, cal.domain)
    d, alpha = g["d_over_L"], np.radians(g["alpha_deg"])
    rows = []
    for a in ALPHA_GRID_DEG:
        m = inside & (g["alpha_deg"] == a)
        if not np.any(m):
            continue
        k_bin = fit_k(d[m], alpha[m], g["exact"][m], g["rear"][m], g["front"][m], basis=_const_basis)[0]
        rows.append((a, int(m.sum()), float(k_bin), float(k_from_coef(cal.k_coef, math.radians(a)))))
    return pd.DataFrame(rows, columns=["alpha_deg", "n", "k_bin", "k_alpha"])


def _const_basis(alpha):
    return np.ones((np.size(alpha), 1))


def k_basis_comparison():
    """Error of [2] inside the domain (calibration grid) for several forms of ``k(alpha)``.

    Each form is fitted by least squares on the same points. Returns a DataFrame with
    columns ``form, parameters, mean_abs_error, rms_error, max_abs_error``.
    """
    import pandas as pd

    g, cal = calibration_grid(), calibration()
    inside = _grid_inside(g, cal.domain)
    d, alpha = g["d_over_L"][inside], np.radians(g["alpha_deg"][inside])
    exact, rear, front = g["exact"][inside], g["rear"][inside], g["front"][inside]
    forms = {
        "constant": _const_basis,
        "c cos^2(alpha)": lambda a: (np.cos(a) ** 2)[:, None],
        "c0 + c1 sin^2(alpha) (used)": k_basis,
        "c0 + c1 sin^2 + c2 sin^4": lambda a: np.stack(
            (np.ones_like(a), np.sin(a) ** 2, np.sin(a) ** 4), axis=-1
        ),
        "one k per grid alpha": lambda a: (
            np.round(np.degrees(a))[:, None] == np.asarray(ALPHA_GRID_DEG)
        ).astype(float),
    }
    rows = []
    for name, basis in forms.items():
        coef = fit_k(d, alpha, exact, rear, front, basis=basis)
        err = np.abs((d * (1.0 + (basis(alpha) @ coef) * rear) + front - exact) / exact)
        rows.append((name, coef.size, err.mean(), np.sqrt(np.mean(err**2)), err.max()))
    return pd.DataFrame(rows, columns=["form", "parameters", "mean_abs_error", "rms_error", "max_abs_error"])


def variant_comparison(n_wide: int = 20000, seed: int = 0):
    """Formula [2] against its OCR-literal alternatives, each with its own fitted ``k(alpha)``.

    Every variant of :func:`segplan.derivation.variants` is evaluated (lambdified sympy
    expression) on the calibration grid; ``k(alpha)`` (same two-parameter form) is fitted
    for each variant inside the domain of the derived [2], and the errors are measured
    there and over a wide sample (:func:`sample_wide`).

    Returns
    -------
    pandas.DataFrame
        One row per variant: ``variant, rear, cross, exponent, k_c0, k_c1, mean_domain,
        max_domain, mean_wide, p95_wide``, sorted by ``mean_domain``.
    """
    import pandas as pd

    from . import derivation
    from .union import chord_slopes

    g, cal = calibration_grid(), calibration()
    inside = _grid_inside(g, cal.domain)
    gd, ga = g["d_over_L"][inside], np.radians(g["alpha_deg"][inside])
    gp0, gp1, ge = np.radians(g["phi0_deg"][inside]), np.radians(g["phi1_deg"][inside]), g["exact"][inside]
    wd, wp0, wp1, wa = sample_wide(n_wide, seed)
    we = exact_values(wd, wp0, wp1, wa, 1.0)
    rows = []
    for name in derivation.variants():
        f = derivation.lambdified(name)

        def split(dl, p0, p1, a, f=f):
            m0, m1 = chord_slopes(p0, p1, a)
            base = f(dl, a, m0, m1, 1.0, 0.0)  # k = 0: d + front
            return base, f(dl, a, m0, m1, 1.0, 1.0) - base  # and d * rear

        base, dr = split(gd, gp0, gp1, ga)
        coef = fit_k(gd, ga, ge, dr / gd, base - gd)
        err_d = np.abs((base + k_from_coef(coef, ga) * dr - ge) / ge)
        wbase, wdr = split(wd, wp0, wp1, wa)
        err_w = np.abs((wbase + k_from_coef(coef, wa) * wdr - we) / we)
        rear, cross, exponent = (part.split("=")[-1] for part in name.split("|"))
        rows.append(
            (
                name,
                rear,
                cross,
                exponent,
                *coef,
                err_d.mean(),
                err_d.max(),
                err_w.mean(),
                np.quantile(err_w, 0.95),
            )
        )
    cols = [
        "variant",
        "rear",
        "cross",
        "exponent",
        "k_c0",
        "k_c1",
        "mean_domain",
        "max_domain",
        "mean_wide",
        "p95_wide",
    ]
    return pd.DataFrame(rows, columns=cols).sort_values("mean_domain", ignore_index=True)


def _parse_variant(name: str) -> tuple[str, str, str]:
    """``"rule|cross=c|exp=e"`` -> ``(rule, c, e)``."""
    rule, cross, exponent = (part.split("=")[-1] for part in name.split("|"))
    return rule, cross, exponent


def variant_terms(name: str, d_over_L, phi0, phi1, alpha):
    """The rear excess (before ``k``) and the front excess of a variant of [2] (``L = 1``).

    ``name`` is a key of :func:`segplan.derivation.variants`; the variant reads
    ``LONGD ~ d (1 + k rear) + front``.
    """
    from . import derivation
    from .union import chord_slopes

    if name not in derivation.variants():
        raise ValueError(f"name must be a variant of segplan.derivation.variants(), got {name!r}")
    rule, cross, exponent = _parse_variant(name)
    m0, m1 = chord_slopes(phi0, phi1, alpha)
    rear = derivation.rear_lambdified(rule)(alpha, m0, m1)
    front = derivation.front_lambdified(cross, exponent)(d_over_L, alpha, m0, m1, 1.0)
    return np.broadcast_to(rear, np.shape(front)), front


def variant_domains():
    """Each variant of [2] calibrated on its own: ``k(alpha)`` and the domain where the bounds hold.

    :func:`variant_comparison` measures every variant inside the domain fitted for the
    derived [2], which favours it. Here each variant of
    :func:`segplan.derivation.variants` goes through the whole calibration
    (:func:`run_calibration` with the variant's terms), so each gets the largest domain
    where *its* errors meet the paper's bounds on the grid; a larger domain is a better
    formula.

    Returns
    -------
    pandas.DataFrame
        One row per variant: ``variant, rear, cross, exponent, k_c0, k_c1, n_inside,
        share_inside`` (of the grid points), ``max_error, mean_error`` (inside its domain),
        sorted by ``n_inside`` (largest first).
    """
    import pandas as pd

    from . import derivation

    g = calibration_grid()
    args = (g["d_over_L"], np.radians(g["phi0_deg"]), np.radians(g["phi1_deg"]), np.radians(g["alpha_deg"]))
    rows = []
    for name in derivation.variants():
        try:
            c = run_calibration(terms=variant_terms(name, *args))
            row = (*c.k_coef, c.n_inside, c.n_inside / c.n_grid, c.max_error, c.mean_error)
        except RuntimeError:  # no domain at all
            row = (math.nan, math.nan, 0, 0.0, math.nan, math.nan)
        rows.append((name, *_parse_variant(name), *row))
    cols = ["variant", "rear", "cross", "exponent", "k_c0", "k_c1", "n_inside", "share_inside"]
    cols += ["max_error", "mean_error"]
    df = pd.DataFrame(rows, columns=cols)
    return df.sort_values(["n_inside", "mean_error"], ascending=[False, True], ignore_index=True)


def exact_split(d_over_L, phi0, phi1, alpha, rtol: float = 1e-10):
    """Exact LONGD [1] and the exact rear-path length of many cases (``L = 1``).

    The rear length is [1] with ``L = 0`` (``int sqrt(1 + f'^2) dx``); LONGD minus it is
    the front-wheel excess that the last term of [2] approximates, and ``rear / d - 1``
    is the rear excess that ``k_alpha`` times the first term approximates.

    Returns
    -------
    longd, rear_length : ndarray
    """
    longd = exact_values(d_over_L, phi0, phi1, alpha, 1.0, rtol=rtol)
    rear = exact_values(d_over_L, phi0, phi1, alpha, 0.0, rtol=rtol)
    return longd, rear


def term_study(
    d_over_L,
    phi0,
    phi1,
    alpha,
    rules=("exact", "simpson", "second_order"),
    fronts=(("-1/2", "-5/2"), ("1/2", "-5/2")),
):
    """Each term of [2] against its exact counterpart, case by case, with no ``k`` fitted.

    Parameters
    ----------
    d_over_L, phi0, phi1, alpha : array_like
        Cases with ``L = 1`` (radians).
    rules : sequence of str
        Rear rules (:func:`segplan.derivation.rear_term`).
    fronts : sequence of (cross, exponent)
        Front terms (:func:`segplan.derivation.front_term`), rationals as strings.

    Returns
    -------
    pandas.DataFrame
        Columns ``d_over_L, alpha_deg, phi0_deg, phi1_deg, longd, rear_excess`` (exact
        ``rear length / d - 1``), ``front_excess`` (exact ``LONGD - rear length``); for
        each rule ``k_ideal|<rule>`` (the ``k`` that would make the first term exact:
        ``rear_excess / term``); for each front term ``front|cross=<c>|exp=<e>`` (its
        value).
    """
    import pandas as pd

    from . import derivation
    from .union import chord_slopes

    dl, p0, p1, a = (np.ravel(v).astype(float) for v in np.broadcast_arrays(d_over_L, phi0, phi1, alpha))
    longd, rear = exact_split(dl, p0, p1, a)
    m0, m1 = chord_slopes(p0, p1, a)
    out = {
        "d_over_L": dl,
        "alpha_deg": np.degrees(a),
        "phi0_deg": np.degrees(p0),
        "phi1_deg": np.degrees(p1),
        "longd": longd,
        "rear_excess": rear / dl - 1.0,
        "front_excess": longd - rear,
    }
    with np.errstate(divide="ignore", invalid="ignore"):  # a zero term (straight union) gives nan
        for rule in rules:
            out[f"k_ideal|{rule}"] = out["rear_excess"] / derivation.rear_lambdified(rule)(a, m0, m1)
    for cross, exponent in fronts:
        out[f"front|cross={cross}|exp={exponent}"] = derivation.front_lambdified(cross, exponent)(
            dl, a, m0, m1, 1.0
        )
    return pd.DataFrame(out)


def romberg_work(d_over_L, phi0, phi1, alpha, rtol: float, min_levels: int = 1):
    """Integrand evaluations Romberg needs for [1] to meet ``rtol``, case by case (``L = 1``).

    Section "Approximate computation of cost function" compares [2] with "Romberg
    integration with the same maximum error bound". Romberg's stopping rule
    (:func:`segplan.romberg.romberg`) is applied to each case alone, from ``min_levels``
    halvings on (level ``k`` uses ``2**k + 1`` points), so the count is the work that
    bound asks for. :func:`segplan.longd_exact` uses at least 4 levels (17 points).

    Returns
    -------
    evaluations : ndarray of int
        Integrand evaluations per case.
    value : ndarray
        Romberg's LONGD per case.
    """
    from .cost import longd_integrand
    from .romberg import romberg

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


def planner_links(scenarios, **options):
    """Every LONGD evaluation the planner makes while solving ``scenarios``, recorded.

    Each scenario is planned with :func:`segplan.plan_scenario` (the paper's search, ``options`` passed on);
    meanwhile every call of the planner's link cost (``Expander.link_cost``, which uses
    [2] inside the domain and [1] outside: :func:`segplan.cost.longd`) is recorded, for
    links (``g``) and heuristic estimates (``h'`` (a)) alike. The unions are the ones the
    search builds: in their optimal reference system
    (:func:`segplan.optimal_alpha_intrinsic`), or the steering fallback's frame.
    Instrumentation only: the planner runs unchanged.

    Parameters
    ----------
    scenarios : dict of str to Scenario
        Named scenarios.

    Returns
    -------
    pandas.DataFrame
        One row per evaluation: ``scenario, d_over_L, phi0_deg, phi1_deg, alpha_deg,
        in_plan`` (the union belongs to the plan found) and ``in_domain``. Scenarios
        without a plan (:class:`segplan.NoPathError`) contribute their evaluations with
        ``in_plan`` False.
    """
    from unittest import mock

    import pandas as pd

    from .expansion import Expander
    from .search import NoPathError, plan_scenario

    record = []
    original = Expander.link_cost

    def link_cost(self, u):
        record.append(u)
        return original(self, u)

    rows = []
    for name, scenario in scenarios.items():
        record.clear()
        with mock.patch.object(Expander, "link_cost", link_cost):
            try:
                unions = {id(u) for u in plan_scenario(scenario, **{"planner": "paper", **options}).unions}
            except NoPathError:
                unions = set()
        rows += [(name, u.d / u.L, u.phi0, u.phi1, u.alpha, id(u) in unions) for u in record]
    cols = ["scenario", "d_over_L", "phi0", "phi1", "alpha", "in_plan"]
    df = pd.DataFrame(rows, columns=cols)
    dl, p0, p1, a = (df[c].to_numpy(dtype=float) for c in ("d_over_L", "phi0", "phi1", "alpha"))
    df["in_domain"] = np.asarray(calibration().domain.contains(dl, p0, p1, a, 1.0), dtype=bool)
    for col in ("phi0", "phi1", "alpha"):
        df[col] = np.degrees(df[col])
    return df.rename(columns={"phi0": "phi0_deg", "phi1": "phi1_deg", "alpha": "alpha_deg"})
