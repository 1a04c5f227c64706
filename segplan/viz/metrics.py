"""Measuring a path of the segment robot: one function for every planner's output.

A path is a dense sequence of rear-axle poses ``(x, y, theta)``, an ``(n, 3)`` array
(A and the heading of A->B, radians), whatever planner produced it: a segplan
:class:`~segplan.planning.plan.Plan` (:func:`plan_poses` samples its unions), an OMPL path
(:func:`se2_poses` reads its states), an analytic curve in a test. :func:`measure_path`
returns a :class:`PathMetrics`:

- ``front_length``: length of the path of the front wheel ``B = A + L (cos theta,
  sin theta)``, the paper's cost (formula [1], section "Cost function"), as a polyline
  through the sampled B;
- ``rear_length``: length of the rear-point path (what OMPL's Dubins and Reeds-Shepp
  spaces minimise), as a polyline through the sampled A;
- ``max_curvature``: the largest ``|kappa|`` of the steering curvature
  ``kappa = d theta / ds`` (``s`` the signed arc length of A: negative while reversing),
  i.e. ``tan(steer) / L`` of the bicycle model, estimated per sample interval as
  ``wrap(theta[i+1] - theta[i]) / s_i``;
- ``curvature_jump`` and ``curvature_jumps``: curvature continuity. A jump of kappa (a
  step of the steering angle) inside sample interval ``i`` shows as
  ``|kappa[i+1] - kappa[i-1]|``: the largest of these is ``curvature_jump``; runs of
  consecutive intervals where it exceeds ``jump_tol`` are counted as one discontinuity
  each (``curvature_jumps``). A Dubins path jumps by ``1/R`` where an arc meets a line or
  an arc of the other sense; a segplan plan jumps at its intermediate nodes, where two
  cubics meet with equal headings but, in general, different curvatures (the paper says
  so). Two true jumps closer than two sample intervals count once;
- ``reversals``: cusps, where the direction of travel of A flips (Reeds-Shepp paths have
  them; forward-only planners must have none), seen as flips of the direction of travel
  between sample intervals: two cusps within one interval go unseen. The curvature
  ignores the two intervals around each cusp and any *fold* (an interval much shorter
  than both neighbours), where the chord misjudges the distance travelled;
- ``clearance``: the smallest distance from the robot's segment A-B (extended by the
  overhangs ``rear`` and ``front``, :class:`segplan.Robot`) at any sample to the
  given polygons and walls, **in the planning model**: pass the obstacles *enlarged* by
  the robot's half-width and the walls *shrunk* by it (``scenario.enlarged``,
  ``scenario.free_bounds``; :func:`measure_scenario_path` does). Because the enlarged
  polygons contain the exact Minkowski sum (:func:`segplan.floor.geometry.enlarge_polygon`), the
  real gap between the robot's body and the raw obstacles is at least this, and at most
  this plus the enlargement's excess (``0.0824 half_width`` by default). A rectangular
  body (``rectangle=w``): the rectangle itself against the raw obstacles and walls, the
  real gap. Negative means a sample lies outside the walls;
- ``collides``: the dense collision oracle. True if the segment of any sample touches a
  polygon (shapely ``intersects``: touching counts, as in :mod:`segplan.floor.collision`) or
  is not strictly inside the walls. It knows nothing of segplan's collision module (an
  independent check of every planner's output);
- ``step``: the largest displacement of A or B between consecutive samples. The sampled
  clearance overestimates the continuous one by at most about ``step / 2``: sample
  densely (the converters default to 1 cm).

shapely (2.x) is imported when :func:`measure_path` first needs it.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import asdict, dataclass

import numpy as np

from ..floor.geometry import check_bounds, finite_number
from ..model.pose import as_poses, check_length, wrap
from ..model.union import Union

__all__ = [
    "PathMetrics",
    "measure_path",
    "measure_scenario_path",
    "plan_clearance",
    "plan_poses",
    "plan_pose_directions",
    "se2_poses",
    "union_poses",
]

#: Default spacing (m) of the samples made by the converters.
DEFAULT_STEP = 0.01


@dataclass(frozen=True)
class PathMetrics:
    """What :func:`measure_path` measures (module docstring); lengths in m, curvature in 1/m."""

    front_length: float
    rear_length: float
    max_curvature: float
    curvature_jump: float
    curvature_jumps: int
    reversals: int
    clearance: float
    collides: bool
    samples: int
    step: float

    def as_dict(self) -> dict:
        """The fields as a plain dict (for a table row)."""
        return asdict(self)


def _polyline_lengths(points: np.ndarray) -> np.ndarray:
    """Lengths of the ``n - 1`` pieces of an ``(n, 2)`` polyline."""
    return np.hypot(*np.diff(points, axis=0).T)


def _curvature(A: np.ndarray, theta: np.ndarray, scale: float):
    """Signed steering curvature per interval, and the number of reversals.

    ``kappa_i = wrap(theta[i+1] - theta[i]) / s_i``, ``s_i = +-|A[i+1] - A[i]|`` (minus
    when A moves against its heading). Intervals where A does not move are dropped; if
    the heading turns there (a turn on the spot) the curvature is infinite. The two
    intervals on either side of a cusp are dropped too: one of them holds the cusp, where
    A goes forth and back within the interval and its chord underestimates the distance
    travelled (the estimate would blow up). So are *folds*, intervals whose chord is under
    half of both neighbours' chords: with samples evenly spaced along the path, A went
    back and forth inside them (two cusps closer than one sample spacing, not counted as
    reversals).
    """
    dA = np.diff(A, axis=0)
    ds = np.hypot(dA[:, 0], dA[:, 1])
    dth = wrap(np.diff(theta))
    moving = ds > 1e-12 * scale
    if np.any(~moving & (np.abs(dth) > 1e-9)):
        return np.array([math.inf]), 0
    mid = theta[:-1] + 0.5 * dth
    along = dA[:, 0] * np.cos(mid) + dA[:, 1] * np.sin(mid)
    direction = np.where(along < 0.0, -1.0, 1.0)[moving]
    kappa = dth[moving] / (direction * ds[moving])
    flips = np.flatnonzero(direction[1:] != direction[:-1])
    keep = np.ones(kappa.size, dtype=bool)
    keep[flips] = keep[flips + 1] = False
    d = ds[moving]
    if d.size >= 3:  # folds: a chord under half of both neighbours' (A went back and forth inside)
        keep[1:-1] &= ~(d[1:-1] < 0.5 * np.minimum(d[:-2], d[2:]))
    return kappa[keep], int(flips.size)


def _jumps(kappa: np.ndarray, tol: float) -> tuple[float, int]:
    """Largest ``|kappa[i+1] - kappa[i-1]|`` and the number of runs above ``tol``."""
    if kappa.size < 3:
        return 0.0, 0
    j = np.abs(kappa[2:] - kappa[:-2])
    if not np.all(np.isfinite(j)):
        return math.inf, int(np.count_nonzero(~np.isfinite(j)))
    above = j > tol
    runs = int(np.count_nonzero(above[1:] & ~above[:-1]) + (1 if above[0] else 0))
    return float(j.max()), runs


def measure_path(
    poses,
    L: float,
    polygons: Iterable = (),
    bounds: Sequence[float] | None = None,
    *,
    jump_tol: float | None = None,
    rear: float = 0.0,
    front: float = 0.0,
    rectangle: float | None = None,
) -> PathMetrics:
    """Measure a path of the segment robot (module docstring).

    Parameters
    ----------
    poses : array_like, shape (n, 3)
        Dense rear-axle poses ``(x, y, theta)``, radians, in the order travelled
        (``n >= 2``).
    L : float
        Robot length A->B (> 0).
    polygons : iterable of (k, 2) arrays
        Obstacles the segment must not touch (the *enlarged* ones, see the module
        docstring); none by default.
    bounds : (xmin, ymin, xmax, ymax), optional
        Walls the segment must stay strictly inside (the *shrunk* ones); none by default
        (then the clearance ignores walls).
    jump_tol : float, optional
        A change of curvature larger than this (1/m) counts as a discontinuity; default
        ``0.1 / L`` (a step of about 6 degrees of the steering angle around straight
        ahead).
    rear, front : float
        The robot's overhangs (:class:`segplan.Robot`; >= 0): the ``clearance`` and
        ``collides`` are of the axis segment from ``A - rear u`` to ``B + front u``, the
        segment the planner checks (the lengths stay those of A and B).
    rectangle : float, optional
        A rectangular body's half-width ``w`` (:class:`segplan.Robot` with
        ``rectangle=True``): the ``clearance`` and ``collides`` are then of the rectangle
        ``[-rear, L + front] x [-w, w]`` at every pose, against ``polygons`` and ``bounds``
        given *raw* (not enlarged, not shrunk): the body the planner's exact rectangle test
        decides (:mod:`segplan.floor.body`). None (default): the segment.

    Returns
    -------
    PathMetrics

    Raises
    ------
    ValueError
        Malformed ``poses`` (not ``(n, 3)`` with ``n >= 2``, non-finite), ``L``,
        ``bounds``, ``jump_tol``, ``rear`` or ``front``.
    """
    P = as_poses(poses, "poses")
    if P.ndim != 2 or P.shape[0] < 2:
        raise ValueError(f"poses must be an (n, 3) array with n >= 2, got shape {P.shape}")
    L = check_length(L)
    rear, front = finite_number(rear, "rear", 0.0), finite_number(front, "front", 0.0)
    b = None if bounds is None else check_bounds(bounds)
    if jump_tol is None:
        jump_tol = 0.1 / L
    elif not (isinstance(jump_tol, int | float) and math.isfinite(jump_tol) and jump_tol > 0):
        raise ValueError(f"jump_tol must be a positive number, got {jump_tol!r}")

    A = P[:, :2]
    theta = P[:, 2]
    B = A + L * np.column_stack((np.cos(theta), np.sin(theta)))  # B = A + L (cos th, sin th)
    dA, dB = _polyline_lengths(A), _polyline_lengths(B)
    scale = L + float(np.abs(A).max())
    kappa, reversals = _curvature(A, theta, scale)
    jump, jumps = _jumps(kappa, float(jump_tol))

    import shapely  # lazily: only the measurement needs it

    U = np.column_stack((np.cos(theta), np.sin(theta)))
    R, F = (A, B) if rear == front == 0.0 else (A - rear * U, A + (L + front) * U)  # the checked segment
    if rectangle is None:
        lines = shapely.linestrings(np.stack((R, F), axis=1))
        ends = np.concatenate((R, F))
    else:  # the rectangle: its corners R -+ w n, F -+ w n (n = the heading turned left)
        w = finite_number(rectangle, "rectangle", 0.0)
        Nw = w * np.column_stack((-U[:, 1], U[:, 0]))
        corners = np.stack((R - Nw, F - Nw, F + Nw, R + Nw), axis=1)
        lines = shapely.polygons(corners)
        ends = corners.reshape(-1, 2)
    clearance = math.inf
    collides = False
    polys = [shapely.Polygon(np.asarray(p, dtype=float)) for p in polygons]
    if polys:
        obstacles = shapely.union_all(polys)
        shapely.prepare(obstacles)
        collides = bool(np.any(shapely.intersects(lines, obstacles)))
        clearance = float(np.min(shapely.distance(lines, obstacles)))
    if b is not None:
        xmin, ymin, xmax, ymax = b
        # distance of a segment (a convex body) inside an axis-aligned box to its walls is
        # attained at an end point (a corner)
        walls = np.minimum.reduce(
            (ends[:, 0] - xmin, xmax - ends[:, 0], ends[:, 1] - ymin, ymax - ends[:, 1])
        )
        wall = float(walls.min())
        collides = collides or wall <= 0.0
        clearance = min(clearance, wall)
    return PathMetrics(
        front_length=float(dB.sum()),
        rear_length=float(dA.sum()),
        max_curvature=float(np.max(np.abs(kappa))) if kappa.size else 0.0,
        curvature_jump=jump,
        curvature_jumps=jumps,
        reversals=reversals,
        clearance=clearance,
        collides=collides,
        samples=int(P.shape[0]),
        step=float(max(dA.max(), dB.max())),
    )


def measure_scenario_path(poses, scenario, *, jump_tol: float | None = None) -> PathMetrics:
    """:func:`measure_path` in a :class:`segplan.Scenario`: its enlarged obstacles and free bounds,
    its robot's overhangs; a rectangular body (:attr:`segplan.Scenario.body`): the rectangle
    among the raw obstacles and walls."""
    r = scenario.robot
    if scenario.body is not None:
        return measure_path(
            poses, r.L, scenario.obstacles, scenario.bounds, jump_tol=jump_tol,
            rear=r.rear_overhang, front=r.front_overhang, rectangle=r.half_width,
        )  # fmt: skip
    return measure_path(
        poses, r.L, scenario.enlarged, scenario.free_bounds, jump_tol=jump_tol,
        rear=r.rear_overhang, front=r.front_overhang,
    )  # fmt: skip


def plan_clearance(plan, scenario, step: float = DEFAULT_STEP) -> float:
    """The smallest gap (m) beyond the robot's half-width between a plan and a floor's obstacles and walls.

    The ``clearance`` of :func:`measure_scenario_path` on :func:`plan_poses` (module docstring):
    measured in the planning model (obstacles enlarged by ``half_width``, walls moved in as
    much), so the real gap between the robot's body and the raw obstacles is at least this
    (a rectangular body: that gap itself). Sampled every ``step`` m or less: it overestimates
    the continuous clearance by at most about ``step / 2``. Negative: the plan leaves the walls.

    Parameters
    ----------
    plan : segplan.Plan or iterable of Union
        A plan (its ``unions``) or its unions.
    scenario : segplan.Scenario
        The floor it is driven on.
    step : float
        Largest spacing (m) of the samples of A and B.
    """
    return measure_scenario_path(plan_poses(plan, step), scenario).clearance


# -- converters ------------------------------------------------------------------------------
def _check_step(step: float) -> float:
    if not (isinstance(step, int | float) and math.isfinite(step) and step > 0):
        raise ValueError(f"step must be a positive number of metres, got {step!r}")
    return float(step)


def union_poses(union: Union, step: float = DEFAULT_STEP) -> np.ndarray:
    """Poses ``(n, 3)`` along a union, A and B moving at most about ``step`` between samples.

    Samples are equally spaced in the alpha frame's abscissa; their number is chosen from
    a first pass of 65 samples so that the longest piece of either the rear or the front
    polyline is at most ``step``.
    """
    if not isinstance(union, Union):
        raise ValueError(f"union must be a segplan.Union, got {type(union).__name__}")
    step = _check_step(step)

    def sample(n: int) -> np.ndarray:
        x = union.xs(n)
        return np.column_stack((union.to_world(x, union.f(x)), union.heading(x)))

    P = sample(65)
    B = P[:, :2] + union.L * np.column_stack((np.cos(P[:, 2]), np.sin(P[:, 2])))
    longest = max(_polyline_lengths(P[:, :2]).max(), _polyline_lengths(B).max())
    n = max(2, math.ceil(64 * 1.05 * longest / step) + 1)
    return sample(n)


def plan_poses(plan, step: float = DEFAULT_STEP) -> np.ndarray:
    """Dense poses ``(n, 3)`` of a segplan plan (or any sequence of consecutive unions), in
    driving order.

    A plan with reverse links (:attr:`segplan.Plan.directions`, issue 26) drives each of
    them backwards: the link's union, made from its far node to its near one, is sampled
    and its poses taken in the reverse order (the same configurations, the heading still the
    robot's), so :func:`measure_path` sees A move against its heading and counts a cusp at
    each change of direction.

    Parameters
    ----------
    plan : segplan.Plan or iterable of Union
        A plan (its ``unions``) or its unions (driven forwards).
    step : float
        Largest spacing (m) of the samples of A and B, see :func:`union_poses`.
    """
    return plan_pose_directions(plan, step)[0]


def plan_pose_directions(plan, step: float = DEFAULT_STEP) -> tuple[np.ndarray, np.ndarray]:
    """:func:`plan_poses` and, per pose, the direction of the motion that reaches it (``1``
    forwards, ``-1`` reversing; the start's the first link's): a cusp is a pose whose
    direction differs from the next one's (:func:`segplan.viz.animate.animate_path` pauses there)."""
    unions = list(getattr(plan, "unions", plan))
    if not unions:
        raise ValueError("plan must hold at least one segplan.Union")
    directions = getattr(plan, "link_directions", None) or (1,) * len(unions)
    parts = [union_poses(u, step)[:: 1 if d > 0 else -1] for u, d in zip(unions, directions, strict=True)]
    # consecutive unions share their node: keep it once (with the link that reaches it)
    parts = [parts[0]] + [p[1:] for p in parts[1:]]
    signs = np.concatenate(
        [np.full(len(p), d, dtype=np.int64) for p, d in zip(parts, directions, strict=True)]
    )
    return np.concatenate(parts), signs


def se2_poses(states: Iterable) -> np.ndarray:
    """Poses ``(n, 3)`` from SE(2) states with ``getX()``, ``getY()``, ``getYaw()`` (OMPL's).

    Duck-typed: segplan does not import OMPL. Densify the path first (OMPL:
    ``path.interpolate(count)``).
    """
    rows = [(s.getX(), s.getY(), s.getYaw()) for s in states]
    if len(rows) < 2:
        raise ValueError(f"states must hold at least 2 states, got {len(rows)}")
    return as_poses(np.array(rows, dtype=float), "states")
