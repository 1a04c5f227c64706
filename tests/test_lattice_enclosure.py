"""The lattice planner: fast "no plan" for an enclosed goal, the approach screen, one option validator."""

import dataclasses
import math

import numpy as np
import pytest
from test_lattice_parts import astar_of, plan_of

from segplan import NoPathError, Robot, make_scenario, plan_scenario
from segplan.planning.lattice import search as lt
from segplan.planning.lattice.approach import steerable
from segplan.planning.plan import check_limits, check_option
from segplan.planning.schedule import SCHEDULE

DEG = math.pi / 180.0


def _wall_goal():
    """Open 20 x 12 m room; the goal 0.56 m from the left wall (beyond the robot's half-width),
    heading into the room: it can only be reached by arriving from inside the wall."""
    robot = Robot(1.0, 0.3, 45 * DEG)
    return make_scenario(robot, (15.0, 6.0, math.pi), (0.86, 1.52, 0.09), [], (0.0, 0.0, 20.0, 12.0))


def test_enclosed_goal_stops_early():
    """The goal's approach tree runs out and the start joins none of it: the search stops
    ENCLOSED_EXPANSIONS later (a limit, said so), long before max_expansions; then the
    escapes' hops try at most HOP_ESCAPES searches of HOP_PROBE expansions."""
    sc = _wall_goal()
    with pytest.raises(NoPathError) as err:
        lt.lattice_search(sc, max_expansions=5000)
    e = err.value
    assert e.reason == "expansions"
    assert "looks enclosed" in str(e) and "not a proof" in str(e)
    hops = lt.HOP_ESCAPES * lt.HOP_PROBE
    assert e.expanded <= SCHEDULE.enclosure_after + SCHEDULE.enclosed_expansions + 1 + hops
    assert e.best is not None and e.best.nodes[0] == sc.start


@pytest.mark.parametrize("name", ["wall_ahead_same", "corridor"])
def test_the_enclosure_is_judged_once_the_tree_is_due(monkeypatch, name):
    """The goal's enclosure is judged when the approach tree is built (``approach_after``
    expansions) and, if the tree is not exhausted then, once more at ``enclosure_after``:
    a search that plans before that counts the states that reach the goal (``reach_all``)
    never, and asks whether the start joins them at most once."""
    from segplan.planning.lattice.approach import GoalApproach
    from segplan.studies.floors import hard_cases

    calls = []
    for method in ("reach_all", "start_joins"):
        original = getattr(GoalApproach, method)

        def spy(self, *a, _original=original, _name=method, **kw):
            calls.append(_name)
            return _original(self, *a, **kw)

        monkeypatch.setattr(GoalApproach, method, spy)
    plan, outcome, _ = plan_of(astar_of(hard_cases()[name]))
    assert outcome == "found" and SCHEDULE.approach_after < plan.expanded < SCHEDULE.enclosure_after
    assert "reach_all" not in calls and calls.count("start_joins") <= 1


def test_forward_search_alone_finds_no_plan_either():
    """Without the approach tree (so without the enclosure test), the forward search finds no
    plan there either."""
    alone = dataclasses.replace(SCHEDULE, approach_after=10**9)
    _, outcome, _ = plan_of(astar_of(_wall_goal(), schedule=alone), max_expansions=1500)
    assert outcome in ("expansions", "exhausted")


def test_default_planner_reports_the_enclosed_goal():
    with pytest.raises(NoPathError) as err:
        plan_scenario(_wall_goal(), max_expansions=5000)
    assert err.value.reason == "expansions" and err.value.expanded < 5000


def test_goal_by_a_wall_reached_by_a_union_is_planned():
    """A goal 0.15 m below the top wall: the goal's lattice reaches it from a handful of
    states only, but a union from the start's lattice does (random floor natural-066)."""
    from segplan.studies.floors import random_floor

    plan = plan_scenario(random_floor("natural", 66), max_expansions=1000)
    assert plan.kinds[-1] == "goal"


def test_reachable_goal_near_a_wall_is_still_planned():
    """The same goal turned to face the wall is reachable: no enclosure is claimed."""
    robot = Robot(1.0, 0.3, 45 * DEG)
    sc = make_scenario(robot, (15.0, 6.0, math.pi), (1.5, 1.52, math.pi), [], (0.0, 0.0, 20.0, 12.0))
    plan = plan_scenario(sc)
    assert plan.nodes[-1] == sc.goal


def test_steerable_screens_unions():
    p0 = (0.0, 0.0, 0.0)
    ahead = np.array([(3.0, 0.5, 0.2), (3.0, -0.5, -0.2)])
    behind = np.array([(-3.0, 0.0, 0.0), (0.0, 0.2, math.pi)])
    slack = SCHEDULE.steer_slack
    assert steerable(p0, ahead, 1.0, slack).all()
    assert not steerable(p0, behind, 1.0, slack).any()
    tight = np.array([(0.3, 0.3, 1.5)])  # a quarter turn within 0.3 m: far beyond curvature 1
    assert not steerable(p0, tight, 1.0, slack).any()


@pytest.mark.parametrize(
    "value, kwargs",
    [(True, {}), (float("nan"), {}), (0.0, {}), (-1.0, {"lo_ok": True}), (1.5, {"integer": True}), ("1", {})],
)
def test_check_option_names_the_argument(value, kwargs):
    with pytest.raises(ValueError, match="my_option"):
        check_option(value, "my_option", 0.0, **kwargs)


def test_check_limits():
    assert check_limits(None, 2) == (None, 2.0)
    assert check_limits(5.0, 0.5) == (5, 0.5)
    with pytest.raises(ValueError, match="max_expansions"):
        check_limits(0, 1.0)
    with pytest.raises(ValueError, match="time_limit"):
        check_limits(10, float("inf"))


def test_vectorised_broad_phase_decides_as_the_scalar_loop(monkeypatch):
    """Above VECTOR_SCREEN_MIN obstacles colliding() and pose_free() screen with arrays (on
    the obstacles the workspace's index files nearby): the same answers, obstacles kept and
    broad-phase counts as the scalar loops."""
    from segplan.model.pose import Pose
    from segplan.planning import validity
    from segplan.planning.links import LinkModel
    from segplan.studies.floors import sweep_floor

    sc = sweep_floor(4.0, 128, 0)  # 80 x 48 m, 128 obstacles
    rng = np.random.default_rng(7)
    fb = sc.free_bounds
    poses = [
        Pose(rng.uniform(fb[0], fb[2]), rng.uniform(fb[1], fb[3]), rng.uniform(-math.pi, math.pi))
        for _ in range(120)
    ]

    def run():
        ws = validity.Workspace(sc.enlarged, sc.robot.L, fb, sc.robot.max_curvature)
        links = LinkModel(ws)
        out = [ws.pose_free(p) for p in poses]
        for a, b in zip(poses[:-1], poses[1:], strict=True):
            u = links.union(a, Pose(a.x + (b.x - a.x) * 0.2, a.y + (b.y - a.y) * 0.2, b.theta))
            if u is not None:
                kept = sorted((i, v) for i, v in ws.facts(u).near.items() if v is not None)
                out.append((ws.colliding(u, first=False), kept))
        return out, ws.stats.broad_rejections

    def some_first():  # a few obstacles asked about first: the broad phase then skips them
        ws = validity.Workspace(sc.enlarged, sc.robot.L, fb, sc.robot.max_curvature)
        links = LinkModel(ws)
        out = []
        for a, b in zip(poses[:-1], poses[1:], strict=True):
            u = links.union(a, Pose(a.x + (b.x - a.x) * 0.2, a.y + (b.y - a.y) * 0.2, b.theta))
            if u is not None:
                out.append((ws.colliding(u, only=list(range(0, 128, 9))), ws.colliding(u, first=False)))
        return out

    vector = run()
    vector_some = some_first()
    monkeypatch.setattr(validity, "VECTOR_SCREEN_MIN", 10**9)
    scalar = run()
    assert vector == scalar and vector_some == some_first()
    assert vector[1] > 0 and any(isinstance(x, tuple) and x[0] for x in vector[0])
    assert [second for _, second in vector_some] == [x[0] for x in vector[0] if isinstance(x, tuple)]


def _tree_of(sc, max_expansions):
    """The goal's approach tree of the lattice search of ``sc`` (one resolution), after a run of
    ``max_expansions`` expansions; built (at its first size) if that run did not."""
    s = astar_of(sc)
    plan_of(s, max_expansions=max_expansions)
    if s.approach.keys is None:
        s.approach.build(SCHEDULE.approach_limit)
    return s.approach


@pytest.mark.parametrize("goal", [(0.86, 1.52, 0.09), (8.86, 4.5, 0.0), (6.0, 3.26, -1.3)])
def test_reach_all_holds_every_state_of_the_approach_tree(goal):
    """The enclosure test's flood fill (grid screen only) finds a superset of the states the
    certified approach tree reaches, so "looks enclosed" by it implies so by the tree.
    Goals facing away from a wall or an obstacle a few decimetres behind them (pockets)."""
    robot = Robot(1.0, 0.3, 45 * DEG)
    box = [[4.0, 4.0], [8.0, 4.0], [8.0, 5.0], [4.0, 5.0]]
    sc = make_scenario(robot, (15.0, 8.0, math.pi), goal, [box], (0.0, 0.0, 20.0, 12.0))
    t = _tree_of(sc, 40)
    t.grow(5000)
    assert t.exhausted
    tree = {tuple(np.round(p, 9)) for p in t.poses.tolist()}
    everything = t.reach_all(5000)
    assert everything is not None
    flood = {tuple(np.round(p, 9)) for p in everything.tolist()}
    assert tree <= flood
    n = len(flood)  # the limit: all of them up to it, None beyond
    assert len(t.reach_all(n)) == n
    assert n == 0 or t.reach_all(n - 1) is None


def test_reach_all_counts_the_wall_pocket():
    """The goal facing away from a wall a few decimetres behind it: a handful of states."""
    t = _tree_of(_wall_goal(), 40)
    poses = t.reach_all(t.enclosure_limit)
    assert poses is not None and len(poses) < 20
    assert not t.start_joins(poses)


def test_enclosure_limit_grows_with_the_turning_radius():
    """Pockets scale with the turning radius: a robot turning wider than L counts more states."""
    wide = Robot(1.0, 0.3, 25 * DEG)  # R = L / tan(25 deg), about 2.1 L
    sc = make_scenario(wide, (15.0, 6.0, math.pi), (6.0, 6.0, 0.0), [], (0.0, 0.0, 20.0, 12.0))
    t = astar_of(sc).approach
    expected = SCHEDULE.enclosure_limit * (wide.min_turning_radius / wide.L) ** 2
    assert t.enclosure_limit == pytest.approx(expected, abs=1.0)


def test_default_planner_caps_the_papers_search(monkeypatch):
    """The default planner runs the paper's search within api.PAPER_EXPANSIONS expansions
    (and within a smaller max_expansions if given); planner="paper" keeps its own default."""
    from segplan.planning import api, default

    calls = []
    search = default.paper_search

    def spy(ctx, options, *a):
        calls.append(options.max_expansions)
        return search(ctx, options, *a)

    monkeypatch.setattr(default, "paper_search", spy)
    monkeypatch.setattr(api, "paper_search", spy)
    sc = _wall_goal()
    for kw in ({}, {"max_expansions": 10}):
        with pytest.raises(NoPathError):
            plan_scenario(sc, time_limit=5.0, **kw)
    with pytest.raises(NoPathError):
        plan_scenario(sc, planner="paper")
    assert calls == [api.PAPER_EXPANSIONS, 10, 3000]
