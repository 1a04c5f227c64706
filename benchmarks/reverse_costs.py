"""``reverse_factor`` and ``cusp_penalty`` walked over the reverse study's floors (issue 26).

The defaults of :class:`segplan.planning.options.LatticeOptions` were first set on 16
floors (``benchmarks/reverse_defaults.py``). This walk uses the study's own floors
(:mod:`segplan.studies.reverse_floors`: bay-out, reverse-park, dead-end, k-turn) against
the stored OMPL Reeds-Shepp runs, split in two so that a choice is not judged on the floors
that made it: pairs are compared on the *even* floors of each kind (``--half even``), the
chosen pair is then run on the *odd* ones (``--half odd``) beside the old default.

Per pair and kind it prints the summary of :func:`segplan.studies.reverse_study.summary`
(success on the floors needing reverse, invalid plans, the front-wheel length over OMPL's,
cusps of both, times) and writes the per-floor rows to ``--out``/``<half>_<factor>_<penalty>.csv``.
Lengths and cusps do not depend on the machine (the searches are bounded by expansions;
the time limit, 120 s, is far above every floor's); the times do (the load is printed).

    python benchmarks/reverse_costs.py --half even --pairs 1.25,0.5 1.1,0.5 1.0,0.25
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import pandas as pd

from segplan.studies import reverse_floors as rf
from segplan.studies import reverse_study as rs
from segplan.studies import robustness as rb

RESULTS = Path(__file__).resolve().parent / "results"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--half", choices=("even", "odd"), required=True)
    ap.add_argument(
        "--pairs", nargs="+", required=True, help="reverse_factor,cusp_penalty (cusp in units of L)"
    )
    ap.add_argument("--kinds", nargs="+", choices=rf.REVERSE_KINDS, default=list(rf.REVERSE_KINDS))
    ap.add_argument("--out", type=Path, required=True, help="folder for the per-floor rows")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    indices = range(0 if args.half == "even" else 1, rf.N_PER_KIND, 2)
    ompl = {s: rb.read_ompl(RESULTS / f"reverse_ompl_{s}.csv") for s in ("reedsshepp", "dubins")}
    for pair in args.pairs:
        factor, penalty = (float(v) for v in pair.split(","))
        options = {"time_limit": 120.0, "lattice": {"reverse_factor": factor, "cusp_penalty": penalty}}
        seg = rs.run_segplan(args.kinds, options=options, indices=indices)
        seg.to_csv(args.out / f"{args.half}_{factor:g}_{penalty:g}.csv", index=False)
        summ = rs.summary(rs.compare(seg, ompl["reedsshepp"], ompl["dubins"]))
        load = os.getloadavg()[0]
        print(f"\nreverse_factor {factor:g}, cusp_penalty {penalty:g} L ({args.half}, load {load:.1f})")
        with pd.option_context("display.width", 220, "display.max_columns", 30, "display.precision", 3):
            print(summ.to_string(index=False))
        sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
