"""The robustness study (issue 12): its floors, the stored OMPL results, the script.

- segplan.studies.floors: deterministic floors that keep the stated rules (room, obstacle
  count and shapes, free start and goal 6 m apart, heading kinds), hard cases as described;
- benchmarks/results/robustness_ompl.csv covers every floor x planner x budget x seed that
  benchmarks/robustness.py defines, each on the floor the generator makes today
  (floor_key), with a provenance record;
- the comparison and the verdicts (segplan.studies.robustness, by segplan.studies.verdicts)
  judge by the stated criteria (synthetic tables);
- ``benchmarks/robustness.py --quick`` runs (its OMPL part only where ompl is installed).
"""

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import shapely

from segplan.planning.api import PAPER_SHARE
from segplan.studies import executor, ompl_runner
from segplan.studies import floors as fl
from segplan.studies import robustness as rb

ROOT = Path(__file__).resolve().parents[1]
STORED = rb.ompl_files(ROOT / "benchmarks" / "results" / rb.OMPL_CSV_NAME)  # the repository's OMPL side


# -- the floors ---------------------------------------------------------------------------
@pytest.fixture(scope="module")
def groups():
    """The study's floors (rb.floor_groups(): 2 x N_FLOORS random, the hard and the large
    ones), generated once for the tests below (about 5 s of CPU; deterministic, checked by
    test_floors_are_deterministic_and_keyed)."""
    return rb.floor_groups()


@pytest.mark.parametrize("kind", fl.KINDS)
def test_random_floors_keep_the_rules(kind, groups):
    for i in range(0, fl.N_FLOORS, 7):
        sc = groups[kind][i]
        assert sc.name == f"{kind}-{i:03d}"
        assert sc.bounds == fl.SMALL_BOUNDS
        assert sc.robot == fl.ROBOT and sc.robot.min_turning_radius == pytest.approx(1.0)
        assert 4 <= len(sc.obstacles) <= 9
        polys = [shapely.Polygon(p) for p in sc.obstacles]
        room = shapely.box(*fl.SMALL_BOUNDS)
        for j, p in enumerate(polys):
            assert room.contains(p)
            assert (
                len(sc.obstacles[j]) == 4
                or np.ptp(np.hypot(*(sc.obstacles[j] - p.centroid.coords[0]).T)) < 1e-5
            )
            assert not any(p.intersects(q) for q in polys[j + 1 :])
        assert sc.is_free(sc.start) and sc.is_free(sc.goal)
        d = math.dist(sc.start[:2], sc.goal[:2])
        assert d >= fl.MIN_DISTANCE
        if kind == "natural":
            direction = math.atan2(sc.goal.y - sc.start.y, sc.goal.x - sc.start.x)
            for p in (sc.start, sc.goal):
                off = (p.theta - direction + math.pi) % (2 * math.pi) - math.pi
                assert abs(off) <= fl.NATURAL_SPREAD + 1e-6


def test_any_headings_cover_the_circle(groups):
    assert len(groups["any"]) == fl.N_FLOORS
    th = np.array([sc.start.theta for sc in groups["any"]])
    assert np.histogram(th, bins=4, range=(-math.pi, math.pi))[0].min() >= 30


def test_floors_are_deterministic_and_keyed():
    a, b = fl.random_floor("any", 5), fl.random_floor("any", 5)
    assert a.to_json() == b.to_json() and fl.floor_key(a) == fl.floor_key(b)
    assert fl.floor_key(a) != fl.floor_key(fl.random_floor("any", 6))
    with pytest.raises(ValueError, match="kind"):
        fl.random_floor("sideways", 0)
    with pytest.raises(ValueError, match="index"):
        fl.random_floor("any", fl.N_FLOORS)
    with pytest.raises(ValueError, match="scale"):
        fl.sweep_floor(0.5)
    with pytest.raises(ValueError, match="scenario"):
        fl.floor_key("any-000")


def test_sweep_and_large_floors(groups):
    sc = fl.sweep_floor(2.0, None, 1)
    assert sc.bounds == (0.0, 0.0, 40.0, 24.0) and len(sc.obstacles) == 32
    assert sc.start.x < 0.1 * 40 + 0.3 and sc.goal.x > 0.9 * 39.4
    large = groups["large"][0]  # fl.large_floor(0)
    assert large.bounds == fl.LARGE_BOUNDS and len(large.obstacles) == 512
    assert fl.floor_key(large) == fl.floor_key(fl.sweep_floor(8.0, 512, 0))


def test_hard_cases_are_what_they_say():
    cases = fl.hard_cases()
    for name in ("wall_ahead_back", "wall_ahead_same", "wall_ahead_low"):
        sc = cases[name]
        assert sc.start.theta == 0.0
        front = sc.start.x + sc.L
        assert sc.free_bounds[2] - front == pytest.approx(0.5)  # 0.5 m from the (shrunk) wall
        assert sc.goal.x < sc.start.x  # behind
        # a circle of radius R = L turning left clears the wall by sqrt(2) L - L less than 0.5 m
        assert 0.5 - (math.sqrt(2.0) - 1.0) * sc.L == pytest.approx(0.0858, abs=1e-3)
    wall = cases["wall_obstacle"]
    gap = wall.enlarged[0][:, 0].min() - (wall.start.x + wall.L)
    assert 0.45 < gap <= 0.5 + 1e-9  # the enlargement's tangent edges sit within r of the wall
    for name in ("enclosed_goal", "enclosed_slit"):
        sc = cases[name]
        ring = shapely.unary_union([shapely.Polygon(p) for p in sc.enlarged])
        inside = shapely.Point(sc.goal.x, sc.goal.y)
        holes = [shapely.Polygon(h) for g in getattr(ring, "geoms", [ring]) for h in g.interiors]
        assert any(h.contains(inside) for h in holes), name  # the goal is cut off in the planning model
    assert cases["turn_around"].robot.L == 1.2


# -- the stored OMPL side -----------------------------------------------------------------
def test_stored_ompl_csv_covers_every_run(groups):
    assert STORED.csv.exists(), "benchmarks/results/robustness_ompl.csv missing: run robustness.py --ompl"
    t = rb.read_ompl(STORED.csv)
    jobs = rb.ompl_jobs(groups)
    want = {rb.job_id(j): fl.floor_key(j[1]) for j in jobs}
    ids = [
        f"{f}|{p}|{b:g}|{s}"
        for f, p, b, s in zip(t["floor"], t["planner"], t["budget"], t["seed"], strict=True)
    ]
    assert len(ids) == len(set(ids)), "a run is stored twice"
    have = dict(zip(ids, t["floor_key"], strict=True))
    missing = sorted(set(want) - set(have))
    assert not missing, f"{len(missing)} runs missing, e.g. {missing[:5]}"
    assert not set(have) - set(want), "stored runs the study does not define"
    stale = [k for k in want if have[k] != want[k]]
    assert not stale, f"{len(stale)} runs were measured on other floors, e.g. {stale[:5]}"
    assert set(t["generator"]) == {fl.GENERATOR_VERSION}
    assert set(t["budget"]) == set(rb.BUDGETS)
    assert t.loc[t["solved"], "front_length"].notna().all()
    assert not (t["valid"] & ~t["solved"]).any()  # valid only if solved
    prov = json.loads(STORED.provenance.read_text())
    for key in ("budgets", "seeds", "generator_version", "sessions"):
        assert key in prov
    for s in prov["sessions"]:
        for key in ("machine", "ompl", "commit", "command", "note"):
            assert key in s
        assert "started" in s or "date" in s  # the first session's format, or ompl_runner.provenance's
        assert s["note"]
    lines = rb.session_lines(prov)
    assert len(lines) == 4 * len(prov["sessions"]) + 1 and "OMPL" in lines[0]
    assert prov["budgets"] == list(rb.BUDGETS) and prov["generator_version"] == fl.GENERATOR_VERSION


def test_stored_ompl_runs_are_fair_with_simplified_paths():
    """Every stored run of 0.5 s or more got at least 0.9 of a core (the rule recorded in the
    latest session), and each exact solution has its simplified path measured beside it."""
    prov = json.loads(STORED.provenance.read_text())
    last = prov["sessions"][-1]
    if "fairness" not in last:
        pytest.skip("the stored runs predate the fairness rule (harness 2): re-run robustness.py --ompl")
    rule = executor.FairnessRule(**{k: v for k, v in last["fairness"].items() if k != "rule"})
    assert rule == executor.FAIRNESS
    t = rb.read_ompl(STORED.csv)
    assert t["cpu_share"].notna().all() and not any(rule.refuses(r) for r in t.to_dict("records"))
    assert t.loc[t["solved"], "simplified_front_length"].notna().all()
    paths = rb.read_ompl_paths(STORED.paths)
    assert any("+simplify" in k for k in paths) and any("+simplify" not in k for k in paths)


def test_the_reference_is_simplified_for_the_refined_planner_raw_for_the_paper():
    seg, ompl = _tables([1.0], [0.01])
    ompl["front_length"], ompl["simplified_front_length"] = 2.0, 1.6
    simple = rb.compare(seg, ompl).iloc[0]
    raw = rb.compare(seg, ompl, simplified=False).iloc[0]
    assert simple["ompl_front"] == 1.6 and simple["ompl_planner"] == "BITstar +simplify"
    assert simple["ompl_id"] == "f0|BITstar +simplify|5|1" and raw["ompl_id"] == "f0|BITstar|5|1"
    assert raw["ompl_front"] == 2.0 and raw["ompl_planner"] == "BITstar"
    assert simple["ratio"] == pytest.approx(1.0 / 1.6) and raw["ratio"] == pytest.approx(0.5)
    assert (simple["ompl_raw_front"], simple["ompl_simplified_front"]) == (2.0, 1.6)


# -- comparison and verdicts --------------------------------------------------------------
def _tables(ratios, seconds, solved=True, valid=True):
    n = len(ratios)
    seg = pd.DataFrame(
        {
            "group": ["any"] * n,
            "floor": [f"f{i}" for i in range(n)],
            "floor_key": ["k"] * n,
            "variant": "default",
            "solved": solved,
            "reason": "",
            "valid": valid,
            "seconds": seconds,
            "cpu_seconds": seconds,
            "front_length": ratios,
        }
    )
    ompl = pd.DataFrame(
        {
            "floor": [f"f{i}" for i in range(n)],
            "floor_key": "k",
            "planner": "BITstar",
            "budget": 5.0,
            "seed": 1,
            "solved": True,
            "valid": True,
            "front_length": 1.0,
            "simplified_valid": True,
            "simplified_front_length": 1.0,
        }
    )
    return seg, ompl


def test_verdicts_follow_the_criteria():
    seg, ompl = _tables([0.9, 1.0, 1.1], [0.01, 0.02, 0.03])
    v = rb.verdicts(rb.compare(seg, ompl)).set_index("target")
    assert set(v.index) == set(rb.TARGETS)
    assert v.loc["success, any headings", "verdict"] == "met"
    assert v.loc["success, natural headings", "verdict"] == "not met"  # nothing measured
    assert v.loc["success, natural headings", "measured"] == "no OMPL results"
    assert v.loc["plan time, median", "value"] == pytest.approx(20.0)
    assert v.loc["plan time, median", "verdict"] == "met" and v.loc["plan time, median", "timed"]
    assert v.loc["front-wheel length / BIT* 5 s, worst", "value"] == pytest.approx(1.1)
    assert v.loc["front-wheel length / BIT* 5 s, median", "verdict"] == "met"
    assert not v.loc["front-wheel length / BIT* 5 s, median", "timed"]
    assert v.loc["invalid plans", "criterion"] == rb.TARGETS["invalid plans"].text()
    seg, ompl = _tables([1.01, 1.2, 1.3], [0.1, 0.2, 0.4], valid=[True, True, False])
    v = rb.verdicts(rb.compare(seg, ompl)).set_index("target")
    assert v.loc["success, any headings", "verdict"] == "not met"  # 2 of 3
    assert v.loc["success, any headings", "value"] == pytest.approx(2 / 3)
    assert v.loc["invalid plans", "verdict"] == "not met"
    assert v.loc["plan time, median", "verdict"] == "not met"
    assert v.loc["front-wheel length / BIT* 5 s, worst", "value"] == pytest.approx(
        1.2
    )  # the invalid one has none
    assert v.loc["front-wheel length / BIT* 5 s, median", "verdict"] == "not met"
    targets = rb.targets(rb.verdicts(rb.compare(seg, ompl)), {"invalid plans": "f2"})
    assert list(targets.columns) == ["target", "ours", "criterion", "verdict", "why"]
    assert len(targets) == len(rb.TARGETS)
    row = targets[targets["target"] == "invalid plans"].iloc[0]
    assert row["why"] == "f2" and row["verdict"] == "not met" and row["ours"] == "1 of 3 plans"


def test_compare_refuses_results_of_other_floors():
    seg, ompl = _tables([1.0], [0.01])
    ompl["floor_key"] = "other"
    with pytest.raises(ValueError, match="other floors"):
        rb.compare(seg, ompl)


def test_options_subset_and_slow_floors():
    sc = fl.random_floor("natural", 1)
    with pytest.raises(ValueError, match="planner"):  # plan_scenario checks the options
        rb.solve_segplan(sc, options=rb.segplan_options("sideways"))
    with pytest.raises(ValueError, match="time_limit"):
        rb.solve_segplan(sc, options=rb.segplan_options(time_limit=0))
    assert rb.segplan_options() == {} and rb.variant_label({}) == "default"
    assert rb.variant_label(rb.segplan_options(refine=True)) == "+refine"
    opts = rb.segplan_options("paper", time_limit=rb.TIME_LIMIT)
    assert (
        opts == {"planner": "paper", "time_limit": rb.TIME_LIMIT}
        and rb.variant_label(opts) == "planner=paper"
    )
    assert rb.loglog_slope([1, 10, 100], [2, 20, 200]) == pytest.approx(1.0)
    # the smallest internal limit of the default planner is 4 x the "slow" threshold
    assert PAPER_SHARE * rb.TIME_LIMIT == pytest.approx(4 * rb.SLOW_SECONDS)
    groups = rb.floor_groups(quick=True)
    sub = rb.subset(groups, n_random=2)
    assert [g for g, _ in sub] == ["any"] * 2 + ["natural"] * 2 + ["hard"] * len(groups["hard"])
    with pytest.raises(ValueError, match="n_random"):
        rb.subset(groups, n_random=-1)
    t = pd.DataFrame({"floor": ["a", "b"], "seconds": [0.1, rb.SLOW_SECONDS + 0.1]})
    assert list(rb.slow_floors(t)["floor"]) == ["b"]


def test_solve_segplan_measures_a_plan():
    sc = fl.random_floor("natural", 1)
    row, plan = rb.solve_segplan(sc, "natural")
    assert row["floor"] == sc.name and row["floor_key"] == fl.floor_key(sc)
    if row["solved"]:
        assert row["front_length"] == pytest.approx(plan.cost, rel=1e-4)
        assert row["valid"]
    else:
        assert plan is None and row["reason"]


def test_quick_run():
    out = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "robustness.py"), "--quick"],
        capture_output=True,
        text=True,
        timeout=900,
        cwd=ROOT,
    )
    assert out.returncode == 0, out.stderr[-3000:]
    assert "invalid plans" in out.stdout and "success, any headings" in out.stdout
    ompl = ompl_runner.ompl_available()
    assert ("OMPL quick:" in out.stderr) == ompl
    assert ("skipping the OMPL side" in out.stderr) == (not ompl)


def test_run_ompl_stores_fair_runs_and_resumes(tmp_path, monkeypatch):
    """run_ompl through the executor, with fake runs: every run stored once (raw and simplified
    paths at the reference budget), the journal removed, and a second call keeps the stored
    runs (nothing run again) while a starved stored run would be."""
    floors = [("any", fl.random_floor("any", i)) for i in range(2)]
    jobs = [(g, sc, "BITstar", b, 1) for g, sc in floors for b in rb.BUDGETS]
    calls = []

    def fake_record(job, resolution, space):
        assert space == "dubins"  # the default space of both studies
        group, sc, planner, budget, seed = job
        calls.append(rb.job_id(job))
        row = dict.fromkeys(rb.OMPL_COLUMNS, math.nan)
        row.update(group=group, floor=sc.name, floor_key=fl.floor_key(sc), generator=fl.GENERATOR_VERSION)
        row.update(planner=planner, budget=budget, seed=seed, status="Exact solution", solved=True)
        row.update(valid=True, simplified_valid=True, seconds=budget, cpu_seconds=0.95 * budget, messages="")
        row.update(front_length=10.0, simplified_front_length=9.0, load_before=0.1, load_after=0.2)
        return {**row, "poses": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], "simplified_poses": [[0.0, 0.0, 0.0]]}

    monkeypatch.setattr(rb, "ompl_record", fake_record)
    files = rb.ompl_files(tmp_path / "o.csv")
    t = rb.run_ompl(jobs, *files, workers=1)
    assert sorted(calls) == sorted(rb.job_id(j) for j in jobs) and len(t) == len(jobs)
    assert np.allclose(t["cpu_share"], 0.95) and (t["attempts"] == 1).all()
    assert not rb.peers.journal_path(files[0]).exists()
    paths = rb.read_ompl_paths(files[1])
    assert sorted(paths) == sorted(
        f"{sc.name}|{p}|{rb.REFERENCE_BUDGET:g}|1"
        for _, sc in floors
        for p in ("BITstar", "BITstar +simplify")
    )
    prov = json.loads(files[2].read_text())
    last = prov["sessions"][-1]
    assert last["fairness"]["min_share"] == 0.9 and last["runs_done"] == len(jobs)
    calls.clear()
    t2 = rb.run_ompl(jobs, *files, workers=1)
    assert calls == [] and len(t2) == len(jobs)  # resumed: nothing run again
    assert last["runs_kept"] == 0
    assert json.loads(files[2].read_text())["sessions"][-1]["runs_kept"] == len(jobs)


def test_shipped_modules_read_no_repository_folder():
    """Issue 24: a module of the package finds nothing through its own path in the repository
    (``parents[...]`` of ``__file__``): in a wheel those folders do not exist. The stored OMPL
    side is passed by the caller (:func:`rb.ompl_files`); the hard cases' ``turn_around`` is the
    shipped scenario, the same floor as the repository's file."""
    import re

    for f in (ROOT / "segplan").rglob("*.py"):
        assert not re.search(r"__file__\)?(\.resolve\(\))?\.parents\[", f.read_text()), f
    assert (
        STORED.paths.name == "robustness_ompl_paths.json.gz"
        and STORED.provenance.name == "robustness_ompl.json"
    )
    shipped = fl.hard_cases()["turn_around"]
    repo = fl.hard_cases(ROOT / "scenarios")["turn_around"]
    assert fl.floor_key(shipped) == fl.floor_key(repo)
