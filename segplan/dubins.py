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

__all__ = ["dubins_length", "dubins_length_scalar"]

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


def dubins_length_scalar(
    x0: float, y0: float, theta0: float, x1: float, y1: float, theta1: float, R: float
) -> float:
    """:func:`dubins_length` of one pair of poses in Python floats (the same formulas, faster
    for one pair than numpy's per-call overhead; the caller validates ``R``)."""
    dx, dy = (x1 - x0) / R, (y1 - y0) / R
    d = math.hypot(dx, dy)
    th = math.atan2(dy, dx)
    a = (theta0 - th) % TWO_PI
    b = (theta1 - th) % TWO_PI
    sa, ca, sb, cb = math.sin(a), math.cos(a), math.sin(b), math.cos(b)
    cab = math.cos(a - b)
    dd = d * d
    best = math.inf
    p2 = 2.0 + dd - 2.0 * cab + 2.0 * d * (sa - sb)  # LSL
    if p2 >= 0:
        t1 = math.atan2(cb - ca, d + sa - sb)
        best = min(best, (t1 - a) % TWO_PI + math.sqrt(p2) + (b - t1) % TWO_PI)
    p2 = 2.0 + dd - 2.0 * cab + 2.0 * d * (sb - sa)  # RSR
    if p2 >= 0:
        t1 = math.atan2(ca - cb, d - sa + sb)
        best = min(best, (a - t1) % TWO_PI + math.sqrt(p2) + (t1 - b) % TWO_PI)
    p2 = -2.0 + dd + 2.0 * cab + 2.0 * d * (sa + sb)  # LSR
    if p2 >= 0:
        p = math.sqrt(p2)
        t2 = math.atan2(-ca - cb, d + sa + sb) - math.atan2(-2.0, p)
        best = min(best, (t2 - a) % TWO_PI + p + (t2 - b) % TWO_PI)
    p2 = -2.0 + dd + 2.0 * cab - 2.0 * d * (sa + sb)  # RSL
    if p2 >= 0:
        p = math.sqrt(p2)
        t2 = math.atan2(ca + cb, d - sa - sb) - math.atan2(2.0, p)
        best = min(best, (a - t2) % TWO_PI + p + (b - t2) % TWO_PI)
    c = (6.0 - dd + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0  # RLR
    if abs(c) <= 1.0:
        p = (TWO_PI - math.acos(c)) % TWO_PI
        t = (a - math.atan2(ca - cb, d - sa + sb) + 0.5 * p) % TWO_PI
        best = min(best, t + p + (a - b - t + p) % TWO_PI)
    c = (6.0 - dd + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0  # LRL
    if abs(c) <= 1.0:
        p = (TWO_PI - math.acos(c)) % TWO_PI
        t = (-a - math.atan2(ca - cb, d + sa - sb) + 0.5 * p) % TWO_PI
        best = min(best, t + p + (b - a - t + p) % TWO_PI)
    return R * best
