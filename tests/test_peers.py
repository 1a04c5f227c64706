"""The OMPL comparison (segplan.studies.peers, its runner segplan.studies.ompl_runner,
benchmarks/peers.py): inputs, the shared validity check, a smoke run, and the stored results
chapter 8 reads."""

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from segplan.studies import executor, ompl_runner, peers

ROOT = Path(__file__).resolve().parents[1]
STORED = ROOT / "benchmarks" / "results" / "peers_ompl.csv"

needs_ompl = pytest.mark.skipif(
    not ompl_runner.ompl_available(),
    reason="the OMPL Python bindings are not installed (pip install 'segplan[peers]')",
)


def test_ompl_heading_is_strictly_inside_minus_pi_pi():
    assert ompl_runner.ompl_heading(math.pi) == -math.pi
    assert ompl_runner.ompl_heading(-math.pi) == -math.pi
    assert ompl_runner.ompl_heading(3 * math.pi) == -math.pi
    assert ompl_runner.ompl_heading(0.25) == pytest.approx(0.25)
    assert ompl_runner.ompl_heading(-1e-20) == pytest.approx(0.0)  # % may round up to 2 pi itself
    for a in np.linspace(-20.0, 20.0, 4001):
        w = ompl_runner.ompl_heading(a)
        assert -math.pi <= w < math.pi
        assert math.isclose(math.cos(w), math.cos(a), abs_tol=1e-12)
        assert math.isclose(math.sin(w), math.sin(a), abs_tol=1e-12)
    with pytest.raises(ValueError, match="theta"):
        ompl_runner.ompl_heading(math.inf)


def test_seed_zero_is_refused():
    with pytest.raises(ValueError, match="seed"):
        ompl_runner.check_seed(0)
    with pytest.raises(ValueError, match="seed"):
        ompl_runner.check_seed(True)
    assert ompl_runner.check_seed(np.int64(3)) == 3


@pytest.mark.parametrize("name", peers.shipped_scenarios())
def test_segment_validity_answers_as_scenario_is_free(name):
    """The filtered check equals Scenario.is_free (segplan's own tests), also near contact."""
    sc = peers.load(name)
    check = ompl_runner.SegmentValidity(sc)
    rng = np.random.default_rng(7)
    xmin, ymin, xmax, ymax = sc.bounds
    n = 600
    poses = np.column_stack(
        (rng.uniform(xmin, xmax, n), rng.uniform(ymin, ymax, n), rng.uniform(-math.pi, math.pi, n))
    )
    near = []  # A or B just on either side of an enlarged vertex or of a free-bound wall
    for poly in sc.enlarged:
        for v in poly:
            for eps in (-1e-7, 0.0, 1e-7, 1e-3):
                th = rng.uniform(-math.pi, math.pi)
                near.append((v[0] + eps, v[1] + eps, th))
                near.append((v[0] - sc.L * math.cos(th) + eps, v[1] - sc.L * math.sin(th) - eps, th))
    fx0, fy0, fx1, fy1 = sc.free_bounds
    for eps in (-1e-7, 0.0, 1e-7, 1e-3):
        near += [(fx0 + eps, 0.5 * (fy0 + fy1), 0.0), (fx1 - sc.L - eps, fy0 + 1.0, 0.0)]
        near += [(fx0 + 1.0, fy1 - eps, -0.5 * math.pi), (fx0 + 1.0, fy0 + sc.L + eps, -0.5 * math.pi)]
    for p in list(map(tuple, poses)) + near:
        assert check(*p) == sc.is_free(p), p
    assert check.calls == len(poses) + len(near)


def test_goal_table_logic():
    rows = [
        {"scenario": "s", "method": "segplan h'=a", "space": "segplan", "budget": math.nan, "seed": 0,
         "solved": True, "valid": True, "front_length": 10.0, "seconds": 0.05},
        {"scenario": "s", "method": "BITstar", "space": "dubins", "budget": 5.0, "seed": 1,
         "solved": True, "valid": True, "front_length": 11.0, "seconds": 5.0},
        {"scenario": "s", "method": "RRTstar", "space": "dubins", "budget": 5.0, "seed": 1,
         "solved": True, "valid": False, "front_length": 9.0, "seconds": 5.0},  # invalid: ignored
        {"scenario": "t", "method": "segplan h'=a", "space": "segplan", "budget": math.nan, "seed": 0,
         "solved": True, "valid": True, "front_length": 10.0, "seconds": 0.2},
        {"scenario": "t", "method": "BITstar", "space": "dubins", "budget": 5.0, "seed": 1,
         "solved": True, "valid": True, "front_length": 9.5, "seconds": 5.0},
    ]  # fmt: skip
    g = peers.goal_table(pd.DataFrame(rows), 5.0, refine=False).set_index("scenario")
    assert g.loc["s", "ompl_best_front"] == 11.0 and g.loc["s", "ompl_planner"] == "BITstar"
    assert bool(g.loc["s", "goal_met"]) and g.loc["s", "time_ratio"] == pytest.approx(100.0)
    assert (
        not bool(g.loc["t", "shorter"]) and not bool(g.loc["t", "fast"]) and not bool(g.loc["t", "goal_met"])
    )
    # the refined planner's rows are judged apart (default): none here, so no segplan length
    g = peers.goal_table(pd.DataFrame(rows), 5.0).set_index("scenario")
    assert not g["shorter"].any() and g["segplan_front"].isna().all()
    rows[0]["method"] = peers.segplan_method("a", refine=True)
    g = peers.goal_table(pd.DataFrame(rows), 5.0).set_index("scenario")
    assert bool(g.loc["s", "goal_met"]) and math.isnan(g.loc["t", "segplan_front"])


def test_configs():
    full = peers.full_config()
    assert full.scenarios == peers.shipped_scenarios()
    dubins = [j for j in full.jobs() if j[4] == "dubins"]
    assert len(dubins) == len(full.scenarios) * 3 * 3 * 5
    assert len(set(full.jobs())) == len(full.jobs())


def test_stored_results_cover_every_floor_planner_budget_and_seed():
    """benchmarks/results/peers_ompl.csv holds a run for every shipped floor x planner x budget
    x seed of the full study (and nothing else), with its provenance and the figures' poses."""
    table, paths, meta = peers.read_ompl_results(STORED)
    full = peers.full_config()
    assert peers.missing_runs(table, full) == []
    assert len(table) == len(full.jobs()), "runs outside the full study, or repeated"
    assert set(table["scenario"]) == set(peers.shipped_scenarios())
    for key in ("date", "machine", "ompl", "commit", "command"):
        assert meta[key], key
    assert meta["ompl"] != "none" and len(meta["commit"]) == 40
    assert meta["config"]["blocks"] == [
        {k: list(v) if isinstance(v, tuple) else v for k, v in vars(b).items()} for b in full.blocks
    ]
    best = peers.best_paths(table, dict.fromkeys(paths))  # keys only: which runs the figures draw
    assert set(best) == set(paths)
    for P in paths.values():
        assert P.ndim == 2 and P.shape[1] == 3 and len(P) >= 2


def test_stored_results_are_fair_runs_with_simplified_paths():
    """Every stored run of 0.5 s or more got at least 0.9 of a core (the executor's rule, recorded
    in the provenance), and every exact solution has its simplified path measured beside it."""
    table, paths, meta = peers.read_ompl_results(STORED)
    if "fairness" not in meta:
        pytest.skip("the stored runs predate the fairness rule (harness 2): re-run benchmarks/peers.py")
    rule = executor.FairnessRule(**{k: v for k, v in meta["fairness"].items() if k != "rule"})
    assert rule == executor.FAIRNESS and meta["harness_version"] == ompl_runner.HARNESS_VERSION
    assert not any(rule.refuses(r) for r in table.to_dict("records"))
    assert np.allclose(table["cpu_share"], table["cpu_seconds"] / table["seconds"], rtol=1e-12)
    solved = table[table["solved"]]
    assert solved["simplified_front_length"].notna().all() and solved["simplify_seconds"].notna().all()
    simple = {k for k in paths if k[1].endswith(peers.SIMPLIFIED)}
    runs = set(
        zip(table["scenario"], table["method"], table["space"], table["budget"], table["seed"], strict=True)
    )
    assert simple and {(k[0], k[1].removesuffix(peers.SIMPLIFIED), *k[2:]) for k in simple} <= runs


def test_goal_table_compares_like_with_like():
    """Refined segplan against OMPL's simplified paths, segplan as found against the raw ones."""
    rows = [
        {"scenario": "s", "method": "segplan h'=a", "space": "segplan", "budget": math.nan, "seed": 0,
         "solved": True, "valid": True, "front_length": 10.5, "seconds": 0.05},
        {"scenario": "s", "method": "segplan h'=a +refine", "space": "segplan", "budget": math.nan,
         "seed": 0, "solved": True, "valid": True, "front_length": 10.0, "seconds": 0.05},
        {"scenario": "s", "method": "BITstar", "space": "dubins", "budget": 5.0, "seed": 1,
         "solved": True, "valid": True, "front_length": 11.0, "seconds": 5.0, "simplify_seconds": 0.01,
         **{f: math.nan for f in ompl_runner.SIMPLIFIED_FIELDS},
         "simplified_front_length": 9.5, "simplified_valid": True},
    ]  # fmt: skip
    t = pd.DataFrame(rows)
    raw = peers.goal_table(t, 5.0, refine=False).iloc[0]
    assert raw["ompl_best_front"] == 11.0 and raw["ompl_planner"] == "BITstar" and raw["shorter"]
    simple = peers.goal_table(t, 5.0).iloc[0]
    assert simple["ompl_best_front"] == 9.5 and simple["ompl_planner"] == "BITstar +simplify"
    assert not simple["shorter"]
    s = peers.simplified_rows(t).iloc[0]
    assert s["seconds"] == pytest.approx(5.01) and s["method"] == "BITstar +simplify"


def test_stored_results_round_trip(tmp_path):
    rows = [
        {"scenario": "s", "method": "BITstar", "space": "dubins", "budget": 1.0, "seed": s, "solved": True,
         "valid": True, "front_length": 10.0 + s, "messages": "" if s == 1 else "Warning: x"}
        for s in (1, 2)
    ]  # fmt: skip
    poses = {
        ("s", "BITstar", "dubins", 1.0, s): np.array([[0.0, 0.0, 0.0], [1.23456, 2.0, 0.123456]])
        for s in (1, 2)
    }
    peers.write_ompl_results(pd.DataFrame(rows), poses, tmp_path / "r.csv", {"date": "today"})
    table, paths, meta = peers.read_ompl_results(tmp_path / "r.csv")
    assert meta == {"date": "today"} and list(table["messages"]) == ["", "Warning: x"]
    assert list(paths) == [("s", "BITstar", "dubins", 1.0, 1)]  # the shortest valid run only
    assert paths[("s", "BITstar", "dubins", 1.0, 1)][1].tolist() == [1.235, 2.0, 0.1235]
    with pytest.raises(ValueError, match="csv_path"):
        peers.read_ompl_results(tmp_path / "none.csv")


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    """`python benchmarks/peers.py --quick`, run once for the two tests that read it."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    out = tmp_path_factory.mktemp("peers") / "quick.csv"
    proc = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "peers.py"), "--quick", "--out", str(out)],
        capture_output=True, text=True, timeout=600, env=env, check=False,
    )  # fmt: skip
    return proc, out


@needs_ompl
def test_command_line_quick_run(quick_run):
    """`python benchmarks/peers.py --quick` runs end to end and stores its runs."""
    proc, out = quick_run
    assert proc.returncode == 0, proc.stderr[-3000:]
    table, _, meta = peers.read_ompl_results(out)
    assert peers.missing_runs(table, peers.quick_config()) == []
    assert "--quick" in meta["command"]
    assert "goal at 0.05 s" in proc.stdout


@needs_ompl
def test_ompl_smoke_run_one_scenario(quick_run):
    """One scenario, a tiny budget, one seed: the harness runs end to end, paths measured.

    OMPL's runs are those the command line's quick run stored (the same configuration,
    ``peers.quick_config()``: not run twice); segplan's rows are computed here."""
    proc, out = quick_run
    assert proc.returncode == 0, proc.stderr[-3000:]
    cfg = peers.quick_config(("single_obstacle",))
    assert cfg == peers.quick_config()  # what the command line ran
    ompl = peers.read_ompl_results(out)[0]
    t = pd.concat([peers.run_segplan(cfg), ompl], ignore_index=True)
    assert set(t["method"]) == {"segplan h'=a", "segplan h'=a +refine", "RRTstar"}
    assert set(t["space"]) == {"segplan", "dubins", "reedsshepp"}
    for _, ours in t[t["space"] == "segplan"].iterrows():
        assert ours["solved"] and ours["valid"]
        assert ours["front_length"] == pytest.approx(ours["plan_cost"], rel=1e-4)  # measured = LONGD [1]
        assert ours["curvature_jumps"] >= 0 and ours["reversals"] == 0
    found, refined = (
        t.set_index("method").loc[peers.segplan_method("a", r), "front_length"] for r in (False, True)
    )
    assert refined <= found
    for _, r in t[t["space"] != "segplan"].iterrows():
        assert r["checks"] > 0 and r["seconds"] > 0
        assert "Exact" in r["status"] or "Approximate" in r["status"] or "Timeout" in r["status"]
        if r["solved"] and r["space"] == "dubins":
            assert r["reversals"] == 0
            assert r["rear_length"] == pytest.approx(r["ompl_cost"], rel=1e-4)
    assert "nanobind" not in " ".join(t["messages"])


@needs_ompl
def test_ompl_accepts_a_heading_of_pi():
    """turn_around's goal heads at exactly +pi: normalised, the run is a valid problem."""
    sc = peers.load("turn_around")
    assert sc.goal.theta == math.pi
    row = ompl_runner.solve_ompl_isolated(sc, "BITstar", 0.3, 1)
    assert "Invalid" not in row["status"], row["status"]
    if row["solved"]:
        assert row["valid"] and row["reversals"] == 0


@needs_ompl
def test_a_worker_past_its_limit_is_killed_and_its_run_recorded_as_overrun(monkeypatch):
    """BIT* overran a 5 s budget 50-fold on a Reeds-Shepp floor; the harness must not hang
    or crash: the worker is killed at worker_limit and the run is not solved, with the
    process's own wall and CPU time (so the fairness rule can judge it)."""
    monkeypatch.setattr(ompl_runner, "worker_limit", lambda budget: 1.0)
    row = ompl_runner.solve_ompl_isolated(peers.load("fig5_example1"), "BITstar", 5.0, 1)
    assert row["status"].startswith("overrun") and not row["solved"] and not row["valid"]
    # the worker's own CPU time: its threads may use more than one core (seen: 1.22 s in 1.01 s)
    assert 1.0 <= row["seconds"] < 5.0
    assert 0.0 < row["cpu_seconds"] <= (os.cpu_count() or 1) * row["seconds"] + 0.1


def test_a_crashed_worker_is_recorded_not_raised(monkeypatch, tmp_path):
    """OMPL died of SIGSEGV in a Reeds-Shepp run of the reverse study: the run is recorded as
    crashed (not solved, no times to judge), the study goes on."""
    crash = tmp_path / "crash.sh"
    crash.write_text("#!/bin/sh\ncat > /dev/null\nkill -SEGV $$\n")
    crash.chmod(0o755)
    monkeypatch.setattr(sys, "executable", str(crash))
    row = ompl_runner.solve_ompl_isolated(peers.load("fig5_example1"), "BITstar", 5.0, 1, "reedsshepp")
    assert row["status"] == "crashed: the OMPL worker died of signal 11"
    assert not row["solved"] and not row["valid"] and math.isnan(row["seconds"])
    assert not executor.FAIRNESS.refuses(row)  # not a starved run: nothing to judge
