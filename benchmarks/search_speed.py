"""Planning speed per shipped scenario (not a timed test).

For every scenario in ``scenarios/`` (and a few random worlds of ten obstacles) and every
heuristic, plan ``--runs`` times and report the median planning time (CPU time of this
process, ``time.process_time``: less inflated by other processes than the wall-clock
median beside it, though not immune, since caches, SMT siblings and a virtual machine's
stolen time are shared), the expansions, the generated nodes, the LONGD cost and the
collision checks per second (distinct union-obstacle pairs decided by the bounding box, a
certain hit or the full test of :func:`segplan.floor.collision.collides`; ``exact/s`` counts
only the latter).

Target: a plan on an industrial floor of about ten obstacles in under 50 ms
median on one core.

One core: the script sets ``OMP_NUM_THREADS``, ``OPENBLAS_NUM_THREADS`` and
``MKL_NUM_THREADS`` to 1 (unless already set) before numpy loads. Off-line work is not
timed: the fitted coefficients of the heuristic reference system
(:data:`segplan.model.frame.HEURISTIC_FIT`) and the calibration of formula [2] are read
from the package's data file (:mod:`segplan.model.constants`) when segplan is imported,
and the cost of that read is printed separately; each scenario and heuristic is then planned
once untimed (it also caches ``d_s`` of heuristic (c), per scenario) before the timed
runs. The machine's load average is printed with the numbers (CPU time is the robust
measure on a loaded machine, but caches and frequency are shared).

Usage::

    python benchmarks/search_speed.py [--runs 7] [--heuristics a c] [--csv out.csv]
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import segplan  # noqa: E402
from segplan import NoPathError, plan_scenario, random_world  # noqa: E402
from segplan.model import constants  # noqa: E402
from segplan.model.frame import HeuristicFit  # noqa: E402
from segplan.studies.progress import progress  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def offline_costs() -> dict:
    """CPU seconds of reading the fitted constants (heuristic frame, formula [2]) from the
    package's data file, measured again here: segplan did it once, at import, before any clock.
    """
    c0 = time.process_time()
    values = json.loads(constants.PATH.read_text(encoding="utf-8"))
    HeuristicFit.from_values(values["heuristic_frame"])
    return {"constants_s": time.process_time() - c0}


def bench(scenario, heuristic: str, runs: int, warmup: bool = True, **options) -> dict:
    """Median time and counters of ``runs`` plans of one scenario.

    With ``warmup`` one untimed plan runs first (per-scenario caches: ``d_s``).
    """
    if warmup:
        try:
            plan_scenario(scenario, heuristic=heuristic, **{"planner": "paper", **options})
        except NoPathError:
            pass
    times, cpu, result, error = [], [], None, None
    for _ in range(runs):
        t0, c0 = time.perf_counter(), time.process_time()
        try:
            result = plan_scenario(scenario, heuristic=heuristic, **{"planner": "paper", **options})
        except NoPathError as exc:
            error = exc
        cpu.append(time.process_time() - c0)
        times.append(time.perf_counter() - t0)
    med = statistics.median(cpu)
    row = {
        "scenario": scenario.name,
        "obstacles": len(scenario.obstacles),
        "h": heuristic,
        "median_ms": 1e3 * med,
        "wall_ms": 1e3 * statistics.median(times),
    }
    if result is None:
        row.update(found=False, expanded=error.expanded, generated=error.generated, cost=float("nan"))
        row.update(checks_per_s=float("nan"), exact_per_s=float("nan"), nodes=0)
        return row
    row.update(found=True, expanded=result.expanded, generated=result.generated, cost=result.cost)
    row.update(nodes=len(result.nodes))
    row.update(checks_per_s=result.collision_checks / med, exact_per_s=result.exact_checks / med)
    return row


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--runs", type=int, default=7, help="plans per scenario and heuristic (median)")
    parser.add_argument("--heuristics", nargs="+", default=["a", "b", "c"], choices=["a", "b", "c"])
    parser.add_argument("--random", type=int, default=5, help="random worlds of ten obstacles (seeds 0..N-1)")
    parser.add_argument("--csv", help="also write the table to this CSV file")
    args = parser.parse_args(argv)
    threads = ", ".join(f"{v}={os.environ.get(v)}" for v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS"))
    print(f"load average at start: {'/'.join(f'{x:.2f}' for x in os.getloadavg())} (1/5/15 min); {threads}")
    off = offline_costs()
    print(
        f"one-off off-line work, at import and not in the times below: reading the fitted constants "
        f"(heuristic frame, formula [2]) {off['constants_s']:.4f} s (CPU)"
    )
    print("each scenario and heuristic: one untimed warm-up plan, then the timed runs (CPU time)\n")
    scenarios = [segplan.load_scenario(p) for p in sorted((ROOT / "scenarios").glob("*.json"))]
    scenarios += [random_world(seed, 10) for seed in range(args.random)]
    rows = []
    header = (
        f"{'scenario':38s} {'obst':>4s} {'h':>1s} {'found':>5s} {'cpu ms':>7s} {'wall ms':>7s} {'exp':>5s} "
        f"{'gen':>5s} {'nodes':>5s} {'LONGD m':>8s} {'checks/s':>9s} {'exact/s':>8s}"
    )
    print(header)
    print("-" * len(header))
    todo = [(sc, h) for sc in scenarios for h in args.heuristics]
    bar = progress(todo, desc="search speed", unit="floor x h'")
    for sc, h in bar:
        r = bench(sc, h, args.runs)
        rows.append(r)
        bar.write(  # above the bar on a terminal, a plain line elsewhere
            f"{r['scenario'][:38]:38s} {r['obstacles']:4d} {h:>1s} {str(r['found']):>5s} "
            f"{r['median_ms']:7.1f} {r['wall_ms']:7.1f} "
            f"{r['expanded']:5d} {r['generated']:5d} {r['nodes']:5d} {r['cost']:8.2f} "
            f"{r['checks_per_s']:9.0f} {r['exact_per_s']:8.0f}"
        )
    floors = [r for r in rows if r["found"] and r["obstacles"] >= 8 and r["h"] == "a"]
    if floors:
        worst = max(r["median_ms"] for r in floors)
        print(f"\nten-obstacle floors, heuristic a: worst median CPU time {worst:.1f} ms (target < 50 ms)")
    print(f"load average at end: {'/'.join(f'{x:.2f}' for x in os.getloadavg())} (1/5/15 min)")
    if args.csv:
        import csv

        with open(args.csv, "w", newline="") as fh:
            writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
