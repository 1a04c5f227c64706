"""The lattice planner's parts, each alone (issue 24): the lattice frame, the lazy edges, the schedule.

Also the helpers the other lattice tests build a search with: :func:`astar_of` composes the
A* that ``plan_lattice(scenario, retry=False)`` runs first from its parts (a subclass, a
schedule or parts of the test's choosing), :func:`plan_of` runs it as the planner does.
"""

import dataclasses
import math
import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from segplan.planning.lattice.astar import LatticeAStar
from segplan.planning.lattice.edges import LazyEdges
from segplan.planning.lattice.frame import NH, LatticeFrame, heading_angles
from segplan.planning.lattice.primitives import primitive_set
from segplan.planning.lattice.search import GOAL_RADIUS, lattice_floor, lattice_resolutions
from segplan.planning.links import LinkModel
from segplan.planning.schedule import SCHEDULE, Schedule
from segplan.planning.validity import Workspace

DEG = math.pi / 180.0


# -- helpers of the lattice tests ------------------------------------------------------------
def astar_of(
    sc, *, cls=LatticeAStar, resolution=None, weight=2.0, analytic_every=8, schedule=SCHEDULE, **parts
):
    """The A* that ``plan_lattice(sc, retry=False, ...)`` runs first (same grid, field and
    lattice), as ``cls`` with ``schedule`` and the given ``parts``; not run."""
    robot = sc.robot
    tries, cell = lattice_resolutions(sc, resolution, False, None, schedule)
    ws = Workspace(sc.enlarged, robot.L, sc.free_bounds, robot.max_curvature)
    grid, field = lattice_floor(sc, ws, tries, cell, schedule)
    radius = GOAL_RADIUS[0] * robot.min_turning_radius + GOAL_RADIUS[1] * robot.L
    return cls(
        sc, ws, LinkModel(ws), grid, field, tries[0], weight=weight, analytic_every=analytic_every,
        goal_radius=radius, banned=set(), schedule=schedule, **parts,
    )  # fmt: skip


def plan_of(search, max_expansions=200_000, final_check=True):
    """Run ``search`` as the planner does at one resolution: a found plan's unions checked by
    the certified test (the search runs again without a refused one, unless not
    ``final_check``). Returns ``(plan or None, outcome, plans made)``."""
    t0 = time.perf_counter()
    made = []
    while True:
        outcome, expanded = search.run(max_expansions, t0 + 120.0)
        if outcome != "found":
            return None, outcome, made
        edges = search.chain(search.goal_parent[0])
        plan = search.make_plan(edges, search.goal_parent[1], expanded, t0)
        made.append(list(edges))
        bad = [i for i, u in enumerate(plan.unions) if not search.ws.union_free(u)] if final_check else []
        if not bad:
            return plan, outcome, made
        for i in bad:
            search.banned.add(edges[i] if i < len(edges) else ("final", search.goal_parent[0]))


# -- the lattice frame -----------------------------------------------------------------------
origins = st.tuples(st.floats(-50, 50), st.floats(-50, 50), st.floats(-math.pi, math.pi))
states = st.tuples(st.integers(-60, 60), st.integers(-60, 60), st.integers(0, NH - 1))


def _state_of(frame, pose):
    """The lattice state of a world pose (the inverse of LatticeFrame.pose, computed apart)."""
    dx, dy = pose[0] - frame.x, pose[1] - frame.y
    c, s = math.cos(frame.theta), math.sin(frame.theta)
    i, j = (c * dx + s * dy) / frame.r, (-s * dx + c * dy) / frame.r
    dth = math.remainder(pose[2] - frame.theta, 2 * math.pi)
    h = int(np.argmin(np.abs(np.remainder(heading_angles() - dth + math.pi, 2 * math.pi) - math.pi)))
    return (i, j, h)


@settings(max_examples=200)
@given(origin=origins, key=states, r=st.sampled_from([0.0625, 0.125, 0.25]))
def test_state_to_pose_to_state(origin, key, r):
    frame = LatticeFrame(origin, r, 1.0)
    i, j, h = _state_of(frame, frame.pose(key))
    assert (i, j) == pytest.approx(key[:2], abs=1e-6) and h == key[2]


def test_the_origin_state_is_the_origin_pose():
    frame = LatticeFrame((1.5, -2.0, 0.7), 0.125, 1.0)
    assert frame.pose((0, 0, 0)) == (1.5, -2.0, 0.7)
    assert frame.pose((0, 0, 4)) == pytest.approx((1.5, -2.0, 0.7 + math.pi / 2))


@settings(max_examples=60)
@given(origin=origins, key=states, r=st.sampled_from([0.0625, 0.125]))
def test_a_primitives_union_joins_the_two_states_poses(origin, key, r):
    frame = LatticeFrame(origin, r, 1.0)
    for p in primitive_set(1.0, 45 * DEG, r).by_heading[key[2]]:
        u = frame.union(key, p)
        end = frame.end(key, p)
        assert end == (key[0] + p.di, key[1] + p.dj, p.h1)
        assert tuple(u.p0) == frame.pose(key) and tuple(u.p1) == frame.pose(end)  # exactly
        assert u.alpha == p.alpha and u.d == pytest.approx(p.d, rel=1e-9)


# -- the lazy edges on a toy graph -----------------------------------------------------------
class _Toy:
    """Edges ``(state, m)`` with a grid screen and a check chosen by the test; logs the checks."""

    def __init__(self, screen=None, passing=()):
        self.screens = screen or {}
        self.passing = set(passing)
        self.checked = []

    def screen(self, edge):
        return self.screens.get(edge, (False, False))

    def check(self, edge):
        self.checked.append(edge)
        return edge in self.passing


def test_a_deferred_edge_is_checked_once_when_its_state_is_due():
    toy = _Toy(passing={("a", 0)})
    edges = LazyEdges(toy.screen, toy.check)
    edges.defer("x", free=False)
    edges.defer("y", free=True)  # the grid cleared it: nothing to check
    assert edges.pending("x") and not edges.pending("y")
    assert toy.checked == []  # nothing checked before the state is due
    assert edges.check("x", ("a", 0))
    assert not edges.pending("x") and toy.checked == [("a", 0)]
    edges.defer("z", free=False)
    edges.defer("z", free=True)  # a new edge the grid clears replaces the unsure one
    assert not edges.pending("z")


def test_a_failed_check_is_remembered_and_the_edge_never_used_again():
    toy = _Toy()
    edges = LazyEdges(toy.screen, toy.check)
    edges.defer("x", free=False)
    assert not edges.check("x", ("a", 0))
    assert ("a", 0) in edges.failed
    toy.passing.add(("a", 0))  # even if it would pass now
    assert edges.repair([(1.0, "a", ("a", 0))]) is None
    assert toy.checked == [("a", 0)]  # the repair skipped it without a check


def test_repair_takes_the_cheapest_passing_edge():
    options = [(3.0, "c", ("c", 0)), (1.0, "a", ("a", 0)), (2.0, "b", ("b", 1)), (2.0, "b", ("b", 0))]
    # the cheapest fails its check, ("b", 0) is certainly failing on the grid, ("b", 1) passes
    toy = _Toy(screen={("b", 0): (False, True)}, passing={("b", 1), ("c", 0)})
    edges = LazyEdges(toy.screen, toy.check)
    assert edges.repair(options) == (2.0, "b", ("b", 1))
    assert toy.checked == [("a", 0), ("b", 1)]  # cheapest first; the grid's failure unchecked
    assert edges.failed == {("a", 0), ("b", 0)}
    # an edge the grid clears needs no check
    toy2 = _Toy(screen={("c", 0): (True, False)})
    assert LazyEdges(toy2.screen, toy2.check).repair(options[:1]) == options[0] and toy2.checked == []


def test_repair_within_a_budget_and_without_a_passing_edge():
    toy = _Toy(passing={("a", 0), ("b", 0)})
    edges = LazyEdges(toy.screen, toy.check)
    assert edges.repair([(5.0, "a", ("a", 0)), (4.0, "b", ("b", 0))], budget=4.5) == (4.0, "b", ("b", 0))
    edges.reset()
    assert edges.repair([(5.0, "a", ("a", 0))], budget=4.5) is None
    assert ("a", 0) in edges.failed  # over the budget: not used again
    assert edges.repair([]) is None
    edges.reset()
    assert edges.repair([(4.5, "a", ("a", 0))], budget=4.5) == (4.5, "a", ("a", 0))  # within: at it too


# -- the schedule ----------------------------------------------------------------------------
def test_the_default_schedule_is_the_one_every_plan_was_made_with():
    # the values the search used before the record (issue 24): pinned
    assert dataclasses.asdict(SCHEDULE) == {
        "approach_after": 32,
        "approach_limit": 60,
        "approach_tries": 2,
        "approach_candidates": 8,
        "steer_slack": 1.1,
        "enclosure_after": 256,
        "enclosure_limit": 300,
        "approach_growth": 120,
        "enclosed_expansions": 192,
        "guide_after": 64,
        "guided_weight": 1.2,
        "escalate_every": 20_000,  # issue 25: above what any planned 30 x 20 m kind floor needs
        "escalate_factor": 1.3,
        "guide_window": (4.0, 4.0, 0.1),  # issue 25: only where the whole grid's guide is too large
        "deadline_every": 64,
        "grid_margin": (4.0, 4.0),
        "max_escapes": 16,
        "improve_gap": 1.3,
        "shortcut_window": 16,
        "wide_turn_cells": 32,  # issue 25: no usual robot's plan changes (the test below)
    }
    assert SCHEDULE == Schedule()
    assert SCHEDULE.margin(1.0, 1.0) == 8.0 and SCHEDULE.margin(0.5, 2.0) == 4.0 * 0.5 + 4.0 * 2.0


@pytest.mark.parametrize(
    "field, value",
    [
        ("approach_after", 0),
        ("approach_after", 2.5),
        ("approach_after", True),
        ("approach_tries", -1),
        ("enclosure_limit", float("nan")),
        ("guided_weight", 0.9),
        ("escalate_factor", 0.99),
        ("escalate_every", 0),
        ("steer_slack", 0.0),
        ("improve_gap", -1.0),
        ("grid_margin", (4.0,)),
        ("grid_margin", (4.0, -1.0)),
        ("guide_window", (4.0, 4.0)),
        ("guide_window", (4.0, 4.0, -0.1)),
        ("deadline_every", "64"),
    ],
)
def test_a_bad_schedule_is_refused_naming_the_field(field, value):
    with pytest.raises(ValueError, match=field):
        Schedule(**{field: value})


def test_a_schedule_is_a_frozen_value():
    s = Schedule(approach_tries=0, guide_after=10**9)
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.guide_after = 1  # type: ignore[misc]
    assert s == dataclasses.replace(SCHEDULE, approach_tries=0, guide_after=10**9)


def test_a_wide_turning_robot_gets_a_coarser_lattice_and_the_usual_ones_keep_L_over_8():
    """Issue 25: the default resolution is L / 8, or R / wide_turn_cells (at most L) for a robot
    turning wider than 4 L, so its primitives stay few; every usual robot keeps L / 8 exactly."""
    from segplan import load_scenario
    from segplan.planning.lattice.search import _default_resolution

    for L in (0.5, 1.0, 1.2, 2.5):
        for steer in (25, 35, 45, 60, 14.05):  # R = L / tan(steer) <= 4 L
            R = L / math.tan(math.radians(steer))
            assert _default_resolution(L, R, SCHEDULE) == 0.125 * L
        R = L / math.tan(math.radians(5.0))  # about 11.4 L
        assert _default_resolution(L, R, SCHEDULE) == R / SCHEDULE.wide_turn_cells
        assert _default_resolution(L, 1e9 * L, SCHEDULE) == L
    sc = load_scenario("fig5_example1")
    tries, _ = lattice_resolutions(sc, None, True, None, SCHEDULE)
    assert tries == [0.125 * sc.robot.L, 0.0625 * sc.robot.L]


@pytest.mark.parametrize("steer_deg", [1e-6, 0.01])
def test_a_robot_that_cannot_turn_on_the_floor_is_refused_at_once(steer_deg, monkeypatch):
    """Issue 25: a 1e-6 deg steering limit on Fig. 5's floor took 10 GB before an "array is
    too big"; now a ValueError naming max_steer, before any work (no primitives computed).
    The paper's planner, which needs no lattice, still runs."""
    import segplan
    from segplan.planning.lattice import search

    base = segplan.load_scenario("fig5_example1")
    robot = segplan.Robot(base.robot.L, base.robot.half_width, math.radians(steer_deg))
    sc = segplan.make_scenario(robot, base.start, base.goal, list(base.outlines), base.bounds)

    def no_primitives(*args):
        raise AssertionError("primitives computed for a robot that cannot turn on the floor")

    monkeypatch.setattr(search, "primitive_set", no_primitives)
    with pytest.raises(ValueError, match="max_steer=.*turns far wider than the floor"):
        segplan.plan_scenario(sc)
    with pytest.raises(segplan.NoPathError):
        segplan.plan_scenario(sc, planner="paper", max_expansions=50)


def test_a_schedule_accepts_each_field_at_its_bound():
    """The bounds the fields are refused beyond are themselves accepted: no approach tries, a
    guided weight of 1, a grid margin of 0 (the grid then covers the floor's items exactly)."""
    s = Schedule(approach_tries=0, guided_weight=1.0, grid_margin=(0.0, 0.0), deadline_every=1)
    assert s.margin(1.0, 2.0) == 0.0
    assert Schedule(grid_margin=(0.0, 0.5)).margin(1.0, 2.0) == 1.0
    assert Schedule(grid_margin=(0.25, 0.0)).margin(2.0, 1.0) == 0.5


# -- the planner composed of its parts ------------------------------------------------------
def _behind_a_wall():
    """No walls; the goal behind a wall, facing back: the direct union is blocked."""
    from segplan import Robot, make_scenario

    wall = [[-3.0, 1.2], [3.0, 1.2], [3.0, 1.8], [-3.0, 1.8]]
    return make_scenario(Robot(1.0), (0.0, 0.0, 0.0), (0.0, 3.0, 3.14), [wall])


def _searched(plan):
    return plan.expanded, plan.generated, plan.search_cost


def test_the_planners_options_reach_its_search():
    """``lattice_search`` (one resolution, no tight arcs) makes the search that
    :func:`astar_of` composes with the same resolution and schedule: the same expansions,
    states and search cost; and those options matter on this floor (a coarser lattice, a
    clearance grid without margin: other searches)."""
    from segplan.planning.lattice.search import lattice_search

    sc = _behind_a_wall()
    bare = dataclasses.replace(SCHEDULE, grid_margin=(0.0, 0.0))
    runs = {}
    for resolution, schedule in ((None, SCHEDULE), (0.25, SCHEDULE), (None, bare)):
        plan, _ = lattice_search(sc, resolution=resolution, retry=False, escapes=False, schedule=schedule)
        composed, outcome, _ = plan_of(astar_of(sc, resolution=resolution, schedule=schedule))
        assert outcome == "found" and _searched(plan) == _searched(composed)
        runs[resolution, schedule.grid_margin] = _searched(plan)
    assert len(set(runs.values())) == 3


def test_a_large_floor_coarsens_the_lattice_unless_the_resolution_is_given():
    """Where the clearance grid would exceed ``MAX_CELLS`` (its estimate: half the square of
    the floor's width plus height, any rotation), the retry is dropped and then, only when no
    resolution was given, the lattice coarsens by halves (up to ``L``): the first of ``L / 8``,
    ``L / 4``, ... whose cells fit. A given resolution is kept."""
    from segplan import Robot, make_scenario
    from segplan.planning.lattice.clearance import MAX_CELLS

    def floor(size):
        return make_scenario(
            Robot(1.0), (1.0, 1.0, 0.0), (size - 2.0, size - 2.0, 0.0), [], (0, 0, size, size)
        )

    assert lattice_resolutions(floor(20.0), None, True, None) == ([0.125, 0.0625], 0.0625)
    for size in (150.0, 400.0, 700.0):
        area = 0.5 * (2.0 * size) ** 2
        r = 0.125
        while area / r**2 > MAX_CELLS and 2.0 * r <= 1.0:
            r *= 2.0
        assert r > 0.125  # these floors do coarsen
        assert lattice_resolutions(floor(size), None, True, None) == ([r], r)
        assert lattice_resolutions(floor(size), 0.125, True, None) == ([0.125], 0.125)
