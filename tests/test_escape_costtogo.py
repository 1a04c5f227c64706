"""The lattice planner's tight arcs (segplan.planning.lattice.escape) and coarse cost-to-go
(segplan.planning.lattice.guide), issue 12.

Independent oracles: shapely's dense sampling of the swept segment
(:func:`segplan.measure_scenario_path`) for freedom and the front-wheel length, the circle
through the arc's poses (its centre from the pose's heading) for the arc's shape, and for the
wall-facing starts a bound from the kinematics alone: a forward path that starts with the
rear point A heading straight at a wall and turns its heading by 45 degrees moves the front
wheel B at least ``sqrt(R^2 + L^2) - L`` towards the wall (``dB_x = cos(theta) ds - L
sin(theta) dtheta`` with ``ds >= R |dtheta|``), so a start whose front wheel is closer to the
wall than that admits no forward plan to a goal behind it, escapes or not.
"""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from load_file import ROOT, load_file
from test_lattice_parts import astar_of, plan_of

import segplan.planning.lattice.search as lattice_module
from segplan import (
    NoPathError,
    ScenarioError,
    make_scenario,
    measure_scenario_path,
    plan_poses,
    plan_scenario,
)
from segplan.planning.context import workspace_of
from segplan.planning.dubins import dubins_length_scalar
from segplan.planning.lattice.clearance import ClearanceGrid
from segplan.planning.lattice.escape import (
    RADIUS_FACTORS,
    STEP,
    TURNS,
    hop_pairs,
    improve_with_arcs,
    tight_arcs,
)
from segplan.planning.lattice.frame import heading_angles
from segplan.planning.lattice.guide import FINER_CELLS, Guide, HeadingField, turns_tighter
from segplan.planning.lattice.primitives import max_reach
from segplan.planning.lattice.search import lattice_search, plan_lattice
from segplan.planning.links import LinkModel
from segplan.planning.plan import union_longd, unions_longd
from segplan.planning.schedule import SCHEDULE
from segplan.planning.validity import Workspace
from segplan.studies import floors

ROBOT = floors.ROBOT
BOUNDS = floors.SMALL_BOUNDS
R = ROBOT.min_turning_radius
ANGLES = heading_angles()


def _rect(x0, y0, x1, y1):
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


def _scenario(start, goal, obstacles=()):
    return make_scenario(ROBOT, start, goal, list(obstacles), BOUNDS)


def _workspace(sc):
    return Workspace(sc.enlarged, sc.robot.L, sc.free_bounds, sc.robot.max_curvature)


def _assert_joined(unions):
    for u, v in zip(unions, unions[1:], strict=False):
        assert u.p1 == v.p0  # exactly: the next union starts at the pose the last one ends


def _assert_valid(plan, sc):
    """Ends exact, unions joined, steering limit per union, and the dense shapely oracle."""
    assert plan.nodes[0] == sc.start and plan.nodes[-1] == sc.goal
    assert plan.unions[0].p0 == sc.start and plan.unions[-1].p1 == sc.goal
    _assert_joined(plan.unions)
    assert tuple(plan.nodes[1:]) == tuple(u.p1 for u in plan.unions)
    for u in plan.unions:
        assert u.max_curvature() <= sc.robot.max_curvature * (1 + 1e-9)
    m = measure_scenario_path(plan_poses(plan), sc)
    assert not m.collides
    assert m.reversals == 0
    # LONGD is the front wheel's path length: the plan's cost against shapely-free sampling
    assert m.front_length == pytest.approx(plan.cost, rel=2e-3)
    return m


# -- 1. tight arcs ----------------------------------------------------------------------------
OBSTACLE = _rect(9.0, 5.0, 11.0, 7.0)
poses = st.tuples(st.floats(6.0, 14.0), st.floats(2.0, 10.0), st.floats(-math.pi, math.pi, exclude_max=True))


def _side(arc):
    """1: the arc turns left, -1: right."""
    u = arc.unions[0]
    return 1 if math.remainder(u.p1.theta - u.p0.theta, 2 * math.pi) > 0 else -1


def _check_arcs(sc, pose, into):
    ws = _workspace(sc)
    arcs = tight_arcs(LinkModel(ws), pose, R, into=into)
    p = tuple(pose)
    for arc in arcs:
        assert arc.into is into
        assert len(arc.unions) >= 1
        _assert_joined(arc.unions)
        assert arc.unions[0].p0 == arc.first and arc.unions[-1].p1 == arc.last
        if into:
            assert tuple(arc.last) == p and arc.inner == arc.first
        else:
            assert tuple(arc.first) == p and arc.inner == arc.last
        assert arc.cost == pytest.approx(unions_longd(arc.unions), rel=1e-12)
        assert arc.cost == pytest.approx(sum(union_longd(u) for u in arc.unions), rel=1e-12)
        for u in arc.unions:
            assert u.max_curvature() <= ROBOT.max_curvature * (1 + 1e-9)
        # the turn: every union turns by STEP the same way, and the whole is one of TURNS
        steps = [math.remainder(u.p1.theta - u.p0.theta, 2 * math.pi) for u in arc.unions]
        side = 1 if steps[0] > 0 else -1
        assert steps == pytest.approx([side * STEP] * len(steps), abs=1e-9)
        turn = abs(sum(steps))
        assert min(abs(turn - t) for t in TURNS) < 1e-9
        # along a circle: radius from the chord over the whole arc, and every node on the
        # circle tangent to the fixed pose at it, on the turning side
        chord = math.dist(arc.first[:2], arc.last[:2])
        rho = chord / (2 * math.sin(turn / 2))
        assert RADIUS_FACTORS[0] * R * (1 - 1e-9) <= rho <= 1.1 * R * (1 + 1e-9)
        cx = p[0] - side * rho * math.sin(p[2])
        cy = p[1] + side * rho * math.cos(p[2])
        for q in [arc.first] + [u.p1 for u in arc.unions]:
            assert math.hypot(q[0] - cx, q[1] - cy) == pytest.approx(rho, abs=1e-9)
        # free: shapely's dense oracle over the whole chain (and so every union)
        m = measure_scenario_path(plan_poses(arc.unions), sc)
        assert not m.collides
        assert m.reversals == 0
    return arcs


def _valid_or_skip(pose, goal, obstacles):
    try:
        return _scenario(pose, goal, obstacles)
    except ScenarioError:
        assume(False)


@settings(max_examples=25)
@given(pose=poses, into=st.booleans())
def test_tight_arcs_in_an_empty_room_join_keep_the_limit_turn_on_a_circle_and_are_free(pose, into):
    sc = _valid_or_skip(pose, (2.0, 2.0, 0.0), ())
    arcs = _check_arcs(sc, sc.start, into)
    # far from the walls every side and every turn is offered (6 .. 10 m from x walls)
    if min(pose[0] - 0.3, 19.7 - pose[0], pose[1] - 0.3, 11.7 - pose[1]) > 2 * 1.1 * R + ROBOT.L:
        assert len(arcs) == 2 * len(TURNS)


@settings(max_examples=30)
@given(pose=poses, into=st.booleans())
def test_tight_arcs_next_to_an_obstacle_join_keep_the_limit_and_are_free(pose, into):
    sc = _valid_or_skip(pose, (2.0, 2.0, 0.0), [OBSTACLE])
    _check_arcs(sc, sc.start, into)


@pytest.mark.parametrize("into", [False, True])
def test_tight_arcs_in_the_open_offer_every_turn_on_both_sides(into):
    sc = _scenario((10.0, 6.0, 0.3), (2.0, 2.0, 0.0))
    arcs = _check_arcs(sc, sc.start, into)
    assert {_side(a) for a in arcs} == {1, -1}
    assert sorted(len(a.unions) for a in arcs) == sorted(2 * [int(round(t / STEP)) for t in TURNS])


def test_tight_arcs_stop_before_an_obstacle_the_dense_oracle_sees():
    """A pose just left of a block: the left arcs end before the block (and are free), the
    right ones go all the way."""
    sc = _scenario((10.0, 4.6, 0.0), (2.0, 2.0, 0.0), [_rect(8.0, 6.0, 14.0, 7.0)])
    arcs = _check_arcs(sc, sc.start, False)
    assert sum(_side(a) == -1 for a in arcs) == len(TURNS)
    assert sum(_side(a) == 1 for a in arcs) < len(TURNS)


# -- 2. escapes -------------------------------------------------------------------------------
XMAX = BOUNDS[2] - ROBOT.half_width  # the free bounds' right wall


def _facing_wall(gap, heading=0.0, y=6.0):
    """Front wheel ``gap`` m from the right wall (planning model), goal 7 m behind heading back."""
    bx = XMAX - gap
    ax, ay = bx - ROBOT.L * math.cos(heading), y - ROBOT.L * math.sin(heading)
    return _scenario((ax, ay, heading), (ax - 7.0, y, math.pi))


@pytest.mark.parametrize(("gap", "heading"), [(0.43, 0.0), (0.46, 0.0), (0.49, 0.0), (0.35, 0.1), (0.3, 0.2)])
def test_a_start_facing_a_wall_escapes_by_tight_arcs(gap, heading):
    sc = _facing_wall(gap, heading)
    with pytest.raises(NoPathError) as e:
        lattice_search(sc, escapes=False)
    assert e.value.reason == "exhausted"
    plan, _ = lattice_search(sc)
    assert "arc" in plan.kinds
    assert plan.kinds[0] == "start" and plan.kinds[-1] == "goal"
    _assert_valid(plan, sc)


@pytest.mark.parametrize("gap", [0.3, 0.35, 0.4])
def test_no_escape_where_the_kinematics_forbid_a_forward_turn(gap):
    """Heading straight at the wall with the front wheel closer than sqrt(R^2 + L^2) - L:
    no forward plan exists (module docstring); the arcs must not invent one."""
    assert gap < math.hypot(R, ROBOT.L) - ROBOT.L
    sc = _facing_wall(gap)
    with pytest.raises(NoPathError) as e:
        lattice_search(sc)
    assert e.value.reason == "exhausted"
    # the message says what was tried and counts what the error counts (issue 25: --json and
    # the message disagreed after the escapes), and claims no proof it does not have
    message = str(e.value)
    assert message.endswith(f"; expanded {e.value.expanded} states")
    assert "searches between tight arcs at the ends:" in message and "none joined" in message
    assert "not a proof that no path exists" in message and "tighter than the lattice's" in message


def test_escape_searches_run_at_the_first_resolution_only(monkeypatch):
    """The search between the start and the goal retries at the finer resolution; the
    searches between the arcs' ends do not (lattice_search's docstring)."""
    calls = []
    inner = lattice_module._lattice_search

    def spy(sub, **kw):
        calls.append(kw["retry"])
        return inner(sub, **kw)

    monkeypatch.setattr(lattice_module, "_lattice_search", spy)
    with pytest.raises(NoPathError) as e:
        lattice_search(_facing_wall(0.35))  # no forward plan: every escape pair is tried
    assert e.value.reason == "exhausted"
    assert calls[0] is True and len(calls) > 2 and not any(calls[1:])


def test_escape_searches_keep_the_callers_schedule(monkeypatch):
    """The searches between the arcs' ends run with the caller's schedule: at most its
    ``max_escapes`` of them, each with that schedule; then the hops' (``HOP_ESCAPES`` at most),
    with it too."""
    calls = []
    inner = lattice_module._lattice_search

    def spy(sub, **kw):
        calls.append(kw["schedule"])
        return inner(sub, **kw)

    monkeypatch.setattr(lattice_module, "_lattice_search", spy)
    schedule = dataclasses.replace(SCHEDULE, max_escapes=2, guide_after=32)
    with pytest.raises(NoPathError):
        lattice_search(_facing_wall(0.35), schedule=schedule)  # no forward plan: escapes run out
    sc = _facing_wall(0.35)
    hopping = min(lattice_module.HOP_ESCAPES, len(hop_pairs(sc, LinkModel(workspace_of(sc)))))
    assert hopping > 0 and len(calls) == 1 + 2 + hopping and all(s is schedule for s in calls)


def test_random_floor_any_114_needs_the_arcs():
    sc = floors.random_floor("any", 114)
    with pytest.raises(NoPathError) as e:
        lattice_search(sc, escapes=False)
    assert e.value.reason == "exhausted"
    plan, _ = lattice_search(sc)
    assert "arc" in plan.kinds
    assert plan.cost == pytest.approx(unions_longd(plan.unions), rel=1e-12)
    _assert_valid(plan, sc)


@pytest.mark.parametrize(("kind", "index"), [("any", 114), ("natural", 77)])
def test_plan_scenario_solves_floors_the_lattice_alone_exhausts(kind, index):
    sc = floors.random_floor(kind, index)
    with pytest.raises(NoPathError):
        lattice_search(sc, escapes=False)
    _assert_valid(plan_scenario(sc), sc)


# -- 3. improvement by arcs -------------------------------------------------------------------
def test_improve_with_arcs_turns_under_the_obstacle_on_any_166():
    sc = floors.random_floor("any", 166)
    lattice_only, _ = lattice_search(sc, escapes=False)
    dubins = dubins_length_scalar(*sc.start, *sc.goal, R)
    assert lattice_only.cost > SCHEDULE.improve_gap * dubins  # the condition for trying the arcs
    improved, _ = lattice_search(sc)
    assert "arc" in improved.kinds
    assert improved.cost < lattice_only.cost
    assert improved.cost == pytest.approx(unions_longd(improved.unions), rel=1e-12)  # its own LONGD
    m0 = _assert_valid(lattice_only, sc)
    m1 = _assert_valid(improved, sc)
    assert m1.front_length < m0.front_length  # shorter by the independent measure too


def test_improve_with_arcs_returns_a_plan_near_the_dubins_length_unchanged():
    sc = floors.hard_cases()["door"]
    ws = _workspace(sc)
    plan, _ = lattice_search(sc, escapes=False, workspace=ws)
    assert plan.cost <= SCHEDULE.improve_gap * dubins_length_scalar(*sc.start, *sc.goal, R)
    assert improve_with_arcs(sc, LinkModel(ws), plan, 0.0) is plan
    again, _ = lattice_search(sc)
    assert [(u.p0, u.p1, u.alpha) for u in again.unions] == [(u.p0, u.p1, u.alpha) for u in plan.unions]
    assert again.kinds == plan.kinds and again.cost == plan.cost


# -- 4. the coarse cost-to-go -----------------------------------------------------------------
def _field(sc, cells=2):
    """The HeadingField (cell ``L / cells``) of a scenario, on a clearance grid built as the
    lattice search builds it (:func:`_grid_of`)."""
    grid, goal_l = _grid_of(sc)
    rc = HeadingField.resolution(grid, sc.robot.L, cells)
    assert rc == sc.robot.L / cells
    return HeadingField(grid, sc.robot, goal_l, rc), goal_l


def _h(theta):
    (k,) = np.nonzero(np.abs(ANGLES - theta) < 1e-9)[0]
    return int(k)


def test_heading_field_near_and_far_in_an_empty_room():
    sc = _scenario((2.0, 6.0, 0.0), (14.0, 6.0, 0.0))  # lattice frame = world shifted by the start
    field, (gx, gy, gth) = _field(sc)
    assert (gx, gy, gth) == (12.0, 0.0, 0.0)
    assert field.estimate(gx - 0.1, gy, _h(0.0)) < 0.5
    for x, y, th in [
        (0.0, 0.0, 0.0),
        (-1.0, 4.0, math.pi / 2),
        (2.0, -4.0, math.pi),
        (0.0, 5.0, -math.pi / 2),
    ]:
        e = field.estimate(x, y, _h(th))
        assert math.isfinite(e)
        assert e >= math.hypot(gx - x, gy - y) - 2 * field.rc
        # not absurdly above a Dubins car's length (plus the union's detour of the front wheel)
        assert e <= 1.5 * dubins_length_scalar(x, y, th, gx, gy, gth, R) + 2 * ROBOT.L


def test_heading_field_is_mirror_symmetric_in_a_symmetric_room():
    """Start and goal on the room's middle line, facing along it: the floor is symmetric about
    that line, so is the cost-to-go (coarse state (i, j, h) and (i, -j, -h)), edge rows
    included (an oracle of the graph's construction: every primitive kept or dropped alike on
    both sides)."""
    sc = _scenario((2.0, 6.0, 0.0), (14.0, 6.0, 0.0))  # BOUNDS: y from 0 to 12
    field, _ = _field(sc)
    j = np.arange(field.ny) + field.J0
    assert np.array_equal(j, -j[::-1])  # the coarse rows are symmetric about the start's
    mirror = [
        int(np.argmin(np.abs(np.remainder(ANGLES + a + math.pi, 2 * math.pi) - math.pi))) for a in ANGLES
    ]
    assert all(
        abs(math.remainder(ANGLES[k] + a, 2 * math.pi)) < 1e-12 for k, a in zip(mirror, ANGLES, strict=True)
    )
    t = field.table
    m = t[:, ::-1, :][:, :, mirror]
    assert np.array_equal(np.isinf(t), np.isinf(m)) and np.isfinite(t).sum() > 1000
    finite = np.isfinite(t)
    assert np.allclose(t[finite], m[finite], rtol=1e-12, atol=1e-12)


def test_heading_field_knows_the_heading():
    sc = _scenario((2.0, 6.0, 0.0), (14.0, 6.0, 0.0))
    field, (gx, gy, _) = _field(sc)
    facing = field.estimate(gx - 1.0, gy, _h(0.0))
    away = field.estimate(gx - 1.0, gy, _h(math.pi))
    assert facing < 1.5
    assert away > facing + 2 * R  # a loop of radius >= R to come about
    # just past the goal with its heading: a whole turn (rear path >= 2 pi R, and the front
    # wheel's is longer), up to the coarse lattice's rounding
    assert field.estimate(gx + 1.0, gy, _h(0.0)) > 2 * math.pi * R - 2 * field.rc


def test_heading_field_is_finite_in_the_open():
    """Optimistic: in an empty room every coarse state at least 2 R + L from the walls
    (room for a turn whichever way it faces) has a coarse route to the goal."""
    sc = _scenario((2.0, 6.0, 0.0), (14.0, 6.0, 0.0))
    field, _ = _field(sc)
    X = (np.arange(field.nx) + field.I0) * field.rc + sc.start.x  # world (the start heads along x)
    Y = (np.arange(field.ny) + field.J0) * field.rc + sc.start.y
    m = 2 * R + ROBOT.L
    xmin, ymin, xmax, ymax = BOUNDS
    inner = ((X >= xmin + m) & (X <= xmax - m))[:, None] & ((Y >= ymin + m) & (Y <= ymax - m))[None, :]
    assert inner.sum() > 300
    assert np.isfinite(field.table[inner]).all()


@pytest.mark.parametrize("width", [0.2, 1.0])
def test_heading_field_is_infinite_beyond_a_wall_across_the_room(width):
    wall = _rect(10.0 - width / 2, 0.0, 10.0 + width / 2, 12.0)
    sc = _scenario((2.0, 6.0, 0.0), (16.0, 6.0, 0.0), [wall])
    field, (gx, gy, _) = _field(sc)
    assert field.estimate(gx - 0.1, gy, _h(0.0)) < 0.5  # the goal's side is reached
    for x, y in [(0.0, 0.0), (2.0, 3.0), (5.0, -4.0)]:  # the start's side
        for th in (0.0, math.pi / 2, math.pi):
            assert field.estimate(x, y, _h(th)) == math.inf
    # every coarse state whose segment lies wholly on the start's side of the enlarged wall
    X = (np.arange(field.nx) + field.I0) * field.rc + sc.start.x
    left = 10.0 - width / 2 - ROBOT.half_width
    assert np.isinf(field.table[X + ROBOT.L < left]).all()
    assert np.isfinite(field.table[X > 10.0 + width / 2 + ROBOT.half_width]).any()


def test_a_state_without_a_coarse_route_ranks_after_every_state_with_one():
    """Where the field is infinite, the guided h' is the bound plus the field's largest finite
    value: above every finite estimate, so A* (equal g) expands such a state after them."""
    wall = _rect(9.9, 0.0, 10.1, 12.0)
    sc = _scenario((2.0, 6.0, 0.0), (16.0, 6.0, 0.0), [wall])
    field, _ = _field(sc)
    finite = field.table[np.isfinite(field.table)]
    assert finite.size and field.worst == finite.max()

    guide = Guide(None, sc.robot, None)  # no grid: the field is handed to it
    assert guide.raise_bound(0.0, 0.0, 0, 3.0) == 3.0  # no field built: the bound
    guide.field = field
    assert field.estimate(0.0, 0.0, 0) == math.inf  # the start's side of the wall
    for bound in (0.0, 3.0, 11.5):
        assert guide.raise_bound(0.0, 0.0, 0, bound) == bound + field.worst >= finite.max()
    x, y = 12.0, 1.0  # the goal's side of the wall (lattice frame): the estimate, or a larger bound
    e = field.estimate(x, y, 0)
    assert math.isfinite(e)
    assert guide.raise_bound(x, y, 0, 0.0) == e
    assert guide.raise_bound(x, y, 0, e + 1.0) == e + 1.0


def _wide_floor():
    """robot-002 of benchmarks/robots.py: a robot of 25 degree steering (R = 2.14 L) on a 10 x 9 m
    floor whose goal is reached by a loop around an obstacle."""
    sc = load_file(ROOT / "benchmarks" / "robots.py", "robots_probe").robot_floor(2)
    assert math.isclose(math.degrees(sc.robot.max_steer), 25.0)
    return sc


def test_a_robot_that_turns_widely_gets_the_finer_coarse_field():
    """Its coarse primitives (cell L / 2) leave the start without a route; the finer lattice
    (L / FINER_CELLS) has one, and the search is guided to a valid plan in few expansions."""
    sc = _wide_floor()
    wide = sc.robot
    coarse, _ = _field(sc)
    finer, _ = _field(sc, FINER_CELLS)
    assert coarse.estimate(0.0, 0.0, 0) == math.inf
    assert math.isfinite(finer.estimate(0.0, 0.0, 0))
    assert turns_tighter(wide, wide.L / 2, wide.L / FINER_CELLS)
    # the default robot's two lattices turn alike: no finer field
    assert not turns_tighter(ROBOT, ROBOT.L / 2, ROBOT.L / FINER_CELLS)
    plan, _ = lattice_search(sc, max_expansions=1000, time_limit=60.0)  # expansions decide
    assert SCHEDULE.guide_after < plan.expanded < 1000
    _assert_valid(plan, sc)
    # the guide's length estimate from the start is close to the plan's LONGD
    assert 0.8 * plan.cost < finer.estimate(0.0, 0.0, 0) < 1.2 * plan.cost


# -- 5. bad input -----------------------------------------------------------------------------
@pytest.mark.parametrize("bad", [1, 0, None, "yes"])
def test_escapes_must_be_a_bool(bad):
    sc = _facing_wall(0.46)
    with pytest.raises(ValueError, match="escapes"):
        lattice_search(sc, escapes=bad)


# -- 6. the guide -----------------------------------------------------------------------------
def test_the_guide_solves_any_6_in_few_expansions():
    sc = floors.random_floor("any", 6)
    plan = plan_lattice(sc, max_expansions=1000, time_limit=60.0)  # the expansions decide, not time
    assert SCHEDULE.guide_after < plan.expanded < 1000  # needed the guide, and it did the job
    _assert_valid(plan, sc)
    # the same search, composed as the planner composes it, finds it; without the guide the
    # same limit is not enough
    found, outcome, _ = plan_of(astar_of(sc), max_expansions=1000)
    assert outcome == "found" and found.expanded == plan.expanded
    unguided = dataclasses.replace(SCHEDULE, guide_after=10**9)
    _, outcome, _ = plan_of(astar_of(sc, schedule=unguided), max_expansions=1000)
    assert outcome == "expansions"


# -- 5. the guide's window on floors too large for a whole-grid guide --------------------------
def _grid_of(sc):
    """The clearance grid of a scenario as the lattice search lays it out, and the goal in
    the lattice frame."""
    L, R_ = sc.robot.L, sc.robot.min_turning_radius
    ws = _workspace(sc)
    cell = L / 16
    pad = int(math.ceil(max_reach(L, sc.robot.max_steer, L / 8) / cell)) + 2
    grid = ClearanceGrid(ws.convex, tuple(sc.start), sc.free_bounds, cell, pad, sc.goal, 4 * L + 4 * R_)
    gx, gy = grid.to_lattice(np.array([sc.goal[:2]]))[0]
    return grid, (gx, gy, math.remainder(sc.goal.theta - sc.start.theta, 2 * math.pi))


@settings(max_examples=20, deadline=None)
@given(
    extra=st.floats(0.0, 6.0),
    share=st.floats(0.0, 0.5),
    gap=st.floats(2.0, 9.0),
)
def test_the_corridor_is_the_box_of_every_cell_of_a_route_short_enough(extra, share, gap):
    """Brute force over the field's cells: the corridor keeps exactly the cells whose octile
    distances from start and goal sum to at most the shortest route's, grown; its box spans
    them, and its near cells are them and their neighbours."""
    from segplan.planning.lattice.clearance import DistanceField

    wall = _rect(9.9, 0.0, 10.1, 12.0 - gap)  # a wall with a gap of ``gap`` at the top
    sc = _scenario((2.0, 2.0, 0.0), (16.0, 2.0, 0.0), [wall])
    grid, (gx, gy, _) = _grid_of(sc)
    field = DistanceField(grid, (gx, gy), 0.25)
    corridor = field.corridor((0.0, 0.0), extra, share)
    box = corridor.box
    total = field.octile_from((0.0, 0.0)) + field.octile_goal
    best = total.min()
    kept = total <= best * (1 + share + 1e-9) + extra
    assert np.array_equal(corridor.cells, kept)
    ii, jj = np.nonzero(kept)
    X, Y = field.x0 + ii * field.c, field.y0 + jj * field.c
    assert box == (X.min(), Y.min(), X.max() + field.c, Y.max() + field.c)
    # near: a kept cell within one cell (8-neighbourhood), by brute force
    ni, nj = np.nonzero(corridor.near)
    for a, b in zip(ni, nj, strict=True):
        assert kept[max(a - 1, 0) : a + 2, max(b - 1, 0) : b + 2].any()
    assert corridor.near[kept].all()
    assert corridor.area == pytest.approx(len(ni) * field.c**2)
    # covers: a point lies in a near cell (cell centres, and points off the field)
    cx = field.x0 + (np.arange(-2, field.nx + 2) + 0.5) * field.c
    cy = field.y0 + (np.arange(-2, field.ny + 2) + 0.5) * field.c
    inside = np.zeros((field.nx + 4, field.ny + 4), dtype=bool)
    inside[2:-2, 2:-2] = corridor.near
    assert np.array_equal(corridor.covers(cx, cy), inside)
    # both ends inside; the route over the gap (above the wall's top) inside
    for x, y in ((0.0, 0.0), (gx, gy)):
        assert box[0] <= x <= box[2] and box[1] <= y <= box[3]
    top = 12.0 - gap - sc.start.y  # lattice frame: y shifted by the start
    assert box[3] >= top


def test_the_corridor_is_none_where_the_ends_are_not_joined():
    from segplan.planning.lattice.clearance import DistanceField

    wall = _rect(9.9, 0.0, 10.1, 12.0)
    sc = _scenario((2.0, 6.0, 0.0), (16.0, 6.0, 0.0), [wall])
    grid, (gx, gy, _) = _grid_of(sc)
    field = DistanceField(grid, (gx, gy), 0.25)
    assert field.corridor((0.0, 0.0), 5.0) is None
    assert field.corridor((-50.0, 0.0), 5.0) is None  # off the field


def test_a_guide_too_large_for_the_whole_grid_is_built_over_the_window(monkeypatch):
    """With a state budget below the whole grid's, the guide is built over the corridor's cells
    (grown while the start has no coarse route in it): the same estimates inside the window
    where the whole grid's route stays inside it, never below the whole grid's (a part of its
    graph), ``inf`` outside it."""
    import segplan.planning.lattice.guide as guide_module
    from segplan.planning.lattice.clearance import DistanceField

    sc = _scenario((2.0, 6.0, 0.0), (16.0, 6.0, 0.0))
    grid, goal_l = _grid_of(sc)
    field = DistanceField(grid, goal_l[:2], 0.25)
    whole = Guide(grid, sc.robot, goal_l)
    assert whole.build()
    states = whole.field.nx * whole.field.ny * 16
    asked = []

    def window(scale):  # a slack of 1 m, doubled on request (the schedule's is wider)
        asked.append(scale)
        return field.corridor((0.0, 0.0), 1.0 * scale)

    monkeypatch.setattr(guide_module, "MAX_STATES", states // 2)
    assert Guide(grid, sc.robot, goal_l).build() is False  # no window: no guide, as before
    windowed = Guide(grid, sc.robot, goal_l, window)
    assert windowed.build() and asked == [1.0]  # the start has a route in the first window
    assert SCHEDULE.guide_box(field, 1.0, 1.0, 2.0) == field.corridor((0.0, 0.0), 16.0, 0.2)
    f = windowed.field
    corridor = window(asked[-1])
    box = corridor.box
    X, Y = (np.arange(f.nx) + f.I0) * f.rc, (np.arange(f.ny) + f.J0) * f.rc
    inside = corridor.covers(X, Y)
    assert inside.sum() * 16 <= states // 2 < states
    assert np.isinf(f.table[~inside]).all()  # no estimate off the corridor
    w = whole.field  # the same coarse lattice (cell, origin) over the whole grid
    assert w.rc == f.rc
    part = w.table[f.I0 - w.I0 : f.I0 - w.I0 + f.nx, f.J0 - w.J0 : f.J0 - w.J0 + f.ny]
    assert part.shape == f.table.shape
    assert (f.table[inside] >= part[inside] * (1 - 1e-12)).all()
    assert f.estimate(0.0, 0.0, 0) < math.inf
    # a straight run along the room: the window's estimate equals the whole grid's there
    for x in (0.0, 4.0, 8.0):
        assert f.estimate(x, 0.0, 0) == pytest.approx(whole.field.estimate(x, 0.0, 0), rel=1e-12)
    # beyond the window: no estimate
    if box[3] + 2.0 < 6.0:
        assert f.estimate(4.0, box[3] + 2.0, 0) == math.inf
