"""segplan.Planner: many plans on one floor, the off-line work once; every plan the one
segplan.plan_scenario makes of the same scenario and options."""

from __future__ import annotations

import math

import numpy as np
import pytest

import segplan
from segplan import DefaultOptions, PaperOptions
from segplan.floor.scenario import prepare_floor
from segplan.studies import floor_kinds

ROBOT = segplan.Robot(1.0, 0.3, math.radians(45))
OBSTACLES = [[(4, 2), (6, 2), (6, 6), (4, 6)], [(7, 4), (8, 4), (8, 5.5)]]
BOUNDS = (0, 0, 10, 8)


def _key(p: segplan.Plan):
    """Everything of a plan but its times."""
    return (
        p.nodes,
        [(u.p0, u.p1, u.alpha) for u in p.unions],
        p.cost,
        p.kinds,
        p.expanded,
        p.generated,
        p.collision_checks,
        p.exact_checks,
        p.planner,
        p.options,
    )


@pytest.mark.parametrize(
    "options",
    [{}, {"planner": "paper"}, {"planner": "paper", "heuristic": "c"}, {"clearance": 0.1}, {"refine": False}],
)
def test_every_plan_is_plan_scenarios(options):
    planner = segplan.Planner(OBSTACLES, ROBOT, BOUNDS, **options)
    pairs = [((1, 1, 0), (8.3, 7, 0)), ((1, 7, 0), (8.3, 1, 0)), ((2, 4, math.pi / 2), (9, 3, -math.pi / 2))]
    for start, goal in pairs * 2:  # twice: nothing of one call leaks into the next
        sc = segplan.make_scenario(ROBOT, start, goal, OBSTACLES, BOUNDS)
        mine = _outcome(lambda: planner.plan(start, goal))  # noqa: B023 (called at once)
        assert mine == _outcome(lambda: segplan.plan_scenario(sc, **options))  # noqa: B023
        if isinstance(mine[-1], PaperOptions | DefaultOptions):
            assert mine[-1] == planner.options


def _outcome(call):
    """The plan's :func:`_key`, or the failure's reason, counts and message."""
    try:
        return _key(call())
    except segplan.NoPathError as exc:
        return (exc.reason, exc.expanded, exc.generated, str(exc))


def test_the_floors_work_is_done_once():
    planner = segplan.Planner(OBSTACLES, ROBOT, BOUNDS)
    floor = planner.floor
    planner.plan((1, 1, 0), (8.3, 7, 0))
    ws = planner._workspace
    planner.plan((1, 7, 0), (8.3, 1, 0))
    assert planner.floor is floor and planner._workspace is ws
    fresh = prepare_floor(ROBOT, OBSTACLES, BOUNDS)
    assert all(np.array_equal(a, b) for a, b in zip(floor.enlarged, fresh.enlarged, strict=True))


def test_a_kind_floor_and_a_map():
    sc = floor_kinds.kind_floor("warehouse", 3)
    planner = segplan.Planner(sc.outlines, sc.robot, sc.bounds)
    assert _key(planner.plan(sc.start, sc.goal)) == _key(segplan.plan_scenario(sc))
    grid = np.zeros((60, 100), dtype=bool)
    grid[20:40, 45:55] = True  # a block in the middle of a 10 x 6 m room (cells of 0.1 m)
    floor = segplan.Floor.from_occupancy(grid, 0.1)
    on_map = segplan.Planner(floor, ROBOT)
    plan = on_map.plan((1, 1, 0), (8.5, 5, 0))
    sc = segplan.make_scenario(ROBOT, (1, 1, 0), (8.5, 5, 0), floor)
    assert _key(plan) == _key(segplan.plan_scenario(sc))


def test_bad_input_is_refused_at_the_door():
    with pytest.raises(ValueError, match="planner"):
        segplan.Planner(OBSTACLES, ROBOT, BOUNDS, planner="rrt")
    with pytest.raises(ValueError, match="time_limit"):
        segplan.Planner(OBSTACLES, ROBOT, BOUNDS, time_limit=-1)
    with pytest.raises(ValueError, match="robot must be a segplan.Robot"):
        segplan.Planner(OBSTACLES, (1.0, 0.3), BOUNDS)
    with pytest.raises(segplan.ScenarioError, match="bounds"):
        segplan.Planner(OBSTACLES, ROBOT, (0, 0, -1, 8))
    planner = segplan.Planner(OBSTACLES, ROBOT, BOUNDS, clearance=0.2)
    with pytest.raises(
        segplan.ScenarioError,
        match=r"Planner.plan \(clearance=0.2 m beyond half_width=0.3\): start pose .* collides",
    ):
        planner.plan((5, 4, 0), (8.3, 7, 0))
    with pytest.raises(segplan.ScenarioError, match="beyond 2 pi"):
        planner.plan((1, 1, 90), (8.3, 7, 0))
    # 0.15 m from the block's enlarged edge: free without clearance, not with 0.2 m of it
    start = (1.0, 4.0, 0.0)
    assert segplan.Planner(OBSTACLES, ROBOT, BOUNDS).scenario(start, (8.3, 7, 0)).is_free(start)
    with pytest.raises(segplan.ScenarioError, match="clearance=0.2"):
        planner.plan((2.55, 4.0, 0.0), (8.3, 7, 0))
    assert segplan.Planner(OBSTACLES, ROBOT, BOUNDS).scenario((2.55, 4.0, 0.0), (8.3, 7, 0))
    assert "Planner(2 convex obstacles, L=1" in repr(planner)


# -- progress ---------------------------------------------------------------------------------
def test_progress_watches_every_stage_and_changes_nothing():
    sc = floor_kinds.kind_floor("large", 0)  # a site: a search of hundreds of expansions
    events: list = []
    plan = segplan.plan_scenario(sc, progress=events.append)
    assert _key(plan) == _key(segplan.plan_scenario(sc))
    stages = [(e.stage, e.event) for e in events if e.event != "expanded"]
    assert stages == [
        ("paper", "start"),
        ("paper", "done"),
        ("lattice", "start"),
        ("lattice", "done"),
        ("refine", "start"),
        ("refine", "done"),
    ]
    counts = [e.expanded for e in events if e.event == "expanded"]
    assert counts and all(n % 64 == 0 for n in counts) and counts == sorted(set(counts))
    assert all(a.seconds <= b.seconds for a, b in zip(events[:-1], events[1:], strict=True))
    assert all(e.limit == 10.0 for e in events)
    lattice = next(e for e in events if (e.stage, e.event) == ("lattice", "done"))
    assert events[-1].cost == plan.cost and lattice.cost >= plan.cost
    # the paper's planner: its search and its refinement
    events.clear()
    paper = segplan.Planner(OBSTACLES, ROBOT, BOUNDS, planner="paper", refine=True)
    paper.plan((1, 1, 0), (8.3, 7, 0), progress=events.append)
    assert [(e.stage, e.event) for e in events] == [
        ("paper", "start"),
        ("paper", "done"),
        ("refine", "start"),
        ("refine", "done"),
    ]


def test_progress_can_stop_a_call_and_must_be_callable():
    sc = floor_kinds.kind_floor("large", 0)

    class EnoughError(Exception):
        pass

    def stop(event):
        if event.event == "expanded":
            raise EnoughError

    with pytest.raises(EnoughError):
        segplan.plan_scenario(sc, progress=stop)
    with pytest.raises(ValueError, match="progress must be callable"):
        segplan.plan_scenario(sc, progress="bar")


# -- the study of many plans on one floor (segplan.studies.planner_reuse) ---------------------
def test_turned_is_the_same_footprint_facing_the_other_way():
    from segplan.studies.planner_reuse import turned

    for pose in [(1.0, 2.0, 0.3), (5.0, 5.0, -2.9), (0.0, 0.0, math.pi)]:
        x, y, th = turned(pose, 1.5)
        a, b = np.array(pose[:2]), np.array(pose[:2]) + 1.5 * np.array([math.cos(pose[2]), math.sin(pose[2])])
        assert np.allclose((x, y), b, atol=1e-6)  # A moved to B
        assert np.allclose(np.array((x, y)) + 1.5 * np.array([math.cos(th), math.sin(th)]), a, atol=1e-5)
        assert -math.pi < th <= math.pi


def test_floor_queries_are_free_on_the_kinds_floors():
    from segplan.studies.planner_reuse import QUERIES, floor_queries

    for kind in ("warehouse", "rooms", "parking", "clutter", "robots"):
        sc = floor_kinds.kind_floor(kind, 0)
        queries = floor_queries(sc)
        assert [q[0] for q in queries] == list(QUERIES)
        assert queries[0][1:] == (tuple(sc.start), tuple(sc.goal))
        floor = prepare_floor(sc.robot, sc.outlines, sc.bounds)
        for _, a, b in queries:
            floor.scenario(a, b)  # raises ScenarioError for a pose that is not free
    with pytest.raises(ValueError, match="segplan.Scenario"):
        floor_queries((1, 2, 3))


def test_run_reuse_times_both_ways_and_finds_the_same_plans():
    from segplan.studies.planner_reuse import REUSE_COLUMNS, run_reuse

    sc = segplan.make_scenario(ROBOT, (1, 1, 0), (8.3, 7, 0), OBSTACLES, BOUNDS, name="box")
    lines = []
    table = run_reuse([("box", sc)], {"max_expansions": 5000}, progress=lines.append)
    assert list(table.columns) == list(REUSE_COLUMNS)
    assert list(table["order"]) == list(range(len(table))) and len(table) == 4 == len(lines)
    assert table["same_plan"].all() and table["solved"].iloc[0]  # an unsolved query: NoPathError both ways
    assert (table[["fresh_seconds", "reused_seconds", "build_seconds"]] > 0).all().all()
    assert table["build_seconds"].nunique() == 1
