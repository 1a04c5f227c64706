"""Mutation testing of segplan with mutmut (issue 15): chosen modules, a random sample each.

Not part of CI's default run (it takes minutes to about half an hour). For each chosen
module the repository (package, tests, scenarios, benchmarks) is copied into a temporary directory
with a ``[tool.mutmut]`` configuration that mutates only that module and runs only its
targeted tests (``TARGETS``); mutmut then runs, for each mutant, the targeted tests that
call the mutated function. The working tree is never touched.

A sample is drawn at random (``--seed``) among the module's mutants; mutmut runs twice per
module (once to generate the mutants and collect which tests call which function, once on
the sample). The report gives, per module, the mutants killed, survived, timed out (a
mutant that loops: counted as killed, as mutmut's own "timeout" is a detection) and with no
covering test, the kill rate over the sample, and the survivors' names (``--show`` prints
their diffs: read them, and list the equivalent ones with the reason).

Run, niced (the machine is shared)::

    PYTHONPATH=$PWD nice -n 10 python benchmarks/mutation.py \
        --modules planning/paper/search planning/refine --sample 20
    PYTHONPATH=$PWD nice -n 10 python benchmarks/mutation.py --sample 40 --json mutation.json

Budget: about 30 minutes for 6 modules x 40 mutants with 2 workers; about 25 minutes for the 25
modules of ``planning/`` x 10 (issue 24).

The stored run is ``benchmarks/results/mutation.json`` (its ``meta`` says when, on which
commit, with which command and seed); the survivors judged equivalent are listed, each with
its reason, in ``benchmarks/results/mutation_equivalent.md``. The kill rates in ``CONTRIBUTING.md`` are
written from those two files, never typed::

    python benchmarks/mutation.py --readme     # rewrite CONTRIBUTING.md's block; runs nothing
"""

from __future__ import annotations

import argparse
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

#: Targeted tests per module: fast, and between them guarding the module's behaviour.
#: Issue 15 names search, refine, expansion, collision, cost and frame; since the layout of
#: issue 11 their code also lives in problem (h', the cost-to-go), links (a link's union and
#: LONGD), validity (is a pose, a union free: the planner's view of collision), sweep (the
#: swept segment), geometry (the segment-polygon and pose predicates, polygons, bounds) and
#: frame_exact (the exact optimal frame), so those are mutated too. Issue 24 adds every other
#: module of ``planning/``: the entry points and the default pipeline (api, default, stages,
#: context, options, schedule, plan), the paper's bisectrix and Dubins' lower bound, and each
#: part of the lattice (``LATTICE``: its search, A*, frame, primitives, clearance, edges,
#: approach, guide, escape and shortcut), each with the lattice's oracles and parts tests.
LATTICE = [
    "tests/test_lattice_oracles.py",  # optimal on the graph it generated, Dubins vs OMPL, exact LONGD
    "tests/test_lattice_parts.py",
    "tests/test_deferred.py",  # the deferred repair: the cheapest passing edge
    "tests/test_escape_costtogo.py",
    "tests/test_lattice_enclosure.py",
    "tests/test_lattice_deadline.py",
    "tests/test_lattice.py",
    "tests/test_lattice_layers.py",
    "tests/test_lattice_pinned.py",
    "tests/test_no_path_messages.py",  # what a failed lattice says of its ends (dead end, way out)
]
TARGETS = {
    # the planner's search and refinement
    "planning/paper/search": [
        "tests/test_search_oracles.py",
        "tests/test_search.py",
        "tests/test_no_path_messages.py",  # what an exhausted search says
    ],
    "planning/paper/problem": ["tests/test_search_oracles.py", "tests/test_search.py"],
    "planning/paper/expansion": [
        "tests/test_expansion.py",
        "tests/test_fast_paths.py",
        "tests/test_search_oracles.py",
    ],
    "planning/links": [
        "tests/test_fast_paths.py",
        "tests/test_expansion.py",
        "tests/test_search_oracles.py",
        "tests/test_search.py",  # the link observer
    ],
    "planning/refine": ["tests/test_refine_oracles.py", "tests/test_refine.py", "tests/test_buckets.py"],
    # collision
    "planning/validity": [
        "tests/test_expansion.py",
        "tests/test_fast_paths.py",
        "tests/test_refine_oracles.py",
        "tests/test_refine.py",
        "tests/test_search_oracles.py::test_collision_counters_pinned",  # the shortcuts' counters
        # the broad phase of many obstacles (arrays) against the scalar loop
        "tests/test_lattice_enclosure.py::test_vectorised_broad_phase_decides_as_the_scalar_loop",
        # the obstacles' index and the tests that read it, against brute force (issue 25)
        "tests/test_buckets.py",
    ],
    # issue 24: the rest of planning/ -- entry points, options and the default pipeline
    "planning/api": [
        "tests/test_search.py",
        "tests/test_search_oracles.py",
        "tests/test_context.py",
        "tests/test_default_pipeline.py",
        "tests/test_options.py",
        "tests/test_cli_options.py",
        "tests/test_approx.py",  # plan_scenario_observed
        "tests/test_lattice_enclosure.py",
        "tests/test_lattice_pinned.py",
    ],
    "planning/default": [
        "tests/test_context.py",
        "tests/test_default_pipeline.py",
        "tests/test_options.py",
        "tests/test_lattice_enclosure.py",
        "tests/test_lattice_pinned.py",
    ],
    "planning/stages": [
        "tests/test_default_pipeline.py",
        "tests/test_context.py",
        "tests/test_search_oracles.py",
        "tests/test_refine.py",
        "tests/test_lattice_enclosure.py",
        "tests/test_lattice_pinned.py",
        "tests/test_cli_options.py",
    ],
    "planning/context": [
        "tests/test_context.py",
        "tests/test_default_pipeline.py",
        "tests/test_lattice_deadline.py",
        "tests/test_lattice_enclosure.py",
    ],
    "planning/options": [
        "tests/test_options.py",
        "tests/test_default_pipeline.py",
        "tests/test_context.py",
        "tests/test_cli_options.py",
    ],
    "planning/schedule": [
        "tests/test_lattice_parts.py",
        "tests/test_lattice_oracles.py",
        "tests/test_options.py",
        "tests/test_lattice_deadline.py",
        "tests/test_lattice_enclosure.py",
    ],
    "planning/plan": [
        "tests/test_cost_chain.py",
        "tests/test_lattice_oracles.py",
        "tests/test_lattice_enclosure.py",
        "tests/test_escape_costtogo.py",
        "tests/test_default_pipeline.py",
        "tests/test_search.py",
        "tests/test_options.py",  # a plan's summary (to_dict), the limits' messages
    ],
    "planning/dubins": [
        "tests/test_lattice.py",
        "tests/test_lattice_oracles.py",  # Dubins against a brute-force shortest path
        "tests/test_escape_costtogo.py",
    ],
    "planning/paper/bisectrix": [
        "tests/test_expansion.py",
        "tests/test_fast_paths.py",
        "tests/test_search_oracles.py",
    ],
    # the lattice's parts
    "planning/lattice/search": [*LATTICE, "tests/test_options.py"],
    "planning/lattice/astar": LATTICE,
    "planning/lattice/frame": LATTICE,
    "planning/lattice/primitives": [*LATTICE, "tests/test_primitives_data.py"],
    "planning/lattice/clearance": ["tests/test_clearance.py", *LATTICE],
    "planning/lattice/edges": LATTICE,
    "planning/lattice/approach": LATTICE,
    "planning/lattice/guide": LATTICE,
    "planning/lattice/escape": LATTICE,
    "planning/lattice/shortcut": LATTICE,
    "planning/lattice/chains": [*LATTICE, "tests/test_batched_unions.py"],
    "planning/lattice/dead_end": ["tests/test_no_path_messages.py"],
    "floor/collision": ["tests/test_collision.py", "tests/test_collision_fallbacks.py"],
    "floor/sweep": ["tests/test_collision.py", "tests/test_collision_fallbacks.py"],
    "floor/buckets": ["tests/test_buckets.py"],
    "floor/geometry": [
        "tests/test_geometry.py",
        "tests/test_collision.py",
        "tests/test_collision_fallbacks.py",
        "tests/test_world.py::test_enlargement_excess_is_attained_on_a_square",
    ],
    # the cost and the frame
    "model/cost": [
        "tests/test_approx.py",
        "tests/test_cost_gauss.py",  # the refinement's Gauss-Legendre cost
        "tests/test_derivation.py",
        "tests/test_romberg.py",
        "tests/test_fast_paths.py",
        "tests/test_cost_chain.py",  # a chain's exact LONGD (chain_longd)
    ],
    "model/frame": ["tests/test_frame.py"],
    "model/frame_exact": ["tests/test_frame.py"],
}

RESULTS = ROOT / "benchmarks" / "results"
STORED = RESULTS / "mutation.json"
EQUIVALENT = RESULTS / "mutation_equivalent.md"
START, END = "<!-- mutation:start -->", "<!-- mutation:end -->"

KILLED = {1, 3}  # pytest failed (3: an internal error, counted as a kill by mutmut)
TIMEOUT = {36, -24, 24, 152, 255}
NO_TESTS = {5, 33}

CONFIG = """
[tool.mutmut]
source_paths = ["segplan"]
only_mutate = ["segplan/{module}.py"]
also_copy = ["scenarios", "benchmarks"]
pytest_add_cli_args = ["-p", "no:cacheprovider", "-q"]
pytest_add_cli_args_test_selection = {tests}
use_git_change_detection = false
"""


def _pyproject(module: str) -> str:
    text = (ROOT / "pyproject.toml").read_text()
    # drop the repository's own defaults: from the table's header to the next table
    text = re.sub(r"\n\[tool\.mutmut\]\n(?:(?!\n\[).)*", "\n", text, flags=re.DOTALL)
    return text + CONFIG.format(module=module, tests=json.dumps(TARGETS[module]))


def _mutmut(args, cwd: Path, python: str, log) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH="", HYPOTHESIS_STORAGE_DIRECTORY=str(cwd / ".hypothesis"))
    proc = subprocess.run([python, "-m", "mutmut", *args], cwd=cwd, env=env, capture_output=True, text=True)
    log.write(proc.stdout[-4000:] + proc.stderr[-4000:])
    return proc


def _meta(cwd: Path, module: str) -> dict:
    path = cwd / "mutants" / "segplan" / f"{module}.py.meta"
    return json.loads(path.read_text())["exit_code_by_key"] if path.exists() else {}


def _commit() -> str:
    """The commit of the working tree, with ``+dirty`` if it has uncommitted changes."""
    git = ["git", "-C", str(ROOT)]
    head = subprocess.run([*git, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(
        [*git, "status", "--porcelain", "segplan", "tests"], capture_output=True, text=True
    )
    return head + ("+dirty" if dirty.stdout.strip() else "")


def _mutmut_version(python: str) -> str:
    code = "import importlib.metadata as m; print(m.version('mutmut'))"
    return subprocess.run([python, "-c", code], capture_output=True, text=True).stdout.strip()


def run_module(
    module: str, sample: int, seed: int, python: str, workers: int, show: bool, log, only=None
) -> dict:
    """Run a random sample of ``module``'s mutants (or the mutants named in ``only``)."""
    t0 = time.perf_counter()
    # the tree is copied now: record its commit and time per module (tests may grow meanwhile)
    copied = {"commit": _commit(), "started": time.strftime("%Y-%m-%d %H:%M:%S %Z")}
    with tempfile.TemporaryDirectory(prefix=f"mutmut-{module.replace('/', '-')}-") as tmp:
        tmp = Path(tmp)
        # benchmarks too: some tests load a benchmark script (the robots' floors of test_escape_costtogo)
        for part in ("segplan", "tests", "scenarios", "benchmarks"):
            shutil.copytree(ROOT / part, tmp / part, ignore=shutil.ignore_patterns("__pycache__"))
        (tmp / "pyproject.toml").write_text(_pyproject(module))
        # 1. generate the mutants and the test-to-function stats (a name that matches nothing)
        _mutmut(["run", "--max-children", str(workers), "segplan.nothing_matches_this"], tmp, python, log)
        names = sorted(_meta(tmp, module))
        if not names:
            raise RuntimeError(f"mutmut generated no mutants for {module} (see the log)")
        if only is None:
            chosen = sorted(random.Random(f"{seed}:{module}").sample(names, min(sample, len(names))))
        else:
            missing = sorted(set(only) - set(names))
            if missing:
                raise RuntimeError(f"{module}: no such mutants (the code changed?): {missing}")
            chosen = sorted(only)
        # 2. run the sample
        _mutmut(["run", "--max-children", str(workers), *chosen], tmp, python, log)
        codes = _meta(tmp, module)
        result = {"module": module, "mutants": len(names), "sample": len(chosen), **copied}
        groups = {"killed": [], "timeout": [], "survived": [], "no_tests": [], "other": []}
        for name in chosen:
            code = codes.get(name)
            key = (
                "killed"
                if code in KILLED
                else "timeout"
                if code in TIMEOUT
                else "survived"
                if code == 0
                else "no_tests"
                if code in NO_TESTS
                else "other"
            )
            groups[key].append(name if key != "other" else f"{name} (exit {code})")
        result.update({k: len(v) for k, v in groups.items()})
        result["survivors"] = groups["survived"]
        result["uncovered"] = groups["no_tests"]
        result["unclassified"] = groups["other"]
        decided = len(chosen) - len(groups["other"])
        caught = len(groups["killed"]) + len(groups["timeout"])
        result["kill_rate"] = caught / decided if decided else float("nan")
        if show:
            result["diffs"] = {
                name: _mutmut(["show", name], tmp, python, log).stdout for name in groups["survived"]
            }
    result["seconds"] = time.perf_counter() - t0
    return result


def equivalent_mutants(path: Path = EQUIVALENT) -> set[str]:
    """Names of the mutants judged equivalent: each list item of the file starts with one."""
    return set(re.findall(r"^- `([^`]+)`", path.read_text(), flags=re.MULTILINE))


def summary(stored: dict, equivalent: set[str]) -> list[dict]:
    """Per module: sample, killed (timeouts included), equivalent, real survivors, kill rate.

    The kill rate excludes the equivalent mutants: ``killed / (sample - equivalent)``.
    """
    rows = []
    for r in stored["results"]:
        eq = [n for n in r["survivors"] if n in equivalent]
        live = [n for n in r["survivors"] if n not in equivalent]
        killed = r["killed"] + r["timeout"]
        judged = r["sample"] - r["other"] - len(eq)
        rows.append(
            {
                "module": r["module"],
                "mutants": r["mutants"],
                "sample": r["sample"],
                "killed": killed,
                "equivalent": len(eq),
                "survived": live,
                "uncovered": r["no_tests"],
                "kill_rate": killed / judged if judged else float("nan"),
            }
        )
    return rows


def readme_block(stored: dict, equivalent: set[str]) -> str:
    """The table of kill rates in CONTRIBUTING.md, from the stored run and the equivalent list."""
    meta, rows = stored["meta"], summary(stored, equivalent)
    lines = [
        f"Measured on {meta['when']} at commit `{meta['commit'][:12]}`, mutmut {meta['mutmut']}, "
        f"seed {meta['seed']}, {meta['sample_per_module']} random mutants per module, by "
        f"`{meta['command']}` (stored in `benchmarks/results/mutation.json`; equivalent mutants, "
        "each with its reason, in `benchmarks/results/mutation_equivalent.md`; this block is "
        "written by `python benchmarks/mutation.py --readme`).",
    ]
    if meta.get("note"):
        lines[0] += " " + meta["note"]
    for merged in meta.get("merged", []):
        names = ", ".join(f"`{m}`" for m in merged["modules"])
        lines[0] += (
            f" {names} ran later, on {merged['when']} at commit `{merged['commit'][:12]}` "
            f"(seed {merged['seed']}, {merged['sample_per_module']} random mutants, by "
            f"`{merged['command']}`), and was merged in (`--merge`)."
        )
    reruns = sorted({(r["when"], r["commit"]) for m in stored["results"] for r in m.get("reruns", [])})
    if reruns:
        when = ", ".join(f"on {w} at commit `{c[:12]}`" for w, c in reruns)
        lines[0] += (
            f" The survivors of the modules that got new tests were then run again ({when}: "
            "`--rerun-survivors`) with the tests "
            "added to kill them; the package was unchanged, so earlier kills stand."
        )
    lines += [
        "",
        "| module | mutants | sampled | killed | equivalent | survived | no targeted test | kill rate |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        lines.append(
            f"| `{r['module']}` | {r['mutants']} | {r['sample']} | {r['killed']} | {r['equivalent']} "
            f"| {len(r['survived'])} | {r['uncovered']} | {100 * r['kill_rate']:.0f} % |"
        )
    killed = sum(r["killed"] for r in rows)
    judged = sum(r["sample"] - r["equivalent"] for r in rows)
    sampled = sum(r["sample"] for r in rows)
    lines += [
        "",
        f"In all: {killed} of {judged} non-equivalent mutants killed ({100 * killed / judged:.1f} %) "
        f"in a sample of {sampled} (target: at least 90 % of at least 200).",
    ]
    return "\n".join(lines)


def write_readme(readme: Path = ROOT / "CONTRIBUTING.md") -> None:
    stored = json.loads(STORED.read_text())
    text = readme.read_text()
    head, rest = text.split(START, 1)
    _, tail = rest.split(END, 1)
    block = readme_block(stored, equivalent_mutants())
    readme.write_text(f"{head}{START}\n{block}\n{END}{tail}")


def rerun_survivors(args) -> int:
    """Run the stored survivors of ``args.modules`` again and record which are now killed.

    Tests are only ever added between the two runs (the package is unchanged), so a mutant
    killed in the stored run stays killed; only the survivors, and the mutants that no
    targeted test called, need to run again. The re-run's provenance is kept beside the
    first run's, per module.
    """
    stored = json.loads(args.json.read_text())
    rerun = {
        "when": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "commit": _commit(),
        "command": " ".join(["python", *sys.argv]),
    }
    stored["meta"].setdefault("reruns", []).append(rerun)
    with open(args.log, "w") as log:
        for r in stored["results"]:
            # the survivors, and the mutants no targeted test called (tests may cover them now)
            names = r["survivors"] + r["uncovered"]
            if r["module"] not in args.modules or not names:
                continue
            again = run_module(
                r["module"], 0, args.seed, args.python, args.workers, args.show, log, only=names
            )
            newly = [n for n in names if n not in again["survivors"] + again["uncovered"]]
            r["killed"] += again["killed"]
            r["timeout"] += again["timeout"]
            r["other"] += again["other"]
            r["unclassified"] += again["unclassified"]
            r["survivors"] = again["survivors"]
            r["survived"] = len(again["survivors"])
            r["uncovered"] = again["uncovered"]
            r["no_tests"] = len(again["uncovered"])
            decided = r["sample"] - r["other"]
            r["kill_rate"] = (r["killed"] + r["timeout"]) / decided if decided else float("nan")
            if "diffs" in r:
                r["diffs"] = {n: d for n, d in r["diffs"].items() if n in r["survivors"]}
                r["diffs"].update(again.get("diffs", {}))
            r.setdefault("reruns", []).append({**rerun, "killed_now": newly, "seconds": again["seconds"]})
            print(
                f"{r['module']:10s} re-run of {len(names)} survivors and uncovered: {len(newly)} now killed"
            )
            for name in r["survivors"]:
                print(f"    still survives: {name}")
            for name in r["uncovered"]:
                print(f"    still no test calls it: {name}")
            args.json.write_text(json.dumps(stored, indent=1) + "\n")
    return 0


def merge_run(args) -> int:
    """Merge the modules of another run (``--merge RUN.json``) into ``--json`` (the stored run).

    A module already stored is replaced; the others are kept. Each merged module keeps its
    run's provenance (``run``: when, commit, command, seed, sample), and the stored
    ``meta`` lists the merges.
    """
    stored = json.loads(args.json.read_text())
    run = json.loads(args.merge.read_text())
    m = run["meta"]
    provenance = {k: m[k] for k in ("when", "commit", "command", "seed", "sample_per_module", "mutmut")}
    modules = [r["module"] for r in run["results"]]
    by_module = {r["module"]: i for i, r in enumerate(stored["results"])}
    for r in run["results"]:
        r = {**r, "run": provenance}
        if r["module"] in by_module:
            stored["results"][by_module[r["module"]]] = r
        else:
            stored["results"].append(r)
    stored["meta"].setdefault("merged", []).append({**provenance, "modules": modules})
    for module in modules:
        stored["meta"]["targets"][module] = m["targets"][module]
    args.json.write_text(json.dumps(stored, indent=1) + "\n")
    print(f"merged {', '.join(modules)} from {args.merge} into {args.json}")
    return 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--modules", nargs="+", default=list(TARGETS), choices=list(TARGETS))
    parser.add_argument("--sample", type=int, default=40, help="mutants per module (random sample)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--python", default=sys.executable)
    parser.add_argument("--json", type=Path, help="write the results here")
    parser.add_argument("--show", action="store_true", help="keep the survivors' diffs")
    parser.add_argument("--log", type=Path, default=Path(tempfile.gettempdir()) / "segplan-mutmut.log")
    parser.add_argument("--readme", action="store_true", help="only rewrite CONTRIBUTING.md's block")
    parser.add_argument(
        "--merge",
        type=Path,
        metavar="RUN_JSON",
        help="merge the modules of another run into --json (a module stored there is replaced)",
    )
    parser.add_argument(
        "--rerun-survivors",
        action="store_true",
        help="run the survivors stored in --json again (after tests were added) and update it",
    )
    args = parser.parse_args(argv)
    if args.readme:
        write_readme()
        return 0
    if args.rerun_survivors:
        return rerun_survivors(args)
    if args.merge:
        args.json = args.json or STORED
        return merge_run(args)
    meta = {
        "when": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "host": os.uname().nodename,
        "cores": os.cpu_count(),
        "commit": _commit(),
        "command": " ".join(["python", *sys.argv]),
        "seed": args.seed,
        "sample_per_module": args.sample,
        "workers": args.workers,
        "mutmut": _mutmut_version(args.python),
        "targets": {m: TARGETS[m] for m in args.modules},
    }
    results = []
    with open(args.log, "w") as log:
        for module in args.modules:
            r = run_module(module, args.sample, args.seed, args.python, args.workers, args.show, log)
            results.append(r)
            print(
                f"{module:10s} {r['killed'] + r['timeout']:3d}/{r['sample'] - r['other']:3d} killed "
                f"({100 * r['kill_rate']:5.1f} %), {r['survived']} survived, {r['no_tests']} without tests, "
                f"{r['other']} unclassified; {r['mutants']} mutants in all; {r['seconds']:.0f} s",
                flush=True,
            )
            for name in r["uncovered"]:
                print(f"    no test calls it: {name}")
            for name in r["survivors"]:
                print(f"    survived: {name}")
                if args.show:
                    print(r["diffs"][name])
            if args.json:  # after each module, so an interrupted run keeps what it measured
                meta["finished"] = time.strftime("%Y-%m-%d %H:%M:%S %Z")
                args.json.write_text(json.dumps({"meta": meta, "results": results}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
