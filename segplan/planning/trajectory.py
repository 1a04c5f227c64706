"""A plan as a controller reads it: poses by arc length, the steering at its nodes, a time law.

Beyond the paper (issue 27). Section "Results. Graph-search" of Campoy et al. (1989) ends
at the chain of cubic unions; a robot needs them sampled, timed and its steering steps
named. Three things, each exact per union from the cubic ``y = f(x) = c1 x + c2 x^2 +
c3 x^3`` of its alpha frame (:class:`segplan.Union`, section "Generation of the trajectory
of union between two nodes"):

**Samples** (:func:`sample_path`, :meth:`segplan.Plan.poses`). Along the arc length ``s``
of the rear point A, ``ds = sqrt(1 + f'^2) dx``, integrated by the Romberg rule of the cost
([1] with ``L = 0``: :func:`segplan.model.cost.partial_lengths`). A union of rear length
``S`` gets ``n = max(2, ceil(S / step))`` equal intervals of ``S / n <= step``; the frame
abscissa of each sample solves ``s(x) = j S / n`` by Newton's method (``s' = sqrt(1 +
f'^2) >= 1``) to ``1e-9 S``. Each union's block holds both its ends, so an interior node
appears twice, as the end of the union before it and as the start of the one after it,
with the same pose (the node's, exactly: ``x``, ``y``, and ``theta`` up to a whole turn)
and each side's own curvature and steering angle. Per sample: the heading ``theta`` of A->B
(``frame angle + arctan f'``, continuous along the plan, starting at the start node's
``theta``), the front wheel ``B = A + L (cos theta, sin theta)``, the signed curvature of
A's path ``kappa = f'' / (1 + f'^2)^(3/2)`` (left turns positive) and the steering angle
``steer = arctan(L kappa)`` (section "Mobile robot modelling": the robot is tangent to the
rear path, a bicycle steered at the front wheel).

**Reverse links** (beyond the paper, issue 26: :attr:`segplan.Plan.directions`). A
backward link is its union, made from the node it drives back to (``p0``) to the node the
robot is at (``p1``), driven from ``p1`` to ``p0``: its block is sampled as above and taken
in the reverse order (as :func:`segplan.viz.metrics.plan_poses` does), so the rows follow
the robot in driving order and ``s`` is the *travelled* rear arc length (non-decreasing);
each row's ``direction`` is ``+1`` or ``-1``. ``theta`` stays the robot's heading (A->B),
not the direction of travel. *Curvature and steering while reversing*: with ``sigma`` the
arc length signed along the heading (``d sigma = direction ds``), the bicycle model with
signed speed ``v`` is ``x' = v cos theta``, ``y' = v sin theta``, ``theta' = v tan(steer) /
L``, so ``d theta / d sigma = tan(steer) / L`` whatever the sign of ``v``. ``kappa`` is that
curvature, ``d theta / d sigma`` (the curve's curvature along its own forward tangent, the
union's ``f'' / (1 + f'^2)^(3/2)``), and ``steer = arctan(L kappa)`` is the wheel angle that
follows the path in either direction: a reversed row has the kappa and steer of the same
point driven forwards. The heading's rate along the travelled length is ``d theta / ds =
direction * kappa`` (tests/test_trajectory_reverse.py integrates the bicycle model backwards
with these angles and lands on the link's far node).

**Steering at the nodes** (:func:`plan_facts`, :meth:`segplan.Plan.facts`). Two unions meet
at a node with the same position and heading but, in general, different curvatures: the
steering angle steps there by ``arctan(L kappa_out) - arctan(L kappa_in)``.

**Time law** (:func:`time_law`, :meth:`segplan.Plan.trajectory`). ``v`` is the speed of A
along ``s``. Limits: ``v <= v_max``; ``|dv/dt| <= a_max``; ``v^2 |kappa| <= a_lat_max``;
``|d steer / dt| = |d steer / ds| v <= steer_rate_max``. The robot starts and ends at rest,
its wheel already at the first sample's steering angle. *Jump model*: the steering cannot
step while the robot moves, so at a node whose steering steps by more than ``jump_tol``
(rounding) the robot stops, re-steers standing for ``|jump| / steer_rate_max`` seconds, and
drives on; a node's two rows then hold the two stamps (the steering rate while standing is
``steer_rate_max`` exactly). *Cusps*: at a node where the direction changes the robot
stops (``v = 0`` on both rows), re-steers standing if the steering steps there, and
accelerates the other way; ``v`` is signed (negative while reversing), and every limit
applies to ``|v|`` the same both ways. *Profile*: the classic forward-backward pass over the samples
(forward from rest, ``v_{i+1}^2 <= v_i^2 + 2 a_max ds_i``; backward from rest at the end,
``v_i^2 <= v_{i+1}^2 + 2 a_max ds_i``; each sample's speed the least of its cap and both
passes), each sample capped by the speed limits of the intervals on either side; between
two samples the acceleration is constant (``a = (v_{i+1}^2 - v_i^2) / (2 ds)``, time
``2 ds / (v_i + v_{i+1})``), so ``v^2`` is linear in ``s`` and ``v`` lies between its end
values. *The caps are exact, not sampled*: for each interval the largest ``|kappa|`` (at
its ends and at the curvature's stationary points inside,
:meth:`segplan.Union.curvature_stationary`) and an upper bound of ``|d steer / ds| =
L |kappa_s| / (1 + L^2 kappa^2)`` with ``kappa_s = N / (1 + f'^2)^3``
(:func:`segplan.model.union.curvature_polynomials`): the largest ``|N|`` over the interval
over the smallest ``(1 + f'^2)^3`` and ``1 + L^2 kappa^2``, each found at the interval's
ends and the roots of a polynomial (:func:`interval_bounds`). Every limit therefore holds
everywhere between the samples, not only at them, to rounding (tests/test_trajectory.py
checks it on dense resamplings of every union: ``1e-9`` relative for the speed and the
acceleration, ``1e-6`` where its finite differences enter). *Discretisation error*: in the
time only, never in a limit. An interval's caps hold for its worst point, so the law is
slower than the time-optimal one along the same path by ``O(step)``; measured
(``test_time_converges_with_step``), the total time at the default step of 0.05 m is within
0.03 % of the time at 6.25 mm on the shipped floor ``turn_around`` (its lattice plan) and
within 0.001 % on ``fig5_example1``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..model.cost import partial_lengths
from ..model.union import Union, curvature_polynomials
from .checks import check_option
from .export import nav_path, write_csv, write_nav_path

__all__ = [
    "DEFAULT_STEP",
    "JUMP_TOL",
    "POSE_COLUMNS",
    "TRAJECTORY_COLUMNS",
    "PathSamples",
    "PlanFacts",
    "Trajectory",
    "interval_bounds",
    "plan_facts",
    "sample_path",
    "time_law",
]

#: Default spacing (m) of the samples along the rear point's path: a few per robot length at
#: the book's ``L = 1.2`` m. Set by hand in issue 27; not measured.
DEFAULT_STEP = 0.05
#: A steering step at a node up to this (radians) is rounding, not a jump: the curvatures
#: of two unions that meet smoothly agree to about 1e-15 / L. Set by hand in issue 27.
JUMP_TOL = 1e-9
#: The columns of :class:`PathSamples` (CSV order).
POSE_COLUMNS = ("s", "x", "y", "theta", "x_front", "y_front", "kappa", "steer", "union", "direction")
#: The columns of :class:`Trajectory` (CSV order).
TRAJECTORY_COLUMNS = ("t", "s", "v", "a") + POSE_COLUMNS[1:]

#: Romberg's relative tolerance on the arc lengths; Newton's tolerance on ``s(x) = target``.
_ARC_RTOL = 1e-12
_NEWTON_TOL = 1e-9


def _frozen(a, dtype=float) -> np.ndarray:
    a = np.array(a, dtype=dtype)
    a.setflags(write=False)
    return a


# -- samples -----------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class PathSamples:
    """A plan's rear path sampled by arc length (module docstring); read-only arrays of one length.

    Attributes
    ----------
    s : ndarray
        Arc length travelled by the rear point A from the start (m); non-decreasing,
        repeated at the interior nodes (two rows each).
    x, y : ndarray
        A, world coordinates (m).
    theta : ndarray
        Heading of A->B (radians), continuous along the plan (not wrapped; the yaw); the
        robot's heading also while it reverses.
    x_front, y_front : ndarray
        The front wheel B (m).
    kappa : ndarray
        Signed curvature of A's path along the heading, ``d theta / d sigma`` (1/m; positive
        turning left when driven forwards; module docstring, "reverse links").
    steer : ndarray
        Steering angle ``arctan(L kappa)`` (radians), the same driving either way.
    union : ndarray of int
        The union each row belongs to.
    direction : ndarray of int
        ``1`` driving forwards, ``-1`` reversing (the row's link's direction).
    frame_x : ndarray
        Abscissa of each row in its union's alpha frame (m); not a CSV column.
    L : float
        Robot length (m).
    step : float
        The spacing asked for (m): each union's rows are ``S / ceil(S / step)`` apart
        (at least two intervals per union).
    """

    s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    x_front: np.ndarray
    y_front: np.ndarray
    kappa: np.ndarray
    steer: np.ndarray
    union: np.ndarray
    direction: np.ndarray
    frame_x: np.ndarray
    L: float
    step: float

    def __len__(self) -> int:
        return int(self.s.size)

    def columns(self) -> dict[str, np.ndarray]:
        """The CSV columns, name -> array (:data:`POSE_COLUMNS`)."""
        return {name: getattr(self, name) for name in POSE_COLUMNS}

    def to_csv(self, path) -> None:
        """Write the :meth:`columns` to ``path`` (:func:`segplan.planning.export.write_csv`)."""
        write_csv(path, self.columns())

    def nav_path(self, frame_id: str = "map", stamp: float = 0.0) -> dict:
        """The poses as a ``nav_msgs/Path``-shaped dict, each stamped ``stamp``
        (:func:`segplan.planning.export.nav_path`; a node listed once). ``nav_msgs/Path``
        has no direction: a reversing pose is listed in driving order with the robot's
        heading (it moves against it); the direction is the CSV's ``direction`` column."""
        return nav_path(self.x, self.y, self.theta, frame_id=frame_id, stamp=stamp)

    def save_nav_path(self, path, frame_id: str = "map") -> None:
        """Write :meth:`nav_path` as JSON, or YAML for ``.yaml``/``.yml``."""
        write_nav_path(path, self.nav_path(frame_id))


def _check_unions(unions) -> tuple[Union, ...]:
    unions = tuple(unions)
    if not unions:
        raise ValueError("the plan has no unions (its start is its goal): there is no path to sample")
    if not all(isinstance(u, Union) for u in unions):
        raise ValueError("unions must be segplan.Union objects")
    if len({u.L for u in unions}) != 1:
        raise ValueError(f"the unions disagree on L: {sorted({u.L for u in unions})}")
    return unions


def _abscissae(u: Union, step: float) -> tuple[np.ndarray, float]:
    """Frame abscissae of ``n + 1`` samples of ``u`` equally spaced in the rear arc length,
    ``n = max(2, ceil(S / step))``, and the union's rear length ``S``."""
    _, c1, c2, c3 = u.coefficients
    X = u.x_end
    S = float(partial_lengths(X, c1, c2, c3, 0.0, rtol=_ARC_RTOL))  # int_0^X sqrt(1 + f'^2) dx
    n = max(2, math.ceil(S / step))
    target = S * np.arange(1, n) / n
    x = X * np.arange(1, n) / n  # first guess: s proportional to x
    for _ in range(50):
        residual = partial_lengths(x, c1, c2, c3, 0.0, rtol=_ARC_RTOL) - target  # s(x) - s*
        if np.max(np.abs(residual)) <= _NEWTON_TOL * S:
            break
        fp = u.slope(x)
        x = np.clip(x - residual / np.sqrt(1.0 + fp * fp), 0.0, X)  # Newton: x -= (s - s*) / s'
    else:  # pragma: no cover - s' >= 1 and bounded: Newton converges in a few steps
        raise RuntimeError(f"arc-length inversion did not converge on {u!r}")
    return np.concatenate(([0.0], x, [X])), S


def _check_directions(directions, n: int) -> tuple:
    """``directions`` as :attr:`segplan.Plan.link_directions`: ``()`` is all forwards, else
    one ``1`` or ``-1`` per union."""
    directions = tuple(directions)
    if not directions:
        return (1,) * n
    if len(directions) != n or any(isinstance(d, bool) or d not in (1, -1) for d in directions):
        raise ValueError(f"directions must be () or 1 or -1 for each of {n} unions, got {directions!r}")
    return tuple(int(d) for d in directions)


def sample_path(
    unions: Sequence[Union], step: float = DEFAULT_STEP, directions: Sequence[int] = ()
) -> PathSamples:
    """Sample a chain of unions by the arc length of the rear point (module docstring).

    Parameters
    ----------
    unions : sequence of Union
        Consecutive unions of one robot (a plan's ``unions``).
    step : float
        Largest spacing (m) of the samples along the rear path, > 0.
    directions : sequence of int
        :attr:`segplan.Plan.directions`: ``()`` (every union forwards) or ``1`` / ``-1``
        per union; a backward union is driven from its ``p1`` to its ``p0`` (module
        docstring, "reverse links").

    Returns
    -------
    PathSamples

    Raises
    ------
    ValueError
        No unions, unions of different ``L``, a bad ``step`` or ``directions``.
    """
    unions = _check_unions(unions)
    step = check_option(step, "step (m)", 0.0)
    directions = _check_directions(directions, len(unions))
    L = unions[0].L
    blocks = []
    s0 = 0.0
    first = unions[0]
    theta0 = float(first.p0.theta if directions[0] > 0 else first.p1.theta)  # the start node's heading
    for k, (u, d) in enumerate(zip(unions, directions, strict=True)):
        x, S = _abscissae(u, step)
        _, c1, _, _ = u.coefficients
        A = u.to_world(x, u.f(x))
        A[0] = u.p0.x, u.p0.y  # the nodes exactly
        A[-1] = u.p1.x, u.p1.y
        # the robot enters at p0 (row 0) forwards, at p1 (the last row) backwards
        enter, leave, end = (0, -1, u.p1) if d > 0 else (-1, 0, u.p0)
        turn_in = math.atan(c1) if d > 0 else math.atan(float(u.slope(x[-1])))  # f' where it enters
        theta = theta0 + (np.arctan(u.slope(x)) - turn_in)  # frame angle + arctan f', unwrapped
        theta[enter] = theta0
        theta1 = end.theta + 2.0 * math.pi * round((theta[leave] - end.theta) / (2.0 * math.pi))
        theta[leave] = theta1  # the node it leaves the union at, on the continuous branch
        kappa = u.curvature(x)  # f'' / (1 + f'^2)^(3/2): d theta / d sigma, either way
        if d < 0:  # driving order (as segplan.viz.metrics.plan_poses)
            x, A, theta, kappa = x[::-1], A[::-1], theta[::-1], kappa[::-1]
        s = s0 + S * np.arange(x.size) / (x.size - 1)
        s[-1] = s0 + S
        blocks.append((s, A, theta, kappa, np.full(x.size, k), np.full(x.size, d), x))
        s0, theta0 = s0 + S, theta1
    s, A, theta, kappa, index, direction, frame_x = (
        np.concatenate(parts) for parts in zip(*blocks, strict=True)
    )
    B = A + L * np.column_stack((np.cos(theta), np.sin(theta)))  # B = A + L (cos theta, sin theta)
    return PathSamples(
        s=_frozen(s),
        x=_frozen(A[:, 0]),
        y=_frozen(A[:, 1]),
        theta=_frozen(theta),
        x_front=_frozen(B[:, 0]),
        y_front=_frozen(B[:, 1]),
        kappa=_frozen(kappa),
        steer=_frozen(np.arctan(L * kappa)),  # tan(steer) = L kappa
        union=_frozen(index, dtype=np.int64),
        direction=_frozen(direction, dtype=np.int64),
        frame_x=_frozen(frame_x),
        L=float(L),
        step=step,
    )


# -- the plan's facts ---------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class PlanFacts:
    """What a controller needs to know of a plan before driving it (module docstring).

    Per node (start, intermediate nodes, goal; ``nan`` where a side has no union):

    Attributes
    ----------
    kappa_in, kappa_out : ndarray
        Curvature of the rear path arriving at / leaving the node (1/m).
    steer_in, steer_out : ndarray
        The steering angles there, ``arctan(L kappa)`` (radians).
    steer_jump : ndarray
        ``steer_out - steer_in``: the step of the steering angle at each node (radians;
        ``nan`` at the start and the goal).
    max_curvature : float
        Largest ``|kappa|`` of the rear path over the plan, exact
        (:meth:`segplan.Union.max_curvature`).
    max_steer_used : float
        ``arctan(L max_curvature)`` (radians).
    curvature_limit : float or None
        ``tan(max_steer) / L`` when a steering limit was given, else None.
    within_limit : bool or None
        ``max_curvature <= curvature_limit`` (None without a limit).
    rear_length, front_length : float
        Length of the paths of A and B (m): [1] with ``L = 0`` and with ``L``, by Romberg
        (the front length is the plan's ``cost``, LONGD, to ``1e-8``).
    L : float
    """

    kappa_in: np.ndarray
    kappa_out: np.ndarray
    steer_in: np.ndarray
    steer_out: np.ndarray
    steer_jump: np.ndarray
    max_curvature: float
    max_steer_used: float
    curvature_limit: float | None
    within_limit: bool | None
    rear_length: float
    front_length: float
    L: float

    @property
    def max_jump(self) -> float:
        """Largest ``|steer_jump|`` over the intermediate nodes (radians; 0 with none)."""
        inner = np.abs(self.steer_jump[1:-1])
        return float(inner.max()) if inner.size else 0.0


def plan_facts(
    unions: Sequence[Union], max_steer: float | None = None, directions: Sequence[int] = ()
) -> PlanFacts:
    """The steering at each node on each side, its jumps, the largest curvature against the limit.

    Parameters
    ----------
    unions : sequence of Union
        A plan's unions.
    max_steer : float, optional
        The robot's steering limit (radians, in ``(0, pi/2)``; ``Robot.max_steer``).
    directions : sequence of int
        As :func:`sample_path`: a backward union arrives at the node of its ``p0`` and
        leaves the one of its ``p1`` (its steering angles as in the module docstring).

    Returns
    -------
    PlanFacts
    """
    unions = _check_unions(unions)
    directions = _check_directions(directions, len(unions))
    if max_steer is not None and not (isinstance(max_steer, int | float) and 0.0 < max_steer < 0.5 * math.pi):
        raise ValueError(f"max_steer must lie in (0, pi/2) radians, got {max_steer!r}")
    L = unions[0].L
    nan = np.full(len(unions) + 1, np.nan)
    kappa_in, kappa_out = nan.copy(), nan.copy()
    ends = [(0.0, u.x_end)[:: 1 if d > 0 else -1] for u, d in zip(unions, directions, strict=True)]
    kappa_out[:-1] = [float(u.curvature(a)) for u, (a, _) in zip(unions, ends, strict=True)]
    kappa_in[1:] = [float(u.curvature(b)) for u, (_, b) in zip(unions, ends, strict=True)]
    steer_in, steer_out = np.arctan(L * kappa_in), np.arctan(L * kappa_out)
    max_k = max(u.max_curvature() for u in unions)
    limit = None if max_steer is None else math.tan(max_steer) / L
    rear = front = 0.0
    for u in unions:
        _, c1, c2, c3 = u.coefficients
        rear += float(partial_lengths(u.x_end, c1, c2, c3, 0.0))  # [1] with L = 0
        front += float(partial_lengths(u.x_end, c1, c2, c3, L))  # [1]: LONGD
    return PlanFacts(
        kappa_in=_frozen(kappa_in),
        kappa_out=_frozen(kappa_out),
        steer_in=_frozen(steer_in),
        steer_out=_frozen(steer_out),
        steer_jump=_frozen(steer_out - steer_in),
        max_curvature=float(max_k),
        max_steer_used=math.atan(L * max_k),
        curvature_limit=limit,
        within_limit=None if limit is None else bool(max_k <= limit),
        rear_length=rear,
        front_length=front,
        L=float(L),
    )


# -- exact bounds over the intervals between samples ---------------------------------------------
def _real_roots(p, lo: float, hi: float) -> np.ndarray:
    """Real roots of the polynomial ``p`` strictly inside ``(lo, hi)`` (none if ``p`` is constant)."""
    if p.degree() < 1 or not np.any(p.coef[1:] != 0):
        return np.empty(0)
    r = p.roots()
    r = r[np.abs(r.imag) < 1e-9].real
    return r[(r > lo) & (r < hi)]


def interval_bounds(u: Union, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Over each interval ``[x_i, x_{i+1}]`` of a union: the largest ``|kappa|`` and a bound of
    ``|d steer / ds|`` (module docstring, "the caps are exact").

    Every extremum of a smooth function over an interval is at an end or at a stationary
    point inside; the stationary points here are roots of polynomials
    (:func:`segplan.model.union.curvature_polynomials`): ``kappa`` is stationary where
    ``N = 0``, ``N`` where ``N' = 0``, ``1 + f'^2`` where ``f'' = 0``; ``kappa`` vanishes
    where ``f'' = 0``. With ``w = 1 + f'^2``::

        |d steer / ds| = L |N| / w^3 / (1 + L^2 kappa^2)
                      <= L max|N| / (min w)^3 / (1 + L^2 min kappa^2).

    Parameters
    ----------
    u : Union
    x : ndarray
        Increasing frame abscissae in ``[0, x_end]`` (``n + 1`` of them).

    Returns
    -------
    kappa_max, steer_slope : ndarray
        ``n`` values each (1/m, radians/m).
    """
    _, c1, c2, c3 = u.coefficients
    L = u.L
    fp, fpp, crit = curvature_polynomials(c1, c2, c3)
    a, b = x[:-1], x[1:]

    def kappa(z):
        return fpp(z) / (1.0 + fp(z) ** 2) ** 1.5  # f'' / (1 + f'^2)^(3/2)

    def at(points, values, fold, out):
        """Fold ``values`` at ``points`` into ``out`` (``np.maximum`` or ``np.minimum``) on the
        intervals that hold them."""
        i = np.searchsorted(x, points, side="right") - 1
        inside = (i >= 0) & (i < a.size)
        fold.at(out, i[inside], values[inside])

    ka, kb = np.abs(kappa(a)), np.abs(kappa(b))
    k_max, k_min = np.maximum(ka, kb), np.minimum(ka, kb)
    stationary = np.asarray(u.curvature_stationary(), dtype=float)
    at(stationary, np.abs(kappa(stationary)), np.maximum, k_max)
    at(stationary, np.abs(kappa(stationary)), np.minimum, k_min)
    zeros = _real_roots(fpp, 0.0, u.x_end)  # kappa = 0 where f'' = 0
    at(zeros, np.zeros(zeros.size), np.minimum, k_min)
    n_max = np.maximum(np.abs(crit(a)), np.abs(crit(b)))
    turns = _real_roots(crit.deriv(), 0.0, u.x_end)
    at(turns, np.abs(crit(turns)), np.maximum, n_max)
    w_min = 1.0 + np.minimum(fp(a) ** 2, fp(b) ** 2)
    flat = np.concatenate((zeros, _real_roots(fp, 0.0, u.x_end)))  # w stationary where f' f'' = 0
    at(flat, 1.0 + fp(flat) ** 2, np.minimum, w_min)
    slope = L * n_max / w_min**3 / (1.0 + (L * k_min) ** 2)  # >= L |N| / w^3 / (1 + L^2 kappa^2)
    return k_max, slope


# -- the time law -------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Trajectory:
    """A plan in time (module docstring): the samples of :class:`PathSamples` with a time law.

    Attributes
    ----------
    t : ndarray
        Time of each row (s), non-decreasing (repeated where two rows of a node meet without
        a jump).
    s, x, y, theta, x_front, y_front, kappa, steer, union, frame_x :
        As in :class:`PathSamples`.
    v : ndarray
        Velocity of the rear point A along the heading (m/s): its speed, negative while
        reversing (``direction``); the front wheel's is ``v / cos(steer)``.
    a : ndarray
        Acceleration ``dv/dt`` from each row to the next (m/s^2; constant in between; 0 on the
        last row and while standing).
    direction : ndarray of int
        As in :class:`PathSamples`: ``1`` forwards, ``-1`` reversing.
    total_time : float
        ``t[-1]`` (s).
    jump_time : float
        What the steering jumps cost (s): ``total_time`` minus the time of the same profile
        with the jumps ignored (no stop, no re-steering; the stops at the cusps kept); it
        includes :attr:`dwell_time`.
    dwell_time : float
        Time spent standing to re-steer, ``sum |jump| / steer_rate_max`` (s).
    jumps : int
        Nodes where the robot stops to re-steer (steering steps above ``jump_tol``; at a
        cusp too, where it stops anyway).
    cusps : int
        Nodes where the robot stops to change direction.
    v_max, a_max, a_lat_max, steer_rate_max : float
        The limits the law respects (m/s, m/s^2, m/s^2, rad/s).
    step : float
        The sample spacing asked for (m).
    L : float
        Robot length (m).
    """

    t: np.ndarray
    s: np.ndarray
    v: np.ndarray
    a: np.ndarray
    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    x_front: np.ndarray
    y_front: np.ndarray
    kappa: np.ndarray
    steer: np.ndarray
    union: np.ndarray
    direction: np.ndarray
    frame_x: np.ndarray
    total_time: float
    jump_time: float
    dwell_time: float
    jumps: int
    cusps: int
    v_max: float
    a_max: float
    a_lat_max: float
    steer_rate_max: float
    step: float
    L: float

    def __len__(self) -> int:
        return int(self.t.size)

    def columns(self) -> dict[str, np.ndarray]:
        """The CSV columns, name -> array (:data:`TRAJECTORY_COLUMNS`)."""
        return {name: getattr(self, name) for name in TRAJECTORY_COLUMNS}

    def to_csv(self, path) -> None:
        """Write the :meth:`columns` to ``path`` (:func:`segplan.planning.export.write_csv`)."""
        write_csv(path, self.columns())

    def nav_path(self, frame_id: str = "map", stamp: float = 0.0) -> dict:
        """The poses as a ``nav_msgs/Path``-shaped dict, stamped ``stamp + t``
        (:func:`segplan.planning.export.nav_path`); reversing poses as in
        :meth:`PathSamples.nav_path` (the sign is ``v``'s, in the CSV)."""
        return nav_path(self.x, self.y, self.theta, self.t, frame_id=frame_id, stamp=stamp)

    def save_nav_path(self, path, frame_id: str = "map") -> None:
        """Write :meth:`nav_path` as JSON, or YAML for ``.yaml``/``.yml``."""
        write_nav_path(path, self.nav_path(frame_id))


def _profile(ds: np.ndarray, cap: np.ndarray, a_max: float) -> np.ndarray:
    """The forward-backward pass: the largest ``v <= cap`` with ``|v_{i+1}^2 - v_i^2| <= 2 a_max ds_i``."""
    v = cap.astype(float).tolist()
    d = ds.tolist()
    for i in range(len(d)):  # forward: v_{i+1}^2 <= v_i^2 + 2 a ds
        v[i + 1] = min(v[i + 1], math.sqrt(v[i] * v[i] + 2.0 * a_max * d[i]))
    for i in range(len(d) - 1, -1, -1):  # backward: v_i^2 <= v_{i+1}^2 + 2 a ds
        v[i] = min(v[i], math.sqrt(v[i + 1] * v[i + 1] + 2.0 * a_max * d[i]))
    return np.array(v)


def _times(ds: np.ndarray, v: np.ndarray, dwell: np.ndarray) -> np.ndarray:
    """Time of each interval: ``2 ds / (v_i + v_{i+1})`` (constant acceleration); ``dwell``
    where ``ds = 0`` (the two rows of a node)."""
    dt = dwell.copy()
    moving = ds > 0.0
    dt[moving] = 2.0 * ds[moving] / (v[:-1][moving] + v[1:][moving])
    return dt


def time_law(
    unions: Sequence[Union],
    v_max: float,
    a_max: float,
    a_lat_max: float,
    steer_rate_max: float,
    *,
    step: float = DEFAULT_STEP,
    jump_tol: float = JUMP_TOL,
    directions: Sequence[int] = (),
) -> Trajectory:
    """A time law along a chain of unions that respects every limit (module docstring).

    Parameters
    ----------
    unions : sequence of Union
        A plan's unions.
    v_max : float
        Largest speed of the rear point A (m/s, > 0).
    a_max : float
        Largest ``|dv/dt|`` (m/s^2, > 0).
    a_lat_max : float
        Largest lateral acceleration ``v^2 |kappa|`` (m/s^2, > 0).
    steer_rate_max : float
        Largest ``|d steer / dt|`` (rad/s, > 0).
    step : float
        Sample spacing along the rear path (m, > 0; :func:`sample_path`).
    jump_tol : float
        Steering steps at a node up to this (radians, >= 0) are rounding and driven through;
        larger ones stop the robot (the jump model).
    directions : sequence of int
        As :func:`sample_path`; the robot stops at each cusp.

    Returns
    -------
    Trajectory

    Raises
    ------
    ValueError
        A limit that is not a positive finite number (named), or bad unions or ``step``.
    """
    v_max = check_option(v_max, "v_max (m/s)", 0.0)
    a_max = check_option(a_max, "a_max (m/s^2)", 0.0)
    a_lat_max = check_option(a_lat_max, "a_lat_max (m/s^2)", 0.0)
    rate = check_option(steer_rate_max, "steer_rate_max (rad/s)", 0.0)
    jump_tol = check_option(jump_tol, "jump_tol (rad)", 0.0, lo_ok=True)
    unions = _check_unions(unions)
    path = sample_path(unions, step, directions)
    n = len(path)
    ds = np.diff(path.s)
    # per interval: the speed its curvature and steering slope allow (inf between two rows of a node)
    k_max, slope = np.zeros(n - 1), np.zeros(n - 1)
    for k, u in enumerate(unions):
        rows = np.flatnonzero(path.union == k)
        order = 1 if path.direction[rows[0]] > 0 else -1  # a backward union's rows: x decreasing
        km, sl = interval_bounds(u, path.frame_x[rows][::order])
        k_max[rows[:-1]], slope[rows[:-1]] = km[::order], sl[::order]
    with np.errstate(divide="ignore"):
        allowed = np.minimum(np.sqrt(a_lat_max / k_max), rate / slope)  # v^2 kappa <= a_lat, v steer' <= rate
    allowed = np.minimum(allowed, v_max)
    cap = np.minimum(np.append(allowed, v_max), np.insert(allowed, 0, v_max))  # both neighbours
    cap[0] = cap[-1] = 0.0  # at rest at both ends
    node_link = ds == 0.0  # the two rows of an interior node
    jump = np.where(node_link, np.abs(np.diff(path.steer)), 0.0)
    cusp = node_link & (np.diff(path.direction) != 0)  # stop, then drive the other way
    stops = (jump > jump_tol) | cusp
    dwell = np.where(jump > jump_tol, jump / rate, 0.0)  # re-steering standing: |jump| / steer_rate_max
    cap[:-1][cusp] = 0.0
    cap[1:][cusp] = 0.0
    free = _profile(ds, cap, a_max)  # the jumps ignored
    cap[:-1][stops] = 0.0
    cap[1:][stops] = 0.0
    v = _profile(ds, cap, a_max)
    dt = _times(ds, v, dwell)
    t = np.concatenate(([0.0], np.cumsum(dt)))
    t_free = float(np.cumsum(_times(ds, free, np.zeros(n - 1)))[-1])  # summed as t is
    acc = np.zeros(n)
    moving = ds > 0.0
    acc[:-1][moving] = (v[1:][moving] ** 2 - v[:-1][moving] ** 2) / (2.0 * ds[moving])  # v dv/ds
    return Trajectory(
        t=_frozen(t),
        s=path.s,
        v=_frozen(v * path.direction + 0.0),  # signed: negative while reversing (+ 0.0: no -0.0)
        a=_frozen(acc * path.direction + 0.0),
        x=path.x,
        y=path.y,
        theta=path.theta,
        x_front=path.x_front,
        y_front=path.y_front,
        kappa=path.kappa,
        steer=path.steer,
        union=path.union,
        direction=path.direction,
        frame_x=path.frame_x,
        total_time=float(t[-1]),
        jump_time=float(t[-1]) - t_free,
        dwell_time=float(np.sum(dwell)),
        jumps=int(np.count_nonzero(jump > jump_tol)),
        cusps=int(np.count_nonzero(cusp)),
        v_max=v_max,
        a_max=a_max,
        a_lat_max=a_lat_max,
        steer_rate_max=rate,
        step=path.step,
        L=path.L,
    )
