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
    for k in range(1, max_levels + 1):
        h *= 0.5
        mids = a + h * (2 * np.arange(2 ** (k - 1)) + 1)
        trap = 0.5 * row[0] + h * np.asarray(f(mids), dtype=float).sum(axis=0)  # R(k, 0)
        new = [trap]
        for j in range(1, k + 1):  # R(k, j) = R(k, j-1) + (R(k, j-1) - R(k-1, j-1)) / (4^j - 1)
            new.append(new[j - 1] + (new[j - 1] - row[j - 1]) / (4.0**j - 1.0))
        error = np.abs(new[k] - row[k - 1])
        row = new
        if k >= min_levels and np.all(error <= np.maximum(atol, rtol * np.abs(new[k]))):
            return new[k], error
    worst = float(np.max(error / np.maximum(np.abs(row[-1]), np.finfo(float).tiny)))
    raise RombergError(
        f"Romberg did not reach rtol={rtol}, atol={atol} in {max_levels} levels "
        f"(worst relative error estimate {worst:.3g})"
    )
