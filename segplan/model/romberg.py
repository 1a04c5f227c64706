"""Romberg integration with an error estimate, vectorised over a batch of integrals.

Section "Exact computation of cost function": "A Romberg numerical integration can be
used to assure a maximum error bound." ``scipy.integrate.romberg`` was removed from SciPy,
so the method is written here: the composite trapezoid rule on 1, 2, 4, ... intervals,
each level reusing the previous one's points, followed by Richardson extrapolation
(Romberg, 1955).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["RombergError", "romberg"]


class RombergError(RuntimeError):
    """Romberg integration did not reach the requested tolerance."""


def romberg(
    f: Callable[[np.ndarray], np.ndarray],
    a: float,
    b: float,
    rtol: float = 1e-10,
    atol: float = 0.0,
    min_levels: int = 4,
    max_levels: int = 22,
    each: bool = False,
) -> tuple[np.ndarray, np.ndarray]:
    """Integrate ``f`` over ``[a, b]`` by Romberg's method.

    Parameters
    ----------
    f : callable
        ``f(x)`` with ``x`` of shape ``(m,)`` returns an array of shape ``(m, *batch)``:
        a batch of integrands evaluated at the same abscissae.
    a, b : float
        Finite limits.
    rtol, atol : float
        Stop when ``|R(k, k) - R(k-1, k-1)| <= max(atol, rtol |R(k, k)|)`` holds for every
        integral of the batch, the usual Romberg error estimate.
    min_levels, max_levels : int
        Halvings done at least / at most (level ``k`` uses ``2**k + 1`` points).
    each : bool
        Stop each integral of the batch at the first level where its own estimate meets the
        tolerance (the value and error estimate of a call for that integral alone), rather
        than every integral at the first level where all do. A call for one integral sums
        its samples as one 1-d array; where ``f`` returns each integral's samples contiguous
        (the transpose of a ``(*batch, m)`` array), numpy sums each the same way, and the
        batch gives every integral's value of its own call to the last bit.

    Returns
    -------
    value, error : ndarray of shape ``batch``
        The extrapolated integrals and their error estimates.

    Raises
    ------
    ValueError
        Bad limits or tolerances.
    RombergError
        If the tolerance is not met after ``max_levels`` halvings (never a silent answer).
    """
    if not (np.isfinite(a) and np.isfinite(b)):
        raise ValueError(f"limits must be finite, got a={a}, b={b}")
    if not (rtol >= 0 and atol >= 0 and (rtol > 0 or atol > 0)):
        raise ValueError(f"need rtol >= 0, atol >= 0, not both zero; got rtol={rtol}, atol={atol}")
    if not 1 <= min_levels <= max_levels:
        raise ValueError(f"need 1 <= min_levels <= max_levels, got {min_levels}, {max_levels}")
    h = b - a
    ends = np.asarray(f(np.array([a, b], dtype=float)), dtype=float)
    row = [0.5 * h * (ends[0] + ends[1])]  # R(0, 0): one trapezoid
    if each:  # the integrals stopped, their values and error estimates
        done = np.zeros(np.shape(row[0]), dtype=bool)
        value = estimate = np.zeros(done.shape)
    for k in range(1, max_levels + 1):
        h *= 0.5
        mids = a + h * (2 * np.arange(2 ** (k - 1)) + 1)
        trap = 0.5 * row[0] + h * np.asarray(f(mids), dtype=float).sum(axis=0)  # R(k, 0)
        new = [trap]
        for j in range(1, k + 1):  # R(k, j) = R(k, j-1) + (R(k, j-1) - R(k-1, j-1)) / (4^j - 1)
            new.append(new[j - 1] + (new[j - 1] - row[j - 1]) / (4.0**j - 1.0))
        error = np.abs(new[k] - row[k - 1])
        row = new
        if k < min_levels:
            continue
        met = error <= np.maximum(atol, rtol * np.abs(new[k]))
        if not each:
            if np.all(met):
                return new[k], error
            continue
        stop = met & ~done
        value, estimate = np.where(stop, new[k], value), np.where(stop, error, estimate)
        done = done | met
        if np.all(done):
            return value, estimate
    if each:
        error = np.where(done, 0.0, error)  # the worst of those not stopped
    worst = float(np.max(error / np.maximum(np.abs(row[-1]), np.finfo(float).tiny)))
    raise RombergError(
        f"Romberg did not reach rtol={rtol}, atol={atol} in {max_levels} levels "
        f"(worst relative error estimate {worst:.3g})"
    )
