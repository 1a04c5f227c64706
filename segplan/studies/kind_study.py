"""The floor kinds study (issue 25; beyond the paper): segplan on the floors robots drive,
OMPL's BIT* as the oracle.

The floors are :mod:`segplan.studies.floor_kinds`: :data:`~segplan.studies.floor_kinds.N_PER_KIND`
floors of each kind (warehouse, rooms, parking, clutter, other robots, large sites;
:func:`kind_groups`). Both sides are measured as chapter 9's robustness study measures
them, by its own functions (:mod:`segplan.studies.robustness`):

**OMPL** (optional dependency; slow, run once on a quiet machine and stored by
:func:`run_ompl` in the files of :func:`segplan.studies.robustness.ompl_files` for the CSV
:data:`OMPL_CSV_NAME` in the repository's ``benchmarks/results/``): BIT* on the Dubins
space of radius ``L / tan(max_steer)``, :data:`BUDGET` = 5 s, seed 1, one fresh process per
run through :func:`segplan.studies.robustness.run_ompl` and so through the one executor
(:mod:`segplan.studies.executor`: one run per free core, a run given less than 0.9 of a
core refused and run again, resumable). It is the feasibility oracle and the length
reference: like with like, BIT*'s path after OMPL's ``PathSimplifier``, since the default
planner refines (:func:`segplan.studies.robustness.reference`).

**segplan** (:func:`segplan.studies.robustness.run_segplan`): the default planner with the
robustness study's limits (``max_expansions=MAX_EXPANSIONS``, ``time_limit=TIME_LIMIT``), in
a warm process, each plan checked by the dense oracle
(:func:`segplan.viz.metrics.measure_scenario_path`).

:func:`summary` tells per kind how many floors OMPL and segplan solve, how many plans are
invalid, the front-wheel length over BIT*'s (median, worst) and the plan times (median,
90th percentile, largest); :func:`worst_floors` names the floors chapter 9 draws.
``benchmarks/floor_kinds.py`` is the command line.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from ..floor.scenario import Scenario
from . import floor_kinds as fk
from . import robustness as rb

__all__ = [
    "BUDGET",
    "OMPL_CSV_NAME",
    "SEED",
    "SEGPLAN_CSV_NAME",
    "SUMMARY_COLUMNS",
    "kind_groups",
    "ompl_about",
    "ompl_jobs",
    "read_segplan",
    "run_ompl",
    "summary",
    "worst_floors",
]

#: File names of the stored runs in the repository's ``benchmarks/results/``.
OMPL_CSV_NAME = "floor_kinds_ompl.csv"
SEGPLAN_CSV_NAME = "floor_kinds_segplan.csv"
#: BIT*'s budget (s), the robustness study's length reference, and its seed.
BUDGET = rb.REFERENCE_BUDGET
SEED = 1
#: :func:`summary`'s columns.
SUMMARY_COLUMNS = (
    "kind",
    "floors",
    "ompl_runs",
    "ompl_solved",
    "segplan_solved",
    "solved_of_ompl",
    "segplan_only",
    "invalid",
    "no_plan",
    "ratio_floors",
    "ratio_median",
    "ratio_worst",
    "time_median_ms",
    "time_p90_ms",
    "time_p95_ms",
    "time_max_ms",
    "cpu_median_ms",
)


def _check_kinds(kinds: Sequence[str]) -> tuple[str, ...]:
    kinds = tuple(kinds)
    bad = [k for k in kinds if k not in fk.FLOOR_KINDS]
    if bad or not kinds:
        raise ValueError(f"kinds must be some of {fk.FLOOR_KINDS}, got {list(kinds)!r}")
    return kinds


def kind_groups(n: int = fk.N_PER_KIND, kinds: Sequence[str] = fk.FLOOR_KINDS) -> dict[str, list[Scenario]]:
    """The study's floors by kind: the first ``n`` of each of ``kinds``."""
    return {k: fk.kind_floors(k, n) for k in _check_kinds(kinds)}


def ompl_jobs(groups: dict[str, list[Scenario]], budget: float = BUDGET) -> list[tuple]:
    """Every OMPL run of the study, ``(kind, scenario, "BITstar", budget, SEED)``, the kinds
    taken in turn (floor 0 of each kind, then floor 1, ...), so that a partial run covers
    every kind."""
    if not (isinstance(budget, int | float) and math.isfinite(budget) and budget > 0):
        raise ValueError(f"budget must be a positive number of seconds, got {budget!r}")
    jobs = []
    for i in range(max(map(len, groups.values()), default=0)):
        for kind, floors in groups.items():
            if i < len(floors):
                jobs.append((kind, floors[i], "BITstar", float(budget), SEED))
    return jobs


def ompl_about(budget: float = BUDGET) -> dict:
    """What the stored OMPL side of this study is, for its provenance
    (:func:`segplan.studies.robustness.run_ompl`'s ``about``)."""
    return {
        "what": "OMPL BIT* on segplan.studies.floor_kinds (segplan.studies.kind_study); raw paths and "
        "after OMPL's PathSimplifier (simplified_*)",
        "generator": "segplan.studies.floor_kinds",
        "generator_version": fk.GENERATOR_VERSION,
        "budgets": [float(budget)],
        "seeds": {"every floor": [SEED]},
    }


def run_ompl(
    groups: dict[str, list[Scenario]],
    csv: str | Path,
    workers: int | None = None,
    scheduler=None,
    argv: Sequence[str] = ("benchmarks/floor_kinds.py", "--ompl"),
    budget: float = BUDGET,
) -> pd.DataFrame:
    """The OMPL side: :func:`ompl_jobs` through :func:`segplan.studies.robustness.run_ompl`
    (fair, resumable, stored in ``csv`` and the two files beside it,
    :func:`segplan.studies.robustness.ompl_files`); the whole stored table."""
    files = rb.ompl_files(csv)
    return rb.run_ompl(
        ompl_jobs(groups, budget),
        *files,
        workers=workers,
        scheduler=scheduler,
        argv=argv,
        about=ompl_about(budget),
    )


def read_segplan(path: str | Path) -> pd.DataFrame:
    """Stored segplan rows (:data:`segplan.studies.robustness.SEGPLAN_COLUMNS`), ``solved``
    and ``valid`` as booleans, ``reason`` as text."""
    t = pd.read_csv(path, keep_default_na=False, na_values=[""], dtype={"reason": str})
    for c in ("solved", "valid"):
        t[c] = t[c].astype(bool)
    t["reason"] = t["reason"].fillna("").astype(str)
    return t


def _numeric(table: pd.DataFrame) -> pd.DataFrame:
    """``table`` with ``ratio`` and ``ompl_runs`` as numbers (without OMPL results
    :func:`segplan.studies.robustness.compare` leaves them as objects) and the flags as booleans."""
    t = table.copy()
    for c in ("ratio", "ompl_runs"):
        t[c] = pd.to_numeric(t[c], errors="coerce")
    for c in ("solved", "valid", "ompl_solved"):
        t[c] = t[c].astype(bool)
    return t


def _ms(values: pd.Series, q: float) -> float:
    return 1e3 * float(values.quantile(q)) if len(values) else math.nan


def summary(table: pd.DataFrame) -> pd.DataFrame:
    """Per kind (``group``) of :func:`segplan.studies.robustness.compare`'s table:

    ``floors``; ``ompl_runs`` (floors with a stored OMPL run) and ``ompl_solved`` (a valid
    path, raw or simplified: the feasibility oracle); ``segplan_solved`` (a plan the dense
    oracle accepts), ``solved_of_ompl`` (of the floors OMPL solves) and ``segplan_only`` (on
    floors OMPL did not solve); ``invalid`` (plans the dense oracle rejects); ``no_plan``
    (``NoPathError``s by reason, e.g. ``"no path: 3, time limit: 1"``); the front-wheel
    length over BIT*'s at 5 s after its simplifier on floors both solve: ``ratio_floors``,
    ``ratio_median``, ``ratio_worst``; the plan's wall time ``time_median_ms``,
    ``time_p90_ms`` (the issue's table), ``time_p95_ms`` (its target), ``time_max_ms``
    (every floor) and its CPU time ``cpu_median_ms``.
    """
    rows = []
    for kind, t in _numeric(table).groupby("group", sort=False):
        good = t["solved"] & t["valid"]
        ompl = t["ompl_solved"]
        reasons = t.loc[~t["solved"], "reason"].value_counts()
        r = t["ratio"].dropna()
        rows.append(
            {
                "kind": kind,
                "floors": len(t),
                "ompl_runs": int(t["ompl_runs"].gt(0).sum()),
                "ompl_solved": int(ompl.sum()),
                "segplan_solved": int(good.sum()),
                "solved_of_ompl": int((good & ompl).sum()),
                "segplan_only": int((good & ~ompl & t["ompl_runs"].gt(0)).sum()),
                "invalid": int((t["solved"] & ~t["valid"]).sum()),
                "no_plan": ", ".join(f"{k}: {v}" for k, v in reasons.items()),
                "ratio_floors": len(r),
                "ratio_median": float(r.median()) if len(r) else math.nan,
                "ratio_worst": float(r.max()) if len(r) else math.nan,
                "time_median_ms": _ms(t["seconds"], 0.5),
                "time_p90_ms": _ms(t["seconds"], 0.9),
                "time_p95_ms": _ms(t["seconds"], 0.95),
                "time_max_ms": _ms(t["seconds"], 1.0),
                "cpu_median_ms": _ms(t["cpu_seconds"], 0.5),
            }
        )
    return pd.DataFrame(rows, columns=list(SUMMARY_COLUMNS))


def worst_floors(table: pd.DataFrame, per_kind: int = 2) -> pd.DataFrame:
    """The floors to draw: per kind, every floor OMPL solves and segplan does not, every
    invalid plan, every floor without a plan that OMPL did not solve either (or did not
    run), then the ``per_kind`` largest length ratios and the ``per_kind`` slowest plans;
    columns ``group``, ``floor``, ``why`` and the row's ``solved``, ``valid``, ``reason``,
    ``ratio``, ``seconds``. A floor is listed once, for its first reason."""
    if isinstance(per_kind, bool) or not isinstance(per_kind, int | np.integer) or per_kind < 0:
        raise ValueError(f"per_kind must be an integer >= 0, got {per_kind!r}")
    table = _numeric(table)
    picks = []
    for _, t in table.groupby("group", sort=False):
        good = t["solved"] & t["valid"]
        picks += [(i, "OMPL solves, segplan does not") for i in t.index[t["ompl_solved"] & ~t["solved"]]]
        picks += [(i, "invalid plan") for i in t.index[t["solved"] & ~t["valid"]]]
        unsolved = ~t["solved"] & ~t["ompl_solved"]
        picks += [
            (i, "no plan; OMPL did not solve it either") for i in t.index[unsolved & t["ompl_runs"].gt(0)]
        ]
        picks += [(i, "no plan; no OMPL run") for i in t.index[unsolved & ~t["ompl_runs"].gt(0)]]
        picks += [(i, "largest length ratio") for i in t["ratio"].dropna().nlargest(per_kind).index]
        picks += [(i, "slowest plan") for i in t.loc[good, "seconds"].nlargest(per_kind).index]
    seen, rows = set(), []
    for i, why in picks:
        if i not in seen:
            seen.add(i)
            rows.append({**table.loc[i, ["group", "floor"]].to_dict(), "why": why})
            rows[-1].update(table.loc[i, ["solved", "valid", "reason", "ratio", "seconds"]].to_dict())
    cols = ["group", "floor", "why", "solved", "valid", "reason", "ratio", "seconds"]
    return pd.DataFrame(rows, columns=cols)
