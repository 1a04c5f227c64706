"""Issue 26, reverse motion, step 4: plans report their directions and cusps, saved and loaded with them."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import segplan
from segplan import Plan, load_scenario
from segplan.cli import main
from segplan.planning.lattice.reverse import by_runs, runs, weighted_cost
from segplan.planning.plan import link_ends, plan_from_record, plan_record, union_longd


@pytest.fixture(scope="module")
def bay_plan():
    sc = load_scenario("dead_end_bay")
    return sc, segplan.plan_scenario(sc)


def test_forward_plans_report_forward_links():
    sc = load_scenario("fig5_example1")
    plan = segplan.plan_scenario(sc)
    assert plan.directions == () and plan.cusps == ()
    assert plan.link_directions == (1,) * len(plan.unions)
    d = plan.to_dict()
    assert d["directions"] == [1] * len(plan.unions) and d["cusps"] == []


def test_reverse_plan_directions_and_cusps(bay_plan):
    _, plan = bay_plan
    d = plan.link_directions
    assert len(d) == len(plan.unions) and set(d) == {1, -1}
    assert plan.cusps == tuple(i for i in range(1, len(d)) if d[i] != d[i - 1])
    assert link_ends(plan.nodes[0], plan.unions, plan.directions) == plan.nodes
    assert plan.heuristic == "reeds-shepp"


def test_reverse_plan_saved_and_loaded_bit_for_bit(bay_plan, tmp_path):
    sc, plan = bay_plan
    back = Plan.load(plan.save(tmp_path / "bay.json", sc))
    assert back == plan and back.directions == plan.directions and back.cusps == plan.cusps
    record = plan_record(plan, sc)
    assert record["directions"] == list(plan.link_directions) and record["cusps"] == list(plan.cusps)


def test_saved_plan_with_bad_directions_is_refused(bay_plan):
    sc, plan = bay_plan
    record = json.loads(json.dumps(plan_record(plan, sc)))
    for bad in ([1] * len(plan.unions), [2] * len(plan.unions), [True] * len(plan.unions), [1], "1"):
        record["directions"] = bad
        with pytest.raises(ValueError, match="direction|does not join"):
            plan_from_record(record)


def test_saved_forward_plan_without_directions_loads():
    sc = load_scenario("fig5_example1")
    plan = segplan.plan_scenario(sc)
    record = json.loads(json.dumps(plan_record(plan, sc)))
    del record["directions"], record["cusps"]
    assert plan_from_record(record) == plan


def test_cli_json_shows_directions_and_cusps(capsys):
    assert main(["plan", "dead_end_bay", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["found"] and len(data["cusps"]) == 1 and -1 in data["directions"]


def test_runs_and_by_runs_keep_the_cusps(bay_plan):
    _, plan = bay_plan
    assert runs((1, 1, -1, -1, -1, 1)) == [(0, 2, 1), (2, 5, -1), (5, 6, 1)]
    seen = []

    def step(part):
        assert part.directions == ()  # each run as a forward plan
        assert link_ends(part.nodes[0], part.unions) == part.nodes
        seen.append(part)
        return part

    same = by_runs(plan, step)
    assert len(seen) == len(plan.cusps) + 1
    assert same.nodes == plan.nodes and same.unions == plan.unions and same.directions == plan.directions
    assert same.cost == pytest.approx(sum(union_longd(u) for u in plan.unions), rel=1e-12)


def test_weighted_cost(bay_plan):
    _, plan = bay_plan
    longd = [union_longd(u) for u in plan.unions]
    back = sum(c for c, d in zip(longd, plan.link_directions, strict=True) if d < 0)
    expect = sum(longd) + 0.5 * back + 3.0 * len(plan.cusps)
    assert weighted_cost(plan, 1.5, 3.0) == pytest.approx(expect, rel=1e-12)
    fwd = segplan.plan_scenario(load_scenario("fig5_example1"))
    assert weighted_cost(fwd, 1.5, 3.0) == fwd.cost
    assert math.isfinite(plan.search_cost) and plan.search_cost >= plan.cost


def test_refine_refuses_a_plan_with_reverse_links(bay_plan):
    sc, plan = bay_plan
    raw = segplan.plan_scenario(sc, refine=False)
    assert raw.refinement is None and raw.directions
    with pytest.raises(ValueError, match="reverse links"):
        segplan.refine(raw, sc)
    assert plan.refinement is not None  # the default planner refined it run by run


def test_plan_poses_drive_reverse_links_backwards():
    """viz.metrics.plan_poses samples a reverse plan in driving order: continuous, from the
    start to the goal, one measured reversal per cusp, the front-wheel length the plan's LONGD."""
    import numpy as np

    from segplan.viz.metrics import measure_scenario_path, plan_poses

    sc = segplan.load_scenario(
        Path(__file__).resolve().parents[1] / "scenarios/beyond_the_paper/dead_end_bay.json"
    )
    plan = segplan.plan_scenario(sc)
    assert plan.cusps
    P = plan_poses(plan, 0.01)
    assert np.allclose(P[0], tuple(sc.start)) and np.allclose(P[-1], tuple(sc.goal))
    assert np.hypot(*np.diff(P[:, :2], axis=0).T).max() < 0.02
    m = measure_scenario_path(P, sc)
    assert m.reversals == len(plan.cusps) and not m.collides
    assert m.front_length == pytest.approx(plan.cost, rel=1e-4)


def test_the_figure_draws_reversing_links_apart_and_marks_each_cusp():
    """plan_figure (the command line's --out) with a reverse plan's directions: forward and
    reverse rear paths under their own legend entries, a cross at each cusp (the node where
    the direction changes, in driving order); bad directions refused."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from segplan.viz import plot

    sc = load_scenario("dead_end_bay")
    plan = segplan.plan_scenario(sc)
    fig = plot.plan_figure(sc, plan.unions, "bay", plan.directions)
    try:
        ax = fig.axes[0]
        labels = [line.get_label() for line in ax.lines]
        assert "rear path A, forward" in labels and "rear path A, reverse" in labels
        (cross,) = [line for line in ax.lines if line.get_label() == "cusp"]
        xy = np.column_stack(cross.get_data())
        expected = np.array([[plan.nodes[i].x, plan.nodes[i].y] for i in plan.cusps])
        assert xy == pytest.approx(expected, abs=1e-12)
        reverse = [line for line in ax.lines if line.get_label() == "rear path A, reverse"]
        assert reverse[0].get_color() == plot.REVERSE_COLOR
    finally:
        plt.close(fig)
    with pytest.raises(ValueError, match="directions"):
        plot.plan_figure(sc, plan.unions, "bay", (1,) * (len(plan.unions) - 1))
    with pytest.raises(ValueError, match="directions"):
        plot.plan_figure(sc, plan.unions, "bay", (2,) * len(plan.unions))
