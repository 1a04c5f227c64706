"""Planning speed per shipped scenario (issue 3; not a timed test).

For every scenario in ``scenarios/`` (and a few random worlds of ten obstacles) and every
heuristic, plan ``--runs`` times and report the median planning time (CPU time of this
process, ``time.process_time``, the one-core measure that other processes on the
machine do not inflate; the wall-clock median beside it), the expansions,
the generated nodes, the LONGD cost and the collision checks per second (union-obstacle
pairs decided by the bounding box, a certain hit or the full test of
:func:`segplan.collision.collides`; ``exact/s`` counts only the latter).

Target (issue 3): a plan on an industrial floor of about ten obstacles in under 50 ms
median on one core.

Usage::

    python benchmarks/search_speed.py [--runs 7] [--heuristics a c] [--csv out.csv]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import segplan
from segplan import NoPathError, plan_scenario, random_world

ROOT = Path(__file__).resolve().parent.parent


def bench(scenario, heuristic: str, runs: int, **options) -> dict:
    """Median time and counters of ``runs`` plans of one scenario."""
    times, cpu, result, error = [], [], None, None
    for _ in range(runs):
        t0, c0 = time.perf_counter(), time.process_time()
        try:
            result = plan_scenario(scenario, heuristic=heuristic, **options)
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
    scenarios = [segplan.load_scenario(p) for p in sorted((ROOT / "scenarios").glob("*.json"))]
    scenarios += [random_world(seed, 10) for seed in range(args.random)]
    rows = []
    header = (
        f"{'scenario':38s} {'obst':>4s} {'h':>1s} {'found':>5s} {'cpu ms':>7s} {'wall ms':>7s} {'exp':>5s} "
        f"{'gen':>5s} {'nodes':>5s} {'LONGD m':>8s} {'checks/s':>9s} {'exact/s':>8s}"
    )
    print(header)
    print("-" * len(header))
    for sc in scenarios:
        for h in args.heuristics:
            r = bench(sc, h, args.runs)
            rows.append(r)
            print(
                f"{r['scenario'][:38]:38s} {r['obstacles']:4d} {h:>1s} {str(r['found']):>5s} "
                f"{r['median_ms']:7.1f} {r['wall_ms']:7.1f} "
                f"{r['expanded']:5d} {r['generated']:5d} {r['nodes']:5d} {r['cost']:8.2f} "
                f"{r['checks_per_s']:9.0f} {r['exact_per_s']:8.0f}",
                flush=True,
            )
    floors = [r for r in rows if r["found"] and r["obstacles"] >= 8 and r["h"] == "a"]
    if floors:
        worst = max(r["median_ms"] for r in floors)
        print(f"\nten-obstacle floors, heuristic a: worst median CPU time {worst:.1f} ms (target < 50 ms)")
    if args.csv:
        import csv

        with open(args.csv, "w", newline="") as fh:
            writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
