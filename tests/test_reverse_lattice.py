"""Issue 26, reverse motion, step 3: reverse links on the lattice.

Oracles: the bicycle model integrated backwards (RK4, fine steps) for the formulation of a
reverse link (:mod:`segplan.planning.lattice.reverse`); dense sampling for the swept points
of the reverse primitives (the grid's screen relies on them) and for plans (shapely, both
directions: the swept segment of a union does not depend on the direction); the cost along
the found chain for the heuristic.
"""

import dataclasses
import math

import numpy as np
import pytest
from test_lattice_oracles import dense_collides
from test_lattice_parts import astar_of, plan_of

import segplan
from segplan import NoPathError, Robot, load_scenario
from segplan.floor.scenario import make_scenario
from segplan.model.pose import Pose
from segplan.model.union import Union
from segplan.planning.lattice.frame import NH
from segplan.planning.lattice.search import lattice_search
from segplan.planning.links import LinkModel
from segplan.planning.plan import union_longd
from segplan.planning.validity import Workspace

DEG = math.pi / 180


def _union(p, q, L=1.0):
    ws = Workspace((), L, None, math.inf)
    return LinkModel(ws).union(Pose(*p), Pose(*q))


def _drive_backwards(u: Union, n: int = 4000):
    """Rear points and headings of the bicycle model driven backwards (speed -1 along the rear
    path) from ``u.p1`` with, at each arc length, the steering angle of ``u`` there: RK4 in
    the arc length, the steering interpolated from a dense table of the union."""
    x = np.linspace(0.0, u.x_end, 20001)
    A = u.to_world(x, u.f(x))
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(A, axis=0).T))])
    kappa = u.curvature(x)  # signed curvature of the rear path, d theta / d s going forwards
    S = s[-1]

    def k_at(sigma):  # sigma: distance driven backwards from p1
        return np.interp(S - sigma, s, kappa)

    def rhs(sigma, z):  # d/d sigma of (x, y, theta), driving backwards: ds = -d sigma
        return np.array([-math.cos(z[2]), -math.sin(z[2]), -k_at(sigma)])

    z = np.array([u.p1.x, u.p1.y, u.p1.theta])
    h = S / n
    out = [z.copy()]
    for i in range(n):
        sg = i * h
        k1 = rhs(sg, z)
        k2 = rhs(sg + h / 2, z + h / 2 * k1)
        k3 = rhs(sg + h / 2, z + h / 2 * k2)
        k4 = rhs(sg + h, z + h * k3)
        z = z + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        out.append(z.copy())
    return np.array(out)


def _distance_to(points, curve):
    """Largest distance of ``points`` to the polyline ``curve`` (dense: vertices suffice)."""
    d = np.hypot(points[:, None, 0] - curve[None, :, 0], points[:, None, 1] - curve[None, :, 1])
    return d.min(axis=1).max()


@pytest.mark.parametrize(
    "p, q",
    [((0, 0, 0), (-3, -1, -20 * DEG)), ((1, 2, 90 * DEG), (1.5, -1, 60 * DEG)), ((0, 0, 0), (-2, 0.5, 0))],
)
def test_reverse_link_is_the_forward_union_from_q_to_p_driven_backwards(p, q):
    u = _union(q, p)  # the forward union from q to p: the reverse link from p to q
    path = _drive_backwards(u)
    end = path[-1]
    assert math.hypot(end[0] - q[0], end[1] - q[1]) < 1e-6 and abs(end[2] - q[2]) < 1e-6
    rear, front = u.rear(2001), u.front(2001)
    assert _distance_to(path[::20, :2], rear) < 2e-3  # the same rear curve
    B = path[:, :2] + u.L * np.stack((np.cos(path[:, 2]), np.sin(path[:, 2])), axis=1)
    assert _distance_to(B[::20], front) < 2e-3  # the same front-wheel curve
    assert np.hypot(*np.diff(B, axis=0).T).sum() == pytest.approx(union_longd(u), rel=1e-5)  # LONGD [1]


@pytest.mark.parametrize("p, q", [((0, 0, 0), (-3, -1, -20 * DEG)), ((1, 2, 90 * DEG), (1.5, -1, 60 * DEG))])
def test_turned_headings_union_is_not_the_reverse_motion(p, q):
    u = _union(q, p)
    turned = _union((p[0], p[1], p[2] + math.pi), (q[0], q[1], q[2] + math.pi))
    assert _distance_to(turned.rear(401), u.rear(4001)) < 1e-3  # the same rear path ...
    assert _distance_to(turned.front(401), u.front(4001)) > 0.3 * u.L  # ... not the front wheel's
    # the same length though: A -+ L t both move at sqrt(1 + (L kappa)^2) times A's speed
    assert union_longd(turned) == pytest.approx(union_longd(u), rel=1e-12)
    assert np.hypot(*np.diff(turned.front(20001), axis=0).T).sum() == pytest.approx(union_longd(u), rel=1e-6)


# -- the lattice's reverse edges --------------------------------------------------------------
def _open_floor(reverse=True, steer=45):
    robot = Robot(1.0, 0.0, math.radians(steer), reverse=reverse)
    return make_scenario(robot, (5, 5, 0), (9, 8, 1.0), [], (0, 0, 14, 12))


def test_reverse_edges_join_their_states_and_their_points_cover_the_swept_segment():
    search = astar_of(_open_floor())
    r = search.r
    for s in (0, 3, NH + 5, NH + 10):
        key = (7, -3, s)
        P = search.frame.pose(key)
        fp, fd = search.fine[s]
        n_rev = 0
        for m, (p, back) in enumerate(search.edge_prims[s]):
            di, dj, s1 = search.step[s][m]
            assert s1 // NH == int(back)  # the end state knows the direction it was reached in
            end = search.frame.pose((7 + di, -3 + dj, s1))
            u = search.union(key, m)
            ends = (u.p1, u.p0) if back else (u.p0, u.p1)
            assert np.allclose(ends[0], P) and np.allclose(ends[1], end)
            assert search.length[s][m] == pytest.approx(union_longd(u), rel=1e-7)
            cusp = (s >= NH) != back
            expect = (search.reverse_factor if back else 1.0) * p.cost + cusp * search.cusp_penalty
            assert search.cost[s][m] == pytest.approx(expect, rel=1e-12)
            # every point of the swept segment lies within the covering radius of the points
            world = (fp[m] + (7 * r, -3 * r)) @ search.grid.rot.T + (search.start.x, search.start.y)
            seg = np.concatenate([u.rear(300) * (1 - t) + u.front(300) * t for t in (0, 0.3, 0.7, 1)])
            d = np.hypot(seg[:, None, 0] - world[None, :, 0], seg[:, None, 1] - world[None, :, 1]).min(axis=1)
            assert d.max() <= fd[m] + 1e-9
            n_rev += back
        assert n_rev > 0


def test_forward_robot_has_no_reverse_edge():
    search = astar_of(_open_floor(reverse=False))
    assert len(search.step) == NH and not any(b for edges in search.edge_prims for _, b in edges)


@pytest.mark.parametrize("rf, cp", [(1.0, 0.0), (1.25, 2.0), (0.8, 0.5), (2.0, 4.0)])
def test_heuristic_is_a_lower_bound_along_the_found_chain(rf, cp):
    sc = load_scenario("dead_end_bay")
    search = astar_of(sc, weight=1.0, reverse_factor=rf, cusp_penalty=cp * sc.robot.L)
    plan, outcome, _ = plan_of(search)
    assert outcome == "found"
    chain = search.chain(search.goal_parent[0])
    keys = [k for k, _ in chain] + [search.goal_parent[0]]
    for k in keys:  # h' of each state of the chain at most the chain's cost from it
        assert search.h_state(k, {}) <= search.goal_g - search.g[k] + 1e-9


def test_reverse_options_are_checked():
    sc = load_scenario("dead_end_bay")
    for bad in (0, -1.0, math.inf, True):
        with pytest.raises(ValueError, match="reverse_factor"):
            lattice_search(sc, reverse_factor=bad)
    with pytest.raises(ValueError, match="cusp_penalty"):
        lattice_search(sc, cusp_penalty=-0.1)
    with pytest.raises(ValueError, match="reverse_factor"):
        segplan.planning.options.LatticeOptions(reverse_factor=0.0)


# -- the dead-end bay ---------------------------------------------------------------------------
def _valid(plan, sc):
    """Free by the dense oracle (each union's swept segment, whatever its direction), within the
    steering limit, joining the start to the goal."""
    assert not dense_collides(plan, sc)
    for u in plan.unions:
        assert np.abs(u.curvature(u.xs(4001))).max() <= sc.robot.max_curvature * (1 + 1e-6)
    assert plan.nodes[0] == sc.start and plan.nodes[-1] == sc.goal
    for i, (u, d) in enumerate(zip(plan.unions, plan.link_directions, strict=True)):
        assert ((u.p0, u.p1) if d == 1 else (u.p1, u.p0)) == (plan.nodes[i], plan.nodes[i + 1])


def test_dead_end_bay_needs_reverse_and_backs_out_with_one_cusp():
    sc = load_scenario("dead_end_bay")
    assert sc.robot.reverse
    forward = dataclasses.replace(sc, robot=dataclasses.replace(sc.robot, reverse=False))
    with pytest.raises(NoPathError, match="dead end"):
        segplan.plan_scenario(forward)
    plan = segplan.plan_scenario(sc)
    _valid(plan, sc)
    assert len(plan.cusps) == 1 and plan.link_directions[0] == -1 and plan.link_directions[-1] == 1
    assert plan.cost == pytest.approx(sum(union_longd(u) for u in plan.unions), rel=1e-7)
