"""A forward robot's escape pairs are probed before any is searched in full (issue 25,
:func:`segplan.planning.lattice.search._escape`).

warehouse-020 of the floor-kinds study (``segplan.studies.floor_kinds``) is the floor OMPL's
BIT* solves that the default planner did not with its own limits: the goal faces a rack across
an aisle narrower than the lattice's tightest turn, so the goal looked enclosed and the escapes
ran; the search towards the first pair's arc ran to the time limit, while the fourth pair's
joined in 8 expansions. Every count here is of expansions, so the answers do not depend on the
machine's speed."""

from __future__ import annotations

import math
import re

import pytest

import segplan
from segplan.planning.lattice import search as lattice
from segplan.studies import floor_kinds as fk
from segplan.viz.metrics import measure_scenario_path, plan_poses

#: Expansions for the whole call: far above what the probed escapes take (488 when written),
#: far below what the unprobed first pair's search would take to fail (it ran 10 s, some
#: 70 000 expansions, without a plan).
BUDGET = 5000


def test_probed_escapes_solve_the_aisle_goal():
    sc = fk.kind_floor("warehouse", 20)
    plan = segplan.plan_scenario(sc, max_expansions=BUDGET, time_limit=120.0)
    assert "arc" in plan.kinds  # it came through the escapes
    measured = measure_scenario_path(plan_poses(plan, 0.01), sc)
    assert not measured.collides  # the dense oracle
    assert measured.max_curvature <= sc.robot.max_curvature * (1 + 1e-6)
    assert math.isclose(plan.cost, measured.front_length, rel_tol=1e-3)


def test_without_the_probes_the_first_pair_takes_the_budget(monkeypatch):
    monkeypatch.setattr(lattice, "PROBE_EXPANSIONS", 10**9)  # every probe a full search
    with pytest.raises(segplan.NoPathError) as e:
        segplan.plan_scenario(fk.kind_floor("warehouse", 20), max_expansions=BUDGET, time_limit=120.0)
    assert e.value.reason == "expansions" and e.value.expanded >= BUDGET


def test_a_pair_probed_then_searched_in_full_is_one_try(monkeypatch):
    """The message counts pairs, not searches: at most as many tried as offered."""
    monkeypatch.setattr(lattice, "PROBE_EXPANSIONS", 1)  # every probe cut short: all searched again
    with pytest.raises(segplan.NoPathError) as e:
        segplan.plan_scenario(fk.kind_floor("warehouse", 20), max_expansions=BUDGET, time_limit=120.0)
    tried, offered = map(int, re.search(r"(\d+) of (\d+) tried", str(e.value)).groups())
    assert 0 < tried <= offered
