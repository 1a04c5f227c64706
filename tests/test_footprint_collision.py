"""Footprints (issue 26): the swept axis segment with overhangs, and the body, against dense oracles.

Two oracles, both independent of segplan's collision module:

* the *segment* oracle: the axis segment from ``A - r u`` to ``A + (L + f) u`` placed at
  2001 frame abscissae of a union, each closed segment asked to shapely (as
  ``test_collision``'s oracle for A->B). It can miss a contact between samples, never
  invent one: the planner's sweep (:class:`segplan.floor.sweep.Sweep` with ``rear=r,
  front=f``) must find every collision it finds, and every collision it reports beyond it
  must be a genuine near-touch (shapely's exact distance at the witness);
* the *body* oracle: the robot's footprint (:meth:`segplan.Robot.footprint`: the rectangle,
  or the exact round body as shapely's buffer of the axis segment) placed at 2001 poses along
  the union, against the *raw* obstacle. The planner's decision (the axis segment swept
  against the obstacle enlarged by ``half_width``) must never miss what it finds; how often
  the planner refuses a union the oracle finds free is its pessimism, printed (``pytest -s``):
  for the rectangle, the two round caps beyond its ends.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import assume, given
from hypothesis import strategies as st
from test_collision import N_DENSE, hull, ngon, random_union, tangent_box

import segplan
from segplan import Union
from segplan.floor import collision as col
from segplan.floor import geometry as geo
from segplan.floor import sweep as swp
from segplan.model.pose import alpha_interval


def ends_at(u: Union, x, rear: float, front: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """World rear end, front end and heading of the axis segment at frame abscissae ``x``."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    A = u.to_world(x, u.f(x))
    h = u.heading(x)
    U = np.stack((np.cos(h), np.sin(h)), axis=-1)
    return A - rear * U, A + (u.L + front) * U, h


def dense_segment_collides(u: Union, poly, rear: float, front: float, n: int = N_DENSE) -> bool:
    """Does any of ``n`` sampled axis segments touch the polygon? (shapely decides)."""
    R, F, _ = ends_at(u, u.xs(n), rear, front)
    P = shapely.Polygon(poly)
    return bool(shapely.intersects(P, shapely.linestrings(np.stack((R, F), 1))).any())


def segment_distance(u: Union, poly, x: float, rear: float, front: float) -> float:
    R, F, _ = ends_at(u, [x], rear, front)
    return float(shapely.distance(shapely.LineString([R[0], F[0]]), shapely.Polygon(poly)))


def bodies(robot: segplan.Robot, u: Union, n: int = N_DENSE):
    """The robot's body (shapely geometries) at ``n`` poses along ``u``: the rectangle, or the
    exact round body (the axis segment buffered by ``half_width``)."""
    R, F, h = ends_at(u, u.xs(n), robot.rear_overhang, robot.front_overhang)
    if not robot.rectangle:
        return shapely.buffer(shapely.linestrings(np.stack((R, F), 1)), robot.half_width, quad_segs=16)
    A = u.to_world(u.xs(n), u.f(u.xs(n)))
    c, s = np.cos(h)[:, None], np.sin(h)[:, None]
    fp = robot.footprint()
    wx = A[:, :1] + c * fp[:, 0] - s * fp[:, 1]
    wy = A[:, 1:] + s * fp[:, 0] + c * fp[:, 1]
    return shapely.polygons(np.stack((wx, wy), axis=-1))


def random_overhangs(rng, L: float) -> tuple[float, float]:
    pick = rng.integers(4)
    rear = 0.0 if pick == 0 else L * rng.uniform(0.05, 1.0)
    front = 0.0 if pick == 1 else L * rng.uniform(0.05, 1.0)
    return rear, front


KINDS = ("hull", "regular", "thin", "graze_rear_end", "graze_front_end", "dip_rear_end", "near_end")


def random_polygon(rng, u: Union, rear: float, front: float, kind: str) -> np.ndarray:
    """A convex polygon near the swept axis segment; ``graze_*``/``dip_*``: an edge tangent
    to (or cutting slightly into) the path of one end."""
    L = u.L
    x = rng.uniform(0, u.x_end)
    (R,), (F,), _ = ends_at(u, x, rear, front)
    p = R + rng.uniform(-0.2, 1.2) * (F - R)
    if kind == "hull":
        c = p + rng.normal(size=2) * 0.5 * L
        return hull(c + rng.normal(size=(rng.integers(3, 10), 2)) * L * rng.uniform(0.05, 1.0))
    if kind == "regular":
        return ngon(
            p + rng.normal(size=2) * L, L * rng.uniform(0.05, 1.0), rng.integers(3, 9), rng.uniform(0, 7)
        )
    if kind == "thin":
        ln, t = L * rng.uniform(0.5, 6), rng.uniform(0, math.pi)
        w = ln / rng.uniform(20, 200)
        d = np.array([math.cos(t), math.sin(t)])
        n = np.array([-d[1], d[0]])
        c = p + rng.normal(size=2) * 0.4 * L
        return np.array([c - d * ln / 2 - n * w / 2, c + d * ln / 2 - n * w / 2, c + d * ln / 2 + n * w / 2,
                         c - d * ln / 2 + n * w / 2])  # fmt: skip
    if kind == "near_end":
        c = (R if rng.random() < 0.5 else F) + rng.normal(size=2) * 0.1 * L
        return ngon(c, L * rng.uniform(0.02, 0.2), rng.integers(3, 7), rng.uniform(0, 7))
    Rr, Ff, _ = ends_at(u, [max(x - 1e-6, 0.0), x, min(x + 1e-6, u.x_end)], rear, front)
    P = Ff if kind == "graze_front_end" else Rr
    tang = (P[2] - P[0]) / np.hypot(*(P[2] - P[0]))
    nrm = np.array([-tang[1], tang[0]]) * rng.choice([-1, 1])
    if kind == "dip_rear_end":
        delta = -L * 10 ** rng.uniform(-4, -1)
    else:
        delta = rng.choice([0.0, 1e-9, 1e-6, 1e-3, -1e-9, -1e-6, -1e-3]) * L
    ln = L * rng.uniform(0.3, 3)
    return tangent_box(P[1], tang, nrm, delta, ln, L * rng.uniform(0.1, 2), rng.uniform(-0.5, 0.5) * ln)


@pytest.fixture(scope="module")
def segment_pairs():
    rng = np.random.default_rng(20260126)
    out = []
    while len(out) < 7 * 100:
        u = random_union(rng)
        rear, front = random_overhangs(rng, u.L)
        kind = KINDS[len(out) % len(KINDS)]
        poly = random_polygon(rng, u, rear, front, kind)
        try:
            P = geo.ConvexPolygon(poly)
        except ValueError:
            continue
        out.append((kind, u, rear, front, poly, P))
    return out


def test_swept_axis_segment_misses_nothing(segment_pairs):
    """The sweep with overhangs against the segment oracle: zero misses, genuine alarms only,
    the event test alone complete too, and the quick rejections sound."""
    misses, event_misses, alarms, positives = [], [], 0, 0
    for kind, u, rear, front, poly, P in segment_pairs:
        sw = swp.Sweep(u, rear, front)
        reject, tol = sw.quick_reject(P)
        ours = col.collision_witness(sw, P)
        ref = dense_segment_collides(u, poly, rear, front)
        positives += ref
        if reject:
            assert ours is None and not ref, f"quick rejection of a colliding {kind} polygon"
        if ref and ours is None:
            misses.append((kind, rear, front))
        if ours is not None:
            assert 0.0 <= ours <= u.x_end
            dist = segment_distance(u, poly, ours, rear, front)
            assert dist <= 100 * tol, f"{kind}: witness at distance {dist:.3g} (tol {tol:.3g})"
            alarms += not ref
        V, N, H = sw.local(P)
        ev = col._events(sw, V, N, H, tol)
        if ref and ev is None:
            event_misses.append(kind)
        if ev is not None:
            assert segment_distance(u, poly, ev, rear, front) <= 100 * tol
    print(f"\n{len(segment_pairs)} pairs, {positives} dense collisions, {alarms} alarms beyond the samples")
    assert positives > len(segment_pairs) // 4  # the generator makes contacts
    assert misses == [], f"missed collisions: {misses}"
    assert event_misses == [], f"event test missed collisions: {event_misses}"


def test_the_sweep_of_the_extended_segment_differs_from_a_b(segment_pairs):
    """The overhangs matter: some polygons touched only by the overhangs (a test that ignored
    them would fail here), found by the sweep with them and not by the sweep of A->B."""
    only_overhang = 0
    for _, u, rear, front, _, P in segment_pairs:
        if col.collides(swp.Sweep(u, rear, front), P) and not col.collides(u, P):
            only_overhang += 1
    assert only_overhang > 20


def test_walls_with_overhangs_match_dense_sampling():
    rng = np.random.default_rng(5)
    agree = outside = 0
    for _ in range(150):
        u = random_union(rng)
        rear, front = random_overhangs(rng, u.L)
        R, F, _ = ends_at(u, u.xs(N_DENSE), rear, front)
        pts = np.concatenate((R, F))
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        bounds = (*(lo - rng.uniform(-0.3, 0.5, 2) * u.L), *(hi + rng.uniform(-0.3, 0.5, 2) * u.L))
        if not (bounds[0] < bounds[2] and bounds[1] < bounds[3]):
            continue
        ours = col.sweep_in_bounds(swp.Sweep(u, rear, front), geo.check_bounds(bounds))
        dense = bool(
            np.all(
                (pts[:, 0] > bounds[0])
                & (pts[:, 0] < bounds[2])
                & (pts[:, 1] > bounds[1])
                & (pts[:, 1] < bounds[3])
            )
        )
        if ours:  # inside by our test: inside at every sample
            assert dense
        outside += not dense
        agree += ours == dense
    assert outside > 30 and agree >= 140


def test_default_sweep_is_the_paper_segment_bit_for_bit(segment_pairs):
    """No overhang: the same frame box, bounds and decisions as ``Sweep(union)``."""
    for _, u, _, _, _, P in segment_pairs[:200]:
        a, b = swp.Sweep(u), swp.Sweep(u, 0.0, 0.0)
        assert a.box == b.box and a.K == b.K and a.dc_margin == b.dc_margin and a.size == b.size
        assert a.quick_reject(P) == b.quick_reject(P)
        assert col.collision_witness(a, P) == col.collision_witness(b, P)


def test_pose_conflict_with_overhangs_matches_shapely():
    rng = np.random.default_rng(11)
    hits = 0
    for _ in range(400):
        L = rng.uniform(0.5, 2)
        rear, front = random_overhangs(rng, L)
        pose = (*rng.uniform(-3, 3, 2), rng.uniform(-math.pi, math.pi))
        poly = ngon(rng.uniform(-3, 3, 2), rng.uniform(0.1, 1.5), int(rng.integers(3, 8)), rng.uniform(0, 7))
        ax, ay, dx, dy, _ = geo.axis_segment(*pose, L, rear, front)
        line = shapely.LineString([(ax, ay), (ax + dx, ay + dy)])
        dist = float(shapely.distance(line, shapely.Polygon(poly)))
        ours = geo.pose_collides(pose, L, poly, rear=rear, front=front)
        if dist == 0.0:
            assert ours
        elif dist > 1e-6:
            assert not ours
        hits += ours
    assert hits > 30


# -- the body against the raw obstacle -----------------------------------------------------------
def _planner_says(robot, u, raw) -> bool:
    """The planner's decision: the axis segment swept against the obstacle enlarged by half_width."""
    enlarged = geo.enlarge_polygon(geo.check_convex_polygon(raw), robot.half_width)
    return col.collides(swp.Sweep(u, robot.rear_overhang, robot.front_overhang), enlarged)


def _body_pairs(seed: int, n: int):
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        u = random_union(rng)
        rear, front = random_overhangs(rng, u.L)
        w = u.L * rng.uniform(0.05, 0.5)
        robot = segplan.Robot(u.L, w, front_overhang=front, rear_overhang=rear, rectangle=bool(len(out) % 2))
        x = rng.uniform(0, u.x_end)
        (R,), (F,), _ = ends_at(u, x, rear, front)
        c = R + rng.uniform(-0.3, 1.3) * (F - R) + rng.normal(size=2) * (w + 0.8 * u.L)
        poly = ngon(c, u.L * rng.uniform(0.03, 0.6), int(rng.integers(3, 8)), rng.uniform(0, 7))
        out.append((robot, u, poly))
    return out


def test_body_never_missed_and_its_pessimism():
    """Zero missed collisions of the body (rectangle or round) against a dense shapely oracle
    of the footprint along the union; the pessimism (refused, the oracle free) measured."""
    counts = {True: [0, 0, 0], False: [0, 0, 0]}  # rectangle -> [pairs, oracle hits, pessimistic]
    for robot, u, poly in _body_pairs(26, 400):
        ours = _planner_says(robot, u, poly)
        oracle = bool(shapely.intersects(bodies(robot, u), shapely.Polygon(poly)).any())
        assert ours or not oracle, f"missed collision of {robot} along {u}"
        c = counts[robot.rectangle]
        c[0] += 1
        c[1] += oracle
        c[2] += ours and not oracle
    for rect, (n, hit, pess) in counts.items():
        print(f"\n{'rectangle' if rect else 'round'} body: {n} pairs, {hit} collisions, "
              f"{pess} refused though free ({pess / max(1, n - hit):.1%} of the free ones)")  # fmt: skip
    # the round body is decided exactly but for the enlargement's polygonal excess
    n, hit, pess = counts[False]
    assert hit > 50 and pess <= 0.05 * (n - hit)
    n, hit, pess = counts[True]
    assert hit > 50 and pess > 0  # the caps: conservative, and measurably so


@st.composite
def chord_unions(draw) -> Union:
    """A union along the x axis from the origin: ``L`` 0.3-3, chord 2-10 ``L``, intrinsic
    headings within 69 deg, alpha strictly inside its interval (the body tests' unions)."""
    L = draw(st.floats(0.3, 3.0))
    ratio = draw(st.floats(2.0, 10.0))
    phi0, phi1 = draw(st.floats(-1.2, 1.2)), draw(st.floats(-1.2, 1.2))
    lo, hi = alpha_interval(phi0, phi1)
    alpha = lo + draw(st.floats(0.05, 0.95)) * (hi - lo)
    assume(lo < alpha < hi)
    return Union((0.0, 0.0, phi0), (ratio * L, 0.0, phi1), alpha, L)


@given(
    u=chord_unions(),
    w=st.one_of(st.just(0.0), st.floats(0.01, 0.6)),
    rear=st.floats(0.0, 1.0),
    front=st.floats(0.0, 1.0),
    rectangle=st.booleans(),
    x_frac=st.floats(0.0, 1.0),
    t=st.floats(-0.5, 1.5),
    offset=st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0)),
    size=st.floats(0.02, 1.0),
    k=st.integers(3, 7),
    phase=st.floats(0.0, 6.3),
)
def test_body_never_missed_hypothesis(u, w, rear, front, rectangle, x_frac, t, offset, size, k, phase):
    L = u.L
    robot = segplan.Robot(L, w * L, front_overhang=front * L, rear_overhang=rear * L, rectangle=rectangle)
    (R,), (F,), _ = ends_at(u, [x_frac * u.x_end], robot.rear_overhang, robot.front_overhang)
    poly = ngon(R + t * (F - R) + (w + 0.3) * L * np.asarray(offset), size * L, k, phase)
    if shapely.intersects(bodies(robot, u), shapely.Polygon(poly)).any():
        assert _planner_says(robot, u, poly)
