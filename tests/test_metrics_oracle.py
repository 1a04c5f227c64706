"""The path oracle (segplan.viz.metrics) checked against an independent shapely computation (issue 24).

segplan.viz.metrics is the oracle every planner's output is judged by, so it is itself checked
here, on the cases where a measurement goes wrong first: a swept segment that just touches an
obstacle or a wall (distance exactly 0, and a tiny positive gap), cusps (the direction of
travel reversing, at a sample or inside a sample interval) and a turn much sharper than the
robot is long. The oracle below shares no code with segplan.viz.metrics: one shapely
``LineString`` per sampled segment A-B, measured one polygon at a time in a Python loop
(not the vectorised, unioned and prepared geometry of the module), the lengths as shapely
lengths, the reversals from the signs of the travel along the sampled headings, and, for the
continuous motion between samples, the swept region as the union of the convex hulls of
consecutive segments. The robot's body is the segment buffered by half_width.
"""

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import LineString, MultiPoint, Point, Polygon, box

import segplan
from segplan.viz.metrics import measure_path, measure_scenario_path

L = 1.0


# -- the independent oracle --------------------------------------------------------------------
def ends(P, L):
    A = P[:, :2]
    B = A + L * np.column_stack((np.cos(P[:, 2]), np.sin(P[:, 2])))
    return A, B


def segments(P, L):
    A, B = ends(P, L)
    return [LineString([tuple(a), tuple(b)]) for a, b in zip(A, B, strict=True)]


def oracle_clearance(P, L, polygons=(), bounds=None):
    """(collides, clearance) of the sampled segments, one shapely geometry at a time."""
    collides, clearance = False, math.inf
    for seg in segments(P, L):
        for poly in polygons:
            g = Polygon(poly)
            collides |= seg.intersects(g)
            clearance = min(clearance, seg.distance(g))
        if bounds is not None:
            room = box(*bounds)
            if room.contains_properly(seg):
                clearance = min(clearance, seg.distance(room.exterior))
            else:
                collides = True
                clearance = min(clearance, 0.0)
    return collides, clearance


def swept(P, L):
    """The region the segment sweeps, as the union of the hulls of consecutive sampled segments."""
    A, B = ends(P, L)
    return shapely.union_all(
        [
            MultiPoint([tuple(A[i]), tuple(B[i]), tuple(A[i + 1]), tuple(B[i + 1])]).convex_hull
            for i in range(len(A) - 1)
        ]
    )


def oracle_reversals(P):
    """Flips of the direction of travel: the sign of dA along the heading at the interval's start."""
    dA = np.diff(P[:, :2], axis=0)
    along = dA[:, 0] * np.cos(P[:-1, 2]) + dA[:, 1] * np.sin(P[:-1, 2])
    signs = [s for s in np.sign(along) if s != 0]
    return sum(a != b for a, b in zip(signs[:-1], signs[1:], strict=True))


def straight(x0, x1, y=0.0, n=101, theta=0.0):
    """A moving from x0 to x1 along y (forwards or backwards), heading theta."""
    x = np.linspace(x0, x1, n)
    return np.column_stack((x, np.full(n, y), np.full(n, theta)))


def check_against_oracle(P, L, polygons=(), bounds=None):
    m = measure_path(P, L, polygons, bounds)
    collides, clearance = oracle_clearance(P, L, polygons, bounds)
    A, B = ends(P, L)
    assert m.collides == collides
    if clearance > 0:
        assert m.clearance == pytest.approx(clearance, rel=1e-12, abs=1e-15)
    else:
        assert m.clearance <= 0.0
    assert m.rear_length == pytest.approx(LineString(A).length, rel=1e-12)
    assert m.front_length == pytest.approx(LineString(B).length, rel=1e-12)
    assert m.reversals == oracle_reversals(P)
    return m


# -- touching: distance exactly 0 and a tiny positive gap ------------------------------------------
GAPS = [0.0, 1e-12, 1e-9, 1e-6, 1e-3]


@pytest.mark.parametrize("gap", GAPS)
def test_front_wheel_stops_at_an_obstacle_face(gap):
    """A drives to x = 2, so B reaches x = 3; the obstacle's face is at x = 3 + gap."""
    face = 3.0 + gap
    wall = np.array([[face, -1.0], [face + 1.0, -1.0], [face + 1.0, 1.0], [face, 1.0]])
    m = check_against_oracle(straight(0.0, 2.0), L, [wall])
    assert m.collides == (gap == 0.0)
    assert m.clearance == pytest.approx(gap, abs=1e-15)


@pytest.mark.parametrize("gap", GAPS)
def test_segment_grazes_a_vertex(gap):
    """A triangle's apex at distance gap below the segment's interior (not at a sample's end)."""
    tri = np.array([[2.5, -gap], [3.0, -1.0], [2.0, -1.0]])
    m = check_against_oracle(straight(0.0, 4.0, n=41), L, [tri])
    assert m.collides == (gap == 0.0)
    assert m.clearance == pytest.approx(gap, abs=1e-15)


@pytest.mark.parametrize("gap", GAPS)
def test_diagonal_path_touches_a_corner(gap):
    """Heading 45 deg; a square's corner on the path's line, moved off it by gap along the normal."""
    c = math.sqrt(0.5)
    t = np.linspace(0.0, 3.0, 61)
    P = np.column_stack((c * t, c * t, np.full(t.size, math.pi / 4)))
    corner = np.array([2.0 * c, 2.0 * c]) + gap * np.array([c, -c])  # below-right of the line
    # an axis-aligned square hanging from that corner: every point of it is at least gap from the line
    sq = np.array([corner, corner + [1.0, 0.0], corner + [1.0, -1.0], corner + [0.0, -1.0]])
    m = check_against_oracle(P, L, [sq])
    if gap >= 1e-9:  # below that the diagonal's rounding decides
        assert not m.collides and m.clearance == pytest.approx(gap, rel=1e-4)


@pytest.mark.parametrize("gap", GAPS)
def test_walls_touched_by_the_front_wheel(gap):
    """B reaches x = 3; the right wall at 3 + gap: touching a wall counts (strictly inside)."""
    bounds = (-1.0, -1.0, 3.0 + gap, 1.0)
    m = check_against_oracle(straight(0.0, 2.0), L, bounds=bounds)
    assert m.collides == (gap == 0.0)
    assert m.clearance == pytest.approx(gap, abs=1e-15)


@pytest.mark.parametrize("gap", [0.0, 1e-9, 1e-6, 1e-3, 0.02])
def test_scenario_path_against_the_buffered_body(gap):
    """measure_scenario_path (enlarged obstacles) against the real body: the segment buffered by
    half_width, at distance gap from a raw square beside its straight path."""
    hw = 0.35
    robot = segplan.Robot(L, hw)
    sq = np.array([[2.0, hw + gap], [3.0, hw + gap], [3.0, hw + gap + 1.0], [2.0, hw + gap + 1.0]])
    P = straight(0.0, 4.0, n=401)
    sc = segplan.make_scenario(robot, tuple(P[0]), tuple(P[-1]), [sq], bounds=(-2.0, -3.0, 7.0, 4.0))
    m = measure_scenario_path(P, sc)
    square = Polygon(sq)
    bodies = [s.buffer(hw, quad_segs=64) for s in segments(P, L)]
    gap_real = min(b.distance(square) for b in bodies)
    assert gap_real == pytest.approx(gap, abs=1e-6)  # the buffer's polygon approximates the disc
    # the model's clearance is a lower bound of the real gap, within the enlargement's excess
    assert m.clearance <= gap_real + 1e-6
    assert gap_real <= m.clearance + 0.0824 * hw + 1e-6
    # along an edge (not at a corner) the enlargement is exact
    assert m.clearance == pytest.approx(gap, abs=1e-12)
    assert m.collides == (gap == 0.0)
    # anything touching the real body is a collision of the model
    if any(b.intersects(square) for b in bodies):
        assert m.collides


def test_corner_excess_is_conservative():
    """Passing a square's corner diagonally: the model may report a collision the body misses,
    never the other way round; its clearance stays within the enlargement's excess."""
    hw = 0.35
    robot = segplan.Robot(L, hw)
    c = math.sqrt(0.5)
    for gap in (0.0, 0.01, 0.02, 0.05, 0.2):
        # the corner (2, 2) + d (c, -c), d = hw + gap: the body's gap to it is gap
        d = hw + gap
        corner = np.array([2.0 + d * c, 2.0 - d * c])
        sq = np.array([corner, corner + [1.0, 0.0], corner + [1.0, -1.0], corner + [0.0, -1.0]])
        t = np.linspace(0.0, 4.0, 401)
        P = np.column_stack((c * t, c * t, np.full(t.size, math.pi / 4)))
        sc = segplan.make_scenario(robot, tuple(P[0]), tuple(P[-1]), [sq])
        m = measure_scenario_path(P, sc)
        gap_real = min(s.buffer(hw, quad_segs=64).distance(Polygon(sq)) for s in segments(P, L))
        assert m.clearance <= gap_real + 1e-4
        assert gap_real <= max(m.clearance, 0.0) + 0.0824 * hw + 1e-4
        if gap_real <= 1e-4:
            assert m.collides


# -- cusps ---------------------------------------------------------------------------------------
def test_cusp_at_a_sample_touching_an_obstacle():
    """Forward until B touches the face at x = 3, then back: the touch is at the cusp's sample."""
    face = np.array([[3.0, -1.0], [4.0, -1.0], [4.0, 1.0], [3.0, 1.0]])
    P = np.concatenate((straight(0.0, 2.0), straight(2.0, 0.5)[1:]))
    m = check_against_oracle(P, L, [face])
    assert m.reversals == 1 and m.collides and m.clearance == 0.0
    assert m.rear_length == pytest.approx(3.5) and m.front_length == pytest.approx(3.5)


def test_cusp_inside_a_sample_interval():
    """The cusp falls between two samples: the sampled measurement sees the samples (and agrees
    with the oracle on them) and overestimates the continuous clearance by less than a step."""
    turn_back = 2.0 + 1e-3  # A's farthest x, between samples spaced 0.02
    x_fwd = np.arange(0.0, turn_back, 0.02)
    x_back = turn_back - (np.arange(0.0, turn_back - 0.5, 0.02) + (turn_back - x_fwd[-1]) + 0.005)
    x = np.concatenate((x_fwd, x_back))
    P = np.column_stack((x, np.zeros(x.size), np.zeros(x.size)))
    face_x = 3.0 + turn_back - 2.0 + 1e-4  # the continuous motion's B stops 1e-4 short of the face
    face = np.array([[face_x, -1.0], [face_x + 1.0, -1.0], [face_x + 1.0, 1.0], [face_x, 1.0]])
    m = check_against_oracle(P, L, [face])
    assert m.reversals == 1
    continuous = 1e-4
    assert not m.collides and continuous <= m.clearance <= continuous + 0.5 * m.step
    # the swept region of the samples' hulls misses the part of the motion past the last sample
    assert swept(P, L).distance(Polygon(face)) == pytest.approx(m.clearance, abs=1e-12)


def test_three_point_turn_reversals_and_lengths():
    """Forward-left, reverse-right, forward: two cusps; lengths are the shapely polylines'."""
    R = 1.5
    th = np.linspace(0.0, 1.0, 201)
    leg1 = np.column_stack((R * np.sin(th), R * (1.0 - np.cos(th)), th))
    # reversing on a right lock: the heading keeps increasing while A moves backwards
    c1 = leg1[-1]
    centre = c1[:2] + R * np.array([math.sin(c1[2]), -math.cos(c1[2])])
    phi = c1[2] + th
    leg2 = np.column_stack((centre[0] - R * np.sin(phi), centre[1] + R * np.cos(phi), phi))
    c2 = leg2[-1]
    s = np.linspace(0.0, 2.0, 101)
    leg3 = np.column_stack((c2[0] + s * math.cos(c2[2]), c2[1] + s * math.sin(c2[2]), np.full(s.size, c2[2])))
    P = np.concatenate((leg1, leg2[1:], leg3[1:]))
    block = np.array([[-1.0, 3.0], [3.0, 3.0], [3.0, 4.0], [-1.0, 4.0]])
    m = check_against_oracle(P, L, [block], bounds=(-3.0, -3.0, 6.0, 6.0))
    assert m.reversals == 2
    assert m.rear_length == pytest.approx(2 * R * 1.0 + 2.0, rel=1e-4)
    assert m.max_curvature == pytest.approx(1.0 / R, rel=1e-3)


# -- sharp curvature: a turn of radius R much shorter than L ----------------------------------------
@pytest.mark.parametrize("R", [0.05, 0.2])
def test_sharp_turn_sweeps_an_annulus(R):
    """A full left turn of radius R about (0, R): the segment sweeps the annulus
    R <= r <= sqrt(R^2 + L^2) (A tangent, so the segment's nearest point to the centre is A)."""
    th = np.linspace(0.0, 2.0 * math.pi, 721)
    P = np.column_stack((R * np.sin(th), R * (1.0 - np.cos(th)), th))
    outer = math.hypot(R, L)
    centre = np.array([0.0, R])
    h = 0.01
    inner_sq = centre + np.array([[-h, -h], [h, -h], [h, h], [-h, h]])  # in the annulus' hole
    g = 0.01
    out_sq = centre + np.array([[outer + g, -0.2], [outer + 1.0, -0.2], [outer + 1.0, 0.2], [outer + g, 0.2]])
    m = check_against_oracle(P, L, [inner_sq, out_sq])
    half = 0.5 * (th[1] - th[0])  # the estimate dtheta / chord of a sampled circle
    assert m.max_curvature == pytest.approx(half / math.sin(half) / R, rel=1e-9)
    assert m.front_length == pytest.approx(outer * 2.0 * math.pi, rel=1e-4)
    assert m.rear_length == pytest.approx(R * 2.0 * math.pi, rel=1e-4)
    assert not m.collides
    continuous = min(R - math.hypot(h, h), g)
    assert continuous - 1e-12 <= m.clearance <= continuous + 0.5 * m.step
    region = swept(P, L)
    assert region.distance(Point(*centre)) == pytest.approx(R, rel=1e-4)
    assert region.distance(Polygon(out_sq)) == pytest.approx(g, abs=m.step)
    # an obstacle across the outer circle is hit, one inside the annulus too
    hit = centre + np.array(
        [[outer - 1e-3, -0.01], [outer + 1.0, -0.01], [outer + 1.0, 0.01], [outer - 1e-3, 0.01]]
    )
    assert check_against_oracle(P, L, [hit]).collides


# -- random paths and floors: the module and the loop agree to the last bits ------------------------
@settings(max_examples=30, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n_obst=st.integers(1, 4),
    reverse_at=st.integers(-1, 39),
)
def test_random_paths_agree_with_the_oracle(seed, n_obst, reverse_at):
    rng = np.random.default_rng(seed)
    steps = rng.uniform(0.05, 0.3, 40)
    if reverse_at >= 0:
        steps[reverse_at:] *= -1.0  # a cusp
    theta = np.cumsum(np.concatenate(([rng.uniform(-math.pi, math.pi)], rng.uniform(-0.3, 0.3, 40))))
    A = np.cumsum(np.column_stack((steps * np.cos(theta[:-1]), steps * np.sin(theta[:-1]))), axis=0)
    A = np.concatenate(([[0.0, 0.0]], A))
    P = np.column_stack((A, theta))
    polys = []
    for _ in range(n_obst):
        c = rng.uniform(-5.0, 5.0, 2)
        polys.append(
            np.asarray(MultiPoint(c + rng.uniform(-1.0, 1.0, (6, 2))).convex_hull.exterior.coords)[:-1]
        )
    bounds = (
        *(A.min(axis=0) - 2.0 + rng.uniform(-1.0, 1.5, 2)),
        *(A.max(axis=0) + 2.0 + rng.uniform(-1.5, 1.0, 2)),
    )
    check_against_oracle(P, L, polys, bounds)
