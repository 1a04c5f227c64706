"""How many expansions the default planner needs, floor by floor (issue 25: "no call over 1 s").

Not a timed test. The lattice's expansion limit (``LatticeOptions.max_expansions``)
bounds the calls that fail by running the lattice out; a lower limit would end them sooner
but lose every floor whose plan needs more. This benchmark measures that trade: for every
floor of the chosen sets it calls ``segplan.plan_scenario(sc, time_limit=...)`` with the
planner's own expansion limit and records whether it planned, the reason of a failure and
``expanded`` (the expansions of the whole call: the paper's search, the lattice, its
escapes and hops; ``Plan.expanded`` or ``NoPathError.expanded``). The counts are the same
on any machine as long as no call reaches the time limit (``--time-limit``, 60 s by
default, far above the 10 s of the planner's default so that the 200 000-expansion calls
end by the expansion limit; a call that reached it is marked ``reason="time"``).

Sets (``--sets``):

* ``kinds``: the five 30 x 20 m kinds of :mod:`segplan.studies.floor_kinds` (warehouse,
  rooms, parking, clutter, robots), 100 floors each;
* ``random``: chapter 9's 400 random floors (:func:`segplan.studies.floors.random_floor`,
  200 of each heading kind) and its hard cases;
* ``large``: the large sites of :mod:`segplan.studies.floor_kinds` (``--large`` of them);
* ``reverse``: the reverse study's floors (:mod:`segplan.studies.reverse_floors`) with the
  robot's reverse gear on (``--reverse`` per kind).

The results (every floor, and per set the largest count of a floor that planned) go to
``--out`` (JSON) with when, where and at which commit; the stored runs are in
``benchmarks/results/expansions_needed/`` (its README says how they were made).

Usage::

    python benchmarks/expansions_needed.py --sets kinds random --out kinds_random.json
    python benchmarks/expansions_needed.py --sets large reverse --large 30 --reverse 25 \
        --out large_reverse.json
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import sys
import time

import segplan
from segplan.studies import ompl_runner
from segplan.studies.floor_kinds import FLOOR_KINDS, N_PER_KIND, kind_floor
from segplan.studies.floors import KINDS, N_FLOORS, hard_cases, random_floor
from segplan.studies.reverse_floors import REVERSE_KINDS, reverse_floor
from segplan.studies.reverse_study import with_reverse

#: The 30 x 20 m kinds of the "kinds" set.
SMALL_KINDS = tuple(k for k in FLOOR_KINDS if k != "large")
#: The planner's own expansion limit, the one every call runs with.
LIMIT = segplan.LatticeOptions().max_expansions
#: Counts a summary reports how many planned floors needed more than.
THRESHOLDS = (1_000, 5_000, 20_000, 50_000, 100_000)


def floors(name: str, n_large: int, n_reverse: int):
    """``(floor name, scenario)`` of set ``name`` (module docstring), in a fixed order."""
    if name == "kinds":
        return [(f"{k}-{i:03d}", kind_floor(k, i)) for k in SMALL_KINDS for i in range(N_PER_KIND)]
    if name == "random":
        out = [(f"{k}-{i:03d}", random_floor(k, i)) for k in KINDS for i in range(N_FLOORS)]
        return out + [(f"hard-{n}", sc) for n, sc in hard_cases().items()]
    if name == "large":
        return [(f"large-{i:03d}", kind_floor("large", i)) for i in range(n_large)]
    if name == "reverse":
        return [
            (f"{k}-{i:03d}", with_reverse(reverse_floor(k, i)))
            for k in REVERSE_KINDS
            for i in range(n_reverse)
        ]
    raise SystemExit(f"unknown set {name!r}")


def one(name: str, scenario, time_limit: float) -> dict:
    """Plan once; the outcome and the expansions of the call."""
    t = time.perf_counter()
    try:
        plan = segplan.plan_scenario(scenario, time_limit=time_limit)
        row = {"floor": name, "solved": True, "reason": "", "expanded": int(plan.expanded), "cost": plan.cost}
    except segplan.NoPathError as e:
        row = {"floor": name, "solved": False, "reason": e.reason, "expanded": int(e.expanded), "cost": None}
    row["seconds"] = time.perf_counter() - t
    return row


def summary(rows: list[dict]) -> dict:
    """Per set: floors, planned, the largest counts of planned floors, failures by reason."""
    solved = sorted((r for r in rows if r["solved"]), key=lambda r: r["expanded"])
    failed = [r for r in rows if not r["solved"]]
    return {
        "floors": len(rows),
        "planned": len(solved),
        "largest_planned": [[r["floor"], r["expanded"]] for r in solved[-5:]],
        "planned_above": {str(t): sum(r["expanded"] > t for r in solved) for t in THRESHOLDS},
        "failed": dict(collections.Counter(r["reason"] for r in failed)),
        "failed_at_limit": [
            r["floor"] for r in failed if r["reason"] == "expansions" and r["expanded"] >= LIMIT
        ],
    }


def main(argv: list[str] | None = None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--sets", nargs="+", default=["kinds", "random"], choices=["kinds", "random", "large", "reverse"]
    )
    parser.add_argument("--time-limit", type=float, default=60.0, help="seconds per call (module docstring)")
    parser.add_argument("--large", type=int, default=100, help="large floors 0 .. N-1")
    parser.add_argument("--reverse", type=int, default=100, help="reverse floors 0 .. N-1 of each kind")
    parser.add_argument("--out", metavar="JSON", help="store the results here (with provenance)")
    args = parser.parse_args(argv)
    result = ompl_runner.provenance(
        ["benchmarks/expansions_needed.py", *(sys.argv[1:] if argv is None else argv)], None, None
    )
    result["time_limit"] = args.time_limit
    result["sets"] = {}
    for name in args.sets:
        rows = []
        for floor, sc in floors(name, args.large, args.reverse):
            rows.append(one(floor, sc, args.time_limit))
            r = rows[-1]
            print(f"{name} {floor}: {'planned' if r['solved'] else r['reason']}, {r['expanded']} expansions, "
                  f"{r['seconds']:.2f} s", flush=True)  # fmt: skip
        result["sets"][name] = {"summary": summary(rows), "floors": rows}
        print(name, json.dumps(result["sets"][name]["summary"]), flush=True)
    result["load_average_after"] = list(os.getloadavg())
    if args.out:
        with open(args.out, "w") as f:
            json.dump(result, f, indent=1)
    return result


if __name__ == "__main__":
    main()
