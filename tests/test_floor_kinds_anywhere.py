"""The stored floor-kinds runs of two processors plan alike (the "holds anywhere" issue).

``benchmarks/results/floor_kinds_defaults/`` holds the default planner's run on the 600 kind
floors measured on an AMD EPYC and, in ``rerun_4cee5b8/``, the same command on an Intel Xeon
(the ``machine`` field's ``cpu`` of each provenance file). No plan changed between the two commits, so
every outcome, reason, plan cost (the CSV's full-precision repr) and node count must agree.
"""

import csv
import json
from pathlib import Path

import pytest

RUNS = Path(__file__).resolve().parent.parent / "benchmarks" / "results" / "floor_kinds_defaults"
FIELDS = ("solved", "reason", "plan_cost", "nodes")


def _rows(path: Path) -> dict[str, dict]:
    with path.open() as f:
        return {r["floor"]: r for r in csv.DictReader(f)}


def test_two_processors_make_the_same_plans_on_every_floor():
    a, b = _rows(RUNS / "floor_kinds_segplan.csv"), _rows(RUNS / "rerun_4cee5b8" / "floor_kinds_segplan.csv")
    cpus = {
        json.loads((d / "floor_kinds_segplan.json").read_text())["machine"]["cpu"]
        for d in (RUNS, RUNS / "rerun_4cee5b8")
    }
    if len(cpus) < 2:
        pytest.skip("the two stored runs were made on one kind of processor")
    assert a.keys() == b.keys() and len(a) == 600
    differ = [f for f in a if any(a[f][k] != b[f][k] for k in FIELDS)]
    assert differ == []
