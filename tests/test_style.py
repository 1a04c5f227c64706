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
