"""The reverse study's floors planned the other way in time too: a measurement, not a mechanism (issue 26).

Every floor of :mod:`segplan.studies.reverse_floors` planned by the default planner and
again with start and goal swapped and the costs mirrored, which is the same search backwards
in time (:mod:`segplan.studies.reverse_study`, "Both ways in time";
:func:`~segplan.studies.reverse_study.run_both_ways`). The swapped plan has what the default
lacks: it ends driving forwards into the real start, so the real plan may end with a long
reverse run into the goal (the goal's approach tree is forward only), and a start in a bay
becomes a goal that the approach tree reaches nose-in.

Writes ``--out``/``both_ways_default.csv`` and ``both_ways_swapped.csv`` (the rows of each
side, with the search cost) and ``both_ways.csv`` (the plan a planner that ran both would
keep, the time of both calls; provenance in ``both_ways.json``), and prints
:func:`~segplan.studies.reverse_study.both_ways_summary` against OMPL's stored
Reeds-Shepp BIT* (5 s).

    python benchmarks/both_ways.py --out benchmarks/results/both_ways
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import pandas as pd

from segplan.planning.options import LatticeOptions
from segplan.studies import reverse_floors as rf
from segplan.studies import reverse_study as rs
from segplan.studies import robustness as rb

RESULTS = Path(__file__).resolve().parent / "results"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=rf.N_PER_KIND, help="floors per kind")
    ap.add_argument("--kinds", nargs="+", choices=rf.REVERSE_KINDS, default=list(rf.REVERSE_KINDS))
    ap.add_argument("--out", type=Path, required=True, help="folder for the files (module docstring)")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    lo = LatticeOptions()
    meta = rb.segplan_provenance(
        sys.argv if argv is None else ["benchmarks/both_ways.py", *argv],
        what="segplan's default planner with reverse gear, each floor also planned with start and goal "
        "swapped and the costs mirrored (segplan.studies.reverse_study.run_both_ways)",
        generator="segplan.studies.reverse_floors",
        generator_version=rf.GENERATOR_VERSION,
        kinds=list(args.kinds),
        floors_per_kind=args.n,
        options=f"defaults (reverse_factor {lo.reverse_factor:g}, cusp_penalty {lo.cusp_penalty:g} L); "
        f"swapped: lattice {rs.mirrored_costs()}",
    )
    t0 = time.perf_counter()
    default, swapped, kept = rs.run_both_ways(args.kinds, args.n, progress=print)
    default.to_csv(args.out / "both_ways_default.csv", index=False)
    swapped.to_csv(args.out / "both_ways_swapped.csv", index=False)
    rb.store_segplan(kept, meta, args.out / "both_ways.csv", time.perf_counter() - t0)
    ompl = {s: rb.read_ompl(RESULTS / f"reverse_ompl_{s}.csv") for s in ("reedsshepp", "dubins")}
    summ = rs.both_ways_summary(default, swapped, kept, ompl["reedsshepp"], ompl["dubins"])
    with pd.option_context("display.width", 220, "display.max_columns", 30, "display.precision", 3):
        print(summ.to_string())
    return 0


if __name__ == "__main__":
    sys.exit(main())
