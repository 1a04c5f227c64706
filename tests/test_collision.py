"""Collision detection against an independent oracle: dense shapely sampling of the sweep.

The oracle places the segment A-B at 2001 frame abscissae of the union (``Union.xs``)
and asks shapely whether any of these closed segments touches the closed polygon. It can
miss a contact that happens between samples, never invent one; so our test must find every
collision it finds (zero misses), and every collision we report without it must be a
genuine near-touch: the segment at our witness abscissa is within a tiny distance of the
polygon (checked with shapely's exact distance).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st

import segplan
from segplan import Union
from segplan.floor import collision as col
from segplan.floor import geometry as geo
from segplan.floor import sweep as swp
from segplan.model.pose import alpha_interval

N_DENSE = 2001


# -- generators ------------------------------------------------------------------------------
def random_union(rng) -> Union:
    """A union with d/L in [2, 10], intrinsic headings within 69 deg, alpha inside its interval."""
    while True:
        L = rng.uniform(0.5, 2.0)
        d = L * rng.uniform(2.0, 10.0)
        psi = rng.uniform(-math.pi, math.pi)
        x0, y0 = rng.uniform(-20, 20, 2)
        phi0, phi1 = rng.uniform(-1.2, 1.2, 2)
        lo, hi = alpha_interval(phi0, phi1)
        if hi - lo < 0.1:
            continue
        a = rng.uniform(lo + 0.05 * (hi - lo), hi - 0.05 * (hi - lo))
        p1 = (x0 + d * math.cos(psi), y0 + d * math.sin(psi), psi + phi1)
        return Union((x0, y0, psi + phi0), p1, a, L)


def segments_at(u: Union, x) -> tuple[np.ndarray, np.ndarray]:
    """World end points A, B of the segment at frame abscissae ``x``."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    A = u.to_world(x, u.f(x))
    h = u.heading(x)
    return A, A + u.L * np.stack((np.cos(h), np.sin(h)), axis=-1)


def hull(points) -> np.ndarray:
    return np.asarray(shapely.convex_hull(shapely.multipoints(points)).exterior.coords)[:-1]


def ngon(centre, r, k, phase, squash=1.0) -> np.ndarray:
    ang = phase + np.arange(k) * 2 * math.pi / k
    return np.asarray(centre) + r * np.stack((np.cos(ang), squash * np.sin(ang)), axis=-1)


def tangent_box(P, tang, nrm, delta, ln, dep, off) -> np.ndarray:
    """Rectangle with one edge on the line through ``P + delta nrm`` along ``tang``, body along ``nrm``."""
    base = P + delta * nrm
    a, b = base + tang * (off - ln / 2), base + tang * (off + ln / 2)
    return np.array([a, b, b + nrm * dep, a + nrm * dep])


KINDS = (
    "hull",  # convex hull of random points near the sweep
    "small_between",  # small polygon near a point strictly between A and B
    "regular",
    "large",  # boundary passing near the sweep
    "thin",  # aspect 20-300
    "graze_rear",  # an edge tangent to the rear path, offset 0, +-1e-12 .. +-1e-3 L
    "graze_front",  # the same for the front-wheel path
    "dip_front",  # the front wheel dips 1e-4 .. 1e-1 L through one edge
    "vertex_near",  # a sharp vertex at or near a point of the segment
)


def random_polygon(rng, u: Union, kind: str) -> np.ndarray:
    L = u.L
    x = rng.uniform(0, u.x_end)
    A, B = (p[0] for p in segments_at(u, x))
    p = A + rng.uniform(-0.5, 1.5) * (B - A)
    if kind == "hull":
        c = p + rng.normal(size=2) * L
        return hull(c + rng.normal(size=(rng.integers(3, 12), 2)) * L * rng.uniform(0.05, 2.0))
    if kind == "small_between":
        c = A + rng.uniform(0.05, 0.95) * (B - A) + rng.normal(size=2) * 0.05 * L
        ang = np.sort(rng.uniform(0, 2 * math.pi, rng.integers(3, 9)))
        return hull(c + L * rng.uniform(0.005, 0.08) * np.stack((np.cos(ang), np.sin(ang)), -1))
    if kind == "regular":
        return ngon(
            p + rng.normal(size=2) * L, L * rng.uniform(0.05, 1.5), rng.integers(3, 9), rng.uniform(0, 7)
        )
    if kind == "large":
        k = int(rng.integers(4, 9))
        r = L * rng.uniform(3, 20)
        t = rng.uniform(0, 2 * math.pi)
        c = p + (r * math.cos(math.pi / k) + rng.normal() * 0.3 * L) * np.array([math.cos(t), math.sin(t)])
        return ngon(c, r, k, rng.uniform(0, 7))
    if kind == "thin":
        ln = L * rng.uniform(0.5, 10)
        w = ln / rng.uniform(20, 300)
        t = rng.uniform(0, math.pi)
        d = np.array([math.cos(t), math.sin(t)])
        n = np.array([-d[1], d[0]])
        c = p + rng.normal(size=2) * 0.5 * L
        return np.array(
            [
                c - d * ln / 2 - n * w / 2,
                c + d * ln / 2 - n * w / 2,
                c + d * ln / 2 + n * w / 2,
                c - d * ln / 2 + n * w / 2,
            ]
        )
    if kind in ("graze_rear", "graze_front", "dip_front"):
        Aa, Bb = segments_at(u, [x - 1e-6, x, x + 1e-6])
        P = Aa if kind == "graze_rear" else Bb
        tang = (P[2] - P[0]) / np.hypot(*(P[2] - P[0]))
        nrm = np.array([-tang[1], tang[0]]) * rng.choice([-1, 1])
        if kind == "dip_front":
            delta = -L * 10 ** rng.uniform(-4, -1)
        else:
            delta = rng.choice([0.0, 1e-12, 1e-9, 1e-6, 1e-3, -1e-9, -1e-6, -1e-3]) * L
        ln = L * rng.uniform(0.3, 5)
        return tangent_box(P[1], tang, nrm, delta, ln, L * rng.uniform(0.1, 3), rng.uniform(-0.5, 0.5) * ln)
    if kind == "vertex_near":
        v = A + rng.uniform(0.0, 1.0) * (B - A) + rng.choice([0.0, 1e-9, 1e-6, 1e-3]) * L * rng.normal(size=2)
        t, spread, r = rng.uniform(0, 2 * math.pi), rng.uniform(0.05, 1.2), L * rng.uniform(0.1, 2)
        return np.array(
            [
                v,
                v + r * np.array([math.cos(t - spread), math.sin(t - spread)]),
                v + r * np.array([math.cos(t + spread), math.sin(t + spread)]),
            ]
        )
    raise ValueError(kind)


def dense_collides(u: Union, poly, n: int = N_DENSE) -> bool:
    """Does any of ``n`` sampled segments touch the polygon? (shapely decides every candidate)."""
    A, B = segments_at(u, u.xs(n))
    poly = np.asarray(poly, dtype=float)
    (x0, y0), (x1, y1) = poly.min(axis=0), poly.max(axis=0)
    # only the segments whose bounding box meets the polygon's can touch it (exact comparisons):
    # about 3x faster than asking shapely about all of them, the same answers
    near = (
        (np.minimum(A[:, 0], B[:, 0]) <= x1)
        & (np.maximum(A[:, 0], B[:, 0]) >= x0)
        & (np.minimum(A[:, 1], B[:, 1]) <= y1)
        & (np.maximum(A[:, 1], B[:, 1]) >= y0)
    )
    idx = np.flatnonzero(near)
    if not len(idx):
        return False
    P = shapely.Polygon(poly)
    shapely.prepare(P)

    def touch(i) -> bool:
        return bool(shapely.intersects(P, shapely.linestrings(np.stack((A[i], B[i]), 1))).any())

    # every 16th candidate first: most collisions span many samples, and a hit among these is
    # a hit among all (the same answer); otherwise the others decide. Halves the oracle's time.
    coarse = np.zeros(len(idx), dtype=bool)
    coarse[::16] = True
    return touch(idx[coarse]) or touch(idx[~coarse])


def distance_at(u: Union, poly, x: float) -> float:
    """Exact distance (shapely) between the segment at frame abscissa ``x`` and the polygon."""
    A, B = segments_at(u, [x])
    return float(shapely.distance(shapely.LineString([A[0], B[0]]), shapely.Polygon(poly)))


def random_pairs(seed: int, n: int):
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        u = random_union(rng)
        kind = KINDS[len(out) % len(KINDS)]
        poly = random_polygon(rng, u, kind)
        try:
            P = geo.ConvexPolygon(poly)
        except ValueError:  # a hull that came out degenerate
            continue
        out.append((kind, u, poly, P))
    return out


# -- the swept segment against random polygons -----------------------------------------------------
@pytest.fixture(scope="module")
def pairs():
    return random_pairs(20240601, 9 * 220)


def test_zero_missed_collisions_and_genuine_false_alarms(pairs):
    misses, alarms, positives, rejected = [], [], 0, 0
    events_misses, events_alarms = [], 0
    worst = 0.0
    for kind, u, poly, P in pairs:
        sw = swp.Sweep(u)
        reject, tol = sw.quick_reject(P)
        ours = col.collision_witness(sw, P)
        ref = dense_collides(u, poly)
        positives += ref
        if reject:
            rejected += 1
            assert ours is None and not ref, f"quick rejection of a colliding {kind} polygon"
        if ref and ours is None:
            misses.append(kind)
        if ours is not None:
            # every reported collision is real: the segment at the witness touches (within tolerance)
            assert 0.0 <= ours <= u.x_end
            dist = distance_at(u, poly, ours)
            worst = max(worst, dist / tol)
            assert dist <= 100 * tol, f"{kind}: witness at distance {dist:.3g} (tol {tol:.3g})"
            if not ref:  # a false alarm must be a genuine near-touch that the sampling misses
                assert dist <= 2 * tol, f"{kind}: false alarm at distance {dist:.3g} (tol {tol:.3g})"
                alarms.append(kind)
        # the event test alone (the exact fallback of the certified sweep) must be complete too
        V, N, H = sw.local(P)
        ev = col._events(sw, V, N, H, tol)
        if ref and ev is None:
            events_misses.append(kind)
        if ev is not None:
            assert distance_at(u, poly, ev) <= 100 * tol
            events_alarms += not ref
    by_kind = {k: alarms.count(k) for k in sorted(set(alarms))}
    print(
        f"\n{len(pairs)} pairs, {positives} dense collisions, {rejected} quick rejections, "
        f"false alarms {len(alarms)} ({len(alarms) / len(pairs):.2%}; by kind {by_kind}), "
        f"event-test false alarms {events_alarms}, worst witness distance {worst:.2f} tol"
    )
    assert misses == [], f"missed collisions: {misses}"
    assert events_misses == [], f"event test missed collisions: {events_misses}"


def test_union_free_matches_collides_and_bounds(pairs):
    rng = np.random.default_rng(7)
    for j in range(60):
        group = [pairs[i] for i in rng.choice(len(pairs), 6, replace=False)]
        u = group[0][1]
        obstacles = [g[3] for g in group]
        b = np.concatenate(segments_at(u, u.xs(201)))
        lo, hi = b.min(axis=0), b.max(axis=0)
        bounds = (*(lo - rng.uniform(-0.1, 1)), *(hi + rng.uniform(-0.1, 1)))
        expect = col.union_in_bounds(u, bounds) and not any(col.collides(u, p) for p in obstacles)
        assert col.union_free(u, obstacles, bounds) == expect
        assert col.union_free(u, [g[2] for g in group]) == (not any(col.collides(u, p) for p in obstacles)), j


# -- constructed contacts ----------------------------------------------------------------------------
def s_union() -> Union:
    """An S-shaped union with an inflection point inside (L = 1)."""
    return Union((0.0, 0.0, 0.5), (6.0, 0.0, 0.5), 0.0, 1.0)


def test_front_wheel_dips_through_one_edge():
    # a C-shaped union; a box above the bump that only the front wheel reaches, entering
    # and leaving through the box's bottom edge
    u = Union((0.0, 0.0, 0.7), (6.0, 0.0, -0.7), 0.0, 1.0)
    A, B = segments_at(u, u.xs(4001))
    top_rear, top_front = A[:, 1].max(), B[:, 1].max()
    assert top_front > top_rear + 0.05
    i = int(np.argmax(B[:, 1]))
    sw = swp.Sweep(u)
    for depth, expect in ((1e-3, True), (1e-7, True), (0.0, True), (-1e-6, False)):
        y = top_front - depth
        box = np.array(
            [[B[i, 0] - 0.3, y], [B[i, 0] + 0.3, y], [B[i, 0] + 0.3, y + 1], [B[i, 0] - 0.3, y + 1]]
        )
        assert col.collides(u, box) is expect, depth
        assert (col._events(sw, *sw.local(geo.ConvexPolygon(box)), 1e-8) is not None) is expect, depth


def test_rear_path_touches_a_vertex_inside_a_bend():
    # the rear path bends away from the tangent's side; a vertex touching it from the inner
    # side, with edges steeper than the path, is touched only by A (the segment leaves forward)
    u = Union((0.0, 0.0, 0.9), (5.0, 0.0, -0.9), 0.0, 1.0)
    x0 = 2.0
    (A,), (B,) = segments_at(u, [x0])
    d = (B - A) / u.L
    inner = np.array([d[1], -d[0]])  # right of the heading: the inner side of this left-to-right arc
    assert u.second_derivative(x0) < 0
    sw = swp.Sweep(u)
    for delta, expect in ((0.0, True), (-1e-9, True), (1e-6, False)):
        v = A + delta * inner
        tri = np.array([v, v + 0.5 * (inner + 0.5 * d), v + 0.5 * (inner - 0.5 * d)])
        assert col.collides(u, tri) is expect, delta
        assert (col._events(sw, *sw.local(geo.ConvexPolygon(tri)), 1e-8) is not None) is expect, delta


def test_start_pose_touched_from_behind():
    u = s_union()
    (A,), (B,) = segments_at(u, [0.0])
    d = (B - A) / u.L
    n = np.array([-d[1], d[0]])
    for delta, expect in ((0.0, True), (-1e-9, True), (1e-6, False)):
        box = tangent_box(A - delta * d, n, -d, 0.0, 0.4, 0.3, 0.0)
        assert col.collides(u, box) is expect, delta


def test_polygon_enveloped_between_paths():
    # a small triangle swept by the segment's interior, 0.1 L away from both paths
    u = Union((0.0, 0.0, 0.9), (5.0, 0.0, -0.9), 0.0, 1.0)
    A, B = segments_at(u, [2.4576])
    tri = ngon(A[0] + 0.7 * (B[0] - A[0]), 0.02, 3, 0.3)
    Ad, Bd = segments_at(u, u.xs(20001))
    P = shapely.Polygon(tri)
    assert shapely.distance(shapely.LineString(Ad), P) > 0.05
    assert shapely.distance(shapely.LineString(Bd), P) > 0.05
    assert col.collides(u, tri)
    sw = swp.Sweep(u)
    assert col._events(sw, *sw.local(geo.ConvexPolygon(tri)), 1e-9) is not None


def test_vertex_grazes_segment_at_inflection():
    # at the inflection the segment's line stops turning: a vertex on that line is touched
    # tangentially (a double root of h_V), from the side the nearby lines do not cross
    u = s_union()
    _, c1, c2, c3 = u.coefficients
    xi = -c2 / (3 * c3)
    assert 0 < xi < u.x_end
    A, B = (p[0] for p in segments_at(u, [xi]))
    V = 0.5 * (A + B)
    d = (B - A) / u.L
    n = np.array([-d[1], d[0]])
    xs = np.linspace(xi - 0.3, xi + 0.3, 2001)
    An, Bn = segments_at(u, xs)
    # side of V relative to the nearby segment lines (frame-free): the sign of cross(B - A, V - A)
    e, w = Bn - An, V - An
    sides = e[:, 0] * w[:, 1] - e[:, 1] * w[:, 0]
    sgn = np.sign(np.median(sides[np.abs(xs - xi) > 1e-3]))
    out = sgn * n  # the nearby lines leave V on this side... the polygon extends the other way
    for delta, expect in ((0.0, True), (-1e-9, True), (1e-5, False)):
        v = V + delta * out
        tri = np.array([v, v + 0.3 * (out + 0.8 * d), v + 0.3 * (out - 0.8 * d)])
        assert col.collides(u, tri) is expect, delta
        sw = swp.Sweep(u)
        assert (col._events(sw, *sw.local(geo.ConvexPolygon(tri)), 1e-8) is not None) is expect, delta


def test_start_and_end_poses():
    u = s_union()
    for x in (0.0, u.x_end):
        A, B = (p[0] for p in segments_at(u, [x]))
        tri = ngon(0.5 * (A + B), 1e-3, 3, 0.0)
        assert col.collides(u, tri)


# -- single poses and walls ---------------------------------------------------------------------------
def test_pose_collides_matches_shapely():
    rng = np.random.default_rng(3)
    for _ in range(1500):
        L = rng.uniform(0.3, 3)
        pose = (*rng.uniform(-5, 5, 2), rng.uniform(-4, 4))
        A = np.array(pose[:2])
        B = A + L * np.array([math.cos(pose[2]), math.sin(pose[2])])
        c = A + rng.uniform(-0.5, 1.5) * (B - A) + rng.normal(size=2) * L * 0.7
        poly = hull(c + rng.normal(size=(rng.integers(3, 9), 2)) * L * rng.uniform(0.05, 1))
        if rng.random() < 0.2:  # a vertex exactly on the segment
            poly = np.array([A + rng.uniform(0, 1) * (B - A), *(poly[:2] + 5 * L)])
            e, w = poly[1] - poly[0], poly[2] - poly[0]
            if abs(e[0] * w[1] - e[1] * w[0]) < 1e-6:
                continue
        ref = shapely.intersects(shapely.LineString([A, B]), shapely.Polygon(poly))
        got = geo.pose_collides(pose, L, poly)
        if got != ref:  # only within the touching tolerance
            assert got and shapely.distance(shapely.LineString([A, B]), shapely.Polygon(poly)) < 1e-8


def test_union_in_bounds_matches_dense_sampling():
    rng = np.random.default_rng(11)
    misses = alarms = 0
    for _ in range(500):
        u = random_union(rng)
        A, B = segments_at(u, u.xs(N_DENSE))
        pts = np.concatenate((A, B))
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        scale = u.L * rng.choice([1e-1, 1e-3, 1e-6, 1e-9, 0.0], size=4) * rng.choice([-1, 1], size=4)
        bounds = (lo[0] - scale[0], lo[1] - scale[1], hi[0] + scale[2], hi[1] + scale[3])
        if not (bounds[0] < bounds[2] and bounds[1] < bounds[3]):
            continue
        # the open box contains a segment iff it contains both end points (it is convex): exact
        # comparisons, the answers of shapely.contains_properly at a tenth of its time
        ref = bool(np.all(pts > bounds[:2]) and np.all(pts < bounds[2:]))
        got = col.union_in_bounds(u, bounds)
        if ref and not got:
            alarms += 1
            # genuine near-touch: some wall within 1e-8 of the sampled extremes (margins of 0 or 1e-9 L)
            assert min(np.abs(scale)) <= 1e-9 * u.L
        misses += got and not ref
    assert misses == 0


def test_union_leaving_the_bounds_by_one_side_is_out():
    """Bounds loose on three sides (up to 2 L) and cutting the sampled extent on the fourth:
    never in bounds (the quick test of the frame box must not pass such a union)."""
    rng = np.random.default_rng(12)
    for _ in range(1500):
        u = random_union(rng)
        A, B = segments_at(u, u.xs(N_DENSE))
        pts = np.concatenate((A, B))
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        loose = u.L * rng.uniform(0.0, 2.0, 4)
        cut = int(rng.integers(4))
        loose[cut] = -1e-3 * u.L
        bounds = (lo[0] - loose[0], lo[1] - loose[1], hi[0] + loose[2], hi[1] + loose[3])
        if bounds[0] < bounds[2] and bounds[1] < bounds[3]:
            assert not col.union_in_bounds(u, bounds)


def test_pose_in_bounds():
    assert geo.pose_in_bounds((1, 1, 0), 1.0, (0, 0, 3, 3))
    assert not geo.pose_in_bounds((1, 1, 0), 2.0, (0, 0, 3, 3))  # B on the wall
    assert not geo.pose_in_bounds((0, 1, 0), 1.0, (0, 0, 3, 3))  # A on the wall
    with pytest.raises(ValueError, match="bounds"):
        geo.pose_in_bounds((1, 1, 0), 1.0, (0, 0, -3, 3))


# -- validation ---------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("poly", "message"),
    [
        ([[0, 0], [1, 0]], "at least 3 vertices"),
        ([[0, 0], [1, 0], [np.nan, 1]], "vertex 2: coordinates must be finite"),
        ([[0, 0], [1, 0], [np.inf, 1]], "must be finite"),
        ([[0, 0], [2, 0], [1, 0.2], [2, 2], [0, 2]], "not convex"),
        ([[0, 0], [1, 1], [1, 0], [0, 1]], "not convex"),  # bow-tie
        ([[0, 0], [1, 0], [1, 0], [0, 1]], "vertex 2 repeats vertex 1"),
        ([[0, 0], [1, 0], [2, 0]], "collinear"),  # degenerate; one collinear vertex is dropped (issue 27)
        ([[0, 0], [2, 0], [1, 0], [1, 1]], "doubles back"),
        (ngon((0, 0), 1, 5, 0)[[0, 2, 4, 1, 3]], "self-intersecting"),  # pentagram
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], "shape"),
        ("abc", "array of numbers"),
    ],
)
def test_validation_rejects(poly, message):
    with pytest.raises(ValueError, match=message):
        geo.check_convex_polygon(poly)
    with pytest.raises(ValueError, match=message):
        col.collides(s_union(), poly)


def test_orientation_and_prepared_polygons():
    sq = np.array([[0.0, 0], [1, 0], [1, 1], [0, 1]])
    ccw, cw = geo.ConvexPolygon(sq), geo.ConvexPolygon(sq[::-1])
    assert np.array_equal(ccw.vertices, cw.vertices)
    assert np.allclose(ccw.normals @ ccw.vertices.mean(axis=0) - ccw.offsets, -0.5)
    with pytest.raises(AttributeError):
        ccw.radius = 3.0
    u = s_union()
    for shift in ((2, -0.2), (2, 3), (-3, 0)):
        p = sq * 0.3 + shift
        r = col.collides(u, p)
        assert col.collides(u, geo.ConvexPolygon(p)) == r == col.collides(u, p[::-1], check=False)
    # no validation cache: a mutated array is checked again
    arr = sq.copy()
    col.collides(u, arr)
    arr[2] = (0.2, 0.2)
    with pytest.raises(ValueError, match="not convex"):
        col.collides(u, arr)


def test_stats_and_exports():
    st_ = col.CollisionStats()
    u = s_union()
    far = np.array([[100.0, 100], [101, 100], [101, 101]])
    near = np.array([[2.0, 0.3], [2.5, 0.3], [2.5, 0.8]])
    assert not col.collides(u, far, stats=st_)
    hit = col.collides(u, near, stats=st_)
    assert (st_.calls, st_.rejected, st_.exact) == (2, 1, 1)
    assert st_.collisions == int(hit)  # one collision counted per colliding query
    through = np.array([[0.5, -5.0], [1.5, -5.0], [1.5, 5.0], [0.5, 5.0]])  # across the whole path
    assert col.collides(u, through, stats=st_)
    assert (st_.calls, st_.collisions) == (3, int(hit) + 1)
    st_.reset()
    assert st_.calls == 0
    for name in ("collides", "union_free", "union_in_bounds", "CollisionStats"):
        assert getattr(segplan, name) is getattr(col, name)
    for name in ("pose_collides", "pose_in_bounds", "ConvexPolygon"):
        assert getattr(segplan, name) is getattr(geo, name)


def test_no_module_counters():
    """Issue 24: the module keeps no state; counts go to a CollisionStats the caller passes."""
    assert not hasattr(col, "STATS") and "STATS" not in col.__all__
    u = s_union()
    near = np.array([[2.0, 0.3], [2.5, 0.3], [2.5, 0.8]])
    before = {k: v for k, v in vars(col).items() if not k.startswith("__")}
    col.collides(u, near)
    col.union_free(u, [near])
    assert {k: v for k, v in vars(col).items() if not k.startswith("__")} == before


# -- numerical kernels ------------------------------------------------------------------------------------
@given(
    st.lists(st.floats(-1.0, 2.0), min_size=3, max_size=3),
    st.floats(0.01, 100.0),
    st.sampled_from([1.0, -1.0]),
)
def test_cubic_points_find_real_roots(roots, scale, sign):
    a3, a2, a1, a0 = np.poly(roots) * scale * sign
    got = swp.cubic_points(np.array([a3]), np.array([a2]), np.array([a1]), np.array([a0]))[0]
    for r in roots:
        if 0.0 <= r <= 1.0:
            # each root in [0, 1] is matched by a candidate where the cubic is tiny
            assert (
                np.nanmin(np.abs(got - r)) < 1e-5
                or np.nanmin(np.abs(np.polyval([a3, a2, a1, a0], got))) < 1e-12 * scale
            )


@given(
    st.floats(-1.0, 2.0),
    st.lists(st.floats(0.05, 1.0), min_size=2, max_size=2),
    st.floats(0.01, 100.0),
    st.sampled_from([1.0, -1.0]),
)
def test_cubic_points_find_each_distinct_root(first, gaps, scale, sign):
    """Well separated roots: each is returned once, accurately (one root thrice fails)."""
    roots = first + np.cumsum([0.0, *gaps])
    a3, a2, a1, a0 = np.poly(roots) * scale * sign
    got = swp.cubic_points(np.array([a3]), np.array([a2]), np.array([a1]), np.array([a0]))[0]
    np.testing.assert_allclose(np.sort(got), roots, rtol=0.0, atol=1e-9)


def test_quick_rejection_is_sound():
    rng = np.random.default_rng(5)
    for _ in range(400):
        u = random_union(rng)
        sw = swp.Sweep(u)
        x = rng.uniform(0, u.x_end)
        A, B = (p[0] for p in segments_at(u, [x]))
        c = A + rng.normal(size=2) * u.L * 3
        poly = ngon(c, u.L * rng.uniform(0.05, 1), int(rng.integers(3, 8)), rng.uniform(0, 7))
        if sw.quick_reject(geo.ConvexPolygon(poly))[0]:
            # no sampled segment touches it (shapely's intersects: distance 0 exactly when they meet)
            assert not dense_collides(u, poly)


def test_straight_union_contacts():
    # c2 = c3 = 0: the sweep is the segment from A(0) to B(X) = (X + L, 0); K = 0
    u = Union((0.0, 0.0, 0.0), (4.0, 0.0, 0.0), 0.0, 1.0)
    assert u.coefficients == (0.0, 0.0, 0.0, 0.0)
    sq = np.array([[0.0, 0.0], [1, 0], [1, 1], [0, 1]])
    for shift, expect in (
        ((2.0, 0.0), True),  # an edge along the path
        ((2.0, 1e-6), False),
        ((2.0, -1e-9), True),
        ((5.0, -0.5), True),  # the front wheel's last position touches the left edge
        ((5.0 + 1e-6, -0.5), False),
        ((-1.0, -0.5), True),  # the start pose touches the right edge
        ((-1.0 - 1e-6, -0.5), False),
    ):
        assert col.collides(u, sq * 1.0 + shift) is expect, shift
    tri = np.array([[2.5, 0.0], [3.0, -1.0], [2.0, -1.0]])  # a vertex on the path's line
    assert col.collides(u, tri)
    assert not col.collides(u, tri - (0, 1e-6))


@given(
    L=st.floats(0.3, 3.0),
    ratio=st.floats(2.0, 10.0),
    phi0=st.floats(-1.2, 1.2),
    phi1=st.one_of(st.floats(-1.2, 1.2), st.just(None)),  # None: phi1 = -phi0 (c3 = 0 at alpha = 0)
    frac=st.one_of(st.floats(0.05, 0.95), st.just(None)),  # None: alpha = 0
    x_frac=st.floats(0.0, 1.0),
    t=st.floats(-0.3, 1.3),
    offset=st.tuples(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0)),
    size=st.floats(0.01, 1.5),
    k=st.integers(3, 8),
    phase=st.floats(0.0, 6.3),
)
def test_collides_never_misses_hypothesis(L, ratio, phi0, phi1, frac, x_frac, t, offset, size, k, phase):
    phi1 = -phi0 if phi1 is None else phi1
    lo, hi = alpha_interval(phi0, phi1)
    alpha = 0.0 if frac is None else lo + frac * (hi - lo)
    if not lo < alpha < hi:
        return
    u = Union((0.0, 0.0, phi0), (ratio * L, 0.0, phi1), alpha, L)
    (A,), (B,) = segments_at(u, [x_frac * u.x_end])
    poly = ngon(A + t * (B - A) + L * np.asarray(offset), size * L, k, phase)
    if dense_collides(u, poly):
        assert col.collides(u, poly)
    w = col.collision_witness(u, poly)
    if w is not None:
        assert distance_at(u, poly, w) <= 1e-7 * (L + u.x_end + 10)


def test_quadratic_points_against_numpy_roots():
    """``sweep.quadratic_points``: the real roots (numpy's companion-matrix roots as the
    oracle), the vertex twice for a complex pair, the linear root when ``a2`` vanishes."""
    from segplan.floor.sweep import quadratic_points

    rng = np.random.default_rng(2)
    a2, a1, a0 = rng.normal(size=(3, 400)) * 10.0 ** rng.uniform(-3, 3, (3, 400))
    got = quadratic_points(a2, a1, a0)
    for k in range(400):
        disc = a1[k] ** 2 - 4 * a2[k] * a0[k]
        if disc >= 0:
            want = np.sort(np.roots([a2[k], a1[k], a0[k]]).real)
        else:
            want = np.full(2, -a1[k] / (2 * a2[k]))
        scale = max(1.0, *np.abs(want))
        assert np.allclose(np.sort(got[k]), want, rtol=1e-9, atol=1e-12 * scale), k
    lin = quadratic_points(np.array([0.0]), np.array([2.0]), np.array([-3.0]))
    assert np.allclose(lin, 1.5)


@pytest.mark.parametrize(
    ("a", "b", "c", "roots"),
    [
        (1.0, -1.0, 0.0, [0.0, 1.0]),  # q = 1 exactly: both roots, one of them 0
        (2.0, -1.0, 0.0, [0.0, 0.5]),
        (1.0, 0.0, 0.0, [0.0]),  # q = 0: the double root 0, once (no division by q)
        (1.0, 0.0, -4.0, [-2.0, 2.0]),
        (1.0, -2.0, 1.0, [1.0, 1.0]),  # a double root (both formulas give it)
        (1.0, 0.0, 1.0, []),
        (0.0, 2.0, -3.0, [1.5]),  # linear
        (0.0, 0.0, 1.0, []),
    ],
)
def test_scalar_quadratic_roots(a, b, c, roots):
    """``sweep._quadratic_roots`` (the scalar events' roots) against hand-solved cases."""
    got = sorted(swp._quadratic_roots(a, b, c))
    assert got == pytest.approx(roots, abs=1e-15)


def test_quick_rejection_margin_is_the_stated_bound_and_holds():
    """``Sweep.dc_margin``: every point of the swept segment lies within it of the 16-piece
    polyline of the cubic (extended to ``X + L`` when ``L^2 max|f''| / 2 < L``), measured by
    shapely on dense samples; and it is the stated bound, no looser: ``L^2 max|f''| / 2`` on
    the extended span (else ``L``) plus the polyline's chord error ``max|f''| h^2 / 8``, with
    ``max|f''|`` taken here from dense samples of the union's own ``f''``."""
    rng = np.random.default_rng(7)
    branches = set()
    for _ in range(30):  # 20 extended, 10 not
        u = random_union(rng)
        sw = swp.Sweep(u)
        L, X = u.L, u.x_end
        f2 = float(np.abs(u.second_derivative(np.linspace(0.0, X, 2001))).max())
        f2e = float(np.abs(u.second_derivative(np.linspace(0.0, X + L, 2001))).max())
        extended = 0.5 * L * L * f2e < L
        branches.add(extended)
        end, m, f2c = (X + L, 0.5 * L * L * f2e, f2e) if extended else (X, L, f2)
        assert sw.dc_end == pytest.approx(end, rel=1e-12)
        assert sw.dc_margin == pytest.approx(m + f2c * (end / 16) ** 2 / 8, rel=1e-9)
        # soundness against dense samples of the swept segment, in the frame
        px = np.linspace(0.0, sw.dc_end, 17)
        poly = shapely.LineString(np.column_stack((px, u.f(px))))
        x, fx, ux, uy = sw.segment(np.linspace(0.0, 1.0, 301))
        t = np.linspace(0.0, 1.0, 21)[:, None]
        pts = shapely.points(np.ravel(x + t * L * ux), np.ravel(fx + t * L * uy))
        assert float(shapely.distance(pts, poly).max()) <= sw.dc_margin * (1 + 1e-9)
    assert branches == {True, False}  # both bounds were checked
