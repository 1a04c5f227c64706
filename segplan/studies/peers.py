"""segplan against modern sampling-based planners on the same floors (beyond the paper).

On each shipped scenario, OMPL's asymptotically optimal planners RRT*, Informed RRT* and
BIT* plan for the same robot at fixed time budgets and several seeds, and segplan plans
with each of its heuristics. Every path, ours and theirs, is measured by the one shared
function :func:`segplan.viz.metrics.measure_path` (front-wheel length, the paper's cost; rear
length; curvature; clearance; the dense shapely collision oracle).

OMPL's side is :mod:`segplan.studies.ompl_runner`: how the peers' problem is made as equal
as OMPL allows (state space, validity, motion validity, objective, seeds) and OMPL's sharp
edges met. This module is the study the book's chapter 8 draws:

- **OMPL's runs**: on the Dubins space, RRT*, Informed RRT* and BIT* at wall-clock budgets
  (:data:`BUDGETS`) of 0.1, 1 and 5 s, seeds (:data:`SEEDS`) 1..5; on the Reeds-Shepp
  space (a reference only: it reverses), BIT* at 1 and 5 s (:func:`full_config`).
- **segplan**: :func:`segplan.plan_scenario` with heuristics a, b, c (default options),
  each as the paper's search finds it and refined by :func:`segplan.refine` (beyond the
  paper: shortcuts, splits and local moves of the nodes; ``+refine`` in ``method``);
  time: the median wall time of :data:`SEGPLAN_REPEATS` plans in one process, after the
  process's one-time set-up (:func:`warm_up`: the stored fitted constants loaded, the
  interpreter's caches warmed), measured and reported apart, like OMPL's library load.

Goal: on each scenario segplan's front-wheel length at most that of the best
OMPL result at 5 s, found in under 1/50 of that time (0.1 s). Like is compared with like:
:func:`goal_table` judges segplan refined against OMPL's paths after OMPL's own
``PathSimplifier`` (:func:`simplified_rows`, methods ``"BITstar +simplify"``), and, with
``refine=False``, the paper's search alone against OMPL's raw paths.

Fair runs
---------
Every OMPL run goes through :func:`segplan.studies.executor.run_jobs` (:func:`run_ompl`): one
run per free core, each run's CPU share and load recorded, a run of 0.5 s or more that got
less than 0.9 of a core refused and run again, every accepted run appended to a journal
(``<out>.journal.jsonl``) so that an interrupted study resumes.

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
    python benchmarks/peers.py --scheduler tcp://host:8786   # the OMPL runs on a Dask cluster
"""

from __future__ import annotations

import gzip
import json
import math
import statistics
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from ..floor import scenario as world
from ..floor.scenario import Robot, Scenario, load_scenario, make_scenario
from ..planning.api import plan_scenario
from ..planning.plan import NoPathError
from ..viz.metrics import measure_scenario_path, plan_poses
from .executor import FAIRNESS, FairnessRule, Journal, run_jobs
from .ompl_runner import (
    METRIC_FIELDS,
    PLANNERS,
    PLOT_STEP,
    RESOLUTION,
    SIMPLIFIED_FIELDS,
    SIMPLIFY_SECONDS,
    STEP,
    as_scenario,
    check_seed,
    solve_ompl_isolated,
    thin_poses,
)
from .progress import progress

__all__ = [
    "BUDGETS",
    "HEURISTICS",
    "SEEDS",
    "SIMPLIFIED",
    "Runs",
    "StudyConfig",
    "best_paths",
    "budget_table",
    "full_config",
    "goal_table",
    "journal_path",
    "load",
    "missing_runs",
    "ompl_method",
    "quick_config",
    "read_ompl_results",
    "run_ompl",
    "run_segplan",
    "segplan_method",
    "shipped_scenarios",
    "simplified_rows",
    "solve_segplan",
    "summary_table",
    "warm_up",
    "write_ompl_results",
]

HEURISTICS = ("a", "b", "c")
BUDGETS = (0.1, 1.0, 5.0)
SEEDS = (1, 2, 3, 4, 5)
#: Plans timed per scenario and heuristic (the median is reported).
SEGPLAN_REPEATS = 5
#: The goal's time ratio: segplan within 1/50 of OMPL's budget.
TIME_RATIO = 50.0
#: The ``method`` suffix of OMPL's paths after its ``PathSimplifier`` (``"BITstar +simplify"``).
SIMPLIFIED = " +simplify"


def load(name: str | Path) -> Scenario:
    """A shipped scenario by name (``"fig5_example1"``) or any scenario file path."""
    return load_scenario(name)


# -- segplan -------------------------------------------------------------------------------
def warm_up() -> float:
    """The process's one-time set-up of segplan (seconds): one plan on a small floor.

    The first plan in a process loads the stored fitted constants (:mod:`segplan.model.constants`)
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


def ompl_method(planner: str, simplified: bool = False) -> str:
    """The ``method`` label of OMPL's rows: ``"BITstar"`` (raw), ``"BITstar +simplify"``."""
    return planner + (SIMPLIFIED if simplified else "")


def solve_segplan(
    scenario, heuristic: str = "a", repeats: int = SEGPLAN_REPEATS, step: float = STEP, refine: bool = False
) -> dict:
    """segplan on a scenario: a row like those of :func:`segplan.studies.ompl_runner.solve_ompl`
    (``method``: :func:`segplan_method`).

    ``refine=True`` plans with :func:`segplan.refine` after the search (beyond the
    paper; ``seconds`` counts both).

    ``seconds`` is the median wall time (``Plan.seconds``) of ``repeats`` plans (the plan
    itself is deterministic) after one untimed plan; call :func:`warm_up` once per
    process first. ``plan_cost`` is Plan.cost, the exact LONGD [1], which
    the measured ``front_length`` must match. A NoPathError gives ``solved=False`` and
    ``status`` its reason.
    """
    sc = as_scenario(scenario)
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
        row.update(checks=0, ompl_cost=math.nan, **dict.fromkeys(METRIC_FIELDS, math.nan))
        row.update(valid=False, poses=None, plan_cost=math.nan, nodes=0, messages="")
        return row
    P = plan_poses(plan, step)
    m = measure_scenario_path(P, sc)
    row.update(status="exact", solved=True, seconds=statistics.median(times), checks=plan.collision_checks)
    row.update(ompl_cost=math.nan, **m.as_dict())
    row.update(valid=not m.collides, poses=thin_poses(P, m.rear_length, PLOT_STEP).tolist())
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
    simplify: float = SIMPLIFY_SECONDS

    def jobs(self) -> list:
        """Every OMPL run ``(scenario, planner, budget, seed, space)``, each once."""
        return list(dict.fromkeys(j for block in self.blocks for j in block.jobs()))


def shipped_scenarios() -> tuple[str, ...]:
    """The study's floors: the shipped scenarios whose obstacles are all convex and whose robot
    is the segment A->B widened by half_width, as in the paper.

    A floor with a non-convex obstacle (``l_shaped_rack``, split into convex pieces by
    :mod:`segplan.floor.decompose`, beyond the paper) or a robot with a body beyond the
    segment (``forklift_aisle``: overhangs, a rectangle) is not part of the comparison with
    the peers, whose stored runs (``benchmarks/results/peers_ompl.csv``) cover exactly these.
    """
    out = []
    for name in world.shipped_scenarios():
        sc = load_scenario(name)
        r = sc.robot
        if len(sc.outlines) == len(sc.obstacles) and r.axis == (0.0, r.L) and not r.rectangle:
            out.append(name)
    return tuple(out)


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
    with progress(total=len(todo), desc="segplan") as bar:
        for name, h, refine in todo:
            row = solve_segplan(load(name), h, config.segplan_repeats, config.step, refine)
            del row["poses"]
            rows.append(row)
            bar.update()
    return pd.DataFrame(rows)


def _ompl_job(job: tuple) -> dict:
    """One OMPL run of a study (module level, so that a Dask worker can run it):
    ``job = (scenario, planner, budget, seed, space, resolution, step, simplify)``."""
    s, p, b, seed, space, resolution, step, simplify = job
    kw = {"resolution": resolution, "step": step, "simplify": simplify}
    return solve_ompl_isolated(load(s), p, b, seed, space, **kw)


def journal_path(csv_path: str | Path) -> Path:
    """Where :func:`run_ompl` keeps the accepted runs of a study stored at ``csv_path`` while it
    runs (``<stem>.journal.jsonl`` beside it): an interrupted study resumes from it."""
    csv_path = Path(csv_path)
    return csv_path.with_name(csv_path.stem + ".journal.jsonl")


def run_ompl(
    config: StudyConfig,
    jobs: int | None = None,
    journal: str | Path | None = None,
    scheduler=None,
    rule: FairnessRule = FAIRNESS,
) -> tuple[pd.DataFrame, dict]:
    """Every OMPL run of ``config``, each in a fresh process, through the one executor.

    :func:`segplan.studies.executor.run_jobs` runs at most one run per free core (at most
    ``jobs``; each planner is single-threaded), or on a Dask cluster at ``scheduler``;
    refuses and re-runs a run that got less CPU than ``rule`` asks; appends each accepted
    run to ``journal`` (if given), from which a re-run resumes. A progress bar shows on a
    terminal only.

    Returns
    -------
    table : pandas.DataFrame
        One row per run (:func:`segplan.studies.ompl_runner.solve_ompl`'s fields, ``messages``, ``cpu_share``,
        ``attempts``), without the poses; the simplified path's measures in the
        ``simplified_*`` columns (:func:`simplified_rows` turns them into rows).
    paths : dict
        ``(scenario, method, space, budget, seed) -> (n, 3)`` poses (one every
        :data:`PLOT_STEP` m) of every solved run; the simplified path under the method
        :func:`ompl_method` ``(planner, True)``.
    """
    todo = [(*j, config.resolution, config.step, config.simplify) for j in config.jobs()]
    records = run_jobs(
        _ompl_job,
        todo,
        key=lambda j: "|".join(map(str, j[:5])),
        journal=None if journal is None else Journal(journal),
        rule=rule,
        cap=jobs,
        scheduler=scheduler,
        desc="OMPL",
    )
    rows, paths = [], {}
    for r in records.values():
        r = dict(r)
        poses, simple = r.pop("poses"), r.pop("simplified_poses", None)
        key = (r["scenario"], r["method"], r["space"], r["budget"], r["seed"])
        if poses is not None:
            paths[key] = np.asarray(poses)
        if simple is not None:
            paths[(key[0], ompl_method(key[1], True), *key[2:])] = np.asarray(simple)
        rows.append(r)
    return pd.DataFrame(rows), paths


def simplified_rows(table: pd.DataFrame) -> pd.DataFrame:
    """OMPL's runs after its ``PathSimplifier``, as rows of their own.

    Each OMPL row of ``table`` (``space`` not ``"segplan"``, with the ``simplified_*``
    columns) becomes a row whose ``method`` is :func:`ompl_method` ``(planner, True)``,
    whose measures and ``valid`` are the simplified path's, and whose ``seconds`` add the
    simplification's time to the budget's. Empty when ``table`` has no simplified measures
    (results stored before harness version 3).
    """
    t = table[(table["space"] != "segplan") & ~table["method"].str.endswith(SIMPLIFIED)]
    if "simplified_valid" not in t.columns or t.empty:
        return t.iloc[0:0].copy()
    out = t.copy()
    for f in SIMPLIFIED_FIELDS:
        out[f.removeprefix("simplified_")] = out[f]
    out["valid"] = out["solved"].astype(bool) & out["valid"].astype(bool)
    out["method"] = out["method"] + SIMPLIFIED
    out["seconds"] = out["seconds"] + out["simplify_seconds"].fillna(0.0)
    return out.drop(columns=[*SIMPLIFIED_FIELDS])


def missing_runs(table: pd.DataFrame, config: StudyConfig) -> list[tuple]:
    """The runs of ``config`` (``(scenario, planner, budget, seed, space)``) that ``table`` lacks."""
    have = {
        (r.scenario, r.method, float(r.budget), int(r.seed), r.space)
        for r in table[["scenario", "method", "budget", "seed", "space"]].itertuples(index=False)
    }
    return [j for j in config.jobs() if j not in have]


# -- stored results ---------------------------------------------------------------------------
def _meta_path(csv_path: Path) -> Path:
    return csv_path.with_suffix(".json")


def _paths_path(csv_path: Path) -> Path:
    return csv_path.with_name(csv_path.stem + "_paths.json.gz")


def best_paths(table: pd.DataFrame, paths: dict) -> dict:
    """The poses of the shortest valid run (front-wheel length) per scenario, space, planner
    and budget, raw and simplified (:func:`simplified_rows`): what the figures draw, out of
    every run's poses."""
    table = pd.concat([table, simplified_rows(table)], ignore_index=True)
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

    Like with like: segplan refined against OMPL's paths after its ``PathSimplifier``
    (:func:`simplified_rows`; ``ompl_planner`` ends in :data:`SIMPLIFIED`), segplan as found
    (``refine=False``) against OMPL's raw paths. Results stored before OMPL's paths were
    simplified (harness 2) have raw paths only: then both are judged against those.

    Columns: ``segplan_front``, ``segplan_ms``, ``ompl_best_front``, ``ompl_planner``,
    ``ompl_runs`` (valid runs at that budget), ``length_ratio`` (segplan / OMPL),
    ``time_ratio`` (budget / segplan time), ``shorter``, ``fast`` (time ratio >= 50),
    ``goal_met``. Scenarios without OMPL runs at ``budget`` are left out.
    """
    rows = []
    ours = table[table["method"] == segplan_method(heuristic, refine)].set_index("scenario")
    peers = table[(table["space"] == "dubins") & (table["budget"] == budget)]
    peers = peers[~peers["method"].str.endswith(SIMPLIFIED)]
    if refine and "simplified_valid" in peers.columns:  # results of harness 3 and later
        peers = simplified_rows(peers)
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
    """Per scenario: each segplan variant and, per budget, the best valid Dubins run, raw and
    simplified (front length, ms)."""
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
        d = simplified_rows(t[t["space"] == "dubins"])
        for b, tb in d[d["valid"]].groupby("budget"):
            row[f"OMPL {b:g} s simplified front"] = tb["front_length"].min()
        rows.append(row)
    return pd.DataFrame(rows)
