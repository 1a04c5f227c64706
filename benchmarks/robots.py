"""The default planner on robots other than the book's (L = 1 m, 45 deg): a robustness probe.

Beyond the issue's floors (not a timed test, not in CI). Floor ``i`` draws, from
``numpy.random.default_rng([4242, i])``:

* a robot: ``L`` in {0.5, 1, 1.6, 2.5} m, steering in {25, 35, 45, 60} deg, half-width
  0.15-0.5 ``L``;
* a floor of 10-30 ``L`` by 8-18 ``L`` with 2-13 convex obstacles of circumscribed radius
  0.4-2 ``L`` (:func:`segplan.random_world`, any start and goal heading; fewer obstacles
  when they do not fit).

Each floor is planned once by :func:`segplan.plan_scenario` with its defaults (the first plan
for a robot includes building its primitive sets, as a user's first call would); the plan is
checked by the dense oracle (:func:`segplan.measure_scenario_path`). With ``--ompl SECONDS``,
OMPL's BIT* (Dubins space, radius ``R``, seed 1, in a fresh process) is the feasibility oracle
and length reference (optional dependency), run through the studies' one executor
(:func:`segplan.studies.executor.run_jobs`: one run per free core, ``--jobs`` caps it, or a
Dask cluster with ``--scheduler``; a run starved of CPU is refused and run again; with
``--out`` the accepted runs are journalled beside it, so an interrupted probe resumes). The
plan is compared with OMPL's path after its ``PathSimplifier`` (``ratio``: like with like,
the default planner refines) and with the raw path (``ratio_raw``). ``--out`` writes a CSV
and, next to it, a JSON of how, when and where it was measured
(:func:`segplan.studies.ompl_runner.provenance`, with the fairness rule).

Usage::

    python benchmarks/robots.py [--n 80] [--ompl 3] [--jobs N] [--out benchmarks/results/robots.csv]
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import json
import math
import os
import sys
from pathlib import Path

import numpy as np
import pandas as pd

import segplan
from segplan.studies import ompl_runner as om
from segplan.studies import peers
from segplan.studies import robustness as rb
from segplan.studies.executor import run_jobs

#: Lengths (m), steering angles (deg) drawn per floor.
LENGTHS = (0.5, 1.0, 1.6, 2.5)
STEERING = (25.0, 35.0, 45.0, 60.0)


def robot_floor(i: int) -> segplan.Scenario | None:
    """Floor ``i`` of the probe (module docstring); None if no obstacle layout fits."""
    rng = np.random.default_rng([4242, i])
    L = float(rng.choice(LENGTHS))
    steer = math.radians(float(rng.choice(STEERING)))
    robot = segplan.Robot(L=L, half_width=float(rng.uniform(0.15, 0.5)) * L, max_steer=steer)
    bounds = (0.0, 0.0, float(rng.uniform(10, 30)) * L, float(rng.uniform(8, 18)) * L)
    n = int(rng.integers(2, 14))
    for _ in range(50):
        try:
            seed = int(rng.integers(1 << 30))
            spread = math.pi  # any headings
            sc = segplan.random_world(seed, n, bounds, robot, radius=(0.4 * L, 2 * L), heading_spread=spread)
            return dataclasses.replace(sc, name=f"robot-{i:03d}")
        except ValueError:  # ScenarioError included: fewer obstacles
            n = max(1, n - 1)
    return None


def bitstar(job: tuple, budget: float) -> dict:
    """OMPL's BIT* on floor ``job = (index, scenario)``, seed 1, in a fresh process: its row
    (:func:`segplan.studies.ompl_runner.solve_ompl_isolated`) without the poses."""
    _, sc = job
    row = om.solve_ompl_isolated(sc, "BITstar", budget, 1)
    row.pop("poses")
    row.pop("simplified_poses")
    return row


def main(argv: list[str] | None = None) -> pd.DataFrame:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=80, help="floors")
    parser.add_argument("--ompl", type=float, default=0.0, metavar="SECONDS", help="BIT* budget (0: no OMPL)")
    parser.add_argument(
        "--jobs", type=int, help="at most this many OMPL runs at a time (default: free cores)"
    )
    parser.add_argument("--scheduler", metavar="ADDRESS", help="a Dask scheduler: run OMPL on that cluster")
    parser.add_argument("--out", metavar="CSV")
    args = parser.parse_args(argv)
    if args.ompl > 0 and not om.ompl_available():
        parser.error("--ompl needs OMPL's Python bindings (an optional dependency)")
    meta = om.provenance(sys.argv if argv is None else ["benchmarks/robots.py", *argv], None, args.jobs)
    rows, floors = [], []
    for i in range(args.n):
        sc = robot_floor(i)
        if sc is None:
            continue
        row, _ = rb.solve_segplan(sc, "robots")
        r = sc.robot
        row.update(index=i, L=r.L, steer_deg=math.degrees(r.max_steer), R=r.min_turning_radius)
        rows.append(row)
        floors.append((i, sc))
        print(
            f"{i:3d} L={r.L:g} steer={row['steer_deg']:.0f} "
            f"{'plan' if row['solved'] else 'no plan (' + row['reason'] + ')'} {1e3 * row['seconds']:.0f} ms",
            flush=True,
        )
    if args.ompl > 0:
        journal = peers.journal_path(args.out) if args.out else None
        runs = run_jobs(
            functools.partial(bitstar, budget=args.ompl),
            floors,
            key=lambda job: f"{job[1].name}|BITstar|{args.ompl:g}|1",
            journal=journal,
            cap=args.jobs,
            scheduler=args.scheduler,
            desc="OMPL",
        )
        for row, (_, sc) in zip(rows, floors, strict=True):
            o = runs[f"{sc.name}|BITstar|{args.ompl:g}|1"]
            simple = bool(o["solved"] and o["simplified_valid"])
            row.update(ompl_solved=bool(o["valid"]) or simple, ompl_front=o["front_length"])
            row.update(ompl_simplified_front=o["simplified_front_length"] if simple else math.nan)
            row.update(ompl_cpu_share=o["cpu_share"], ompl_attempts=o["attempts"])
            ok = row["solved"] and row["valid"]
            row["ratio"] = row["front_length"] / row["ompl_simplified_front"] if ok and simple else math.nan
            row["ratio_raw"] = row["front_length"] / o["front_length"] if ok and o["valid"] else math.nan
    t = pd.DataFrame(rows)
    solved = t[t.solved]
    print(
        f"solved {len(solved)} of {len(t)}, invalid {int((~solved.valid).sum())}; time median "
        f"{1e3 * t.seconds.median():.0f} ms, 95th percentile {1e3 * t.seconds.quantile(0.95):.0f} ms"
    )
    if args.ompl > 0:
        o = t[t.ompl_solved]
        print(
            f"OMPL solved {len(o)}; segplan solved {int(o.solved.sum())} of them; length ratio to OMPL "
            f"simplified: median {t.ratio.median():.3f}, largest {t.ratio.max():.3f} (raw: median "
            f"{t.ratio_raw.median():.3f}); OMPL CPU share min {t.ompl_cpu_share.min():.2f}"
        )
    if args.out:
        out = Path(args.out)
        t.to_csv(out, index=False)
        meta["load_average_after"] = list(os.getloadavg())
        out.with_suffix(".json").write_text(json.dumps(meta, indent=1) + "\n", encoding="utf-8")
        if args.ompl > 0:
            peers.journal_path(out).unlink(missing_ok=True)
    return t


if __name__ == "__main__":
    main()
