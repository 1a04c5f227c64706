"""Robustness of segplan on random and hard floors, against OMPL's BIT* (beyond the paper).

The floors are :mod:`segplan.studies.floors` (:func:`floor_groups`): 200 random 20 x 12 m
floors of each heading kind (``any``, ``natural``), the hard cases, six 160 x 96 m floors
with 512 obstacles, and a size sweep (:func:`sweep_floors`). Both sides are measured by
:func:`segplan.viz.metrics.measure_scenario_path` (front-wheel length; the dense oracle).

**OMPL** (optional dependency; slow, run once and stored by :func:`run_ompl` in the three
files of :func:`ompl_files`, in the repository's ``benchmarks/results/``; not shipped with the
package, so every reader is given their place): BIT* on the Dubins space of
radius ``L / tan(max_steer)`` at 2 and 5 s, chapter 8's set-up, one process per run through
the one executor (:mod:`segplan.studies.executor`: one run per free core, a run starved of
CPU refused and run again, resumable); on ``turn_around`` also RRT* and Informed RRT*. It
is the feasibility oracle and, at 5 s, the length reference (:func:`reference`): like with
like, OMPL's paths after its own ``PathSimplifier`` for the default planner (which
refines), the raw paths for the paper's search as found.

**segplan** (:func:`solve_segplan`, computed when asked): :func:`segplan.plan_scenario` per
floor; :func:`compare` adds the ratio to OMPL's length, :func:`verdicts` judges each target
of the planner (:data:`TARGETS`, ours: met or not met) with :func:`segplan.studies.verdicts.meet`.

**Deterministic results, varying times.** The study bounds the default planner by
``max_expansions=`` :data:`MAX_EXPANSIONS` (the same on every machine) and passes
``time_limit=`` :data:`TIME_LIMIT`: the default planner gives the paper's search, and the
lattice after a paper plan, ``PAPER_SHARE`` of it, so no internal limit is below
4 x :data:`SLOW_SECONDS`. A floor that needs more than :data:`SLOW_SECONDS` is listed as slow
(:func:`slow_floors`) with the times, instead of a time-out changing a success count on a
slower machine.

``benchmarks/robustness.py`` is the command line; chapter 9 of the book uses this module.
"""

from __future__ import annotations

import contextlib
import datetime
import gzip
import json
import math
import os
import statistics
import time
from collections.abc import Callable, Iterable, Sequence
from functools import partial
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pandas as pd

from ..floor.scenario import Scenario
from ..planning.api import PAPER_SHARE, plan_scenario
from ..planning.plan import NoPathError
from ..viz.metrics import measure_scenario_path, plan_poses
from . import floors as fl
from . import ompl_runner as om
from . import peers
from .executor import FAIRNESS, FairnessRule, Journal, run_jobs
from .verdicts import Target, meet, targets_table

__all__ = [
    "segplan_provenance",
    "store_segplan",
    "BUDGETS",
    "MAX_EXPANSIONS",
    "OMPL_CSV_NAME",
    "OmplFiles",
    "ompl_files",
    "REFERENCE_BUDGET",
    "SLOW_SECONDS",
    "SUBSET_RANDOM",
    "TARGETS",
    "TIME_LIMIT",
    "compare",
    "floor_groups",
    "job_id",
    "loglog_slope",
    "ompl_record",
    "ompl_jobs",
    "read_ompl",
    "read_ompl_paths",
    "reference",
    "run_ompl",
    "run_segplan",
    "segplan_options",
    "session_lines",
    "slow_floors",
    "solve_segplan",
    "subset",
    "sweep_floors",
    "targets",
    "variant_label",
    "verdicts",
    "warm_up",
]

#: File name of the stored OMPL runs in the repository's ``benchmarks/results/`` (not in the
#: wheel); :func:`ompl_files` names the two files beside it.
OMPL_CSV_NAME = "robustness_ompl.csv"


class OmplFiles(NamedTuple):
    """The stored OMPL side: runs (CSV), paths at the reference budget, provenance."""

    csv: Path
    paths: Path
    provenance: Path


def ompl_files(csv: str | Path) -> OmplFiles:
    """The stored OMPL side of the runs in ``csv``: the paths beside it
    (``<stem>_paths.json.gz``) and the provenance (``<stem>.json``); for the repository's,
    ``ompl_files(root / "benchmarks" / "results" / OMPL_CSV_NAME)``."""
    csv = Path(csv)
    return OmplFiles(csv, csv.with_name(csv.stem + "_paths.json.gz"), csv.with_suffix(".json"))


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
#: Size sweep: scales s of the 20 x 12 m room (8 s^2 obstacles), counts on 160 x 96 m, crossings.
SWEEP_SCALES = (1.0, 2.0**0.5, 2.0, 2.0**1.5, 4.0, 2.0**2.5, 8.0)
SWEEP_COUNTS = (0, 32, 128, 512)
SWEEP_CROSSINGS = 2
#: Stored path poses: about one every PATH_STEP m, rounded to the millimetre.
PATH_STEP = 0.2
#: The book's subset (chapter 9): the first SUBSET_RANDOM random floors of each kind, every
#: hard case, the first large floor.
SUBSET_RANDOM = 40
#: The study's limits of segplan's default planner: expansions (the machine-independent
#: bound), a time limit whose smallest internal share PAPER_SHARE * TIME_LIMIT is
#: 4 x SLOW_SECONDS, and the time (s) above which a floor is "slow".
MAX_EXPANSIONS = 1000
SLOW_SECONDS = 3.0
TIME_LIMIT = 4.0 * SLOW_SECONDS / PAPER_SHARE

OMPL_COLUMNS = tuple(
    (
        "group floor floor_key generator planner budget seed status solved valid seconds "
        "cpu_seconds cpu_share attempts load_before load_after checks ompl_cost front_length "
        "rear_length max_curvature curvature_jumps reversals clearance simplify_seconds "
        "simplified_valid simplified_ompl_cost simplified_front_length simplified_rear_length "
        "simplified_max_curvature simplified_curvature_jumps simplified_clearance messages"
    ).split()
)
SEGPLAN_COLUMNS = tuple(
    (
        "group floor floor_key variant solved reason valid seconds plan_seconds "
        "cpu_seconds front_length plan_cost clearance nodes obstacles area"
    ).split()
)

#: Issue 12's targets, ours (not the paper's): each a :class:`~segplan.studies.verdicts.Target`,
#: met or not met, judged by :func:`verdicts` (``varies``: a time).
_SHARE = "share of the floors OMPL solves that segplan solves validly"
_RATIO = "front-wheel length over BIT*'s at 5 s after OMPL's PathSimplifier (random floors both solve)"
TARGETS = {
    "success, any headings": Target(f"{_SHARE}, any headings", ">=", 0.99, fmt="{:.1%}"),
    "success, natural headings": Target(f"{_SHARE}, natural headings", ">=", 0.99, fmt="{:.1%}"),
    "invalid plans": Target("plans the dense oracle rejects, every floor", "==", 0, fmt="{:.0f}"),
    "plan time, median": Target("median plan time, random floors [ms]", "<=", 50.0, varies=True),
    "plan time, 95th percentile": Target("95th pct. plan time, random floors [ms]", "<=", 300.0, varies=True),
    "front-wheel length / BIT* 5 s, median": Target(f"median {_RATIO}", "<=", 1.00, fmt="{:.3f}"),
    "front-wheel length / BIT* 5 s, worst": Target(f"largest {_RATIO}", "<=", 1.15, fmt="{:.3f}"),
    "turn_around / best OMPL at 5 s": Target(
        "front-wheel length on turn_around over the best simplified OMPL result at 5 s",
        "<=",
        1.05,
        fmt="{:.3f}",
    ),
    "160 x 96 m, 512 obstacles: plan time median": Target(
        "median plan time across 160 x 96 m, 512 obstacles [s]", "<=", 1.0, varies=True
    ),
    "enclosed goal: no plan": Target("plans returned for an enclosed goal", "==", 0, fmt="{:.0f}"),
    "enclosed goal: time": Target("slowest NoPathError for an enclosed goal [s]", "<=", 1.0, varies=True),
}


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


def subset(groups: dict[str, list[Scenario]], n_random: int = SUBSET_RANDOM, n_large: int = 1) -> list:
    """``(group, scenario)`` of the book's subset: the first ``n_random`` random floors of
    each kind, every hard case, the first ``n_large`` large floors."""
    for name, n in (("n_random", n_random), ("n_large", n_large)):
        if isinstance(n, bool) or not isinstance(n, int) or n < 0:
            raise ValueError(f"{name} must be an integer >= 0, got {n!r}")
    out = [(k, sc) for k in fl.KINDS for sc in groups.get(k, [])[:n_random]]
    out += [("hard", sc) for sc in groups.get("hard", [])]
    return out + [("large", sc) for sc in groups.get("large", [])[:n_large]]


def sweep_floors(crossings: int = SWEEP_CROSSINGS) -> list[Scenario]:
    """The size sweep: every scale at the small floors' density, then every obstacle count
    on the 160 x 96 m room; ``crossings`` crossings each."""
    if isinstance(crossings, bool) or not isinstance(crossings, int) or crossings < 1:
        raise ValueError(f"crossings must be an integer >= 1, got {crossings!r}")
    out = [fl.sweep_floor(s, None, i) for s in SWEEP_SCALES for i in range(crossings)]
    out += [fl.sweep_floor(8.0, n, i) for n in SWEEP_COUNTS for i in range(crossings)]
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
    return _run_id(sc.name, p, b, s)


def _run_id(floor: str, planner: str, budget: float, seed: int) -> str:
    return f"{floor}|{planner}|{float(budget):g}|{int(seed)}"


# -- OMPL side (stored) -------------------------------------------------------------------
def ompl_record(job: tuple, resolution: float = om.RESOLUTION, space: str = "dubins") -> dict:
    """One OMPL run in a fresh process (:func:`segplan.studies.ompl_runner.solve_ompl_isolated`)
    on ``space`` (``"dubins"``, or ``"reedsshepp"``: forward and reverse): its CSV row
    (:data:`OMPL_COLUMNS`) with ``poses`` and ``simplified_poses`` (about one every
    :data:`PATH_STEP` m, mm; or None) added. Module level, so that a Dask worker runs it."""
    group, sc, planner, budget, seed = job
    r = om.solve_ompl_isolated(sc, planner, budget, seed, space, resolution=resolution)
    row = {c: r.get(c, math.nan) for c in OMPL_COLUMNS}
    row.update(group=group, floor=sc.name, floor_key=fl.floor_key(sc), generator=fl.GENERATOR_VERSION)
    row.update(planner=planner, budget=float(budget), seed=int(seed))
    k = max(1, round(PATH_STEP / om.PLOT_STEP))
    for name in ("poses", "simplified_poses"):
        P = r.get(name)
        if P is not None:
            P = np.asarray(P)
            P = np.round(P[np.unique(np.r_[np.arange(0, len(P), k), len(P) - 1])], 3).tolist()
        row[name] = P
    return row


def read_ompl(path: str | Path) -> pd.DataFrame:
    """The stored OMPL runs (empty frame with :data:`OMPL_COLUMNS` if none); ``solved``,
    ``valid`` and ``simplified_valid`` as booleans. Columns a file written before harness
    version 3 lacks (CPU share, load, the simplified path) are NaN (``simplified_valid``
    False)."""
    if not Path(path).exists():
        return pd.DataFrame(columns=list(OMPL_COLUMNS))
    t = pd.read_csv(path, keep_default_na=False, na_values=[""])
    for c in OMPL_COLUMNS:
        if c not in t.columns:
            t[c] = False if c == "simplified_valid" else math.nan
    for c in ("solved", "valid", "simplified_valid"):
        t[c] = t[c].astype(bool)
    return t


def read_ompl_paths(path: str | Path) -> dict[str, np.ndarray]:
    """Stored OMPL paths at the reference budget, by :func:`job_id` (the simplified path of a
    run by its id with the planner ``"<planner> +simplify"``)."""
    out = {}
    if Path(path).exists():
        with gzip.open(path, "rt") as fh:
            for line in fh:
                if line.strip():
                    d = json.loads(line)
                    out[d["id"]] = np.asarray(d["poses"])
    return out


def _simplified_id(run_id: str) -> str:
    floor, planner, rest = run_id.split("|", 2)
    return f"{floor}|{peers.ompl_method(planner, True)}|{rest}"


def _path_id(run: pd.Series, simplified: bool) -> str:
    """The key of a stored run's path (raw or simplified) in :func:`read_ompl_paths`."""
    run_id = _run_id(run["floor"], run["planner"], run["budget"], run["seed"])
    return _simplified_id(run_id) if simplified else run_id


def _stored_records(out: Path, paths_out: Path, jobs: list[tuple], rule: FairnessRule) -> dict[str, dict]:
    """The runs already stored in ``out`` that the study can keep, as :func:`ompl_record`'s
    records by :func:`job_id`: measured on today's floor, by this harness (every column of
    :data:`OMPL_COLUMNS`) and accepted by ``rule``. Raises RuntimeError if a stored run was
    measured on another floor."""
    have = read_ompl(out)
    want = {job_id(j): fl.floor_key(j[1]) for j in jobs}
    runs = zip(have["floor"], have["planner"], have["budget"], have["seed"], strict=True)
    ids = [_run_id(*run) for run in runs]
    stale = [i for i, k in zip(ids, have["floor_key"], strict=True) if i in want and want[i] != k]
    if stale:
        raise RuntimeError(f"{len(stale)} stored runs were measured on other floors: delete {out} first")
    paths = read_ompl_paths(paths_out)
    keep = {}
    for i, (_, r) in zip(ids, have.iterrows(), strict=True):
        record = {c: r[c] for c in OMPL_COLUMNS}
        if i not in want or pd.isna(r["cpu_share"]) or rule.refuses(record):
            continue
        record = {k: (v.item() if isinstance(v, np.generic) else v) for k, v in record.items()}
        poses, simple = paths.get(i), paths.get(_simplified_id(i))
        record["poses"] = None if poses is None else poses.tolist()
        record["simplified_poses"] = None if simple is None else simple.tolist()
        keep[i] = record
    return keep


def run_ompl(
    jobs: list[tuple],
    out: str | Path,
    paths_out: str | Path,
    provenance: str | Path,
    workers: int | None = None,
    scheduler=None,
    rule: FairnessRule = FAIRNESS,
    argv: Sequence[str] = ("benchmarks/robustness.py", "--ompl"),
    about: dict | None = None,
    space: str = "dubins",
) -> pd.DataFrame:
    """Run the OMPL jobs not stored yet through the one executor; store every run; the whole table.

    :func:`segplan.studies.executor.run_jobs` runs at most one run per free core (at most
    ``workers``), or on a Dask cluster at ``scheduler``, and refuses and re-runs a run that
    got less CPU than ``rule`` asks. Runs already in ``out`` that this harness measured and
    ``rule`` accepts are kept; each new run is appended to a journal
    (``<out stem>.journal.jsonl``) as it finishes, so an interrupted study resumes. At the
    end ``out`` (one row per run, raw and simplified measures), ``paths_out`` (the paths,
    raw and simplified, at :data:`REFERENCE_BUDGET`) are rewritten and the journal removed;
    ``provenance`` gains a session (:func:`segplan.studies.ompl_runner.provenance` of
    ``argv``, with the fairness rule, the runs done, the refusals and the load during them)
    and drops the sessions of older harness versions, none of whose runs are kept. Each
    stored run carries its own CPU share, load and attempts.

    ``about`` describes another study's floors and runs in the provenance (its ``what``,
    ``generator_version``, ``budgets``, ``seeds``; default: this study's); its
    ``generator_version`` is then the ``generator`` column of every stored run
    (:mod:`segplan.studies.kind_study` runs its floors through here). ``space``: OMPL's
    state space, ``"dubins"`` (forward only) or ``"reedsshepp"`` (forward and reverse, the
    same radius: the reverse-gear study, :mod:`segplan.studies.reverse_floors`).
    """
    if space not in om.SPACES:
        raise ValueError(f"space must be one of {om.SPACES}, got {space!r}")
    out, paths_out, provenance = Path(out), Path(paths_out), Path(provenance)
    out.parent.mkdir(parents=True, exist_ok=True)
    journal = Journal(peers.journal_path(out))
    if not journal.path.exists():
        for k, record in _stored_records(out, paths_out, jobs, rule).items():
            journal.append(k, record)
    record = json.loads(provenance.read_text()) if provenance.exists() else {"sessions": []}
    session = om.provenance(list(argv), None, workers, rule)
    session["note"] = f"Fair runs: {rule.text()}."
    session["scheduler"] = None if scheduler is None else str(scheduler)
    record.update(
        what="OMPL BIT* (and RRT*, Informed RRT* on turn_around) on segplan.studies.floors, "
        "segplan.studies.robustness; raw paths and after OMPL's PathSimplifier (simplified_*)",
        generator_version=fl.GENERATOR_VERSION,
        budgets=list(BUDGETS),
        seeds=dict(
            random=[*RANDOM_SEEDS],
            large=[*RANDOM_SEEDS],
            hard=[*HARD_SEEDS],
            turn_around=[*TURN_AROUND_SEEDS],
        ),
        space=("Dubins" if space == "dubins" else "Reeds-Shepp")
        + ", radius L / tan(max_steer); validity segplan.studies.ompl_runner.SegmentValidity",
        motion_check_resolution_m=om.RESOLUTION,
        measured_by="segplan.viz.metrics.measure_scenario_path, samples every 1 cm",
    )
    record.update(about or {})
    before = set(journal.read())
    records = run_jobs(
        partial(ompl_record, resolution=om.RESOLUTION, space=space),
        jobs,
        key=job_id,
        journal=journal,
        rule=rule,
        cap=workers,
        scheduler=scheduler,
        desc="OMPL",
    )
    new = [r for k, r in records.items() if k not in before]
    loads = [x for r in new for x in (r["load_before"], r["load_after"]) if math.isfinite(x)]
    session.update(
        runs_done=len(new),
        runs_kept=len(records) - len(new),
        refused=sum(int(r["attempts"]) - 1 for r in new),
        finished=datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        load_average_end=list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
    )
    if loads:
        session["load_average_1min"] = {"min": min(loads), "mean": statistics.fmean(loads), "max": max(loads)}
    # the sessions whose runs can still be stored: this harness's (older runs were all run again)
    record["sessions"] = [s for s in record["sessions"] if s.get("harness_version") == om.HARNESS_VERSION]
    record["sessions"].append(session)
    generator = record["generator_version"]
    rows = [{**{c: r[c] for c in OMPL_COLUMNS}, "generator": generator} for r in records.values()]
    _replace(out, lambda tmp: pd.DataFrame(rows, columns=list(OMPL_COLUMNS)).to_csv(tmp, index=False))

    def write_paths(tmp: Path) -> None:
        with gzip.GzipFile(tmp, "wb", mtime=0) as fh:
            for k, r in records.items():
                if r["budget"] != REFERENCE_BUDGET:
                    continue
                for i, poses in ((k, r["poses"]), (_simplified_id(k), r["simplified_poses"])):
                    if poses is not None:
                        fh.write((json.dumps({"id": i, "poses": poses}) + "\n").encode())

    _replace(paths_out, write_paths)
    _replace(provenance, lambda tmp: tmp.write_text(json.dumps(record, indent=1) + "\n"))
    journal.path.unlink(missing_ok=True)
    return read_ompl(out)


def _replace(path: Path, write: Callable[[Path], None]) -> None:
    """Write ``path`` through a temporary file beside it (an interruption leaves the old file)."""
    tmp = path.with_name(path.name + ".tmp")
    write(tmp)
    tmp.replace(path)


def session_lines(record: dict) -> list[str]:
    """The stored provenance in words, a line per fact: per session when, where (CPU,
    cores), OMPL's version, the command and commit, the load, the note. Reads the sessions
    :func:`run_ompl` writes and the first session's own format (``started``, ``host``)."""
    lines = []
    for s in record.get("sessions", []):
        m = s["machine"]
        start = s.get("started", s.get("date", "?"))
        load = s.get("load_average_start") or m.get("load_average_before") or [math.nan]
        la = s.get("load_average_1min", {})
        lines.append(
            f"session {start} to {s.get('finished', '(unfinished)')}: {m['cpu']}, {m['cores']} cores, "
            f"OMPL {s['ompl']}"
        )
        lines.append(
            f"  command: {s['command']} (nice {s.get('nice', m.get('nice'))}), commit {s['commit'][:12]}"
        )
        lines.append(
            f"  load average at start {load[0]:.1f}; during the runs {la.get('min', math.nan):.1f} to "
            f"{la.get('max', math.nan):.1f} (mean {la.get('mean', math.nan):.1f})"
        )
        lines.append(f"  {s['note']}")
    lines.append(
        f"budgets {record['budgets']} s; seeds {record['seeds']}; floors of generator "
        f"v{record['generator_version']}"
    )
    return lines


# -- segplan side ---------------------------------------------------------------------------
def segplan_options(
    planner: str | None = None,
    refine: bool | None = None,
    time_limit: float | None = None,
    max_expansions: int | None = None,
) -> dict:
    """Keyword arguments of :func:`segplan.plan_scenario` for a variant of segplan: those
    given (``{}``: the default planner with its own limits). :func:`segplan.plan_scenario`
    checks them (ValueError naming the argument). The study passes :data:`TIME_LIMIT` and
    :data:`MAX_EXPANSIONS`."""
    given = {"planner": planner, "refine": refine, "time_limit": time_limit, "max_expansions": max_expansions}
    return {k: v for k, v in given.items() if v is not None}


def variant_label(options: dict) -> str:
    """A short name of a variant: ``"default"``, ``"planner=paper +refine"``, ... (the time
    limit is not part of the name)."""
    parts = [f"planner={options['planner']}"] if "planner" in options else []
    if "refine" in options:
        parts.append("+refine" if options["refine"] else "-refine")
    return " ".join(parts) or "default"


def warm_up(options: dict | None = None) -> float:
    """The process's one-time set-up of segplan (s), excluded from the times like OMPL's library
    load: :func:`segplan.studies.peers.warm_up` and plans with ``options`` on natural-0 (the paper's
    search) and any-6 (the lattice and its guide: their first use imports scipy's graphs)."""
    t0 = time.perf_counter()
    peers.warm_up()
    for kind, index in (("natural", 0), ("any", 6)):
        with contextlib.suppress(NoPathError):
            plan_scenario(fl.random_floor(kind, index), **(options or {}))
    return time.perf_counter() - t0


def solve_segplan(scenario: Scenario, group: str = "", options: dict | None = None, step: float = om.STEP):
    """segplan on one floor: its row (:data:`SEGPLAN_COLUMNS`) and the plan (or None).

    ``seconds`` is the wall time of the :func:`segplan.plan_scenario` call (search and,
    if the variant refines, refinement; the first plan on this floor in a warm process,
    see :func:`warm_up`); ``plan_seconds`` the planner's own ``Plan.seconds`` (or the
    ``NoPathError``'s); ``cpu_seconds`` the CPU time of the call. The plan is sampled every
    ``step`` m and measured by :func:`segplan.viz.metrics.measure_scenario_path`: ``valid`` is
    the dense oracle's verdict, ``front_length`` the measured front-wheel length
    (``plan_cost``: the plan's own LONGD).
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
        plan = plan_scenario(scenario, **options)
    except NoPathError as exc:
        row.update(solved=False, reason=exc.reason, valid=False, seconds=time.perf_counter() - t0)
        row.update(cpu_seconds=time.process_time() - c0, plan_seconds=exc.seconds, nodes=0)
        row.update(front_length=math.nan, plan_cost=math.nan, clearance=math.nan)
        return row, None
    seconds, cpu = time.perf_counter() - t0, time.process_time() - c0
    m = measure_scenario_path(plan_poses(plan, step), scenario)
    row.update(solved=True, reason="", valid=not m.collides, seconds=seconds, plan_seconds=plan.seconds)
    row.update(cpu_seconds=cpu, front_length=m.front_length, plan_cost=plan.cost, clearance=m.clearance)
    row["nodes"] = len(plan.nodes)
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


def segplan_provenance(argv: Sequence[str], **about) -> dict:
    """The provenance of a segplan side run in this process (when, where, the commit, the
    command: :func:`segplan.studies.ompl_runner.provenance` without the OMPL side's own keys),
    with ``about`` (what was run, on which floors) and how the plans were measured."""
    meta = om.provenance(list(argv), None, None)
    for key in ("fairness", "simplifier", "ompl", "jobs"):  # the OMPL side's own
        meta.pop(key)
    meta.update(about)
    meta["measured_by"] = "segplan.viz.metrics.measure_scenario_path (dense oracle), plan sampled every 1 cm"
    return meta


def store_segplan(seg: pd.DataFrame, meta: dict, csv: str | Path, wall_seconds: float) -> Path:
    """Write a segplan side's rows to ``csv`` and ``meta`` (:func:`segplan_provenance`),
    completed with the end time, the wall time, the load after and the calls' CPU share, to
    the JSON file beside it; returns that file."""
    share = seg["cpu_seconds"] / seg["seconds"]
    meta.update(
        finished=pd.Timestamp.now(tz="UTC").isoformat(timespec="seconds"),
        wall_seconds=wall_seconds,
        load_average_after=list(os.getloadavg()) if hasattr(os, "getloadavg") else None,
        cpu_share={"min": float(share.min()), "median": float(share.median()), "max": float(share.max())},
        note="Plan times are wall times in a warm process; a CPU share below 0.9 means a loaded machine.",
    )
    csv = Path(csv)
    csv.parent.mkdir(parents=True, exist_ok=True)
    seg.to_csv(csv, index=False)
    out = csv.with_suffix(".json")
    out.write_text(json.dumps(meta, indent=1) + "\n", encoding="utf-8")
    return out


def slow_floors(table: pd.DataFrame, limit: float = SLOW_SECONDS) -> pd.DataFrame:
    """The rows whose call took more than ``limit`` seconds (wall time): the floors a
    machine slower by ``TIME_LIMIT * PAPER_SHARE / limit`` could see time out."""
    return table[table["seconds"] > limit]


# -- comparison and targets -------------------------------------------------------------------
def reference(ompl: pd.DataFrame, simplified: bool = True) -> pd.DataFrame:
    """Per floor, from the stored OMPL runs: ``ompl_runs``, ``ompl_solved`` (some run found
    a valid path, raw or simplified: the feasibility oracle), ``ompl_front`` (the shortest
    valid front-wheel length at :data:`REFERENCE_BUDGET`, over planners and seeds),
    ``ompl_planner`` and ``ompl_id`` (the key of its path in :func:`read_ompl_paths`).

    Like with like: ``simplified=True`` (for a planner that refines its plans, the default
    planner) takes OMPL's paths after its ``PathSimplifier`` (the ``simplified_*`` columns;
    ``ompl_planner`` then ends in ``" +simplify"``), ``simplified=False`` (the paper's search
    as found) the raw paths (also for runs stored before harness version 3, which have no
    simplified path). ``ompl_raw_front`` and ``ompl_simplified_front`` are both given.
    """
    cols = ["floor", "ompl_key", "ompl_runs", "ompl_solved", "ompl_front", "ompl_planner", "ompl_id"]
    cols += ["ompl_raw_front", "ompl_simplified_front"]
    if ompl.empty:
        return pd.DataFrame(columns=cols)
    t = ompl.copy()
    t["valid"] = t["valid"].astype(bool)
    if "simplified_valid" not in t.columns:
        t["simplified_valid"], t["simplified_front_length"] = False, math.nan
    t["simplified_valid"] = t["simplified_valid"].astype(bool) & t["solved"].astype(bool)
    if not t["simplified_valid"].any():  # stored before OMPL's paths were simplified (harness 2)
        simplified = False
    rows = []
    for name, runs in t.groupby("floor", sort=False):
        ref = runs[runs["budget"] == REFERENCE_BUDGET]
        best = {}
        for label, ok, front in (
            ("raw", ref["valid"], "front_length"),
            ("simplified", ref["simplified_valid"], "simplified_front_length"),
        ):
            r = ref[ok]
            best[label] = r.loc[r[front].idxmin()] if len(r) else None
            best[label + "_front"] = math.nan if best[label] is None else float(best[label][front])
        side = "simplified" if simplified else "raw"
        b = best[side]
        rows.append(
            {
                "floor": name,
                "ompl_key": runs["floor_key"].iloc[0],
                "ompl_runs": len(runs),
                "ompl_solved": bool((runs["valid"] | runs["simplified_valid"]).any()),
                "ompl_front": best[side + "_front"],
                "ompl_planner": "" if b is None else peers.ompl_method(str(b["planner"]), simplified),
                "ompl_id": "" if b is None else _path_id(b, simplified),
                "ompl_raw_front": best["raw_front"],
                "ompl_simplified_front": best["simplified_front"],
            }
        )
    return pd.DataFrame(rows, columns=cols)


def compare(seg: pd.DataFrame, ompl: pd.DataFrame, simplified: bool = True) -> pd.DataFrame:
    """segplan's rows with the OMPL reference of their floor and ``ratio`` (segplan's
    front-wheel length over :func:`reference`'s ``ompl_front``, OMPL's paths simplified or
    raw as ``simplified`` says; NaN unless both have a valid path). Raises ValueError if a
    floor's stored OMPL runs were made on another floor (``floor_key``)."""
    out = seg.merge(reference(ompl, simplified), on="floor", how="left")
    stale = out["ompl_key"].notna() & (out["ompl_key"] != out["floor_key"])
    if stale.any():
        raise ValueError(f"ompl: stored runs of {list(out.loc[stale, 'floor'])} were made on other floors")
    out["ompl_solved"] = out["ompl_solved"].astype(object).fillna(False).astype(bool)
    out["solved"] = out["solved"].astype(bool)
    out["valid"] = out["valid"].astype(bool)
    ok = out["solved"] & out["valid"]
    out["ratio"] = np.where(ok, out["front_length"] / out["ompl_front"], math.nan)
    return out


def verdicts(table: pd.DataFrame) -> pd.DataFrame:
    """Each target of the planner (:data:`TARGETS`) judged on :func:`compare`'s table:
    ``target``, ``criterion`` (its text), ``measured``, ``value``, ``verdict`` ("met" or
    "not met", :func:`segplan.studies.verdicts.meet`), ``judged`` (the
    :class:`~segplan.studies.verdicts.Verdict`) and ``timed`` (the value is a time, so the
    verdict may vary from run to run). Nothing measured (e.g. no OMPL result) is "not met",
    with the reason in ``measured``."""
    nan = math.nan
    rows = []  # (target, value, measured)
    random = table[table["group"].isin(fl.KINDS)]
    good = table["solved"] & table["valid"]
    for kind in fl.KINDS:
        t = table[(table["group"] == kind) & table["ompl_solved"]]
        n, rate = int(good[t.index].sum()), good[t.index].mean() if len(t) else nan
        text = f"{n} of {len(t)} ({100 * rate:.1f} %)" if len(t) else "no OMPL results"
        rows.append((f"success, {kind} headings", rate, text))
    bad = int((table["solved"] & ~table["valid"]).sum())
    rows.append(("invalid plans", float(bad), f"{bad} of {int(table['solved'].sum())} plans"))
    for label, q in (("median", 0.5), ("95th percentile", 0.95)):
        v, c = (1e3 * random[k].quantile(q) if len(random) else nan for k in ("seconds", "cpu_seconds"))
        rows.append((f"plan time, {label}", v, f"{v:.1f} ms (wall; CPU {c:.1f} ms)"))
    r = random["ratio"].dropna()
    for label, v in (("median", r.median()), ("worst", r.max())):
        v = float(v) if len(r) else nan
        rows.append((f"front-wheel length / BIT* 5 s, {label}", v, f"{v:.3f} ({len(r)} floors both solve)"))
    ta = table.loc[table["floor"] == "turn_around", "ratio"]
    v = float(ta.iloc[0]) if len(ta) else nan
    rows.append(("turn_around / best OMPL at 5 s", v, f"{v:.3f}" if v == v else "no plan or no OMPL result"))
    large = table[table["group"] == "large"]
    v = float(large["seconds"].median()) if len(large) else nan
    text = f"{v:.2f} s ({int(good[large.index].sum())} of {len(large)} crossings solved)"
    rows.append(("160 x 96 m, 512 obstacles: plan time median", v, text))
    enc = table[table["floor"].str.startswith("enclosed")]
    n = int(enc["solved"].sum())
    rows.append(
        ("enclosed goal: no plan", float(n) if len(enc) else nan, f"{n} of {len(enc)} returned a plan")
    )
    v = float(enc["seconds"].max()) if len(enc) else nan
    rows.append(("enclosed goal: time", v, f"slowest {v:.2f} s"))
    out = pd.DataFrame(rows, columns=["target", "value", "measured"])
    out["criterion"] = [TARGETS[t].text() for t in out["target"]]
    out["judged"] = [meet(v, TARGETS[t]) for t, v in zip(out["target"], out["value"], strict=True)]
    out["verdict"] = [v.word for v in out["judged"]]
    out["timed"] = [TARGETS[t].varies for t in out["target"]]
    return out[["target", "criterion", "measured", "value", "verdict", "judged", "timed"]]


def targets(verdict: pd.DataFrame, why: dict[str, str] | None = None) -> pd.DataFrame:
    """The chapter's table of our targets (:func:`segplan.studies.verdicts.targets_table`: met
    or not met, apart from the paper's claims), a row per target of :func:`verdicts`, with
    ``why`` by target."""
    why = dict(why or {})
    return targets_table(
        {
            "target": v["target"],
            "ours": v["measured"],
            "verdict": v["judged"],
            "why": why.get(v["target"], ""),
        }
        for _, v in verdict.iterrows()
    )


def loglog_slope(x: Sequence[float], y: Sequence[float]) -> float:
    """Least-squares slope of ``log y`` against ``log x`` (the exponent of a power law)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    ok = (x > 0) & (y > 0) & np.isfinite(x) & np.isfinite(y)
    if ok.sum() < 2:
        return math.nan
    return float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])
