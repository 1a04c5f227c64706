"""Deferred edge checks of the lattice search (segplan.planning.lattice.edges): sound, complete, cheapest
repair."""

import math
import zlib

import pytest

from segplan import NoPathError
from segplan.planning.lattice import search as lattice
from segplan.planning.lattice.search import plan_lattice
from segplan.studies.floors import hard_cases, random_floor
from segplan.viz.metrics import measure_scenario_path, plan_poses


def _spy(monkeypatch):
    """Record the searches run and the lattice edges of the plans they make."""
    seen = {"searches": [], "edges": []}
    run, make_plan = lattice._LatticeSearch.run, lattice._LatticeSearch.make_plan

    def spy_run(self, *a):
        seen["searches"].append(self)
        return run(self, *a)

    def spy_make_plan(self, edges, *a):
        seen["edges"].append(list(edges))
        return make_plan(self, edges, *a)

    monkeypatch.setattr(lattice._LatticeSearch, "run", spy_run)
    monkeypatch.setattr(lattice._LatticeSearch, "make_plan", spy_make_plan)
    return seen


@pytest.mark.parametrize("name", ["any-023", "natural-005"])
def test_edges_that_fail_their_deferred_check_are_never_in_the_plan(monkeypatch, name):
    # about half of the edges checked late are declared blocked (as if an obstacle the grid
    # cannot see were there): the search repairs their states and still finds a plan, none
    # of whose edges is one of them, each state's g its parent's plus the edge's LONGD
    failed = set()
    real = lattice._LatticeSearch.edge_free

    def edge_free(self, key, m):
        if zlib.crc32(repr((key, m)).encode()) % 2:
            failed.add((key, m))
            return False
        return real(self, key, m)

    monkeypatch.setattr(lattice._LatticeSearch, "edge_free", edge_free)
    seen = _spy(monkeypatch)
    kind, index = name.rsplit("-", 1)
    sc = random_floor(kind, int(index))
    plan = plan_lattice(sc, escapes=False, retry=False)
    assert failed, "no edge was checked late: the test tests nothing"
    search, edges = seen["searches"][-1], seen["edges"][-1]
    assert not set(edges) & failed
    for key, m in edges:
        i, j, h = key
        di, dj, h1 = search.step[h][m]
        child = (i + di, j + dj, h1)
        assert search.parent[child] == (key, m)
        assert search.g[child] == pytest.approx(search.g[key] + search.cost[h][m], rel=1e-12)
    m = measure_scenario_path(plan_poses(plan), sc)  # the dense shapely oracle
    assert not m.collides and m.reversals == 0


def test_edges_are_checked_only_for_states_taken_from_the_open_list(monkeypatch):
    # the point of deferring: fewer checks than edges the grid could not clear
    calls = []
    real = lattice._LatticeSearch.edge_free

    def edge_free(self, key, m):
        calls.append((key, m))
        return real(self, key, m)

    monkeypatch.setattr(lattice._LatticeSearch, "edge_free", edge_free)
    seen = _spy(monkeypatch)
    plan_lattice(random_floor("any", 23), escapes=False, retry=False)
    search = seen["searches"][-1]
    unsure = 0
    lower = search.grid.lower_blocked_flat
    for parent in search.parent.values():
        if parent is None:
            continue
        (i, j, h), m = parent
        least = lower[search.offsets[h][m] + search.grid.base(i * search.q, j * search.q)].min()
        unsure += bool(least <= search.delta[h][m])
    assert 0 < len(calls) < unsure


def test_repair_gives_the_cheapest_passing_edge_from_an_expanded_state(monkeypatch):
    seen = _spy(monkeypatch)
    sc = random_floor("natural", 0)
    plan_lattice(sc, escapes=False, retry=False)
    s = seen["searches"][-1]
    key = (12, 0, 0)  # ahead of the start, in the open
    preds = [(key[0] - di, key[1] - dj, h0, m) for h0, m, di, dj in s.into_steps[key[2]]]
    assert len(preds) >= 3
    s.heap, s.g, s.parent = [], {}, {}
    closed = set()
    for n, (i, j, h0, _) in enumerate(preds):  # every predecessor expanded, distinct costs
        closed.add((i, j, h0))
        s.g[(i, j, h0)] = 1.0 + 0.01 * n
    options = sorted((s.g[(i, j, h0)] + s.cost[h0][m], (i, j, h0), m) for i, j, h0, m in preds)
    s.g[key], s.parent[key] = -1.0, None
    failed = {(options[0][1], options[0][2])}  # the cheapest edge failed its check
    counter = s.repair(key, closed, failed, 5.0, 7)
    assert counter == 8
    assert (s.g[key], s.parent[key]) == (options[1][0], (options[1][1], options[1][2]))
    assert s.heap == [(options[1][0] + 5.0, 7, key)]
    # no passing edge left: the state is forgotten until a new parent reaches it
    failed = {(p, m) for _, p, m in options}
    assert s.repair(key, closed, failed, 5.0, 8) == 8
    assert key not in s.g and key not in s.parent
    assert math.isfinite(options[1][0])


def _approach_tree(monkeypatch, name, fail_half):
    """The approach tree of ``name``'s lattice search (grown to its enclosure size), with
    about half of the edges it checks declared blocked if ``fail_half``; returns the search,
    the edges declared blocked and every edge checked."""
    failed, checked = set(), []
    real = lattice._LatticeSearch._approach_edge_free

    def edge_free(self, prev, key, h0, m):
        if fail_half and zlib.crc32(repr((prev, h0, m)).encode()) % 2:
            failed.add((prev, h0, m))
            return False
        ok = real(self, prev, key, h0, m)
        checked.append((prev, ok))
        return ok

    monkeypatch.setattr(lattice._LatticeSearch, "_approach_edge_free", edge_free)
    seen = _spy(monkeypatch)
    kind, index = name.rsplit("-", 1)
    try:
        plan_lattice(random_floor(kind, int(index)), escapes=False, retry=False, max_expansions=40)
    except NoPathError:
        pass
    search = seen["searches"][-1]
    search.grow_approaches(300)
    return search, failed, checked


@pytest.mark.parametrize("name", ["any-023", "any-005"])
def test_approach_chains_avoid_edges_that_fail_their_deferred_check(monkeypatch, name):
    s, failed, _ = _approach_tree(monkeypatch, name, fail_half=True)
    assert failed, "no edge was checked late: the test tests nothing"
    cost = s._back["cost"]
    assert len(s.approach_keys) > 20
    for key in s.approach_keys:  # every settled state: a chain of passing edges to the goal
        while s.approach_next[key] is not None:
            nk, h0, m = s.approach_next[key]
            assert (key, h0, m) not in failed
            assert cost[key] == pytest.approx(cost[nk] + s.prims[h0][m].cost, rel=1e-12)
            key = nk


def test_approach_edges_are_checked_only_for_settled_states(monkeypatch):
    s, _, checked = _approach_tree(monkeypatch, "any-023", fail_half=False)
    done = s._back["done"]
    # an edge is checked when its state is settled: it is, unless the edge failed, or the
    # state is the next to settle (checked when a growth stops, to tell whether it could go on)
    waiting = {prev for prev, ok in checked if ok and prev not in done}
    assert checked and len(waiting) <= 2 and waiting <= {key for _, key in s._back["heap"]}
    # states left in the open list with an edge the grid could not clear: never checked
    assert s._back["unchecked"] - done
    for u in [s.approach_chain(k)[0] for k in s.approach_keys[:30]]:  # the dense oracle
        sc = random_floor("any", 23)
        m = measure_scenario_path(plan_poses([u]), sc)
        assert not m.collides


@pytest.mark.parametrize("name", ["enclosed_goal", "enclosed_slit"])
def test_the_approach_tree_is_exhausted_exactly_when_no_checked_edge_is_left(monkeypatch, name):
    # grown without a limit, the tree runs out of states; grown again to exactly that many
    # settled states, the states left in its open list (edges never checked) must be checked
    # before it says whether it is exhausted: the same answer, the same states
    made = []
    init = lattice._LatticeSearch.__init__

    def spy_init(self, *a):
        init(self, *a)
        made.append(self)

    monkeypatch.setattr(lattice._LatticeSearch, "__init__", spy_init)
    with pytest.raises(NoPathError):  # an enclosed goal: the search does not even start
        plan_lattice(hard_cases()[name], escapes=False, retry=False, max_expansions=40)
    s = made[-1]
    s.certified_calls = 0
    s.build_approaches(math.inf, 100_000)
    full, exhausted = list(s.approach_keys), s.approach_exhausted
    s.build_approaches(math.inf, len(full))
    assert s.approach_exhausted == exhausted
    assert s.approach_keys == full
    assert exhausted
