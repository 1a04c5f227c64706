"""Robustness of segplan on random and hard floors, against OMPL's BIT* (issue 12, item 5).

The command line of :mod:`segplan.studies.robustness` (the floors, the stored OMPL side, the
segplan side, the comparison and the verdicts live there). segplan runs with
``max_expansions=MAX_EXPANSIONS`` and ``time_limit=TIME_LIMIT`` by default, as chapter 9 does
(see that module: results do not depend on the machine's speed; floors over
``SLOW_SECONDS`` are listed as slow); ``--planner paper`` keeps the paper's search's own
limits unless ``--max-expansions`` is given; ``--max-expansions 0`` leaves the planner's own.

Usage::

    python benchmarks/robustness.py --ompl --no-segplan    # the stored OMPL side (about an hour
                                                           # on 2 idle cores; resumes if interrupted)
    python benchmarks/robustness.py --ompl --scheduler tcp://host:8786  # on a Dask cluster
    python benchmarks/robustness.py --out segplan.csv      # segplan on every floor (400 random,
                                                           # hard, 6 large, the sweep), targets
    python benchmarks/robustness.py --planner paper        # the same with the paper's search
    python benchmarks/robustness.py --quick                # smoke run (a few floors; OMPL 0.1 s if present)
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

import pandas as pd

from segplan.studies import ompl_runner
from segplan.studies import robustness as rb
from segplan.studies.progress import progress, say

#: The repository's stored results (the OMPL side is not shipped with the package).
RESULTS = Path(__file__).resolve().parent / "results"


def main(argv: Sequence[str] | None = None) -> int:
    """``python benchmarks/robustness.py [--ompl] [--quick] [--out CSV] [...]``."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ompl", action="store_true", help="run the OMPL side (the runs not stored yet)")
    ap.add_argument(
        "--jobs", type=int, help="at most this many OMPL runs at a time (default: one per free core)"
    )
    ap.add_argument(
        "--scheduler", metavar="ADDRESS", help="a Dask scheduler (tcp://host:8786): run OMPL on that cluster"
    )
    ap.add_argument("--ompl-csv", type=Path, default=RESULTS / rb.OMPL_CSV_NAME, help="the stored OMPL runs")
    ap.add_argument(
        "--quick",
        action="store_true",
        help="smoke run: a few floors (OMPL: 0.1 s budget, to a temporary CSV)",
    )
    ap.add_argument("--out", type=Path, help="write segplan's rows (CSV)")
    ap.add_argument("--planner", help="segplan planner (plan_scenario's planner=...)")
    ap.add_argument("--refine", action="store_true", help="refine segplan's plans (segplan.refine)")
    ap.add_argument(
        "--time-limit",
        type=float,
        default=rb.TIME_LIMIT,
        help=f"segplan's time limit (default {rb.TIME_LIMIT:g} s)",
    )
    ap.add_argument(
        "--max-expansions",
        type=int,
        help=f"segplan's expansion limit (default {rb.MAX_EXPANSIONS}, or the paper's search's own "
        "with --planner paper; 0: the planner's own)",
    )
    ap.add_argument("--no-segplan", action="store_true", help="skip segplan's side")
    args = ap.parse_args(argv)
    argv_list = ["benchmarks/robustness.py", *(sys.argv[1:] if argv is None else argv)]
    groups = rb.floor_groups(args.quick)

    def ticking(bar):
        """A ``progress`` callback of the study: the line above the bar, one step of the bar."""

        def tick(line: str) -> None:
            say(line)
            bar.update()

        return tick

    run = {"workers": args.jobs, "scheduler": args.scheduler, "argv": argv_list}
    if args.ompl or args.quick:
        if not ompl_runner.ompl_available():
            say("OMPL is not installed (pip install 'segplan[peers]'): skipping the OMPL side")
        elif args.quick:
            tmp = Path(tempfile.mkdtemp())
            jobs = rb.ompl_jobs({"any": groups["any"][:1], "hard": groups["hard"][:1]}, budgets=(0.1,))
            files = (tmp / "o.csv", tmp / "p.json.gz", tmp / "o.json")
            t = rb.run_ompl(jobs, *files, **run)
            say(f"OMPL quick: {int(t['solved'].sum())} of {len(t)} solved")
        else:
            files = rb.ompl_files(args.ompl_csv)
            rb.run_ompl(
                rb.ompl_jobs(groups), *files, workers=args.jobs, scheduler=args.scheduler, argv=argv_list
            )
    if args.no_segplan:
        return 0
    limit = args.max_expansions
    if limit is None:
        limit = 0 if args.planner == "paper" else rb.MAX_EXPANSIONS
    limit = limit or None
    options = rb.segplan_options(args.planner, True if args.refine else None, args.time_limit, limit)
    say(f"segplan {rb.variant_label(options)}: one-time set-up {rb.warm_up(options):.2f} s")
    floors = [(g, sc) for g, scs in groups.items() for sc in scs]
    if not args.quick:
        floors += [("sweep", sc) for sc in rb.sweep_floors()]
    with progress(total=len(floors), desc="segplan", unit="floor") as bar:
        seg, _ = rb.run_segplan(floors, options, progress=ticking(bar))
    table = rb.compare(seg, rb.read_ompl(args.ompl_csv))
    with pd.option_context("display.width", 200, "display.max_columns", 20, "display.precision", 3):
        print(table.groupby("group")[["solved", "valid", "ompl_solved"]].sum().to_string())
        print(rb.verdicts(table)[["target", "criterion", "measured", "verdict"]].to_string(index=False))
        slow = rb.slow_floors(table)
        print(f"slow (> {rb.SLOW_SECONDS:g} s): {len(slow)} floors " + ", ".join(slow["floor"]))
    if args.out:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        table.to_csv(args.out, index=False)
        say(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
