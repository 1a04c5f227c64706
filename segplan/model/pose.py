"""Poses of the oriented-segment robot and the paper's reference systems.

Section "Mobile robot modelling": the robot is the segment from A (middle of the rear
axle) to B (middle of the front wheel), of length ``L``. A node of the search graph is a
pose ``(x, y, theta)``: A in world coordinates and the heading of A->B, radians,
counter-clockwise from +x. Angle differences are wrapped to ``(-pi, pi]`` (:func:`wrap`,
the package's convention).

Angle wrapping has its one home here. The forms below are not duplicates: they round
differently or differ at ``+-pi``, and the planners' plans depend on their last bits, so
each caller keeps its own (issue 24):

======================= ============== ================================================
function                interval       arithmetic
======================= ============== ================================================
:func:`wrap`            ``(-pi, pi]``  ``a - 2 pi round(a / 2 pi)``, then fold (numpy)
:func:`wrap_scalar`     ``(-pi, pi]``  the same operations on one float (its fast path)
:func:`wrap_fmod`       ``(-pi, pi]``  ``fmod(a + pi, 2 pi)`` (exact), then shift
:func:`wrap_ieee`       ``[-pi, pi]``  IEEE ``remainder(a, 2 pi)`` (exact; ``-pi`` stays)
:func:`wrap_floor`      ``[-pi, pi)``  ``(a + pi) mod 2 pi - pi`` (numpy, floor modulo)
======================= ============== ================================================
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

HALF_PI = 0.5 * math.pi
#: A full turn, ``2 pi`` (radians).
TWO_PI = 2.0 * math.pi

__all__ = [
    "show_pose",
    "wrap_fmod",
    "wrap_scalar",
    "HALF_PI",
    "TWO_PI",
    "Intrinsic",
    "Pose",
    "alpha_interval",
    "arc_end",
    "as_pose",
    "as_poses",
    "check_alpha",
    "check_length",
    "feasible_alpha_interval",
    "intrinsic",
    "intrinsic_interval",
    "wrap",
    "wrap_floor",
    "wrap_ieee",
]


class Pose(NamedTuple):
    """A node: rear-axle point A ``(x, y)`` and heading ``theta`` of A->B (radians)."""

    x: float
    y: float
    theta: float


class Intrinsic(NamedTuple):
    """Two poses in their intrinsic reference system (Fig. 3).

    Attributes
    ----------
    d : float
        Chord length, distance between the two rear-axle points.
    psi : float
        World angle of the chord.
    phi0, phi1 : float
        Intrinsic headings, ``wrap(theta_i - psi)`` in ``(-pi, pi]``.
    """

    d: float
    psi: float
    phi0: float
    phi1: float


def wrap(angle):
    """Wrap angles to ``(-pi, pi]`` (scalars or arrays): segplan's one convention.

    Every angle difference in segplan (intrinsic headings, heading changes) is wrapped
    here, to the half-open interval ``(-pi, pi]``: ``-pi`` maps to ``+pi``, so a reversal
    (a goal heading opposite to the chord) reads ``+pi``. The scalar fast path
    :func:`wrap_scalar` performs the same operations; :func:`wrap_fmod` is the planner's
    scalar form (equal but for the last bit).
    """
    a = np.asarray(angle, dtype=float)
    a = a - TWO_PI * np.round(a / TWO_PI)  # in [-pi, pi] up to rounding
    a = np.where(a <= -math.pi, a + TWO_PI, np.where(a > math.pi, a - TWO_PI, a))
    return float(a) if np.ndim(a) == 0 else a


def as_pose(p: Sequence[float] | Pose, name: str = "pose") -> Pose:
    """Validate a pose given as a ``Pose`` or any ``(x, y, theta)`` sequence.

    Raises
    ------
    ValueError
        If ``p`` does not have three components or any is not a finite number.
    """
    try:
        values = [float(v) for v in p]
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a sequence (x, y, theta) of numbers, got {p!r}") from exc
    if len(values) != 3:
        raise ValueError(f"{name} must have three components (x, y, theta), got {len(values)}")
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"{name} must have finite components, got {tuple(values)}")
    return Pose(*values)


def show_pose(p) -> str:
    """A pose as users read it: ``(x=.., y=.., theta=.. deg)`` (headings in degrees in every
    message, as in scenario files and the command line's output; issue 27)."""
    x, y, theta = (float(v) for v in p)
    return f"(x={x:g}, y={y:g}, theta={math.degrees(theta):g} deg)"


def check_length(L: float, name: str = "L") -> float:
    """Validate the robot length ``L > 0`` (finite)."""
    try:
        value = float(L)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a positive number, got {L!r}") from exc
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"{name} must be a positive finite number, got {value}")
    return value


def as_poses(p, name: str = "pose") -> np.ndarray:
    """Validate one pose ``(3,)`` or a batch ``(..., 3)`` and return a float array.

    Raises
    ------
    ValueError
        If the last axis is not of length 3 or any component is not finite.
    """
    try:
        arr = np.asarray(p, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be (x, y, theta) numbers or an (n, 3) array, got {p!r}") from exc
    if arr.ndim == 0 or arr.shape[-1] != 3:
        raise ValueError(f"{name} must have a last axis of length 3 (x, y, theta), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must have finite components")
    return arr


def intrinsic(p0, p1) -> Intrinsic:
    """Chord length, chord angle and intrinsic headings of two poses (Fig. 3).

    Accepts single poses (returns floats) or batches of shape ``(..., 3)`` that broadcast
    against each other (returns arrays).

    Raises
    ------
    ValueError
        If a pose is malformed or the two rear-axle points coincide (``d == 0``): no
        intrinsic system exists.
    """
    fast = _intrinsic_scalar(p0, p1)
    if fast is not None:
        return fast
    a = as_poses(p0, "p0")
    b = as_poses(p1, "p1")
    dx, dy = b[..., 0] - a[..., 0], b[..., 1] - a[..., 1]
    d = np.hypot(dx, dy)
    scale = np.maximum(
        np.maximum(
            np.maximum(np.abs(a[..., 0]), np.abs(a[..., 1])), np.maximum(np.abs(b[..., 0]), np.abs(b[..., 1]))
        ),
        1.0,
    )
    if np.any(d <= 1e-12 * scale):
        raise ValueError("p0 and p1 have coincident points; the chord length d must be > 0")
    psi = np.arctan2(dy, dx)
    out = Intrinsic(d, psi, wrap(a[..., 2] - psi), wrap(b[..., 2] - psi))
    if np.ndim(d) == 0:
        return Intrinsic(*(float(v) for v in out))
    return out


def wrap_scalar(a: float) -> float:
    """:func:`wrap` of one float, the same operations (``round`` halves to even like numpy's)."""
    a = a - TWO_PI * round(a / TWO_PI)
    if a <= -math.pi:
        return a + TWO_PI
    return a - TWO_PI if a > math.pi else a


def arc_end(x: float, y: float, theta: float, radius: float, side: float, turn: float):
    """The rear point after driving ``turn`` radians (negative: backwards) along the circle
    of ``radius`` to the left (``side = 1``) or the right (``-1``) of the pose ``(x, y,
    theta)``: ``(x, y, heading)``, the heading not wrapped (each caller wraps it its own way).

    The paper's turn states (:meth:`segplan.planning.paper.expansion.Expander.turn_states`) and the tight
    arcs of :mod:`segplan.planning.lattice.escape` are such poses.
    """
    cx, cy = x - side * radius * math.sin(theta), y + side * radius * math.cos(theta)
    t = theta + side * turn
    return cx + side * radius * math.sin(t), cy - side * radius * math.cos(t), t


def wrap_fmod(a: float) -> float:
    """:func:`wrap` of one float computed with ``math.fmod``: the planner's scalar wrap.

    The same convention, ``(-pi, pi]``, and the same value as :func:`wrap_scalar` except,
    for some angles, in the last bit (``fmod`` is exact; the ``round`` form rounds once
    more). The planner's link model and node generation use this form: the paper's search
    is sensitive to the last bit of a heading (a tie between two successors), and its
    published numbers in the book were computed with it, so it stays.
    """
    a = math.fmod(a + math.pi, TWO_PI)
    if a <= 0.0:
        a += TWO_PI
    return a - math.pi


def wrap_ieee(a: float) -> float:
    """One float wrapped to ``[-pi, pi]`` by the IEEE remainder, ``math.remainder(a, 2 pi)``.

    Exact (no rounding at all), but ``-pi`` stays ``-pi`` and a result may be either end:
    not :func:`wrap`'s convention. The lattice planner's headings and the LONGD heuristic's
    fallback bound (:class:`segplan.planning.paper.problem.Problem`) use it.
    """
    return math.remainder(a, TWO_PI)


def wrap_floor(a):
    """Angles wrapped to ``[-pi, pi)`` by ``np.remainder(a + pi, 2 pi) - pi`` (vectorised).

    Floor-division modulo (the sign of ``2 pi``), after rounding ``a + pi``: ``+pi`` maps
    to ``-pi``, and a tiny negative ``a + pi`` may round to ``+pi`` itself. The lattice
    planner's screens (``steerable``, the guide's heading test) use it.
    """
    return np.remainder(a + math.pi, TWO_PI) - math.pi


def _intrinsic_scalar(p0, p1) -> Intrinsic | None:
    """Fast path of :func:`intrinsic` for two plain ``(x, y, theta)`` float triples.

    The same values as the array path (numpy's ``hypot`` and ``arctan2``, whose results
    may differ from the ``math`` module's in the last bit); ``None`` for anything else,
    including non-finite or coincident points, which the array path reports.
    """
    if not (type(p0) in (Pose, tuple) and type(p1) in (Pose, tuple) and len(p0) == 3 and len(p1) == 3):
        return None
    values = (*p0, *p1)
    if not all(type(v) is float and math.isfinite(v) for v in values):
        return None
    x0, y0, t0, x1, y1, t1 = values
    dx, dy = x1 - x0, y1 - y0
    d = float(np.hypot(dx, dy))
    if d <= 1e-12 * max(abs(x0), abs(y0), abs(x1), abs(y1), 1.0):
        return None
    psi = float(np.arctan2(dy, dx))
    return Intrinsic(d, psi, wrap_scalar(t0 - psi), wrap_scalar(t1 - psi))


def intrinsic_interval(p0, p1, margin: float = 0.0):
    """The planner's scalar fast path of :func:`intrinsic` and :func:`alpha_interval`.

    Chord length ``d``, chord angle ``psi``, intrinsic headings ``phi0, phi1`` and the
    interval ``(lo, hi)`` of ``alpha`` where the cubic exists, shrunk by ``margin`` at
    both ends, for two ``(x, y, theta)`` poses the caller has validated; ``None`` for
    coincident points (``d <= 1e-9 max(1, |coordinates|)``, a looser tolerance than
    :func:`intrinsic`'s) or an empty interval (no cubic joins the poses). The link model
    (:class:`segplan.planning.links.LinkModel`) builds every union from it.

    It computes with the ``math`` module and :func:`wrap_fmod`, the planner's scalar wrap,
    so its values equal the array path's to rounding, not always to the last bit; the
    paper's search is sensitive to that last bit and the book's numbers were computed with
    this form (``tests/test_fast_paths.py`` compares the two).

    Returns
    -------
    (d, psi, phi0, phi1, lo, hi) : tuple of float, or None
    """
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    d = math.hypot(dx, dy)
    if d <= 1e-9 * max(1.0, abs(p0[0]), abs(p0[1]), abs(p1[0]), abs(p1[1])):
        return None
    psi = math.atan2(dy, dx)
    phi0, phi1 = wrap_fmod(p0[2] - psi), wrap_fmod(p1[2] - psi)
    lo = -HALF_PI - min(phi0, phi1, 0.0) + margin
    hi = HALF_PI - max(phi0, phi1, 0.0) - margin
    if not hi > lo:
        return None
    return d, psi, phi0, phi1, lo, hi


def alpha_interval(phi0, phi1):
    """Open interval of ``alpha`` for which the cubic exists (vectorised).

    The conditions are ``|alpha| < pi/2`` and ``|phi_i + alpha| < pi/2``. The interval is
    empty (``lo >= hi``) when the spread of ``{0, phi0, phi1}`` reaches ``pi``, for
    example a goal behind the start.

    Returns
    -------
    lo, hi : float or ndarray
    """
    phi0 = np.asarray(phi0, dtype=float)
    phi1 = np.asarray(phi1, dtype=float)
    lo = -HALF_PI - np.minimum(np.minimum(phi0, phi1), 0.0)
    hi = HALF_PI - np.maximum(np.maximum(phi0, phi1), 0.0)
    if lo.ndim == 0:
        return float(lo), float(hi)
    return lo, hi


def feasible_alpha_interval(phi0: float, phi1: float) -> tuple[float, float]:
    """Like :func:`alpha_interval` for scalars, raising when it is empty.

    Raises
    ------
    ValueError
        If no alpha frame gives a cubic (headings opposing the chord, e.g. a goal behind
        the start): such a pair needs an intermediate node.
    """
    lo, hi = alpha_interval(phi0, phi1)
    if not hi - lo > 1e-9:
        raise ValueError(
            "no alpha reference system gives a cubic for intrinsic headings "
            f"phi0={math.degrees(phi0):.3f} deg, phi1={math.degrees(phi1):.3f} deg "
            "(the spread of {0, phi0, phi1} must be below 180 deg; a goal behind the "
            "start needs an intermediate node)"
        )
    return lo, hi


def check_alpha(alpha: float, phi0: float, phi1: float) -> float:
    """Validate that ``alpha`` lies strictly inside the interval where the cubic exists.

    Raises
    ------
    ValueError
        Naming ``alpha`` and the admissible interval, in degrees.
    """
    try:
        a = float(alpha)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"alpha must be a number (radians), got {alpha!r}") from exc
    if not math.isfinite(a):
        raise ValueError(f"alpha must be finite, got {a}")
    lo, hi = feasible_alpha_interval(phi0, phi1)
    if not lo < a < hi:
        raise ValueError(
            f"alpha={math.degrees(a):.4f} deg lies outside the interval "
            f"({math.degrees(lo):.4f}, {math.degrees(hi):.4f}) deg where the cubic exists "
            "(|alpha| < 90 deg and |phi_i + alpha| < 90 deg)"
        )
    return a
