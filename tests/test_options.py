"""The planners' options (issue 24): one frozen dataclass per planner, validated once, every value a field.

Each bad value raises a ValueError naming its field when the object is made; the defaults
are the planners' (pinned to the lattice's own signature and constants, which it still
reads until it takes a :class:`LatticeOptions`); ``plan_scenario``'s arguments become these
objects at the door, and a plan records the one that made it.
"""

import dataclasses
import inspect
import math

import pytest

import segplan
from segplan.planning import api
from segplan.planning.lattice import search as lattice
from segplan.planning.options import (
    DefaultOptions,
    LatticeOptions,
    PaperOptions,
    RefineOptions,
    check_choice,
    check_flag,
    refine_options,
)


def test_paper_options_defaults():
    o = PaperOptions()
    assert (o.heuristic, o.cost, o.version, o.ds, o.alpha_method) == ("a", "longd", "b", None, "heuristic")
    assert (o.max_expansions, o.time_limit, o.max_turn_chain) == (3000, 10.0, 4)
    assert o.expander == () and o.refine is None and o.clearance == 0.0


def test_default_options_list_every_value_of_the_default_planner():
    o = DefaultOptions()
    assert o.paper == PaperOptions(max_expansions=40, time_limit=2.0)
    assert (o.paper_share, o.lattice_after_paper, o.near_lower_bound) == (0.2, 400, 1.3)
    assert o.lattice == LatticeOptions() and o.refine == RefineOptions()
    assert (o.time_limit, o.clearance) == (10.0, 0.0)
    # the former module names read the dataclass
    assert api.PAPER_SHARE == o.paper_share and api.PAPER_EXPANSIONS == o.paper.max_expansions
    assert api.LATTICE_AFTER_PAPER == o.lattice_after_paper and api.NEAR_LOWER_BOUND == o.near_lower_bound
    assert dict(api.LATTICE_REFINE) == {"max_sweeps": o.refine.max_sweeps}


def test_default_options_derive_the_papers_time_from_the_share():
    o = DefaultOptions(time_limit=5.0)
    assert o.paper.time_limit == 0.2 * 5.0
    assert DefaultOptions(time_limit=5.0, paper_share=0.5).paper.time_limit == 2.5
    assert dataclasses.replace(o, time_limit=1.0).paper.time_limit == 0.2 * 1.0


def test_lattice_options_are_the_lattices_defaults():
    """LatticeOptions() holds lattice_search's defaults as literals: pinned here until the
    lattice reads the dataclass (then this test goes)."""
    sig = inspect.signature(lattice.lattice_search).parameters
    o = LatticeOptions()
    for f in dataclasses.fields(LatticeOptions):
        if f.name == "max_expansions":
            assert o.max_expansions == lattice.LATTICE_MAX_EXPANSIONS
        else:
            assert getattr(o, f.name) == sig[f.name].default, f.name
    # and lattice_options() accepts exactly these (but the limits)
    accepted = set(inspect.signature(lattice.lattice_options).parameters) - {"scenario", "schedule"}
    assert accepted == set(o.search_options())
    assert lattice.GOAL_RADIUS == (2.0, 1.0)  # goal_radius None: 2 R + L, as documented


def test_refine_options_are_refines_defaults():
    sig = inspect.signature(segplan.refine).parameters
    o = RefineOptions()
    for name in ("rounds", "split", "first_step", "min_step", "max_sweeps"):
        assert getattr(o, name) == sig[name].default, name
    from segplan.planning import refine

    assert refine.MIN_GAIN == o.min_gain == 1e-3 and refine.CHECKS_PER_UPDATE == o.checks_per_update == 1
    assert refine.MOVES.tolist() == [list(m) for m in o.moves] and len(o.moves) == 10


@pytest.mark.parametrize(
    "cls, kwargs, name",
    [
        (PaperOptions, {"heuristic": "d"}, "heuristic"),
        (PaperOptions, {"cost": "time"}, "cost"),
        (PaperOptions, {"version": "c"}, "version"),
        (PaperOptions, {"alpha_method": "magic"}, "alpha_method"),
        (PaperOptions, {"ds": -1.0}, "ds"),
        (PaperOptions, {"max_expansions": 0}, "max_expansions"),
        (PaperOptions, {"max_expansions": None}, "max_expansions"),
        (PaperOptions, {"time_limit": 0.0}, "time_limit"),
        (PaperOptions, {"time_limit": math.inf}, "time_limit"),
        (PaperOptions, {"max_turn_chain": -1}, "max_turn_chain"),
        (PaperOptions, {"max_turn_chain": 1.5}, "max_turn_chain"),
        (PaperOptions, {"expander": "r0=1"}, "expander"),
        (PaperOptions, {"expander": {"version": "a"}}, "expander"),
        (PaperOptions, {"refine": {"rounds": 2}}, "refine"),
        (PaperOptions, {"clearance": -0.1}, "clearance"),
        (LatticeOptions, {"resolution": 0.0}, "resolution"),
        (LatticeOptions, {"weight": 0.5}, "weight"),
        (LatticeOptions, {"retry": 1}, "retry"),
        (LatticeOptions, {"escapes": "yes"}, "escapes"),
        (LatticeOptions, {"analytic_every": 0}, "analytic_every"),
        (LatticeOptions, {"goal_radius": -1.0}, "goal_radius"),
        (LatticeOptions, {"cell": math.nan}, "cell"),
        (LatticeOptions, {"max_expansions": 2.5}, "max_expansions"),
        (RefineOptions, {"rounds": -1}, "rounds"),
        (RefineOptions, {"split": 0}, "split"),
        (RefineOptions, {"split": True}, "split"),
        (RefineOptions, {"first_step": "0.5"}, "first_step"),
        (RefineOptions, {"min_step": math.nan}, "min_step"),
        (RefineOptions, {"first_step": 0.1, "min_step": 0.2}, "min_step"),
        (RefineOptions, {"max_sweeps": True}, "max_sweeps"),
        (RefineOptions, {"min_gain": -1e-3}, "min_gain"),
        (RefineOptions, {"checks_per_update": 0}, "checks_per_update"),
        (RefineOptions, {"max_chord": 0.0}, "max_chord"),
        (RefineOptions, {"max_chord": math.inf}, "max_chord"),
        (RefineOptions, {"moves": ()}, "moves"),
        (RefineOptions, {"moves": ((1, 0),)}, "moves"),
        (DefaultOptions, {"paper_share": 0.0}, "paper_share"),
        (DefaultOptions, {"paper_share": 1.5}, "paper_share"),
        (DefaultOptions, {"lattice_after_paper": -1}, "lattice_after_paper"),
        (DefaultOptions, {"near_lower_bound": -1.0}, "near_lower_bound"),
        (DefaultOptions, {"time_limit": -1.0}, "time_limit"),
        (DefaultOptions, {"clearance": math.inf}, "clearance"),
        (DefaultOptions, {"paper": {"heuristic": "a"}}, "paper"),
        (DefaultOptions, {"lattice": {}}, "lattice"),
        (DefaultOptions, {"refine": True}, "refine"),
        (DefaultOptions, {"paper": PaperOptions(refine=RefineOptions())}, "paper.refine"),
        (DefaultOptions, {"paper": PaperOptions(clearance=0.1)}, "paper.clearance"),
    ],
)
def test_each_bad_value_is_a_clear_error(cls, kwargs, name):
    with pytest.raises(ValueError, match=name):
        cls(**kwargs)


def test_exact_alpha_is_refused_by_the_default_planner_and_honoured_by_the_papers():
    with pytest.raises(ValueError, match=r"alpha_method='exact'.*planner='paper'"):
        DefaultOptions(paper=PaperOptions(alpha_method="exact"))
    sc = segplan.load_scenario("single_obstacle")
    with pytest.raises(ValueError, match=r"alpha_method='exact'.*planner='paper'"):
        segplan.plan_scenario(sc, alpha_method="exact")
    found = segplan.plan_scenario(sc, planner="paper", alpha_method="exact", heuristic="b", time_limit=300.0)
    assert found.options.alpha_method == "exact"


def test_options_are_frozen_and_normalised():
    o = PaperOptions(expander={"r0": 0.5}, max_expansions=10.0)
    assert o.expander == (("r0", 0.5),) and o.expander_options == {"r0": 0.5}
    assert isinstance(o.max_expansions, int)
    assert hash(o) == hash(PaperOptions(expander={"r0": 0.5}, max_expansions=10))
    with pytest.raises(dataclasses.FrozenInstanceError):
        o.heuristic = "b"
    assert RefineOptions(split=3).split == 3.0 and isinstance(RefineOptions(rounds=2.0).rounds, int)


def test_small_validators():
    assert check_choice("a", ("a", "b"), "x") == "a"
    with pytest.raises(ValueError, match="x must be one of 'a', 'b', got 1"):
        check_choice(1, ("a", "b"), "x")
    assert check_flag(False, "flag") is False
    with pytest.raises(ValueError, match="flag must be True or False"):
        check_flag(0, "flag")
    default = RefineOptions(max_sweeps=3)
    assert refine_options(None, default) is default and refine_options(True, default) is default
    assert refine_options(True, None) == RefineOptions() and refine_options(False, default) is None
    assert refine_options({"rounds": 2}, default) == RefineOptions(rounds=2)  # a dict replaces, as before
    with pytest.raises(ValueError, match="refine must be"):
        refine_options("yes", default)


def test_plan_scenario_turns_its_arguments_into_options_at_the_door():
    sc = segplan.load_scenario("fig5_example1")
    _, o = api.planner_options(sc, "b", max_expansions=30, time_limit=4.0, lattice={"weight": 1.5})
    assert isinstance(o, DefaultOptions)
    assert o.paper.heuristic == "b" and o.paper.max_expansions == 30 and o.paper.time_limit == 0.2 * 4.0
    assert o.lattice.max_expansions == 30 and o.lattice.weight == 1.5 and o.time_limit == 4.0
    _, o = api.planner_options(sc, planner="lattice", max_expansions=500)
    assert o.paper.max_expansions == 40 and o.lattice.max_expansions == 500
    _, o = api.planner_options(sc, planner="paper", refine=True)
    assert isinstance(o, PaperOptions) and o.refine == RefineOptions() and o.max_expansions == 3000
    for kwargs, name in (
        ({"lattice": {"max_expansions": 5}}, "max_expansions"),
        ({"lattice": {"speed": 2}}, "speed"),
        ({"lattice": {"resolution": 100.0}}, "resolution"),  # the lattice's own check: <= L
        ({"planner": "fast"}, "planner"),
        ({"expander": {"r0": -1.0}, "planner": "paper"}, None),
    ):
        if name is None:  # the Expander checks its own options when the search builds it
            with pytest.raises(ValueError, match="r0"):
                segplan.plan_scenario(sc, **kwargs)
        else:
            with pytest.raises(ValueError, match=name):
                api.planner_options(sc, **kwargs)


def test_a_plans_summary_is_plain_json_of_its_fields():
    """``Plan.to_dict``: every field, angles in degrees (as scenario files), the refinement's
    and the options' own summaries; plain JSON."""
    import json

    sc = segplan.load_scenario("single_obstacle")
    plan = segplan.plan_scenario(sc)
    d = plan.to_dict()
    back = json.loads(json.dumps(d))  # plain JSON (the options' pairs come back as lists)
    assert {k: v for k, v in back.items() if k != "options"} == {k: v for k, v in d.items() if k != "options"}
    assert d["nodes"] == [[p.x, p.y, math.degrees(p.theta)] for p in plan.nodes]
    assert d["alphas_deg"] == [math.degrees(u.alpha) for u in plan.unions] and d["kinds"] == list(plan.kinds)
    for name in ("cost", "search_cost", "expanded", "generated", "seconds", "heuristic", "cost_kind"):
        assert d[name] == getattr(plan, name), name
    for name in ("version", "collision_checks", "exact_checks", "planner", "stopped"):
        assert d[name] == getattr(plan, name), name
    assert plan.refinement is not None and d["refinement"] == dataclasses.asdict(plan.refinement)
    assert d["options"] == plan.options.to_dict() and d["L"] == plan.unions[0].L
    assert d["directions"] == [1] * len(plan.unions) and d["cusps"] == []  # issue 26: forward only
    assert len(d) == 20


def test_the_search_limits_are_checked_naming_the_argument():
    import re

    from segplan.planning.plan import check_limits

    assert check_limits(None, 10) == (None, 10.0) and check_limits(5, 0.5) == (5, 0.5)
    for args, message in (
        ((0, 1.0), "max_expansions must be an integer >= 1, got 0"),
        ((2.5, 1.0), "max_expansions must be an integer >= 1, got 2.5"),
        ((1, 0.0), "time_limit must be a finite number > 0.0, got 0.0"),
        ((1, math.inf), "time_limit must be a finite number > 0.0, got inf"),
    ):
        with pytest.raises(ValueError, match=f"^{re.escape(message)}$"):
            check_limits(*args)


def test_a_plan_records_its_planner_and_options():
    sc = segplan.load_scenario("single_obstacle")
    default = segplan.plan_scenario(sc)
    paper = segplan.plan_scenario(sc, planner="paper", heuristic="c")
    assert default.planner == "lattice" and default.options == DefaultOptions()
    assert paper.planner == "paper" and paper.options == PaperOptions(heuristic="c")
    d = default.to_dict()
    assert d["planner"] == "lattice" and d["options"]["paper"]["max_expansions"] == 40
    assert d["options"]["refine"]["max_sweeps"] == 6 and d["options"]["lattice"]["weight"] == 2.0
    # the recorded options plan the same plan again, through the public door
    for made in (default, paper):
        again = segplan.plan_scenario(sc, options=made.options)
        assert again.nodes == made.nodes and again.cost == made.cost and again.planner == made.planner
    # a plan made without them (a stage alone, or by hand) keeps the old constructor
    bare = dataclasses.replace(default, planner=None, options=None)
    assert bare.to_dict()["planner"] is None and bare.to_dict()["options"] is None
    assert bare == dataclasses.replace(default, planner=None)  # options do not take part in ==


def test_options_object_or_keywords_not_both():
    sc = segplan.load_scenario("single_obstacle")
    with pytest.raises(ValueError, match="either options or heuristic, time_limit"):
        segplan.plan_scenario(sc, "b", time_limit=3.0, options=DefaultOptions())
    with pytest.raises(ValueError, match="options must be a segplan.PaperOptions"):
        segplan.plan_scenario(sc, options={"heuristic": "b"})
    # a clearance in the options is applied to the scenario as the keyword would be
    kw = segplan.plan_scenario(sc, planner="paper", clearance=0.05)
    ob = segplan.plan_scenario(sc, options=PaperOptions(clearance=0.05))
    assert ob.nodes == kw.nodes and ob.cost == kw.cost
    # the lattice's own check (resolution <= L) holds for an options object too
    with pytest.raises(ValueError, match="resolution"):
        segplan.plan_scenario(sc, options=DefaultOptions(lattice=LatticeOptions(resolution=100.0)))


def test_the_lattices_schedule_is_an_option_that_reaches_the_lattice():
    """DefaultOptions lists the lattice's schedule (every count of when a mechanism starts);
    one set there reaches the search: without the guide, any-6 is not solved within 1000
    expansions (tests/test_escape_costtogo.py shows the guide is what solves it)."""
    from segplan.planning.schedule import SCHEDULE, Schedule
    from segplan.studies import floors

    assert DefaultOptions().lattice.schedule == SCHEDULE == Schedule()
    assert DefaultOptions().to_dict()["lattice"]["schedule"]["guide_after"] == SCHEDULE.guide_after
    sc = floors.random_floor("any", 6)
    lattice = {"retry": False, "escapes": False}
    unguided = DefaultOptions(
        paper=PaperOptions(max_expansions=1),
        lattice=LatticeOptions(
            **lattice, max_expansions=1000, schedule=dataclasses.replace(SCHEDULE, guide_after=10**9)
        ),
        time_limit=60.0,
    )
    guided = dataclasses.replace(unguided, lattice=dataclasses.replace(unguided.lattice, schedule=SCHEDULE))
    found = segplan.plan_scenario(sc, options=guided)
    assert found.options.lattice.schedule == SCHEDULE and found.version == "lattice"
    with pytest.raises(segplan.NoPathError) as err:
        segplan.plan_scenario(sc, options=unguided)
    assert err.value.reason == "expansions"
    with pytest.raises(ValueError, match="schedule"):
        LatticeOptions(schedule={"guide_after": 5})
