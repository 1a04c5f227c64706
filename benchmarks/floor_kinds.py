"""segplan on the floors robots drive, against OMPL's BIT* (issue 25): the command line.

The study is :mod:`segplan.studies.kind_study` (floors: :mod:`segplan.studies.floor_kinds`);
both sides are measured by chapter 9's robustness functions. For every kind and the first
``--n`` floors of it:

* **segplan** (default; skip with ``--no-segplan``): the default planner in this warm
  process, with the robustness study's limits (``--time-limit``, ``--max-expansions``),
  each plan checked by the dense oracle. Writes ``floor_kinds_segplan.csv`` and, beside it,
  ``floor_kinds_segplan.json``: when, where (machine, cores, load average before and after,
  nice), the commit, the command, the generator's version, the options, and the CPU share
  of the plan calls (``cpu_seconds / seconds``; below 0.9 the times are inflated by load).
* **OMPL** (``--ompl``; optional dependency): BIT* on the Dubins space, 5 s, seed 1, each
  run in a fresh process through the one executor (one run per free core, ``--jobs`` caps
  it, or a Dask cluster with ``--scheduler``; a run given less than 0.9 of a core is
  refused and run again; resumable: run the same command again after an interruption).
  Writes ``floor_kinds_ompl.csv``, ``floor_kinds_ompl.json`` (provenance per session) and
  ``floor_kinds_ompl_paths.json.gz``. Run it on a quiet machine.

Then it prints and writes ``floor_kinds_summary.csv`` (per kind: OMPL solved, segplan
solved, invalid plans, length ratio to BIT* median and worst, plan time median, 90th
percentile and largest) and ``floor_kinds_worst.csv`` (the floors to draw), from the
segplan rows and whatever OMPL runs are stored. Files go to ``--results`` (default
``benchmarks/results/``).

Usage::

    nice -n 10 python benchmarks/floor_kinds.py --n 3                  # segplan only, 3 floors a kind
    python benchmarks/floor_kinds.py --ompl --no-segplan               # the OMPL side (600 runs of 5 s:
                                                                       # about 35 min on 2 idle cores)
    python benchmarks/floor_kinds.py                                   # segplan, 100 floors a kind, summary
    python benchmarks/floor_kinds.py --kinds warehouse rooms --n 20    # some kinds
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from pathlib import Path

import pandas as pd

from segplan.studies import floor_kinds as fk
from segplan.studies import kind_study as ks
from segplan.studies import ompl_runner
from segplan.studies import robustness as rb
from segplan.studies.progress import progress, say

#: The repository's stored results.
RESULTS = Path(__file__).resolve().parent / "results"


def _segplan_side(groups, options: dict, argv: list[str], csv: Path) -> pd.DataFrame:
    """segplan on every floor in this warm process; the rows written to ``csv`` with provenance."""
    meta = rb.segplan_provenance(
        argv,
        what="segplan's default planner on segplan.studies.floor_kinds (segplan.studies.kind_study)",
        generator="segplan.studies.floor_kinds",
        generator_version=fk.GENERATOR_VERSION,
        kinds=list(groups),
        floors_per_kind={k: len(v) for k, v in groups.items()},
        options=options,
    )
    meta["warm_up_seconds"] = rb.warm_up(options)
    say(f"segplan {rb.variant_label(options)}: one-time set-up {meta['warm_up_seconds']:.2f} s")
    floors = [(k, sc) for k, scs in groups.items() for sc in scs]
    t0 = time.perf_counter()
    with progress(total=len(floors), desc="segplan", unit="floor") as bar:

        def tick(line: str) -> None:
            say(line)
            bar.update()

        seg, _ = rb.run_segplan(floors, options, progress=tick)
    rb.store_segplan(seg, meta, csv, time.perf_counter() - t0)
    say(f"wrote {csv} and {csv.with_suffix('.json').name}")
    return seg


def main(argv: Sequence[str] | None = None) -> int:
    """``python benchmarks/floor_kinds.py [--n N] [--kinds ...] [--ompl] [--no-segplan] [...]``."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=fk.N_PER_KIND, help=f"floors per kind (default {fk.N_PER_KIND})")
    ap.add_argument("--kinds", nargs="+", choices=fk.FLOOR_KINDS, default=list(fk.FLOOR_KINDS))
    ap.add_argument("--results", type=Path, default=RESULTS, help=f"where the files go (default {RESULTS})")
    ap.add_argument("--ompl", action="store_true", help="run the OMPL side (the runs not stored yet)")
    ap.add_argument("--budget", type=float, default=ks.BUDGET, help="BIT*'s budget (s; the study's: 5)")
    ap.add_argument("--jobs", type=int, help="at most this many OMPL runs at a time (default: free cores)")
    ap.add_argument("--scheduler", metavar="ADDRESS", help="a Dask scheduler (tcp://host:8786)")
    ap.add_argument("--no-segplan", action="store_true", help="skip segplan's side (read the stored one)")
    ap.add_argument(
        "--time-limit",
        type=float,
        default=rb.TIME_LIMIT,
        help=f"segplan's time limit (default {rb.TIME_LIMIT:g} s)",
    )
    ap.add_argument(
        "--max-expansions",
        type=int,
        default=rb.MAX_EXPANSIONS,
        help=f"segplan's expansion limit (default {rb.MAX_EXPANSIONS}; 0: the planner's own)",
    )
    args = ap.parse_args(argv)
    if args.n < 1:
        ap.error("--n must be at least 1")
    argv_list = ["benchmarks/floor_kinds.py", *(sys.argv[1:] if argv is None else argv)]
    groups = ks.kind_groups(args.n, args.kinds)
    ompl_csv = args.results / ks.OMPL_CSV_NAME
    seg_csv = args.results / ks.SEGPLAN_CSV_NAME
    if args.ompl:
        if not ompl_runner.ompl_available():
            ap.error("--ompl needs OMPL's Python bindings (pip install 'segplan[peers]')")
        ks.run_ompl(groups, ompl_csv, args.jobs, args.scheduler, argv_list, args.budget)
    if args.no_segplan:
        if not seg_csv.exists():
            return 0
        seg = ks.read_segplan(seg_csv)
    else:
        options = rb.segplan_options(None, None, args.time_limit, args.max_expansions or None)
        seg = _segplan_side(groups, options, argv_list, seg_csv)
    table = rb.compare(seg, rb.read_ompl(ompl_csv))
    summary, worst = ks.summary(table), ks.worst_floors(table)
    summary.to_csv(args.results / "floor_kinds_summary.csv", index=False)
    worst.to_csv(args.results / "floor_kinds_worst.csv", index=False)
    with pd.option_context("display.width", 220, "display.max_columns", 30, "display.precision", 3):
        print(summary.to_string(index=False))
        print(worst.to_string(index=False))
    return 0


if __name__ == "__main__":
    sys.exit(main())
