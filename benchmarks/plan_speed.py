"""Plan time of the default planner on fixed random floors (issue 12 targets; not a timed test).

Floors from :func:`segplan.random_world`: 20 x 12 m, 4-9 convex obstacles, L = 1 m, 45 deg
steering, start in the left quarter and goal in the right quarter; ``--n`` floors with any
headings (spread pi) and ``--n`` with natural ones (within 60 deg of +x), fixed seeds. Each
floor is planned once to warm up and once timed (wall clock, ``Plan.seconds`` counts search
and refinement); every plan is checked by the dense oracle (:func:`segplan.measure_scenario_path`).
``--large`` instead plans across a 160 x 96 m floor with 512 obstacles (``--n`` seeds).

The machine is shared, so the numbers are noisy: the load average is printed with them.

Usage::

    python benchmarks/plan_speed.py [--n 15] [--large] [--planner lattice] [--csv out.csv]
"""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np

import segplan

DEG = math.pi / 180.0


def floors(n: int, large: bool):
    """``(kind, seed, scenario)`` of the benchmark's floors."""
    robot = segplan.Robot(1.0, 0.0, 45 * DEG)
    out = []
    if large:
        for seed in range(n):
            sc = segplan.random_world(seed, 512, (0.0, 0.0, 160.0, 96.0), robot, radius=(0.5, 2.5))
            out.append(("large", seed, sc))
        return out
    for kind, spread in (("any", math.pi), ("natural", 60 * DEG)):
        for seed in range(n):
            k = 4 + seed % 6
            sc = segplan.random_world(
                1000 + seed, k, (0.0, 0.0, 20.0, 12.0), robot, radius=(0.4, 1.5), heading_spread=spread
            )
            out.append((kind, seed, sc))
    return out


def main(argv: list[str] | None = None) -> list[dict]:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=15, help="floors of each kind")
    parser.add_argument("--large", action="store_true", help="the 160 x 96 m floor with 512 obstacles")
    parser.add_argument("--planner", default="lattice")
    parser.add_argument("--csv", metavar="PATH")
    args = parser.parse_args(argv)
    rows = []
    for kind, seed, sc in floors(args.n, args.large):
        try:
            segplan.plan_scenario(sc, planner=args.planner)
            t = time.perf_counter()
            p = segplan.plan_scenario(sc, planner=args.planner)
            wall = time.perf_counter() - t
            m = segplan.measure_scenario_path(segplan.plan_poses(p), sc)
            valid = not m.collides and p.nodes[-1] == sc.goal
            rows.append(dict(kind=kind, seed=seed, solved=True, valid=valid, s=wall, cost=p.cost))
        except segplan.NoPathError as e:
            rows.append(dict(kind=kind, seed=seed, solved=False, valid=True, s=math.nan, cost=math.nan))
            print(f"{kind} {seed}: no path ({e.reason})")
    for kind in sorted({r["kind"] for r in rows}):
        rs = [r for r in rows if r["kind"] == kind and r["solved"]]
        t = np.array([r["s"] for r in rs])
        print(
            f"{kind}: solved {len(rs)}/{sum(r['kind'] == kind for r in rows)}, invalid "
            f"{sum(not r['valid'] for r in rs)}; time median {1e3 * np.median(t):.0f} ms, "
            f"p95 {1e3 * np.percentile(t, 95):.0f} ms, max {1e3 * t.max():.0f} ms; "
            f"sum of costs {sum(r['cost'] for r in rs):.3f} m"
        )
    t = np.array([r["s"] for r in rows if r["solved"]])
    print(
        f"all: median {1e3 * np.median(t):.0f} ms, p95 {1e3 * np.percentile(t, 95):.0f} ms; "
        f"load average {os.getloadavg()}"
    )
    if args.csv:
        with open(args.csv, "w", encoding="utf-8") as f:
            f.write("kind,seed,solved,valid,seconds,cost\n")
            for r in rows:
                f.write(f"{r['kind']},{r['seed']},{r['solved']},{r['valid']},{r['s']!r},{r['cost']!r}\n")
    return rows


if __name__ == "__main__":
    main()
