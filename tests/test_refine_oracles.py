"""Oracles for the refinement (issue 15): its moves, its guard and its screening filter.

* Every accepted local move strictly lowers the chain's cost: over a polish, the cost falls
  by at least ``MIN_GAIN * L`` per accepted move; shortcuts never raise it.
* The refined plan is never longer than the input: also where nothing improves (a single
  straight union), and against an adversarial objective that rewards length (the final
  "never longer" guard must then return the input's chain unchanged).
* ``certain_failures`` flags the obvious failures (a link through an obstacle's centre, a
  link that bulges past a wall) and never a link that a dense shapely sampling finds free.

Every reach into the package's internals is in the helpers of the first section.
"""

import math
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest
import shapely
from test_search import check_plan

import segplan
from segplan import Pose, Robot, Union, make_scenario, plan_scenario, random_world, refine

SCENARIOS = Path(__file__).resolve().parent.parent / "scenarios"
NAMES = sorted(p.stem for p in SCENARIOS.glob("*.json"))


# -- the reaches into internals ----------------------------------------------------------
@contextmanager
def watching_the_refiner():
    """Record every polish and shortcut: ``(step, cost before, cost after, accepted moves)``.

    Wraps ``_Refiner.polish`` and ``_Refiner.shortcut`` (internal); a chain's cost is the
    sum of the refiner's own checked link costs (``_Refiner.link``).
    """
    from segplan.planning.refine import MIN_GAIN, _Refiner

    log = []
    polish, shortcut = _Refiner.polish, _Refiner.shortcut

    def chain_cost(self, nodes):
        return sum(self.link(a, b) for a, b in zip(nodes[:-1], nodes[1:], strict=True))

    def watched_polish(self, nodes, *args):
        before, moves = chain_cost(self, nodes), self.moves
        out = polish(self, nodes, *args)
        log.append(("polish", before, chain_cost(self, out), self.moves - moves, MIN_GAIN * self.L))
        return out

    def watched_shortcut(self, nodes, kinds):
        before = chain_cost(self, nodes)
        out = shortcut(self, nodes, kinds)
        log.append(("shortcut", before, chain_cost(self, out[0]), 0, 0.0))
        return out

    _Refiner.polish, _Refiner.shortcut = watched_polish, watched_shortcut
    try:
        yield log
    finally:
        _Refiner.polish, _Refiner.shortcut = polish, shortcut


@contextmanager
def length_rewarded():
    """The refiner's link cost negated (internal ``_Refiner.cost``): it then seeks longer chains."""
    from segplan.planning.refine import _Refiner

    original = _Refiner.cost
    _Refiner.cost = staticmethod(lambda u: -original(u))
    try:
        yield
    finally:
        _Refiner.cost = staticmethod(original)


def random_links(rng, bounds, n: int, aim: float, turn: float):
    """``n`` random links ``A[k] -> B[k]`` (poses, ``(n, 3)``): ``A`` uniform in ``bounds`` with
    any heading, ``B`` 0.5 to 6 m ahead within ``aim`` of ``A``'s heading, its heading within
    ``turn`` of ``A``'s."""
    xmin, ymin, xmax, ymax = bounds
    A = np.column_stack(
        (rng.uniform(xmin, xmax, n), rng.uniform(ymin, ymax, n), rng.uniform(-np.pi, np.pi, n))
    )
    step = rng.uniform(0.5, 6.0, n)
    ang = A[:, 2] + rng.uniform(-aim, aim, n)
    B = np.column_stack(
        (A[:, 0] + step * np.cos(ang), A[:, 1] + step * np.sin(ang), A[:, 2] + rng.uniform(-turn, turn, n))
    )
    return A, B


def flagged(scenario, A, B):
    """``certain_failures`` of the links ``A[k] -> B[k]`` in their heuristic frames (internal).

    Returns the flags and the unions (None where no cubic joins the poses).
    """
    from segplan.model.frame import heuristic_alpha
    from segplan.model.union import cubic_coefficients
    from segplan.planning.refine import certain_failures
    from segplan.planning.validity import Workspace

    robot = scenario.robot
    ws = Workspace(scenario.enlarged, robot.L, scenario.free_bounds, robot.max_curvature)
    A, B = np.atleast_2d(A).astype(float), np.atleast_2d(B).astype(float)
    d = np.hypot(B[:, 0] - A[:, 0], B[:, 1] - A[:, 1])
    psi = np.arctan2(B[:, 1] - A[:, 1], B[:, 0] - A[:, 0])
    phi0, phi1 = np.angle(np.exp(1j * (A[:, 2] - psi))), np.angle(np.exp(1j * (B[:, 2] - psi)))
    lo = -np.pi / 2 - np.minimum(np.minimum(phi0, phi1), 0.0)
    hi = np.pi / 2 - np.maximum(np.maximum(phi0, phi1), 0.0)
    assert np.all(hi - lo > 0.02), "test links must admit a cubic"
    alpha = np.atleast_1d(heuristic_alpha(d, phi0, phi1, robot.L))
    bad = certain_failures(ws, A, psi - alpha, *cubic_coefficients(d, phi0, phi1, alpha))
    unions = [Union(Pose(*a), Pose(*b), float(al), robot.L) for a, b, al in zip(A, B, alpha, strict=True)]
    return bad, unions


# -- dense oracle ----------------------------------------------------------------------------
def dense_clearance(u: Union, scenario, n: int = 801) -> float:
    """Least distance of the sampled swept segment to the enlarged obstacles and the walls.

    Negative (-1) if the exact curvature breaks the steering limit or a sample leaves the
    free bounds; 0 if it touches an obstacle.
    """
    if u.max_curvature() > scenario.robot.max_curvature:
        return -1.0
    a, b = u.rear(n), u.front(n)
    segs = shapely.linestrings(np.stack((a, b), axis=1))
    best = math.inf
    for p in scenario.enlarged:
        best = min(best, float(shapely.distance(segs, shapely.Polygon(p)).min()))
    if scenario.free_bounds is not None:
        xmin, ymin, xmax, ymax = scenario.free_bounds
        pts = np.vstack((a, b))
        wall = min((pts[:, 0] - xmin).min(), (xmax - pts[:, 0]).min(), (pts[:, 1] - ymin).min())
        wall = min(wall, (ymax - pts[:, 1]).min())
        if wall <= 0:
            return -1.0
        best = min(best, wall)
    return best


def load(name):
    return segplan.load_scenario(SCENARIOS / f"{name}.json")


# -- every accepted move lowers the cost -------------------------------------------------------
@pytest.mark.parametrize("name", ["fig5_example1", "fig6_example2", "turn_around", "narrow_passage"])
def test_every_accepted_move_lowers_the_cost(name):
    sc = load(name)
    found = plan_scenario(sc, planner="paper")
    with watching_the_refiner() as log:
        refined = refine(found, sc, rounds=2)
    polishes = [entry for entry in log if entry[0] == "polish"]
    assert len(polishes) == 2 and len(log) == 5  # shortcut, (polish, shortcut) x 2
    moves = 0
    for step, before, after, accepted, gain in log:
        assert math.isfinite(before) and math.isfinite(after), step
        # each accepted move lowers its node's two links by more than the gain; the other
        # links are untouched (nodes of one parity share no link)
        assert after <= before - accepted * gain + 1e-12 * before, step
        moves += accepted
    assert moves == refined.refinement.moves
    if name in ("fig5_example1", "fig6_example2"):
        assert moves > 0  # the oracle was exercised
    assert refined.cost <= found.cost


def test_moves_are_exercised_and_checked_on_random_worlds():
    total = 0
    for seed in (2, 3, 7):
        sc = random_world(seed, 8)
        found = plan_scenario(sc, planner="paper")
        with watching_the_refiner() as log:
            refined = refine(found, sc)
        for step, before, after, accepted, gain in log:
            assert after <= before - accepted * gain + 1e-12 * before, step
            total += accepted
        check_plan(refined, sc, n=150)
        assert refined.cost <= found.cost
    assert total > 0


# -- never longer than the input -----------------------------------------------------------
def test_nothing_to_improve_returns_the_input():
    """A single straight union: no shortcut, no split, no node to move; the plan is unchanged."""
    sc = make_scenario(Robot(1.0), (0.0, 0.0, 0.0), (2.5, 0.0, 0.0), [], None)
    found = plan_scenario(sc, planner="paper")
    refined = refine(found, sc)
    assert refined.nodes == found.nodes and refined.unions == found.unions
    assert refined.cost == found.cost
    info = refined.refinement
    assert (info.shortcuts, info.splits, info.moves) == (0, 0, 0)


@pytest.mark.parametrize("name", ["fig5_example1", "fig6_example2", "single_obstacle"])
def test_never_longer_guard_against_an_objective_that_rewards_length(name):
    """The refiner made to prefer longer chains: the guard must hand back the input's chain."""
    sc = load(name)
    found = plan_scenario(sc, planner="paper")
    with length_rewarded():
        refined = refine(found, sc)
    assert refined.cost == found.cost
    assert refined.nodes == found.nodes and refined.unions == found.unions
    assert refined.kinds == found.kinds
    # the objective did change the chain the refiner made (else this test proves nothing)
    with watching_the_refiner() as log, length_rewarded():
        refine(found, sc)
    assert any(after != before for _, before, after, _, _ in log)


# -- certain_failures ----------------------------------------------------------------------------
BOX = [[9.0, -1.0], [11.0, -1.0], [11.0, 1.0], [9.0, 1.0]]
ROOM = make_scenario(Robot(1.0, 0.2), (1.0, 0.0, 0.0), (17.0, 0.0, 0.0), [BOX], (0.0, -5.0, 20.0, 5.0))


def test_certain_failures_flag_a_link_through_an_obstacle_centre():
    # straight and curved links whose rear path crosses the box's centre (10, 0)
    A, B = [], []
    for ang in np.radians([0.0, 20.0, -35.0, 60.0, 180.0]):
        c, s = math.cos(ang), math.sin(ang)
        for turn in (0.0, 0.3, -0.3):
            A.append((10.0 - 4.0 * c, -4.0 * s, ang + turn))
            B.append((10.0 + 4.0 * c, 4.0 * s, ang - turn))
    bad, unions = flagged(ROOM, A, B)
    assert bad.all()
    assert all(dense_clearance(u, ROOM) <= 0.0 for u in unions)  # the oracle agrees


def test_certain_failures_flag_a_link_past_a_wall():
    # a cubic that bulges above the top wall (y = 5 - half width), ends inside
    A = [(2.0, 3.5, 1.2), (14.0, -3.5, -1.2), (15.0, 3.0, 0.0)]
    B = [(7.0, 3.5, -1.2), (18.0, -3.5, 1.2), (19.9, 3.0, 0.0)]  # the last: front wheel past x = 20
    bad, unions = flagged(ROOM, A, B)
    assert bad.all()
    assert all(dense_clearance(u, ROOM) < 0.0 for u in unions)


@pytest.mark.parametrize("seed", range(4))
def test_certain_failures_never_flag_a_free_link(seed):
    """Dense shapely sampling: every link free with a margin is left unflagged; some links are flagged."""
    sc = random_world(seed, 8)
    rng = np.random.default_rng(seed)
    A, B = random_links(rng, sc.free_bounds, 250, aim=0.6, turn=0.6)
    bad, unions = flagged(sc, A, B)
    clearance = np.array([dense_clearance(u, sc, n=151) for u in unions])
    free = clearance > 1e-6
    assert free.sum() >= 25 and bad.sum() >= 25  # both sides of the claim are exercised
    assert not np.any(bad & free), np.flatnonzero(bad & free)
    # and the screening is useful: most links that sampled points prove blocked are flagged
    assert np.mean(bad[clearance < 0]) > 0.5


# -- pinned refinements of the shipped scenarios ---------------------------------------------
#: ``scenario: (cost, nodes, shortcuts, splits, moves)`` of ``refine`` with its defaults on
#: ``plan_scenario``'s plan (h' a), measured on this branch. Why pinned: the oracles above
#: hold for many refiners (any that only takes improving moves); a change of the order of
#: the moves, of the splits or of the screening shows here. Cost: relative tolerance 1e-6
#: (the exact [1] by Romberg at rtol 1e-8); counts: exact, as the refinement is
#: deterministic. A deliberate change of the search or the refinement re-pins these in the
#: same commit and says why.
REFINED = {
    "empty_room": (7.982004167484209, 3, 0, 1, 3),
    "fig5_example1": (31.298825811526513, 7, 1, 3, 16),
    "fig6_example2": (33.067645829354305, 5, 5, 3, 20),
    "narrow_passage": (11.34738466897761, 5, 2, 2, 15),
    "single_obstacle": (9.770496933108397, 3, 2, 2, 6),
    "turn_around": (11.359883725298682, 6, 0, 1, 14),
}


@pytest.mark.parametrize("name", NAMES)
def test_shipped_refinements_pinned(name):
    sc = load(name)
    refined = refine(plan_scenario(sc, planner="paper"), sc)
    cost, nodes, shortcuts, splits, moves = REFINED[name]
    info = refined.refinement
    assert refined.cost == pytest.approx(cost, rel=1e-6)
    assert (len(refined.nodes), info.shortcuts, info.splits, info.moves) == (nodes, shortcuts, splits, moves)
