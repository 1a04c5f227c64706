"""The optimal reference system: the alpha frame whose cubic minimises LONGD.

Section "Optimal Reference System": every alpha frame gives a different cubic between
the same two nodes; the problem is to find ``alpha_0`` minimising ``LONGD(alpha)`` (the
length [1] of the front-wheel path).

Exact algorithm ("Exact Algorithm"): solve ``d LONGD / d tan(alpha) = 0`` by a secant
method "modified to avoid inflexion points", stopping when ``|LONGD(a) - LONGD(a_0)|``
is below a tolerance (the paper's criterion is on LONGD, not on alpha). Here the
derivative is the integral of the analytic alpha-derivative of the integrand of [1]
(Leibniz's rule; the normalised abscissa ``tau = x / X`` has fixed limits), computed by
:func:`segplan.romberg.romberg`; the secant only runs inside brackets where the
derivative goes from negative to positive (minima, never maxima or inflexions) and falls
back to bisection; a sign scan over the whole feasible interval finds every minimum and
the best one is kept (LONGD(alpha) may have two local minima).

Heuristic algorithm ("Heuristic Algorithm"): closed forms, see :func:`heuristic_alpha`.
Case a (intrinsic slopes of opposite signs, a C-shaped union): the frame minimising the
area between trajectory and chord, ``tan(alpha) = (1/m0 + 1/m1) / 2`` in our convention
(chord at ``+alpha``); that frame makes the union a parabola, and it is always a
stationary point of LONGD(alpha) (:func:`parabola_alpha`). Case b (same signs, an
S-shaped union): the paper's formula was never printed; ours is fitted to exact optima by
:func:`fit_heuristic` (lazily, at first use). :func:`heuristic_error_study` measures both
against the exact optimum.
"""

from __future__ import annotations

import math

import numpy as np

from ._frame_fit import HeuristicFit, fit_heuristic, heuristic_error_study
from .pose import HALF_PI, alpha_interval, check_length, intrinsic
from .romberg import RombergError, romberg
from .union import chord_slopes

__all__ = [
    "HeuristicFit",
    "fit_heuristic",
    "heuristic_error_study",
    "case_b_alpha",
    "heuristic_alpha",
    "heuristic_coefficients",
    "dlongd_integrand",
    "dlongd_dtan_intrinsic",
    "parabola_alpha",
    "exact_alpha_intrinsic",
    "optimal_alpha_intrinsic",
    "optimal_alpha",
]

#: Largest |mbar| (chord-relative end slope) at which the sign scan evaluates the
#: derivative. Inside the study range the optimum has |mbar| < 15; the cap bounds
#: Romberg's cost next to the ends of the feasible interval, where LONGD -> infinity.
MBAR_SCAN_CAP = 2.0e3
#: Romberg (rtol, atol) of the sign scan: only the sign of the derivative matters there.
SCAN_TOL = (1e-4, 1e-6)


# -- the derivative of [1] with respect to alpha ---------------------------------------
def dlongd_integrand(tau, d, phi0, phi1, alpha, L):
    """Integrand of [1] and its analytic derivative with respect to ``alpha``.

    On the normalised abscissa ``tau = x / X`` in ``[0, 1]`` (``X = d cos alpha``) the
    integrand of [1] is ``F = X sqrt(w + L^2 f''^2 / w^2)`` with ``w = 1 + f'^2``; with
    ``P = X f'' = mbar0 h10''(tau) + mbar1 h11''(tau)`` (no ``X`` in it)::

        F = sqrt(X^2 w + L^2 P^2 / w^2)
        dF/da = [2 X X_a w + X^2 w_a + 2 L^2 P P_a / w^2 - 2 L^2 P^2 w_a / w^3] / (2 F)

    with ``X_a = -d sin(alpha)``, ``w_a = 2 f' f'_a``, and the chain rule through
    :func:`segplan.union.chord_slopes`: ``mbar_i = tan(phi_i + alpha) - tan(alpha)`` so
    ``d mbar_i / d alpha = tan^2(phi_i + alpha) - tan^2(alpha)``,
    ``f' = tan(alpha) + mbar0 h10' + mbar1 h11'`` so
    ``f'_a = 1 + tan^2(alpha) + mbar0_a h10' + mbar1_a h11'``, and
    ``P_a = mbar0_a h10'' + mbar1_a h11''``. The limits of the ``tau`` integral do not
    depend on alpha, so Leibniz's rule reduces to differentiating under the integral.

    Parameters
    ----------
    tau : ndarray of shape (m,)
        Normalised abscissae.
    d, phi0, phi1, alpha, L : float or ndarray
        Intrinsic parameters (broadcast against each other, shape ``batch``); the caller
        keeps alpha inside the feasible interval.

    Returns
    -------
    F, dF_dalpha : ndarray of shape (m, *batch)
    """
    t = np.tan(alpha)
    T0, T1 = np.tan(np.add(phi0, alpha)), np.tan(np.add(phi1, alpha))
    m0, m1 = chord_slopes(phi0, phi1, alpha)  # mbar_i = tan(phi_i + alpha) - tan(alpha)
    m0a, m1a = T0 * T0 - t * t, T1 * T1 - t * t  # d mbar_i / d alpha
    X = np.multiply(d, np.cos(alpha))  # X = d cos(alpha)
    Xa = -np.multiply(d, np.sin(alpha))  # dX/dalpha
    s = np.reshape(tau, np.shape(tau) + (1,) * np.ndim(X))
    h10p, h11p = (3.0 * s - 4.0) * s + 1.0, (3.0 * s - 2.0) * s  # Hermite h10', h11'
    h10pp, h11pp = 6.0 * s - 4.0, 6.0 * s - 2.0  # h10'', h11''
    fp = t + m0 * h10p + m1 * h11p  # f'
    fpa = 1.0 + t * t + m0a * h10p + m1a * h11p  # d f' / d alpha
    P = m0 * h10pp + m1 * h11pp  # X f''
    Pa = m0a * h10pp + m1a * h11pp  # d P / d alpha
    w = 1.0 + fp * fp  # 1 + f'^2
    wa = 2.0 * fp * fpa  # dw/dalpha
    LP_w = L * P / w
    F = np.sqrt(X * X * w + LP_w * LP_w)  # [1] on tau
    dF = (2.0 * X * Xa * w + X * X * wa + 2.0 * L * L * P * Pa / (w * w) - 2.0 * LP_w * LP_w * wa / w) / (
        2.0 * F
    )
    return F, dF


def _romberg_levels(mbar_max):
    """Romberg halvings expected for chord-relative slopes up to ``mbar_max``.

    The integrand has peaks of width ~ 1 / (2 |mbar|) (where f' crosses zero while f''
    is large), which the trapezoid rule must resolve; measured: 8-10 halvings for
    ``|mbar| < 2`` at ``rtol = 1e-9``, one or two more per factor 4 in ``|mbar|``.
    """
    return np.clip(np.ceil(np.log2(np.maximum(mbar_max, 1.0))).astype(int) + 9, 9, 20)


def _bucketed(fun, mbar_max, rtol, atol, budget=1 << 20, max_levels=20):
    """Romberg over a batch of 1-d problems, bucketed by difficulty to bound the cost.

    ``fun(tau, idx)`` returns the integrand for the problems ``idx`` as ``(m, len(idx))``.
    Problems with similar ``mbar_max`` are integrated together, in chunks small enough
    that ``points x chunk`` stays below ``budget`` at the expected level; each chunk stops
    at its own level. A chunk that does not converge there is split and retried with
    three more levels, up to ``max_levels``; beyond that
    :class:`segplan.romberg.RombergError` propagates (never a silent value).
    """
    mbar_max = np.asarray(mbar_max, dtype=float)
    out = np.empty(mbar_max.shape)

    def run(idx, top):
        try:
            out[idx] = romberg(lambda tau: fun(tau, idx), 0.0, 1.0, rtol, atol, max_levels=top)[0]
        except RombergError:
            if top >= max_levels:
                raise
            sub = max(1, idx.size >> 3)
            for start in range(0, idx.size, sub):
                run(idx[start : start + sub], min(max_levels, top + 3))

    levels = _romberg_levels(mbar_max)
    for lev in np.unique(levels):
        idx_all = np.flatnonzero(levels == lev)
        chunk = max(1, budget >> int(lev))
        for start in range(0, idx_all.size, chunk):
            run(idx_all[start : start + chunk], int(lev))
    return out


def _mbar_max(phi0, phi1, alpha):
    m0, m1 = chord_slopes(phi0, phi1, alpha)
    return np.maximum(np.abs(m0), np.abs(m1))


def _dlongd_dalpha_unit(lam, phi0, phi1, alpha, rtol=1e-9, atol=1e-11):
    """``d (LONGD/d) / d alpha`` for ``d = 1``, ``L = lam = L/d``; 1-d arrays, same size.

    ``atol`` is relative to ``(1 + L/d)(1 + mbar^2)``, the size of the integrand (the
    integral cancels near a minimum, so an absolute bound must follow that size).
    """

    mbar = _mbar_max(phi0, phi1, alpha)
    scale = (1.0 + lam) * (1.0 + mbar * mbar)  # size of dF/dalpha: atol is relative to it

    def fun(tau, idx):
        return dlongd_integrand(tau, 1.0, phi0[idx], phi1[idx], alpha[idx], lam[idx])[1] / scale[idx]

    return _bucketed(fun, mbar, rtol, atol) * scale


def _longd_unit(lam, phi0, phi1, alpha, rtol=1e-12):
    """``LONGD / d`` by [1] for ``d = 1``, ``L = lam``; 1-d arrays of the same size."""

    def fun(tau, idx):
        return dlongd_integrand(tau, 1.0, phi0[idx], phi1[idx], alpha[idx], lam[idx])[0]

    return _bucketed(fun, _mbar_max(phi0, phi1, alpha), rtol, 0.0)


def dlongd_dtan_intrinsic(d, phi0, phi1, alpha, L, rtol=1e-10):
    """``d LONGD / d tan(alpha)``, the quantity the paper's secant method zeroes.

    Integral over ``tau`` of :func:`dlongd_integrand`'s derivative, by Romberg, times
    ``d alpha / d tan(alpha) = cos^2(alpha)``. Vectorised; the caller guarantees valid
    inputs (alpha inside the feasible interval).

    Parameters
    ----------
    d, phi0, phi1, alpha, L : float or ndarray
        Chord length, intrinsic headings, frame angle (radians) and robot length.
    rtol : float
        Romberg tolerance, relative to the derivative or, near its zeros, to ``d``.
    """
    d, phi0, phi1, alpha, L = (
        np.asarray(v, dtype=float) for v in np.broadcast_arrays(d, phi0, phi1, alpha, L)
    )
    shape = d.shape
    g = _dlongd_dalpha_unit(*(np.ravel(v) for v in (L / d, phi0, phi1, alpha)), rtol=rtol, atol=rtol * 1e-2)
    out = np.reshape(g, shape) * d * np.cos(alpha) ** 2
    return float(out) if out.ndim == 0 else out


# -- case a: the minimum-area frame (a parabola) ---------------------------------------
def parabola_alpha(phi0, phi1):
    """The paper's case-a closed form: the frame of minimum area, where the cubic is a parabola.

    Section "Heuristic Algorithm", case a. The signed area between the cubic and the chord
    is ``X^2 (mbar0 - mbar1) / 12``, and ``cos^2(alpha) mbar_i = 1 / (1/m_i - tan alpha)``
    with ``m_i = tan(phi_i)``; for slopes of opposite signs the feasible ``tan(alpha)``
    lies between ``1/m1`` and ``1/m0`` and the area is least at their midpoint::

        tan(alpha_a) = (1/m0 + 1/m1) / 2 = sin(phi0 + phi1) / (2 sin(phi0) sin(phi1)),

    where ``mbar0 = -mbar1``: the cubic term vanishes and the union is the parabola
    through both poses (its axis is parallel to the line from the chord's midpoint to
    the intersection of the two heading lines). That frame is always a stationary point
    of LONGD(alpha), for every ``L``: near it, the cubic of a rotated frame equals the
    rotated parabola up to second order in the rotation (a first-order rotation of
    ``y = c x^2`` is a cubic), so the curve itself - and every functional of it - is
    stationary. Whether it is the global minimum is another matter (see the book).

    Vectorised. For slopes of the same sign (case b) or a zero slope, the midpoint lies
    outside the feasible interval; the value is then ``atan`` of the formula, clipped to
    ``[-pi/2, pi/2]`` (not a usable frame; :func:`heuristic_alpha` clips it inside).
    """
    s0, s1 = np.sin(phi0), np.sin(phi1)
    num = np.sin(np.add(phi0, phi1))
    den = 2.0 * s0 * s1
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.arctan2(num * np.sign(den), np.abs(den))  # atan(num / den) in [-pi/2, pi/2]
    out = np.where(den == 0.0, HALF_PI * np.sign(num), out)
    return float(out) if np.ndim(out) == 0 else out


# -- exact algorithm --------------------------------------------------------------------
def _secant_refine(lam, phi0, phi1, al, ar, gl, gr, tol, max_iter=80):
    """Safeguarded secant on ``G(t) = d LONGD / d tan(alpha)`` inside brackets.

    Each bracket ``[al, ar]`` (alpha, radians) has ``G(al) < 0 <= G(ar)``, so it holds a
    minimum. The secant runs in ``t = tan(alpha)`` on the last two iterates; a step that
    leaves the bracket, or a bracket that did not halve over two steps, is replaced by
    bisection. Stops when ``|G_alpha(x)| (ar - al) <= tol``: with ``G`` monotone in the
    bracket, ``|LONGD(x) - LONGD(x_0)| <= |G_alpha(x)| |x - x_0|`` (the paper's criterion
    on LONGD).
    """
    al, ar, gl, gr = (np.array(v, dtype=float) for v in (al, ar, gl, gr))
    n = al.size
    x = np.where(np.abs(gl) < np.abs(gr), al, ar)
    gx = np.where(np.abs(gl) < np.abs(gr), gl, gr)
    # secant memory in t: previous and current iterates (start with the two ends)
    tp, gp = np.tan(al), gl * np.cos(al) ** 2
    tc, gc = np.tan(ar), gr * np.cos(ar) ** 2
    width_old = np.full(n, np.inf)
    active = np.abs(gx) * (ar - al) > tol
    for _ in range(max_iter):
        if not active.any():
            break
        i = np.flatnonzero(active)
        with np.errstate(divide="ignore", invalid="ignore"):
            tn = tc[i] - gc[i] * (tc[i] - tp[i]) / (gc[i] - gp[i])  # secant step in t
        xn = np.arctan(tn)
        mid = 0.5 * (al[i] + ar[i])
        width = ar[i] - al[i]
        bad = ~np.isfinite(xn) | (xn <= al[i]) | (xn >= ar[i]) | (width > 0.5 * width_old[i])
        xn = np.where(bad, mid, xn)
        width_old[i] = np.where(bad, width, width_old[i])
        # loose rtol while |G| is large; atol (relative to the integrand's size) near the root
        g = _dlongd_dalpha_unit(lam[i], phi0[i], phi1[i], xn, rtol=1e-3, atol=0.1 * tol)
        neg = g < 0.0
        al[i] = np.where(neg, xn, al[i])
        ar[i] = np.where(neg, ar[i], xn)
        tp[i], gp[i] = tc[i], gc[i]
        tc[i], gc[i] = np.tan(xn), g * np.cos(xn) ** 2
        x[i], gx[i] = xn, g
        active[i] = (np.abs(g) * (ar[i] - al[i]) > tol) & (ar[i] - al[i] > 1e-15 * (1.0 + np.abs(xn)))
    return x


def _scan_grid(lo, hi, n):
    """``n`` evenly spread interior scan points per problem (shape ``(k, n)``)."""
    u = np.arange(1, n + 1) / (n + 1)
    return lo[:, None] + (hi - lo)[:, None] * u[None, :]


def _edge_probe(lam, phi0, phi1, edge, inner, g_inner, want_negative, cap, rounds=40):
    """Walk from a scan point towards an end of the interval, halving the distance.

    Looks for a derivative of the sign that closes a minimum bracket next to the end
    (``want_negative``: a negative derivative next to the lower end). Stops at the
    first such sign, or when ``|mbar|`` exceeds ``cap``. Returns the last point, its
    derivative, and whether the bracket closed.
    """
    n = edge.size
    cur, gcur = inner.copy(), g_inner.copy()
    last, glast = inner.copy(), g_inner.copy()
    found = np.zeros(n, dtype=bool)
    active = np.ones(n, dtype=bool)
    for _ in range(rounds):
        i = np.flatnonzero(active)
        if i.size == 0:
            break
        probe = edge[i] + 0.5 * (cur[i] - edge[i])
        ok = (_mbar_max(phi0[i], phi1[i], probe) <= cap) & (probe != cur[i])
        active[i[~ok]] = False
        i, probe = i[ok], probe[ok]
        if i.size == 0:
            break
        g = _dlongd_dalpha_unit(lam[i], phi0[i], phi1[i], probe, *SCAN_TOL)
        last[i], glast[i] = cur[i], gcur[i]
        cur[i], gcur[i] = probe, g
        hit = (g < 0.0) if want_negative else (g >= 0.0)
        found[i[hit]] = True
        active[i[hit]] = False
    return cur, gcur, last, glast, found


def _exact_candidates(lam, p0, p1, rtol, n_scan):
    """Every local minimum the exact algorithm finds (see :func:`exact_alpha_intrinsic`).

    1-d arrays ``lam = L/d``, ``p0``, ``p1``. Returns ``(problem index, alpha, LONGD/d,
    number of minima per problem)``, candidates in no particular order.
    """
    n = lam.size
    lo, hi = (np.atleast_1d(v) for v in alpha_interval(p0, p1))
    straight = (p0 == 0.0) & (p1 == 0.0)  # LONGD == d for every alpha: keep alpha = 0

    # 1. scan points (flat: problem index, alpha); in case a, four more points astride the
    # parabola frame, always a stationary point: when it is a maximum, the minima on both
    # sides get cells of their own
    case_a = (np.sin(p0) * np.sin(p1) < 0.0) & ~straight
    a_par = np.where(case_a, parabola_alpha(p0, p1), np.nan)
    near, far = 1e-3 * (hi - lo), 2e-2 * (hi - lo)
    grid = np.column_stack((_scan_grid(lo, hi, n_scan), a_par - far, a_par - near, a_par + near, a_par + far))
    prob = np.broadcast_to(np.arange(n)[:, None], grid.shape).ravel()
    sa = grid.ravel()
    keep = np.isfinite(sa) & (sa > lo[prob]) & (sa < hi[prob]) & ~straight[prob]
    prob, sa = prob[keep], sa[keep]
    keep = _mbar_max(p0[prob], p1[prob], sa) <= MBAR_SCAN_CAP
    prob, sa = prob[keep], sa[keep]
    sg = _dlongd_dalpha_unit(lam[prob], p0[prob], p1[prob], sa, *SCAN_TOL)

    # 1b. where G has a positive local minimum (or a negative local maximum) it may cross
    # zero twice between scan points, hiding a minimum: subdivide both cells, twice
    for _ in range(2):
        order = np.lexsort((sa, prob))
        prob, sa, sg = prob[order], sa[order], sg[order]
        same = (prob[1:-1] == prob[:-2]) & (prob[1:-1] == prob[2:])
        gm, g0, gp = sg[:-2], sg[1:-1], sg[2:]
        dip = same & (((g0 > 0) & (g0 < gm) & (g0 < gp)) | ((g0 < 0) & (g0 > gm) & (g0 > gp)))
        j = np.flatnonzero(dip) + 1
        if j.size == 0:
            break
        frac = np.array([0.25, 0.5, 0.75])
        new_a = np.concatenate(
            [
                (sa[j - 1, None] + (sa[j] - sa[j - 1])[:, None] * frac).ravel(),
                (sa[j, None] + (sa[j + 1] - sa[j])[:, None] * frac).ravel(),
            ]
        )
        new_p = np.concatenate([np.repeat(prob[j], 3), np.repeat(prob[j], 3)])
        ok = _mbar_max(p0[new_p], p1[new_p], new_a) <= MBAR_SCAN_CAP
        new_p, new_a = new_p[ok], new_a[ok]
        prob = np.concatenate([prob, new_p])
        sa = np.concatenate([sa, new_a])
        sg = np.concatenate([sg, _dlongd_dalpha_unit(lam[new_p], p0[new_p], p1[new_p], new_a, *SCAN_TOL)])
    order = np.lexsort((sa, prob))
    prob, sa, sg = prob[order], sa[order], sg[order]

    # 2. brackets between consecutive scan points of a problem: G < 0 then G >= 0
    j = np.flatnonzero((prob[1:] == prob[:-1]) & (sg[:-1] < 0.0) & (sg[1:] >= 0.0))
    br = [prob[j], sa[j], sa[j + 1], sg[j], sg[j + 1]]
    cand_prob, cand_a = [], []

    # 3. ends of the interval: probe where LONGD decreases towards an end
    starts = np.r_[True, prob[1:] != prob[:-1]]
    ends = np.r_[prob[1:] != prob[:-1], True]
    for side in ("lo", "hi"):
        if side == "lo":
            i = np.flatnonzero(starts & (sg >= 0.0))
            edge, want_neg = lo[prob[i]], True
        else:
            i = np.flatnonzero(ends & (sg < 0.0))
            edge, want_neg = hi[prob[i]], False
        if i.size == 0:
            continue
        k = prob[i]
        cur, gcur, prev, gprev, found = _edge_probe(
            lam[k], p0[k], p1[k], edge, sa[i], sg[i], want_neg, MBAR_SCAN_CAP
        )
        if want_neg:  # cur < prev, G(cur) < 0 <= G(prev)
            add = [k[found], cur[found], prev[found], gcur[found], gprev[found]]
        else:  # prev < cur, G(prev) < 0 <= G(cur)
            add = [k[found], prev[found], cur[found], gprev[found], gcur[found]]
        br = [np.concatenate([a, b]) for a, b in zip(br, add, strict=True)]
        cand_prob.append(k[~found])  # LONGD still decreasing at the cap: infimum at the end
        cand_a.append(cur[~found])

    # 4. refine every minimum bracket
    n_min = np.bincount(br[0], minlength=n) + np.bincount(
        np.concatenate(cand_prob or [np.zeros(0, int)]), minlength=n
    )
    if br[0].size:
        cand_prob.append(br[0])
        cand_a.append(_secant_refine(lam[br[0]], p0[br[0]], p1[br[0]], *br[1:], tol=rtol))
    par_ok = np.flatnonzero(case_a)
    par_ok = par_ok[_mbar_max(p0[par_ok], p1[par_ok], a_par[par_ok]) <= MBAR_SCAN_CAP]
    cand_prob.append(par_ok)  # the parabola frame itself (exactly stationary)
    cand_a.append(a_par[par_ok])
    # problems without any candidate (LONGD flat to the scan's accuracy): all scan points
    missing = np.setdiff1d(np.flatnonzero(~straight), np.concatenate(cand_prob))
    sel = np.isin(prob, missing)
    cand_prob.append(prob[sel])
    cand_a.append(sa[sel])
    cand_prob = np.concatenate(cand_prob).astype(int)
    cand_a = np.concatenate(cand_a).astype(float)

    vals = _longd_unit(lam[cand_prob], p0[cand_prob], p1[cand_prob], cand_a, rtol=max(1e-13, 1e-2 * rtol))
    return cand_prob, cand_a, vals, n_min


def exact_alpha_intrinsic(d, phi0, phi1, L, rtol=1e-10, n_scan=24, full_output=False):
    """Globally optimal alpha by the paper's exact algorithm (vectorised).

    Section "Optimal Reference System", "Exact Algorithm". Works on ``LONGD/d``, a
    function of ``(L/d, phi0, phi1, alpha)``:

    1. Scan the sign of ``dLONGD/dalpha`` at ``n_scan`` points evenly spread over the
       feasible interval, plus four points astride the parabola frame in case a
       (:func:`parabola_alpha`, always a stationary point), skipping points where
       ``|mbar| > MBAR_SCAN_CAP``. Where the derivative has a positive local minimum (or
       a negative local maximum) between scan points, subdivide those cells (twice): a
       pair of sign changes may hide there.
    2. Where LONGD decreases from the first (last) scan point towards the end of the
       interval, probe towards that end by halving the distance until the derivative
       changes sign. At an end where an end slope turns vertical (``phi_i + alpha ->
       +-pi/2`` with ``phi_i != 0``) LONGD -> infinity, so the sign always changes. At an
       end ``alpha -> +-pi/2`` with both headings on the other side of the chord (or
       zero), ``X -> 0`` and the cubic degenerates into the chord with the robot
       pivoting in place at its ends: LONGD tends to the finite limit
       ``d + L (|phi0| + |phi1|)``, which can be the infimum (large d/L); the probe
       then stops where ``|mbar|`` reaches ``MBAR_SCAN_CAP``.
    3. Refine every bracket where the derivative goes from negative to positive (a
       minimum; maxima and inflexions never qualify) by the safeguarded secant of
       :func:`_secant_refine`, to ``|LONGD(a) - LONGD(a_0)| <= rtol * d``.
    4. Keep the candidate (refined minima, the parabola frame) with the least LONGD
       [1] (Romberg, to ``rtol / 100``).

    Parameters
    ----------
    d, phi0, phi1, L : float or ndarray
        Broadcast against each other. Validated by the caller (``d > 0``, ``L > 0``,
        finite, non-empty feasible interval; see :func:`optimal_alpha_intrinsic`).
    rtol : float
        Tolerance on LONGD relative to ``d`` (``LONGD >= d``).
    n_scan : int
        Evenly spread scan points per problem.
    full_output : bool
        Also return the optimal LONGD and the number of local minima found.

    Returns
    -------
    alpha : float or ndarray
        Strictly inside the feasible interval. ``0`` for ``phi0 = phi1 = 0`` (a straight
        union: LONGD = d in every frame). When LONGD keeps decreasing towards a pivot end
        (an infimum that no cubic attains) the frame of the last probe before ``|mbar|``
        reaches the scan cap.
    longd, n_minima : float or ndarray, int or ndarray
        Only with ``full_output=True``.

    Raises
    ------
    segplan.romberg.RombergError
        Only for feasible intervals so narrow (well beyond the +-90 deg of headings the
        planner uses) that Romberg cannot reach its tolerance in 2**20 intervals.
    """
    d, phi0, phi1, L = (np.asarray(v, dtype=float) for v in np.broadcast_arrays(d, phi0, phi1, L))
    shape = d.shape
    lam, p0, p1 = (np.ravel(v) for v in (L / d, phi0, phi1))
    n = lam.size
    lo, hi = (np.atleast_1d(v) for v in alpha_interval(p0, p1))
    cand_prob, cand_a, vals, n_min = _exact_candidates(lam, p0, p1, rtol, n_scan)
    alpha = np.zeros(n)
    longd = np.ones(n)
    if cand_prob.size:
        order = np.lexsort((vals, cand_prob))
        cp, ca, cv = cand_prob[order], cand_a[order], vals[order]
        firsts = np.r_[True, cp[1:] != cp[:-1]]
        alpha[cp[firsts]] = ca[firsts]
        longd[cp[firsts]] = cv[firsts]
    alpha = np.clip(alpha, np.nextafter(lo, hi), np.nextafter(hi, lo))
    alpha, longd = alpha.reshape(shape), (longd * np.ravel(d)).reshape(shape)
    n_min = n_min.reshape(shape)
    if shape == ():
        alpha, longd, n_min = float(alpha), float(longd), int(n_min)
    if full_output:
        return alpha, longd, n_min
    return alpha


# -- heuristic algorithm ----------------------------------------------------------------
_FIT_CACHE: dict = {}


def heuristic_coefficients():
    """The fitted case-b coefficients, computed at first use and cached in memory.

    Runs :func:`segplan._frame_fit.fit_heuristic` with its defaults (396 exact optima,
    about half a second); no coefficient is typed in.
    """
    if "fit" not in _FIT_CACHE:
        _FIT_CACHE["fit"] = fit_heuristic()
    return _FIT_CACHE["fit"]


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
    The coefficients ``c_ijk`` come from :func:`segplan._frame_fit.fit_heuristic`; the
    headings and ``l`` are clamped to the fitted box (by default headings to 80 deg,
    d/L in [0.25, 100]), outside which the formula is a constant extrapolation that
    stays inside the interval.

    Vectorised; requires ``phi0 * phi1 >= 0`` (case b, or a zero slope), not both zero.
    """
    fit = heuristic_coefficients() if fit is None else fit
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
      frame :func:`parabola_alpha` is always a stationary point of LONGD(alpha) and the
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
    :func:`segplan._frame_fit.heuristic_error_study` and random samples; see the book):
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
        Case-b coefficients; default :func:`heuristic_coefficients`.
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
        alpha[case_a] = np.where(_mbar_max(p0, p1, a_b) < _mbar_max(p0, p1, a_par), a_b, a_par)
    alpha = inside(alpha, phi0, phi1, margin)
    return float(alpha) if np.ndim(alpha) == 0 else alpha


def _interval(phi0, phi1):
    """Scalar :func:`segplan.pose.alpha_interval`."""
    return -HALF_PI - min(phi0, phi1, 0.0), HALF_PI - max(phi0, phi1, 0.0)


def _inside_scalar(alpha, phi0, phi1, margin):
    lo, hi = _interval(phi0, phi1)
    m = margin * (hi - lo)
    return min(max(alpha, lo + m), hi - m)


def _mbar_scalar(phi0, phi1, alpha):
    t = math.tan(alpha)
    return max(abs(math.tan(phi0 + alpha) - t), abs(math.tan(phi1 + alpha) - t))


def _terms(fit):
    """``(c_ijk, i, j, k)`` of a fit as plain Python numbers (cached per fit object)."""
    cached = _FIT_CACHE.get("terms")
    if cached is None or cached[0] is not fit:
        cached = (fit, [(c, *e) for c, e in zip(fit.coef.tolist(), fit.exponents(), strict=True)])
        _FIT_CACHE["terms"] = cached
    return cached[1]


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
    fit = heuristic_coefficients() if fit is None else fit
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
        (:func:`segplan.pose.alpha_interval`) must be non-empty.
    L : float or ndarray
        Robot length (> 0).
    method : {"heuristic", "exact", "parabola"}
        ``"exact"``: :func:`exact_alpha_intrinsic` (keyword arguments go to it).
        ``"heuristic"``: :func:`heuristic_alpha`. ``"parabola"``: the paper's case-a
        formula alone (:func:`parabola_alpha`), clipped inside the feasible interval -
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
    :func:`segplan.frame.heuristic_alpha` (the paper's case a, our fitted case b).

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
