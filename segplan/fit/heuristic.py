"""The fit of the heuristic optimal reference system, case b.

Section "Optimal Reference System", "Heuristic Algorithm", case b: "A simple closed
formula has been developed, which interpolates optimal values computed exactly." The
paper never printed it; :func:`fit_heuristic` builds ours (:func:`segplan.model.frame.case_b_alpha`)
from exact optima (:func:`segplan.model.frame_exact.exact_alpha_intrinsic`) by weighted least
squares. The planner does not run this: it reads the coefficients stored with the package
(:func:`segplan.model.frame.heuristic_coefficients`, written by ``python -m segplan.fit``).
"""

from __future__ import annotations

import math

import numpy as np

from ..model.frame import HeuristicFit, heuristic_features
from ..model.frame_exact import exact_alpha_intrinsic, longd_unit
from ..model.pose import alpha_interval

__all__ = ["fit_heuristic"]


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
    vp = longd_unit(lam, p0, p1, np.minimum(alpha + h, hi - 1e-9), rtol=1e-10)
    vm = longd_unit(lam, p0, p1, np.maximum(alpha - h, lo + 1e-9), rtol=1e-10)
    k = np.maximum((vp + vm - 2.0 * v0) / (h * h * v0), 1e-9)
    u = (alpha - lo) / (hi - lo)
    z = np.log(u / (1.0 - u))
    w = np.sqrt(k) * (hi - lo) * u * (1.0 - u)  # d alpha / dz, scaled by sqrt(k)
    X = heuristic_features(p0, p1, np.log(dl), degree)
    coef, *_ = np.linalg.lstsq(X * w[:, None], z * w, rcond=None)
    rms = float(np.sqrt(np.mean((w * (X @ coef - z)) ** 2)))
    return HeuristicFit(
        coef, degree, math.radians(phi_max_deg), (math.log(lo_dl), math.log(hi_dl)), len(grid), rms
    )
