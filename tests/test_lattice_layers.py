"""The lattice planner's collision defence, one layer at a time (issue 24).

A union of a plan is made to collide by putting a small obstacle on it (the same floor with
one more square across the union's middle). Then each layer, alone, must refuse it:

* the clearance grid's screen (:class:`segplan.planning.lattice.clearance.ClearanceGrid`) does not clear it
  (neither the screen of the primitive tables nor
  :meth:`~segplan.planning.lattice.clearance.ClearanceGrid.screen`);
* the deferred check of a lattice edge (``edge_free``, :mod:`segplan.planning.lattice.edges`) fails it;
* the final certified check (:meth:`segplan.planning.validity.Workspace.union_free`) fails it;

and, end to end: with the deferred check disabled (every edge it is asked about passes), the
search plans through the obstacle and the final certified check catches that plan (the search
runs again without the edge); with the final check disabled as well, the plan through the
obstacle is returned and the dense shapely oracle of ``test_lattice_oracles`` sees it.
"""

import numpy as np
import pytest
from test_lattice_oracles import dense_collides

from segplan import NoPathError, make_scenario
from segplan.planning import validity
from segplan.planning.lattice import search as lattice
from segplan.planning.lattice.clearance import union_points
from segplan.studies.floors import random_floor

NAME = ("natural", 3)


def _spy(monkeypatch):
    """The searches made (``__init__``) and the lattice edges of every plan made."""
    seen = {"searches": [], "edges": []}
    init, make_plan = lattice._LatticeSearch.__init__, lattice._LatticeSearch.make_plan

    def spy_init(self, *a):
        init(self, *a)
        seen["searches"].append(self)

    def spy_make_plan(self, edges, *a):
        seen["edges"].append(list(edges))
        return make_plan(self, edges, *a)

    monkeypatch.setattr(lattice._LatticeSearch, "__init__", spy_init)
    monkeypatch.setattr(lattice._LatticeSearch, "make_plan", spy_make_plan)
    return seen


@pytest.fixture
def blocked(monkeypatch):
    """``(floor, edge, union, floor with an obstacle on the union, search on that floor)``:
    the middle lattice edge of the plan of ``NAME``, and a search object of the blocked
    floor (same start, so the same lattice; its run stopped at once)."""
    seen = _spy(monkeypatch)
    sc = random_floor(*NAME)
    lattice.plan_lattice(sc, escapes=False, retry=False)
    edges = seen["edges"][-1]
    assert len(edges) >= 3
    s = seen["searches"][-1]
    key, m = edges[len(edges) // 2]
    u = s.union(key, m)
    mid = u.rear(3)[1]
    square = mid + 0.05 * np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)])
    sc2 = make_scenario(sc.robot, sc.start, sc.goal, [*sc.obstacles, square], sc.bounds)
    try:
        lattice.plan_lattice(sc2, escapes=False, retry=False, max_expansions=1)
    except NoPathError:
        pass
    s2 = seen["searches"][-1]
    assert s2.r == s.r and s2.union(key, m).p0 == u.p0  # the same lattice
    seen["edges"].clear()
    return sc, (key, m), u, sc2, s2


class _Plan:
    def __init__(self, unions):
        self.unions = unions


def test_the_union_collides_by_the_dense_oracle(blocked):
    sc, _, u, sc2, _ = blocked
    assert not dense_collides(_Plan([u]), sc)
    assert dense_collides(_Plan([u]), sc2) == [0]


def test_the_grid_screen_alone_does_not_clear_it(blocked):
    _, (key, m), u, _, s2 = blocked
    i, j, h = key
    b = s2.grid.base(i * s2.q, j * s2.q)
    least = s2.grid.lower_blocked_flat[s2.offsets[h][m] + b].min()
    assert not least > s2.delta[h][m]  # the primitive tables' screen: not certainly free
    pts, dl = union_points(u)
    free, _ = s2.grid.screen(s2.grid.to_lattice(pts)[None], dl)
    assert not free[0]  # the union's screen: not certainly free


def test_the_deferred_check_alone_fails_it(blocked):
    _, (key, m), _, _, s2 = blocked
    assert not s2.edge_free(key, m)


def test_the_final_certified_check_alone_fails_it(blocked):
    _, _, u, sc2, _ = blocked
    ws = validity.Workspace(sc2.enlarged, sc2.robot.L, sc2.free_bounds, sc2.robot.max_curvature)
    assert not ws.union_free(u)


def test_without_the_deferred_check_the_final_check_catches_the_plan(blocked, monkeypatch):
    _, _, _, sc2, _ = blocked
    monkeypatch.setattr(lattice._LatticeSearch, "edge_free", lambda self, key, m: True)
    seen = _spy(monkeypatch)
    plan = lattice.plan_lattice(sc2, escapes=False, retry=False)
    assert len(seen["edges"]) >= 2  # a plan was found, refused and found again
    assert seen["searches"][-1].banned  # the edges the final check refused
    assert not dense_collides(plan, sc2)


def test_without_the_deferred_and_final_checks_the_plan_goes_through(blocked, monkeypatch):
    # the end-to-end test above is not vacuous: without the final check too, the plan found
    # crosses the obstacle
    _, _, _, sc2, _ = blocked
    monkeypatch.setattr(lattice._LatticeSearch, "edge_free", lambda self, key, m: True)
    monkeypatch.setattr(validity.Workspace, "union_free", lambda self, u: True)
    plan = lattice.plan_lattice(sc2, escapes=False, retry=False)
    assert dense_collides(plan, sc2)
