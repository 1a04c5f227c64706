"""The code style the developers' guide asks for: ``ruff`` clean (lint everywhere, format on code).

ruff is a test dependency (``segplan[test]``, pinned in environment.txt).
"""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def ruff(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "ruff", *args], cwd=ROOT, capture_output=True, text=True)


def test_ruff_lint_is_clean():
    out = ruff("check", "segplan", "tests", "benchmarks", "notebooks")
    assert out.returncode == 0, out.stdout + out.stderr


def test_ruff_format_is_clean():
    out = ruff("format", "--check", "segplan", "tests", "benchmarks")
    assert out.returncode == 0, out.stdout + out.stderr


#: A smoke alarm, not a rule to code to (issue 24): a module is one idea and is split where a
#: concept ends, never to fit a number; a module past this many lines is worth a look.
SMOKE_ALARM_LINES = 800


def test_no_module_sets_off_the_line_smoke_alarm():
    long = {
        str(p.relative_to(ROOT)): n
        for p in sorted((ROOT / "segplan").rglob("*.py"))
        if (n := len(p.read_text(encoding="utf-8").splitlines())) > SMOKE_ALARM_LINES
    }
    assert not long, f"modules over {SMOKE_ALARM_LINES} lines (is each still one idea?): {long}"
