"""Maps in (issue 27): load time of a 2000 x 3000-cell ROS map and the free space its cover loses.

Not a timed test. A synthetic office map (:func:`office_map`, deterministic) of 2000 rows x
3000 columns at 5 cm (100 x 150 m) is written as a ``map_server`` PGM and YAML, then:

* ``segplan.load_ros_map`` is timed ``--runs`` times (wall clock, ``time.perf_counter``,
  reading the files, the cells, the convex cover, the floor); target: at most 2 s;
* for tolerances of 0 to 3 cells, the cover's convex pieces and vertices, and the free
  space it loses: the fraction of the free cells that some piece touches
  (:meth:`segplan.Floor.free_space_loss`, the cells' open squares meeting a piece);
* with ``--plan``, one plan across the building (L = 1.2 m, half-width 0.35 m, 45 deg).

The office: unknown (grey 205) around the building, 15 cm walls (3 cells) with 2 m doors
on a 12.5 x 15-20 m grid of rooms, six slanted walls 12.5 m long, forty pieces of
furniture, ragged wall edges as SLAM leaves them (30 % of the cells along every wall
occupied), specks (5e-5 of the free cells) and unknown pockets (2e-5 of them, 5 x 5
cells). The results, with when, where and at which commit they were measured, go to
``benchmarks/results/maps.json`` (``--out``).

Usage::

    python benchmarks/maps.py [--runs 5] [--plan] [--out benchmarks/results/maps.json]
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import scipy
from scipy import ndimage

import segplan

ROOT = Path(__file__).resolve().parents[1]
RESOLUTION = 0.05
ORIGIN = (-10.0, -5.0)
#: Start and goal of ``--plan`` (x, y in m, theta in deg): two rooms apart, through doors.
START, GOAL = (8.0, 20.0, 0.0), (25.0, 45.0, 90.0)


def office_map(rows: int = 2000, cols: int = 3000, seed: int = 0) -> np.ndarray:
    """A synthetic SLAM-like office map: grey levels (uint8, row 0 the top row), as map_server writes.

    254 free, 0 occupied, 205 unknown; the module docstring lists what is in it (lengths in
    cells for 2000 rows, scaled with ``rows / 2000`` for other sizes; walls stay 3 cells).
    """
    rng = np.random.default_rng(seed)
    f = rows / 2000.0

    def n(cells: float) -> int:
        return max(2, round(cells * f))

    img = np.full((rows, cols), 205, dtype=np.uint8)
    m, t, door = n(40), 3, n(40)  # margin of unknown, wall thickness, door width (cells)
    img[m : rows - m, m : cols - m] = 254
    occ = np.zeros((rows, cols), dtype=bool)
    occ[m : m + t, m : cols - m] = occ[rows - m - t : rows - m, m : cols - m] = True
    occ[m : rows - m, m : m + t] = occ[m : rows - m, cols - m - t : cols - m] = True
    for x in range(m + n(250), cols - m - n(100), n(250)):  # walls between rooms, a door every 300 rows
        occ[m : rows - m, x : x + t] = True
        for y in range(m + n(100), rows - m - door, n(300)):
            occ[y : y + door, x : x + t] = False
    for y in range(m + n(400), rows - m - n(100), n(400)):  # corridors' walls, a door in every room
        occ[y : y + t, m : cols - m] = True
        for x in range(m + n(100), cols - m - door, n(250)):
            occ[y : y + t, x : x + door] = False
    for _ in range(6):  # slanted walls, 2 cells thick
        x0, y0 = rng.integers(m + n(50), cols - m - n(300)), rng.integers(m + n(50), rows - m - n(300))
        a = rng.uniform(0.0, math.pi)
        s = np.linspace(0.0, n(250), 4 * n(250))
        xs, ys = (x0 + s * math.cos(a)).astype(int), (y0 + s * math.sin(a)).astype(int)
        for dx in (0, 1):
            for dy in (0, 1):
                occ[ys + dy, xs + dx] = True
    for _ in range(40):  # furniture
        x, y = rng.integers(m, cols - m - n(40)), rng.integers(m, rows - m - n(40))
        occ[y : y + rng.integers(n(5), n(40) + 1), x : x + rng.integers(n(5), n(40) + 1)] = True
    edge = ndimage.binary_dilation(occ) & ~occ  # ragged edges
    occ |= edge & (rng.random((rows, cols)) < 0.3)
    inside = img == 254
    occ |= (rng.random((rows, cols)) < 5e-5) & inside  # specks
    pockets = ndimage.binary_dilation((rng.random((rows, cols)) < 2e-5) & inside, iterations=2)
    img[pockets & inside] = 205
    img[occ] = 0
    return img


def write_map(folder: Path, img: np.ndarray, name: str = "office") -> Path:
    """Write ``img`` as ``name.pgm`` (P5) and ``name.yaml`` (map_server keys) in ``folder``."""
    rows, cols = img.shape
    (folder / f"{name}.pgm").write_bytes(b"P5\n%d %d\n255\n" % (cols, rows) + img.tobytes())
    yaml = folder / f"{name}.yaml"
    yaml.write_text(
        f"image: {name}.pgm\nresolution: {RESOLUTION}\norigin: [{ORIGIN[0]}, {ORIGIN[1]}, 0.0]\n"
        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
        encoding="utf-8",
    )
    return yaml


def provenance(argv: list[str]) -> dict:
    """When, where and at which commit: date (UTC), machine, load, versions, commit, clean tree."""

    def git(*args: str) -> str:
        out = subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=False)
        return out.stdout.strip()

    return {
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "machine": {
            "system": f"{platform.system()} {platform.release()}",
            "arch": platform.machine(),
            "cores": os.cpu_count(),
            "load_average_before": [round(x, 2) for x in os.getloadavg()],
        },
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "segplan": segplan.__version__,
        "commit": git("rev-parse", "HEAD"),
        "tree_clean": git("status", "--porcelain", "--untracked-files=no") == "",
        "command": " ".join(["python", *argv]),
    }


def main(argv: list[str] | None = None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5, help="timed loads (default 5)")
    parser.add_argument("--plan", action="store_true", help="also plan across the building")
    parser.add_argument("--out", metavar="JSON", help="store the results here (with provenance)")
    args = parser.parse_args(argv)
    result = provenance(["benchmarks/maps.py", *(sys.argv[1:] if argv is None else argv)])
    img = office_map()
    result["map"] = {"rows": img.shape[0], "cols": img.shape[1], "resolution_m": RESOLUTION}
    with tempfile.TemporaryDirectory() as tmp:
        yaml = write_map(Path(tmp), img)
        times = []
        for _ in range(args.runs):
            t = time.perf_counter()
            floor = segplan.load_ros_map(yaml)
            times.append(time.perf_counter() - t)
        result["load_seconds"] = {
            "runs": [round(x, 3) for x in times],
            "median": round(statistics.median(times), 3),
        }
        print(
            f"load_ros_map, {img.shape[0]} x {img.shape[1]} cells: median {statistics.median(times):.2f} s "
            f"(runs {', '.join(f'{x:.2f}' for x in times)}; target <= 2 s)"
        )
        rows = []
        for k in (0, 1, 2, 3):
            t = time.perf_counter()
            f = segplan.load_ros_map(yaml, tolerance=k * RESOLUTION)
            seconds = time.perf_counter() - t
            row = {
                "tolerance_cells": k,
                "pieces": len(f.obstacles),
                "vertices": sum(len(p) for p in f.obstacles),
                "free_space_loss": round(f.free_space_loss(), 5),
                "load_seconds": round(seconds, 3),
            }
            rows.append(row)
            print(
                f"tolerance {k} cells: {row['pieces']} pieces, {row['vertices']} vertices, "
                f"{100 * row['free_space_loss']:.2f} % of the free cells touched, load {seconds:.2f} s"
            )
        result["tolerances"] = rows
        free = int(np.count_nonzero(~floor.blocked))
        result["map"]["free_cells"] = free
        if args.plan:
            robot = segplan.Robot(1.2, 0.35, math.radians(45.0))
            start, goal = ((x, y, math.radians(th)) for x, y, th in (START, GOAL))
            t = time.perf_counter()
            sc = segplan.make_scenario(robot, start, goal, floor)
            made = time.perf_counter() - t
            try:
                p = segplan.plan_scenario(sc, time_limit=60.0)
                result["plan"] = {"found": True, "cost_m": round(p.cost, 3), "seconds": round(p.seconds, 2)}
            except segplan.NoPathError as exc:
                result["plan"] = {"found": False, "reason": exc.reason, "seconds": round(exc.seconds, 2)}
            result["plan"] |= {"start": START, "goal": GOAL, "make_scenario_seconds": round(made, 3)}
            print(f"plan {START} -> {GOAL}: {result['plan']}")
    result["machine"]["load_average_after"] = [round(x, 2) for x in os.getloadavg()]
    if args.out:
        Path(args.out).write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
        print(f"stored in {args.out}")
    return result


if __name__ == "__main__":
    main()
