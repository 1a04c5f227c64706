"""The one executor of the time-budgeted runs (segplan.studies.executor): free cores, the
fairness rule (a starved run is refused, run again, never stored; a run that stays starved
stops the study), the journal that lets a study resume, the Dask path, and a tiny real OMPL
run through it with OMPL's PathSimplifier."""

import json
import math
import sys
import threading
import time

import pytest

from segplan.studies import executor as ex
from segplan.studies import ompl_runner, peers


def fake(job):
    """A fake time-budgeted run: ``job = (name, seconds, cpu_seconds)``."""
    name, seconds, cpu = job
    return {"name": name, "seconds": seconds, "cpu_seconds": cpu}


def test_free_cores_is_cores_less_load_at_least_one_at_most_cap():
    assert ex.free_cores(cores=2, load=0.3) == 2
    assert ex.free_cores(cores=2, load=0.6) == 1
    assert ex.free_cores(cores=2, load=11.0) == 1
    assert ex.free_cores(cores=8, load=1.2) == 7
    assert ex.free_cores(cap=3, cores=8, load=0.0) == 3
    assert 1 <= ex.free_cores() <= (ex.os.cpu_count() or 1)
    with pytest.raises(ValueError, match="cap"):
        ex.free_cores(cap=0)


def test_the_rule_refuses_long_starved_runs_only():
    rule = ex.FAIRNESS
    assert (rule.min_share, rule.min_seconds) == (0.9, 0.5)
    assert rule.refuses({"seconds": 5.0, "cpu_seconds": 2.5})  # share 0.5
    assert rule.refuses({"seconds": 0.5, "cpu_seconds": 0.4})  # share 0.8 at the threshold
    assert not rule.refuses({"seconds": 5.0, "cpu_seconds": 4.6})  # share 0.92
    assert not rule.refuses({"seconds": 0.1, "cpu_seconds": 0.01})  # too short to judge
    assert rule.refuses({"seconds": 1.0, "cpu_seconds": math.nan})  # not measured: refused
    assert ex.cpu_share({"seconds": 2.0, "cpu_seconds": 1.0}) == 0.5
    assert math.isnan(ex.cpu_share({"seconds": 0.0, "cpu_seconds": 1.0}))
    text = rule.provenance()["rule"]
    assert "0.9" in text and "0.5 s" in text and "never stored" in text
    with pytest.raises(ValueError, match="min_share"):
        ex.FairnessRule(min_share=1.5)
    with pytest.raises(ValueError, match="retries"):
        ex.FairnessRule(retries=-1)
    with pytest.raises(ValueError, match="backoff"):
        ex.FairnessRule(backoff=-1.0)


def test_runs_are_stored_as_they_finish_and_a_rerun_resumes(tmp_path):
    journal = tmp_path / "runs.jsonl"
    jobs = [(f"j{i}", 1.0, 0.99) for i in range(5)]
    out = ex.run_jobs(fake, jobs, key=lambda j: j[0], journal=journal, cap=2)
    assert list(out) == [f"j{i}" for i in range(5)]
    assert all(r["attempts"] == 1 and r["cpu_share"] == pytest.approx(0.99) for r in out.values())
    assert len(journal.read_text().splitlines()) == 5
    calls = []

    def counted(job):
        calls.append(job[0])
        return fake(job)

    more = [*jobs, ("j5", 1.0, 1.0)]
    again = ex.run_jobs(counted, more, key=lambda j: j[0], journal=journal, cap=2)
    assert calls == ["j5"]  # the five stored runs are not run again
    assert set(again) == {f"j{i}" for i in range(6)}
    with journal.open("a") as fh:  # an interruption in the middle of a line
        fh.write('{"key": "j6", "rec')
    assert set(ex.Journal(journal).read()) == set(again)


def test_a_stored_starved_run_is_run_again(tmp_path):
    journal = ex.Journal(tmp_path / "runs.jsonl")
    journal.append("a", {"seconds": 5.0, "cpu_seconds": 2.0})  # stored before the rule
    calls = []

    def counted(job):
        calls.append(job[0])
        return fake(job)

    out = ex.run_jobs(counted, [("a", 5.0, 4.9)], key=lambda j: j[0], journal=journal)
    assert calls == ["a"] and out["a"]["cpu_share"] == pytest.approx(0.98)


def test_a_starved_run_is_refused_run_again_and_never_stored(tmp_path):
    """A fake run reporting a CPU share of 0.5 over 5 s: refused; its second attempt, fair, is stored."""
    journal = tmp_path / "runs.jsonl"
    attempts = {}

    def starved_once(job):
        attempts[job] = attempts.get(job, 0) + 1
        share = 0.5 if attempts[job] == 1 else 1.0
        return {"seconds": 5.0, "cpu_seconds": 5.0 * share}

    rule = ex.FairnessRule(backoff=0.05)
    t0 = time.monotonic()
    out = ex.run_jobs(starved_once, ["a", "b"], journal=journal, rule=rule, cap=1)
    assert time.monotonic() - t0 >= 0.05  # each retry waited its back-off
    assert attempts == {"a": 2, "b": 2}
    assert all(r["attempts"] == 2 and r["cpu_share"] == 1.0 for r in out.values())
    stored = [json.loads(line)["record"] for line in journal.read_text().splitlines()]
    assert len(stored) == 2 and all(r["cpu_share"] == 1.0 for r in stored)  # no refused run stored


def test_a_run_that_stays_starved_stops_the_study_loudly(tmp_path):
    journal = tmp_path / "runs.jsonl"
    rule = ex.FairnessRule(retries=2, backoff=0.01)
    assert [rule.wait(a) for a in (1, 2, 3)] == [0.01, 0.02, 0.04]

    def run(job):
        return {"seconds": 1.0, "cpu_seconds": 0.5 if job == "starved" else 1.0}

    with pytest.raises(ex.UnfairRunError, match="starved: CPU share below 0.9 in 3 attempts"):
        ex.run_jobs(run, ["fair", "starved"], journal=journal, rule=rule, cap=1)
    assert set(ex.Journal(journal).read()) == {"fair"}  # the accepted run is kept


def test_at_most_cap_runs_at_once():
    lock, now, peak = threading.Lock(), [0], [0]

    def run(job):
        with lock:
            now[0] += 1
            peak[0] = max(peak[0], now[0])
        time.sleep(0.02)
        with lock:
            now[0] -= 1
        return {"seconds": 0.02, "cpu_seconds": 0.02}

    ex.run_jobs(run, range(12), cap=1)
    assert peak[0] == 1
    with pytest.raises(ValueError, match="same key"):
        ex.run_jobs(run, [1, 1])


def test_a_scheduler_without_distributed_is_a_clear_error(monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed -> ImportError
    with pytest.raises(RuntimeError, match="distributed"):
        ex.run_jobs(fake, [("a", 1.0, 1.0)], scheduler="tcp://127.0.0.1:8786")


def test_runs_on_a_dask_cluster():
    distributed = pytest.importorskip("distributed", reason="dask distributed is not installed")
    with distributed.LocalCluster(
        processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None
    ) as cluster:
        jobs = [(f"j{i}", 1.0, 0.95) for i in range(4)]
        out = ex.run_jobs(fake, jobs, key=lambda j: j[0], scheduler=cluster.scheduler_address)
    assert list(out) == [j[0] for j in jobs]
    assert all(r["name"] == k and r["attempts"] == 1 for k, r in out.items())


@pytest.mark.skipif(not ompl_runner.ompl_available(), reason="the OMPL Python bindings are not installed")
def test_a_real_ompl_run_through_the_executor_with_simplification(tmp_path):
    """RRT* for 0.2 s on single_obstacle, through peers.run_ompl (the executor): raw and
    simplified paths both measured by the shared measure, CPU share and load recorded."""
    cfg = peers.StudyConfig(
        scenarios=("single_obstacle",),
        blocks=(peers.Runs(("single_obstacle",), planners=("RRTstar",), budgets=(0.2,), seeds=(1,)),),
        heuristics=(),
    )
    journal = tmp_path / "j.jsonl"
    table, paths = peers.run_ompl(cfg, jobs=1, journal=journal)
    assert len(table) == 1 and len(journal.read_text().splitlines()) == 1
    r = table.iloc[0]
    assert r["solved"] and r["valid"] and r["simplified_valid"]
    assert 0 < r["simplify_seconds"] <= ompl_runner.SIMPLIFY_SECONDS + 0.5
    assert r["cpu_share"] > 0 and r["attempts"] == 1
    assert math.isfinite(r["load_before"]) and math.isfinite(r["load_after"])
    assert r["simplified_reversals"] == 0 and r["simplified_front_length"] > 0
    assert r["simplified_rear_length"] == pytest.approx(r["simplified_ompl_cost"], rel=1e-4)
    simple = peers.simplified_rows(table)
    assert list(simple["method"]) == ["RRTstar +simplify"]
    assert simple.iloc[0]["front_length"] == r["simplified_front_length"]
    assert set(paths) == {("single_obstacle", m, "dubins", 0.2, 1) for m in ("RRTstar", "RRTstar +simplify")}
