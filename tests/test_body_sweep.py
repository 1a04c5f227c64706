"""The rectangular body swept exactly (issue 26; :mod:`segplan.floor.body`) against dense oracles.

The oracle: the rectangle ``[-rear, L + front] x [-w, w]`` of the robot's frame placed at
2001 poses along a union (:func:`test_footprint_collision.bodies`), each asked to shapely
against the *raw* polygon. It can miss a contact between samples, never invent one: the
exact test must find every collision it finds (no miss), and every collision it reports
beyond it must be a genuine near-touch (shapely's distance, refined around the closest
sample, within ``NEAR`` of the polygon). Polygons graze the corners' paths and the sides on
purpose (``graze_corner``, ``vertex_side``), at gaps from ``-1e-3 L`` to ``+1e-3 L``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from test_collision import N_DENSE, hull, ngon, random_union, tangent_box
from test_footprint_collision import _planner_says, bodies, chord_unions, random_overhangs

import segplan
from segplan import Union
from segplan.floor import body as bd
from segplan.floor import geometry as geo
from segplan.floor import sweep as swp

#: A reported collision the dense oracle does not see must come this close (m): the
#: touching tolerance is ~1e-9 of a scene of tens of metres, the refined sampling's own
#: error below 1e-7 m on these unions.
NEAR = 1e-6
KINDS = ("near", "graze_corner", "vertex_side", "thin", "hull", "cap")
GAPS = (0.0, 1e-9, 1e-6, 1e-3, -1e-9, -1e-6, -1e-3)


def corner_paths(robot, u: Union, x) -> np.ndarray:
    """World corners ``(n, 4, 2)`` of the rectangle at frame abscissae ``x``."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    A = u.to_world(x, u.f(x))
    h = u.heading(x)
    c, s = np.cos(h)[:, None], np.sin(h)[:, None]
    fp = robot.footprint()
    return np.stack((A[:, :1] + c * fp[:, 0] - s * fp[:, 1], A[:, 1:] + s * fp[:, 0] + c * fp[:, 1]), axis=-1)


def random_case(rng, kind: str):
    """A rectangle robot, a union and a raw convex polygon near its body."""
    u = random_union(rng)
    L = u.L
    rear, front = random_overhangs(rng, L)
    w = L * rng.uniform(0.05, 0.5)
    robot = segplan.Robot(L, w, front_overhang=front, rear_overhang=rear, rectangle=True)
    x = rng.uniform(0, u.x_end)
    C = corner_paths(robot, u, [max(x - 1e-6, 0.0), x, min(x + 1e-6, u.x_end)])
    k = int(rng.integers(4))
    gap = float(rng.choice(GAPS)) * L
    if kind == "near":
        c = C[1].mean(axis=0) + rng.normal(size=2) * (w + 0.8 * L)
        return robot, u, ngon(c, L * rng.uniform(0.03, 0.6), int(rng.integers(3, 8)), rng.uniform(0, 7))
    if kind == "hull":
        c = C[1, k] + rng.normal(size=2) * 0.3 * L
        return robot, u, hull(c + rng.normal(size=(int(rng.integers(3, 9)), 2)) * L * rng.uniform(0.05, 0.8))
    if kind == "thin":
        ln, t = L * rng.uniform(0.5, 6), rng.uniform(0, math.pi)
        d = np.array([math.cos(t), math.sin(t)])
        n = np.array([-d[1], d[0]])
        c = C[1, k] + rng.normal(size=2) * 0.4 * L
        th = ln / rng.uniform(20, 200)
        return robot, u, np.array([c - d * ln / 2 - n * th / 2, c + d * ln / 2 - n * th / 2,
                                   c + d * ln / 2 + n * th / 2, c - d * ln / 2 + n * th / 2])  # fmt: skip
    if kind == "graze_corner":  # an edge tangent to corner k's path, the box on either side
        P = C[:, k]
        tang = (P[2] - P[0]) / np.hypot(*(P[2] - P[0]))
        nrm = np.array([-tang[1], tang[0]]) * rng.choice([-1, 1])
        ln = L * rng.uniform(0.3, 3)
        return (
            robot,
            u,
            tangent_box(P[1], tang, nrm, gap, ln, L * rng.uniform(0.1, 2), rng.uniform(-0.5, 0.5) * ln),
        )
    if kind == "cap":  # a small polygon in a round cap of the round body, beyond an end side,
        # at the last pose ahead of the front side, or at the first behind the rear side:
        # where no other pose of the union reaches
        t, sign, x = (robot.L + front, 1.0, u.x_end) if rng.random() < 0.5 else (-rear, -1.0, 0.0)
        phi = rng.uniform(-1.3, 1.3)
        h = float(u.heading(x))
        rot = np.array([[math.cos(h), -math.sin(h)], [math.sin(h), math.cos(h)]])
        local = np.array([t + sign * 0.8 * w * math.cos(phi), 0.8 * w * math.sin(phi)])
        c = u.to_world(np.array([x]), u.f(np.array([x])))[0] + rot @ local
        return robot, u, ngon(c, 0.1 * w, int(rng.integers(3, 7)), rng.uniform(0, 7))
    # vertex_side: a triangle's apex at distance gap outside the middle of side k at x
    a, b = C[1, k], C[1, (k + 1) % 4]
    side = (b - a) / np.hypot(*(b - a))
    out = np.array([side[1], -side[0]])  # outward normal of a counter-clockwise outline
    apex = a + rng.uniform(0.1, 0.9) * (b - a) + gap * out
    spread, depth = L * rng.uniform(0.05, 1.0), L * rng.uniform(0.1, 1.0)
    return robot, u, np.array([apex, apex + depth * out + spread * side, apex + depth * out - spread * side])


def refined_distance(robot, u: Union, poly) -> float:
    """Shapely's distance from the body to ``poly``, refined around the closest dense sample."""
    P = shapely.Polygon(poly)
    xs = u.xs(N_DENSE)
    d = shapely.distance(bodies(robot, u), P)
    i = int(np.argmin(d))
    lo, hi = xs[max(i - 1, 0)], xs[min(i + 1, len(xs) - 1)]
    fine = np.linspace(lo, hi, 4001)
    C = corner_paths(robot, u, fine)
    return float(min(d.min(), shapely.distance(shapely.polygons(C), P).min()))


@pytest.fixture(scope="module")
def cases():
    rng = np.random.default_rng(20261203)
    out = []
    while len(out) < 100 * len(KINDS):
        kind = KINDS[len(out) % len(KINDS)]
        robot, u, poly = random_case(rng, kind)
        try:
            P = geo.ConvexPolygon(poly)
        except ValueError:
            continue
        out.append((kind, robot, u, poly, P))
    return out


def test_rectangle_sweep_exact(cases):
    """No miss; every collision beyond the oracle's a near-touch; free where the round body
    was pessimistic (the caps)."""
    misses, alarms, counts = [], [], {k: [0, 0, 0] for k in KINDS}
    for kind, robot, u, poly, P in cases:
        sw = swp.Sweep(u, robot.rear_overhang, robot.front_overhang)
        ours = bd.rectangle_collides(sw, P, robot.half_width)
        oracle = bool(shapely.intersects(bodies(robot, u), shapely.Polygon(poly)).any())
        c = counts[kind]
        c[0] += 1
        c[1] += oracle
        c[2] += _planner_says(robot, u, poly) and not ours  # the caps' pessimism, removed
        if oracle and not ours:
            misses.append((kind, u, poly))
        elif ours and not oracle:
            d = refined_distance(robot, u, poly)
            alarms.append(d)
            if d > NEAR:
                misses.append((kind, "false alarm", d, u, poly))
    print(
        "\nkind: pairs, collisions, refused by the round body but free",
        counts,
        f"near-touch alarms {len(alarms)}",
    )
    assert not misses, misses[:3]
    for kind in KINDS[:-1]:
        assert counts[kind][1] > 10, kind  # the cases do collide (the caps', by design, do not)
    assert counts["cap"][2] > 10  # the round caps' refusals are gone


@settings(max_examples=150, deadline=None)
@given(
    u=chord_unions(),
    w=st.floats(0.01, 0.6),
    rear=st.floats(0.0, 1.0),
    front=st.floats(0.0, 1.0),
    x_frac=st.floats(0.0, 1.0),
    corner=st.integers(0, 3),
    offset=st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0)),
    size=st.floats(0.02, 1.0),
    k=st.integers(3, 7),
    phase=st.floats(0.0, 6.3),
)
def test_rectangle_sweep_never_misses_hypothesis(u, w, rear, front, x_frac, corner, offset, size, k, phase):
    L = u.L
    robot = segplan.Robot(L, w * L, front_overhang=front * L, rear_overhang=rear * L, rectangle=True)
    C = corner_paths(robot, u, [x_frac * u.x_end])[0]
    poly = ngon(C[corner] + 0.5 * L * np.asarray(offset), size * L, k, phase)
    sw = swp.Sweep(u, robot.rear_overhang, robot.front_overhang)
    ours = bd.rectangle_collides(sw, geo.ConvexPolygon(poly), robot.half_width)
    if shapely.intersects(bodies(robot, u), shapely.Polygon(poly)).any():
        assert ours
    elif ours:
        assert refined_distance(robot, u, poly) <= NEAR


def test_rectangle_in_bounds_against_corners():
    """The walls: inside iff every dense corner is (no miss; alarms only within NEAR of a wall)."""
    rng = np.random.default_rng(7)
    decided = {True: 0, False: 0}
    for _ in range(300):
        u = random_union(rng)
        rear, front = random_overhangs(rng, u.L)
        robot = segplan.Robot(
            u.L, u.L * rng.uniform(0.05, 0.5), front_overhang=front, rear_overhang=rear, rectangle=True
        )
        C = corner_paths(robot, u, u.xs(N_DENSE)).reshape(-1, 2)
        lo, hi = C.min(axis=0), C.max(axis=0)
        pad = rng.choice([-1e-3, -1e-7, 1e-7, 1e-3, 0.2]) * u.L  # walls cutting the body, or not
        side = int(rng.integers(4))
        b = [lo[0] - 0.5, lo[1] - 0.5, hi[0] + 0.5, hi[1] + 0.5]
        b[side] = (lo, lo, hi, hi)[side][side % 2] + (-pad if side < 2 else pad)
        sw = swp.Sweep(u, robot.rear_overhang, robot.front_overhang)
        ours = bd.rectangle_in_bounds(sw, tuple(b), robot.half_width)
        inside = bool(np.all((C[:, 0] > b[0]) & (C[:, 0] < b[2]) & (C[:, 1] > b[1]) & (C[:, 1] < b[3])))
        if not inside:
            assert not ours
        elif not ours:
            gaps = np.minimum.reduce((C[:, 0] - b[0], b[2] - C[:, 0], C[:, 1] - b[1], b[3] - C[:, 1]))
            assert gaps.min() <= NEAR + 1e-6 * u.L  # dense corners' own sampling error
        decided[ours] += 1
    assert decided[True] > 50 and decided[False] > 50


def test_pose_conflict_against_shapely():
    """One pose: the rectangle's conflict agrees with shapely's polygon intersection."""
    rng = np.random.default_rng(11)
    agree = 0
    for _ in range(400):
        L, w = rng.uniform(0.5, 2), rng.uniform(0.1, 0.6)
        rear, front = rng.uniform(0, 1, 2)
        pose = (rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-math.pi, math.pi))
        robot = segplan.Robot(L, w, front_overhang=front, rear_overhang=rear, rectangle=True)
        poly = ngon(
            pose[:2] + rng.normal(size=2) * (L + w),
            rng.uniform(0.05, 1.0),
            int(rng.integers(3, 8)),
            rng.uniform(0, 7),
        )
        body = bd.RectangleBody([poly], w, None, L, rear, front)
        fp = robot.footprint()
        c, s = math.cos(pose[2]), math.sin(pose[2])
        outline = np.column_stack(
            (pose[0] + c * fp[:, 0] - s * fp[:, 1], pose[1] + s * fp[:, 0] + c * fp[:, 1])
        )
        assert np.allclose(body.corners(pose), outline)
        hit = shapely.intersects(shapely.Polygon(outline), shapely.Polygon(poly))
        ours = body.pose_conflict(pose) == "obstacles[0]"
        if hit != ours:  # only a near-touch may differ
            assert shapely.distance(shapely.Polygon(outline), shapely.Polygon(poly)) <= NEAR
        agree += hit == ours
    assert agree >= 390


def test_bad_input():
    u = Union((0, 0, 0), (5, 0, 0), 0.0, 1.0)
    sw = swp.Sweep(u)
    square = geo.ConvexPolygon([[1, 1], [2, 1], [2, 2], [1, 2]])
    with pytest.raises(ValueError, match="half_width"):
        bd.rectangle_collides(sw, square, -0.1)
    with pytest.raises(ValueError, match="ConvexPolygon"):
        bd.rectangle_collides(sw, [[1, 1], [2, 1], [2, 2]], 0.1)
    with pytest.raises(ValueError, match="Sweep"):
        bd.rectangle_collides(u, square, 0.1)
    with pytest.raises(ValueError, match="bounds"):
        bd.rectangle_in_bounds(sw, (0, 0, -1, 1), 0.1)
