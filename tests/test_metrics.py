"""The shared path measurement (segplan.viz.metrics) against analytic cases and independent oracles."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

import segplan
from segplan.viz.metrics import measure_path, measure_scenario_path, plan_poses, se2_poses, union_poses


def line(d: float, n: int = 101, theta: float = 0.0, start=(0.0, 0.0)) -> np.ndarray:
    t = np.linspace(0.0, d, n)
    return np.column_stack(
        (start[0] + t * math.cos(theta), start[1] + t * math.sin(theta), np.full(n, theta))
    )


def arc(R: float, sweep: float, n: int = 2001, sign: float = 1.0) -> np.ndarray:
    """A left (sign +1) or right (-1) turn of radius R from the origin heading +x."""
    t = np.linspace(0.0, sweep, n)
    return np.column_stack((R * np.sin(t), sign * R * (1.0 - np.cos(t)), sign * t))


def test_straight_line_front_equals_rear_equals_d():
    m = measure_path(line(7.5), L=1.2)
    assert m.front_length == pytest.approx(7.5, rel=1e-12)
    assert m.rear_length == pytest.approx(7.5, rel=1e-12)
    assert m.max_curvature == 0.0
    assert m.curvature_jumps == 0 and m.reversals == 0
    assert not m.collides and m.clearance == math.inf


@settings(max_examples=25)
@given(
    R=st.floats(0.5, 20.0),
    sweep=st.floats(0.1, 2.0 * math.pi),
    L=st.floats(0.2, 3.0),
    sign=st.sampled_from([-1.0, 1.0]),
)
def test_circular_arc(R, sweep, L, sign):
    m = measure_path(arc(R, sweep, sign=sign), L=L)
    assert m.rear_length == pytest.approx(R * sweep, rel=1e-6)  # R theta
    assert m.front_length == pytest.approx(math.hypot(R, L) * sweep, rel=1e-6)  # sqrt(R^2 + L^2) theta
    assert m.max_curvature == pytest.approx(1.0 / R, rel=1e-6)
    assert m.curvature_jump < 1e-6 / R and m.curvature_jumps == 0
    assert m.reversals == 0


def test_line_then_arc_has_one_jump_of_one_over_r():
    R, L = 2.0, 1.0
    a = arc(R, math.pi / 2)
    a[:, 0] += 3.0
    path = np.concatenate((line(3.0, 301), a[1:]))
    m = measure_path(path, L=L)
    assert m.curvature_jumps == 1
    assert m.curvature_jump == pytest.approx(1.0 / R, rel=1e-6)
    assert m.front_length == pytest.approx(3.0 + math.hypot(R, L) * math.pi / 2, rel=1e-6)


def test_jump_inside_a_sample_interval_is_caught():
    """A junction that falls between two samples still shows its full jump."""
    R = 1.5
    s = np.linspace(0.0, 6.0, 601) + 0.004  # the junction at s = 3 lies strictly inside an interval
    s = s[s <= 6.0]
    xy = np.where(s[:, None] <= 3.0, np.column_stack((s, 0 * s)), 0.0)
    t = np.clip(s - 3.0, 0.0, None) / R
    xy = np.where(s[:, None] <= 3.0, xy, np.column_stack((3.0 + R * np.sin(t), R * (1.0 - np.cos(t)))))
    m = measure_path(np.column_stack((xy, t)), L=1.0)
    assert m.curvature_jumps == 1
    assert m.curvature_jump == pytest.approx(1.0 / R, rel=1e-5)  # chord/arc of one interval: 2e-6


def test_reversal_counts_cusps_and_keeps_steering_curvature():
    forward = line(2.0, 201)
    back = forward[::-1][1:]  # back the way it came, heading unchanged
    m = measure_path(np.concatenate((forward, back)), L=1.0)
    assert m.reversals == 1
    assert m.rear_length == pytest.approx(4.0)
    # a Reeds-Shepp cusp L+ | R- inside a sample interval: the heading keeps turning left while A
    # comes back; steering curvature +1/R, then -1/R (right lock, reversing)
    R = 2.0
    th = np.linspace(0.0, 2.0, 201) + 0.004
    th = th[th < 2.0]
    fwd = np.column_stack((R * np.sin(th), R * (1.0 - np.cos(th))))
    cusp = np.array([R * math.sin(1.0), R * (1.0 - math.cos(1.0))])
    back = cusp - R * np.column_stack((np.sin(th) - math.sin(1.0), math.cos(1.0) - np.cos(th)))
    A = np.where((th <= 1.0)[:, None], fwd, back)
    m = measure_path(np.column_stack((A, th)), L=1.0)
    assert m.reversals == 1
    assert m.max_curvature == pytest.approx(1.0 / R, rel=1e-4)
    assert m.curvature_jumps == 1 and m.curvature_jump == pytest.approx(2.0 / R, rel=1e-4)
    # two cusps inside one interval (a back-and-forth shorter than the sample spacing) leave a
    # fold: a chord much shorter than its neighbours'. The curvature ignores it.
    R = 2.0
    a = arc(R, 1.0, n=201)
    chord = a[101, :2] - a[100, :2]
    a[101:, :2] -= 0.8 * chord  # interval 100 keeps its heading change on a fifth of its chord
    assert measure_path(a, L=1.0).max_curvature == pytest.approx(1.0 / R, rel=1e-4)
    # reversing along a left arc: the heading *decreases* as A moves backwards, steering stays left
    a = arc(2.0, 1.0)
    m = measure_path(a[::-1], L=1.0)
    assert m.reversals == 0  # one direction throughout (backwards)
    assert m.max_curvature == pytest.approx(0.5, rel=1e-6)


def test_clearance_and_collision_against_a_square_and_walls():
    square = np.array([[2.0, 1.0], [3.0, 1.0], [3.0, 2.0], [2.0, 2.0]])
    path = line(5.0, 501, start=(0.0, 0.0))  # A from x=0 to x=5, B one metre ahead
    m = measure_path(path, 1.0, [square])
    assert not m.collides and m.clearance == pytest.approx(1.0)
    m = measure_path(path, 1.0, [square], bounds=(-1.0, -0.25, 7.0, 3.0))
    assert not m.collides and m.clearance == pytest.approx(0.25)  # the wall below
    m = measure_path(path, 1.0, [square], bounds=(-1.0, -0.25, 5.5, 3.0))
    assert m.collides and m.clearance == pytest.approx(-0.5)  # B leaves through the right wall
    m = measure_path(line(5.0, 501, start=(0.0, 1.0)), 1.0, [square])
    assert m.collides and m.clearance == 0.0  # touching the square's lower edge counts


def test_validation():
    with pytest.raises(ValueError, match="poses"):
        measure_path(np.zeros((1, 3)), 1.0)
    with pytest.raises(ValueError, match="poses"):
        measure_path(np.zeros((4, 2)), 1.0)
    with pytest.raises(ValueError, match="poses"):
        measure_path([[0, 0, 0], [1, 0, np.nan]], 1.0)
    with pytest.raises(ValueError, match="L"):
        measure_path(line(1.0), 0.0)
    with pytest.raises(ValueError, match="bounds"):
        measure_path(line(1.0), 1.0, bounds=(0, 0, -1, 1))
    with pytest.raises(ValueError, match="jump_tol"):
        measure_path(line(1.0), 1.0, jump_tol=-1.0)
    with pytest.raises(ValueError, match="step"):
        union_poses(segplan.Union((0, 0, 0), (3, 1, 0), 0.0, 1.0), step=0.0)
    with pytest.raises(ValueError, match="union"):
        union_poses("not a union")
    with pytest.raises(ValueError, match="states"):
        se2_poses([])


def test_turn_on_the_spot_is_infinite_curvature():
    path = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 0.5], [1.0, 0.0, 0.5]])
    assert measure_path(path, 1.0).max_curvature == math.inf


# -- segplan unions: against LONGD [1] (Romberg) and quad -------------------------------------
@settings(max_examples=15)
@given(
    x=st.floats(2.0, 8.0),
    y=st.floats(-3.0, 3.0),
    th0=st.floats(-0.7, 0.7),
    th1=st.floats(-0.7, 0.7),
    L=st.floats(0.5, 2.0),
)
def test_union_lengths_match_longd_and_quad(x, y, th0, th1, L):
    p0, p1 = segplan.Pose(0.0, 0.0, th0), segplan.Pose(x, y, th1)
    u = segplan.Union(p0, p1, 0.0, L)
    m = measure_path(union_poses(u, step=0.005), L)
    assert m.front_length == pytest.approx(segplan.longd_exact(p0, p1, 0.0, L, rtol=1e-10), rel=1e-5)
    rear, _ = quad(lambda s: math.sqrt(1.0 + float(u.slope(s)) ** 2), 0.0, u.x_end, epsabs=0, epsrel=1e-11)
    assert m.rear_length == pytest.approx(rear, rel=1e-5)
    assert m.max_curvature == pytest.approx(u.max_curvature(), rel=1e-3, abs=1e-4)
    assert m.curvature_jumps == 0 and m.reversals == 0
    assert m.step <= 0.005 * 1.001


def test_two_unions_jump_at_their_node_by_the_difference_of_end_curvatures():
    L = 1.0
    a, b, c = segplan.Pose(0, 0, 0.0), segplan.Pose(4, 1, 0.3), segplan.Pose(8, 0, -0.2)
    u1, u2 = segplan.Union(a, b, 0.0, L), segplan.Union(b, c, 0.0, L)
    P = plan_poses([u1, u2], step=0.005)
    assert np.allclose(P[0], a) and np.allclose(P[-1], c)
    assert len(P) == len(union_poses(u1, 0.005)) + len(union_poses(u2, 0.005)) - 1  # node kept once
    m = measure_path(P, L)
    expected = abs(float(u1.curvature(u1.x_end)) - float(u2.curvature(0.0)))
    assert expected > 0.1 / L
    assert m.curvature_jumps == 1
    assert m.curvature_jump == pytest.approx(expected, rel=0.02)
    assert m.front_length == pytest.approx(
        segplan.longd_exact(a, b, 0.0, L) + segplan.longd_exact(b, c, 0.0, L), rel=1e-5
    )


class _State:
    def __init__(self, x, y, yaw):
        self.x, self.y, self.yaw = x, y, yaw

    def getX(self):  # noqa: N802 (OMPL's names)
        return self.x

    def getY(self):  # noqa: N802
        return self.y

    def getYaw(self):  # noqa: N802
        return self.yaw


def test_se2_poses_reads_getters():
    P = se2_poses([_State(0, 1, 0.5), _State(2, 3, -0.5)])
    assert P.tolist() == [[0, 1, 0.5], [2, 3, -0.5]]


def test_measure_scenario_path_uses_the_enlarged_model():
    sc = segplan.load_scenario(_scenario("single_obstacle.json"))
    P = line(1.0, 11, start=(sc.start.x, sc.start.y))
    m = measure_scenario_path(P, sc)
    direct = measure_path(P, sc.L, sc.enlarged, sc.free_bounds)
    assert m == direct and not m.collides


def _scenario(name):
    from pathlib import Path

    return Path(__file__).resolve().parents[1] / "scenarios" / name
