"""The defaults of ``reverse_factor`` and ``cusp_penalty`` (issue 26): plans of a robot that may reverse.

For each pair of values, the default planner (``segplan.plan_scenario``, 60 s) on a small
set of floors that need or invite reversing, with the robot's ``reverse`` set:

* ``bay``: the shipped ``dead_end_bay`` (parked nose-in, goal elsewhere: needs one cusp);
* ``park-k``: the same floor, the robot outside, the goal inside the bay facing out
  (reverse parking: it must back in), three starts;
* ``turn-k``: a corridor whose free width for the robot's segment (the walls enlarged by
  its half-width) is 2.6 or 3.2 m (about two turning radii of the robot, 3 m), start and
  goal in it 3 m apart facing opposite ways (a K-turn);
* ``natural-k``: chapter 9's random floors 0-9 (``segplan.studies.floors``), which a forward
  robot solves: what enabling reverse costs there.

Prints, per pair: floors solved, the median and the largest CPU time per plan (seconds,
``time.process_time``, a warm process), the total front-wheel length (LONGD, summed over
the floors every pair solved), cusps in all, and the share of the length driven backwards.

    python benchmarks/reverse_defaults.py
"""

from __future__ import annotations

import dataclasses
import math
import statistics
import sys
import time

import segplan
from segplan import Robot, load_scenario
from segplan.floor.scenario import make_scenario
from segplan.planning.plan import union_longd
from segplan.studies.floors import random_floor

FACTORS = (1.0, 1.25, 1.5)
PENALTIES = (0.5, 2.0, 4.0)
#: Seconds per plan: far above the slowest (the K-turns, a few seconds of CPU), so that no
#: outcome depends on the machine's load.
TIME_LIMIT = 60.0


def floors() -> dict:
    """The floor set (module docstring), every robot with ``reverse=True``."""
    bay = load_scenario("dead_end_bay")
    out = {"bay": bay}
    inside = (10.0, 3.3, math.pi / 2)  # in the bay, facing out (north)
    for k, start in enumerate([(4.0, 8.0, 0.0), (15.0, 9.0, math.pi), (10.0, 9.5, 0.0)]):
        out[f"park-{k}"] = dataclasses.replace(bay, start=segplan.Pose(*start), goal=segplan.Pose(*inside))
    robot = Robot(1.5, 0.45, math.radians(45), reverse=True)
    for k, w in enumerate((2.6, 3.2)):
        hi = 4.0 + w + 2 * robot.half_width
        walls = [[[0, 0], [30, 0], [30, 4.0], [0, 4.0]], [[0, hi], [30, hi], [30, 11], [0, 11]]]
        y = 0.5 * (4.0 + hi)
        out[f"turn-{k}"] = make_scenario(robot, (10.0, y, 0.0), (13.0, y, math.pi), walls, (0, 0, 30, 11))
    for i in range(10):
        sc = random_floor("natural", i)
        out[f"natural-{i}"] = dataclasses.replace(sc, robot=dataclasses.replace(sc.robot, reverse=True))
    return out


def run(sc, factor: float, penalty: float):
    """``(plan or None, CPU seconds)``."""
    t = time.process_time()
    try:
        options = {"reverse_factor": factor, "cusp_penalty": penalty}
        plan = segplan.plan_scenario(sc, time_limit=TIME_LIMIT, lattice=options)
    except segplan.NoPathError:
        plan = None
    return plan, time.process_time() - t


def main() -> int:
    fl = floors()
    for sc in fl.values():  # warm: primitives, tables
        run(sc, 1.25, 2.0)
    rows = {}
    for f in FACTORS:
        for c in PENALTIES:
            rows[f, c] = {name: run(sc, f, c) for name, sc in fl.items()}
    common = [n for n in fl if all(rows[k][n][0] is not None for k in rows)]
    head = ("factor", "cusp/L", "solved", "cpu med", "cpu max", "length", "cusps", "back %")
    print("{:>6} {:>6} {:>6} {:>8} {:>8} {:>8} {:>5} {:>6}".format(*head))
    for (f, c), res in rows.items():
        solved = [n for n, (p, _) in res.items() if p is not None]
        cpu = [t for _, t in res.values()]
        length = sum(res[n][0].cost for n in common)
        cusps = sum(len(res[n][0].cusps) for n in common)
        back = sum(
            union_longd(u)
            for n in common
            for u, d in zip(res[n][0].unions, res[n][0].link_directions, strict=True)
            if d < 0
        )
        print(
            f"{f:6.2f} {c:6.1f} {len(solved):3d}/{len(fl):2d} {statistics.median(cpu):8.3f} {max(cpu):8.3f} "
            f"{length:8.2f} {cusps:5d} {100 * back / length:6.1f}"
        )
        sys.stdout.flush()
    for key in rows:
        print(f"per floor (factor {key[0]:g}, penalty {key[1]:g} L):")
        for n, (p, t) in rows[key].items():
            print(
                f"  {n:10s} {'-' if p is None else f'{p.cost:7.2f} m, {len(p.cusps)} cusps'}  cpu {t:.3f} s"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
