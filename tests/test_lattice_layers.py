"""The lattice planner's collision defence, one layer at a time (issue 24).

A union of a plan is made to collide by putting a small obstacle on it (the same floor with
one more square across the union's middle). Then each layer, alone, must refuse it:

* the clearance grid's screen (:class:`segplan.planning.lattice.clearance.ClearanceGrid`) does not clear it
  (neither the screen of the primitive tables nor
  :meth:`~segplan.planning.lattice.clearance.ClearanceGrid.screen`);
* the deferred check of a lattice edge (:meth:`segplan.planning.lattice.astar.LatticeAStar.check_edge`,
  the check of its :class:`segplan.planning.lattice.edges.LazyEdges`) fails it;
* the final certified check (:meth:`segplan.planning.validity.Workspace.union_free`) fails it;

and, end to end: a search composed with lazy edges whose check passes every edge plans
through the obstacle and the final certified check catches that plan (the search runs again
without the edge); without the final check as well, the plan through the obstacle is returned
and the dense shapely oracle of ``test_lattice_oracles`` sees it.
"""

import numpy as np
import pytest
from test_lattice_oracles import dense_collides
from test_lattice_parts import astar_of, plan_of

from segplan import make_scenario
from segplan.planning import validity
from segplan.planning.lattice.astar import LatticeAStar
from segplan.planning.lattice.clearance import union_points
from segplan.planning.lattice.edges import LazyEdges
from segplan.studies.floors import random_floor

NAME = ("natural", 3)


class _Unchecked(LatticeAStar):
    """A search whose lazy edges pass every edge they are asked to check."""

    def __init__(self, *a, **kw):
        super().__init__(*a, edges=LazyEdges(self.screen_edge, lambda edge: True), **kw)


@pytest.fixture(scope="module")
def blocked():
    """``(floor, edge, union, floor with an obstacle on the union, search on that floor)``:
    the middle lattice edge of the plan of ``NAME``, and a search of the blocked floor (same
    start, so the same lattice; not run)."""
    sc = random_floor(*NAME)
    s = astar_of(sc)
    plan, outcome, made = plan_of(s)
    assert outcome == "found" and len(made) == 1
    edges = made[-1]
    assert len(edges) >= 3
    key, m = edges[len(edges) // 2]
    u = s.union(key, m)
    mid = u.rear(3)[1]
    square = mid + 0.05 * np.array([(-1, -1), (1, -1), (1, 1), (-1, 1)])
    sc2 = make_scenario(sc.robot, sc.start, sc.goal, [*sc.obstacles, square], sc.bounds)
    s2 = astar_of(sc2)
    assert s2.r == s.r and s2.union(key, m).p0 == u.p0  # the same lattice
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
    assert not s2.screen_edge((key, m))[0]  # the lazy edges' screen: not certainly free
    pts, dl = union_points(u)
    free, _ = s2.grid.screen(s2.grid.to_lattice(pts)[None], dl)
    assert not free[0]  # the union's screen: not certainly free


def test_the_deferred_check_alone_fails_it(blocked):
    _, (key, m), _, _, s2 = blocked
    assert not s2.check_edge((key, m))
    assert not s2.edges.check(key, (key, m)) and (key, m) in s2.edges.failed


def test_the_final_certified_check_alone_fails_it(blocked):
    _, _, u, sc2, _ = blocked
    ws = validity.Workspace(sc2.enlarged, sc2.robot.L, sc2.free_bounds, sc2.robot.max_curvature)
    assert not ws.union_free(u)


def test_without_the_deferred_check_the_final_check_catches_the_plan(blocked):
    _, _, _, sc2, _ = blocked
    s = astar_of(sc2, cls=_Unchecked)
    plan, outcome, made = plan_of(s)
    assert outcome == "found"
    assert len(made) >= 2  # a plan was found, refused and found again
    assert s.banned  # the edges the final check refused
    assert not dense_collides(plan, sc2)


def test_without_the_deferred_and_final_checks_the_plan_goes_through(blocked):
    # the end-to-end test above is not vacuous: without the final check too, the plan found
    # crosses the obstacle
    _, _, _, sc2, _ = blocked
    plan, outcome, _ = plan_of(astar_of(sc2, cls=_Unchecked), final_check=False)
    assert outcome == "found"
    assert dense_collides(plan, sc2)
