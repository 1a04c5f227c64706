"""The README's promises: its two commands are what CI runs, its numbers come from a script."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text()


def quick_start_commands():
    section = README.split("## Quick start", 1)[1].split("##", 1)[0]
    block = re.search(r"```bash\n(.*?)```", section, re.S).group(1)
    return [line.split("#", 1)[0].strip() for line in block.splitlines() if line.strip()]


def test_quick_start_has_exactly_two_commands_and_ci_runs_the_test_one():
    commands = quick_start_commands()
    assert commands == ["bash .ci/book", "bash .ci/test"]
    ci = (ROOT / ".ci" / "run").read_text()
    assert "bash .ci/test" in ci
    test = (ROOT / ".ci" / "test").read_text()
    assert "pytest --nbval tests notebooks" in test


def test_every_script_the_readme_names_exists():
    for path in re.findall(r"`((?:benchmarks|scenarios|\.ci)/[\w./-]+)`", README):
        assert (ROOT / path.split()[0]).exists(), path


def test_benchmark_block_is_written_by_the_script():
    block = README.split("<!-- benchmarks:start -->", 1)[1].split("<!-- benchmarks:end -->", 1)[0]
    assert "by `python benchmarks/readme.py`" in block
    assert "Measured on" in block
