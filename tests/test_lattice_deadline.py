"""The lattice planner's work after a search honours the call's deadline (issue 24): the
improvement by tight arcs and the greedy shortcuts add nothing once it has passed, and
change nothing while there is time left."""

import time

from test_lattice_parts import astar_of, plan_of

from segplan.planning.lattice.escape import improve_with_arcs
from segplan.planning.lattice.search import lattice_search
from segplan.planning.lattice.shortcut import shortcut_plan
from segplan.planning.links import LinkModel
from segplan.planning.schedule import SCHEDULE
from segplan.planning.validity import Workspace
from segplan.studies import floors


def test_improve_with_arcs_stops_at_the_deadline():
    sc = floors.random_floor("any", 166)  # a plan the arcs improve (test_escape_costtogo)
    ws = Workspace(sc.enlarged, sc.robot.L, sc.free_bounds, sc.robot.max_curvature)
    plan, _ = lattice_search(sc, escapes=False, workspace=ws)
    assert improve_with_arcs(sc, LinkModel(ws), plan, 0.0, deadline=time.perf_counter() - 1.0) is plan
    improved = improve_with_arcs(sc, LinkModel(ws), plan, 0.0, deadline=time.perf_counter() + 60.0)
    assert "arc" in improved.kinds and improved.cost < plan.cost
    # the default (no deadline) is the same plan as a deadline far away
    assert improve_with_arcs(sc, LinkModel(ws), plan, 0.0).nodes == improved.nodes


def test_shortcuts_stop_at_the_deadline():
    s = astar_of(floors.random_floor("natural", 5))
    plan, outcome, _ = plan_of(s)
    assert outcome == "found" and len(plan.unions) > 3
    late = shortcut_plan(
        plan, s.ex, s.grid, 0.0, SCHEDULE.shortcut_window, deadline=time.perf_counter() - 1.0
    )
    assert late.nodes == plan.nodes  # no shortcut tried
    timely = shortcut_plan(
        plan, s.ex, s.grid, 0.0, SCHEDULE.shortcut_window, deadline=time.perf_counter() + 60.0
    )
    assert len(timely.nodes) < len(plan.nodes)
    assert shortcut_plan(plan, s.ex, s.grid, 0.0, SCHEDULE.shortcut_window).nodes == timely.nodes
    # the shortened plan's time counts from the planning's start, its shortcuts included
    before = time.perf_counter()
    again = shortcut_plan(plan, s.ex, s.grid, before - 100.0, SCHEDULE.shortcut_window)
    assert again.nodes == timely.nodes and 100.0 <= again.seconds <= time.perf_counter() - before + 100.0
