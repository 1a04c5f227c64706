"""The reverse study's floors planned the other way in time too: a measurement, not a mechanism (issue 26).

A robot that may reverse can drive any plan from the goal to the start backwards in time:
the same unions in the opposite order, each driven the other way (the same poses, the same
front-wheel length, the same swept area; :mod:`segplan.planning.lattice.reverse`). So the
scenario with start and goal swapped, planned with ``reverse_factor`` ``1 / f`` and
``cusp_penalty`` ``p / f`` (``f``, ``p`` the defaults), minimises the same search cost up to
the factor ``f``: its reverse links are the real forward ones. Its plan has what the
default planner lacks: it ends driving forwards into the real start, so it may end the real
plan with a long reverse run into the goal (the goal's approach tree is forward only), and a
start in a bay becomes a goal the approach tree reaches nose-in.

This script plans every floor of :mod:`segplan.studies.reverse_floors` both ways with the
default planner, checks both plans with the dense oracle, and writes per floor the search
cost of each (:func:`segplan.planning.lattice.reverse.weighted_cost`, the swapped plan's
mirrored back), the front-wheel lengths, the times, and which plan a planner that ran both
would keep (the lower search cost): ``--out``/``both_ways.csv``, with provenance in
``both_ways.json``. It then prints, per kind, the front-wheel length over OMPL's stored
Reeds-Shepp BIT* (5 s) for the default, for the swapped plan and for the kept one, and the
time of the default against that of both.

    python benchmarks/both_ways.py --out benchmarks/results/both_ways
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import time
from pathlib import Path

import pandas as pd

from segplan.planning.lattice.reverse import weighted_cost
from segplan.planning.options import LatticeOptions
from segplan.studies import reverse_floors as rf
from segplan.studies import reverse_study as rs
from segplan.studies import robustness as rb

RESULTS = Path(__file__).resolve().parent / "results"


def swapped(sc):
    """The scenario planned backwards in time: start and goal swapped (the same name)."""
    return dataclasses.replace(sc, start=sc.goal, goal=sc.start)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=rf.N_PER_KIND, help="floors per kind")
    ap.add_argument("--kinds", nargs="+", choices=rf.REVERSE_KINDS, default=list(rf.REVERSE_KINDS))
    ap.add_argument("--out", type=Path, required=True, help="folder for both_ways.csv and .json")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    lo = LatticeOptions()
    f, p = lo.reverse_factor, lo.cusp_penalty
    mirrored = {"lattice": {"reverse_factor": 1.0 / f, "cusp_penalty": p / f}}
    meta = rb.segplan_provenance(
        sys.argv if argv is None else ["benchmarks/both_ways.py", *argv],
        what="segplan's default planner with reverse gear, each floor also planned with start and goal "
        "swapped and the costs mirrored (module docstring)",
        generator="segplan.studies.reverse_floors",
        generator_version=rf.GENERATOR_VERSION,
        kinds=list(args.kinds),
        floors_per_kind=args.n,
        options=f"defaults (reverse_factor {f:g}, cusp_penalty {p:g} L); swapped: {mirrored}",
    )
    t0 = time.perf_counter()
    floors = [(k, rs.with_reverse(sc)) for k in args.kinds for sc in rf.reverse_floors(k, args.n)]
    keys = [rs.floor_key(rf.reverse_floor(k, int(sc.name.rsplit("-", 1)[1]))) for k, sc in floors]
    fwd, fwd_plans = rb.run_segplan(floors, None, progress=print)
    back, back_plans = rb.run_segplan([(k, swapped(sc)) for k, sc in floors], mirrored, progress=print)
    costs = {"default": [], "swapped": []}
    for _, sc in floors:
        pen = p * sc.robot.L
        pa, pb = fwd_plans[sc.name], back_plans[sc.name]
        costs["default"].append(weighted_cost(pa, f, pen) if pa is not None else math.inf)
        costs["swapped"].append(f * weighted_cost(pb, 1.0 / f, pen / f) if pb is not None else math.inf)
    fwd = fwd.assign(floor_key=keys, search_cost=costs["default"])
    back = back.assign(floor_key=keys, search_cost=costs["swapped"])
    # a planner that ran both keeps the valid plan of lower search cost (the default's on a tie)
    ok_a, ok_b = fwd["solved"] & fwd["valid"], back["solved"] & back["valid"]
    take_b = ok_b & (~ok_a | (back["search_cost"] < fwd["search_cost"]))
    kept = fwd.where(~take_b, back).assign(
        kept=["swapped" if t else "default" for t in take_b],
        seconds=fwd["seconds"] + back["seconds"],
        cpu_seconds=fwd["cpu_seconds"] + back["cpu_seconds"],
    )
    back.to_csv(args.out / "both_ways_swapped.csv", index=False)
    fwd.to_csv(args.out / "both_ways_default.csv", index=False)
    rb.store_segplan(kept, meta, args.out / "both_ways.csv", time.perf_counter() - t0)
    with pd.option_context("display.width", 220, "display.max_columns", 30, "display.precision", 3):
        print(summary(fwd, back, kept).to_string(index=False))
    return 0


def summary(default: pd.DataFrame, swapped_rows: pd.DataFrame, kept: pd.DataFrame) -> pd.DataFrame:
    """Per kind and for all: :func:`segplan.studies.reverse_study.summary`'s length ratios
    (front wheel over OMPL's stored Reeds-Shepp BIT*) of the default, the swapped and the
    kept plans, the swapped plans kept, invalid plans, and the median times of the default
    and of both."""
    ompl = {s: rb.read_ompl(RESULTS / f"reverse_ompl_{s}.csv") for s in ("reedsshepp", "dubins")}
    out = []
    tables = {n: rs.compare(t, ompl["reedsshepp"], ompl["dubins"]) for n, t in
              (("default", default), ("swapped", swapped_rows), ("kept", kept))}  # fmt: skip
    groups = [*kept["group"].unique(), "all"]
    for kind in groups:
        row = {"kind": kind}
        for name, t in tables.items():
            g = t if kind == "all" else t[t["group"] == kind]
            r = g["ratio"].dropna()
            row[f"{name} median"], row[f"{name} worst"] = r.median(), r.max()
            row[f"{name} invalid"] = int((g["solved"] & ~g["valid"]).sum())
        k = kept if kind == "all" else kept[kept["group"] == kind]
        worst = tables["kept"].loc[(tables["kept"]["group"] == kind) | (kind == "all"), "ratio"]
        row["worst floor kept"] = tables["kept"].loc[worst.idxmax(), "floor"]
        row["swapped kept"] = int((k["kept"] == "swapped").sum())
        d = default if kind == "all" else default[default["group"] == kind]
        row["default s median"], row["both s median"] = d["seconds"].median(), k["seconds"].median()
        out.append(row)
    return pd.DataFrame(out).round(3)


if __name__ == "__main__":
    sys.exit(main())
