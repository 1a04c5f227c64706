"""The reverse study planned both ways in time (segplan.studies.reverse_study, "Both ways in time")."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pandas as pd
import pytest

import segplan
from segplan.planning.lattice.reverse import weighted_cost
from segplan.planning.options import LatticeOptions
from segplan.studies import reverse_floors as rf
from segplan.studies import reverse_study as rs
from segplan.studies import robustness as rb

RESULTS = Path(__file__).resolve().parent.parent / "benchmarks" / "results"


def _time_reversed(plan):
    """The plan driven from its goal to its start: the same unions in the other order, each
    the other way (this test's own construction, as the module docstring states it)."""
    directions = tuple(-d for d in reversed(plan.link_directions))
    return dataclasses.replace(plan, unions=plan.unions[::-1], directions=directions)


def test_swapped_and_mirrored_costs():
    sc = rs.with_reverse(rf.reverse_floor("dead-end", 0))
    back = rs.swapped(sc)
    assert (back.start, back.goal, back.name) == (sc.goal, sc.start, sc.name)
    assert rs.swapped(back).start == sc.start
    lo = LatticeOptions()
    m = rs.mirrored_costs()
    assert m["reverse_factor"] * lo.reverse_factor == pytest.approx(1.0, abs=1e-15)
    assert m["cusp_penalty"] == pytest.approx(lo.cusp_penalty / lo.reverse_factor, abs=1e-15)
    # other options: theirs mirrored
    assert rs.mirrored_costs(LatticeOptions(reverse_factor=2.0, cusp_penalty=1.0)) == {
        "reverse_factor": 0.5,
        "cusp_penalty": 0.5,
    }


def test_a_swapped_plan_costs_the_same_up_to_the_factor():
    """The swapped floor's plan, driven backwards in time, is a plan of the floor whose search
    cost is ``f`` times the swapped one's: the identity run_both_ways relies on (rounding
    only: the sums run in another order)."""
    sc = rs.with_reverse(rf.reverse_floor("dead-end", 0))
    plan = segplan.plan_scenario(rs.swapped(sc), lattice=rs.mirrored_costs())
    assert plan.cusps, "the floor's plan should reverse somewhere for the test to mean anything"
    lo = LatticeOptions()
    f, pen = lo.reverse_factor, lo.cusp_penalty * sc.robot.L
    real = weighted_cost(_time_reversed(plan), f, pen)
    assert real == pytest.approx(f * weighted_cost(plan, 1.0 / f, pen / f), rel=1e-12)
    assert len(_time_reversed(plan).cusps) == len(plan.cusps)


def test_run_both_ways_keeps_the_cheaper_valid_plan():
    default, back, kept = rs.run_both_ways(["bay-out"], 3)
    assert list(kept["floor"]) == list(default["floor"]) == list(back["floor"])
    rows = (t.to_dict("records") for t in (default, back, kept))
    for a, b, k in zip(*rows, strict=True):
        assert math.isfinite(a["search_cost"]) and math.isfinite(b["search_cost"])
        want = "swapped" if b["search_cost"] < a["search_cost"] else "default"
        assert k["kept"] == want
        side = b if want == "swapped" else a
        assert k["front_length"] == side["front_length"] and k["search_cost"] == side["search_cost"]
        assert k["seconds"] == pytest.approx(a["seconds"] + b["seconds"])
    # the default's rows are the study's own (the same planner, the same floors)
    study = rs.run_segplan(["bay-out"], 3)
    assert list(study["front_length"]) == list(default["front_length"])


def test_stored_both_ways_summary():
    """The stored run (benchmarks/both_ways.py): the kept plan is never dearer than the
    default's, no plan is invalid, and the summary's worst is the worst kept ratio."""
    b = RESULTS / "both_ways"
    sides = [pd.read_csv(b / f"{n}.csv") for n in ("both_ways_default", "both_ways_swapped", "both_ways")]
    default, _, kept = sides
    assert (kept["search_cost"] <= default["search_cost"]).all()
    ompl = {s: rb.read_ompl(RESULTS / f"reverse_ompl_{s}.csv") for s in ("reedsshepp", "dubins")}
    summ = rs.both_ways_summary(*sides, ompl["reedsshepp"], ompl["dubins"])
    assert set(summ.index) == {*rf.REVERSE_KINDS, "all"}
    assert (summ[[c for c in summ.columns if c.endswith("invalid")]] == 0).all().all()
    kept_ratio = rs.compare(kept, ompl["reedsshepp"], ompl["dubins"])["ratio"]
    assert summ.loc["all", "kept worst"] == kept_ratio.max()
    assert summ.loc["all", "kept worst"] <= summ.loc["all", "default worst"]
