"""benchmarks/robots.py: its floors are deterministic, vary the robot, and its stored run is
of those floors (beyond the paper; the probe itself is not run in the tests)."""

import json
import math
from pathlib import Path

import pandas as pd
from load_file import load_file

from segplan.studies import floors as fl

ROOT = Path(__file__).resolve().parent.parent


def _probe():
    return load_file(ROOT / "benchmarks" / "robots.py", "robots_probe")


def test_floors_are_deterministic_and_vary_the_robot():
    probe = _probe()
    first = [probe.robot_floor(i) for i in range(12)]
    again = [probe.robot_floor(i) for i in range(12)]
    assert [fl.floor_key(a) for a in first] == [fl.floor_key(b) for b in again]
    assert len({(s.robot.L, s.robot.max_steer) for s in first}) > 4
    for s in first:
        assert s.robot.L in probe.LENGTHS
        assert round(math.degrees(s.robot.max_steer), 6) in probe.STEERING
        assert 0.15 * s.robot.L <= s.robot.half_width <= 0.5 * s.robot.L


def test_stored_run_is_of_the_probes_floors():
    """Each stored row's floor key is that of the generator's floor of its index, and the
    provenance names the command and a commit."""
    probe = _probe()
    table = pd.read_csv(ROOT / "benchmarks" / "results" / "robots.csv")
    meta = json.loads((ROOT / "benchmarks" / "results" / "robots.json").read_text())
    assert "benchmarks/robots.py" in meta["command"] and len(meta["commit"]) == 40
    assert len(table) >= 40
    for row in table.head(10).itertuples():
        sc = probe.robot_floor(int(row.index))
        assert fl.floor_key(sc) == row.floor_key
        assert math.isclose(sc.robot.L, row.L)
    solved = table[table.solved]
    assert solved.valid.all()
