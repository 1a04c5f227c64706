"""Robustness of segplan on random and hard floors, against OMPL's BIT* (issue 12, item 5).

The floors are :mod:`segplan.studies.floors`: 200 random 20 x 12 m floors of each heading
kind (``any``, ``natural``), the hard cases (a start facing a wall, doors and corridors,
enclosed goals, ``turn_around``), six 160 x 96 m floors with 512 obstacles (one crossing each),
and a size sweep. Two sides, measured by the same yardstick
(:func:`segplan.metrics.measure_scenario_path`: front-wheel length, the paper's cost, and
validity by the dense shapely oracle):

**OMPL** (optional dependency ``ompl``; slow, run once and stored): BIT* on the Dubins
space of radius ``R = L / tan(max_steer)`` with segplan's own pose test as validity, at 2
and 5 s, one fresh process per run (:func:`peers.solve_ompl_isolated`, whose set-up is
chapter 8's). It is the feasibility oracle (a floor counts if BIT* solves it) and the
length reference (BIT* at 5 s). On ``turn_around`` RRT* and Informed RRT* also run at 5 s
(the target there is the best OMPL result). :func:`ompl_jobs` lists every run
(floor x planner x budget x seed); :func:`run_ompl` writes them, as they finish, to
``benchmarks/results/robustness_ompl.csv`` (resumable: runs already stored for the same
floor are skipped), the paths at 5 s to ``robustness_ompl_paths.json.gz``, and a
provenance record ``robustness_ompl.json`` (date, machine, cores, load, OMPL version,
commit, command line, budgets, seeds).

**segplan** (computed at run time, deterministic but for the times): per floor
:func:`segplan.plan_scenario` with the default planner, or with ``planner=...`` where that
argument exists (:func:`solve_segplan`): solved, valid, time (``Plan.seconds``, or the
``NoPathError``'s), front-wheel length; :func:`compare` adds the ratio to BIT* at 5 s and
:func:`verdicts` judges each target of issue 12.

Usage::

    python benchmarks/robustness.py --ompl --jobs 2        # the stored OMPL side (about 40 min)
    python benchmarks/robustness.py --out segplan.csv      # segplan on every floor, targets
    python benchmarks/robustness.py --quick                # smoke run (a few floors; OMPL 0.1 s if present)
"""

from __future__ import annotations

import argparse
import datetime
import gzip
import inspect
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import ThreadPoolExecutor, as_completed
from pathlib import Path

import numpy as np
import pandas as pd

import segplan
from segplan.metrics import measure_scenario_path, plan_poses
from segplan.studies import floors as fl
from segplan.studies import peers
from segplan.world import Scenario

ROOT = Path(__file__).resolve().parents[1]

RESULTS = ROOT / "benchmarks" / "results"
OMPL_CSV = RESULTS / "robustness_ompl.csv"
OMPL_PATHS = RESULTS / "robustness_ompl_paths.json.gz"
OMPL_PROVENANCE = RESULTS / "robustness_ompl.json"

#: BIT*'s budgets (s): the feasibility oracle and the length reference (the largest).
BUDGETS = (2.0, 5.0)
REFERENCE_BUDGET = 5.0
#: OMPL seeds: one per random floor and large crossing, three per hard case.
RANDOM_SEEDS = (1,)
HARD_SEEDS = (1, 2, 3)
#: On turn_around the target is the best OMPL result at 5 s: all three planners, five seeds.
TURN_AROUND_PLANNERS = ("RRTstar", "InformedRRTstar", "BITstar")
TURN_AROUND_SEEDS = (1, 2, 3, 4, 5)
#: 160 x 96 m floors with 512 obstacles, one crossing each.
N_LARGE = 6
#: The size sweep: scales s of the 20 x 12 m room (obstacles 8 s^2), obstacle counts on the
#: 160 x 96 m room, and crossings per point.
SWEEP_SCALES = (1.0, 2.0**0.5, 2.0, 2.0**1.5, 4.0, 2.0**2.5, 8.0)
SWEEP_COUNTS = (0, 32, 128, 512)
SWEEP_CROSSINGS = 2
#: Stored path poses: about one every PATH_STEP m, rounded to the millimetre.
PATH_STEP = 0.2
OMPL_COLUMNS = (
    "group",
    "floor",
    "floor_key",
    "generator",
    "planner",
    "budget",
    "seed",
    "status",
    "solved",
    "valid",
    "seconds",
    "cpu_seconds",
    "checks",
    "ompl_cost",
    "front_length",
    "rear_length",
    "max_curvature",
    "curvature_jumps",
    "reversals",
    "clearance",
    "messages",
)

#: Issue 12's targets.
TARGET_SUCCESS = 0.99
TARGET_MEDIAN_MS = 50.0
TARGET_P95_MS = 300.0
TARGET_RATIO_MEDIAN = 1.00
TARGET_RATIO_WORST = 1.15
TARGET_TURN_AROUND = 1.05
TARGET_LARGE_S = 1.0
TARGET_ENCLOSED_S = 1.0


# -- the floors ---------------------------------------------------------------------------
def floor_groups(quick: bool = False) -> dict[str, list[Scenario]]:
    """The study's floors by group: ``any``, ``natural`` (random), ``hard``, ``large``.

    ``quick``: three random floors of each kind, every hard case but none large.
    """
    n = 3 if quick else fl.N_FLOORS
    groups = {kind: [fl.random_floor(kind, i) for i in range(n)] for kind in fl.KINDS}
    groups["hard"] = list(fl.hard_cases().values())
    groups["large"] = [] if quick else [fl.large_floor(i) for i in range(N_LARGE)]
    return groups


def sweep_floors() -> list[Scenario]:
    """The size sweep: every scale at the small floors' density, then every obstacle count
    on the 160 x 96 m room; :data:`SWEEP_CROSSINGS` crossings each."""
    out = [fl.sweep_floor(s, None, i) for s in SWEEP_SCALES for i in range(SWEEP_CROSSINGS)]
    out += [fl.sweep_floor(8.0, n, i) for n in SWEEP_COUNTS for i in range(SWEEP_CROSSINGS)]
    return list({sc.name: sc for sc in out}.values())


def ompl_jobs(groups: dict[str, list[Scenario]], budgets: Sequence[float] = BUDGETS) -> list[tuple]:
    """Every OMPL run the study defines: ``(group, scenario, planner, budget, seed)``.

    BIT* at each budget on every floor (seeds :data:`RANDOM_SEEDS` on random and large
    floors, :data:`HARD_SEEDS` on hard cases); on ``turn_around`` also
    :data:`TURN_AROUND_PLANNERS` x :data:`TURN_AROUND_SEEDS` at the largest budget.
    Ordered so that a partial run covers every group: hard and large floors first, then
    the random floors of both kinds alternately.
    """
    jobs = []
    for group in ("hard", "large"):
        for sc in groups.get(group, ()):
            seeds = HARD_SEEDS if group == "hard" else RANDOM_SEEDS
            jobs += [(group, sc, "BITstar", float(b), s) for b in budgets for s in seeds]
            if sc.name == "turn_around":
                for p in TURN_AROUND_PLANNERS:
                    jobs += [(group, sc, p, float(max(budgets)), s) for s in TURN_AROUND_SEEDS]
    random = [groups.get(k, []) for k in fl.KINDS]
    for i in range(max(map(len, random), default=0)):
        for kind, scs in zip(fl.KINDS, random, strict=True):
            if i < len(scs):
                jobs += [(kind, scs[i], "BITstar", float(b), s) for b in budgets for s in RANDOM_SEEDS]
    return list({(g, sc.name, p, b, s): (g, sc, p, b, s) for g, sc, p, b, s in jobs}.values())


def job_id(job: tuple) -> str:
    """``"floor|planner|budget|seed"``: a run's key in the stored files."""
    _, sc, p, b, s = job
    return f"{sc.name}|{p}|{b:g}|{s}"


# -- OMPL side ----------------------------------------------------------------------------
def _git_commit() -> str:
    try:
        out = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"], capture_output=True, text=True)
        dirty = subprocess.run(
            ["git", "-C", str(ROOT), "status", "--porcelain"], capture_output=True, text=True
        )
    except OSError:
        return "unknown"
    return out.stdout.strip() + (" (uncommitted changes)" if dirty.stdout.strip() else "")


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def machine() -> dict:
    """Where a measurement runs: host, CPU model, cores, OS, Python."""
    return {
        "host": platform.node(),
        "cpu": _cpu_model(),
        "cores": os.cpu_count(),
        "os": platform.platform(),
        "python": platform.python_version(),
    }


def ompl_row(job: tuple, resolution: float = peers.RESOLUTION) -> tuple[dict, list | None]:
    """One OMPL run in a fresh process (:func:`peers.solve_ompl_isolated`): its CSV row and
    its path (poses about every :data:`PATH_STEP` m, or None)."""
    group, sc, planner, budget, seed = job
    r = peers.solve_ompl_isolated(sc, planner, budget, seed, "dubins", resolution=resolution)
    row = {c: r.get(c, math.nan) for c in OMPL_COLUMNS}
    row.update(group=group, floor=sc.name, floor_key=fl.floor_key(sc), generator=fl.GENERATOR_VERSION)
    row.update(planner=planner, budget=float(budget), seed=int(seed))
    poses = r.get("poses")
    if poses is not None:
        P = np.asarray(poses)
        k = max(1, round(PATH_STEP / peers.PLOT_STEP))
        P = P[np.unique(np.r_[np.arange(0, len(P), k), len(P) - 1])]
        poses = np.round(P, 3).tolist()
    return row, poses


def read_ompl(path: Path = OMPL_CSV) -> pd.DataFrame:
    """The stored OMPL runs (empty frame with :data:`OMPL_COLUMNS` if none)."""
    if not Path(path).exists():
        return pd.DataFrame(columns=list(OMPL_COLUMNS))
    return pd.read_csv(path, keep_default_na=False, na_values=[""])


def read_ompl_paths(path: Path = OMPL_PATHS) -> dict[str, np.ndarray]:
    """Stored OMPL paths at the reference budget, by :func:`job_id`."""
    out = {}
    if Path(path).exists():
        with gzip.open(path, "rt") as fh:
            for line in fh:
                if line.strip():
                    d = json.loads(line)
                    out[d["id"]] = np.asarray(d["poses"])
    return out


def run_ompl(
    jobs: list[tuple],
    out: Path = OMPL_CSV,
    paths_out: Path = OMPL_PATHS,
    provenance: Path = OMPL_PROVENANCE,
    workers: int = 2,
    progress: Callable[[str], None] | None = None,
    command: str = "",
) -> pd.DataFrame:
    """Run the OMPL jobs not stored yet, ``workers`` processes at a time; append each row
    to ``out`` as it finishes, the paths at the reference budget to ``paths_out``, and
    keep ``provenance`` up to date. Returns the whole stored table."""
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers must be an integer >= 1, got {workers!r}")
    out, paths_out, provenance = Path(out), Path(paths_out), Path(provenance)
    out.parent.mkdir(parents=True, exist_ok=True)
    have = read_ompl(out)
    done = {
        f"{f}|{p}|{b:g}|{s}": k
        for f, p, b, s, k in zip(
            have["floor"], have["planner"], have["budget"], have["seed"], have["floor_key"], strict=True
        )
    }
    todo = [j for j in jobs if done.get(job_id(j)) != fl.floor_key(j[1])]
    stale = [j for j in jobs if job_id(j) in done and done[job_id(j)] != fl.floor_key(j[1])]
    if stale:
        raise RuntimeError(f"{len(stale)} stored runs were measured on other floors: delete {out} first")
    record = json.loads(provenance.read_text()) if provenance.exists() else {"sessions": []}
    session = {
        "started": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "machine": machine(),
        "load_average_start": list(os.getloadavg()),
        "nice": os.nice(0),
        "workers": workers,
        "command": command or " ".join([sys.executable, *sys.argv]),
        "commit": _git_commit(),
        "ompl": peers.ompl_version(),
        "runs_to_do": len(todo),
        "note": (
            "Measured on a shared 2-core machine while other work (other helpers' tests and "
            "notebooks) ran on it: budgets are wall-clock, so BIT* got less CPU than its budget "
            "in some runs (cpu_seconds / seconds < 1)."
        ),
    }
    record.update(
        {
            "what": "OMPL BIT* (and RRT*, Informed RRT* on turn_around) on segplan.studies.floors, "
            "benchmarks/robustness.py",
            "generator_version": fl.GENERATOR_VERSION,
            "budgets": list(BUDGETS),
            "seeds": {
                "random": list(RANDOM_SEEDS),
                "large": list(RANDOM_SEEDS),
                "hard": list(HARD_SEEDS),
                "turn_around": list(TURN_AROUND_SEEDS),
            },
            "space": "Dubins, radius L / tan(max_steer); validity benchmarks.peers.SegmentValidity",
            "motion_check_resolution_m": peers.RESOLUTION,
            "measured_by": "segplan.metrics.measure_scenario_path, samples every 1 cm",
        }
    )
    record["sessions"].append(session)

    def save_record():
        tmp = provenance.with_suffix(".tmp")
        tmp.write_text(json.dumps(record, indent=1) + "\n")
        tmp.replace(provenance)

    save_record()
    header = not out.exists() or out.stat().st_size == 0
    loads = []
    with ThreadPoolExecutor(max_workers=workers) as pool:
        futures = {pool.submit(ompl_row, j): j for j in todo}
        for n, fut in enumerate(as_completed(futures), 1):
            job = futures[fut]
            row, poses = fut.result()
            pd.DataFrame([row], columns=list(OMPL_COLUMNS)).to_csv(out, mode="a", header=header, index=False)
            header = False
            if poses is not None and job[3] == REFERENCE_BUDGET:
                with gzip.open(paths_out, "at") as fh:
                    fh.write(json.dumps({"id": job_id(job), "poses": poses}) + "\n")
            loads.append(os.getloadavg()[0])
            if progress:
                progress(
                    f"[{n}/{len(todo)}] {job_id(job)} solved={row['solved']} front={row['front_length']:.3f}"
                )
            if n % 20 == 0 or n == len(todo):
                session.update(
                    runs_done=n,
                    load_average_1min={"min": min(loads), "mean": statistics.fmean(loads), "max": max(loads)},
                )
                save_record()
    session["finished"] = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    session["load_average_end"] = list(os.getloadavg())
    save_record()
    return read_ompl(out)


# -- segplan side ---------------------------------------------------------------------------
def segplan_options(planner: str | None = None, refine: bool | None = None) -> dict:
    """Keyword arguments of :func:`segplan.plan_scenario` for a variant of segplan.

    ``planner`` is passed only if given, and only where :func:`segplan.plan_scenario`
    has that argument (ValueError otherwise); ``refine`` only if given. ``{}`` is the
    default planner, whatever it is.
    """
    params = inspect.signature(segplan.plan_scenario).parameters
    kw: dict = {}
    if planner is not None:
        if "planner" not in params:
            raise ValueError(f"planner={planner!r}: this segplan's plan_scenario has no planner argument")
        kw["planner"] = planner
    if refine is not None:
        if not isinstance(refine, bool):
            raise ValueError(f"refine must be True, False or None, got {refine!r}")
        kw["refine"] = refine
    return kw


def variant_label(options: dict) -> str:
    """A short name of a variant: ``"default"``, ``"planner=paper +refine"``, ..."""
    if not options:
        return "default"
    parts = [f"planner={options['planner']}"] if "planner" in options else []
    if "refine" in options:
        parts.append("+refine" if options["refine"] else "-refine")
    return " ".join(parts)


def warm_up(options: dict | None = None) -> float:
    """The process's one-time set-up of segplan (s), excluded from the times like OMPL's
    library load: one plan on a small floor (:func:`peers.warm_up`) and one with ``options``."""
    t0 = time.perf_counter()
    for call in (
        peers.warm_up,
        lambda: segplan.plan_scenario(fl.random_floor("natural", 0), **(options or {})),
    ):
        try:
            call()
        except segplan.NoPathError:  # a planner whose set-up counts against its time limit
            pass
    return time.perf_counter() - t0


SEGPLAN_COLUMNS = (
    "group",
    "floor",
    "floor_key",
    "variant",
    "solved",
    "reason",
    "valid",
    "seconds",
    "plan_seconds",
    "cpu_seconds",
    "front_length",
    "plan_cost",
    "clearance",
    "nodes",
    "obstacles",
    "area",
)


def solve_segplan(scenario: Scenario, group: str = "", options: dict | None = None, step: float = peers.STEP):
    """segplan on one floor: its row (:data:`SEGPLAN_COLUMNS`) and the plan (or None).

    ``seconds`` is the wall time of the :func:`segplan.plan_scenario` call (search and,
    if the variant refines, refinement; the first plan on this floor in a warm process,
    see :func:`warm_up`); ``plan_seconds`` the planner's own ``Plan.seconds`` (or the
    ``NoPathError``'s); ``cpu_seconds`` the CPU time of the call (on a busy machine the
    wall time exceeds it by the time other processes had the core). The plan is sampled
    every ``step`` m and measured by
    :func:`segplan.metrics.measure_scenario_path`: ``valid`` is the dense oracle's
    verdict, ``front_length`` the measured front-wheel length (``plan_cost``: the plan's
    own LONGD).
    """
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    options = dict(options or {})
    xmin, ymin, xmax, ymax = scenario.bounds
    row = {
        "group": group,
        "floor": scenario.name,
        "floor_key": fl.floor_key(scenario),
        "variant": variant_label(options),
        "obstacles": len(scenario.obstacles),
        "area": (xmax - xmin) * (ymax - ymin),
    }
    t0, c0 = time.perf_counter(), time.process_time()
    try:
        plan = segplan.plan_scenario(scenario, **options)
    except segplan.NoPathError as exc:
        row.update(solved=False, reason=exc.reason, valid=False, seconds=time.perf_counter() - t0)
        row["cpu_seconds"] = time.process_time() - c0
        row.update(
            plan_seconds=exc.seconds, front_length=math.nan, plan_cost=math.nan, clearance=math.nan, nodes=0
        )
        return row, None
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    m = measure_scenario_path(plan_poses(plan, step), scenario)
    row.update(solved=True, reason="", valid=not m.collides, seconds=seconds, plan_seconds=plan.seconds)
    row["cpu_seconds"] = cpu
    row.update(front_length=m.front_length, plan_cost=plan.cost, clearance=m.clearance, nodes=len(plan.nodes))
    return row, plan


def run_segplan(
    scenarios: Iterable[tuple[str, Scenario]],
    options: dict | None = None,
    progress: Callable[[str], None] | None = None,
) -> tuple[pd.DataFrame, dict]:
    """:func:`solve_segplan` on every ``(group, scenario)``: the table and the plans by floor name."""
    rows, plans = [], {}
    for group, sc in scenarios:
        row, plan = solve_segplan(sc, group, options)
        rows.append(row)
        plans[sc.name] = plan
        if progress:
            progress(
                f"{group} {sc.name}: solved={row['solved']} valid={row['valid']} {row['reason']} "
                f"front={row['front_length']:.3f} {1e3 * row['seconds']:.1f} ms "
                f"(CPU {1e3 * row['cpu_seconds']:.1f} ms)"
            )
    return pd.DataFrame(rows, columns=list(SEGPLAN_COLUMNS)), plans


# -- comparison and targets -------------------------------------------------------------------
def reference(ompl: pd.DataFrame) -> pd.DataFrame:
    """Per floor, from the stored OMPL runs: ``ompl_runs``, ``ompl_solved`` (some run found
    a valid path: the feasibility oracle), ``ompl_front`` (the shortest valid front-wheel
    length at :data:`REFERENCE_BUDGET`, over planners and seeds), ``ompl_planner``, and
    ``bit2_solved`` / ``bit5_solved`` (runs of BIT* at 2 / 5 s that found a valid path)."""
    if ompl.empty:
        return pd.DataFrame(columns=["floor", "ompl_runs", "ompl_solved", "ompl_front", "ompl_planner"])
    t = ompl.copy()
    t["valid"] = t["valid"].astype(bool)
    rows = []
    for name, runs in t.groupby("floor", sort=False):
        ok = runs[runs["valid"]]
        ref = ok[ok["budget"] == REFERENCE_BUDGET]
        best = ref.loc[ref["front_length"].idxmin()] if len(ref) else None
        bit = ok[ok["planner"] == "BITstar"]
        rows.append(
            {
                "floor": name,
                "ompl_key": runs["floor_key"].iloc[0],
                "ompl_runs": len(runs),
                "ompl_solved": bool(len(ok)),
                "ompl_front": math.nan if best is None else float(best["front_length"]),
                "ompl_planner": "" if best is None else str(best["planner"]),
                "bit2_solved": int((bit["budget"] == 2.0).sum()),
                "bit5_solved": int((bit["budget"] == 5.0).sum()),
            }
        )
    return pd.DataFrame(rows)


def compare(seg: pd.DataFrame, ompl: pd.DataFrame) -> pd.DataFrame:
    """segplan's rows with the OMPL reference of their floor and ``ratio`` (segplan's
    front-wheel length over :func:`reference`'s ``ompl_front``; NaN unless both have a
    valid path). Raises ValueError if a floor's stored OMPL runs were made on another floor
    (``floor_key``)."""
    out = seg.merge(reference(ompl), on="floor", how="left")
    stale = out["ompl_key"].notna() & (out["ompl_key"] != out["floor_key"])
    if stale.any():
        raise ValueError(f"ompl: stored runs of {list(out.loc[stale, 'floor'])} were made on other floors")
    out["ompl_solved"] = out["ompl_solved"].fillna(False).astype(bool)
    ok = out["solved"].astype(bool) & out["valid"].astype(bool)
    out["ratio"] = np.where(ok, out["front_length"] / out["ompl_front"], math.nan)
    return out


def _verdict(value: float, limit: float, at_most: bool = True) -> str:
    if not math.isfinite(value):
        return "not measured"
    return "met" if (value <= limit if at_most else value >= limit) else "missed"


def verdicts(table: pd.DataFrame) -> pd.DataFrame:
    """Each target of issue 12 from :func:`compare`'s table: ``target``, ``criterion``,
    ``measured``, ``value``, ``verdict`` (met / missed / not measured, from the value and
    the criterion) and ``timed`` (the value is a time, so it varies from run to run)."""
    rows = []
    random = table[table["group"].isin(fl.KINDS)]
    good = table["solved"].astype(bool) & table["valid"].astype(bool)
    for kind in fl.KINDS:
        t = table[(table["group"] == kind) & table["ompl_solved"]]
        n_ok = int(good[t.index].sum())
        rate = n_ok / len(t) if len(t) else math.nan
        rows.append(
            {
                "target": f"success, {kind} headings",
                "criterion": f">= {100 * TARGET_SUCCESS:g} % of the floors OMPL solves",
                "measured": f"{n_ok} of {len(t)} ({100 * rate:.1f} %)" if len(t) else "no OMPL results",
                "value": rate,
                "verdict": _verdict(rate, TARGET_SUCCESS, at_most=False),
            }
        )
    solved = table[table["solved"].astype(bool)]
    bad = int((~solved["valid"].astype(bool)).sum())
    rows.append(
        {
            "target": "invalid plans",
            "criterion": "0 (dense oracle, every floor)",
            "measured": f"{bad} of {len(solved)} plans",
            "value": float(bad),
            "verdict": _verdict(bad, 0),
        }
    )
    ms = 1e3 * random["seconds"]
    for label, q, limit in (("median", 0.5, TARGET_MEDIAN_MS), ("95th percentile", 0.95, TARGET_P95_MS)):
        v = float(ms.quantile(q)) if len(ms) else math.nan
        rows.append(
            {
                "target": f"plan time, {label}",
                "criterion": f"<= {limit:g} ms (random floors, every call)",
                "measured": f"{v:.1f} ms",
                "value": v,
                "verdict": _verdict(v, limit),
            }
        )
    r = random["ratio"].dropna()
    for label, v, limit in (
        ("median", float(r.median()) if len(r) else math.nan, TARGET_RATIO_MEDIAN),
        ("worst", float(r.max()) if len(r) else math.nan, TARGET_RATIO_WORST),
    ):
        rows.append(
            {
                "target": f"front-wheel length / BIT* 5 s, {label}",
                "criterion": f"<= {limit:.2f} (random floors both solve: {len(r)})",
                "measured": f"{v:.3f}",
                "value": v,
                "verdict": _verdict(v, limit),
            }
        )
    ta = table[table["floor"] == "turn_around"]
    v = float(ta["ratio"].iloc[0]) if len(ta) else math.nan
    rows.append(
        {
            "target": "turn_around / best OMPL at 5 s",
            "criterion": f"<= {TARGET_TURN_AROUND:.2f}",
            "measured": f"{v:.3f}" if math.isfinite(v) else "no plan or no OMPL result",
            "value": v,
            "verdict": _verdict(v, TARGET_TURN_AROUND),
        }
    )
    large = table[table["group"] == "large"]
    v = float(large["seconds"].median()) if len(large) else math.nan
    n_ok = int(good[large.index].sum())
    rows.append(
        {
            "target": "160 x 96 m, 512 obstacles: plan time median",
            "criterion": f"<= {TARGET_LARGE_S:g} s",
            "measured": f"{v:.2f} s ({n_ok} of {len(large)} crossings solved)",
            "value": v,
            "verdict": _verdict(v, TARGET_LARGE_S),
        }
    )
    enc = table[table["floor"].str.startswith("enclosed")]
    v = float(enc["seconds"].max()) if len(enc) else math.nan
    wrong = int(enc["solved"].astype(bool).sum())
    rows.append(
        {
            "target": "enclosed goal: NoPathError",
            "criterion": f"no plan, within {TARGET_ENCLOSED_S:g} s",
            "measured": f"slowest {v:.2f} s; {wrong} of {len(enc)} returned a plan",
            "value": v,
            "verdict": "missed" if wrong else _verdict(v, TARGET_ENCLOSED_S),
        }
    )
    out = pd.DataFrame(rows)
    out["timed"] = out["target"].str.contains("time") | out["target"].str.startswith("enclosed")
    return out


def loglog_slope(x: Sequence[float], y: Sequence[float]) -> float:
    """Least-squares slope of ``log y`` against ``log x`` (the exponent of a power law)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    ok = (x > 0) & (y > 0) & np.isfinite(x) & np.isfinite(y)
    if ok.sum() < 2:
        return math.nan
    return float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])


# -- command line -------------------------------------------------------------------------
def main(argv: Sequence[str] | None = None) -> int:
    """``python benchmarks/robustness.py [--ompl] [--quick] [--out CSV] [...]``."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ompl", action="store_true", help="run the OMPL side (the runs not stored yet)")
    ap.add_argument("--jobs", type=int, default=2, help="OMPL processes at a time (default 2)")
    ap.add_argument("--ompl-csv", type=Path, default=OMPL_CSV, help="the stored OMPL runs")
    ap.add_argument(
        "--quick",
        action="store_true",
        help="smoke run: a few floors (OMPL: 0.1 s budget, to a temporary CSV)",
    )
    ap.add_argument("--out", type=Path, help="write segplan's rows (CSV)")
    ap.add_argument("--planner", help="segplan planner (plan_scenario's planner=..., where it exists)")
    ap.add_argument("--refine", action="store_true", help="refine segplan's plans (segplan.refine)")
    ap.add_argument("--no-segplan", action="store_true", help="skip segplan's side")
    args = ap.parse_args(argv)
    groups = floor_groups(args.quick)
    say = lambda s: print(s, file=sys.stderr, flush=True)  # noqa: E731
    if args.ompl or args.quick:
        if not peers.ompl_available():
            say("OMPL is not installed (pip install 'segplan[peers]'): skipping the OMPL side")
        elif args.quick:
            import tempfile

            tmp = Path(tempfile.mkdtemp())
            jobs = ompl_jobs({"any": groups["any"][:1], "hard": groups["hard"][:1]}, budgets=(0.1,))
            t = run_ompl(jobs, tmp / "o.csv", tmp / "p.json.gz", tmp / "o.json", workers=args.jobs)
            say(f"OMPL quick: {int(t['solved'].sum())} of {len(t)} solved")
        else:
            run_ompl(ompl_jobs(groups), args.ompl_csv, workers=args.jobs, progress=say)
    if args.no_segplan:
        return 0
    options = segplan_options(args.planner, True if args.refine else None)
    say(f"segplan {variant_label(options)}: one-time set-up {warm_up(options):.2f} s")
    floors = [(g, sc) for g, scs in groups.items() for sc in scs]
    if not args.quick:
        floors += [("sweep", sc) for sc in sweep_floors()]
    seg, _ = run_segplan(floors, options, progress=say)
    table = compare(seg, read_ompl(args.ompl_csv))
    with pd.option_context("display.width", 200, "display.max_columns", 20, "display.precision", 3):
        print(table.groupby("group")[["solved", "valid", "ompl_solved"]].sum().to_string())
        print(verdicts(table)[["target", "criterion", "measured", "verdict"]].to_string(index=False))
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        table.to_csv(args.out, index=False)
        say(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
