"""The method against the paper's distance baseline (segplan.studies.searches), by hand-made tables."""

import math

import numpy as np
import pandas as pd
import pytest

from segplan.studies.searches import (
    CLEAR_IMPROVEMENT,
    EQUAL_WITHIN,
    best_change,
    improvement_criterion,
    relative_changes,
    versus_baseline,
)
from segplan.studies.verdicts import judge, worst

COST = pd.DataFrame(
    {
        "a": [10.0, 11.2, 9.0, np.nan],
        "b": [10.0, 9.5, 9.0, 8.0],
        "distance": [10.0, 10.0, 9.005, 8.0],
    },
    index=["same", "b better", "within tol", "a failed"],
)


def test_relative_changes_by_hand_and_rows_with_a_failure_left_out():
    change = relative_changes(COST, "distance")
    assert list(change.columns) == ["a", "b"]
    assert list(change.index) == ["same", "b better", "within tol"]
    assert change.loc["b better", "a"] == pytest.approx(0.12)
    assert change.loc["b better", "b"] == pytest.approx(-0.05)
    assert change.loc["within tol", "b"] == pytest.approx(9.0 / 9.005 - 1.0)


def test_best_change_is_the_most_negative_search_per_case():
    best = best_change(COST, "distance")
    assert best.to_dict() == pytest.approx({"same": 0.0, "b better": -0.05, "within tol": 9.0 / 9.005 - 1.0})


def test_versus_baseline_counts_and_extremes():
    table = versus_baseline(COST, "distance")
    a, b = table.loc["a"], table.loc["b"]
    assert (a["cases"], a["better"], a["equal"], a["worse"]) == (3, 0, 2, 1)
    assert (b["cases"], b["better"], b["equal"], b["worse"]) == (3, 1, 2, 0)
    assert a["best"] == pytest.approx(9.0 / 9.005 - 1.0) and a["worst"] == pytest.approx(0.12)
    assert b["best"] == pytest.approx(-0.05) and b["worst"] == 0.0
    assert b["mean change"] == pytest.approx(np.mean([0.0, -0.05, 9.0 / 9.005 - 1.0]))
    # a looser tolerance turns the small difference into "equal", a zero one into "better"
    assert versus_baseline(COST, "distance", tol=0.0).loc["a", "better"] == 1


@pytest.mark.parametrize(
    ("value", "word"),
    [
        (-0.05, "reproduced"),
        (CLEAR_IMPROVEMENT, "reproduced"),
        (-0.005, "partly reproduced"),
        (-EQUAL_WITHIN, "partly reproduced"),
        (-0.0005, "not reproduced"),
        (0.0, "not reproduced"),
        (0.1, "not reproduced"),
        (math.nan, "not reproduced"),
    ],
)
def test_improvement_criterion_bands(value, word):
    assert judge(value, improvement_criterion("Fig. 5")).word == word


def test_improvement_required_in_every_case():
    """One figure without improvement makes the claim not reproduced, whatever the other shows."""
    best = best_change(COST, "distance")
    verdicts = [judge(v, improvement_criterion(case)) for case, v in best.items()]
    assert [v.word for v in verdicts] == ["not reproduced", "reproduced", "not reproduced"]
    assert worst(verdicts).word == "not reproduced"
    assert "Fig. 6" in improvement_criterion("Fig. 6").text()
    assert "at most -1.00%" in improvement_criterion("Fig. 6").text()


def test_bad_input():
    with pytest.raises(ValueError, match="cost"):
        relative_changes(COST.to_numpy(), "distance")
    with pytest.raises(ValueError, match="baseline"):
        relative_changes(COST, "nowhere")
    with pytest.raises(ValueError, match="cost"):
        relative_changes(COST[["distance"]], "distance")
    with pytest.raises(ValueError, match="positive"):
        relative_changes(COST.assign(b=-1.0), "distance")
    with pytest.raises(ValueError, match="tol"):
        versus_baseline(COST, "distance", tol=-0.1)
    with pytest.raises(ValueError, match="where"):
        improvement_criterion("  ")


# -- the optimum bracketed from both sides ------------------------------------------------------
def test_best_known_plans_read_the_stored_ompl_runs_and_bracket_the_optimum(tmp_path):
    from pathlib import Path

    import segplan
    from segplan.studies.searches import best_known_plans, optimum_interval, point_lower_bounds

    results = Path(__file__).resolve().parents[1] / "benchmarks" / "results"
    sc = segplan.load_scenario("single_obstacle")
    paper = segplan.plan_scenario(sc, planner="paper", heuristic="b")
    known = best_known_plans(sc, results / "peers_ompl.csv", plans={"as found": paper}, heuristics=("b",))
    assert list(known.columns) == ["planner", "LONGD [m]", "source"]
    assert known["LONGD [m]"].is_monotonic_increasing
    assert (
        "as found" in set(known["planner"]) and not known["planner"].str.contains("reeds", case=False).any()
    )
    stored = pd.read_csv(results / "peers_ompl.csv")
    mine = stored[(stored["scenario"] == sc.name) & (stored["space"] == "dubins")]
    mine = mine[mine["solved"].astype(bool) & mine["valid"].astype(bool)]
    ompl = known[known["planner"].str.startswith("OMPL")]
    # the raw runs' best per planner, read from the file, not typed
    for method, best in mine.groupby("method")["front_length"].min().items():
        assert ompl.set_index("planner").loc[f"OMPL {method} (Dubins)", "LONGD [m]"] <= best + 1e-12
    interval = optimum_interval(sc, known)
    assert interval["low"] == pytest.approx(point_lower_bounds(sc)["front"])
    assert interval["low"] <= interval["high"] <= paper.cost
    assert interval["high"] == known["LONGD [m]"].min()
    # without OMPL: segplan's planners only, the same bound or a longer one
    alone = best_known_plans(sc, heuristics=("b",))
    assert not alone["planner"].str.startswith("OMPL").any()
    assert alone["LONGD [m]"].min() >= interval["high"]
    with pytest.raises(ValueError, match="known"):
        optimum_interval(sc, known.iloc[0:0])
    with pytest.raises(ValueError, match="csv_path"):
        best_known_plans(sc, tmp_path / "none.csv", heuristics=())


def test_search_cpu_seconds_times_every_search_on_every_case():
    import segplan
    from segplan.studies.searches import search_cpu_seconds

    cases = [({"floor": name}, segplan.load_scenario(name)) for name in ("single_obstacle", "empty_room")]
    t = search_cpu_seconds(cases, {"a": {"heuristic": "a"}, "b": {"heuristic": "b"}}, repeats=2)
    assert list(t.columns) == ["floor", "search", "cpu seconds"]
    assert list(zip(t["floor"], t["search"], strict=True)) == [
        ("single_obstacle", "a"),
        ("single_obstacle", "b"),
        ("empty_room", "a"),
        ("empty_room", "b"),
    ]
    assert (t["cpu seconds"] > 0).all() and (t["cpu seconds"] < 60).all()
    with pytest.raises(ValueError, match="repeats"):
        search_cpu_seconds(cases, {"a": {}}, repeats=0)
    with pytest.raises(ValueError, match="cases"):
        search_cpu_seconds([("x", None)], {"a": {}})
