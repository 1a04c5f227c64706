"""Dubins path length: an admissible estimate of LONGD for the lattice planner (beyond the paper).

Every union of a plan keeps the rear path's curvature within ``1 / R``,
``R = L / tan(max_steer)``, and the robot drives forward only, so the rear point's path
from a pose to the goal is at least the shortest forward path of bounded curvature, the
Dubins path (Dubins 1957; the six words LSL, RSR, LSR, RSL, RLR, LRL, in the closed forms
of Shkel and Lumelsky 2001). The front wheel travels at least as far as the rear point
(its speed is the rear speed divided by the cosine of the steering angle), so the Dubins
length never exceeds LONGD [1]: ``h'`` built on it is admissible.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["dubins_length"]

TWO_PI = 2.0 * math.pi


def _mod(a):
    return np.mod(a, TWO_PI)


def dubins_length(x0, y0, theta0, x1, y1, theta1, R: float) -> np.ndarray:
    """Length of the shortest forward path of curvature at most ``1 / R`` (vectorised).

    Parameters
    ----------
    x0, y0, theta0, x1, y1, theta1 : float or array_like
        Start and end poses (radians); broadcast against each other.
    R : float
        Minimum turning radius (> 0).

    Returns
    -------
    ndarray
        Path lengths (same unit as the coordinates).
    """
    if not (isinstance(R, int | float) and math.isfinite(R) and R > 0):
        raise ValueError(f"R must be a finite number > 0, got {R!r}")
    dx = (np.asarray(x1, dtype=float) - x0) / R
    dy = (np.asarray(y1, dtype=float) - y0) / R
    d = np.hypot(dx, dy)
    th = np.arctan2(dy, dx)
    a = _mod(np.asarray(theta0, dtype=float) - th)
    b = _mod(np.asarray(theta1, dtype=float) - th)
    sa, ca, sb, cb = np.sin(a), np.cos(a), np.sin(b), np.cos(b)
    cab = np.cos(a - b)
    inf = np.inf
    with np.errstate(invalid="ignore"):
        # LSL
        p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sa - sb)
        t1 = np.arctan2(cb - ca, d + sa - sb)
        lsl = np.where(p2 >= 0, _mod(t1 - a) + np.sqrt(np.maximum(p2, 0)) + _mod(b - t1), inf)
        # RSR
        p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa)
        t1 = np.arctan2(ca - cb, d - sa + sb)
        rsr = np.where(p2 >= 0, _mod(a - t1) + np.sqrt(np.maximum(p2, 0)) + _mod(t1 - b), inf)
        # LSR
        p2 = -2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb)
        p = np.sqrt(np.maximum(p2, 0))
        t2 = np.arctan2(-ca - cb, d + sa + sb) - np.arctan2(-2.0, p)
        lsr = np.where(p2 >= 0, _mod(t2 - a) + p + _mod(t2 - b), inf)
        # RSL
        p2 = -2.0 + d * d + 2.0 * cab - 2.0 * d * (sa + sb)
        p = np.sqrt(np.maximum(p2, 0))
        t2 = np.arctan2(ca + cb, d - sa - sb) - np.arctan2(2.0, p)
        rsl = np.where(p2 >= 0, _mod(a - t2) + p + _mod(b - t2), inf)
        # RLR
        c = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0
        p = _mod(TWO_PI - np.arccos(np.clip(c, -1, 1)))
        t = _mod(a - np.arctan2(ca - cb, d - sa + sb) + 0.5 * p)
        rlr = np.where(np.abs(c) <= 1, t + p + _mod(a - b - t + p), inf)
        # LRL
        c = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0
        p = _mod(TWO_PI - np.arccos(np.clip(c, -1, 1)))
        t = _mod(-a - np.arctan2(ca - cb, d + sa - sb) + 0.5 * p)
        lrl = np.where(np.abs(c) <= 1, t + p + _mod(b - a - t + p), inf)
    return R * np.minimum.reduce((lsl, rsr, lsr, rsl, rlr, lrl))
