"""Re-create the hand-made mutations of issue 15 and check that each now fails a test.

Each mutation is one textual patch of one module (``old`` must occur exactly once). For
each, the package, the tests and the scenarios are copied into a temporary directory, the
patch is applied there (the working tree is never touched), and the targeted tests run
with ``pytest -x``. A mutation is *killed* when pytest fails. The script exits non-zero if
any mutation survives or a patch no longer applies (the code moved: update ``old``).

Run (about a minute per mutation on a quiet 2-core machine)::

    PYTHONPATH=$PWD python benchmarks/issue15_mutations.py            # all
    PYTHONPATH=$PWD python benchmarks/issue15_mutations.py h_b_zero   # some, by name

The consistent sign flip of the cross term of [2] (also listed in issue 15) is guarded by
the golden-constant tests of the other half of the issue, not re-created here.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


@dataclass(frozen=True)
class Mutation:
    name: str
    module: str  # path relative to the repository
    old: str
    new: str
    tests: tuple[str, ...]
    what: str


SEARCH_TESTS = ("tests/test_search_oracles.py",)
REFINE_TESTS = ("tests/test_refine_oracles.py",)

MUTATIONS = (
    Mutation(
        "h_b_zero",
        "segplan/planning/paper/problem.py",
        'if self.cost == "distance" or self.heuristic == "b" or d == 0.0 and pose.theta == goal.theta:\n'
        "            return d",
        'if self.heuristic == "b":\n'
        "            return 0.0\n"
        '        if self.cost == "distance" or d == 0.0 and pose.theta == goal.theta:\n'
        "            return d",
        SEARCH_TESTS,
        "h' (b) returns 0 (uniform cost)",
    ),
    Mutation(
        "no_closed_set",
        "segplan/planning/paper/search.py",
        "            closed.add(key)\n",
        "            pass\n",
        SEARCH_TESTS,
        "the closed set removed",
    ),
    Mutation(
        "f_is_h",
        "segplan/planning/paper/search.py",
        'f = g + (0.0 if succ.kind == "goal" else self.problem.cost_to_go(succ.pose, depth))',
        'f = 0.0 if succ.kind == "goal" else self.problem.cost_to_go(succ.pose, depth)',
        SEARCH_TESTS,
        "f = h' instead of g + h' (greedy)",
    ),
    Mutation(
        "move_adds_length",
        "segplan/planning/refine.py",
        "if self.link(a, q) + self.link(q, b) < now - gain:",
        "if self.link(a, q) + self.link(q, b) > now - gain:",
        REFINE_TESTS,
        "a local move is accepted unless it lowers the cost",
    ),
    Mutation(
        "move_unchecked",
        "segplan/planning/refine.py",
        "if self.link(a, q) + self.link(q, b) < now - gain:",
        "if True:",
        REFINE_TESTS,
        "a screened local move is taken without its exact check",
    ),
    Mutation(
        "no_never_longer_guard",
        "segplan/planning/refine.py",
        "if not cost < plan.cost:",
        "if False:",
        REFINE_TESTS,
        "the final 'never longer' guard removed",
    ),
    Mutation(
        "certain_failures_never",
        "segplan/planning/refine.py",
        "        bad[look] = np.any(ws.inside(wx[look], wy[look]), axis=1)\n    return bad",
        "        bad[look] = np.any(ws.inside(wx[look], wy[look]), axis=1)\n    return bad & False",
        REFINE_TESTS,
        "certain_failures flags nothing",
    ),
    Mutation(
        "certain_failures_walls_skipped",
        "segplan/planning/refine.py",
        "    if ws.bounds is not None:\n        xmin, ymin, xmax, ymax = ws.bounds",
        "    if False:\n        xmin, ymin, xmax, ymax = ws.bounds",
        REFINE_TESTS,
        "certain_failures ignores the walls",
    ),
    Mutation(
        "front_fallback_free",
        "segplan/floor/collision.py",
        "            return float(cand[np.argmin((sw.point(cand, t) @ N.T - H).max(axis=1))])",
        "            return None",
        ("tests/test_collision_fallbacks.py",),
        "the front-wheel fallback answers 'free' instead of 'collision'",
    ),
    Mutation(
        "wall_fallback_free",
        "segplan/floor/collision.py",
        "        if e <= tol or np.count_nonzero(live) > _FRONT_MAX_PIECES:\n            return True",
        "        if e <= tol or np.count_nonzero(live) > _FRONT_MAX_PIECES:\n            return False",
        ("tests/test_collision_fallbacks.py",),
        "the walls' front-wheel fallback answers 'inside' instead of 'out'",
    ),
    Mutation(
        "cubic_one_root",
        "segplan/floor/sweep.py",
        "    r = np.linalg.eigvals(comp).real\n",
        "    r = np.linalg.eigvals(comp).real\n    r = np.repeat(r[:, :1], 3, axis=1)\n",
        (
            "tests/test_collision.py::test_cubic_points_find_real_roots",
            "tests/test_collision.py::test_cubic_points_find_each_distinct_root",
        ),
        "sweep.cubic_points returns one root three times",
    ),
)


def run(m: Mutation, python: str) -> tuple[str, float, str]:
    with tempfile.TemporaryDirectory(prefix=f"mut-{m.name}-") as tmp:
        tmp = Path(tmp)
        for part in ("segplan", "tests", "scenarios"):
            shutil.copytree(ROOT / part, tmp / part, ignore=shutil.ignore_patterns("__pycache__"))
        shutil.copy(ROOT / "pyproject.toml", tmp / "pyproject.toml")
        path = tmp / m.module
        text = path.read_text()
        if text.count(m.old) != 1:
            return "no-patch", 0.0, f"{m.module}: the patched text occurs {text.count(m.old)} times"
        path.write_text(text.replace(m.old, m.new))
        t0 = time.perf_counter()
        proc = subprocess.run(
            [python, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", *m.tests],
            cwd=tmp,
            env={"PYTHONPATH": str(tmp), "PATH": "/usr/bin:/bin", "HOME": str(tmp)},
            capture_output=True,
            text=True,
        )
        seconds = time.perf_counter() - t0
        failed = [line for line in proc.stdout.splitlines() if line.startswith("FAILED")]
        status = "killed" if proc.returncode == 1 else "survived" if proc.returncode == 0 else "error"
        detail = failed[0] if failed else proc.stdout.strip().splitlines()[-1] if proc.stdout.strip() else ""
        return status, seconds, detail


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("names", nargs="*", help="mutations to run (default: all)")
    parser.add_argument("--python", default=sys.executable)
    args = parser.parse_args(argv)
    chosen = [m for m in MUTATIONS if not args.names or m.name in args.names]
    bad = 0
    for m in chosen:
        status, seconds, detail = run(m, args.python)
        bad += status != "killed"
        print(f"{m.name:32s} {status:9s} {seconds:6.1f} s  {m.what}\n{'':32s} {detail}", flush=True)
    print(f"{len(chosen) - bad}/{len(chosen)} killed")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
