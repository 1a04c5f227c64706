"""The exact optimal reference system: the paper's secant method on dLONGD/dtan(alpha).

Section "Optimal Reference System", "Exact Algorithm": every alpha frame gives a different
cubic between the same two nodes; ``alpha_0`` minimises ``LONGD(alpha)`` (the length [1]
of the front-wheel path). The paper solves ``d LONGD / d tan(alpha) = 0`` by a secant
method "modified to avoid inflexion points", stopping when ``|LONGD(a) - LONGD(a_0)|`` is
below a tolerance (the paper's criterion is on LONGD, not on alpha). Here the derivative
is the integral of the analytic alpha-derivative of the integrand of [1] (Leibniz's rule;
the normalised abscissa ``tau = x / X`` has fixed limits), computed by
:func:`segplan.model.romberg.romberg`; the secant only runs inside brackets where the
derivative goes from negative to positive (minima, never maxima or inflexions) and falls
back to bisection; a sign scan over the whole feasible interval finds every minimum and
the best one is kept (LONGD(alpha) may have two local minima).

The paper's case-a closed form (:func:`parabola_alpha`, section "Heuristic Algorithm")
lives here too: its frame is always a stationary point of LONGD(alpha), so the exact
algorithm scans astride it. The public entry points are in :mod:`segplan.model.frame`.
"""

from __future__ import annotations

import numpy as np

from .pose import HALF_PI, alpha_interval
from .romberg import RombergError, romberg
from .union import chord_slopes

__all__ = [
    "MBAR_SCAN_CAP",
    "SCAN_TOL",
    "dlongd_integrand",
    "dlongd_dtan_intrinsic",
    "exact_alpha_intrinsic",
    "longd_unit",
    "mbar_max",
    "parabola_alpha",
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
    :func:`segplan.model.union.chord_slopes`: ``mbar_i = tan(phi_i + alpha) - tan(alpha)`` so
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
    :class:`segplan.model.romberg.RombergError` propagates (never a silent value).
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


def mbar_max(phi0, phi1, alpha):
    """``max(|mbar0|, |mbar1|)``: the larger chord-relative end slope (vectorised)."""
    m0, m1 = chord_slopes(phi0, phi1, alpha)
    return np.maximum(np.abs(m0), np.abs(m1))


def _dlongd_dalpha_unit(lam, phi0, phi1, alpha, rtol=1e-9, atol=1e-11):
    """``d (LONGD/d) / d alpha`` for ``d = 1``, ``L = lam = L/d``; 1-d arrays, same size.

    ``atol`` is relative to ``(1 + L/d)(1 + mbar^2)``, the size of the integrand (the
    integral cancels near a minimum, so an absolute bound must follow that size).
    """

    mbar = mbar_max(phi0, phi1, alpha)
    scale = (1.0 + lam) * (1.0 + mbar * mbar)  # size of dF/dalpha: atol is relative to it

    def fun(tau, idx):
        return dlongd_integrand(tau, 1.0, phi0[idx], phi1[idx], alpha[idx], lam[idx])[1] / scale[idx]

    return _bucketed(fun, mbar, rtol, atol) * scale


def longd_unit(lam, phi0, phi1, alpha, rtol=1e-12):
    """``LONGD / d`` by [1] for ``d = 1``, ``L = lam = L/d``; 1-d arrays of the same size.

    Romberg bucketed by difficulty (the integrand of :func:`dlongd_integrand`), to ``rtol``.
    """

    def fun(tau, idx):
        return dlongd_integrand(tau, 1.0, phi0[idx], phi1[idx], alpha[idx], lam[idx])[0]

    return _bucketed(fun, mbar_max(phi0, phi1, alpha), rtol, 0.0)


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
    ``[-pi/2, pi/2]`` (not a usable frame; :func:`segplan.model.frame.heuristic_alpha` clips it inside).
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
        ok = (mbar_max(phi0[i], phi1[i], probe) <= cap) & (probe != cur[i])
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
    keep = mbar_max(p0[prob], p1[prob], sa) <= MBAR_SCAN_CAP
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
        ok = mbar_max(p0[new_p], p1[new_p], new_a) <= MBAR_SCAN_CAP
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
    par_ok = par_ok[mbar_max(p0[par_ok], p1[par_ok], a_par[par_ok]) <= MBAR_SCAN_CAP]
    cand_prob.append(par_ok)  # the parabola frame itself (exactly stationary)
    cand_a.append(a_par[par_ok])
    # problems without any candidate (LONGD flat to the scan's accuracy): all scan points
    missing = np.setdiff1d(np.flatnonzero(~straight), np.concatenate(cand_prob))
    sel = np.isin(prob, missing)
    cand_prob.append(prob[sel])
    cand_a.append(sa[sel])
    cand_prob = np.concatenate(cand_prob).astype(int)
    cand_a = np.concatenate(cand_a).astype(float)

    vals = longd_unit(lam[cand_prob], p0[cand_prob], p1[cand_prob], cand_a, rtol=max(1e-13, 1e-2 * rtol))
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
        finite, non-empty feasible interval; see :func:`segplan.model.frame.optimal_alpha_intrinsic`).
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
    segplan.model.romberg.RombergError
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
