"""OMPL on the floors that need reverse gear (issue 26): the peers' side of the reverse study.

The floors are :mod:`segplan.studies.reverse_floors` (bay-out, reverse-park, dead-end,
k-turn; the first ``--n`` of each). For every floor, OMPL's BIT* at 5 s, seed 1, each run
in a fresh process through the one executor at full CPU (a run given less than 0.9 of a
core is refused and run again; resumable), on

* the **Reeds-Shepp** space (forward and reverse, radius ``L / tan(max_steer)``): the
  feasibility oracle and the length reference of a robot with reverse gear;
  ``reverse_ompl_reedsshepp.csv`` (with ``.json`` provenance and ``_paths.json.gz``);
* the **Dubins** space (forward only): which floors need reverse at all (those Reeds-Shepp
  solves and Dubins does not); ``reverse_ompl_dubins.csv`` and the files beside it.

With ``--segplan``: segplan's default planner with reverse gear on the same floors in this
warm process (:mod:`segplan.studies.reverse_study`), each plan checked by the dense oracle;
``reverse_segplan.csv`` and ``reverse_segplan.json`` (when, where, load, commit, CPU share),
then the summary against the stored OMPL runs (``reverse_summary.csv``).

Usage::

    python benchmarks/reverse_floors.py --space reedsshepp dubins   # 800 runs of 5 s
    python benchmarks/reverse_floors.py --n 3 --results /tmp/r      # a try
    python benchmarks/reverse_floors.py --space --segplan           # segplan's side, the summary
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from pathlib import Path

import pandas as pd

from segplan.studies import kind_study as ks
from segplan.studies import ompl_runner
from segplan.studies import reverse_floors as rf
from segplan.studies import reverse_study as rs
from segplan.studies import robustness as rb

#: The repository's stored results.
RESULTS = Path(__file__).resolve().parent / "results"


def ompl_csv(results: Path, space: str) -> Path:
    """Where the OMPL runs on ``space`` are stored."""
    return results / f"reverse_ompl_{space}.csv"


def main(argv: Sequence[str] | None = None) -> int:
    """``python benchmarks/reverse_floors.py [--n N] [--kinds ...] [--space ...] [--jobs J]``."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=rf.N_PER_KIND, help=f"floors per kind (default {rf.N_PER_KIND})")
    ap.add_argument("--kinds", nargs="+", choices=rf.REVERSE_KINDS, default=list(rf.REVERSE_KINDS))
    ap.add_argument("--space", nargs="*", choices=ompl_runner.SPACES, default=["reedsshepp"])
    ap.add_argument("--segplan", action="store_true", help="segplan's side and the summary")
    ap.add_argument("--results", type=Path, default=RESULTS, help=f"where the files go (default {RESULTS})")
    ap.add_argument("--budget", type=float, default=ks.BUDGET, help="BIT*'s budget (s; the study's: 5)")
    ap.add_argument("--jobs", type=int, help="at most this many OMPL runs at a time (default: free cores)")
    args = ap.parse_args(argv)
    if args.n < 1:
        ap.error("--n must be at least 1")
    if args.space and not ompl_runner.ompl_available():
        ap.error("OMPL's Python bindings are needed (pip install 'segplan[peers]')")
    argv_list = ["benchmarks/reverse_floors.py", *(sys.argv[1:] if argv is None else argv)]
    groups = {k: rf.reverse_floors(k, args.n) for k in args.kinds}
    for space in args.space:
        about = {
            "what": f"OMPL BIT* on the {space} space on segplan.studies.reverse_floors; raw paths and "
            "after OMPL's PathSimplifier (simplified_*)",
            "generator": "segplan.studies.reverse_floors",
            "generator_version": rf.GENERATOR_VERSION,
            "budgets": [float(args.budget)],
            "seeds": {"every floor": [ks.SEED]},
        }
        table = rb.run_ompl(
            ks.ompl_jobs(groups, args.budget),
            *rb.ompl_files(ompl_csv(args.results, space)),
            workers=args.jobs,
            argv=argv_list,
            about=about,
            space=space,
        )
        solved = table.groupby("group")["solved"].agg(["sum", "count"])
        print(f"{space}:\n{solved.to_string()}")
    if args.segplan:
        _segplan_side(args, argv_list)
    return 0


def _segplan_side(args, argv: list[str]) -> None:
    """segplan with reverse gear on the floors, stored with provenance; the summary printed and stored."""
    meta = rb.segplan_provenance(
        argv,
        what="segplan's default planner, the robot with reverse gear, on segplan.studies.reverse_floors",
        generator="segplan.studies.reverse_floors",
        generator_version=rf.GENERATOR_VERSION,
        kinds=list(args.kinds),
        floors_per_kind=args.n,
        options="the planner's defaults (reverse_factor, cusp_penalty, time_limit)",
    )
    t0 = time.perf_counter()
    seg = rs.run_segplan(args.kinds, args.n, None, progress=print)
    rb.store_segplan(seg, meta, args.results / "reverse_segplan.csv", time.perf_counter() - t0)
    ompl = {s: rb.read_ompl(ompl_csv(args.results, s)) for s in ompl_runner.SPACES}
    summ = rs.summary(rs.compare(seg, ompl["reedsshepp"], ompl["dubins"]))
    summ.to_csv(args.results / "reverse_summary.csv", index=False)
    with pd.option_context("display.width", 220, "display.max_columns", 30, "display.precision", 3):
        print(summ.to_string(index=False))


if __name__ == "__main__":
    sys.exit(main())
