"""Deferred edge checks of the lattice search (segplan.planning.lattice.edges) in real searches:
sound, complete, cheapest repair; the search and the goal's approach tree, each composed with
its lazy edges (the toy graph: tests/test_lattice_parts.py)."""

import math
import zlib

import pytest
from test_lattice_parts import astar_of, plan_of

from segplan.planning.lattice.approach import GoalApproach
from segplan.planning.lattice.astar import LatticeAStar
from segplan.studies.floors import hard_cases, random_floor
from segplan.viz.metrics import measure_scenario_path, plan_poses


def _half_fail(edge) -> bool:
    """About half of the edges, declared blocked (as if an obstacle the grid cannot see were there)."""
    return bool(zlib.crc32(repr(edge).encode()) % 2)


class _HalfBlocked(LatticeAStar):
    """A search whose deferred checks fail about half of the edges (``failed``), the others
    checked for real (``calls``)."""

    def __init__(self, *a, fail=True, **kw):
        self.fail, self.declared, self.calls = fail, set(), []
        super().__init__(*a, **kw)

    def check_edge(self, edge):
        self.calls.append(edge)
        if self.fail and _half_fail(edge):
            self.declared.add(edge)
            return False
        return super().check_edge(edge)


@pytest.mark.parametrize("name", ["any-023", "natural-005"])
def test_edges_that_fail_their_deferred_check_are_never_in_the_plan(name):
    # about half of the edges checked late are declared blocked: the search repairs their
    # states and still finds a plan, none of whose edges is one of them, each state's g its
    # parent's plus the edge's LONGD
    kind, index = name.rsplit("-", 1)
    sc = random_floor(kind, int(index))
    search = astar_of(sc, cls=_HalfBlocked)
    plan, outcome, made = plan_of(search)
    assert outcome == "found"
    assert search.declared, "no edge was checked late: the test tests nothing"
    edges = made[-1]
    assert not set(edges) & search.declared
    for key, m in edges:
        i, j, h = key
        di, dj, h1 = search.step[h][m]
        child = (i + di, j + dj, h1)
        assert search.parent[child] == (key, m)
        assert search.g[child] == pytest.approx(search.g[key] + search.cost[h][m], rel=1e-12)
    m = measure_scenario_path(plan_poses(plan), sc)  # the dense shapely oracle
    assert not m.collides and m.reversals == 0


def test_edges_are_checked_only_for_states_taken_from_the_open_list():
    # the point of deferring: fewer checks than edges the grid could not clear
    search = astar_of(random_floor("any", 23), cls=_HalfBlocked, fail=False)
    plan_of(search)
    unsure = 0
    for parent in search.parent.values():
        if parent is None:
            continue
        free, bad = search.screen_edge(parent)
        assert not bad
        unsure += not free
    assert 0 < len(search.calls) < unsure


def test_repair_gives_the_cheapest_passing_edge_from_an_expanded_state():
    s = astar_of(random_floor("natural", 0))
    plan_of(s)
    key = (12, 0, 0)  # ahead of the start, in the open
    preds = [(key[0] - di, key[1] - dj, h0, m) for h0, m, di, dj in s.into_steps[key[2]]]
    assert len(preds) >= 3
    s.heap, s.g, s.parent = [], {}, {}
    s.edges.reset()
    closed = set()
    for n, (i, j, h0, _) in enumerate(preds):  # every predecessor expanded, distinct costs
        closed.add((i, j, h0))
        s.g[(i, j, h0)] = 1.0 + 0.01 * n
    options = sorted((s.g[(i, j, h0)] + s.cost[h0][m], (i, j, h0), m) for i, j, h0, m in preds)
    s.g[key], s.parent[key] = -1.0, None
    s.edges.failed.add((options[0][1], options[0][2]))  # the cheapest edge failed its check
    counter = s.repair(key, closed, 5.0, 7)
    assert counter == 8
    assert (s.g[key], s.parent[key]) == (options[1][0], (options[1][1], options[1][2]))
    assert s.heap == [(options[1][0] + 5.0, 7, key)]
    # no passing edge left: the state is forgotten until a new parent reaches it
    s.edges.failed.update((p, m) for _, p, m in options)
    assert s.repair(key, closed, 5.0, 8) == 8
    assert key not in s.g and key not in s.parent
    assert math.isfinite(options[1][0])


class _HalfBlockedTree(GoalApproach):
    """An approach tree whose deferred checks fail about half of the edges (if ``fail``)."""

    fail = True

    def __init__(self, *a, **kw):
        self.declared, self.checked = set(), []
        super().__init__(*a, **kw)

    def check_edge(self, edge):
        if self.fail and _half_fail(edge):
            self.declared.add(edge)
            return False
        ok = super().check_edge(edge)
        self.checked.append((edge[0], ok))
        return ok


class _SoundTree(_HalfBlockedTree):
    fail = False


def _approach_tree(sc, tree_cls, limit=300):
    """The approach tree of ``sc``'s lattice search, composed as ``tree_cls``, grown to ``limit``."""
    s = astar_of(sc)  # the lattice's parts, for the tree's
    tree = tree_cls(sc.robot, sc.start, sc.goal, s.r, s.prims, s.fine, s.grid, s.ws, s.ex, s.schedule)
    tree.build(s.schedule.approach_limit)
    tree.grow(limit)
    return tree


@pytest.mark.parametrize("name", ["any-023", "any-005"])
def test_approach_chains_avoid_edges_that_fail_their_deferred_check(name):
    kind, index = name.rsplit("-", 1)
    t = _approach_tree(random_floor(kind, int(index)), _HalfBlockedTree)
    assert t.declared, "no edge was checked late: the test tests nothing"
    assert len(t.keys) > 20
    for key in t.keys:  # every settled state: a chain of passing edges to the goal
        while t.next[key] is not None:
            nk, h0, m = t.next[key]
            assert (key, m) not in t.declared
            assert t.to_goal[key] == pytest.approx(t.to_goal[nk] + t.prims[h0][m].cost, rel=1e-12)
            key = nk


def test_the_exhausted_approach_tree_is_the_least_cost_tree_of_the_edges_that_pass():
    """Grown until exhausted with half of its deferred checks failing, the approach tree holds
    every state that an edge that certainly passes (its check not declared failed, the
    certified test passing its union, tested here apart) joins to a state of the tree, at no
    more than that edge's cost plus that state's (Bellman's inequality): a state whose edge
    failed is repaired to its cheapest passing edge, not forgotten."""
    t = _approach_tree(hard_cases()["enclosed_slit"], _HalfBlockedTree, limit=100_000)
    assert t.exhausted and t.declared and len(t.keys) > 20
    settled = set(t.keys) | {(0, 0, 0)}
    frontier = {}  # states outside the tree: (i, j, h0) -> [(m, p)] of edges into it
    for i, j, h1 in settled:
        for h0, prims in enumerate(t.prims):
            for m, p in enumerate(prims):
                if p.h1 == h1:
                    frontier.setdefault((i - p.di, j - p.dj, h0), []).append((m, p))
    tighter, missing = [], []
    for key, into in frontier.items():
        for m, p in into:
            if _half_fail((key, m)):
                continue
            succ = (key[0] + p.di, key[1] + p.dj, p.h1)
            bound = t.to_goal[succ] + p.cost
            if key in settled and not bound < t.to_goal[key] * (1 - 1e-12):
                continue
            if bound <= t.budget and t.ws.union_free(t.frame.union(key, p)):
                (tighter if key in settled else missing).append((key, m))
    assert not tighter and not missing


def test_approach_edges_are_checked_only_for_settled_states():
    sc = random_floor("any", 23)
    t = _approach_tree(sc, _SoundTree)
    # an edge is checked when its state is settled: it is, unless the edge failed, or the
    # state is the next to settle (checked when a growth stops, to tell whether it could go on)
    waiting = {prev for prev, ok in t.checked if ok and prev not in t.settled}
    assert t.checked and len(waiting) <= 2 and waiting <= {key for _, key in t.open}
    # states left in the open list with an edge the grid could not clear: never checked
    assert t.edges.unchecked - t.settled
    for u in [t.chain(k)[0] for k in t.keys[:30]]:  # the dense oracle
        m = measure_scenario_path(plan_poses([u]), sc)
        assert not m.collides


@pytest.mark.parametrize("name", ["enclosed_goal", "enclosed_slit"])
def test_the_approach_tree_is_exhausted_exactly_when_no_checked_edge_is_left(name):
    # grown without a limit, the tree runs out of states; grown again to exactly that many
    # settled states, the states left in its open list (edges never checked) must be checked
    # before it says whether it is exhausted: the same answer, the same states
    sc = hard_cases()[name]
    t = _approach_tree(sc, _SoundTree, limit=100_000)
    full, exhausted = list(t.keys), t.exhausted
    t.build(len(full))
    assert t.exhausted == exhausted
    assert t.keys == full
    assert exhausted
