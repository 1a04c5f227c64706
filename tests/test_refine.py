"""Refinement of a found plan (beyond the paper, issue 5): segplan.refine.

Oracles: every refined plan passes the search's full check (dense shapely sampling of the
swept segment, exact curvature maximum, forward motion, exact end poses, cost = Romberg's
[1]); its cost is never above the search's; the screening filter never rejects a link
that the exact test accepts. (The Gauss-Legendre link cost is checked in test_cost_gauss.py.)
"""

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_refine_oracles import random_links
from test_search import check_plan

import segplan
from segplan import NoPathError, Refinement, plan_scenario, random_world, refine
from segplan.model.frame import heuristic_alpha
from segplan.model.pose import Pose
from segplan.model.union import Union, cubic_coefficients
from segplan.planning.refine import certain_failures
from segplan.planning.validity import Workspace

SCENARIOS = Path(__file__).resolve().parent.parent / "scenarios"
NAMES = sorted(p.stem for p in SCENARIOS.glob("*.json"))


@pytest.fixture(scope="module")
def plans():
    out = {}
    for name in NAMES:
        sc = segplan.load_scenario(SCENARIOS / f"{name}.json")
        found = plan_scenario(sc, planner="paper")
        out[name] = (sc, found, refine(found, sc))
    return out


@pytest.mark.parametrize("name", NAMES)
def test_refined_plans_are_valid_and_not_longer(plans, name):
    sc, found, refined = plans[name]
    check_plan(refined, sc)
    info = refined.refinement
    assert isinstance(info, Refinement)
    assert info.cost_before == found.cost and info.cost_after == refined.cost
    assert refined.cost <= found.cost
    assert len(refined.kinds) == len(refined.nodes) == info.nodes_after
    assert refined.kinds[0] == "start" and refined.kinds[-1] == "goal"
    # moved or added nodes are marked, the others are the search's own
    for pose, kind in zip(refined.nodes, refined.kinds, strict=True):
        assert (kind == "refined") == (pose not in found.nodes)
    assert refined.seconds >= found.seconds
    assert found.refinement is None


def test_refinement_counters_are_consistent():
    """Each accepted move is a tried node update; a refinement that moved nodes tried some.

    Refines here, not through the module's fixture, so that a mutation tool that selects
    tests by the functions they call runs this one.
    """
    for name in ("fig5_example1", "fig6_example2"):
        sc = segplan.load_scenario(SCENARIOS / f"{name}.json")
        info = refine(plan_scenario(sc, planner="paper"), sc).refinement
        assert info.updates >= info.moves > 0, name
        assert info.checked > 0 and info.splits >= 0 and info.shortcuts >= 0, name


def test_refinement_shortens_the_paper_examples(plans):
    """Figs. 5 and 6: the refined front-wheel path is shorter by more than a per cent."""
    for name in ("fig5_example1", "fig6_example2"):
        _, found, refined = plans[name]
        assert refined.cost < 0.99 * found.cost, name


def test_deterministic_and_same_as_plan_option(plans):
    sc, found, refined = plans["fig6_example2"]
    again = refine(found, sc)
    assert again.nodes == refined.nodes and again.cost == refined.cost
    # through plan_scenario, with the search's own caches: the same chain
    direct = plan_scenario(sc, refine=True, planner="paper")
    assert direct.nodes == refined.nodes and direct.cost == refined.cost
    assert direct.refinement is not None


def test_rounds_zero_only_shortcuts(plans):
    sc, found, _ = plans["fig6_example2"]
    short = refine(found, sc, rounds=0)
    assert set(short.nodes) <= set(found.nodes)
    assert short.refinement.splits == short.refinement.moves == 0
    assert short.cost <= found.cost


def test_shortcuts_within_max_chord(plans):
    """Shortcuts join nodes at most ``max_chord * L`` apart, and every link checked before:
    with a bound shorter than every chord none is taken; with one longer than the floor,
    the chain of no bound (None), bit for bit."""
    from segplan.planning.links import LinkModel
    from segplan.planning.options import RefineOptions
    from segplan.planning.refine import refine_with

    sc, found, _ = plans["fig6_example2"]

    def shortcuts(max_chord):
        ws = Workspace(sc.enlarged, sc.robot.L, sc.free_bounds, sc.robot.max_curvature)
        return refine_with(found, LinkModel(ws), RefineOptions(rounds=0, max_chord=max_chord))

    free = shortcuts(None)
    assert free.refinement.shortcuts > 0
    assert shortcuts(1e-6).nodes == found.nodes  # only the plan's own (checked) links
    assert shortcuts(100.0).nodes == free.nodes and shortcuts(100.0).cost == free.cost


@settings(max_examples=12)
@given(seed=st.integers(0, 10_000), n=st.integers(2, 6))
def test_random_worlds(seed, n):
    sc = random_world(seed, n)
    try:
        found = plan_scenario(sc, planner="paper")
    except NoPathError:
        return
    refined = refine(found, sc)
    check_plan(refined, sc)
    assert refined.cost <= found.cost


def test_bad_input(plans):
    sc, found, refined = plans["fig5_example1"]
    other = segplan.load_scenario(SCENARIOS / "empty_room.json")
    with pytest.raises(ValueError, match="plan must be"):
        refine("plan", sc)
    with pytest.raises(ValueError, match="scenario must be"):
        refine(found, "fig5")
    with pytest.raises(ValueError, match="start to its goal"):
        refine(found, other)
    with pytest.raises(ValueError, match="already refined"):
        refine(refined, sc)
    for kw in (
        {"rounds": -1},
        {"rounds": 1.5},
        {"split": 0},
        {"split": True},  # a bool is no step size
        {"first_step": "0.5"},  # a ValueError, not a TypeError
        {"min_step": math.nan},
        {"max_sweeps": True},
    ):
        with pytest.raises(ValueError, match=next(iter(kw))):
            refine(found, sc, **kw)
    with pytest.raises(ValueError, match="must not exceed"):
        refine(found, sc, first_step=0.1, min_step=0.2)
    with pytest.raises(ValueError, match="refine must be"):
        plan_scenario(sc, refine="yes")
    # the same start and goal, another floor where the plan's unions are not free
    blocked = segplan.make_scenario(
        sc.robot,
        sc.start,
        sc.goal,
        [
            *sc.obstacles,
            *(
                u.rear(3)[1] + np.array([[-0.3, -0.3], [0.3, -0.3], [0.3, 0.3], [-0.3, 0.3]])
                for u in found.unions[:1]
            ),
        ],
        sc.bounds,
    )
    with pytest.raises(ValueError, match="not free in this scenario"):
        refine(found, blocked)


# -- the Gauss-Legendre link cost ------------------------------------------------------
# -- the screening filter is sound -------------------------------------------------------
@settings(max_examples=60)
@given(seed=st.integers(0, 10_000))
def test_certain_failures_never_reject_a_free_link(seed):
    """Every link flagged as a certain failure is refused by the exact tests."""
    sc = random_world(seed % 50, 6)
    ws = Workspace(sc.enlarged, sc.robot.L, sc.free_bounds, sc.robot.max_curvature)
    rng = np.random.default_rng(seed)
    A, B = random_links(rng, sc.free_bounds, 60, aim=0.8, turn=1.2)
    dx, dy = B[:, 0] - A[:, 0], B[:, 1] - A[:, 1]
    d, psi = np.hypot(dx, dy), np.arctan2(dy, dx)
    phi0 = np.angle(np.exp(1j * (A[:, 2] - psi)))
    phi1 = np.angle(np.exp(1j * (B[:, 2] - psi)))
    keep = (np.pi / 2 - np.maximum(np.maximum(phi0, phi1), 0)) - (
        -np.pi / 2 - np.minimum(np.minimum(phi0, phi1), 0)
    ) > 0.02
    A, B, d, psi, phi0, phi1 = A[keep], B[keep], d[keep], psi[keep], phi0[keep], phi1[keep]
    alpha = heuristic_alpha(d, phi0, phi1, sc.robot.L)
    bad = certain_failures(ws, A, psi - alpha, *cubic_coefficients(d, phi0, phi1, alpha))
    assert bad.any()  # something was flagged, so the claim below was exercised
    for k in np.flatnonzero(bad):
        u = Union(Pose(*A[k]), Pose(*B[k]), float(alpha[k]), sc.robot.L)
        assert not ws.union_free(u), k
