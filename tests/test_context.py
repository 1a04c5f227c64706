"""One planning call's context (issue 24): the scenario, its one validity checker, the deadline."""

import time

import pytest

import segplan
from segplan.planning.context import Deadline, PlanningContext, workspace_of
from segplan.planning.validity import Workspace


def test_deadline_counts_from_its_start():
    d = Deadline(10.0)
    assert 0.0 <= d.elapsed() < 1.0 and 9.0 < d.left() <= 10.0 and not d.expired()
    assert d.at == pytest.approx(d.start + 10.0)
    past = Deadline(0.5, start=time.perf_counter() - 1.0)
    assert past.expired() and past.left() < 0.0 and past.elapsed() >= 1.0
    short = Deadline(0.02)
    time.sleep(0.03)
    assert short.expired() and "limit=0.02 s" in repr(short)


def test_context_builds_one_workspace_of_the_scenario():
    sc = segplan.load_scenario("fig5_example1")
    ctx = PlanningContext(sc, 3.0)
    ws = ctx.workspace
    assert isinstance(ws, Workspace) and ws.L == sc.robot.L and ws.max_curvature == sc.robot.max_curvature
    assert ws.bounds == workspace_of(sc).bounds and len(ws.convex) == len(sc.enlarged)
    assert ctx.deadline.limit == 3.0 and ctx.scenario is sc and not ctx.counters
    links = ctx.link_model()
    assert links.ws is ws and links.alpha_method == "heuristic"
    with pytest.raises(ValueError, match="scenario"):
        PlanningContext("fig5", 1.0)


def test_one_workspace_per_call(monkeypatch):
    """The default planner's stages share the call's validity checker: one Workspace per call."""
    made = []
    init = Workspace.__init__

    def counting(self, *a, **kw):
        made.append(1)
        init(self, *a, **kw)

    monkeypatch.setattr(Workspace, "__init__", counting)
    for name in ("fig6_example2", "turn_around"):  # the lattice runs on both
        made.clear()
        plan = segplan.plan_scenario(segplan.load_scenario(name))
        assert made == [1] and plan.refinement is not None


def test_counters_record_the_stages():
    from segplan.planning import api
    from segplan.planning.context import PlanningContext as Ctx
    from segplan.planning.default import default_pipeline

    sc = segplan.load_scenario("fig6_example2")
    scenario, options = api.planner_options(sc)
    ctx = Ctx(scenario, options.time_limit, options)
    default_pipeline(ctx, options)
    assert ctx.counters["paper_runs"] == 1 and ctx.counters["paper_expanded"] > 0
    assert ctx.counters["lattice_runs"] <= 1
    # the paper's search alone, in a context of its own: a plan is counted as one
    from segplan.planning.stages import paper_search

    alone = Ctx(scenario, options.time_limit, options)
    try:
        found = paper_search(alone, options.paper)[0]
    except segplan.NoPathError as exc:
        found, expanded = None, exc.expanded
    else:
        expanded = found.expanded
    assert found is not None  # fig6_example2: the paper's search plans it
    assert dict(alone.counters) == {"paper_runs": 1, "paper_plans": 1, "paper_expanded": expanded}
    assert ctx.counters["paper_plans"] == 1 and ctx.counters["paper_expanded"] == expanded
    # a failed run counts its expansions, no plan
    failed = Ctx(scenario, options.time_limit, options)
    with pytest.raises(segplan.NoPathError):
        paper_search(failed, segplan.PaperOptions(max_expansions=1))
    assert dict(failed.counters) == {"paper_runs": 1, "paper_plans": 0, "paper_expanded": 1}


def test_the_contexts_link_model_keeps_its_options():
    """``link_model``: the context's workspace, the steering fallback as asked (on by
    default), and the observer called with each link cost."""
    from segplan.model.pose import Pose

    ctx = PlanningContext(segplan.load_scenario("fig5_example1"), 3.0)
    assert ctx.link_model().steer_fallback is True
    assert ctx.link_model(steer_fallback=False).steer_fallback is False
    seen = []
    links = ctx.link_model("exact", observer=lambda u, c: seen.append((u, c)))
    u = links.union(Pose(0.0, 0.0, 0.0), Pose(5.0, 1.0, 0.3))
    cost = links.link_cost(u)
    assert links.alpha_method == "exact" and links.ws is ctx.workspace and seen == [(u, cost)]
