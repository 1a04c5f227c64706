"""The A*-type search (issue 3, section "Results. Graph-search").

Every returned plan is checked against independent oracles: a dense shapely sampling of
the swept segment (rear path, front-wheel path and the robot at many positions) against
the enlarged obstacles and the walls, the exact curvature maximum, forward motion along
the sampled path, and exact equality of the end poses.
"""

import math
import time
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

import segplan
from segplan import NoPathError, Plan, Pose, Robot, make_scenario, plan, plan_scenario, random_world
from segplan.model.cost import longd_exact
from segplan.planning.paper.problem import characteristic_dimension, polygon_gap

SCENARIOS = Path(__file__).resolve().parent.parent / "scenarios"
SQUARE = [[4.0, -1.0], [6.0, -1.0], [6.0, 1.0], [4.0, 1.0]]


def check_plan(result: Plan, scenario, n: int = 300) -> None:
    """Assert every constraint of a returned plan with independent oracles."""
    robot = scenario.robot
    kappa = math.tan(robot.max_steer) / robot.L
    assert result.nodes[0] == scenario.start
    assert result.nodes[-1] == scenario.goal  # exactly, not approximately
    assert len(result.unions) == len(result.nodes) - 1 >= 1
    assert result.unions[-1].p1 == scenario.goal
    polys = [shapely.Polygon(p) for p in scenario.enlarged]
    fb = scenario.free_bounds
    for i, u in enumerate(result.unions):
        assert isinstance(u, segplan.Union)
        # consecutive unions share the node pose: continuous position and heading
        assert u.p0 == result.nodes[i] and u.p1 == result.nodes[i + 1]
        # steering limit, exact maximum of the rear path's curvature
        assert u.max_curvature() <= kappa * (1 + 1e-9)
        a, b = u.rear(n), u.front(n)
        # forward only: the rear point advances along the robot's heading
        h = u.heading(u.xs(n))
        step = np.diff(a, axis=0)
        assert np.all(step[:, 0] * np.cos(h[:-1]) + step[:, 1] * np.sin(h[:-1]) > 0)
        # free: dense shapely check of the swept segment
        segs = shapely.linestrings(np.stack((a, b), axis=1))
        rear, front = shapely.LineString(a), shapely.LineString(b)
        for k, poly in enumerate(polys):
            assert not np.any(shapely.intersects(poly, segs)), f"union {i} hits obstacle {k}"
            assert not poly.intersects(rear) and not poly.intersects(front), f"union {i} hits obstacle {k}"
        if fb is not None:
            pts = np.vstack((a, b))
            assert np.all((pts[:, 0] > fb[0]) & (pts[:, 0] < fb[2])), f"union {i} leaves the bounds"
            assert np.all((pts[:, 1] > fb[1]) & (pts[:, 1] < fb[3])), f"union {i} leaves the bounds"
    exact = sum(longd_exact(u.p0, u.p1, u.alpha, u.L, rtol=1e-8) for u in result.unions)
    assert math.isclose(result.cost, exact, rel_tol=1e-6)
    added = 0 if result.refinement is None else result.refinement.splits  # nodes refine() added
    assert result.expanded >= 1 and result.generated + added >= len(result.nodes)
    assert result.seconds > 0


# -- property test over random worlds ----------------------------------------------------
@settings(max_examples=40)
@given(seed=st.integers(0, 10_000), n=st.integers(1, 8), heuristic=st.sampled_from("abc"))
def test_random_world_plans_are_valid(seed, n, heuristic):
    sc = random_world(seed, n, bounds=(0.0, 0.0, 24.0, 16.0))
    try:
        result = plan_scenario(sc, heuristic=heuristic, max_expansions=400, planner="paper")
    except NoPathError as exc:
        assert exc.expanded >= 1
        return
    check_plan(result, sc)


def test_random_worlds_mostly_solved():
    """Success rate over fixed seeds (not a timed test)."""
    solved = 0
    for seed in range(20):
        sc = random_world(seed, 10)
        try:
            result = plan_scenario(sc, planner="paper")
        except NoPathError:
            continue
        check_plan(result, sc, n=150)
        solved += 1
    assert solved >= 18


@pytest.mark.parametrize(
    "name",
    ["single_obstacle", "turn_around", "fig5_example1", "fig6_example2", "empty_room", "narrow_passage"],
)
@pytest.mark.parametrize("heuristic", ["a", "c"])
def test_shipped_scenarios(name, heuristic):
    sc = segplan.load_scenario(SCENARIOS / f"{name}.json")
    result = plan_scenario(sc, heuristic=heuristic, planner="paper")
    check_plan(result, sc)


def test_distance_baseline_and_admissible_heuristic():
    """The paper's baseline (link cost = distance) and h' (b) also give valid plans."""
    sc = segplan.load_scenario(SCENARIOS / "single_obstacle.json")
    for kw in ({"cost": "distance"}, {"heuristic": "b"}, {"version": "a"}):
        result = plan_scenario(sc, **kw, planner="paper")
        check_plan(result, sc)
        assert result.cost_kind == kw.get("cost", "longd")


def test_plan_through_a_gap_with_half_width():
    obstacles = [
        [[4.0, -5.0], [6.0, -5.0], [6.0, -0.9], [4.0, -0.9]],
        [[4.0, 0.9], [6.0, 0.9], [6.0, 5.0], [4.0, 5.0]],
    ]
    result = plan(
        (0.0, 0.0, 0.0),
        (11.0, 0.0, 0.0),
        obstacles,
        1.0,
        bounds=(-1, -5, 13, 5),
        half_width=0.3,
        planner="paper",
    )
    sc = make_scenario(Robot(1.0, 0.3), (0.0, 0.0, 0.0), (11.0, 0.0, 0.0), obstacles, (-1, -5, 13, 5))
    check_plan(result, sc)


def test_trivial_plans():
    same = plan((1.0, 2.0, 0.3), (1.0, 2.0, 0.3), [], 1.0, planner="paper")
    assert same.nodes == (Pose(1.0, 2.0, 0.3),) and same.unions == () and same.cost == 0.0
    straight = plan((0.0, 0.0, 0.0), (5.0, 0.0, 0.0), [], 1.0, planner="paper")
    assert len(straight.unions) == 1 and math.isclose(straight.cost, 5.0, rel_tol=1e-9)


def _line_search(max_turn_chain, reset_every=0):
    """The search alone on a line graph: from x = 0 each node has one successor at x + 1, of
    kind ``"turn"`` (``"vertex"`` every ``reset_every``-th step), offered only while the
    search allows turn states, except vertex steps; at x = 8 the goal. Returns the plan or the
    ``NoPathError`` and the ``(x, turns)`` of each expansion."""
    from types import SimpleNamespace

    from segplan.planning.paper.search import astar

    goal = Pose(8.0, 0.0, 0.0)
    problem = SimpleNamespace(
        start=Pose(0.0, 0.0, 0.0),
        goal=goal,
        cost_to_go=lambda pose, depth: goal.x - pose.x,
        link_cost=lambda union: 1.0,
        prepare=lambda poses: None,
    )
    calls = []

    def successors(pose, turns):
        calls.append((pose.x, turns))
        x = pose.x + 1.0
        if x == goal.x:
            return [SimpleNamespace(pose=goal, union=None, kind="goal", key=("goal",))]
        kind = "vertex" if reset_every and int(x) % reset_every == 0 else "turn"
        if kind == "turn" and not turns:
            return []
        return [SimpleNamespace(pose=Pose(x, 0.0, 0.0), union=None, kind=kind, key=(kind, x))]

    def finish(nodes, unions, kinds, search_cost, expanded, generated):
        return nodes, kinds, search_cost

    try:
        out = astar(problem, successors, finish, max_expansions=100, time_limit=60.0, t0=time.perf_counter(),
                    max_turn_chain=max_turn_chain)  # fmt: skip
    except NoPathError as exc:
        out = exc
    return out, calls


def test_chains_of_turn_states_are_cut_at_max_turn_chain():
    """``max_turn_chain``: a node ending k consecutive turn states may have turn successors only
    while k < max_turn_chain; a node of another kind starts the count again."""
    for limit in (1, 4):
        out, calls = _line_search(limit)
        # the node at x ends a chain of x turn states: turns allowed while x < limit
        assert calls == [(float(x), x < limit) for x in range(limit + 1)]
        assert isinstance(out, NoPathError) and out.reason == "exhausted" and out.expanded == limit + 1
    nodes, kinds, cost = _line_search(20)[0]
    assert len(nodes) == 9 and cost == 8.0 and kinds[-1] == "goal"
    # a vertex state every third step: the node at x ends x % 3 turn states, the goal is reached
    (nodes, kinds, _), calls = _line_search(2, reset_every=3)
    assert kinds == ("start", "turn", "turn", "vertex", "turn", "turn", "vertex", "turn", "goal")
    assert calls == [(float(x), x % 3 < 2) for x in range(8)]


# -- no path: bounded search, what was explored -------------------------------------------
def test_enclosed_goal_raises_no_path_error():
    ring = [
        [[8.0, -3.0], [14.0, -3.0], [14.0, -2.0], [8.0, -2.0]],
        [[8.0, 2.0], [14.0, 2.0], [14.0, 3.0], [8.0, 3.0]],
        [[7.0, -3.0], [8.0, -3.0], [8.0, 3.0], [7.0, 3.0]],
        [[14.0, -3.0], [15.0, -3.0], [15.0, 3.0], [14.0, 3.0]],
    ]
    with pytest.raises(NoPathError) as info:
        plan(
            (0.0, 0.0, 0.0),
            (10.5, 0.0, 0.0),
            ring,
            1.0,
            bounds=(-2, -6, 18, 6),
            max_expansions=300,
            planner="paper",
        )
    exc = info.value
    assert exc.reason in ("exhausted", "expansions")
    assert exc.expanded >= 1 and exc.generated >= 1 and exc.seconds >= 0
    assert isinstance(exc.best, Plan) and exc.best.nodes[0] == Pose(0.0, 0.0, 0.0)
    assert "no path" in str(exc)
    if exc.reason == "exhausted":
        assert "the paper's node generation" in str(exc) and "enclosed" not in str(exc)


def test_limits_stop_the_search():
    sc = segplan.load_scenario(SCENARIOS / "turn_around.json")
    with pytest.raises(NoPathError) as info:
        plan_scenario(sc, max_expansions=1, planner="paper")
    assert info.value.reason == "expansions" and info.value.expanded == 1
    assert "the expansion limit max_expansions=1 was reached" in str(info.value)
    with pytest.raises(NoPathError) as info:
        plan_scenario(sc, time_limit=1e-9, planner="paper")
    assert info.value.reason == "time"
    assert "the time limit time_limit=1e-09 s was reached" in str(info.value)


# -- bad input -----------------------------------------------------------------------------
@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"L": 0.0}, "L"),
        ({"L": float("nan")}, "L"),
        ({"start": (0.0, 0.0)}, "start"),
        ({"goal": (0.0, float("inf"), 0.0)}, "goal"),
        ({"heuristic": "d"}, "heuristic"),
        ({"cost": "time"}, "cost"),
        ({"version": "c"}, "version"),
        ({"max_steer": 2.0}, "max_steer"),
        ({"half_width": -1.0}, "half_width"),
        ({"max_expansions": 0}, "max_expansions"),
        ({"time_limit": -1.0}, "time_limit"),
        ({"obstacles": [[[0.0, 0.0], [1.0, 0.0]]]}, "3 vertices"),
        ({"obstacles": [[[3, 0], [5, 2], [5, 0], [3, 2]]]}, "not a simple polygon"),  # a bow tie
        ({"obstacles": [[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]]}, "start"),
        ({"bounds": (0.0, 0.0, 1.0)}, "bounds"),
    ],
)
def test_bad_input_raises_value_error(kwargs, match):
    args = {"start": (0.0, 0.0, 0.0), "goal": (8.0, 0.0, 0.0), "obstacles": [], "L": 1.0}
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        plan(args.pop("start"), args.pop("goal"), args.pop("obstacles"), args.pop("L"), **args)


def test_a_bad_problem_given_to_plan_is_reported_as_plan_s():
    """``plan()`` makes the scenario: its errors name ``plan()`` as their source, as a
    scenario file's name its path (``make_scenario(source=...)``)."""
    with pytest.raises(segplan.ScenarioError, match=r"^plan\(\): start .*collides"):
        plan((0.0, 0.0, 0.0), (8.0, 0.0, 0.0), [[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]], 1.0)


def test_plan_scenario_rejects_non_scenario():
    with pytest.raises(ValueError, match="Scenario"):
        plan_scenario({"L": 1.0})


# -- heuristic (c) -------------------------------------------------------------------------
def test_characteristic_dimension():
    a = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    b = a + [3.0, 0.0]
    assert math.isclose(polygon_gap(a, b), 2.0)
    assert polygon_gap(a, a + 0.5) == 0.0
    shapely_gap = shapely.Polygon(a).distance(shapely.Polygon(b + [0.5, 2.5]))
    assert math.isclose(polygon_gap(a, b + [0.5, 2.5]), shapely_gap)
    assert math.isclose(characteristic_dimension([a, b]), 2.0)
    assert math.isclose(characteristic_dimension([a, b], bounds=(-0.5, -0.5, 10, 10)), 0.5)
    assert characteristic_dimension([], bounds=(0, 0, 4, 3)) == 3.0
    assert characteristic_dimension([]) == 1.0 and characteristic_dimension([], fallback=2.5) == 2.5


@pytest.mark.parametrize("wall", range(4))
def test_characteristic_dimension_measures_each_wall(wall):
    """One obstacle nearest to one wall: d_s is its gap to that wall (shapely's distance)."""
    bounds = (0.0, 0.0, 10.0, 8.0)
    corner = [(0.3, 3.0), (5.0, 0.4), (8.8, 3.0), (4.0, 6.5)][wall]  # 0.3, 0.4, 0.2, 0.5 from a wall
    a = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]) + corner
    walls = shapely.Polygon([(0, 0), (10, 0), (10, 8), (0, 8)]).exterior
    expected = shapely.Polygon(a).distance(walls)
    assert expected == pytest.approx([0.3, 0.4, 0.2, 0.5][wall])
    assert characteristic_dimension([a], bounds=bounds) == pytest.approx(expected)


def test_problem_defaults_are_the_papers_method():
    """``Problem``'s defaults: h' (a), the LONGD link cost, d_s = 0 and no turning radius."""
    from segplan.planning.paper.problem import Problem

    p = Problem(Pose(0.0, 0.0, 0.0), Pose(5.0, 0.0, 0.0), links=None)
    assert (p.heuristic, p.cost, p.ds_over_L, p.R) == ("a", "longd", 0.0, 0.0)


def test_heuristic_c_limits():
    """(c) with d_s = 0 weighs (a) fully; with a huge d_s it is the distance (b)."""
    sc = segplan.load_scenario(SCENARIOS / "fig5_example1.json")
    assert (
        plan_scenario(sc, "c", ds=0.0, planner="paper").nodes == plan_scenario(sc, "a", planner="paper").nodes
    )
    assert (
        plan_scenario(sc, "c", ds=1e12, planner="paper").nodes
        == plan_scenario(sc, "b", planner="paper").nodes
    )
    with pytest.raises(ValueError, match="ds"):
        plan_scenario(sc, "c", ds=-1.0, planner="paper")


def test_link_observer_records_without_changing_the_plan():
    """api.plan_scenario_observed: a study sees every link cost of a search; the plan is unchanged."""
    from segplan.planning.api import plan_scenario_observed

    sc = segplan.load_scenario(Path(__file__).resolve().parents[1] / "scenarios" / "fig5_example1.json")
    seen = []
    observed = plan_scenario_observed(sc, lambda u, c: seen.append((u, c)), heuristic="a")
    plain = plan_scenario(sc, heuristic="a", planner="paper")
    assert observed.nodes == plain.nodes and observed.cost == plain.cost
    assert len(seen) > len(observed.unions)
    ids = {id(u) for u, _ in seen}
    assert all(id(u) in ids for u in observed.unions)  # every link of the plan was costed
    for u, c in seen[:50]:
        assert c == pytest.approx(longd_exact(u.p0, u.p1, u.alpha, u.L), rel=0.03)
    with pytest.raises(ValueError, match="observer"):
        plan_scenario_observed(sc, "not callable")
