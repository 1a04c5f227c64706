"""The refinement's time, A/B against another checkout, floor by floor in one process (issue 25).

Not a timed test. Loads this tree's ``segplan`` and another checkout's (``--base``, its
``segplan`` package imported under the name ``segplan_base`` through a symbolic link in a
temporary directory; the package imports itself relatively) into one warm process, then for
the first ``--n`` floors of each kind (default :data:`KINDS`), ``--reps`` times,
alternating which side goes first:

* the whole call ``plan_scenario(sc)`` with the defaults (the refinement's inputs recorded on
  the way: the plans found and their link models' workspace and options);
* the refinement alone: ``refine_with`` on those inputs with a fresh link model (no cached
  unions), the default ``RefineOptions``.

Per floor and side, the least CPU time (``time.process_time``) over the repetitions; both
sides must give the same plan (checked: same cost, bit for bit). Pairing floor by floor in one
process keeps the comparison meaningful on a loaded machine, where each side's absolute times
are upper bounds (the load average before and after is printed). Prints per kind the medians,
90th percentiles and sums of both sides and the median of the per-floor ratios.

Usage::

    nice -n 19 python benchmarks/refine_ab.py --base /path/to/main --n 20 --reps 3
"""

from __future__ import annotations

import argparse
import importlib
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import segplan
from segplan.studies.floor_kinds import FLOOR_KINDS

#: The default kinds: the 30 x 20 m ones of issue 25 (those ``benchmarks/same_plans.py --kinds`` records).
KINDS = ("warehouse", "rooms", "parking", "clutter", "robots")


def load_base(base: Path):
    """The other checkout's ``segplan`` package, imported as ``segplan_base``."""
    tmp = Path(tempfile.mkdtemp(prefix="refine_ab_"))
    (tmp / "segplan_base").symlink_to(base.resolve() / "segplan")
    sys.path.insert(0, str(tmp))
    return importlib.import_module("segplan_base")


class Side:
    """One checkout's planner: a whole call recording the refinement's inputs, and the refinement alone."""

    def __init__(self, pkg):
        self.pkg = pkg
        self.default = importlib.import_module(pkg.__name__ + ".planning.default")
        self.LinkModel = importlib.import_module(pkg.__name__ + ".planning.links").LinkModel
        self.Workspace = importlib.import_module(pkg.__name__ + ".planning.validity").Workspace
        self.kind_floor = importlib.import_module(pkg.__name__ + ".studies.floor_kinds").kind_floor

    def whole(self, sc):
        """CPU seconds of ``plan_scenario(sc)``, the plan's cost (None: no plan) and the
        refinement's inputs."""
        got = []
        refine_with = self.default.refine_with

        def record(plan, links, options, deadline=None):
            ws = links.ws
            got.append((plan, (ws.polygons, ws.L, ws.bounds, ws.max_curvature), links.alpha_method, options))
            return refine_with(plan, links, options, deadline=deadline)

        self.default.refine_with = record
        try:
            t = time.process_time()
            try:
                cost = self.pkg.plan_scenario(sc).cost
            except self.pkg.NoPathError:
                cost = None
            return time.process_time() - t, cost, got
        finally:
            self.default.refine_with = refine_with

    def refine(self, got) -> float:
        """CPU seconds of the refinement of the recorded plans, with fresh link models."""
        calls = [(p, self.LinkModel(self.Workspace(*w), a), o) for p, w, a, o in got]
        t = time.process_time()
        for plan, links, options in calls:
            self.default.refine_with(plan, links, options)
        return time.process_time() - t


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument(
        "--base", type=Path, required=True, help="the other checkout (a directory holding segplan/)"
    )
    ap.add_argument("--n", type=int, default=20, help="floors per kind (default 20)")
    ap.add_argument(
        "--reps", type=int, default=3, help="repetitions per floor; the least time counts (default 3)"
    )
    ap.add_argument("--kinds", nargs="+", choices=FLOOR_KINDS, default=list(KINDS))
    args = ap.parse_args(argv)
    if args.n < 1 or args.reps < 1:
        raise ValueError(f"--n and --reps must be positive, got {args.n} and {args.reps}")
    sides = {"this": Side(segplan), "base": Side(load_base(args.base))}
    print(f"load average before: {os.getloadavg()}", flush=True)
    for side in sides.values():  # warm both
        side.whole(side.kind_floor(args.kinds[0], 0))
    rows = {}
    for kind in args.kinds:
        for i in range(args.n):
            best = {}
            costs = {}
            for r in range(args.reps):
                for name in ("this", "base") if r % 2 == 0 else ("base", "this"):
                    side = sides[name]
                    dt, cost, got = side.whole(side.kind_floor(kind, i))
                    costs[name] = cost
                    rt = side.refine(got)
                    w, f = best.get((name, "whole"), dt), best.get((name, "refine"), rt)
                    best[(name, "whole")], best[(name, "refine")] = min(w, dt), min(f, rt)
            if costs["this"] != costs["base"]:
                raise AssertionError(f"{kind} {i}: plans differ ({costs['this']!r} vs {costs['base']!r})")
            rows.setdefault(kind, []).append(best)
    print(f"load average after: {os.getloadavg()}")
    print(
        "CPU ms per floor, least of the repetitions: median / 90th percentile / sum;"
        " ratio: median of this/base"
    )
    groups = {**rows, "all": [b for k in rows for b in rows[k]]}
    for kind, bests in groups.items():
        for stage in ("whole", "refine"):
            parts = []
            for name in ("base", "this"):
                v = sorted(1e3 * b[(name, stage)] for b in bests)
                parts.append(
                    f"{name} {statistics.median(v):6.1f} / {v[int(0.9 * len(v))]:6.1f} / {sum(v):7.0f}"
                )
            ratio = statistics.median(b[("this", stage)] / b[("base", stage)] for b in bests)
            print(f"{kind:10s} {stage:7s} " + " | ".join(parts) + f" | ratio {ratio:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
