"""The README's promises: its two commands are what CI runs, its numbers come from a script."""

import re
from pathlib import Path

from load_file import load_file

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()
CONTRIBUTING = (ROOT / "CONTRIBUTING.md").read_text()


def quick_start_commands():
    section = README.split("## Quick start", 1)[1].split("##", 1)[0]
    block = re.search(r"```bash\n(.*?)```", section, re.S).group(1)
    return [line.split("#", 1)[0].strip() for line in block.splitlines() if line.strip()]


TEST_COMMAND = ".venv/bin/python -m pytest --nbval tests notebooks"


def ci_commands():
    lines = (ROOT / ".ci" / "run").read_text().splitlines()
    return [line.strip() for line in lines if line.strip() and not line.lstrip().startswith("#")]


def test_quick_start_has_two_commands_and_ci_runs_exactly_them_in_order():
    commands = quick_start_commands()
    assert commands == ["bash .ci/book", TEST_COMMAND]
    ci = ci_commands()
    assert all(c in ci for c in commands), ci
    assert ci.index(commands[0]) < ci.index(commands[1])


def test_every_script_the_readme_names_exists():
    for path in re.findall(r"`((?:benchmarks|scenarios|\.ci)/[\w./-]+)`", README + CONTRIBUTING):
        assert (ROOT / path.split()[0]).exists(), path


def test_benchmark_block_is_written_by_the_script():
    block = README.split("<!-- benchmarks:start -->", 1)[1].split("<!-- benchmarks:end -->", 1)[0]
    assert "by `python benchmarks/readme.py`" in block
    assert "Measured on" in block


def test_mutation_block_is_written_from_the_stored_run():
    """The kill rates in CONTRIBUTING.md are those of benchmarks/results/mutation.json."""
    import json

    mutation = load_file(ROOT / "benchmarks" / "mutation.py", "mutation")
    stored = json.loads(mutation.STORED.read_text())
    block = CONTRIBUTING.split(mutation.START, 1)[1].split(mutation.END, 1)[0]
    assert block.strip() == mutation.readme_block(stored, mutation.equivalent_mutants()).strip()
    equivalent = mutation.equivalent_mutants()
    survivors = {n for r in stored["results"] for n in r["survivors"]}
    assert equivalent <= survivors  # the list names only mutants of the stored run


def test_commands_block_is_written_from_the_stored_run():
    """The two commands' times in the README are those of benchmarks/results/readme_commands.json."""
    import json
    import os
    import sys

    environ = dict(os.environ)  # the script pins BLAS threads for its own timings: not for this session
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        script = load_file(ROOT / "benchmarks" / "readme.py", "readme_script")
    finally:
        sys.path.remove(str(ROOT / "benchmarks"))
        os.environ.clear()
        os.environ.update(environ)
    stored = json.loads(script.COMMANDS_JSON.read_text())
    assert [c["command"] for c in stored["commands"]] == quick_start_commands()  # the README's, as typed
    assert all(c["seconds"] > 0 for c in stored["commands"]) and "book_build_seconds" in stored["commands"][0]
    block = README.split(script.COMMANDS_START, 1)[1].split(script.COMMANDS_END, 1)[0]
    assert block.strip() == script.commands_block(stored).strip()


def test_the_first_plan_example_runs(tmp_path, monkeypatch):
    """The README's first Python example, as typed, plans and writes its trajectory."""
    section = README.split("## Install and a first plan", 1)[1].split("\n## ", 1)[0]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md", "exec"), {})
    header = (tmp_path / "trajectory.csv").read_text().splitlines()[0]
    assert header.startswith("t,s,v,a,x,y,theta")


def test_the_library_example_runs(tmp_path, monkeypatch):
    """The README's "Using the library" example, as typed, runs (its files in a temporary folder)."""
    section = README.split("## Using the library", 1)[1].split("\n## ", 1)[0]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md", "exec"), {})
    assert {p.name for p in tmp_path.iterdir()} >= {"law.csv", "law.yaml", "plan.json"}
