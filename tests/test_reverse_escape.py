"""Escapes of a robot that may reverse (issue 26): tight arcs driven backwards, hops, and the
dead-end bays whose lattice is exhausted inside the bay (:mod:`segplan.planning.lattice.escape`)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from test_lattice_oracles import dense_collides
from test_reverse_lattice import _valid

import segplan
from segplan.floor.scenario import make_scenario
from segplan.model.pose import Pose
from segplan.planning.context import workspace_of
from segplan.planning.lattice import escape, legs
from segplan.planning.lattice.reverse import weighted_cost
from segplan.planning.links import LinkModel
from segplan.planning.plan import link_ends, union_longd
from segplan.studies import reverse_floors as rf
from segplan.studies import reverse_study as rs


def _bay(index: int = 10):
    return rs.with_reverse(rf.reverse_floor("dead-end", index))


def _nodes_of(arc: escape.Arc) -> tuple:
    """The arc's nodes from ``first`` as a plan stores its links (:func:`link_ends`)."""
    return link_ends(arc.first, arc.unions, arc.link_directions)


@pytest.mark.parametrize("into", [False, True])
@pytest.mark.parametrize("direction", [1, -1])
def test_hops_are_free_within_the_limit_and_join_their_end(into, direction):
    sc = _bay()
    links = LinkModel(workspace_of(sc))
    end = sc.start if not into else sc.goal
    found = escape.hops(links, end, sc.robot.L, into, direction, 1.25)
    if not into:  # nose-in at the bay's end: no room ahead of the start, some behind it
        assert bool(found) == (direction == -1)
    for arc in found:
        (u,) = arc.unions
        assert arc.link_directions == (direction,) and arc.into == into
        assert arc.search_cost == pytest.approx(arc.cost * (1.0 if direction > 0 else 1.25))
        assert (arc.last if into else arc.first) == Pose(*end)
        assert _nodes_of(arc)[-1] == arc.last  # the stored union joins first to last, driven so
        assert arc.cost == pytest.approx(union_longd(u), rel=1e-12)
        assert np.abs(u.curvature(u.xs(2001))).max() <= sc.robot.max_curvature * (1 + 1e-6)
    if not found:
        return
    chain = type("Chain", (), {"unions": tuple(a.unions[0] for a in found)})
    assert not dense_collides(chain, sc)  # the dense oracle agrees: every hop is free
    # ahead of the end when the forward union starts there (out forwards, into backwards)
    ahead = (direction > 0) != into
    for arc in found:
        p, q = Pose(*end), arc.inner
        along = (q.x - p.x) * math.cos(p.theta) + (q.y - p.y) * math.sin(p.theta)
        assert (along > 0) == ahead


@pytest.mark.parametrize("into", [False, True])
def test_reversed_arc_drives_the_same_unions_the_other_way(into):
    robot = segplan.Robot(1.5, 0.45, math.radians(45), reverse=True)
    sc = make_scenario(robot, (5.0, 6.0, 0.3), (15.0, 6.0, -2.0), [], (0.0, 0.0, 20.0, 12.0))
    links = LinkModel(workspace_of(sc))
    R = sc.robot.min_turning_radius
    end = sc.goal if into else sc.start
    arcs = escape.tight_arcs(links, end, R, into=into)
    assert arcs
    for arc in arcs:
        back = escape.reversed_arc(arc, 1.25, 0.75)
        assert back.link_directions == (-1,) * len(arc.unions) and back.into == (not into)
        assert back.search_cost == pytest.approx(1.25 * arc.cost, rel=1e-9)  # no cusp within
        assert set(back.unions) == set(arc.unions) and back.cost == arc.cost
        nodes = _nodes_of(back)
        assert nodes[0] == back.first and nodes[-1] == back.last
        assert (back.first if back.into else back.last) == back.inner
        # the end pose stays where it was: out of it backwards, or into it backwards
        assert (back.last if back.into else back.first) == Pose(*end)


def test_a_forward_robot_has_no_hop_or_reversed_arc_among_its_pairs():
    sc = _bay()
    forward = dataclasses.replace(sc, robot=dataclasses.replace(sc.robot, reverse=False))
    links = LinkModel(workspace_of(forward))
    pairs = escape.arc_pairs(forward, links, "both")
    arcs = [arc for _, a, b in pairs for arc in (a, b) if arc is not None]
    assert arcs and all(arc.link_directions == (1,) * len(arc.unions) for arc in arcs)
    assert all(len(arc.unions) > 1 for arc in arcs)  # tight arcs only: no hop
    assert [p[0] for p in pairs] == sorted(p[0] for p in pairs)  # one order, by the estimate


@pytest.mark.parametrize("index", [10, 37, 64])
def test_dead_end_bays_too_narrow_to_tilt_in_are_left_by_a_hop(index):
    """Floors whose lattice is exhausted inside the bay (every state it reaches lies on the
    bay's axis): a hop backwards out of it, then a search, gives a valid plan."""
    sc = _bay(index)
    with pytest.raises(segplan.NoPathError, match="every lattice state reachable"):
        segplan.plan_scenario(sc, lattice={"escapes": False})
    plan = segplan.plan_scenario(sc)
    _valid(plan, sc)
    assert -1 in plan.link_directions


@pytest.mark.parametrize("index", [8, 11, 37, 79])
def test_k_turns_in_a_corridor_narrower_than_two_turning_radii(index):
    """The k-turn floors the lattice could not turn around in (it searched for 10 s): a
    turn-around out of the start (forward and backward legs along tight circles, each
    turning the same way; on k-turn-037, near the corridor's closed end, after a straight
    move) then a search; valid, with cusps."""
    sc = rs.with_reverse(rf.reverse_floor("k-turn", index))
    plan = segplan.plan_scenario(sc)
    _valid(plan, sc)
    assert len(plan.cusps) >= 2


def test_turn_arounds_turn_one_way_to_the_target_and_join_their_legs():
    sc = rs.with_reverse(rf.reverse_floor("k-turn", 8))
    links = LinkModel(workspace_of(sc))
    R = sc.robot.min_turning_radius
    start = Pose(*sc.start)
    arcs = escape.turn_arounds(links, start, sc.goal[2], R, 1.25, 0.75)
    assert arcs
    for arc in arcs:
        nodes = _nodes_of(arc)
        assert nodes[0] == start and nodes[-1] == arc.last == arc.inner
        assert abs(math.remainder(arc.last.theta - sc.goal[2], 2 * math.pi)) < 0.5 * escape.STEP
        turns = np.diff(np.unwrap([n.theta for n in nodes]))
        turns = turns[np.abs(turns) > 1e-9]  # a straight move may lead in
        assert (np.sign(turns) == np.sign(turns[0])).all()  # every leg turns the same way
        d = arc.link_directions
        cusps = _cusps(d)
        assert cusps >= 1
        back = sum(union_longd(u) for u, x in zip(arc.unions, d, strict=True) if x < 0)
        assert arc.search_cost == pytest.approx(arc.cost + 0.25 * back + 0.75 * cusps, rel=1e-9)
        chain = type("Chain", (), {"unions": arc.unions})
        assert not dense_collides(chain, sc)
    assert escape.turn_arounds(links, start, start.theta, R) == []  # already there


def test_a_turn_around_near_a_closed_end_starts_after_a_straight_move():
    sc = rs.with_reverse(rf.reverse_floor("k-turn", 37))
    links = LinkModel(workspace_of(sc))
    R = sc.robot.min_turning_radius
    start = Pose(*sc.start)
    arcs = escape.turn_arounds(links, start, sc.goal[2], R)
    assert arcs
    for arc in arcs:
        lead = arc.unions[0]
        assert lead.p0.theta == lead.p1.theta == start.theta  # straight, along the heading
        assert math.hypot(lead.p1.x - lead.p0.x, lead.p1.y - lead.p0.y) / R in escape.TURN_SHIFTS


def _cusps(directions) -> int:
    return sum(a != b for a, b in zip(directions[:-1], directions[1:], strict=True))


def _arc_key(arc: escape.Arc) -> tuple:
    return arc.first, arc.last, arc.link_directions, tuple(u.alpha for u in arc.unions)


@pytest.mark.parametrize("index", [8, 60])
def test_every_share_and_start_is_a_superset_and_the_budget_drops_only_dearer_turns(index):
    """The improvement's search over the legs' lengths and the turn's position
    (``every``): every turn-around of the first share from the nearest start is among them;
    each is valid and within the steering limit; with a ``budget``, exactly the turns
    through which a plan could cost at most the budget are kept (the bound:
    ``min(1, reverse_factor)`` times LONGD and the distance to ``toward`` plus the legs'
    cusps' penalty), the others dropped."""
    sc = rs.with_reverse(rf.reverse_floor("k-turn", index))
    links = LinkModel(workspace_of(sc))
    R = sc.robot.min_turning_radius
    start, goal = Pose(*sc.start), Pose(*sc.goal)
    rf_, cp = 1.25, 0.5 * sc.robot.L
    first = escape.turn_arounds(links, start, goal.theta, R, rf_, cp, escape.IMPROVE_SHARES[:1])
    every = escape.turn_arounds(links, start, goal.theta, R, rf_, cp, escape.IMPROVE_SHARES, True)
    keys = {_arc_key(a) for a in every}
    assert first and {_arc_key(a) for a in first} <= keys
    assert len(keys) > len(first)  # other shares and starts get there too
    ws = links.ws
    for arc in every:
        assert all(ws.curvature_ok(u) and ws.union_free(u) for u in arc.unions)
        assert abs(math.remainder(arc.last.theta - goal.theta, 2 * math.pi)) < 0.5 * escape.STEP
        assert arc.longds is not None and math.fsum(arc.longds) == arc.cost

    def bound(arc):  # the cusps of the legs (a straight move may lead in: not counted)
        lead = arc.unions[0].p0.theta == arc.unions[0].p1.theta
        d = arc.link_directions[1:] if lead else arc.link_directions
        cusps = _cusps(d)
        rest = math.hypot(goal.x - arc.last.x, goal.y - arc.last.y)
        return min(1.0, rf_) * (arc.cost + rest) + cp * cusps

    budget = float(np.median([bound(a) for a in every]))
    shares = escape.IMPROVE_SHARES
    kept = escape.turn_arounds(links, start, goal.theta, R, rf_, cp, shares, True, budget, goal)
    kept_keys = {_arc_key(a) for a in kept}
    assert kept_keys <= keys
    for arc in every:  # a turn's bound grows leg by leg: the last leg's decides
        if bound(arc) <= budget * (1 - 1e-6):
            assert _arc_key(arc) in kept_keys
    assert all(bound(a) <= budget * (1 + 1e-6) for a in kept)
    assert len(kept) < len(every)


@pytest.mark.parametrize("index", [3, 14])
def test_turns_stopped_short_end_near_the_target_and_shorten_the_worst_k_turns(index):
    """``near``: a turn-around stopped within each tolerance of the target heading (the
    first tolerance, ``STEP / 2``, gives the turns of the default call, the same arcs); each
    ends within its tolerance and before it turns all the way, its legs free and within the
    steering limit. On k-turn-003 and k-turn-014 (the reverse study's worst K-turns before
    :data:`escape.IMPROVE_NEAR`: OMPL turns round near the start and reverses down the
    corridor into the goal) the plan is shorter, valid, than with whole turns only."""
    sc = rs.with_reverse(rf.reverse_floor("k-turn", index))
    links = LinkModel(workspace_of(sc))
    R = sc.robot.min_turning_radius
    start, goal = Pose(*sc.start), Pose(*sc.goal)
    args = (links, start, goal.theta, R, 1.25, 0.5 * sc.robot.L, escape.IMPROVE_SHARES, True)
    whole = escape.turn_arounds(*args)
    near = escape.turn_arounds(*args, near=escape.IMPROVE_NEAR)
    assert [_arc_key(a) for a in near[: len(whole)]] == [_arc_key(a) for a in whole]
    short = near[len(whole) :]
    assert short
    ws = links.ws
    for arc in short:
        off = abs(math.remainder(arc.last.theta - goal.theta, 2 * math.pi))
        assert 0.5 * escape.STEP <= off < max(escape.IMPROVE_NEAR)
        assert all(ws.curvature_ok(u) and ws.union_free(u) for u in arc.unions)
    plan = segplan.plan_scenario(sc)
    _valid(plan, sc)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(escape, "IMPROVE_NEAR", escape.IMPROVE_NEAR[:1])
        before = segplan.plan_scenario(sc)
    assert plan.cost < 0.95 * before.cost


def test_a_reversed_turn_around_keeps_its_longds_and_its_search_cost():
    """A goal's turn-around driven the other way (:func:`escape.reversed_arc`) reuses the
    unions' LONGDs: its search cost is the one computed from each union's own LONGD (the
    legs' congruent unions stand for each other) to rounding."""
    sc = rs.with_reverse(rf.reverse_floor("k-turn", 8))
    links = LinkModel(workspace_of(sc))
    R = sc.robot.min_turning_radius
    goal = Pose(*sc.goal)
    for arc in escape.turn_arounds(links, goal, sc.start[2], R, 1.25, 0.5):
        back = escape.reversed_arc(arc, 1.25, 0.5)
        assert back.longds == tuple(reversed(arc.longds))
        plain = escape.reversed_arc(dataclasses.replace(arc, longds=None), 1.25, 0.5)
        assert back.search_cost == pytest.approx(plain.search_cost, rel=1e-9)
        assert back.unions == plain.unions and back.link_directions == plain.link_directions


def test_reversing_plans_are_improved_by_turn_arounds_and_arcs():
    """The improvement of a reversing robot's plan (tight arcs either way, turn-arounds, one
    union between, compared by the search's cost) never makes the plan dearer and finds the
    K-turn that the lattice's coarse headings miss (k-turn-064: 10.6 m from the lattice)."""
    sc = rs.with_reverse(rf.reverse_floor("k-turn", 64))
    plain = segplan.plan_scenario(sc, lattice={"escapes": False}, refine=None)
    plan = segplan.plan_scenario(sc, refine=None)
    _valid(plan, sc)
    w = weighted_cost(plan, 1.25, 0.5 * sc.robot.L)
    assert w < weighted_cost(plain, 1.25, 0.5 * sc.robot.L) - 0.5


def test_cusps_move_where_the_search_cost_drops_and_the_plan_stays_valid(monkeypatch):
    """polish_cusps: the refinement's local moves on each cusp (its two links driven opposite
    ways), after the runs' refinement; the plan stays valid with its cusps; on bay-out-041
    the cusp the lattice put on its coarse headings moves and the search's cost drops."""
    from segplan.planning import default
    from segplan.planning.options import RefineOptions
    from segplan.planning.refine import polish_cusps

    sc = rs.with_reverse(rf.reverse_floor("bay-out", 41))
    cp = 0.5 * sc.robot.L
    polished = segplan.plan_scenario(sc)
    monkeypatch.setattr(default, "polish_cusps", lambda plan, *args, **kw: (plan, 0))
    kept = segplan.plan_scenario(sc)
    _valid(polished, sc)
    assert len(polished.cusps) == len(kept.cusps) >= 1
    assert weighted_cost(polished, 1.25, cp) < weighted_cost(kept, 1.25, cp) - 0.1
    assert polished.cost == pytest.approx(sum(union_longd(u) for u in polished.unions), rel=1e-9)
    calls = []  # (plan in, plan out, moves) of every call the pipeline makes

    def record(plan, *args, **kw):
        out = polish_cusps(plan, *args, **kw)
        calls.append((plan, *out))
        return out

    monkeypatch.setattr(default, "polish_cusps", record)
    segplan.plan_scenario(sc)
    segplan.plan_scenario(rs.with_reverse(rf.reverse_floor("bay-out", 70)))  # its links were rebuilt once
    assert any(taken for _, _, taken in calls)
    for before, after, taken in calls:
        moved = {i for i, (p, q) in enumerate(zip(after.nodes, before.nodes, strict=True)) if p != q}
        assert moved <= set(before.cusps) and bool(moved) == bool(taken)
        for k, u in enumerate(after.unions):  # a link whose nodes stayed keeps its union
            assert ({k, k + 1} & moved) or u is before.unions[k]
    # a plan without cusps is returned as it is
    plain = segplan.load_scenario("single_obstacle")
    forward = segplan.plan_scenario(plain)
    assert polish_cusps(forward, LinkModel(workspace_of(plain)), RefineOptions(), 1.25) == (forward, 0)


def _leg_key(leg) -> list:
    return [(u.p0, u.p1, u.alpha, q) for u, q in leg]


@pytest.mark.parametrize("floor", [("k-turn", 4), ("dead-end", 10), ("bay-out", 3)])
def test_legs_kept_for_reuse_answer_as_a_leg_driven_afresh(floor):
    # legs.Legs keeps each leg it drives; a later request with another stop or length is cut
    # from it or driven further: union for union what a Legs driven for that request alone gives
    sc = rs.with_reverse(rf.reverse_floor(*floor))
    links = LinkModel(workspace_of(sc))
    R = sc.robot.min_turning_radius
    kept = legs.Legs(links, R)
    rng = np.random.default_rng(26)
    starts = [Pose(*sc.start), Pose(*sc.goal)]
    for _ in range(60):
        p = starts[rng.integers(2)]
        side, direction = int(rng.choice([1, -1])), int(rng.choice([1, -1]))
        steps = int(rng.integers(1, legs.LEG_STEPS + 1))
        target, tol = float(rng.uniform(-math.pi, math.pi)), float(rng.uniform(0.05, 1.0))

        def stop(q, target=target, tol=tol):
            return abs(math.remainder(q.theta - target, 2 * math.pi)) < tol

        got = kept.leg(p, side, direction, stop, steps)
        fresh = legs.Legs(links, R).leg(p, side, direction, stop, steps)
        assert _leg_key(got) == _leg_key(fresh)
        if got:
            assert kept.piece(p, side, direction) == union_longd(got[0][0])
    with pytest.raises(ValueError, match="another link model"):
        escape.tight_arcs(LinkModel(workspace_of(sc)), sc.start, R, legs=kept)
