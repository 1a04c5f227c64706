"""The mutation scripts of issue 15 still apply to the code (their patches and targets exist)."""

import json
from pathlib import Path

import pytest
from load_file import load_file

ROOT = Path(__file__).resolve().parent.parent


def load(name):
    return load_file(ROOT / "benchmarks" / f"{name}.py", name)


@pytest.mark.parametrize("mutation", load("issue15_mutations").MUTATIONS, ids=lambda m: m.name)
def test_hand_made_mutation_applies(mutation):
    """Each patch text occurs exactly once (else the code moved: update the script)."""
    assert (ROOT / mutation.module).read_text().count(mutation.old) == 1
    assert mutation.old != mutation.new
    for test in mutation.tests:
        assert (ROOT / test.split("::")[0]).is_file()


def test_mutmut_targets_exist():
    mutation = load("mutation")
    for module, tests in mutation.TARGETS.items():
        assert (ROOT / "segplan" / f"{module}.py").is_file()
        assert all((ROOT / t.split("::")[0]).is_file() for t in tests)
        for t in tests:  # a test named by node id exists in its file
            if "::" in t:
                path, name = t.split("::")
                assert f"def {name}(" in (ROOT / path).read_text(), t
    config = mutation._pyproject("planning/paper/search")
    assert (
        config.count("[tool.mutmut]") == 1 and 'only_mutate = ["segplan/planning/paper/search.py"]' in config
    )


def test_merge_replaces_and_adds_modules_with_their_provenance(tmp_path):
    """``mutation.py --merge``: a later run's modules replace or join the stored ones."""
    mutation = load("mutation")

    def run(when, modules):
        meta = {"when": when, "commit": "c" * 40, "command": f"python mutation.py {when}", "seed": 0}
        meta |= {
            "sample_per_module": 5,
            "mutmut": "3.8.1",
            "targets": {m: [f"tests/{m}.py"] for m in modules},
        }
        results = [{"module": m, "sample": 5, "survivors": [], "when": when} for m in modules]
        return {"meta": meta, "results": results}

    stored, later = tmp_path / "stored.json", tmp_path / "later.json"
    stored.write_text(json.dumps(run("first", ["search", "frame"])))
    later.write_text(json.dumps(run("later", ["frame", "frame_exact"])))
    assert mutation.main(["--merge", str(later), "--json", str(stored)]) == 0
    merged = json.loads(stored.read_text())
    assert [(r["module"], r["when"]) for r in merged["results"]] == [
        ("search", "first"), ("frame", "later"), ("frame_exact", "later"),
    ]  # fmt: skip
    assert "run" not in merged["results"][0] and merged["results"][2]["run"]["when"] == "later"
    assert merged["meta"]["when"] == "first" and merged["meta"]["merged"][0]["modules"] == [
        "frame",
        "frame_exact",
    ]
    assert merged["meta"]["targets"]["frame_exact"] == ["tests/frame_exact.py"]


def test_same_plans_compare_reports_every_difference():
    same_plans = load_file(ROOT / "benchmarks" / "same_plans.py", "same_plans")
    before = {
        "a": ["plan", (2.0).hex(), [[(0.0).hex()] * 3]],
        "b": ["fail", "exhausted"],
        "c": ["fail", "time"],
    }
    assert same_plans.compare(before, dict(before)) == []
    after = {**before, "a": ["plan", (2.02).hex(), before["a"][2]], "b": ["plan", (3.0).hex(), []]}
    del after["c"]
    lines = same_plans.compare(before, after)
    assert lines[0] == "a: 2.000000 m -> 2.020000 m (+1.000%)"
    assert (
        lines[1].startswith("b: ['fail', 'exhausted'] -> ['plan'")
        and lines[2] == "c: ['fail', 'time'] -> None"
    )
    # nodes alone differing is a difference too
    moved = {**before, "a": ["plan", before["a"][1], [[(1.0).hex()] * 3]]}
    assert same_plans.compare(before, moved) == ["a: 2.000000 m -> 2.000000 m (+0.000%)"]


def test_same_plans_refuses_records_of_different_time_limits(tmp_path, capsys):
    same_plans = load_file(ROOT / "benchmarks" / "same_plans.py", "same_plans")
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    a.write_text(json.dumps({"time_limit": [120.0], "x": ["fail", "time"]}))
    b.write_text(json.dumps({"time_limit": [10.0], "x": ["fail", "time"]}))
    assert same_plans.main(["--compare", str(a), str(b)]) == 2
    assert "different time limits" in capsys.readouterr().out
    assert same_plans.main(["--compare", str(a), str(a)]) == 0
    assert "the same 1 plans" in capsys.readouterr().out
