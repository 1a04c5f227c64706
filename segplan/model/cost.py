"""The cost LONGD: length of the front-wheel path, exact [1] and approximate [2].

Section "Cost function": the cost of a union is the length of the path of the front
wheel B (the only driving wheel; at constant wheel speed, the traversal time). With the
rear point on ``y = f(x)``, ``x`` in ``[x0, x1]``, formula [1] reads::

    LONGD = integral_x0^x1 sqrt(1 + f'(x)^2 + L^2 f''(x)^2 / (1 + f'(x)^2)^2) dx.   [1]

Formula [2] holds a fitted ``k_alpha`` and is used only inside a validated domain; both
are fitted by :mod:`segplan.fit.formula2` and read here from the data stored with the
package (:mod:`segplan.model.constants`): nothing is fitted at run time.

Every function here is vectorised: pose components, ``alpha`` and ``L`` may be arrays
that broadcast against each other.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from . import constants
from .pose import alpha_interval, check_length, intrinsic
from .romberg import romberg
from .union import Union, chord_slopes, cubic_coefficients

__all__ = [
    "chain_longd",
    "longd_intrinsic_scalar",
    "BLOCK",
    "K_COEF",
    "S2_CAP",
    "APPROX_DOMAIN",
    "Domain",
    "approx_terms",
    "checked_intrinsic",
    "exact_values",
    "in_domain",
    "k_alpha",
    "k_from_coef",
    "longd",
    "longd_approx",
    "longd_approx_intrinsic",
    "longd_exact",
    "longd_exact_intrinsic",
    "longd_gauss_intrinsic",
    "longd_integrand",
    "longd_intrinsic",
    "partial_lengths",
]


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
def _speed(x, X, c1, c2, c3, L):
    """``X`` times the integrand of [1] at the frame abscissae ``x``."""
    fp = c1 + (2.0 * c2 + 3.0 * c3 * x) * x  # f'(x)
    fpp = 2.0 * c2 + 6.0 * c3 * x  # f''(x)
    w = 1.0 + fp * fp  # 1 + f'^2
    return X * np.sqrt(w + (L * fpp / w) ** 2)  # [1]


def _front_speed(X, c1, c2, c3, L, each=False):
    """The integrand of [1] as a function of ``tau = x / X``, coefficients computed once:
    ``tau`` of shape ``(m,)`` gives ``(m, *batch)``; with ``each``, each union's ``m`` values
    contiguous (a transposed view: :func:`segplan.model.romberg.romberg`'s ``each``)."""
    if not each:
        return lambda tau: _speed(np.multiply.outer(tau, X), X, c1, c2, c3, L)
    cols = [np.asarray(v)[..., None] for v in (X, c1, c2, c3, L)]
    return lambda tau: np.moveaxis(_speed(np.multiply.outer(X, tau), *cols), -1, 0)


def longd_integrand(tau, d, phi0, phi1, alpha, L):
    """Integrand of [1] on the normalised abscissa ``tau = x / X`` in ``[0, 1]``.

    ``X sqrt(1 + f'^2 + L^2 f''^2 / (1 + f'^2)^2)`` at ``x = X tau``; ``tau`` of shape
    ``(m,)`` against parameters of shape ``batch`` gives ``(m, *batch)``.
    """
    return _front_speed(*cubic_coefficients(d, phi0, phi1, alpha), L)(tau)


def longd_exact_intrinsic(d, phi0, phi1, alpha, L, rtol=1e-10, full_output=False, each=False):
    """Formula [1] by Romberg integration, in intrinsic parameters (vectorised).

    The caller guarantees valid inputs (see :func:`checked_intrinsic`). A batch stops where
    every union's estimate meets ``rtol``; with ``each``, each union stops where its own
    does, and its value and error are those of a call for that union alone, to the last bit
    (:func:`segplan.model.romberg.romberg`): a batch of unions for about the time of one.

    Returns
    -------
    longd : float or ndarray
    error : float or ndarray
        Romberg's error estimate, only with ``full_output=True``.
    """
    d, phi0, phi1, alpha, L = np.broadcast_arrays(d, phi0, phi1, alpha, L)
    coef = cubic_coefficients(d, phi0, phi1, alpha, each=each)  # with each: as its own call computes them
    integrand = _front_speed(*coef, L, each)  # coefficients once
    value, error = romberg(integrand, 0.0, 1.0, rtol=rtol, each=each)
    if full_output:
        return _scalar_or_array(value), _scalar_or_array(error)
    return _scalar_or_array(value)


def partial_lengths(x, c1: float, c2: float, c3: float, L: float, rtol: float = 1e-10) -> np.ndarray:
    """Path lengths of one union from its start to the frame abscissae ``x``: [1] on ``[0, x]``.

    The integrand of [1] (:func:`longd_integrand`) integrated by the same Romberg rule
    (:func:`segplan.model.romberg.romberg`) over ``[0, x]`` instead of the whole span:
    with ``L`` the robot's length, the length of the front wheel's path up to ``x``
    (LONGD of the union at ``x = x_end``); with ``L = 0``, the arc length of the rear point
    A, ``int_0^x sqrt(1 + f'^2) dx`` (the "rear length" of :func:`segplan.studies.approx.exact_split`).

    Parameters
    ----------
    x : array_like
        Abscissae in the union's alpha frame, in ``[0, x_end]``.
    c1, c2, c3 : float
        The cubic's coefficients (:func:`segplan.model.union.cubic_coefficients`).
    L : float
        Robot length (>= 0; 0: the rear point's arc length).
    rtol : float
        Romberg's relative tolerance, met by every abscissa at once.

    Returns
    -------
    ndarray
        Lengths, shaped as ``x``.
    """
    x = np.asarray(x, dtype=float)
    value, _ = romberg(_front_speed(x, c1, c2, c3, L), 0.0, 1.0, rtol=rtol)  # int_0^1 x F(x tau) dtau
    return value


def chain_longd(unions: Iterable[Union], rtol: float, *, from_poses: bool = False) -> float:
    """Formula [1] of a chain of unions: the sum of each union's Romberg LONGD, in order.

    Section "Cost function": the cost of a path is the length of the front wheel's path,
    the sum over its unions of [1]. The planners report a plan's ``cost`` so, whatever
    cost guided their search ([2] inside its domain).

    Parameters
    ----------
    unions : iterable of Union
        The chain, in order (0.0 for none).
    rtol : float
        Romberg's relative tolerance for each union (:func:`longd_exact_intrinsic`).
    from_poses : bool
        Take each union's intrinsic parameters from its end poses again
        (:func:`checked_intrinsic`: numpy's ``hypot``, ``arctan2`` and :func:`segplan.model.pose.wrap`)
        instead of those it was built with (``u.d``, ``u.phi0``, ``u.phi1``); the two may
        differ in the last bit (a union built by :meth:`Union.from_intrinsic` from the
        ``math`` module's values). The paper planner and the refinement do so, the lattice
        planner does not; each keeps its form, so that no plan's cost changes.

    Returns
    -------
    float
        ``((0 + LONGD_1) + LONGD_2) + ...``, added one union at a time.
    """
    total = 0.0
    for u in unions:
        if from_poses:
            geo = checked_intrinsic(u.p0, u.p1, u.alpha, u.L)
        else:
            geo = (u.d, u.phi0, u.phi1, u.alpha, u.L)
        total += float(longd_exact_intrinsic(*geo, rtol=rtol))  # [1] by Romberg
    return total


def exact_values(d, phi0, phi1, alpha, L, rtol: float = 1e-6, chunk: int = 1024) -> np.ndarray:
    """Exact LONGD [1] of many cases, in chunks of similar difficulty.

    Romberg on a batch runs until its hardest member converges; sorting by the steepest
    frame heading ``max |phi_i + alpha|`` keeps easy cases in cheap batches.
    """
    d, phi0, phi1, alpha, L = (np.ravel(v) for v in np.broadcast_arrays(d, phi0, phi1, alpha, L))
    key = np.maximum(np.abs(phi0 + alpha), np.abs(phi1 + alpha))
    order = np.argsort(key, kind="stable")
    out = np.empty(d.shape)
    for part in np.array_split(order, max(1, -(-d.size // chunk))):
        out[part] = longd_exact_intrinsic(d[part], phi0[part], phi1[part], alpha[part], L[part], rtol=rtol)
    return out


#: Nodes and weights of the Gauss-Legendre rule of :func:`longd_gauss_intrinsic`, on [0, 1].
_GAUSS_NODES = 24
_GL_T, _GL_W = np.polynomial.legendre.leggauss(_GAUSS_NODES)
_GL_T, _GL_W = 0.5 * (_GL_T + 1.0), 0.5 * _GL_W


def longd_gauss_intrinsic(d, phi0, phi1, alpha, L):
    """Formula [1] by a fixed 24-point Gauss-Legendre rule (vectorised, no error estimate).

    Not the paper's: a cheap quadrature of the same integrand as :func:`longd_exact_intrinsic`,
    for the many trial links of :func:`segplan.refine` (screening and comparing them in
    one objective). No error bound; measured against Romberg at ``rtol=1e-12`` on 9,800
    random unions within the steering limit ``|kappa| <= 1/L`` (``d/L`` in [0.5, 20],
    headings to +-80 deg, heuristic frame): relative error at most 2.5e-5, median 7e-16;
    on a regular grid of 43,560 such unions the worst is 4.0e-5 (d/L = 11.5, headings
    +-80 deg). tests/test_cost_gauss.py checks a 5e-5 bound against ``scipy.integrate.quad``. Sharper cubics
    integrate less accurately: use :func:`longd_exact_intrinsic` where a bound matters.

    The caller guarantees valid inputs (see :func:`checked_intrinsic`).
    """
    d, phi0, phi1, alpha, L = np.broadcast_arrays(d, phi0, phi1, alpha, L)
    integrand = _front_speed(*cubic_coefficients(d, phi0, phi1, alpha), L)
    value = np.tensordot(_GL_W, integrand(_GL_T), axes=1)  # sum_k w_k F(tau_k)
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
    segplan.model.romberg.RombergError
        If the bound cannot be met (never a silent answer).
    """
    return longd_exact_intrinsic(*checked_intrinsic(p0, p1, alpha, L), rtol=rtol)


# -- the fitted constants of [2]: k_alpha and the validated domain ----------------------
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
        """Vectorised membership test (see :func:`in_domain`); a scalar fast path for floats."""
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


_STORED = constants.formula2()
#: ``(c0, c1)`` of ``k_alpha = c0 + c1 min(sin^2 alpha, S2_CAP)`` (stored fit).
K_COEF: tuple[float, float] = (float(_STORED["k_coef"][0]), float(_STORED["k_coef"][1]))
#: ``sin^2`` of the largest calibrated ``|alpha|`` (45 deg): ``k_alpha`` is constant beyond it.
S2_CAP: float = float(_STORED["s2_cap"])
#: The validated domain of [2] (stored fit).
APPROX_DOMAIN = Domain(
    tuple(float(v) for v in _STORED["domain"]["band_lower"]),
    tuple(float(v) for v in _STORED["domain"]["alpha_max"]),
    tuple(float(v) for v in _STORED["domain"]["phi_max"]),
)


def k_from_coef(coef, alpha, s2_cap: float = S2_CAP):
    """``k_alpha`` from its coefficients (vectorised): ``c0 + c1 min(sin^2 alpha, s2_cap)``."""
    return coef[0] + coef[1] * np.minimum(np.sin(alpha) ** 2, s2_cap)


def k_alpha(alpha):
    """The fitted ``k_alpha`` of formula [2] (vectorised; radians)."""
    return k_from_coef(K_COEF, alpha)


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
        (:data:`APPROX_DOMAIN`, fitted by :func:`segplan.fit.formula2.run_calibration`), False
        elsewhere.
    """
    inside = APPROX_DOMAIN.contains(d, phi0, phi1, alpha, L)
    return bool(inside) if np.ndim(inside) == 0 else inside


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
    Derivation (checked symbolically in :mod:`segplan.model.derivation`): a first-order
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


def longd_approx_intrinsic(d, phi0, phi1, alpha, L, k=None):
    """Formula [2] in intrinsic parameters (vectorised, no validation).

    ::

        LONGD ~ d [1 + k_alpha cos^2(alpha) Q1 / 15]
                + 2 L^2 / (d cos alpha) [1 / cos^2(alpha) + 2 Q1 / 15]^(-5/2) Q2      [2]

    with ``mbar_i = tan(phi_i + alpha) - tan(alpha)``, ``Q1 = mbar0^2 + mbar1^2 -
    mbar0 mbar1 / 2`` and ``Q2 = mbar0^2 + mbar1^2 + mbar0 mbar1`` (see
    :func:`approx_terms` and :mod:`segplan.model.derivation`).

    Parameters
    ----------
    d, phi0, phi1, alpha, L : float or ndarray
        Chord length, intrinsic headings and reference-system angle (radians), robot
        length; broadcast against each other. The caller guarantees validity
        (:func:`checked_intrinsic`).
    k : float or ndarray, optional
        ``k_alpha``; by default the fitted one (:func:`k_alpha`).

    Returns
    -------
    float or ndarray
    """
    if k is None:
        c0, c1 = K_COEF
    if np.ndim(d) == np.ndim(phi0) == np.ndim(phi1) == np.ndim(alpha) == np.ndim(L) == np.ndim(k) == 0:
        d, phi0, phi1, alpha, L = float(d), float(phi0), float(phi1), float(alpha), float(L)
        kk = c0 + c1 * min(math.sin(alpha) ** 2, S2_CAP) if k is None else float(k)
        return _approx_scalar(d, phi0, phi1, alpha, L, kk)
    if k is None:
        d, phi0, phi1, alpha, L = np.broadcast_arrays(d, phi0, phi1, alpha, L)
    else:
        d, phi0, phi1, alpha, L, k = np.broadcast_arrays(d, phi0, phi1, alpha, L, k)
    t = np.tan(alpha)
    m0 = np.tan(np.add(phi0, alpha))
    m0 -= t  # mbar0 = tan(phi0 + alpha) - tan(alpha)
    m1 = np.tan(np.add(phi1, alpha))
    m1 -= t  # mbar1
    q2 = m0 * m1  # mbar0 mbar1
    q1 = m0 * m0
    q1 += m1 * m1
    q1 -= 0.5 * q2  # Q1 = mbar0^2 + mbar1^2 - mbar0 mbar1 / 2
    q2 *= 1.5
    q2 += q1  # Q2 = Q1 + (3/2) mbar0 mbar1
    sec2 = t * t
    sec2 += 1.0  # 1 / cos^2(alpha)
    if k is None:
        kk = t * t
        kk /= sec2  # sin^2(alpha)
        np.minimum(kk, S2_CAP, out=kk)
        kk *= c1
        kk += c0  # k_alpha = c0 + c1 min(sin^2(alpha), S2_CAP)
    else:
        kk = k.astype(float)
    rear = kk * q1
    rear /= sec2
    rear *= 1.0 / 15.0
    rear += 1.0
    rear *= d  # d [1 + k_alpha cos^2(alpha) Q1 / 15]
    a = q1 * (2.0 / 15.0)
    a += sec2  # A = 1 / cos^2(alpha) + 2 Q1 / 15
    front = np.sqrt(a)
    front *= a
    front *= a  # A^(5/2)
    front = q2 / front  # Q2 A^(-5/2)
    front *= np.sqrt(sec2)
    front *= L * L
    front /= d
    front *= 2.0  # 2 L^2 / (d cos alpha) A^(-5/2) Q2
    rear += front
    return rear


def _approx_scalar(d: float, phi0: float, phi1: float, alpha: float, L: float, k: float) -> float:
    """Formula [2] for one case with the ``math`` module (same arithmetic as the array path)."""
    t = math.tan(alpha)
    m0 = math.tan(phi0 + alpha) - t  # mbar0
    m1 = math.tan(phi1 + alpha) - t  # mbar1
    q1 = m0 * m0 + m1 * m1 - 0.5 * m0 * m1  # Q1
    q2 = q1 + 1.5 * m0 * m1  # Q2
    sec2 = 1.0 + t * t  # 1 / cos^2(alpha)
    rear = d * (1.0 + k * q1 / sec2 / 15.0)  # d [1 + k_alpha cos^2(alpha) Q1 / 15]
    a = sec2 + q1 * (2.0 / 15.0)  # A = 1 / cos^2(alpha) + 2 Q1 / 15
    return rear + 2.0 * L * L * math.sqrt(sec2) / d * q2 / (
        a * a * math.sqrt(a)
    )  # + 2 L^2 / (d cos a) A^-5/2 Q2


def longd_approx(p0, p1, alpha, L):
    """LONGD by the closed approximation [2] (vectorised).

    Section "Approximate computation of cost function". Valid (``|relative error|`` under
    2.5 %) only inside the domain of :func:`in_domain`; use
    :func:`longd` to fall back on formula [1] outside it.

    Parameters
    ----------
    p0, p1 : (x, y, theta) or arrays of shape (..., 3)
        Start and end nodes.
    alpha : float or ndarray
        Reference-system angle (radians), inside the interval where the cubic exists.
    L : float or ndarray
        Robot length (> 0).

    Returns
    -------
    float or ndarray

    Raises
    ------
    ValueError
        Invalid input (see :func:`checked_intrinsic`).
    """
    shape = _block_shape(p0, p1, alpha, L)
    size = math.prod(shape) if shape is not None else 0
    if size <= 2 * BLOCK:
        return longd_approx_intrinsic(*checked_intrinsic(p0, p1, alpha, L))
    # Cache blocking: validate and evaluate BLOCK cases at a time (about 2x faster on
    # large arrays: the temporaries stay in cache).
    a, b = np.broadcast_to(p0, (*shape, 3)).reshape(-1, 3), np.broadcast_to(p1, (*shape, 3)).reshape(-1, 3)
    al = np.broadcast_to(np.asarray(alpha, dtype=float), shape).reshape(-1)
    ll = np.broadcast_to(np.asarray(L, dtype=float), shape).reshape(-1)
    out = np.empty(size)
    try:
        for i in range(0, size, BLOCK):
            j = i + BLOCK
            out[i:j] = longd_approx_intrinsic(*checked_intrinsic(a[i:j], b[i:j], al[i:j], ll[i:j]))
    except ValueError:
        checked_intrinsic(p0, p1, alpha, L)  # raises with the message for the whole input
        raise
    return out.reshape(shape)


#: Cases per block in :func:`longd_approx` on large inputs.
BLOCK = 16384


def _block_shape(p0, p1, alpha, L):
    """Broadcast shape of well-formed numeric array inputs, else None (unblocked path)."""
    if not all(isinstance(v, np.ndarray) and v.dtype.kind == "f" for v in (p0, p1)):
        return None
    if p0.ndim == 0 or p1.ndim == 0 or p0.shape[-1] != 3 or p1.shape[-1] != 3:
        return None
    try:
        alpha, L = np.asarray(alpha, dtype=float), np.asarray(L, dtype=float)
        return np.broadcast_shapes(p0.shape[:-1], p1.shape[:-1], alpha.shape, L.shape)
    except (TypeError, ValueError):
        return None


def longd_intrinsic(d, phi0, phi1, alpha, L, rtol=1e-10):
    """The planner's LONGD in intrinsic parameters: [2] inside the domain, [1] outside.

    The caller guarantees valid inputs (see :func:`checked_intrinsic`).
    """
    if np.ndim(d) == np.ndim(phi0) == np.ndim(phi1) == np.ndim(alpha) == np.ndim(L) == 0:
        d, phi0, phi1, alpha, L = float(d), float(phi0), float(phi1), float(alpha), float(L)
        if in_domain(d, phi0, phi1, alpha, L):
            return longd_approx_intrinsic(d, phi0, phi1, alpha, L)
        return longd_exact_intrinsic(d, phi0, phi1, alpha, L, rtol=rtol)
    d, phi0, phi1, alpha, L = np.broadcast_arrays(d, phi0, phi1, alpha, L)
    inside = in_domain(d, phi0, phi1, alpha, L)
    out = np.empty(d.shape)
    if np.any(inside):
        out[inside] = longd_approx_intrinsic(d[inside], phi0[inside], phi1[inside], alpha[inside], L[inside])
    outside = ~inside
    if np.any(outside):
        out[outside] = exact_values(
            d[outside], phi0[outside], phi1[outside], alpha[outside], L[outside], rtol=rtol
        )
    return out


def longd_intrinsic_scalar(d: float, phi0: float, phi1: float, alpha: float, L: float, rtol: float) -> float:
    """:func:`longd_intrinsic` of one union given in floats (the same value, faster).

    Formula [2] inside its domain (:func:`in_domain`), else Romberg on [1]; the scalar
    fast path the planner's link model uses.
    """
    if in_domain(d, phi0, phi1, alpha, L):
        return float(longd_approx_intrinsic(d, phi0, phi1, alpha, L))
    return float(longd_exact_intrinsic(d, phi0, phi1, alpha, L, rtol=rtol))


def longd(p0, p1, alpha, L, rtol=1e-10):
    """LONGD as the planner computes it: [2] inside its validated domain, [1] outside.

    Section "Approximate computation of cost function": "Out of the evaluated range for
    formula [2], the Romberg algorithm is used." The domain (bands of ``d / L``, ranges
    of ``|alpha|`` and of the intrinsic headings ``|phi_i|``) and ``k_alpha`` are fitted by
    :func:`segplan.fit.formula2.run_calibration` and stored with the package
    (:data:`K_COEF`, :data:`APPROX_DOMAIN`).

    Parameters
    ----------
    p0, p1 : (x, y, theta) or arrays of shape (..., 3)
        Start and end nodes.
    alpha : float or ndarray
        Reference-system angle (radians), inside the interval where the cubic exists.
    L : float or ndarray
        Robot length (> 0).
    rtol : float
        Romberg tolerance outside the domain.

    Returns
    -------
    float or ndarray

    Raises
    ------
    ValueError
        Invalid input (see :func:`checked_intrinsic`).
    """
    return longd_intrinsic(*checked_intrinsic(p0, p1, alpha, L), rtol=rtol)
