"""Reeds–Shepp path length: the lower bound of LONGD for a robot that may reverse (beyond the paper).

Issue 26. A robot that may drive backwards (``Robot(..., reverse=True)``) follows, between
two poses, a rear path of curvature at most ``1 / R`` (``R = L / tan(max_steer)``) with
cusps where it changes direction. The shortest such path is the Reeds–Shepp path (Reeds
and Shepp 1990, "Optimal paths for a car that goes both forwards and backwards", Pacific
J. Math. 145(2)): one of 48 words of at most five pieces (circle arcs C of radius ``R`` and
straight segments S, each driven forwards or backwards), in nine families: CSC, CCC,
CCCC (C|CuCu|C and CCu|CuC), CC|SC and CS|CC, and C|CSC|C. The paper gives, for a few
base words, closed forms of the piece lengths ``(t, u, v)`` from the end pose
``(x, y, phi)`` in units of ``R`` (its formulas 8.1-8.11); the other words come from three
symmetries of the problem (section 7):

* **timeflip** ``(x, y, phi) -> (-x, y, -phi)``: the same path driven in the other
  direction (every piece's sign flipped),
* **reflect** ``(x, y, phi) -> (x, -y, -phi)``: left and right swapped,
* **backwards** ``(x, y, phi) -> (x cos phi + y sin phi, x sin phi - y cos phi, phi)``:
  the path from the end to the start (the pieces in reverse order), needed by the
  families whose words are not palindromes (CCC and CC|SC / CS|CC).

A word's length is ``|t| + |u| + |v|`` plus its fixed pieces (``2|u|`` for the CCCC
families, a quarter turn ``pi / 2`` for CC|SC, two quarter turns for C|CSC|C). This
module follows the paper's formulas and their order as OMPL's ``ReedsSheppStateSpace``
(Moll; the corrected formulas 8.4 and 8.11) computes them, so the two agree
(``tests/test_reverse_reeds_shepp.py``: thousands of random pose pairs against
``ompl.base.ReedsSheppStateSpace.distance``); it computes the length only.

Why it bounds LONGD [1] from below: every union of a plan keeps the rear path's curvature
within ``1 / R``, so a plan's rear path, forward and reverse links alike, is a path of the
Reeds–Shepp car; its length is at least the Reeds–Shepp length, and the front wheel travels
at least as far as the rear point on every link (its speed is the rear speed divided by the
cosine of the steering angle), so ``LONGD >= rear length >= reeds_shepp_length``. It is also
at most the Dubins length (a forward-only path is one of the car's) and at least the
Euclidean distance between the rear points.
"""

from __future__ import annotations

import math

__all__ = ["reeds_shepp_length"]

_PI = math.pi
_TWO_PI = 2.0 * math.pi
#: Rounding allowance of the words' sign conditions (units of ``R`` and radians): a piece
#: within ``ZERO`` of the wrong sign is a zero piece that rounding pushed across 0. The
#: value of OMPL's ``ReedsSheppStateSpace`` (10 machine epsilons), so that both accept the
#: same words on the boundary cases.
ZERO = 10.0 * 2.220446049250313e-16


def _mod(a: float) -> float:
    """``a`` modulo ``2 pi``, in ``[-pi, pi]``."""
    v = math.fmod(a, _TWO_PI)
    if v < -_PI:
        v += _TWO_PI
    elif v > _PI:
        v -= _TWO_PI
    return v


def _tau_omega(u: float, v: float, xi: float, eta: float, phi: float) -> tuple[float, float]:
    """The first and last arcs ``(t, v)`` of the CCCC words (the paper's tau and omega, section 8)."""
    delta = _mod(u - v)
    a = math.sin(u) - math.sin(delta)
    b = math.cos(u) - math.cos(delta) - 1.0
    t1 = math.atan2(eta * a - xi * b, xi * a + eta * b)
    t2 = 2.0 * (math.cos(delta) - math.cos(v) - math.cos(u)) + 3.0
    tau = _mod(t1 + _PI) if t2 < 0.0 else _mod(t1)
    return tau, _mod(tau - u + v - phi)


# -- the base words: length in units of R, inf where the word does not reach (x, y, phi) ---------
# (``sp``, ``cp``: sin phi and cos phi)
def _csc_same(x: float, y: float, phi: float, sp: float, cp: float) -> float:
    """L+ S+ L+ (formula 8.1)."""
    u = math.hypot(x - sp, y - 1.0 + cp)
    t = math.atan2(y - 1.0 + cp, x - sp)
    if t >= -ZERO:
        v = _mod(phi - t)
        if v >= -ZERO:
            return t + u + v
    return math.inf


def _csc_opposite(x: float, y: float, phi: float, sp: float, cp: float) -> float:
    """L+ S+ R+ (formula 8.2)."""
    xi, eta = x + sp, y - 1.0 - cp
    rr = xi * xi + eta * eta
    if rr < 4.0:
        return math.inf
    u = math.sqrt(rr - 4.0)
    t = _mod(math.atan2(eta, xi) + math.atan2(2.0, u))
    v = _mod(t - phi)
    return t + u + v if t >= -ZERO and v >= -ZERO else math.inf


def _ccc(x: float, y: float, phi: float, sp: float, cp: float) -> float:
    """L+ R- L (formulas 8.3 and 8.4)."""
    xi, eta = x - sp, y - 1.0 + cp
    rho = math.hypot(xi, eta)
    if rho > 4.0:
        return math.inf
    u = -2.0 * math.asin(0.25 * rho)
    t = _mod(math.atan2(eta, xi) + 0.5 * u + _PI)
    v = _mod(phi - t + u)
    return abs(t) + abs(u) + abs(v) if t >= -ZERO and u <= ZERO else math.inf


def _cccc_a(x: float, y: float, phi: float, sp: float, cp: float) -> float:
    """L+ R+u L-u R- (formula 8.7)."""
    xi, eta = x + sp, y - 1.0 - cp
    rho = 0.25 * (2.0 + math.hypot(xi, eta))
    if rho > 1.0:
        return math.inf
    u = math.acos(rho)
    t, v = _tau_omega(u, -u, xi, eta, phi)
    return abs(t) + 2.0 * abs(u) + abs(v) if t >= -ZERO and v <= ZERO else math.inf


def _cccc_b(x: float, y: float, phi: float, sp: float, cp: float) -> float:
    """L+ R-u L-u R+ (formula 8.8)."""
    xi, eta = x + sp, y - 1.0 - cp
    rho = (20.0 - xi * xi - eta * eta) / 16.0
    if not 0.0 <= rho <= 1.0:
        return math.inf
    u = -math.acos(rho)
    if u < -0.5 * _PI:
        return math.inf
    t, v = _tau_omega(u, u, xi, eta, phi)
    return abs(t) + 2.0 * abs(u) + abs(v) if t >= -ZERO and v >= -ZERO else math.inf


def _ccsc_same(x: float, y: float, phi: float, sp: float, cp: float) -> float:
    """L+ R-(pi/2) S- L- (formula 8.9)."""
    xi, eta = x - sp, y - 1.0 + cp
    rho = math.hypot(xi, eta)
    if rho < 2.0:
        return math.inf
    r = math.sqrt(rho * rho - 4.0)
    u = 2.0 - r
    t = _mod(math.atan2(eta, xi) + math.atan2(r, -2.0))
    v = _mod(phi - 0.5 * _PI - t)
    ok = t >= -ZERO and u <= ZERO and v <= ZERO
    return abs(t) + abs(u) + abs(v) + 0.5 * _PI if ok else math.inf


def _ccsc_opposite(x: float, y: float, phi: float, sp: float, cp: float) -> float:
    """L+ R-(pi/2) S- R- (formula 8.10)."""
    xi, eta = x + sp, y - 1.0 - cp
    rho = math.hypot(-eta, xi)
    if rho < 2.0:
        return math.inf
    t = math.atan2(xi, -eta)
    u = 2.0 - rho
    v = _mod(t + 0.5 * _PI - phi)
    ok = t >= -ZERO and u <= ZERO and v <= ZERO
    return abs(t) + abs(u) + abs(v) + 0.5 * _PI if ok else math.inf


def _ccscc(x: float, y: float, phi: float, sp: float, cp: float) -> float:
    """L+ R-(pi/2) S- L-(pi/2) R+ (formula 8.11)."""
    xi, eta = x + sp, y - 1.0 - cp
    rho = math.hypot(xi, eta)
    if rho < 2.0:
        return math.inf
    u = 4.0 - math.sqrt(rho * rho - 4.0)
    if u > ZERO:
        return math.inf
    t = _mod(math.atan2((4.0 - u) * xi - 2.0 * eta, -2.0 * xi + (u - 4.0) * eta))
    v = _mod(t - phi)
    return abs(t) + abs(u) + abs(v) + _PI if t >= -ZERO and v >= -ZERO else math.inf


#: The base words whose timeflips and reflections give the others; those of the second tuple
#: also need the backwards symmetry (module docstring).
_SYMMETRIC = (_csc_same, _csc_opposite, _cccc_a, _cccc_b, _ccscc)
_ASYMMETRIC = (_ccc, _ccsc_same, _ccsc_opposite)
#: The words tried on the backwards-transformed pose (the asymmetric ones).
_BACKWARDS = _ASYMMETRIC


def _shortest(x: float, y: float, phi: float) -> float:
    """The Reeds–Shepp length (units of R) to the pose ``(x, y, phi)`` from ``(0, 0, 0)``.

    Every word gets ``sin phi`` and ``cos phi`` with the pose (computed once: the
    symmetries only flip their signs)."""
    sp, cp = math.sin(phi), math.cos(phi)
    # as is, timeflip, reflect, both
    flips = ((x, y, phi, sp), (-x, y, -phi, -sp), (x, -y, -phi, -sp), (-x, -y, phi, sp))
    best = math.inf
    for word in _SYMMETRIC + _ASYMMETRIC:
        for a, b, f, s in flips:
            length = word(a, b, f, s, cp)
            if length < best:
                best = length
    xb, yb = x * cp + y * sp, x * sp - y * cp  # backwards
    for word in _BACKWARDS:
        for a, b, f, s in (
            (xb, yb, phi, sp),
            (-xb, yb, -phi, -sp),
            (xb, -yb, -phi, -sp),
            (-xb, -yb, phi, sp),
        ):
            length = word(a, b, f, s, cp)
            if length < best:
                best = length
    return best


def reeds_shepp_length(
    x0: float, y0: float, theta0: float, x1: float, y1: float, theta1: float, R: float
) -> float:
    """Length of the shortest path of curvature at most ``1 / R`` from pose 0 to pose 1, driven
    forwards and backwards with any number of cusps (Reeds and Shepp 1990; module docstring).

    Parameters
    ----------
    x0, y0, theta0, x1, y1, theta1 : float
        Start and end poses (radians).
    R : float
        Minimum turning radius (> 0).

    Returns
    -------
    float
        The length (same unit as the coordinates): a lower bound of LONGD [1] of any plan
        between the poses of a robot that may reverse.

    Raises
    ------
    ValueError
        ``R`` not a finite number > 0.
    """
    if isinstance(R, bool) or not (isinstance(R, int | float) and math.isfinite(R) and R > 0):
        raise ValueError(f"R must be a finite number > 0, got {R!r}")
    dx, dy = x1 - x0, y1 - y0
    c, s = math.cos(theta0), math.sin(theta0)
    return R * _shortest((c * dx + s * dy) / R, (-s * dx + c * dy) / R, theta1 - theta0)
