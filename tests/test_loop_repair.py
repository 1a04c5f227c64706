"""The loops at a plan's ends (issue 25; :func:`segplan.planning.lattice.search._repair_loops`).

Where the best path turns round on its smallest circle in an aisle crossing, the lattice's
plan went round a rack row (chapter 11's warehouse-013, twice BIT*'s length). A forward plan
longer than ``LOOP_GAP`` times the Dubins length of its ends is searched again towards the
tight loops at its ends; the oracle of the result is the dense one of the metrics.
"""

from __future__ import annotations

import math

import pytest

import segplan
from segplan.planning.lattice import search
from segplan.studies import floor_kinds as fk
from segplan.viz.metrics import measure_scenario_path, plan_poses


def without_repair(monkeypatch, sc):
    with monkeypatch.context() as m:
        m.setattr(search, "LOOP_GAP", math.inf)
        return segplan.plan_scenario(sc)


def test_a_loop_in_the_aisle_crossing_instead_of_round_the_rack(monkeypatch):
    sc = fk.kind_floor("warehouse", 13)
    before = without_repair(monkeypatch, sc)
    plan = segplan.plan_scenario(sc)
    assert plan.cost < 0.6 * before.cost  # 15.8 m against 32.9 m when measured
    assert "arc" in plan.kinds  # through a tight arc at an end
    m = measure_scenario_path(plan_poses(plan, 0.01), sc)
    assert not m.collides and m.max_curvature <= sc.robot.max_curvature * (1 + 1e-6)
    again = segplan.plan_scenario(sc)
    assert again.unions == plan.unions  # counted in expansions: the same plan every time


@pytest.mark.parametrize("name", ["fig5_example1", "l_shaped_rack", "narrow_passage"])
def test_plans_within_the_gap_are_untouched(monkeypatch, name):
    sc = segplan.load_scenario(name)
    plan = segplan.plan_scenario(sc)
    assert plan.unions == without_repair(monkeypatch, sc).unions


def test_reversing_robots_are_left_to_their_turn_arounds(monkeypatch):
    sc = segplan.load_scenario("dead_end_bay")
    assert sc.robot.reverse
    assert segplan.plan_scenario(sc).unions == without_repair(monkeypatch, sc).unions
