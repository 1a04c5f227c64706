"""Issue 26: plans with reverse links sampled and timed in driving order (Plan.poses, Plan.trajectory).

Oracles that do not share the code under test:

- a forward plan's unions driven backwards from its goal to its start (every link reverse):
  the samples must be the forward samples in the reverse order, and the time law the forward
  law played backwards (the limits are the same both ways);
- the bicycle model ``x' = v cos theta, y' = v sin theta, theta' = v tan(steer) / L``
  integrated with ``v = -1`` (scipy ``solve_ivp``) under the sampled steering angles: it
  must drive each backward link from its near node to its far node (and does not with the
  opposite sign);
- the limits on a dense resampling of every union in driving order, as tests/test_trajectory.py.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from test_trajectory import _dense_worst

import segplan
from segplan.planning.plan import lattice_plan
from segplan.planning.trajectory import POSE_COLUMNS, TRAJECTORY_COLUMNS, sample_path, time_law

LIMITS = [(1.0, 0.5, 0.5, math.radians(30)), (3.0, 2.0, 5.0, 0.1), (0.5, 0.1, 0.05, 2.0)]


@pytest.fixture(scope="module")
def bay():
    sc = segplan.load_scenario("dead_end_bay")
    plan = segplan.plan_scenario(sc)
    assert plan.cusps
    return sc, plan


@pytest.fixture(scope="module")
def forward():
    return segplan.plan_scenario(segplan.load_scenario("turn_around"))


def test_samples_follow_the_robot_in_driving_order(bay):
    sc, plan = bay
    P = plan.poses()
    assert tuple(P.columns()) == POSE_COLUMNS
    assert np.all(np.diff(P.s) >= 0) and P.s[0] == 0.0
    assert np.allclose((P.x[0], P.y[0], P.theta[0]), tuple(sc.start), atol=1e-12)
    assert np.allclose((P.x[-1], P.y[-1], math.remainder(P.theta[-1] - sc.goal.theta, 2 * math.pi)),
                       (sc.goal.x, sc.goal.y, 0.0), atol=1e-12)  # fmt: skip
    assert np.array_equal(P.direction, np.array(plan.link_directions)[P.union])
    for k, node in enumerate(plan.nodes[:-1]):  # each link starts at its node
        i = np.flatnonzero(P.union == k)[0]
        assert (P.x[i], P.y[i]) == (node.x, node.y)
        assert math.remainder(P.theta[i] - node.theta, 2 * math.pi) == pytest.approx(0.0, abs=1e-12)
    assert np.hypot(np.diff(P.x), np.diff(P.y)).max() <= P.step * (1 + 1e-9)
    assert np.abs(np.diff(P.theta)).max() < 0.1  # the heading is continuous, also at the cusp
    facts = plan.facts()
    assert P.s[-1] == pytest.approx(facts.rear_length, rel=1e-9)
    nodes = np.flatnonzero(np.diff(P.s) == 0)  # the two rows of each interior node
    assert np.allclose(np.diff(P.steer)[nodes], facts.steer_jump[1:-1], atol=1e-12)


def test_a_plan_driven_backwards_is_the_forward_samples_reversed(forward):
    unions = forward.unions
    ahead = sample_path(unions, 0.05)
    back = sample_path(unions[::-1], 0.05, (-1,) * len(unions))
    assert np.all(back.direction == -1) and np.all(ahead.direction == 1)
    for name in ("x", "y", "x_front", "y_front", "kappa", "steer", "frame_x"):
        assert np.allclose(getattr(back, name), getattr(ahead, name)[::-1], atol=1e-12), name
    turn = back.theta - ahead.theta[::-1]
    assert np.allclose(turn, turn[0], atol=1e-12) and math.remainder(turn[0], 2 * math.pi) == pytest.approx(
        0.0
    )
    assert np.allclose(back.s, ahead.s[-1] - ahead.s[::-1], atol=1e-9)
    # forward: an explicit all-forward direction changes nothing, bit for bit
    same = sample_path(unions, 0.05, (1,) * len(unions))
    assert all(np.array_equal(getattr(same, n), getattr(ahead, n)) for n in POSE_COLUMNS)


def _drive_back(s, steer, q0, L, sign=1.0):
    """The bicycle model with v = -1 from the pose ``q0`` over the travelled length ``s[-1]``,
    steering ``sign * steer`` interpolated in ``s``: the final pose (x, y, theta)."""

    def rhs(t, q):
        delta = sign * np.interp(t, s, steer)
        return [-math.cos(q[2]), -math.sin(q[2]), -math.tan(delta) / L]

    return solve_ivp(rhs, (0.0, s[-1]), q0, rtol=1e-10, atol=1e-12, max_step=0.01).y[:, -1]


def test_the_steering_drives_the_bicycle_model_backwards(bay):
    """Integrate the bicycle model with v = -1 under the samples' steering angles: it lands on the
    link's far node; with the steering's sign flipped it does not (the sign is derived, not free)."""
    _, plan = bay
    P = plan.poses(0.005)
    backward = [k for k, d in enumerate(plan.link_directions) if d < 0]
    assert backward
    flipped_tested = False
    for k in backward:
        rows = np.flatnonzero(P.union == k)
        s, steer = P.s[rows] - P.s[rows[0]], P.steer[rows]
        q0 = [P.x[rows[0]], P.y[rows[0]], P.theta[rows[0]]]
        far = plan.nodes[k + 1]
        end = _drive_back(s, steer, q0, P.L)
        error = math.hypot(end[0] - far.x, end[1] - far.y)
        assert error < 1e-3 and abs(math.remainder(end[2] - far.theta, 2 * math.pi)) < 1e-3
        if plan.unions[k].max_curvature() > 0.05:
            flipped = _drive_back(s, steer, q0, P.L, -1.0)
            assert math.hypot(flipped[0] - far.x, flipped[1] - far.y) > 10 * max(error, 1e-4)
            flipped_tested = True
    assert flipped_tested


@pytest.mark.parametrize("limits", LIMITS)
def test_the_robot_stops_at_each_cusp_and_keeps_every_limit(bay, limits):
    _, plan = bay
    law = plan.trajectory(*limits)
    assert tuple(law.columns()) == TRAJECTORY_COLUMNS and law.cusps == len(plan.cusps)
    assert np.all(law.v * law.direction >= 0) and (law.v < 0).any() and (law.v > 0).any()
    gear = np.flatnonzero(np.diff(law.direction) != 0)
    assert gear.size == len(plan.cusps)
    for i in gear:  # the cusp's two rows: standing, re-steering for the step of the steering
        assert law.v[i] == law.v[i + 1] == 0.0 and law.s[i] == law.s[i + 1]
        jump = abs(law.steer[i + 1] - law.steer[i])
        assert law.t[i + 1] - law.t[i] == pytest.approx(jump / law.steer_rate_max, rel=1e-12, abs=1e-15)
    assert law.v[0] == law.v[-1] == 0.0 and law.total_time == law.t[-1]
    worst = _dense_worst(plan, law)
    assert worst["v"] <= 1 + 1e-9 and worst["a"] <= 1 + 1e-9, worst
    assert worst["lat"] <= 1 + 1e-6 and worst["rate"] <= 1 + 1e-6, worst
    dt, ds = np.diff(law.t), np.diff(law.s)
    travelled = np.sum(0.5 * np.abs(law.v[:-1] + law.v[1:]) * dt)  # int |v| dt, exact for constant a
    assert travelled == pytest.approx(plan.facts().rear_length, rel=1e-9)
    moving = ds > 0
    assert np.allclose(law.v[1:][moving], (law.v[:-1] + law.a[:-1] * dt)[moving], rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("limits", LIMITS)
def test_a_plan_driven_backwards_takes_the_forward_time(forward, limits):
    """The limits are the same both ways: the forward law, played backwards, with v negated."""
    ahead = forward.trajectory(*limits)
    back = time_law(forward.unions[::-1], *limits, directions=(-1,) * len(forward.unions))
    assert back.total_time == pytest.approx(ahead.total_time, rel=1e-9)
    assert np.allclose(back.v, -ahead.v[::-1], atol=1e-9) and back.cusps == 0 and back.jumps == ahead.jumps


def test_a_cusp_is_a_stop_even_without_a_steering_step(bay):
    """A cusp whose steering step is called rounding (jump_tol above every step): v is still 0
    there, and the jump cost excludes it."""
    _, plan = bay
    law = plan.trajectory(*LIMITS[0], jump_tol=math.pi)
    assert law.jumps == 0 and law.jump_time == 0.0 == law.dwell_time and law.cusps == 1
    i = np.flatnonzero(np.diff(law.direction) != 0)[0]
    assert law.v[i] == law.v[i + 1] == 0.0 and law.t[i] == law.t[i + 1]


def test_reverse_exports_carry_the_direction(bay, tmp_path):
    _, plan = bay
    law = plan.trajectory(*LIMITS[0])
    law.to_csv(tmp_path / "t.csv")
    table = np.genfromtxt(tmp_path / "t.csv", delimiter=",", names=True)
    assert np.array_equal(table["direction"], law.direction) and np.array_equal(table["v"], law.v)
    message = law.nav_path()
    assert len(message["poses"]) >= len(law) - 2 * len(plan.nodes)


def test_bad_directions_are_named(bay):
    _, plan = bay
    with pytest.raises(ValueError, match="directions"):
        sample_path(plan.unions, 0.05, (1,))
    with pytest.raises(ValueError, match="directions"):
        time_law(plan.unions, *LIMITS[0], directions=(2,) * len(plan.unions))


def test_a_hand_made_plan_reports_its_directions():
    """lattice_plan's directions reach the samples (the nodes from link_ends)."""
    u = segplan.plan_scenario(segplan.load_scenario("fig5_example1")).unions[0]
    stats = type("S", (), {"collision_checks": 0, "exact_checks": 0})()
    plan = lattice_plan(u.p1, [u], ["start", "goal"], 1.0, 1.0, 0, 0, 0.0, stats, directions=(-1,))
    P = plan.poses()
    assert (P.x[0], P.y[0], P.x[-1], P.y[-1]) == (u.p1.x, u.p1.y, u.p0.x, u.p0.y) and set(P.direction) == {-1}


def test_the_command_line_summarises_and_exports_a_reverse_plan(tmp_path, capsys):
    from segplan.cli import main

    files = {flag: tmp_path / name for flag, name in (("--poses", "p.csv"), ("--trajectory", "t.csv"))}
    args = [str(x) for pair in files.items() for x in pair]
    assert main(["plan", "dead_end_bay", *args, "--nav-path", str(tmp_path / "n.yaml")]) == 0
    text = capsys.readouterr().out
    assert "cusps: 1)" in text and "(cusp)" in text and "stops at cusps: 1" in text
    assert "(reversing to it)" in text and text.count(", cusp\n") == 1
    poses = np.genfromtxt(files["--poses"], delimiter=",", names=True)
    law = np.genfromtxt(files["--trajectory"], delimiter=",", names=True)
    assert set(poses["direction"]) == {-1, 1} and np.all(np.diff(poses["s"]) >= 0)
    assert np.all(law["v"] * law["direction"] >= 0) and law["v"].min() < 0
    assert main(["plan", "fig5_example1", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["plan_facts"]["cusps"] == []
