"""segplan against modern sampling-based planners on the same floors (beyond the paper).

On each shipped scenario, OMPL's asymptotically optimal planners RRT*, Informed RRT* and
BIT* (the ``ompl`` 2.x Python bindings, optional dependency group ``peers``) plan for the
same robot at fixed time budgets and several seeds, and segplan plans with each of its
heuristics. Every path, ours and theirs, is measured by the one shared function
:func:`segplan.metrics.measure_path` (front-wheel length, the paper's cost; rear length;
curvature; clearance; the dense shapely collision oracle).

The peers' problem, made as equal as OMPL allows
------------------------------------------------
- **State space**: OMPL's ``DubinsStateSpace`` (forward only) with turning radius
  ``R = L / tan(max_steer)``, the limit segplan plans under (``Robot.min_turning_radius``);
  ``(x, y)`` bounded by the scenario's free bounds. The Reeds-Shepp space (same ``R``)
  is run as a *reference only*: it reverses, which neither segplan nor the paper's
  robot does; its paths carry cusps (``reversals``).
- **Validity**: a state is valid iff the robot's segment A-B at that pose is free of every
  *enlarged* obstacle and strictly inside the free bounds: :class:`SegmentValidity`, which
  calls segplan's own pose tests (:func:`segplan.geometry.pose_collides`,
  :func:`segplan.geometry.pose_in_bounds`) behind exact-safe bounding-box filters.
  It answers exactly as :meth:`segplan.Scenario.is_free` (tested).
- **Motion validity**: the discrete validator OMPL installs for these spaces
  (``DubinsMotionValidator``, ``ReedsSheppMotionValidator``): states along the curve every
  :data:`RESOLUTION` = 2 cm of rear-point arc length (``setStateValidityCheckingResolution``
  as a fraction of the space's maximum extent). Between two checked states the front
  wheel moves at most ``2 cm (1 + L / R)``; every returned path is re-checked by the
  dense oracle at 1 cm, and any invalid one is reported (``valid`` column).
- **Objective**: ``PathLengthOptimizationObjective``, OMPL's default, which for these
  spaces is the length of the *rear point's* path (the space's distance): OMPL
  optimises a different cost from segplan's (front-wheel length, formula [1]). Its cost
  threshold is left at 0, so every planner uses its whole budget. Planners run with
  their default parameters; no path simplification.
- **Budgets and seeds**: wall-clock budgets (``SimpleSetup.solve(seconds)``) of 0.1, 1
  and 5 s; seeds 1..5. Each run is a fresh Python process (:func:`solve_ompl_isolated`),
  because OMPL seeds its generators only before the first one is created in a process.
  Deterministic given the seed is the *sequence* of samples; how many of them fit in a
  budget depends on the machine and its load, so results vary from run to run.
- **segplan**: :func:`segplan.plan_scenario` with heuristics a, b, c (default options),
  each as the paper's search finds it and refined by :func:`segplan.refine` (beyond the
  paper: shortcuts, splits and local moves of the nodes; ``+refine`` in ``method``);
  time: the median wall time of :data:`SEGPLAN_REPEATS` plans in one process, after the
  process's one-time set-up (the first-use fit of the heuristic frame's coefficients,
  :func:`segplan.frame.heuristic_coefficients`, about a second, measured and reported
  apart, like OMPL's library load).

Goal: on each scenario segplan's front-wheel length at most that of the best
OMPL result at 5 s, found in under 1/50 of that time (0.1 s). :func:`goal_table` judges
the refined planner by default (``refine=False``: the paper's search alone).

OMPL's sharp edges met (ompl 2.0.1 wheel)
------------------------------------------
- A heading of exactly ``+pi`` fails ``satisfiesBounds`` (SO(2) is ``[-pi, pi)``) and the
  start is rejected as invalid: :func:`ompl_heading` wraps into ``[-pi, pi)`` strictly.
- ``RNG.setSeed(0)`` warns "seed cannot be 0. Using 1 instead": seeds 0 and 1 would be
  the same run. We use seeds >= 1 and refuse 0.
- ``RNG.setSeed`` after any generator exists (a state space's sampler, a planner) only
  prints "Random number generation already started. Changing seed now will not lead to
  deterministic sampling": hence one process per run, seeded first.
- RRT* and Informed RRT* warn that they "require a state space with symmetric distance
  and symmetric interpolation" on Dubins (asymmetric by nature); Informed RRT* also that
  the space "is not metric", so informed pruning may not hold. ``DubinsStateSpace(R,
  isSymmetric=True)`` would silence the warning but its interpolation then follows the
  reverse curve backwards (the robot reversing), so we keep the default and report the
  warnings (``messages`` column).
- ``ProblemDefinition.setIntermediateSolutionCallback`` does not accept a Python
  function in these bindings (no time-to-first-solution is recorded).
- At interpreter exit nanobind prints "leaked instances" reports on stderr; they are
  filtered from the captured output.

Results as data
---------------
OMPL's runs stop at a wall-clock budget, so they depend on the machine and its load:
they are measured once by ``python benchmarks/peers.py`` (the command line over this
module) and stored: :func:`write_ompl_results` writes one CSV row per run, the poses of
the best valid run per floor, space, planner and budget, and the provenance (date,
machine, OMPL version, commit, command line) beside it; :func:`read_ompl_results` reads
them back. segplan's side is deterministic (:func:`run_segplan`) and is recomputed
wherever it is needed (the book computes it at build time).

Usage::

    python benchmarks/peers.py                               # the full study, stored in benchmarks/results/
    python benchmarks/peers.py --quick --out /tmp/peers.csv  # smoke run (tiny budgets, 1 seed)
"""

from __future__ import annotations

import datetime
import gzip
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import time
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import pandas as pd
from tqdm import tqdm

from .. import world
from ..api import plan_scenario
from ..geometry import as_polygon, pose_collides, pose_in_bounds
from ..metrics import measure_scenario_path, plan_poses, se2_poses
from ..path import NoPathError
from ..world import Robot, Scenario, load_scenario, make_scenario, scenario_from_dict

__all__ = [
    "BUDGETS",
    "HEURISTICS",
    "PLANNERS",
    "SEEDS",
    "Runs",
    "SegmentValidity",
    "StudyConfig",
    "best_paths",
    "budget_table",
    "check_seed",
    "full_config",
    "goal_table",
    "load",
    "missing_runs",
    "ompl_available",
    "ompl_heading",
    "ompl_version",
    "provenance",
    "quick_config",
    "read_ompl_results",
    "run_ompl",
    "run_segplan",
    "segplan_method",
    "shipped_scenarios",
    "solve_ompl",
    "solve_ompl_isolated",
    "solve_segplan",
    "summary_table",
    "warm_up",
    "write_ompl_results",
]

PLANNERS = ("RRTstar", "InformedRRTstar", "BITstar")
SPACES = ("dubins", "reedsshepp")
HEURISTICS = ("a", "b", "c")
BUDGETS = (0.1, 1.0, 5.0)
SEEDS = (1, 2, 3, 4, 5)
#: Rear-point arc length (m) between states checked by OMPL's motion validator.
RESOLUTION = 0.02
#: Spacing (m) of the samples every path is measured on.
STEP = 0.01
#: Spacing (m) of the poses kept for figures.
PLOT_STEP = 0.05
#: Plans timed per scenario and heuristic (the median is reported).
SEGPLAN_REPEATS = 5
#: The goal's time ratio: segplan within 1/50 of OMPL's budget.
TIME_RATIO = 50.0
#: Bump when the harness changes in a way that invalidates cached results.
HARNESS_VERSION = 2
_MARK = "@@peers@@"


# -- inputs OMPL accepts -------------------------------------------------------------------
def ompl_heading(theta: float) -> float:
    """``theta`` wrapped strictly into ``[-pi, pi)``, the interval OMPL's SO(2) accepts.

    OMPL rejects a start heading of exactly ``+pi`` as out of bounds. ``x % (2 pi)`` can
    round up to ``2 pi`` itself for tiny negative ``x``; the result is folded back.
    """
    a = (float(theta) + math.pi) % (2.0 * math.pi) - math.pi
    if a >= math.pi:
        a -= 2.0 * math.pi
    if not -math.pi <= a < math.pi or not math.isfinite(a):
        raise ValueError(f"theta must be a finite angle, got {theta!r}")
    return a


def check_seed(seed) -> int:
    """OMPL seeds are integers >= 1 (``setSeed(0)`` is silently replaced by 1)."""
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 1:
        raise ValueError(f"seed must be an integer >= 1 (OMPL replaces 0 by 1), got {seed!r}")
    return int(seed)


# -- the validity check both planners share ------------------------------------------------
class SegmentValidity:
    """Is the robot's segment at ``(x, y, theta)`` free? The planning model of segplan.

    Valid iff :func:`segplan.geometry.pose_in_bounds` holds for the free bounds and
    :func:`segplan.geometry.pose_collides` is false for every enlarged obstacle. Those
    two functions decide every case that is not clear by a wide margin: a polygon whose
    bounding box, grown by ``margin``, misses the segment's bounding box cannot touch the
    segment, and a segment whose end points are inside the free bounds (or outside one of
    them) by more than ``margin`` is in bounds (out of bounds), so neither is asked.
    ``margin`` is a thousandth of the scene's size, a million times the collision
    module's touching tolerance: the answers are those of :meth:`segplan.Scenario.is_free`
    (tested), only cheaper. ``calls`` counts the queries.

    Parameters
    ----------
    scenario : Scenario
    """

    def __init__(self, scenario: Scenario):
        if not isinstance(scenario, Scenario):
            raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
        self.L = scenario.robot.L
        self.bounds = scenario.free_bounds
        self.polygons = [as_polygon(p) for p in scenario.enlarged]
        extent = self.L + max(
            [abs(v) for v in (self.bounds or ())]
            + [float(np.abs(p.vertices).max()) for p in self.polygons]
            + [abs(scenario.start.x), abs(scenario.start.y), abs(scenario.goal.x), abs(scenario.goal.y)]
        )
        self.margin = m = 1e-3 * extent  # >= 1e6 x TOUCH_RTOL (1e-9) x the scene size
        self._boxes = [
            (*(p.vertices.min(axis=0) - m).tolist(), *(p.vertices.max(axis=0) + m).tolist(), p)
            for p in self.polygons
        ]
        if self.bounds is not None:
            xmin, ymin, xmax, ymax = self.bounds
            self._inner = (xmin + m, ymin + m, xmax - m, ymax - m)
            self._outer = (xmin - m, ymin - m, xmax + m, ymax + m)
        self.calls = 0

    def __call__(self, x: float, y: float, theta: float) -> bool:
        self.calls += 1
        L = self.L
        bx, by = x + L * math.cos(theta), y + L * math.sin(theta)
        lox, hix = (x, bx) if x <= bx else (bx, x)
        loy, hiy = (y, by) if y <= by else (by, y)
        pose = (x, y, theta)
        if self.bounds is not None:
            ix0, iy0, ix1, iy1 = self._inner
            if not (ix0 < lox and hix < ix1 and iy0 < loy and hiy < iy1):
                ox0, oy0, ox1, oy1 = self._outer
                if not (ox0 < lox and hix < ox1 and oy0 < loy and hiy < oy1):
                    return False
                if not pose_in_bounds(pose, L, self.bounds):
                    return False
        for px0, py0, px1, py1, poly in self._boxes:
            if hix < px0 or lox > px1 or hiy < py0 or loy > py1:
                continue
            if pose_collides(pose, L, poly, check=False):
                return False
        return True


# -- OMPL ----------------------------------------------------------------------------------
def ompl_available() -> bool:
    """Can the OMPL Python bindings be imported?"""
    try:
        from ompl import base, geometric, util  # noqa: F401
    except ImportError:
        return False
    return True


def ompl_version() -> str:
    """The installed OMPL bindings' version (``"none"`` without them)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("ompl")
    except PackageNotFoundError:
        return "none"


def _scenario_arg(scenario) -> Scenario:
    if isinstance(scenario, Scenario):
        return scenario
    if isinstance(scenario, str | Path):
        return load(scenario)
    raise ValueError(f"scenario must be a segplan.Scenario or a scenario name/path, got {scenario!r}")


def load(name: str | Path) -> Scenario:
    """A shipped scenario by name (``"fig5_example1"``) or any scenario file path."""
    return load_scenario(name)


def solve_ompl(
    scenario,
    planner: str,
    budget: float,
    seed: int,
    space: str = "dubins",
    resolution: float = RESOLUTION,
    step: float = STEP,
) -> dict:
    """One OMPL run, *in this process*; a row of the study plus the path's poses.

    The seed is effective only if no OMPL random generator exists yet in the process:
    use :func:`solve_ompl_isolated` for reproducible seeds.

    Returns
    -------
    dict
        ``method`` (planner name), ``space``, ``budget``, ``seed``, ``status`` (OMPL's
        planner status), ``solved`` (an exact solution), ``seconds`` (wall time of
        ``solve``), ``cpu_seconds`` (the CPU time it got), ``checks`` (state validity
        queries), ``ompl_cost`` (OMPL's objective, the rear path length), the
        :class:`segplan.metrics.PathMetrics` fields (NaN without an exact solution),
        ``valid`` (solved and passes the dense oracle) and ``poses`` (``(n, 3)`` list,
        one pose every :data:`PLOT_STEP` m, or None).
    """
    from ompl import base as ob
    from ompl import geometric as og
    from ompl import util as ou

    sc = _scenario_arg(scenario)
    seed = check_seed(seed)
    if planner not in PLANNERS:
        raise ValueError(f"planner must be one of {PLANNERS}, got {planner!r}")
    if space not in SPACES:
        raise ValueError(f"space must be one of {SPACES}, got {space!r}")
    if not (isinstance(budget, int | float) and math.isfinite(budget) and budget > 0):
        raise ValueError(f"budget must be a positive number of seconds, got {budget!r}")
    if sc.free_bounds is None:
        raise ValueError("scenario must have bounds: OMPL samples (x, y) inside them")
    ou.RNG.setSeed(seed)  # before any generator exists (fresh process)
    ou.setLogLevel(ou.LOG_WARN)

    R = sc.robot.min_turning_radius  # L / tan(max_steer)
    ss_space = ob.DubinsStateSpace(R) if space == "dubins" else ob.ReedsSheppStateSpace(R)
    xmin, ymin, xmax, ymax = sc.free_bounds
    b = ob.RealVectorBounds(2)
    b.setLow(0, xmin)
    b.setHigh(0, xmax)
    b.setLow(1, ymin)
    b.setHigh(1, ymax)
    ss_space.setBounds(b)
    ss = og.SimpleSetup(ss_space)
    validity = SegmentValidity(sc)
    ss.setStateValidityChecker(lambda s: validity(s.getX(), s.getY(), s.getYaw()))
    si = ss.getSpaceInformation()
    si.setStateValidityCheckingResolution(resolution / ss_space.getMaximumExtent())
    start, goal = ss_space.allocState(), ss_space.allocState()
    for st, p in ((start, sc.start), (goal, sc.goal)):
        st.setXY(p.x, p.y)
        st.setYaw(ompl_heading(p.theta))
    ss.setStartAndGoalStates(start, goal)
    ss.setOptimizationObjective(ob.PathLengthOptimizationObjective(si))
    ss.setPlanner(getattr(og, planner)(si))
    ss.setup()
    t0, c0 = time.perf_counter(), time.process_time()
    status = ss.solve(float(budget))
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    solved = bool(ss.haveExactSolutionPath())
    row = {
        "scenario": sc.name,
        "method": planner,
        "space": space,
        "budget": float(budget),
        "seed": seed,
        "status": str(status),
        "solved": solved,
        "seconds": seconds,
        "cpu_seconds": cpu,
        "checks": validity.calls,
        "ompl_cost": math.nan,
    }
    poses = None
    metrics = dict.fromkeys(_METRIC_FIELDS, math.nan)
    if solved:
        path = ss.getSolutionPath()
        row["ompl_cost"] = float(path.length())
        path.interpolate(max(2, math.ceil(path.length() / (0.5 * step)) + 1))
        P = se2_poses(path.getStates())
        metrics = measure_scenario_path(P, sc).as_dict()
        poses = _thin(P, path.length(), PLOT_STEP).tolist()
    row.update(metrics)
    row["valid"] = bool(solved and not metrics["collides"])
    row["poses"] = poses
    return row


_METRIC_FIELDS = (
    "front_length",
    "rear_length",
    "max_curvature",
    "curvature_jump",
    "curvature_jumps",
    "reversals",
    "clearance",
    "collides",
    "samples",
    "step",
)


def _thin(P: np.ndarray, length: float, step: float) -> np.ndarray:
    """About one pose every ``step`` metres of ``P`` (first and last kept)."""
    k = max(1, int(len(P) * step / max(length, 1e-12)))
    idx = np.unique(np.r_[np.arange(0, len(P), k), len(P) - 1])
    return P[idx]


def _clean_stderr(text: str) -> list[str]:
    """OMPL's warnings and errors from a worker's stderr, without nanobind's leak report."""
    out = []
    for line in text.splitlines():
        s = line.strip()
        if s.startswith(("Warning:", "Error:")):
            out.append(s)
    return out


def solve_ompl_isolated(
    scenario, planner: str, budget: float, seed: int, space: str = "dubins", **kw
) -> dict:
    """:func:`solve_ompl` in a fresh Python process, so that ``seed`` takes effect.

    The row gains ``messages``: OMPL's warnings and errors of the run (`` | ``-joined,
    without nanobind's leak report at exit). A worker that fails raises RuntimeError with
    its stderr.
    """
    sc = _scenario_arg(scenario)
    job = {
        "scenario": sc.to_dict(),
        "planner": planner,
        "budget": budget,
        "seed": check_seed(seed),
        "space": space,
        **kw,
    }
    proc = subprocess.run(
        [sys.executable, "-m", __name__, "--worker"],
        input=json.dumps(job),
        capture_output=True,
        text=True,
        timeout=60.0 + 3.0 * float(budget),
        check=False,
    )
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith(_MARK)]
    if proc.returncode != 0 or not lines:
        raise RuntimeError(
            f"OMPL worker failed ({planner}, {space}, {budget} s, seed {seed}) with code {proc.returncode}:\n"
            + proc.stderr[-3000:]
        )
    row = json.loads(lines[-1][len(_MARK) :])
    row["scenario"] = sc.name
    row["messages"] = " | ".join(dict.fromkeys(_clean_stderr(proc.stderr)))
    return row


def _worker() -> None:
    job = json.loads(sys.stdin.read())
    sc = scenario_from_dict(job.pop("scenario"), source="<peers worker>")
    row = solve_ompl(sc, **job)
    sys.stdout.write(_MARK + json.dumps(row) + "\n")
    sys.stdout.flush()


# -- segplan -------------------------------------------------------------------------------
def warm_up() -> float:
    """The process's one-time set-up of segplan (seconds): one plan on a small floor.

    The first plan in a process loads the stored fitted constants (:mod:`segplan.constants`)
    and warms the interpreter's caches, once. It is excluded from the times, like OMPL's
    library load.
    """
    robot = Robot(1.0, 0.0)
    sc = make_scenario(
        robot,
        (1.0, 1.0, 0.0),
        (6.0, 3.0, 0.5),
        [[[3, 3.5], [4, 3.5], [3.5, 4.5]]],
        (0.0, 0.0, 8.0, 6.0),
        name="warm-up",
    )
    t0 = time.perf_counter()
    for h in HEURISTICS:
        plan_scenario(sc, heuristic=h, planner="paper")
    return time.perf_counter() - t0


def segplan_method(heuristic: str = "a", refine: bool = False) -> str:
    """The ``method`` label of segplan's rows: ``"segplan h'=a"``, ``"segplan h'=a +refine"``."""
    return f"segplan h'={heuristic}" + (" +refine" if refine else "")


def solve_segplan(
    scenario, heuristic: str = "a", repeats: int = SEGPLAN_REPEATS, step: float = STEP, refine: bool = False
) -> dict:
    """segplan on a scenario: a row like :func:`solve_ompl`'s (``method``: :func:`segplan_method`).

    ``refine=True`` plans with :func:`segplan.refine` after the search (beyond the
    paper; ``seconds`` counts both).

    ``seconds`` is the median wall time (``Plan.seconds``) of ``repeats`` plans (the plan
    itself is deterministic) after one untimed plan; call :func:`warm_up` once per
    process first. ``plan_cost`` is Plan.cost, the exact LONGD [1], which
    the measured ``front_length`` must match. A NoPathError gives ``solved=False`` and
    ``status`` its reason.
    """
    sc = _scenario_arg(scenario)
    if isinstance(repeats, bool) or not isinstance(repeats, int) or repeats < 1:
        raise ValueError(f"repeats must be an integer >= 1, got {repeats!r}")
    row = {
        "scenario": sc.name,
        "method": segplan_method(heuristic, refine),
        "space": "segplan",
        "budget": math.nan,
        "seed": 0,
    }
    times, plan = [], None
    try:
        plan_scenario(
            sc, heuristic=heuristic, refine=refine, planner="paper"
        )  # untimed: per-scenario caches (d_s)
        for _ in range(repeats):
            plan = plan_scenario(sc, heuristic=heuristic, refine=refine, planner="paper")
            times.append(plan.seconds)
    except NoPathError as exc:
        times.append(exc.seconds)
        row.update(status=f"no path ({exc.reason})", solved=False, seconds=statistics.median(times))
        row.update(checks=0, ompl_cost=math.nan, **dict.fromkeys(_METRIC_FIELDS, math.nan))
        row.update(valid=False, poses=None, plan_cost=math.nan, nodes=0, messages="")
        return row
    P = plan_poses(plan, step)
    m = measure_scenario_path(P, sc)
    row.update(status="exact", solved=True, seconds=statistics.median(times), checks=plan.collision_checks)
    row.update(ompl_cost=math.nan, **m.as_dict())
    row.update(valid=not m.collides, poses=_thin(P, m.rear_length, PLOT_STEP).tolist())
    row.update(plan_cost=plan.cost, nodes=len(plan.nodes), messages="")
    return row


# -- the study ----------------------------------------------------------------------------
@dataclass(frozen=True)
class Runs:
    """One block of OMPL runs: every scenario x planner x budget x seed in one space."""

    scenarios: tuple[str, ...]
    planners: tuple[str, ...] = PLANNERS
    budgets: tuple[float, ...] = BUDGETS
    seeds: tuple[int, ...] = SEEDS
    space: str = "dubins"

    def jobs(self):
        for s in self.scenarios:
            for b in self.budgets:
                for p in self.planners:
                    for seed in self.seeds:
                        yield (s, p, float(b), check_seed(seed), self.space)


@dataclass(frozen=True)
class StudyConfig:
    """What a study runs: segplan on ``scenarios`` with ``heuristics`` (each as found by the
    search and, if ``True`` is in ``refine``, refined), and OMPL ``blocks``."""

    scenarios: tuple[str, ...]
    blocks: tuple[Runs, ...]
    heuristics: tuple[str, ...] = HEURISTICS
    refine: tuple[bool, ...] = (False, True)
    resolution: float = RESOLUTION
    step: float = STEP
    segplan_repeats: int = SEGPLAN_REPEATS

    def jobs(self) -> list:
        """Every OMPL run ``(scenario, planner, budget, seed, space)``, each once."""
        return list(dict.fromkeys(j for block in self.blocks for j in block.jobs()))


def shipped_scenarios() -> tuple[str, ...]:
    """The study's floors: the shipped scenarios whose obstacles are all convex, as in the paper.

    A floor with a non-convex obstacle (``l_shaped_rack``, split into convex pieces by
    :mod:`segplan.decompose`, beyond the paper) is not part of the comparison with the
    peers, whose stored runs (``benchmarks/results/peers_ompl.csv``) cover exactly these.
    """
    names = world.shipped_scenarios()
    return tuple(n for n in names if len((sc := load_scenario(n)).outlines) == len(sc.obstacles))


def full_config() -> StudyConfig:
    """The full study: every shipped scenario, 3 planners x 3 budgets x 5 seeds on Dubins;
    Reeds-Shepp (reference) with BIT* at 1 and 5 s, 5 seeds."""
    names = shipped_scenarios()
    return StudyConfig(
        scenarios=names,
        blocks=(Runs(names), Runs(names, planners=("BITstar",), budgets=(1.0, 5.0), space="reedsshepp")),
    )


def quick_config(scenarios: Sequence[str] = ("single_obstacle",)) -> StudyConfig:
    """A smoke run: tiny budget, one seed, one planner per space, one heuristic."""
    names = tuple(scenarios)
    return StudyConfig(
        scenarios=names,
        blocks=(
            Runs(names, planners=("RRTstar",), budgets=(0.05,), seeds=(1,)),
            Runs(names, planners=("RRTstar",), budgets=(0.05,), seeds=(1,), space="reedsshepp"),
        ),
        heuristics=("a",),
        segplan_repeats=1,
    )


def _progress(total: int, desc: str):
    """A tqdm bar on a terminal; silent when stderr is not one (book build, pytest, logs)."""
    return tqdm(total=total, desc=desc, unit="run", disable=None, leave=False)


def run_segplan(config: StudyConfig) -> pd.DataFrame:
    """segplan's rows of a study: every scenario x heuristic x refine, in this process.

    Deterministic but for the ``seconds`` column (median wall times); calls
    :func:`warm_up` first. One row per plan, as :func:`solve_segplan`; the poses are
    dropped (plans are cheap to recompute).
    """
    if config.heuristics:
        warm_up()
    rows = []
    todo = [(n, h, r) for n in config.scenarios for h in config.heuristics for r in config.refine]
    with _progress(len(todo), "segplan") as bar:
        for name, h, refine in todo:
            row = solve_segplan(load(name), h, config.segplan_repeats, config.step, refine)
            del row["poses"]
            rows.append(row)
            bar.update()
    return pd.DataFrame(rows)


def run_ompl(config: StudyConfig, jobs: int = 1) -> tuple[pd.DataFrame, dict]:
    """Every OMPL run of ``config``, ``jobs`` processes at a time, each in a fresh process.

    ``jobs=2`` on a two-core machine runs one OMPL process per core (each planner is
    single-threaded); more than the free cores would shorten the budgets' real work.
    A progress bar shows on a terminal only.

    Returns
    -------
    table : pandas.DataFrame
        One row per run (:func:`solve_ompl`'s fields, ``messages``), without the poses.
    paths : dict
        ``(scenario, method, space, budget, seed) -> (n, 3)`` poses (one every
        :data:`PLOT_STEP` m) of every solved run.
    """
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs must be an integer >= 1, got {jobs!r}")
    todo = config.jobs()

    def one(job):
        s, p, b, seed, space = job
        return solve_ompl_isolated(load(s), p, b, seed, space, resolution=config.resolution, step=config.step)

    rows = []
    with _progress(len(todo), "OMPL") as bar, ThreadPoolExecutor(max_workers=jobs) as pool:
        for row in pool.map(one, todo):
            rows.append(row)
            bar.update()
    paths = {}
    for r in rows:
        poses = r.pop("poses")
        if poses is not None:
            paths[(r["scenario"], r["method"], r["space"], r["budget"], r["seed"])] = np.asarray(poses)
    return pd.DataFrame(rows), paths


def missing_runs(table: pd.DataFrame, config: StudyConfig) -> list[tuple]:
    """The runs of ``config`` (``(scenario, planner, budget, seed, space)``) that ``table`` lacks."""
    have = {
        (r.scenario, r.method, float(r.budget), int(r.seed), r.space)
        for r in table[["scenario", "method", "budget", "seed", "space"]].itertuples(index=False)
    }
    return [j for j in config.jobs() if j not in have]


# -- stored results ---------------------------------------------------------------------------
def _git(*args: str) -> str:
    here = Path(__file__).resolve().parent
    try:
        out = subprocess.run(["git", *args], cwd=here, capture_output=True, text=True, timeout=10, check=True)
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return out.stdout.strip()


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def provenance(argv: Sequence[str], config: StudyConfig | None, jobs: int) -> dict:
    """How, when and where a study is measured: date (UTC), machine (CPU, cores, load),
    Python, numpy and OMPL versions, the commit (and whether the tree had changes), the
    command line, the configuration (``None`` for a study that records its own, such as
    :mod:`segplan.studies.robustness`) and the harness version."""
    from .. import __version__

    status = _git("status", "--porcelain", "--untracked-files=no")
    return {
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "machine": {
            "system": f"{platform.system()} {platform.release()}",
            "arch": platform.machine(),
            "cpu": _cpu_model(),
            "cores": os.cpu_count(),
            "load_average_before": list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
            "nice": os.nice(0) if hasattr(os, "nice") else None,
        },
        "python": platform.python_version(),
        "numpy": np.__version__,
        "ompl": ompl_version(),
        "segplan": __version__,
        "commit": _git("rev-parse", "HEAD"),
        "tree_clean": status == "",
        "command": " ".join(["python", *argv]),
        "jobs": jobs,
        "harness_version": HARNESS_VERSION,
        "config": None if config is None else asdict(config),
    }


def _meta_path(csv_path: Path) -> Path:
    return csv_path.with_suffix(".json")


def _paths_path(csv_path: Path) -> Path:
    return csv_path.with_name(csv_path.stem + "_paths.json.gz")


def best_paths(table: pd.DataFrame, paths: dict) -> dict:
    """The poses of the shortest valid run (front-wheel length) per scenario, space, planner
    and budget: what the figures draw, out of every run's poses."""
    valid = table[table["valid"] == True]  # noqa: E712 (pandas)
    keep = {}
    for _, g in valid.groupby(["scenario", "space", "method", "budget"], sort=True):
        r = g.loc[g["front_length"].idxmin()]
        key = (r["scenario"], r["method"], r["space"], float(r["budget"]), int(r["seed"]))
        keep[key] = paths[key]
    return keep


def write_ompl_results(table: pd.DataFrame, paths: dict, csv_path: str | Path, meta: dict) -> list[Path]:
    """Store OMPL's runs: ``csv_path`` (one row per run), its provenance ``meta`` beside it
    (same name, ``.json``, with the wall time and load average after the runs added by the
    caller) and the poses of :func:`best_paths` (``<stem>_paths.json.gz``, mm and 1e-4 rad).

    Returns the three paths written.
    """
    csv_path = Path(csv_path)
    csv_path.parent.mkdir(parents=True, exist_ok=True)
    table.to_csv(csv_path, index=False)
    meta_path = _meta_path(csv_path)
    meta_path.write_text(json.dumps(meta, indent=1) + "\n", encoding="utf-8")
    scale = np.array([1e3, 1e3, 1e4])  # mm, 1e-4 rad
    stored = {
        "|".join(map(str, k)): (np.round(np.asarray(v) * scale) / scale).tolist()
        for k, v in best_paths(table, paths).items()
    }
    gz = _paths_path(csv_path)
    with gzip.GzipFile(gz, "wb", mtime=0) as fh:
        fh.write(json.dumps(stored, separators=(",", ":")).encode())
    return [csv_path, meta_path, gz]


def read_ompl_results(csv_path: str | Path) -> tuple[pd.DataFrame, dict, dict]:
    """OMPL's stored runs: ``(table, paths, meta)`` as :func:`write_ompl_results` wrote them.

    ``paths`` maps ``(scenario, method, space, budget, seed)`` to ``(n, 3)`` poses of the
    best valid run per scenario, space, planner and budget.
    """
    csv_path = Path(csv_path)
    if not csv_path.is_file():
        raise ValueError(f"csv_path: no stored OMPL results at {csv_path} (run benchmarks/peers.py)")
    table = pd.read_csv(csv_path, keep_default_na=False, na_values=[""])
    table["messages"] = table["messages"].fillna("").astype(str)
    meta = json.loads(_meta_path(csv_path).read_text(encoding="utf-8"))
    with gzip.open(_paths_path(csv_path), "rb") as fh:
        raw = json.loads(fh.read())
    paths = {}
    for key, poses in raw.items():
        scenario, method, space, budget, seed = key.split("|")
        paths[(scenario, method, space, float(budget), int(seed))] = np.asarray(poses)
    return table, paths, meta


# -- tables -------------------------------------------------------------------------------
def budget_table(table: pd.DataFrame, space: str = "dubins") -> pd.DataFrame:
    """Per scenario, planner and budget: runs, exact solutions, invalid paths, and the
    best / median front-wheel length of the valid ones."""
    t = table[table["space"] == space]
    valid = t[t["valid"] == True]  # noqa: E712 (pandas)
    g = t.groupby(["scenario", "method", "budget"], sort=True)
    out = pd.DataFrame(
        {
            "runs": g.size(),
            "solved": g["solved"].sum().astype(int),
            "invalid": (g["solved"].sum() - g["valid"].sum()).astype(int),
        }
    )
    gv = valid.groupby(["scenario", "method", "budget"])
    out["best_front"] = gv["front_length"].min()
    out["median_front"] = gv["front_length"].median()
    out["best_rear"] = gv["rear_length"].min()
    return out.reset_index()


def goal_table(
    table: pd.DataFrame, budget: float = 5.0, heuristic: str = "a", refine: bool = True
) -> pd.DataFrame:
    """The issue's goal per scenario: segplan (``heuristic``, refined or as found) against
    the best valid Dubins run at ``budget`` (over planners and seeds), by front-wheel length.

    Columns: ``segplan_front``, ``segplan_ms``, ``ompl_best_front``, ``ompl_planner``,
    ``ompl_runs`` (valid runs at that budget), ``length_ratio`` (segplan / OMPL),
    ``time_ratio`` (budget / segplan time), ``shorter``, ``fast`` (time ratio >= 50),
    ``goal_met``. Scenarios without OMPL runs at ``budget`` are left out.
    """
    rows = []
    ours = table[table["method"] == segplan_method(heuristic, refine)].set_index("scenario")
    peers = table[(table["space"] == "dubins") & (table["budget"] == budget)]
    for name, runs in peers.groupby("scenario", sort=True):
        valid = runs[runs["valid"] == True]  # noqa: E712
        s = ours.loc[name] if name in ours.index else None
        seg_front = float(s["front_length"]) if s is not None and bool(s["solved"]) else math.nan
        seg_s = float(s["seconds"]) if s is not None else math.nan
        if len(valid):
            best = valid.loc[valid["front_length"].idxmin()]
            o_front, o_planner = float(best["front_length"]), str(best["method"])
        else:
            o_front, o_planner = math.nan, "none"
        shorter = bool(seg_front <= o_front) if math.isfinite(seg_front) else False
        if math.isfinite(seg_front) and not math.isfinite(o_front):
            shorter = True  # OMPL found no valid path at all
        fast = bool(math.isfinite(seg_front) and seg_s * TIME_RATIO < budget)
        rows.append(
            {
                "scenario": name,
                "segplan_front": seg_front,
                "segplan_ms": 1e3 * seg_s,
                "ompl_best_front": o_front,
                "ompl_planner": o_planner,
                "ompl_runs": int(len(valid)),
                "length_ratio": seg_front / o_front if math.isfinite(o_front) else math.nan,
                "time_ratio": budget / seg_s if seg_s > 0 else math.inf,
                "shorter": shorter,
                "fast": fast,
                "goal_met": shorter and fast,
            }
        )
    return pd.DataFrame(rows)


def summary_table(table: pd.DataFrame) -> pd.DataFrame:
    """Per scenario: each segplan variant and, per budget, the best valid Dubins run (front length, ms)."""
    rows = []
    for name, t in table.groupby("scenario", sort=True):
        row = {"scenario": name}
        for _, r in t[t["space"] == "segplan"].iterrows():
            h = r["method"].removeprefix("segplan h'=")
            row[f"segplan {h} front"] = r["front_length"]
            row[f"segplan {h} ms"] = 1e3 * r["seconds"]
        d = t[(t["space"] == "dubins") & (t["valid"] == True)]  # noqa: E712
        for b, tb in d.groupby("budget"):
            row[f"OMPL {b:g} s front"] = tb["front_length"].min()
        rows.append(row)
    return pd.DataFrame(rows)


if __name__ == "__main__":  # the worker of solve_ompl_isolated: python -m segplan.studies.peers --worker
    if sys.argv[1:] != ["--worker"]:
        sys.exit("this module is the OMPL worker; the command line is benchmarks/peers.py")
    _worker()
