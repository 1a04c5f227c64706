"""Oracles for the lattice planner (issue 24, "Tests that catch the lattice's bugs").

Each check stands outside the search it judges:

* **Dijkstra on the generated graph.** A recorder watches a lattice search (no library
  change: a subclass of :class:`segplan.planning.lattice.astar.LatticeAStar` whose ``g`` is
  a recording twin and whose ``try_goal`` logs its calls) and keeps the states it expanded
  and the states that tried the direct union to the goal. The oracle rebuilds that graph on its own:
  every primitive out of every expanded state, kept if the certified test
  (:meth:`segplan.planning.validity.Workspace.union_free`, no grid screen, no deferred check)
  passes it; every tried direct union to the goal, kept if free. An independent Dijkstra
  on it gives the optimum: weight 1 must reach it, weight ``w`` stay within ``w`` times it.
* **h' never above the cost-to-go.** The Dubins length against OMPL's Dubins space, against
  forward paths of bounded curvature drawn at random (hypothesis), and below LONGD of every
  union within the steering limit; the search's own ``h'`` (Dubins and grid distance)
  against the cost-to-go of the graph above (a reverse Dijkstra: that graph's cost-to-go is
  at least the true one, so ``h'`` above it is a proof of inadmissibility).
* **Every returned plan.** Its cost the sum of its unions' exact LONGD [1]; every union
  within the steering limit (curvature sampled densely) and free by a dense shapely oracle
  of the swept segment (quadrilaterals between consecutive segment positions).
* **The search's bookkeeping.** No state expanded twice; a state's ``g`` lowered only; every
  deferred repair in a real search takes the cheapest edge from an expanded state that the
  certified test passes (every primitive of every heading tried, not the search's tables).

The coarse guide (:class:`segplan.planning.lattice.guide.Guide`) is an estimate, not a bound,
and the goal's approach tree adds edges this recorder does not rebuild: the optimality
oracles turn both off (a schedule of the test, :class:`segplan.planning.schedule.Schedule`).
The mutation tests at the end show that the oracles fail when the search is broken (h' times
1.5, duplicate detection broken, a Dubins word missing, the repair taking the first passing
edge).
"""

import dataclasses
import heapq
import inspect
import math
import sys
import textwrap

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from ompl_distance import ompl_distance
from test_lattice_parts import astar_of, plan_of

from segplan import longd_exact
from segplan.model.pose import Pose
from segplan.planning import dubins
from segplan.planning.dubins import dubins_length, dubins_length_scalar
from segplan.planning.lattice import edges as edges_module
from segplan.planning.lattice import search as lattice
from segplan.planning.lattice.astar import LatticeAStar
from segplan.planning.lattice.edges import LazyEdges
from segplan.planning.lattice.frame import LatticeFrame
from segplan.planning.lattice.primitives import primitive_set
from segplan.planning.plan import union_longd
from segplan.planning.schedule import SCHEDULE
from segplan.studies.floors import random_floor

GOAL = ("goal",)
DEG = math.pi / 180.0


# -- the recorder (every reach into the search's internals is here) -------------------------
def _caller() -> str:
    """The name of the method that called the caller (``run``, ``repair``), also when a mutation
    tool has wrapped it (mutmut renames ``run`` to ``xǁLatticeAStarǁrun__mutmut_orig`` or
    ``..._mutmut_7`` behind a trampoline of the old name)."""
    name = sys._getframe(2).f_code.co_name
    return name.rsplit("\u01c1", 1)[-1].split("__mutmut_")[0]


class _RecordedG(dict):
    """The search's ``g``: logs every write (caller, key, value) and every read by ``run``
    (``g = self.g[key]``, once per expansion) and deletions (a repair forgets a state).
    ``forget``: a mutant whose ``get`` sees no earlier path (duplicate detection broken)."""

    forget = False

    def __init__(self, d, log):
        super().__init__(d)
        self.log = log

    def __setitem__(self, k, v):
        self.log.append(("set", _caller(), k, v))
        super().__setitem__(k, v)

    def __delitem__(self, k):
        self.log.append(("del", _caller(), k, None))
        super().__delitem__(k)

    def __getitem__(self, k):
        if _caller() == "run":
            self.log.append(("expand", k))
        return super().__getitem__(k)

    def get(self, k, default=None):
        return default if self.forget else super().get(k, default)


class Recorded(LatticeAStar):
    """A lattice search that records: ``glog`` (the log of :class:`_RecordedG`, per run) and
    ``tried`` (``(key, world pose)`` of the states that tried the direct union to the goal).
    ``forget``: the duplicate-detection mutant."""

    forget = False

    @property
    def g(self):
        return self.__dict__["g"]

    @g.setter
    def g(self, value):
        log = []
        g = _RecordedG(value, log)
        g.forget = self.forget
        self.__dict__.update(g=g, glog=log, tried=[])

    def try_goal(self, key, P, g):
        self.tried.append((key, P))
        return super().try_goal(key, P, g)


def recorded(name, weight, every=1, guide=False, approaches=False, cls=Recorded, parts=None):
    """The search ``plan_lattice`` runs on a random floor (one resolution, no tight arcs, every
    expanded state trying the direct union to the goal by default), recorded, not run. Without
    ``guide`` nor ``approaches``, the coarse guide is never built and no union goes to the
    goal's approach tree (the tree still serves the enclosure test)."""
    kind, index = name.rsplit("-", 1)
    schedule = SCHEDULE
    if not guide:
        schedule = dataclasses.replace(schedule, guide_after=10**9)
    if not approaches:
        schedule = dataclasses.replace(schedule, approach_tries=0)
    sc = random_floor(kind, int(index))
    return astar_of(sc, cls=cls, weight=weight, analytic_every=every, schedule=schedule, **(parts or {}))


def expanded_states(search) -> list:
    """The states the search expanded, in order (repeats kept)."""
    return [e[1] for e in search.glog if e[0] == "expand"]


# -- the oracle ----------------------------------------------------------------------------
def generated_graph(search) -> dict:
    """The graph the search generated, rebuilt without its screens: ``{state: [(state, cost)]}``.

    Every primitive out of every expanded state, kept if the certified test passes its
    union; its cost the primitive's LONGD (checked against formula [1] once per primitive
    by :func:`test_primitive_costs_are_exact_longd`). Every direct union to the goal the
    search tried, kept if it exists and is free; its cost the search's link cost.
    """
    if "oracle_graph" in search.__dict__:
        return search.oracle_graph
    ws, edges = search.ws, {}
    search.oracle_graph = edges
    for key in dict.fromkeys(expanded_states(search)):
        i, j, h = key
        out = edges.setdefault(key, [])
        for m, (di, dj, h1) in enumerate(search.step[h]):
            if ws.union_free(search.union(key, m)):
                out.append(((i + di, j + dj, h1), search.cost[h][m]))
    for key, P in search.tried:
        u = search.ex.union(Pose(*P), search.goal)
        if u is not None and ws.union_free(u):
            edges[key].append((GOAL, search.ex.link_cost(u)))
    return edges


def dijkstra(edges: dict, source) -> dict:
    """Least costs from ``source`` over ``edges`` (``{node: [(node, cost)]}``)."""
    dist, done, heap, n = {source: 0.0}, set(), [(0.0, 0, source)], 1
    while heap:
        d, _, k = heapq.heappop(heap)
        if k in done:
            continue
        done.add(k)
        for nk, c in edges.get(k, ()):
            if d + c < dist.get(nk, math.inf):
                dist[nk] = d + c
                heapq.heappush(heap, (d + c, n, nk))
                n += 1
    return dist


def reverse(edges: dict) -> dict:
    back: dict = {}
    for k, out in edges.items():
        for nk, c in out:
            back.setdefault(nk, []).append((k, c))
    return back


def optimum(search) -> float:
    return dijkstra(generated_graph(search), (0, 0, 0)).get(GOAL, math.inf)


def h_violations(search, weight: float = 1.0) -> list:
    """States whose ``h'`` (the search's, divided by ``weight``) exceeds their cost-to-go on
    the generated graph (a reverse Dijkstra from the goal)."""
    ctg = dijkstra(reverse(generated_graph(search)), GOAL)
    bad = []
    for key in dict.fromkeys(expanded_states(search)):
        c = ctg.get(key, math.inf)
        h = search.h(key[0] * search.r, key[1] * search.r, key[2]) / weight
        if h > c + 1e-9 * max(c, 1.0):
            bad.append((key, h, c))
    return bad


def dearer_reparents(search) -> list:
    """Writes of ``g`` by the search's expansion that did not lower a known ``g`` (a repair
    of a state whose edge failed may raise it, or forget it: not counted)."""
    seen, bad = {}, []
    for e in search.glog:
        if e[0] == "del":
            seen.pop(e[2])
        if e[0] != "set":
            continue
        _, caller, k, v = e
        if caller == "run" and k in seen and not v < seen[k]:
            bad.append((k, seen[k], v))
        seen[k] = v
    return bad


def run(name, weight, every=1, **kw):
    """:func:`recorded`, run as the planner runs it: ``(plan, search)``."""
    search = recorded(name, weight, every, **kw)
    plan, outcome, _ = plan_of(search)
    assert outcome == "found", outcome
    return plan, search


# floors solved in 0.1-0.4 s at weight 1 (guide and approach tree off)
W1 = ["natural-003", "natural-005", "natural-002"]
W2 = ["any-001", "any-004", "any-011"]


@pytest.mark.parametrize("name", W1)
def test_weight_one_is_optimal_on_the_graph_it_generated(name):
    plan, s = run(name, 1.0)
    expanded = expanded_states(s)
    assert plan.expanded == len(expanded) == len(set(expanded))  # no state expanded twice
    assert not dearer_reparents(s)
    best = optimum(s)
    assert plan.search_cost == pytest.approx(best, rel=1e-12, abs=0.0)
    assert not h_violations(s)


@pytest.mark.parametrize("name", W2)
def test_weight_two_is_within_its_bound_on_the_graph_it_generated(name):
    plan, s = run(name, 2.0)
    expanded = expanded_states(s)
    assert plan.expanded == len(expanded) == len(set(expanded))
    assert not dearer_reparents(s)
    best = optimum(s)
    assert best * (1 - 1e-12) <= plan.search_cost <= 2.0 * best
    assert not h_violations(s, weight=2.0)  # h' / weight is the admissible bound


def test_the_guided_search_expands_each_state_once_and_only_lowers_g():
    # the coarse guide re-ranks the open list (and lowers the weight): bookkeeping still holds
    plan, s = run("any-005", 2.0, guide=True, approaches=True)
    assert s.guide.field is not None, "the guide was not built: the test tests nothing"
    assert s.weight == SCHEDULE.guided_weight  # built at guide_after: the weight lowered
    expanded = expanded_states(s)
    assert plan.expanded == len(expanded) == len(set(expanded)) > SCHEDULE.guide_after
    assert not dearer_reparents(s)


def test_an_escalating_search_keeps_its_bookkeeping_and_multiplies_its_weight():
    # Schedule.escalate_every: the weight grows at each multiple without a plan once the guide
    # is built, and each run starts again at the weight it was given
    every, factor = 24, 1.5  # multiples before the guide (at guide_after) do nothing
    schedule = dataclasses.replace(SCHEDULE, escalate_every=every, escalate_factor=factor, deadline_every=1)
    s = astar_of(random_floor("any", 5), cls=Recorded, weight=2.0, analytic_every=1, schedule=schedule)
    seen = []
    s.progress = lambda n: seen.append((n, s.boost, s.goal_parent is None))
    plan, outcome, _ = plan_of(s)
    assert outcome == "found" and s.guide.field is not None
    searching = [(n, b) for n, b, none_yet in seen if none_yet]
    assert any(b > 1.0 for _, b in searching), "never escalated: the test tests nothing"
    for n, b in searching:  # reported before the expansion it counts: the multiples passed
        assert b == factor ** max(0, n // every - SCHEDULE.guide_after // every)
    assert [b for _, b, _ in seen] == sorted(b for _, b, _ in seen)
    boosted = s.h(1.0, 0.5, 3)
    boost, s.boost = s.boost, 1.0
    assert boosted == pytest.approx(boost * s.h(1.0, 0.5, 3), rel=1e-15)
    s.boost = boost
    expanded = expanded_states(s)
    assert plan.expanded == len(expanded) == len(set(expanded))
    assert not dearer_reparents(s)
    s.run(1, math.inf)
    assert s.boost == 1.0


def test_primitive_costs_are_exact_longd():
    L, steer = 1.0, 45 * DEG
    for r in (0.125, 0.0625):
        for prims in primitive_set(L, steer, r).by_heading:
            for p in prims:
                # the lattice laid out at (0.3, -0.2) heading 0, so its state (0, 0, h0) heads angles[h0]
                u = LatticeFrame((0.3, -0.2, 0.0), r, L).union((0, 0, p.h0), p)
                assert p.cost == pytest.approx(longd_exact(u.p0, u.p1, u.alpha, L), rel=1e-7)


# -- mutations: the oracles fail when the search is broken ---------------------------------
def merged(*searches) -> dict:
    """The union of the graphs the searches generated."""
    out: dict = {}
    for search in searches:
        for k, v in generated_graph(search).items():
            out.setdefault(k, []).extend(v)
    return out


class _InflatedH(Recorded):
    """The mutant: h' times 1.5."""

    def h(self, *a):
        return 1.5 * super().h(*a)


@pytest.mark.parametrize("name", ["natural-003", "natural-005"])
def test_an_inadmissible_h_is_caught(name):
    # h' times 1.5 (the Dubins bound inflated): h' exceeds the cost-to-go, and on the union of
    # the graphs generated with and without the mutation, weight 1 is optimal only unmutated
    plan, s = run(name, 1.0)
    mutant, ms = run(name, 1.0, cls=_InflatedH)
    assert h_violations(ms)
    best = dijkstra(merged(s, ms), (0, 0, 0))[GOAL]
    assert plan.search_cost == pytest.approx(best, rel=1e-12, abs=0.0)
    assert mutant.search_cost > best * (1 + 1e-9)


class _Forgetful(Recorded):
    """The mutant: the search's ``g.get`` sees no earlier path."""

    forget = True


def test_broken_duplicate_detection_is_caught():
    # the search sees no earlier path to a state: dearer paths re-parent states, and the plan
    # is dearer than its graph's optimum
    plan, s = run("natural-003", 1.0, cls=_Forgetful)
    assert dearer_reparents(s)
    assert plan.search_cost > optimum(s) * (1 + 1e-9)


# -- h': the Dubins bound ----------------------------------------------------------------------
def _ompl_dubins(R):
    return ompl_distance("dubins", R)


def _poses(seed, n):
    rng = np.random.default_rng(seed)
    X = rng.uniform(-4, 4, (n, 6))
    X[:, 2] = rng.uniform(-math.pi, math.pi, n)
    X[:, 5] = rng.uniform(-math.pi, math.pi, n)
    X[: n // 4, 3:5] = X[: n // 4, 0:2] + rng.uniform(-1, 1, (n // 4, 2))  # close pairs: CCC words
    return X


def _against_ompl(length, R=1.3, n=1500):
    ompl = _ompl_dubins(R)
    X = _poses(5, n)
    ours = np.array([length(*x, R) for x in X])
    theirs = np.array([ompl(x[:3], x[3:]) for x in X])
    return ours, theirs


def test_dubins_length_equals_ompl():
    ours, theirs = _against_ompl(dubins_length_scalar)
    assert np.allclose(ours, theirs, rtol=1e-9, atol=1e-9)
    X = _poses(5, 1500)
    assert np.allclose(dubins_length(*X.T, 1.3), theirs, rtol=1e-9, atol=1e-9)


def _skip_if_wrapped(src: str) -> None:
    """A hand-made mutant needs the function's own source: under mutmut (benchmarks/mutation.py
    mutating that module) it is a trampoline, and mutmut's own mutants stand in for this one."""
    if "_mutmut_" in src:
        pytest.skip("the source is a mutation tool's trampoline")


def _mutant(drop: str):
    """``dubins_length_scalar`` with one word left out (its block's test made False)."""
    src = textwrap.dedent(inspect.getsource(dubins_length_scalar))
    _skip_if_wrapped(src)
    lines = src.splitlines()
    k = next(i for i, line in enumerate(lines) if line.rstrip().endswith(f"# {drop}"))
    lines[k + 1] = lines[k + 1].replace(lines[k + 1].strip(), "if False:")  # the word's test
    ns = dict(vars(dubins))
    exec("\n".join(lines), ns)
    return ns["dubins_length_scalar"]


@pytest.mark.parametrize("word", ["LSL", "RSR", "LSR", "RSL", "RLR", "LRL"])
def test_a_missing_dubins_word_is_caught_by_ompl(word):
    ours, theirs = _against_ompl(_mutant(word), n=600)
    assert np.any(ours > theirs + 1e-6)


def test_an_inflated_dubins_length_is_caught_by_ompl():
    ours, theirs = _against_ompl(lambda *a: 1.5 * dubins_length_scalar(*a), n=100)
    assert np.any(ours > theirs + 1e-6)


def _drive(pose, pieces, R):
    """End pose of a forward path of pieces ``(length, curvature)``, ``|curvature| <= 1 / R``."""
    x, y, th = pose
    for s, k in pieces:
        k = k / R
        if abs(k) < 1e-12:
            x, y = x + s * math.cos(th), y + s * math.sin(th)
        else:
            x += (math.sin(th + k * s) - math.sin(th)) / k
            y -= (math.cos(th + k * s) - math.cos(th)) / k
            th += k * s
    return x, y, th


# curvatures strictly inside the limit: the end poses are generic (see the xfail below for
# the exact Dubins words with a part of length zero)
curvature = st.floats(-0.999, 0.999).filter(lambda k: abs(k) > 1e-3)
pieces = st.lists(st.tuples(st.floats(0.01, 3.0), curvature), min_size=1, max_size=6)


@settings(max_examples=300)
@given(pieces=pieces, theta=st.floats(-math.pi, math.pi), R=st.floats(0.5, 2.0))
def test_dubins_length_is_at_most_every_forward_path_of_bounded_curvature(pieces, theta, R):
    # brute force from the other side: any forward path of curvature <= 1 / R is at least
    # as long as the shortest one
    end = _drive((0.2, -0.1, theta), pieces, R)
    length = sum(s for s, _ in pieces)
    tol = 1e-7 * (1 + length)  # near-straight words lose digits in sqrt(p2) (2e-9 seen)
    assert dubins_length_scalar(0.2, -0.1, theta, *end, R) <= length + tol
    assert float(dubins_length(0.2, -0.1, theta, *end, R)) <= length + tol


@pytest.mark.parametrize("turn", [-1.0, 0.0, 1.0])
def test_dubins_length_of_one_exact_arc_or_segment_is_its_length(turn):
    bad = []
    for theta in np.linspace(-3.0, 3.0, 13):
        for s in np.linspace(0.1, 5.0, 13):
            end = _drive((0.2, -0.1, theta), [(s, turn)], 1.0)
            if dubins_length_scalar(0.2, -0.1, theta, *end, 1.0) > s + 1e-9:
                bad.append((theta, s))
            if float(dubins_length(0.2, -0.1, theta, *end, 1.0)) > s + 1e-9:
                bad.append((theta, s, "vectorised"))
    assert not bad, f"{len(bad)} of 169 arcs or segments"
    assert dubins_length_scalar(0.2, -0.1, 0.5537453572206095, 0.2, -0.1, 0.5537453572206095, 1.0) == 0.0


@settings(max_examples=200)
@given(
    d=st.floats(0.2, 4.0),
    phi0=st.floats(-1.2, 1.2),
    phi1=st.floats(-1.2, 1.2),
    t=st.floats(0.05, 0.95),
    psi=st.floats(-math.pi, math.pi),
)
def test_longd_of_a_union_within_the_steering_limit_is_at_least_its_dubins_length(d, phi0, phi1, t, psi):
    from segplan.model.union import Union

    L, R = 1.0, 1.0  # 45 deg
    lo = -0.5 * math.pi - min(phi0, phi1, 0.0)
    hi = 0.5 * math.pi - max(phi0, phi1, 0.0)
    if not hi - lo > 0.02:
        return
    alpha = lo + 0.01 + t * (hi - lo - 0.02)
    p0 = Pose(0.5, 0.25, psi + phi0)
    p1 = Pose(0.5 + d * math.cos(psi), 0.25 + d * math.sin(psi), psi + phi1)
    u = Union(p0, p1, alpha, L)
    if np.abs(u.curvature(u.xs(2001))).max() > 1.0 / R:
        return  # not within the steering limit: no claim
    assert longd_exact(p0, p1, alpha, L) >= dubins_length_scalar(*p0, *p1, R) - 1e-9


# -- every returned plan ---------------------------------------------------------------------
def swept_quads(u, n=400) -> np.ndarray:
    """Quadrilaterals between consecutive positions of the segment rear -> front, ``(n-1, 4, 2)``."""
    A, B = u.rear(n), u.front(n)
    return np.stack((A[:-1], B[:-1], B[1:], A[1:]), axis=1)


def dense_collides(plan, sc) -> list:
    """Indices of the plan's unions whose swept segment meets an enlarged obstacle or leaves
    the free bounds (shapely, :func:`swept_quads`)."""
    obstacles = shapely.union_all([shapely.Polygon(p) for p in sc.enlarged]) if len(sc.enlarged) else None
    room = shapely.box(*sc.free_bounds) if sc.free_bounds is not None else None
    bad = []
    for k, u in enumerate(plan.unions):
        quads = shapely.polygons(swept_quads(u))
        lines = shapely.linestrings(np.concatenate([u.rear(400), u.front(400)[::-1]]))
        hit = obstacles is not None and (
            shapely.intersects(obstacles, quads).any() or obstacles.intersects(lines)
        )
        ends = np.concatenate([u.rear(400), u.front(400)])  # the room is convex
        out = room is not None and not shapely.contains_xy(room, ends[:, 0], ends[:, 1]).all()
        if hit or out:
            bad.append(k)
    return bad


# 20 floors the lattice solves (natural-007 it does not, within its limits)
PLANS = [f"natural-{i:03d}" for i in range(15) if i != 7] + [f"any-{i:03d}" for i in (1, 2, 4, 9, 10, 11)]


@pytest.mark.parametrize("name", PLANS)
def test_every_plan_costs_its_exact_longd_keeps_the_limit_and_is_free(name):
    kind, index = name.rsplit("-", 1)
    sc = random_floor(kind, int(index))
    try:
        plan = lattice.plan_lattice(sc, time_limit=5.0)
    except lattice.NoPathError:
        pytest.skip("no plan on this floor")
    L, kmax = sc.robot.L, sc.robot.max_curvature
    assert plan.nodes[0] == sc.start and plan.nodes[-1] == sc.goal
    exact = sum(longd_exact(u.p0, u.p1, u.alpha, L) for u in plan.unions)
    assert plan.cost == pytest.approx(exact, rel=1e-7)
    for a, b, u in zip(plan.nodes[:-1], plan.nodes[1:], plan.unions, strict=True):
        assert (u.p0, u.p1) == (a, b)
        assert np.abs(u.curvature(u.xs(4001))).max() <= kmax * (1 + 1e-6)
    assert not dense_collides(plan, sc)


def test_the_dense_oracle_sees_a_plan_through_an_obstacle():
    # the shapely oracle is not vacuous: the same plan on the floor with one more obstacle
    # across its middle union collides
    from segplan import make_scenario

    sc = random_floor("natural", 3)
    plan = lattice.plan_lattice(sc)
    u = plan.unions[len(plan.unions) // 2]
    mid = u.rear(3)[1]
    block = mid + 0.05 * np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)])
    sc2 = make_scenario(sc.robot, sc.start, sc.goal, [*sc.obstacles, block], sc.bounds)
    assert dense_collides(plan, sc2) == [len(plan.unions) // 2]
    assert np.isclose(union_longd(u), longd_exact(u.p0, u.p1, u.alpha, sc.robot.L), rtol=1e-7)


# -- the deferred repair in a real search ------------------------------------------------------
def _cheapest_passing_edge(s, key, closed, failed):
    """The cheapest edge into ``key`` from an expanded state, not refused before (``failed``,
    ``banned``), that the certified test passes: ``(g, (prev, m))`` or None. Every primitive of
    every heading is tried (not the search's table of edges into a heading)."""
    best = None
    for h0, steps in enumerate(s.step):
        for m, (di, dj, h1) in enumerate(steps):
            prev = (key[0] - di, key[1] - dj, h0)
            if h1 != key[2] or prev not in closed or (prev, m) in failed or (prev, m) in s.banned:
                continue
            ng = dict.__getitem__(s.g, prev) + s.cost[h0][m]
            if (best is None or ng < best[0]) and s.ws.union_free(s.union(prev, m)):
                best = (ng, (prev, m))
    return best


class _Judged(Recorded):
    """Every repair judged by :func:`_cheapest_passing_edge`: ``judged`` holds ``(expected, got)``."""

    def __init__(self, *a, **kw):
        super().__init__(*a, **kw)
        self.judged = []

    def repair(self, key, closed, h, counter):
        expected = _cheapest_passing_edge(self, key, closed, set(self.edges.failed))
        out = super().repair(key, closed, h, counter)
        got = (dict.__getitem__(self.g, key), self.parent[key]) if key in self.g else None
        self.judged.append((expected, got))
        return out


def _same(expected, got) -> bool:
    """The repair gave the expected ``g`` (ties between edges of one cost may go either way),
    or forgot the state exactly when no edge passes."""
    if expected is None or got is None:
        return expected is got
    return got[0] == pytest.approx(expected[0], rel=1e-12)


@pytest.mark.parametrize("name", ["natural-003", "natural-005"])
def test_every_repair_takes_the_cheapest_passing_edge(name):
    _, s = run(name, 1.0, cls=_Judged)
    assert len(s.judged) >= 10, "few repairs: the test tests little"
    assert all(_same(e, g) for e, g in s.judged)


def _first_passing():
    """The mutant: :class:`LazyEdges` whose repair lacks its sort (its source, one call removed):
    the first passing edge, not the cheapest."""
    src = textwrap.dedent(inspect.getsource(LazyEdges.repair))
    _skip_if_wrapped(src)
    sort = "sorted(o for o in options if o[2] not in self.failed)"
    assert sort in src
    ns = dict(vars(edges_module))
    exec(src.replace(sort, "[o for o in options if o[2] not in self.failed]"), ns)
    return type("FirstPassing", (LazyEdges,), {"repair": ns["repair"]})


class _JudgedFirstPassing(_Judged):
    def __init__(self, *a, **kw):
        super().__init__(*a, edges=_first_passing()(self.screen_edge, self.check_edge), **kw)


def test_a_repair_taking_the_first_passing_edge_is_caught():
    _, s = run("any-009", 1.0, cls=_JudgedFirstPassing)  # 4 of its 86 repairs then take a dearer edge
    assert not all(_same(e, g) for e, g in s.judged)
