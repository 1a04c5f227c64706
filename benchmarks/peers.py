"""segplan against OMPL's RRT*, Informed RRT* and BIT* on the shipped floors: the command line.

The study itself is :mod:`segplan.studies.peers` (see its docstring for how the problems
are made equal). OMPL's runs stop at wall-clock budgets, so they are measured here, once,
and stored with their provenance; the book's chapter 8 reads them and recomputes
segplan's deterministic side at build time.

Usage::

    nice -n -10 python benchmarks/peers.py             # the full study -> benchmarks/results/peers_ompl.*
    python benchmarks/peers.py --quick --out /tmp/peers.csv  # smoke run: tiny budget, one seed, one floor
    python benchmarks/peers.py --scheduler tcp://host:8786   # the OMPL runs on a Dask cluster

The OMPL runs go through :func:`segplan.studies.executor.run_jobs`: one per free core
(``--jobs`` caps it), each run's CPU share recorded and a starved run refused and run again
(:data:`segplan.studies.executor.FAIRNESS`). Accepted runs are appended to
``OUT.journal.jsonl`` as they finish: run the same command again after an interruption and
it resumes. Writes ``OUT`` (default ``benchmarks/results/peers_ompl.csv``, one row per OMPL
run, raw and simplified measures), ``OUT.json`` (date, machine, OMPL version, commit,
command line, configuration, fairness rule, wall time) and ``OUT_paths.json.gz`` (the poses
of the best valid run per floor, space, planner and budget, raw and simplified), removes
the journal, and prints the summary tables against segplan. Progress shows on a terminal.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Sequence
from pathlib import Path

import pandas as pd

from segplan.studies import ompl_runner, peers

DEFAULT_OUT = Path(__file__).resolve().parent / "results" / "peers_ompl.csv"


def main(argv: Sequence[str] | None = None) -> int:
    """Run the study, print its tables, store OMPL's runs; returns the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument(
        "--out", type=Path, default=DEFAULT_OUT, help=f"CSV of every OMPL run (default {DEFAULT_OUT})"
    )
    ap.add_argument("--quick", action="store_true", help="smoke run: tiny budget, 1 seed, one scenario")
    ap.add_argument("--scenarios", nargs="+", help="scenario names (default: all shipped)")
    ap.add_argument("--planners", nargs="+", choices=ompl_runner.PLANNERS, default=list(ompl_runner.PLANNERS))
    ap.add_argument("--budgets", nargs="+", type=float, default=list(peers.BUDGETS))
    ap.add_argument("--seeds", nargs="+", type=int, default=list(peers.SEEDS))
    ap.add_argument(
        "--reeds-shepp",
        nargs="*",
        type=float,
        default=[1.0, 5.0],
        metavar="BUDGET",
        help="budgets of the Reeds-Shepp reference (BIT*); none to skip",
    )
    ap.add_argument(
        "--jobs", type=int, help="at most this many OMPL runs at a time (default: one per free core)"
    )
    ap.add_argument(
        "--scheduler", metavar="ADDRESS", help="a Dask scheduler (tcp://host:8786): run OMPL on that cluster"
    )
    args = ap.parse_args(argv)
    if not ompl_runner.ompl_available():
        print("peers.py needs the OMPL Python bindings: pip install 'segplan[peers]'", file=sys.stderr)
        return 2
    if args.quick:
        config = peers.quick_config(args.scenarios or ("single_obstacle",))
    else:
        names = tuple(args.scenarios or peers.shipped_scenarios())
        blocks = [peers.Runs(names, tuple(args.planners), tuple(args.budgets), tuple(args.seeds))]
        if args.reeds_shepp:
            blocks.append(
                peers.Runs(names, ("BITstar",), tuple(args.reeds_shepp), tuple(args.seeds), "reedsshepp")
            )
        config = peers.StudyConfig(scenarios=names, blocks=tuple(blocks))
    meta = ompl_runner.provenance(["benchmarks/peers.py", *argv], config, args.jobs)
    meta["scheduler"] = args.scheduler
    journal = peers.journal_path(args.out)
    t0 = time.perf_counter()
    ompl, paths = peers.run_ompl(config, jobs=args.jobs, journal=journal, scheduler=args.scheduler)
    meta["wall_seconds"] = round(time.perf_counter() - t0, 1)
    meta["load_average_after"] = list(os.getloadavg()) if hasattr(os, "getloadavg") else None
    written = peers.write_ompl_results(ompl, paths, args.out, meta)
    journal.unlink(missing_ok=True)
    ours = peers.run_segplan(config)
    t = pd.concat([ours, ompl], ignore_index=True)
    with pd.option_context("display.width", 200, "display.max_columns", 30, "display.precision", 3):
        print(peers.summary_table(t).to_string(index=False))
        print()
        print(peers.budget_table(t).to_string(index=False))
        print()
        for b in sorted(set(t.loc[t["space"] == "dubins", "budget"])):
            for refine in (False, True):
                side = "simplified" if refine else "raw"
                print(f"goal at {b:g} s, {peers.segplan_method('a', refine)} (OMPL {side}):")
                print(peers.goal_table(t, b, refine=refine).to_string(index=False))
    bad = t[(t["solved"] == True) & (t["valid"] == False)]  # noqa: E712
    print(f"\ninvalid paths (solved but failing the dense oracle): {len(bad)}")
    if len(bad):
        print(bad[["scenario", "method", "space", "budget", "seed", "clearance"]].to_string(index=False))
    print(f"OMPL runs {meta['wall_seconds']:.0f} s; wrote " + ", ".join(map(str, written)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
