"""The cost LONGD: length of the front-wheel path, exact [1] and approximate [2].

Section "Cost function": the cost of a union is the length of the path of the front
wheel B (the only driving wheel; at constant wheel speed, the traversal time). With the
rear point on ``y = f(x)``, ``x`` in ``[x0, x1]``, formula [1] reads::

    LONGD = integral_x0^x1 sqrt(1 + f'(x)^2 + L^2 f''(x)^2 / (1 + f'(x)^2)^2) dx.   [1]

Every function here is vectorised: pose components, ``alpha`` and ``L`` may be arrays
that broadcast against each other.
"""

from __future__ import annotations

import numpy as np

from .pose import alpha_interval, check_length, intrinsic
from .romberg import romberg
from .union import chord_slopes, cubic_coefficients


# -- validation shared by the public functions -----------------------------------------
def checked_intrinsic(p0, p1, alpha, L):
    """Validate poses, ``alpha`` and ``L`` and return broadcast intrinsic parameters.

    Returns
    -------
    d, phi0, phi1, alpha, L : ndarray
        Broadcast against each other.

    Raises
    ------
    ValueError
        Malformed or non-finite poses, coincident points, ``L <= 0``, non-finite
        ``alpha`` or ``alpha`` outside the interval where the cubic exists.
    """
    geo = intrinsic(p0, p1)
    alpha = np.asarray(alpha, dtype=float)
    L = np.asarray(L, dtype=float)
    if not np.all(np.isfinite(alpha)):
        raise ValueError("alpha must be finite (radians)")
    if L.ndim == 0:
        check_length(float(L))
    elif not np.all(np.isfinite(L) & (L > 0)):
        raise ValueError("L must be positive and finite")
    d, phi0, phi1, alpha, L = np.broadcast_arrays(geo.d, geo.phi0, geo.phi1, alpha, L)
    lo, hi = alpha_interval(phi0, phi1)
    bad = ~((lo < alpha) & (alpha < hi))
    if np.any(bad):
        i = np.flatnonzero(bad.ravel())[0]
        lo_i, hi_i = np.ravel(lo)[i], np.ravel(hi)[i]
        where = "" if bad.ndim == 0 else f" (first at flat index {i})"
        raise ValueError(
            f"alpha={np.degrees(np.ravel(alpha)[i]):.4f} deg{where} lies outside the interval "
            f"({np.degrees(lo_i):.4f}, {np.degrees(hi_i):.4f}) deg where the cubic exists "
            "(|alpha| < 90 deg and |phi_i + alpha| < 90 deg; an empty interval means no "
            "alpha frame joins these headings)"
        )
    return d, phi0, phi1, alpha, L


def _scalar_or_array(value):
    return float(value) if np.ndim(value) == 0 else value


# -- formula [1] -----------------------------------------------------------------------
def longd_integrand(tau, d, phi0, phi1, alpha, L):
    """Integrand of [1] on the normalised abscissa ``tau = x / X`` in ``[0, 1]``.

    ``X sqrt(1 + f'^2 + L^2 f''^2 / (1 + f'^2)^2)`` at ``x = X tau``; ``tau`` of shape
    ``(m,)`` against parameters of shape ``batch`` gives ``(m, *batch)``.
    """
    X, c1, c2, c3 = cubic_coefficients(d, phi0, phi1, alpha)
    x = np.multiply.outer(tau, X)
    fp = c1 + (2.0 * c2 + 3.0 * c3 * x) * x  # f'(x)
    fpp = 2.0 * c2 + 6.0 * c3 * x  # f''(x)
    w = 1.0 + fp * fp  # 1 + f'^2
    return X * np.sqrt(w + (L * fpp / w) ** 2)  # [1]


def longd_exact_intrinsic(d, phi0, phi1, alpha, L, rtol=1e-10, full_output=False):
    """Formula [1] by Romberg integration, in intrinsic parameters (vectorised).

    The caller guarantees valid inputs (see :func:`checked_intrinsic`).

    Returns
    -------
    longd : float or ndarray
    error : float or ndarray
        Romberg's error estimate, only with ``full_output=True``.
    """
    d, phi0, phi1, alpha, L = np.broadcast_arrays(d, phi0, phi1, alpha, L)
    value, error = romberg(lambda tau: longd_integrand(tau, d, phi0, phi1, alpha, L), 0.0, 1.0, rtol=rtol)
    if full_output:
        return _scalar_or_array(value), _scalar_or_array(error)
    return _scalar_or_array(value)


def longd_exact(p0, p1, alpha, L, rtol=1e-10):
    """LONGD by formula [1], Romberg integration to relative error ``rtol``.

    Parameters
    ----------
    p0, p1 : (x, y, theta) or arrays of shape (..., 3)
        Start and end nodes.
    alpha : float or ndarray
        Reference-system angle (radians), inside the interval where the cubic exists.
    L : float or ndarray
        Robot length (> 0).
    rtol : float
        Relative error bound of the Romberg estimate (section "Exact computation of
        cost function").

    Returns
    -------
    float or ndarray
        Front-wheel path length.

    Raises
    ------
    ValueError
        Invalid input (see :func:`checked_intrinsic`).
    segplan.romberg.RombergError
        If the bound cannot be met (never a silent answer).
    """
    return longd_exact_intrinsic(*checked_intrinsic(p0, p1, alpha, L), rtol=rtol)


# -- formula [2] -----------------------------------------------------------------------
def approx_terms(d, phi0, phi1, alpha, L):
    """The two terms of the closed approximation [2] before ``k_alpha`` is applied.

    With ``mbar_i`` the end slopes relative to the chord,
    ``Q1 = mbar0^2 + mbar1^2 - mbar0 mbar1 / 2`` and ``Q2 = mbar0^2 + mbar1^2 + mbar0 mbar1``::

        LONGD ~ d [1 + k_alpha cos^2(alpha) Q1 / 15]
                + 2 L^2 / (d cos alpha) [1 / cos^2(alpha) + 2 Q1 / 15]^(-5/2) Q2      [2]

    Returns
    -------
    rear_excess, front_excess : ndarray
        ``cos^2(alpha) Q1 / 15`` (multiplied by ``d k_alpha`` in [2]) and the last term.

    Notes
    -----
    Derivation (checked symbolically in :mod:`segplan.derivation`): a first-order
    binomial expansion of the rear-path element gives ``d + (cos alpha / 2) int g'^2``,
    and ``int g'^2 = (2 X / 15) Q1`` for the Hermite bump ``g``; the front-wheel excess
    ``(L^2 / 2) int f''^2 (1 + f'^2)^(-5/2)`` takes the mean of ``1 + f'^2``
    (``1/cos^2 alpha + 2 Q1 / 15``) out of the integral, leaving ``int f''^2 = 4 Q2 / X``.
    """
    m0, m1 = chord_slopes(phi0, phi1, alpha)
    c = np.cos(alpha)
    q1 = m0 * m0 + m1 * m1 - 0.5 * m0 * m1
    q2 = m0 * m0 + m1 * m1 + m0 * m1
    rear_excess = c * c * q1 / 15.0
    front_excess = 2.0 * L * L / (d * c) * (1.0 / (c * c) + 2.0 * q1 / 15.0) ** -2.5 * q2
    return rear_excess, front_excess
