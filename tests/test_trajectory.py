"""Trajectories out (issue 27): Plan.poses, Plan.trajectory, Plan.facts, Plan.save/load, exports.

Each claim is checked against an oracle that does not share the code under test:

- the samples against the union's own sampling (``Union.rear``/``front`` polylines), the arc
  length against ``scipy.integrate.quad`` and ``segplan.measure_path``, the curvature against
  the circle through three consecutive samples (positions only);
- the time law against every limit on a dense resampling of each union (its own arc length by
  the trapezoid rule, the steering slope by finite differences), with the speed between two
  samples from the constant acceleration of the law: tolerance ``1e-9`` relative for the
  speed and the acceleration (rounding), ``1e-6`` where finite differences enter;
  against the closed form on a straight line (the trapezoidal profile);
- the saved plan against itself, every float by ``float.hex`` (hypothesis over plans of
  several floors and over random chains built by both union constructors);
- the nav_msgs poses against the headings (unit quaternions, ``2 atan2(z, w) = theta``).
"""

from __future__ import annotations

import dataclasses
import json
import math
import pickle
import types

import numpy as np
import pandas as pd
import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

import segplan
from segplan import Plan, Pose, Union
from segplan.model.pose import alpha_interval, intrinsic, wrap
from segplan.planning.options import (
    DefaultOptions,
    LatticeOptions,
    PaperOptions,
    RefineOptions,
    options_from_dict,
)
from segplan.planning.plan import lattice_plan, plan_from_record, plan_record, unions_longd
from segplan.planning.trajectory import POSE_COLUMNS, TRAJECTORY_COLUMNS, interval_bounds
from segplan.viz.metrics import measure_scenario_path, plan_poses

#: The search counters of a plan made here by hand (:func:`lattice_plan` reads them).
STATS = types.SimpleNamespace(collision_checks=0, exact_checks=0)

LIMITS = [  # (v_max, a_max, a_lat_max, steer_rate_max): each limit binding somewhere
    (1.0, 0.5, 0.5, math.radians(30)),
    (3.0, 2.0, 5.0, 0.1),
    (0.5, 0.1, 0.05, 2.0),
]


@pytest.fixture(scope="module")
def floors():
    names = ["fig5_example1", "turn_around", "l_shaped_rack"]
    return {name: segplan.load_scenario(name) for name in names} | {"random": segplan.random_world(3, 5)}


@pytest.fixture(scope="module")
def plans(floors):
    """Plans of four floors by both planners (the paper's search fails on l_shaped_rack)."""
    out = {}
    for name, sc in floors.items():
        for planner in ("lattice", "paper"):
            if (name, planner) != ("l_shaped_rack", "paper"):
                out[name, planner] = segplan.plan_scenario(sc, planner=planner)
    return out


def _union_rows(samples, k):
    return np.flatnonzero(samples.union == k)


# -- samples ------------------------------------------------------------------------------------------
def test_samples_lie_on_the_unions_rear_and_front_paths(plans):
    plan = plans["fig5_example1", "lattice"]
    P = plan.poses(0.05)
    assert tuple(P.columns()) == POSE_COLUMNS and len(P) == P.s.size
    for k, u in enumerate(plan.unions):
        rows = _union_rows(P, k)
        for samples, dense in (((P.x, P.y), u.rear(40001)), ((P.x_front, P.y_front), u.front(40001))):
            pts = np.column_stack([c[rows] for c in samples])
            gap = np.min(np.hypot(*(pts[:, None, :] - dense[None, ::4, :]).transpose(2, 0, 1)), axis=1)
            assert gap.max() < 2e-3  # nearest of every 4th dense point: within one dense spacing
            dist = np.array([_distance_to_polyline(p, dense) for p in pts])
            assert dist.max() < 1e-7, dist.max()
        assert np.allclose(wrap(P.theta[rows] - u.heading(P.frame_x[rows])), 0.0, atol=1e-12)


def _distance_to_polyline(p, line):
    i = int(np.argmin(np.hypot(*(line - p).T)))
    best = math.inf
    for j in (i - 1, i):
        if 0 <= j < len(line) - 1:
            a, b = line[j], line[j + 1]
            t = np.clip(np.dot(p - a, b - a) / np.dot(b - a, b - a), 0.0, 1.0)
            best = min(best, float(np.hypot(*(a + t * (b - a) - p))))
    return best


def test_arc_length_is_the_integral_and_the_spacing_the_step(plans):
    plan = plans["turn_around", "paper"]
    step = 0.07
    P = plan.poses(step)
    for k, u in enumerate(plan.unions):
        rows = _union_rows(P, k)
        ds = np.diff(P.s[rows])
        assert ds.max() <= step and np.allclose(ds, ds[0], rtol=1e-12, atol=0) and rows.size >= 3
        s0 = P.s[rows[0]]

        def speed(x, u=u):
            return math.sqrt(1.0 + float(u.slope(x)) ** 2)  # ds/dx

        for i in rows[1:]:
            exact = quad(speed, 0.0, P.frame_x[i], epsabs=1e-13)[0]
            assert P.s[i] - s0 == pytest.approx(exact, rel=1e-9, abs=1e-12)


def test_lengths_agree_with_measure_path_and_the_cost(plans):
    for plan in plans.values():
        P = plan.poses(0.01)
        m = segplan.measure_path(plan_poses(plan, 0.005), plan.unions[0].L)
        facts = plan.facts()
        assert P.s[-1] == pytest.approx(m.rear_length, rel=2e-6)  # the polyline is a little shorter
        assert P.s[-1] == pytest.approx(facts.rear_length, rel=1e-9)
        assert facts.front_length == pytest.approx(plan.cost, rel=1e-7)  # LONGD [1]
        assert facts.front_length == pytest.approx(m.front_length, rel=2e-5)


def test_every_node_is_a_sample_on_each_side(plans):
    for plan in plans.values():
        P = plan.poses()
        firsts = [_union_rows(P, k)[0] for k in range(len(plan.unions))]
        lasts = [_union_rows(P, k)[-1] for k in range(len(plan.unions))]
        sides = [[firsts[0]]] + [[a, b] for a, b in zip(lasts[:-1], firsts[1:], strict=True)] + [[lasts[-1]]]
        for node, rows in zip(plan.nodes, sides, strict=True):
            for i in rows:
                assert (P.x[i], P.y[i]) == (node.x, node.y)  # exactly
                assert wrap(P.theta[i] - node.theta) == pytest.approx(0.0, abs=1e-12)
        assert P.theta[0] == plan.nodes[0].theta
        assert np.all(np.abs(np.diff(P.theta)) < 0.1)  # continuous: no wrap jumps
        assert np.all(np.diff(P.s) >= 0) and P.s[0] == 0.0


def test_curvature_agrees_with_the_circle_through_three_samples(plans):
    """Menger curvature of consecutive positions (no heading used) vs ``kappa``; ``steer = atan(L kappa)``."""
    plan = plans["fig5_example1", "paper"]
    P = plan.poses(0.01)
    L = plan.unions[0].L
    assert np.array_equal(P.steer, np.arctan(L * P.kappa))
    for k in range(len(plan.unions)):
        rows = _union_rows(P, k)
        a, b, c = (
            np.column_stack((P.x[rows[j : rows.size - 2 + j]], P.y[rows[j : rows.size - 2 + j]]))
            for j in (0, 1, 2)
        )
        cross = (b - a)[:, 0] * (c - b)[:, 1] - (b - a)[:, 1] * (c - b)[:, 0]
        sides = np.hypot(*(b - a).T) * np.hypot(*(c - b).T) * np.hypot(*(c - a).T)
        menger = 2.0 * cross / sides  # signed: left turns positive
        assert np.allclose(menger, P.kappa[rows[1:-1]], rtol=0, atol=2e-4)


def test_facts_name_the_steering_jumps_and_the_limit(plans, floors):
    plan = plans["fig5_example1", "lattice"]
    robot = floors["fig5_example1"].robot
    facts = plan.facts(robot.max_steer)
    P = plan.poses()
    n = len(plan.nodes)
    assert facts.steer_jump.shape == (n,) and np.isnan(facts.steer_jump[[0, -1]]).all()
    # the same closed-form steering at the same node by two code paths (the facts' and the
    # samples'), whose arithmetic may differ in the last bits: 1e-12 relative, 1e-15 rad
    same = {"rel": 1e-12, "abs": 1e-15}
    for k in range(1, n - 1):  # the two rows of node k: the end of union k-1, the start of union k
        i = _union_rows(P, k - 1)[-1]
        assert facts.steer_in[k] == pytest.approx(P.steer[i], **same)
        assert facts.steer_out[k] == pytest.approx(P.steer[i + 1], **same)
        assert facts.steer_jump[k] == pytest.approx(P.steer[i + 1] - P.steer[i], rel=1e-9, abs=1e-14)
    assert facts.max_jump == np.nanmax(np.abs(facts.steer_jump)) > math.radians(1)
    assert facts.max_curvature >= np.abs(P.kappa).max() - 1e-12
    assert facts.curvature_limit == robot.max_curvature and facts.within_limit is True
    assert facts.max_steer_used <= robot.max_steer
    assert plan.facts().within_limit is None and plan.facts().curvature_limit is None


def test_plan_clearance_is_the_gap_beyond_half_width(floors):
    sc = floors["fig5_example1"]
    margin = segplan.plan_scenario(sc, clearance=0.1)
    plain = segplan.plan_scenario(sc)
    step = 0.01
    assert (
        segplan.plan_clearance(plain, sc, step)
        == measure_scenario_path(plan_poses(plain, step), sc).clearance
    )
    assert segplan.plan_clearance(plain, sc, step) >= 0.0
    assert segplan.plan_clearance(margin, sc, step) >= 0.1 - 1e-9


# -- the time law ---------------------------------------------------------------------------------
def _dense_worst(plan, law, m=3001):
    """Largest ratio of each quantity to its limit on a dense resampling of every union, in
    driving order (a reverse link from its far end; the speed is ``|v|``, its rate ``a``
    times the direction: for a forward plan, ``v`` and ``a`` themselves)."""
    speed, along = np.abs(law.v), law.a * law.direction  # d|v|/dt
    worst = {"v": 0.0, "a": float(np.abs(law.a).max() / law.a_max), "lat": 0.0, "rate": 0.0}
    for k, (u, d) in enumerate(zip(plan.unions, plan.link_directions, strict=True)):
        rows = np.flatnonzero(law.union == k)
        x = np.linspace(0.0, u.x_end, m)[:: 1 if d > 0 else -1]
        g = np.sqrt(1.0 + u.slope(x) ** 2)
        s = law.s[rows[0]] + np.concatenate(([0.0], np.cumsum(0.5 * (g[1:] + g[:-1]) * np.abs(np.diff(x)))))
        kappa = u.curvature(x)
        steer_slope = np.gradient(np.arctan(u.L * kappa), s)
        i = np.clip(np.searchsorted(law.s[rows], s, side="right") - 1, 0, rows.size - 2)
        v2 = np.maximum(speed[rows][i] ** 2 + 2.0 * along[rows][i] * (s - law.s[rows][i]), 0.0)
        worst["v"] = max(worst["v"], float(np.sqrt(v2).max() / law.v_max))
        worst["lat"] = max(worst["lat"], float(np.max(v2 * np.abs(kappa)) / law.a_lat_max))
        worst["rate"] = max(
            worst["rate"], float(np.max(np.sqrt(v2) * np.abs(steer_slope)) / law.steer_rate_max)
        )
    return worst


@pytest.mark.parametrize("limits", LIMITS)
def test_the_time_law_respects_every_limit_between_the_samples(plans, limits):
    for plan in plans.values():
        law = plan.trajectory(*limits)
        worst = _dense_worst(plan, law)
        assert worst["v"] <= 1 + 1e-9 and worst["a"] <= 1 + 1e-9, worst
        assert worst["lat"] <= 1 + 1e-6 and worst["rate"] <= 1 + 1e-6, worst
        assert max(worst.values()) > 0.99  # and some limit binds


def test_the_law_is_consistent_in_time(plans):
    plan = plans["l_shaped_rack", "lattice"]
    law = plan.trajectory(*LIMITS[0])
    assert tuple(law.columns()) == TRAJECTORY_COLUMNS
    assert law.v[0] == law.v[-1] == 0.0 and law.t[0] == 0.0 and law.total_time == law.t[-1]
    dt, ds = np.diff(law.t), np.diff(law.s)
    assert np.all(dt >= 0) and np.all(law.v >= 0)
    moving = ds > 0
    assert np.allclose(
        ds[moving], 0.5 * (law.v[:-1] + law.v[1:])[moving] * dt[moving], rtol=1e-12
    )  # s = int v dt
    assert np.allclose(law.v[1:][moving], (law.v[:-1] + law.a[:-1] * dt)[moving], rtol=1e-9, atol=1e-12)


def test_a_steering_jump_stops_the_robot_to_re_steer(plans):
    plan = plans["fig5_example1", "lattice"]
    rate = math.radians(30)
    law = plan.trajectory(1.0, 0.5, 0.5, rate)
    jumps = plan.facts().steer_jump[1:-1]
    assert law.jumps == np.count_nonzero(np.abs(jumps) > 1e-9) >= 1
    assert law.dwell_time == pytest.approx(np.sum(np.abs(jumps)) / rate, rel=1e-12)
    for k in range(1, len(plan.nodes) - 1):
        i = _union_rows(law, k - 1)[-1]
        assert law.v[i] == law.v[i + 1] == 0.0 and law.s[i] == law.s[i + 1]
        assert law.t[i + 1] - law.t[i] == pytest.approx(abs(jumps[k - 1]) / rate, rel=1e-12)
    driven_through = plan.trajectory(1.0, 0.5, 0.5, rate, jump_tol=1.0)  # every jump called rounding
    assert driven_through.jumps == 0 and driven_through.jump_time == 0.0 == driven_through.dwell_time
    assert law.total_time == pytest.approx(driven_through.total_time + law.jump_time, rel=1e-12)
    assert law.jump_time > law.dwell_time > 0


def test_a_straight_line_takes_the_trapezoidal_profile():
    """10 m straight, v_max 1, a_max 0.5: 2 s to speed up over 1 m, 8 s cruising, 2 s braking."""
    u = Union((0.0, 0.0, 0.0), (10.0, 0.0, 0.0), 0.0, 1.2)
    plan = lattice_plan(Pose(0.0, 0.0, 0.0), [u], ["start", "goal"], 10.0, 10.0, 0, 0, 0.0, STATS)
    law = plan.trajectory(1.0, 0.5, 1.0, 1.0, step=0.05)
    assert law.total_time == pytest.approx(12.0, rel=1e-12) and law.jumps == 0
    short = plan.trajectory(10.0, 0.5, 1.0, 1.0, step=0.05)  # never at v_max: a triangle
    assert short.total_time == pytest.approx(2.0 * math.sqrt(10.0 / 0.5), rel=1e-12)


def test_time_converges_with_step(plans):
    """The discretisation error is the time only, O(step): step 0.05 m within 0.05 % of 6.25 mm."""
    plan = plans["turn_around", "lattice"]
    fine = plan.trajectory(*LIMITS[0], step=0.00625).total_time
    times = [plan.trajectory(*LIMITS[0], step=h).total_time for h in (0.2, 0.05)]
    assert times[0] > times[1] > fine * (1 - 1e-4)
    assert times[1] - fine < 5e-4 * fine


def test_interval_bounds_hold_on_dense_samples():
    """The exact caps: no dense sample of an interval beats its bound of |kappa| or |d steer / ds|."""
    rng = np.random.default_rng(7)
    for _ in range(40):
        p1 = (rng.uniform(2, 9), rng.uniform(-3, 3), rng.uniform(-1.2, 1.2))
        lo, hi = alpha_interval(intrinsic((0, 0, 0.3), p1).phi0, intrinsic((0, 0, 0.3), p1).phi1)
        u = Union((0.0, 0.0, 0.3), p1, lo + (hi - lo) * rng.uniform(0.1, 0.9), 1.2)
        x = np.linspace(0.0, u.x_end, 7)
        k_max, slope = interval_bounds(u, x)
        for i in range(6):
            z = np.linspace(x[i], x[i + 1], 4001)
            kappa = u.curvature(z)
            s = np.concatenate(([0.0], np.cumsum(np.hypot(np.diff(z), np.diff(u.f(z))))))
            assert np.abs(kappa).max() <= k_max[i] * (1 + 1e-12) + 1e-15
            assert np.abs(np.gradient(np.arctan(1.2 * kappa), s)).max() <= slope[i] * (1 + 1e-5) + 1e-12


def test_bad_input_is_named():
    u = Union((0.0, 0.0, 0.0), (5.0, 1.0, 0.2), 0.1, 1.2)
    plan = lattice_plan(Pose(0.0, 0.0, 0.0), [u], ["start", "goal"], 1.0, 1.0, 0, 0, 0.0, STATS)
    for kwargs, name in (
        ({"v_max": 0.0}, "v_max"),
        ({"a_max": -1.0}, "a_max"),
        ({"a_lat_max": math.inf}, "a_lat_max"),
    ):
        limits = {"v_max": 1.0, "a_max": 1.0, "a_lat_max": 1.0, "steer_rate_max": 1.0} | kwargs
        with pytest.raises(ValueError, match=name):
            plan.trajectory(**limits)
    with pytest.raises(ValueError, match="steer_rate_max"):
        plan.trajectory(1.0, 1.0, 1.0, "fast")
    with pytest.raises(ValueError, match="step"):
        plan.poses(0.0)
    with pytest.raises(ValueError, match="max_steer"):
        plan.facts(2.0)
    empty = lattice_plan(Pose(0.0, 0.0, 0.0), [], ["start"], 0.0, 0.0, 0, 0, 0.0, STATS)
    with pytest.raises(ValueError, match="no unions"):
        empty.poses()


# -- save and load -------------------------------------------------------------------------------
def _bits(plan: Plan) -> list:
    """Every number of a plan, floats as ``float.hex``."""
    out = [tuple(float(v).hex() for v in n) for n in plan.nodes]
    for u in plan.unions:
        state = u.state()
        out.append({k: [float(v).hex() for v in np.ravel(val)] for k, val in state.items()})
    out += [float(plan.cost).hex(), float(plan.search_cost).hex(), float(plan.seconds).hex()]
    return out


def _round_trip(plan, tmp_path, scenario=None):
    path = plan.save(tmp_path / "plan.json", scenario)
    loaded = Plan.load(path)
    assert loaded == plan and _bits(loaded) == _bits(plan)
    assert all(a == b and a.state() == b.state() for a, b in zip(loaded.unions, plan.unions, strict=True))
    assert loaded.options == plan.options and loaded.to_dict() == plan.to_dict()
    assert loaded.poses().x.tobytes() == plan.poses().x.tobytes()  # and it samples alike, to the bit
    return json.loads(path.read_text())


@settings(max_examples=12)
@given(key=st.sampled_from(["fig5_example1", "turn_around", "l_shaped_rack", "random"]), paper=st.booleans())
def test_saved_plans_of_the_floors_load_bit_for_bit(plans, floors, tmp_path_factory, key, paper):
    if (key, "paper" if paper else "lattice") not in plans:
        paper = False
    plan = plans[key, "paper" if paper else "lattice"]
    record = _round_trip(plan, tmp_path_factory.mktemp("plan"), floors[key])
    assert record["L"] == plan.unions[0].L and record["max_steer"] == floors[key].robot.max_steer
    assert record["floor"]["name"] == floors[key].name and record["format"] == "segplan-plan"
    assert {k: record[k] for k in plan.to_dict()} == json.loads(
        json.dumps(plan.to_dict())
    )  # its keys as they were
    again = segplan.plan_scenario(floors[key], options=plan_from_record(record).options)
    assert again.nodes == plan.nodes  # the options plan as they planned


@st.composite
def chains(draw):
    """Random chains of unions built by ``Union(...)`` (numpy) or ``Union.from_intrinsic`` (math)."""
    L = draw(st.floats(0.5, 2.0))
    x, y, th = draw(st.floats(-50, 50)), draw(st.floats(-50, 50)), draw(st.floats(-3.14, 3.14))
    nodes, unions = [Pose(x, y, th)], []
    for _ in range(draw(st.integers(1, 4))):
        p0 = nodes[-1]
        d = draw(st.floats(0.5, 10.0)) * L
        psi = p0.theta + draw(st.floats(-1.0, 1.0))
        p1 = Pose(p0.x + d * math.cos(psi), p0.y + d * math.sin(psi), psi + draw(st.floats(-1.0, 1.0)))
        geo = intrinsic(p0, p1)
        lo, hi = alpha_interval(geo.phi0, geo.phi1)
        alpha = float(lo + (hi - lo) * draw(st.floats(0.02, 0.98)))
        if draw(st.booleans()):
            u = Union(p0, p1, alpha, L)
        else:
            u = Union.from_intrinsic(p0, p1, alpha, L, *(float(v) for v in geo))
        nodes.append(p1)
        unions.append(u)
    return nodes, unions


@settings(max_examples=40)
@given(chain=chains(), options=st.sampled_from([None, PaperOptions(heuristic="c", ds=1.5), DefaultOptions()]))
def test_saved_random_chains_load_bit_for_bit(tmp_path_factory, chain, options):
    nodes, unions = chain
    cost = unions_longd(unions)
    plan = lattice_plan(
        nodes[0],
        unions,
        ["start"] + ["lattice"] * (len(unions) - 1) + ["goal"],
        cost,
        cost,
        3,
        7,
        0.1,
        STATS,
    )
    planner = None if options is None else ("paper" if isinstance(options, PaperOptions) else "lattice")
    plan = dataclasses.replace(plan, options=options, planner=planner, iterations=(1, 2))
    record = _round_trip(plan, tmp_path_factory.mktemp("chain"))
    assert record["L"] == unions[0].L and record["max_steer"] is None and record["floor"] is None
    assert plan.to_dict()["L"] == unions[0].L  # to_dict's keys kept, L added


def test_a_corrupted_file_is_refused(plans, tmp_path):
    plan = plans["fig5_example1", "lattice"]
    record = plan_record(plan)
    bad = json.loads(json.dumps(record))
    bad["exact"]["unions"][1]["coefficients"][1] *= 1.001
    with pytest.raises(ValueError, match="c2"):
        plan_from_record(bad)
    bad = json.loads(json.dumps(record))
    bad["exact"]["nodes"][2][0] += 1e-6
    with pytest.raises(ValueError, match="union 1 does not join"):
        plan_from_record(bad)
    with pytest.raises(ValueError, match="format"):
        plan_from_record({"nodes": []})
    (tmp_path / "x.json").write_text("{not json")
    with pytest.raises(ValueError, match="not JSON"):
        Plan.load(tmp_path / "x.json")
    with pytest.raises(ValueError, match="L="):
        plan.save(tmp_path / "p.json", segplan.make_scenario(segplan.Robot(2.0), (0, 0, 0), (5, 0, 0)))


def test_options_and_unions_round_trip_alone():
    for options in (
        PaperOptions(expander={"r0": 0.5}, refine=RefineOptions(rounds=2)),
        DefaultOptions(lattice=LatticeOptions(resolution=0.1), refine=None),
    ):
        assert options_from_dict(json.loads(json.dumps(options.to_dict()))) == options
    u = Union((0.0, 0.0, 0.2), (6.0, 1.0, -0.3), 0.1, 1.2)
    assert pickle.loads(pickle.dumps(u)) == u and hash(pickle.loads(pickle.dumps(u))) == hash(u)
    assert Union.from_state(json.loads(json.dumps(u.state()))) == u
    assert u != Union((0.0, 0.0, 0.2), (6.0, 1.0, -0.3), 0.1000001, 1.2)


# -- exports --------------------------------------------------------------------------------------
def test_csv_reads_back_in_numpy_and_pandas_exactly(plans, tmp_path):
    plan = plans["turn_around", "paper"]
    for table, columns in ((plan.poses(), POSE_COLUMNS), (plan.trajectory(*LIMITS[0]), TRAJECTORY_COLUMNS)):
        path = tmp_path / "t.csv"
        table.to_csv(path)
        frame = pd.read_csv(path)
        array = np.genfromtxt(path, delimiter=",", names=True)
        assert tuple(frame.columns) == columns == array.dtype.names and len(frame) == len(table)
        for name in columns:
            assert np.array_equal(frame[name].to_numpy(), getattr(table, name))
            assert np.array_equal(array[name], getattr(table, name))
        assert frame["union"].dtype.kind == "i"


def test_nav_path_quaternions_are_unit_and_yaw_consistent(plans, tmp_path):
    plan = plans["l_shaped_rack", "lattice"]
    P = plan.poses()
    law = plan.trajectory(*LIMITS[0])
    for source, stamped in ((P, False), (law, True)):
        message = source.nav_path(frame_id="warehouse")
        assert message["header"]["frame_id"] == "warehouse"
        poses = message["poses"]
        q = np.array([[p["pose"]["orientation"][k] for k in "xyzw"] for p in poses])
        xy = np.array([[p["pose"]["position"][k] for k in "xy"] for p in poses])
        assert (
            np.allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-15)
            and np.all(q[:, :2] == 0)
            and np.all(q[:, 3] >= 0)
        )
        yaw = 2.0 * np.arctan2(q[:, 2], q[:, 3])
        stamps = np.array(
            [p["header"]["stamp"]["sec"] + 1e-9 * p["header"]["stamp"]["nanosec"] for p in poses]
        )
        assert np.all(np.diff(stamps) >= 0) and all(p["header"]["frame_id"] == "warehouse" for p in poses)
        interior = len(plan.nodes) - 2
        if stamped:  # a node where the robot re-steers keeps both of its stamps
            assert len(poses) == len(source) - (interior - source.jumps)
            assert stamps[-1] == pytest.approx(law.total_time, abs=1e-9)
        else:  # each node once
            assert len(poses) == len(source) - interior
        # yaw consistent with theta (rows kept in order)
        keep = np.ones(len(source), dtype=bool)
        last = None
        for i in range(len(source)):
            key = (source.x[i], source.y[i], wrap(source.theta[i]), source.t[i] if stamped else 0.0)
            keep[i], last = key != last, key
        assert np.allclose(wrap(yaw - source.theta[keep]), 0.0, atol=1e-12)
        assert np.array_equal(xy, np.column_stack((source.x, source.y))[keep])
        for suffix in (".json", ".yaml"):
            path = tmp_path / f"path{suffix}"
            source.save_nav_path(path, frame_id="warehouse")
            read = yaml.safe_load(path.read_text()) if suffix == ".yaml" else json.loads(path.read_text())
            assert read == message
