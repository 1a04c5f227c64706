"""The stress floor (issue 25): time and peak memory of the default planner on 1 km^2, 5000 obstacles.

Not a timed test. For each floor of ``--floors`` (:func:`segplan.studies.floor_kinds.stress_floor`,
1000 x 1000 m, 5000 rectangles, start and goal in opposite corners), a fresh process builds
the floor, then calls ``segplan.plan_scenario(sc)`` with the defaults (``time_limit`` 10 s)
once, and reports:

* the plan: found, its length (LONGD [1], m), nodes, whether the refinement was stopped by
  the time limit;
* the time of the call (wall clock and the process's CPU time; their ratio is the CPU share
  the process had: below 0.9 the wall times are inflated by the machine's load) and of its
  stages: the workspace (``context.workspace_of``), the paper's search, the lattice, the
  refinement (``default``'s ``paper_search``, ``lattice_stage``, ``refine_with``, wrapped);
* the peak resident memory of the process (``ru_maxrss``) and its resident memory once the
  floor is built, before planning.

Targets of issue 25: at most 5 s and 500 MB per plan. The results, with when, where (load
average, nice value) and at which commit, go to ``--out`` (JSON); the stored run is
``benchmarks/results/stress_floor.json``.

``--cells-per-box`` instead measures the obstacles' bucket grid
(:data:`segplan.floor.buckets.CELLS_PER_BOX`): one plan per value and floor, its CPU time;
the grid changes no decision, so every value must give the same plan, bit for bit (checked).

Usage::

    nice -n 19 python benchmarks/stress_floor.py [--floors 0 1 2] [--out benchmarks/results/stress_floor.json]
    nice -n 19 python benchmarks/stress_floor.py --cells-per-box 0.25 0.5 1 2 4 --floors 0
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: The targets of issue 25: seconds and MB of one plan.
TARGET_SECONDS, TARGET_MB = 5.0, 500.0


def rss_mb() -> float:
    """Peak resident memory of this process so far (MB; Linux reports kB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def one(index: int, cells_per_box: float | None) -> dict:
    """Build stress floor ``index`` and plan on it once, in this process (module docstring)."""
    import segplan
    import segplan.planning.context as context
    import segplan.planning.default as default
    from segplan.floor import buckets
    from segplan.studies.floor_kinds import stress_floor

    if cells_per_box is not None:
        buckets.CELLS_PER_BOX = cells_per_box
    stages: dict = {}

    def timed(module, name: str, label: str) -> None:
        f = getattr(module, name)

        def wrapper(*args, **kwargs):
            t, c = time.perf_counter(), time.process_time()
            try:
                return f(*args, **kwargs)
            finally:
                s = stages.setdefault(label, {"seconds": 0.0, "cpu_seconds": 0.0})
                s["seconds"] += time.perf_counter() - t
                s["cpu_seconds"] += time.process_time() - c

        setattr(module, name, wrapper)

    timed(context, "workspace_of", "workspace")
    timed(default, "paper_search", "paper")
    timed(default, "lattice_stage", "lattice")
    timed(default, "refine_with", "refine")
    sc = stress_floor(index)
    out = {
        "index": index,
        "floor": sc.name,
        "obstacles": len(sc.obstacles),
        "rss_floor_mb": round(rss_mb(), 1),
    }
    t, c = time.perf_counter(), time.process_time()
    try:
        plan = segplan.plan_scenario(sc)
    except segplan.NoPathError as exc:
        out.update(found=False, reason=exc.reason)
    else:
        out.update(
            found=True,
            cost_m=plan.cost,
            cost_hex=float(plan.cost).hex(),
            nodes=len(plan.nodes),
            refinement_stopped=plan.refinement.stopped,
        )
    seconds, cpu = time.perf_counter() - t, time.process_time() - c
    out.update(
        seconds=round(seconds, 3),
        cpu_seconds=round(cpu, 3),
        cpu_share=round(cpu / seconds, 3),
        stages={k: {q: round(v, 3) for q, v in s.items()} for k, s in stages.items()},
        peak_rss_mb=round(rss_mb(), 1),
    )
    return out


def provenance(argv: list[str]) -> dict:
    """When, where and at which commit (:func:`segplan.studies.ompl_runner.provenance`, the
    studies' one record, without its OMPL fields)."""
    from segplan.studies import ompl_runner

    meta = ompl_runner.provenance(argv, None, None)
    for key in ("fairness", "simplifier", "ompl", "jobs", "config", "harness_version"):
        meta.pop(key, None)
    return meta


def child(index: int, cells_per_box: float | None) -> dict:
    """:func:`one` in a fresh process (its own peak memory)."""
    cmd = [sys.executable, __file__, "--one", str(index)]
    if cells_per_box is not None:
        cmd += ["--cells-per-box", str(cells_per_box)]
    env = dict(
        os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))
    )
    out = subprocess.run(cmd, capture_output=True, text=True, check=True, env=env)
    return json.loads(out.stdout.splitlines()[-1])


def main(argv: list[str] | None = None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--floors", type=int, nargs="+", default=[0, 1, 2], help="stress floor indices")
    parser.add_argument("--cells-per-box", type=float, nargs="+", help="measure the bucket grid's cell size")
    parser.add_argument("--out", metavar="JSON", help="store the results here (with provenance)")
    parser.add_argument("--one", type=int, help=argparse.SUPPRESS)  # the child process
    args = parser.parse_args(argv)
    if args.one is not None:
        print(json.dumps(one(args.one, args.cells_per_box[0] if args.cells_per_box else None)))
        return {}
    result = provenance(["benchmarks/stress_floor.py", *(sys.argv[1:] if argv is None else argv)])
    result["targets"] = {"seconds": TARGET_SECONDS, "peak_rss_mb": TARGET_MB}
    runs = []
    for value in args.cells_per_box or [None]:
        for index in args.floors:
            r = child(index, value)
            r["cells_per_box"] = value
            runs.append(r)
            head = f"{r['floor']}" + (f" cells/box {value:g}" if value is not None else "")
            stages = " ".join(
                f"{k} {s['seconds']:.2f} ({s['cpu_seconds']:.2f})" for k, s in r["stages"].items()
            )
            what = f"{r['cost_m']:.3f} m, {r['nodes']} nodes" if r["found"] else f"no plan ({r['reason']})"
            print(
                f"{head}: {r['seconds']:.2f} s (CPU {r['cpu_seconds']:.2f} s, share {r['cpu_share']:.2f}), "
                f"peak {r['peak_rss_mb']:.0f} MB; {what}; stages s (CPU s): {stages}",
                flush=True,
            )
    result["runs"] = runs
    result["machine"]["load_average_after"] = [round(x, 2) for x in os.getloadavg()]
    if args.cells_per_box:
        for index in args.floors:
            plans = {r["cost_hex"] if r["found"] else None for r in runs if r["index"] == index}
            if len(plans) != 1:
                raise SystemExit(f"stress floor {index}: the cell size changed the plan ({plans})")
    else:
        result["met"] = all(
            r["found"] and r["seconds"] <= TARGET_SECONDS and r["peak_rss_mb"] <= TARGET_MB for r in runs
        )
    if args.out:
        Path(args.out).write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
    return result


if __name__ == "__main__":
    main()
