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

from ..model.pose import TWO_PI

__all__ = ["dubins_length", "dubins_length_scalar"]

#: Rounding allowance (radians, and squared units of ``R`` for a straight part): an arc angle
#: within ``ZERO`` below a full turn is a zero arc that rounding pushed below 0 and the
#: wrap then sent to ``2 pi``; a squared straight length within ``ZERO`` below 0 is a zero
#: straight part. Without it an end pose exactly on a turning circle of the start, some
#: straight segments and some identical poses got ``2 pi R`` too much (found against OMPL's
#: Dubins space by ``tests/test_lattice_oracles.py``). A shorter estimate stays admissible.
ZERO = 1e-9
#: A straight part of LSL or RSR shorter than ``SHORT`` (units of ``R``) leaves the direction
#: between the two arcs undefined (``atan2`` of two near-zero numbers), so the two arcs are
#: also taken as one, ``(b - a) mod 2 pi`` (LSL) or ``(a - b) mod 2 pi`` (RSR), plus the
#: straight part: never more than the word's length (the two arcs add up to that turn, or
#: to that turn plus a full turn), so still a lower bound.
SHORT = 1e-6


def _mod(a):
    m = np.mod(a, TWO_PI)
    return np.where(m > TWO_PI - ZERO, 0.0, m)


def _mod_scalar(a: float) -> float:
    m = a % TWO_PI
    return 0.0 if m > TWO_PI - ZERO else m


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
        q = np.sqrt(np.maximum(p2, 0))
        lsl = np.where(p2 >= -ZERO, _mod(t1 - a) + q + _mod(b - t1), inf)
        lsl = np.where(q < SHORT, np.minimum(lsl, q + _mod(b - a)), lsl)  # one arc: t1 undefined
        # RSR
        p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa)
        t1 = np.arctan2(ca - cb, d - sa + sb)
        q = np.sqrt(np.maximum(p2, 0))
        rsr = np.where(p2 >= -ZERO, _mod(a - t1) + q + _mod(t1 - b), inf)
        rsr = np.where(q < SHORT, np.minimum(rsr, q + _mod(a - b)), rsr)
        # LSR
        p2 = -2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb)
        p = np.sqrt(np.maximum(p2, 0))
        t2 = np.arctan2(-ca - cb, d + sa + sb) - np.arctan2(-2.0, p)
        lsr = np.where(p2 >= -ZERO, _mod(t2 - a) + p + _mod(t2 - b), inf)
        # RSL
        p2 = -2.0 + d * d + 2.0 * cab - 2.0 * d * (sa + sb)
        p = np.sqrt(np.maximum(p2, 0))
        t2 = np.arctan2(ca + cb, d - sa - sb) - np.arctan2(2.0, p)
        rsl = np.where(p2 >= -ZERO, _mod(a - t2) + p + _mod(b - t2), inf)
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
    a = _mod_scalar(theta0 - th)
    b = _mod_scalar(theta1 - th)
    sa, ca, sb, cb = math.sin(a), math.cos(a), math.sin(b), math.cos(b)
    cab = math.cos(a - b)
    dd = d * d
    best = math.inf
    p2 = 2.0 + dd - 2.0 * cab + 2.0 * d * (sa - sb)  # LSL
    if p2 >= -ZERO:
        t1 = math.atan2(cb - ca, d + sa - sb)
        q = math.sqrt(max(p2, 0.0))
        best = min(best, _mod_scalar(t1 - a) + q + _mod_scalar(b - t1))
        if q < SHORT:  # one arc: t1 undefined
            best = min(best, q + _mod_scalar(b - a))
    p2 = 2.0 + dd - 2.0 * cab + 2.0 * d * (sb - sa)  # RSR
    if p2 >= -ZERO:
        t1 = math.atan2(ca - cb, d - sa + sb)
        q = math.sqrt(max(p2, 0.0))
        best = min(best, _mod_scalar(a - t1) + q + _mod_scalar(t1 - b))
        if q < SHORT:
            best = min(best, q + _mod_scalar(a - b))
    p2 = -2.0 + dd + 2.0 * cab + 2.0 * d * (sa + sb)  # LSR
    if p2 >= -ZERO:
        p = math.sqrt(max(p2, 0.0))
        t2 = math.atan2(-ca - cb, d + sa + sb) - math.atan2(-2.0, p)
        best = min(best, _mod_scalar(t2 - a) + p + _mod_scalar(t2 - b))
    p2 = -2.0 + dd + 2.0 * cab - 2.0 * d * (sa + sb)  # RSL
    if p2 >= -ZERO:
        p = math.sqrt(max(p2, 0.0))
        t2 = math.atan2(ca + cb, d - sa - sb) - math.atan2(2.0, p)
        best = min(best, _mod_scalar(a - t2) + p + _mod_scalar(b - t2))
    c = (6.0 - dd + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0  # RLR
    if abs(c) <= 1.0:
        p = _mod_scalar(TWO_PI - math.acos(c))
        t = _mod_scalar(a - math.atan2(ca - cb, d - sa + sb) + 0.5 * p)
        best = min(best, t + p + _mod_scalar(a - b - t + p))
    c = (6.0 - dd + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0  # LRL
    if abs(c) <= 1.0:
        p = _mod_scalar(TWO_PI - math.acos(c))
        t = _mod_scalar(-a - math.atan2(ca - cb, d + sa - sb) + 0.5 * p)
        best = min(best, t + p + _mod_scalar(b - a - t + p))
    return R * best
