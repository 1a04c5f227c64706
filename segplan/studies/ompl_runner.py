"""One OMPL run on a segplan scenario: the runner of the peer studies (beyond the paper).

OMPL's asymptotically optimal planners RRT*, Informed RRT* and BIT* (the ``ompl`` 2.x
Python bindings, optional dependency group ``peers``) plan for segplan's robot on a
segplan scenario at a wall-clock budget and a seed, each run in a fresh process
(:func:`solve_ompl_isolated`); every path is measured by the one shared function
:func:`segplan.viz.metrics.measure_scenario_path`. :mod:`segplan.studies.peers` (chapter 8,
``benchmarks/peers.py``) and :mod:`segplan.studies.robustness` (chapter 9,
``benchmarks/robustness.py``) run OMPL through this module and store :func:`provenance`
beside their runs.

The peers' problem, made as equal as OMPL allows
------------------------------------------------
- **State space**: OMPL's ``DubinsStateSpace`` (forward only) with turning radius
  ``R = L / tan(max_steer)``, the limit segplan plans under (``Robot.min_turning_radius``);
  ``(x, y)`` bounded by the scenario's free bounds. The Reeds-Shepp space (same ``R``)
  is run as a *reference only*: it reverses, which neither segplan nor the paper's
  robot does; its paths carry cusps (``reversals``).
- **Validity**: a state is valid iff the robot's segment A-B at that pose (extended by its
  overhangs, :attr:`segplan.Robot.axis`, on a robot with a body) is free of every
  *enlarged* obstacle and strictly inside the free bounds: :class:`SegmentValidity`, which
  calls segplan's own pose tests (:func:`segplan.floor.geometry.pose_collides`,
  :func:`segplan.floor.geometry.pose_in_bounds`) behind exact-safe bounding-box filters.
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
  their default parameters.
- **Simplification, like with like**: segplan's plans are compared as found and refined
  (:func:`segplan.refine`); OMPL's as returned (*raw*) and after OMPL's own
  ``PathSimplifier.simplify`` (vertex reduction, shortcuts, B-spline smoothing, under the
  same objective and motion validator), bounded by :data:`SIMPLIFY_SECONDS` and timed
  (``simplify_seconds``). The simplified path is measured by the same function and the
  same dense oracle; its measures are stored beside the raw ones (``simplified_*``).
- **Fairness**: each run records its CPU time and the machine's 1-minute load average
  before and after ``solve`` (``load_before``, ``load_after``); the executor
  (:mod:`segplan.studies.executor`) refuses a run that got less than its share.
- **Budgets and seeds**: wall-clock budgets (``SimpleSetup.solve(seconds)``) and seeds
  >= 1, the studies' own (:data:`segplan.studies.peers.BUDGETS`, ``SEEDS``). Each run is
  a fresh Python process (:func:`solve_ompl_isolated`), because OMPL seeds its generators
  only before the first one is created in a process.
  Deterministic given the seed is the *sequence* of samples; how many of them fit in a
  budget depends on the machine and its load, so results vary from run to run.

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

"""

from __future__ import annotations

import datetime
import json
import math
import os
import platform
import subprocess
import sys
import time
from collections.abc import Sequence
from dataclasses import asdict, fields
from pathlib import Path

import numpy as np

from ..floor.geometry import as_polygon, axis_segment, pose_collides, pose_in_bounds
from ..floor.scenario import Scenario, load_scenario, scenario_from_dict
from ..model.pose import TWO_PI, wrap_floor
from ..viz.metrics import PathMetrics, measure_scenario_path, se2_poses
from .executor import FAIRNESS, FairnessRule

__all__ = [
    "HARNESS_VERSION",
    "METRIC_FIELDS",
    "PLANNERS",
    "PLOT_STEP",
    "RESOLUTION",
    "SIMPLIFIED_FIELDS",
    "SIMPLIFY_SECONDS",
    "SPACES",
    "STEP",
    "SegmentValidity",
    "as_scenario",
    "check_seed",
    "ompl_available",
    "ompl_heading",
    "ompl_version",
    "provenance",
    "solve_ompl",
    "solve_ompl_isolated",
    "thin_poses",
    "worker_limit",
]

PLANNERS = ("RRTstar", "InformedRRTstar", "BITstar")
SPACES = ("dubins", "reedsshepp")
#: Rear-point arc length (m) between states checked by OMPL's motion validator.
RESOLUTION = 0.02
#: Spacing (m) of the samples every path is measured on.
STEP = 0.01
#: Spacing (m) of the poses kept for figures.
PLOT_STEP = 0.05
#: Bump when the harness changes in a way that invalidates cached results (3: CPU share
#: and load per run, OMPL's PathSimplifier beside the raw path).
HARNESS_VERSION = 3
#: The columns of :class:`segplan.viz.metrics.PathMetrics` in every run's row.
METRIC_FIELDS = tuple(f.name for f in fields(PathMetrics))
#: Longest time (s) OMPL's ``PathSimplifier.simplify`` may take on one path.
SIMPLIFY_SECONDS = 1.0
#: The columns of the simplified path, beside the raw ones: ``simplified_`` + the metric
#: fields, its OMPL cost and validity.
SIMPLIFIED_FIELDS = tuple(f"simplified_{f}" for f in (*METRIC_FIELDS, "ompl_cost", "valid"))
_MARK = "@@peers@@"


def worker_limit(budget: float) -> float:
    """Wall seconds a worker of :func:`solve_ompl_isolated` may take for a run of ``budget``
    seconds before it is killed and its run recorded as overrun: ``60 + 3 budget`` (the
    process's start, OMPL's set-up, the simplifier and the path's measures take a few
    seconds; BIT* on the Reeds-Shepp space was seen to return after 246 s of a 5 s budget,
    on ``dead-end-007`` of :mod:`segplan.studies.reverse_floors`)."""
    return 60.0 + 3.0 * float(budget)


# -- inputs OMPL accepts -------------------------------------------------------------------
def ompl_heading(theta: float) -> float:
    """``theta`` wrapped strictly into ``[-pi, pi)``, the interval OMPL's SO(2) accepts.

    OMPL rejects a start heading of exactly ``+pi`` as out of bounds. ``x % (2 pi)`` can
    round up to ``2 pi`` itself for tiny negative ``x``; the result is folded back.
    """
    t = float(theta)
    if not math.isfinite(t):
        raise ValueError(f"theta must be a finite angle, got {theta!r}")
    a = float(wrap_floor(t))  # (theta + pi) mod 2 pi - pi
    if a >= math.pi:
        a -= TWO_PI
    if not -math.pi <= a < math.pi:
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

    The segment is the robot's axis segment, A->B extended by its overhangs
    (:attr:`segplan.Robot.axis`; A->B itself, the same floats, for the paper's robot), so a
    robot with a body is checked against the same body as segplan's planner. Valid iff
    :func:`segplan.floor.geometry.pose_in_bounds` holds for the free bounds and
    :func:`segplan.floor.geometry.pose_collides` is false for every enlarged obstacle. Those
    two functions decide every case that is not clear by a wide margin: a polygon whose
    bounding box, grown by ``margin``, misses the segment's bounding box cannot touch the
    segment, and a segment whose end points are inside the free bounds (or outside one of
    them) by more than ``margin`` is in bounds (out of bounds), so neither is asked.
    ``margin`` is a thousandth of the scene's size, a million times the collision
    module's touching tolerance: the answers are those of :meth:`segplan.Scenario.is_free`
    (tested), only cheaper. A rectangular body (:attr:`segplan.Scenario.body`): a pose the
    round body fails is asked of the rectangle itself. ``calls`` counts the queries.

    Parameters
    ----------
    scenario : Scenario
    """

    def __init__(self, scenario: Scenario):
        if not isinstance(scenario, Scenario):
            raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
        r = scenario.robot
        self.L, self.body = r.L, {"rear": r.rear_overhang, "front": r.front_overhang}
        self._rectangle = scenario.body  # a rectangular body's exact test, or None
        self.bounds = scenario.free_bounds
        self.polygons = [as_polygon(p) for p in scenario.enlarged]
        extent = (
            self.L
            + r.rear_overhang
            + r.front_overhang
            + max(
                [abs(v) for v in (self.bounds or ())]
                + [float(np.abs(p.vertices).max()) for p in self.polygons]
                + [abs(scenario.start.x), abs(scenario.start.y), abs(scenario.goal.x), abs(scenario.goal.y)]
            )
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
        if self._round_free(x, y, theta):
            return True
        # the round body touches: a rectangular body is asked itself (Scenario.is_free's test)
        return self._rectangle is not None and self._rectangle.pose_conflict((x, y, theta)) is None

    def _round_free(self, x: float, y: float, theta: float) -> bool:
        L, body = self.L, self.body
        ax, ay, dx, dy, _ = axis_segment(x, y, theta, L, body["rear"], body["front"])
        bx, by = ax + dx, ay + dy
        lox, hix = (ax, bx) if ax <= bx else (bx, ax)
        loy, hiy = (ay, by) if ay <= by else (by, ay)
        pose = (x, y, theta)
        if self.bounds is not None:
            ix0, iy0, ix1, iy1 = self._inner
            if not (ix0 < lox and hix < ix1 and iy0 < loy and hiy < iy1):
                ox0, oy0, ox1, oy1 = self._outer
                if not (ox0 < lox and hix < ox1 and oy0 < loy and hiy < oy1):
                    return False
                if not pose_in_bounds(pose, L, self.bounds, **body):
                    return False
        for px0, py0, px1, py1, poly in self._boxes:
            if hix < px0 or lox > px1 or hiy < py0 or loy > py1:
                continue
            if pose_collides(pose, L, poly, check=False, **body):
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


def as_scenario(scenario) -> Scenario:
    """``scenario`` itself, or the scenario a shipped name (``"fig5_example1"``) or file path loads."""
    if isinstance(scenario, Scenario):
        return scenario
    if isinstance(scenario, str | Path):
        return load_scenario(scenario)
    raise ValueError(f"scenario must be a segplan.Scenario or a scenario name/path, got {scenario!r}")


def solve_ompl(
    scenario,
    planner: str,
    budget: float,
    seed: int,
    space: str = "dubins",
    resolution: float = RESOLUTION,
    step: float = STEP,
    simplify: float = SIMPLIFY_SECONDS,
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
        :class:`segplan.viz.metrics.PathMetrics` fields (NaN without an exact solution),
        ``valid`` (solved and passes the dense oracle) and ``poses`` (``(n, 3)`` list,
        one pose every :data:`PLOT_STEP` m, or None); ``load_before``, ``load_after``
        (1-minute load average around ``solve``); the same measures of the path after
        OMPL's ``PathSimplifier.simplify`` (at most ``simplify`` s, 0: not simplified):
        :data:`SIMPLIFIED_FIELDS`, ``simplify_seconds`` (its wall time) and
        ``simplified_poses``.
    """
    from ompl import base as ob
    from ompl import geometric as og
    from ompl import util as ou

    sc = as_scenario(scenario)
    seed = check_seed(seed)
    if planner not in PLANNERS:
        raise ValueError(f"planner must be one of {PLANNERS}, got {planner!r}")
    if space not in SPACES:
        raise ValueError(f"space must be one of {SPACES}, got {space!r}")
    if not (isinstance(budget, int | float) and math.isfinite(budget) and budget > 0):
        raise ValueError(f"budget must be a positive number of seconds, got {budget!r}")
    if not (isinstance(simplify, int | float) and math.isfinite(simplify) and simplify >= 0):
        raise ValueError(f"simplify must be a number of seconds >= 0, got {simplify!r}")
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
    objective = ob.PathLengthOptimizationObjective(si)
    ss.setOptimizationObjective(objective)
    ss.setPlanner(getattr(og, planner)(si))
    ss.setup()
    load_before = _load()
    t0, c0 = time.perf_counter(), time.process_time()
    status = ss.solve(float(budget))
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    load_after = _load()
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
        "load_before": load_before,
        "load_after": load_after,
    }
    raw = simplified = None
    simplify_seconds = math.nan
    if solved:
        path = ss.getSolutionPath()
        shorter = og.PathGeometric(path)  # a copy: the raw path is measured too
        if simplify > 0:
            simplifier = og.PathSimplifier(si, ss.getProblemDefinition().getGoal(), objective)
            t0 = time.perf_counter()
            simplifier.simplify(shorter, float(simplify))
            simplify_seconds = time.perf_counter() - t0
            simplified = shorter
        raw = path
    row.update(_measured(raw, sc, step))
    row["simplify_seconds"] = simplify_seconds
    row.update({f"simplified_{k}": v for k, v in _measured(simplified, sc, step).items()})
    return row


def _measured(path, sc: Scenario, step: float) -> dict:
    """``ompl_cost``, the metric fields, ``valid`` and ``poses`` of an OMPL path (None: NaN, no poses).

    The path is interpolated every ``step / 2`` m, measured by
    :func:`segplan.viz.metrics.measure_scenario_path` and checked by its dense oracle.
    """
    if path is None:
        out = {"ompl_cost": math.nan, **dict.fromkeys(METRIC_FIELDS, math.nan)}
        return {**out, "valid": False, "poses": None}
    length = float(path.length())
    path.interpolate(max(2, math.ceil(length / (0.5 * step)) + 1))
    P = se2_poses(path.getStates())
    metrics = measure_scenario_path(P, sc).as_dict()
    out = {"ompl_cost": length, **metrics, "valid": not metrics["collides"]}
    return {**out, "poses": thin_poses(P, length, PLOT_STEP).tolist()}


def _load() -> float:
    """The machine's 1-minute load average (NaN where the system has none)."""
    return os.getloadavg()[0] if hasattr(os, "getloadavg") else math.nan


def thin_poses(P: np.ndarray, length: float, step: float) -> np.ndarray:
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
    its stderr. A worker still running after :func:`worker_limit` seconds is killed: its
    row says ``status`` ``"overrun"``, not solved, with the wall time and the CPU time the
    process got (both counted from its start). A worker killed by a signal (OMPL crashed)
    gives ``status`` ``"crashed: ..."``, not solved, without times (NaN: nothing to judge;
    such a row is not kept by a study, so the run is tried again in its next session).
    """
    sc = as_scenario(scenario)
    job = {
        "scenario": sc.to_dict(),
        "planner": planner,
        "budget": budget,
        "seed": check_seed(seed),
        "space": space,
        **kw,
    }
    limit = worker_limit(budget)
    t0 = time.perf_counter()
    proc = subprocess.Popen(
        [sys.executable, "-m", __name__, "--worker"],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        stdout, stderr = proc.communicate(json.dumps(job), timeout=limit)
    except subprocess.TimeoutExpired:
        proc.kill()
        _, _, usage = os.wait4(proc.pid, 0)  # this child's own CPU time
        proc.returncode = -9
        for pipe in (proc.stdin, proc.stdout, proc.stderr):
            pipe.close()
        status = f"overrun: no answer in {limit:g} s (budget {float(budget):g} s), killed"
        cpu = usage.ru_utime + usage.ru_stime
        return _unsolved(sc, planner, space, budget, seed, status, time.perf_counter() - t0, cpu)
    proc = subprocess.CompletedProcess(proc.args, proc.returncode, stdout, stderr)
    if proc.returncode < 0:  # killed by a signal: OMPL crashed (seen: SIGSEGV on the Reeds-Shepp space)
        status = f"crashed: the OMPL worker died of signal {-proc.returncode}"
        return _unsolved(sc, planner, space, budget, seed, status, math.nan, math.nan)
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


def _unsolved(sc, planner, space, budget, seed, status: str, seconds: float, cpu: float) -> dict:
    """The row of a run that gave no answer (:func:`solve_ompl_isolated`)."""
    return {
        "scenario": sc.name,
        "method": planner,
        "space": space,
        "budget": float(budget),
        "seed": int(seed),
        "status": status,
        "solved": False,
        "valid": False,
        "seconds": seconds,
        "cpu_seconds": cpu,
        "messages": "",
    }


def _worker() -> None:
    job = json.loads(sys.stdin.read())
    sc = scenario_from_dict(job.pop("scenario"), source="<peers worker>")
    row = solve_ompl(sc, **job)
    sys.stdout.write(_MARK + json.dumps(row) + "\n")
    sys.stdout.flush()


# -- provenance -----------------------------------------------------------------------------
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


def provenance(argv: Sequence[str], config, jobs: int | None, rule: FairnessRule = FAIRNESS) -> dict:
    """How, when and where a study is measured: date (UTC), machine (CPU, cores, load),
    Python, numpy and OMPL versions, the commit (and whether the tree had changes), the
    command line, the configuration (a dataclass such as
    :class:`segplan.studies.peers.StudyConfig`, or ``None`` for a study that records its own,
    such as :mod:`segplan.studies.robustness`), the harness version, the fairness ``rule``
    every stored run passed (:class:`segplan.studies.executor.FairnessRule`) and how OMPL's
    paths were simplified."""
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
        "fairness": rule.provenance(),
        "simplifier": {
            "what": "ompl.geometric.PathSimplifier(si, goal, objective).simplify(path, max_time) on a copy "
            "of each exact solution; raw and simplified both measured (simplified_* columns)",
            "max_time_s": SIMPLIFY_SECONDS,
        },
        "config": None if config is None else asdict(config),
    }


# The worker of solve_ompl_isolated: python -m segplan.studies.ompl_runner --worker
if __name__ == "__main__":
    if sys.argv[1:] != ["--worker"]:
        sys.exit("this module is the OMPL worker; the command line is benchmarks/peers.py")
    _worker()
