"""The default planner as one pipeline (issue 24): the paper's search, the lattice, the refinement.

The stages are called in that order with the budgets of :class:`DefaultOptions`; the deadline
of the call's ``time_limit`` reaches the refinement (with time left it changes nothing, past it
the refinement starts no new work); a time-out names the limit the user gave.
"""

import dataclasses
import time

import pytest

import segplan
from segplan.planning import api, default
from segplan.planning.context import Deadline, PlanningContext
from segplan.planning.options import DefaultOptions, RefineOptions
from segplan.planning.refine import refine_with
from segplan.planning.stages import paper_search


def _context(name, **kwargs):
    scenario, options = api.planner_options(segplan.load_scenario(name), **kwargs)
    return PlanningContext(scenario, options.time_limit, options), options


@pytest.fixture
def stages(monkeypatch):
    """Records the stages the pipeline runs: ``(name, max_expansions)``."""
    calls = []
    paper, lattice, refine = default.paper_search, default.lattice_stage, default.refine_with

    def paper_spy(ctx, options):
        calls.append(("paper", options.max_expansions))
        return paper(ctx, options)

    def lattice_spy(ctx, options, expansions):
        calls.append(("lattice", expansions))
        return lattice(ctx, options, expansions)

    def refine_spy(found, links, options, deadline):
        calls.append(("refine", options.max_sweeps))
        return refine(found, links, options, deadline=deadline)

    monkeypatch.setattr(default, "paper_search", paper_spy)
    monkeypatch.setattr(default, "lattice_stage", lattice_spy)
    monkeypatch.setattr(default, "refine_with", refine_spy)
    return calls


def test_pipeline_runs_paper_lattice_refine(stages):
    ctx, options = _context("turn_around")  # the lattice's plan is far shorter than the paper's
    found = default.default_pipeline(ctx, options)
    # each plan found is refined (the lattice's, the shorter, first), the shorter refined kept
    assert stages == [("paper", 40), ("lattice", 400), ("refine", 6), ("refine", 6)]
    assert found.version == "lattice" and found.refinement is not None


def test_lattice_budget_after_a_paper_plan(stages):
    ctx, options = _context("fig6_example2")
    paper, _ = paper_search(ctx, options.paper)
    budget = default.lattice_budget(ctx, options, paper)
    assert budget in (0, options.lattice_after_paper)
    assert default.lattice_budget(ctx, options, None) == options.lattice.max_expansions
    near = dataclasses.replace(options, near_lower_bound=1e6)  # any plan is "near the bound"
    assert default.lattice_budget(ctx, near, paper) == 0
    far = dataclasses.replace(options, near_lower_bound=0.0)
    assert default.lattice_budget(ctx, far, paper) == options.lattice_after_paper


def test_pipeline_is_plan_scenario():
    for name in ("fig5_example1", "fig6_example2", "turn_around"):
        ctx, options = _context(name)
        found = default.default_pipeline(ctx, options)
        plan = segplan.plan_scenario(segplan.load_scenario(name))
        assert found.nodes == plan.nodes and found.cost == plan.cost
        assert plan.planner == "lattice" and plan.options == options


def test_without_refinement(stages):
    ctx, options = _context("fig5_example1", refine=False)
    assert options.refine is None
    found = default.default_pipeline(ctx, options)
    assert found.refinement is None and [s for s, _ in stages] in (["paper"], ["paper", "lattice"])


def test_both_searches_plans_are_refined_the_cheaper_first(monkeypatch):
    """Both searches plan: each plan is refined with the link model of the search that found
    it, the cheaper first (issue 25), and the shorter refined plan is kept. On the shipped
    floors the lattice's is never the dearer, so the stages are swapped too: the paper's
    search returns the lattice's real plan and the lattice the paper's (and the lattice runs
    after any plan of the paper's search)."""
    ctx, options = _context("fig6_example2")
    options = dataclasses.replace(options, near_lower_bound=0.0)
    paper, paper_links = paper_search(PlanningContext(ctx.scenario, 60.0, options), options.paper)
    lattice, lattice_links = default.lattice_stage(
        PlanningContext(ctx.scenario, 60.0, options), options.lattice, options.lattice_after_paper
    )
    assert lattice.cost < paper.cost
    calls, refined = [], []

    def stage(found, links):
        return lambda *args: calls.append(found) or (found, links)

    def refine_spy(found, links, o, deadline):
        refined.append((found, links))
        return found  # refined as it is: the cheaper plan stays the cheaper

    monkeypatch.setattr(default, "refine_with", refine_spy)
    for first, second in (
        ((lattice, lattice_links), (paper, paper_links)),
        ((paper, paper_links), (lattice, lattice_links)),
    ):
        calls.clear()
        refined.clear()
        monkeypatch.setattr(default, "paper_search", stage(*first))
        monkeypatch.setattr(default, "lattice_stage", stage(*second))
        kept = default.default_pipeline(ctx, options)
        assert calls == [first[0], second[0]]
        assert refined == [(lattice, lattice_links), (paper, paper_links)] and kept is lattice


def test_refinement_with_time_left_is_unchanged():
    sc = segplan.load_scenario("fig6_example2")
    for planner in ("paper", "lattice"):
        scenario, options = api.planner_options(sc, planner=planner, refine=False)
        ctx = PlanningContext(scenario, 10.0)
        search = paper_search if planner == "paper" else default.default_pipeline
        found = search(ctx, options)
        found = found[0] if planner == "paper" else found
        links = ctx.link_model()
        free = refine_with(found, links, RefineOptions())
        timed = refine_with(found, ctx.link_model(), RefineOptions(), deadline=Deadline(60.0))
        assert timed.nodes == free.nodes and timed.cost == free.cost and not timed.refinement.stopped


def test_refinement_past_the_deadline_starts_nothing():
    ctx, options = _context("fig6_example2", refine=False)
    found = default.default_pipeline(ctx, options)
    past = Deadline(1.0, start=time.perf_counter() - 2.0)
    out = refine_with(found, ctx.link_model(), RefineOptions(), deadline=past)
    assert out.refinement.stopped and out.nodes == found.nodes and out.cost == found.cost
    assert out.refinement.checked == out.refinement.updates == 0


def test_refinement_stops_midway_with_a_valid_plan(monkeypatch):
    """A deadline that passes during the refinement: the chain so far, every union free."""
    from segplan.planning import refine as refine_module

    ctx, options = _context("fig6_example2", refine=False)
    found = default.default_pipeline(ctx, options)
    full = refine_with(found, ctx.link_model(), RefineOptions())
    calls = []

    class Countdown(Deadline):
        def expired(self):
            calls.append(1)
            return len(calls) > 6

    out = refine_with(found, ctx.link_model(), RefineOptions(), deadline=Countdown(60.0))
    assert out.refinement.stopped and out.cost <= found.cost
    assert out.refinement.updates < full.refinement.updates
    for u in out.unions:
        assert ctx.workspace.union_free(u)
    assert out.nodes[0] == found.nodes[0] and out.nodes[-1] == found.nodes[-1]
    assert refine_module.refine_with is refine_with


def test_time_out_names_the_users_limit():
    sc = segplan.load_scenario("fig6_example2")
    with pytest.raises(segplan.NoPathError, match=r"time_limit=1e-06 s") as exc:
        segplan.plan_scenario(sc, time_limit=1e-6)
    assert exc.value.reason == "time" and exc.value.seconds >= 0.0


def test_default_options_default_value_is_what_plan_scenario_uses():
    sc = segplan.load_scenario("single_obstacle")
    assert api.planner_options(sc)[1] == DefaultOptions()


@pytest.mark.parametrize("name", segplan.shipped_scenarios())
def test_the_default_is_never_beaten_by_refining_the_papers_plan(name):
    """Issue 25: on every shipped floor, the default plan is at most as long as
    ``segplan.refine(plan_scenario(..., planner="paper"), scenario)``, a call a user can type
    (before: 31.488 m against 31.299 m on Fig. 5)."""
    sc = segplan.load_scenario(name)
    default = segplan.plan_scenario(sc)
    try:
        paper = segplan.plan_scenario(sc, planner="paper")
    except segplan.NoPathError:
        return  # nothing to refine
    assert default.cost <= segplan.refine(paper, sc).cost * (1 + 1e-12)


def test_a_plan_cut_short_by_the_time_limit_says_so(monkeypatch, tmp_path):
    """The lattice stopped by the time limit after the paper's search found a plan: that plan
    (refined) is the answer and Plan.stopped says "time"; a plan made within every limit
    says None, and so does a saved and loaded one."""
    import segplan.planning.default as default_module
    from segplan import NoPathError, load_scenario, plan_scenario
    from segplan.planning.plan import Plan

    sc = load_scenario("fig6_example2")  # the paper's search finds a plan; the lattice runs after it
    whole = plan_scenario(sc)
    assert whole.stopped is None and whole.to_dict()["stopped"] is None

    def timed_out(ctx, options, expansions):
        raise NoPathError("the lattice ran out of time", "time", 10, 20, 1.0, None)

    monkeypatch.setattr(default_module, "lattice_stage", timed_out)
    cut = plan_scenario(sc)
    assert cut.stopped == "time" and cut.to_dict()["stopped"] == "time"
    assert cut.cost == plan_scenario(sc, planner="paper", refine=True).cost  # the refined paper plan
    monkeypatch.undo()
    assert Plan.load(cut.save(tmp_path / "cut.json")).stopped == "time"
