"""Write the README's measured-speed block from the benchmark scripts (never typed by hand).

Runs ``benchmarks/longd_speed.py`` (the cost LONGD, formulas [1] and [2]) and the planner
timing of ``benchmarks/search_speed.py`` on this machine, one core, and replaces the text
between ``<!-- benchmarks:start -->`` and ``<!-- benchmarks:end -->`` in README.md with the
results, the date and the machine they were measured on.

It also writes the block between ``<!-- commands:start -->`` and ``<!-- commands:end -->``:
the time of the README's two Quick-start commands (install and build the book; the test
command), from ``benchmarks/results/readme_commands.json``. ``--commands`` measures them:
it runs the two commands exactly as the README types them, from the repository root, and
stores their wall times with when, where (machine, load average before and after, whether
``.venv`` existed already) and at which commit they ran; the book build's own time is read
from ``.ci/build_book.sh``'s output and the test counts from pytest's summary line.

Usage::

    python benchmarks/readme.py                    # measure the speeds, rewrite both README blocks
    python benchmarks/readme.py --print            # only print the speed block
    python benchmarks/readme.py --commands         # run the two Quick-start commands (minutes), store
                                                   # their times, rewrite the commands block only
    python benchmarks/readme.py --commands-block   # rewrite the commands block from the stored run
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import re
import subprocess
import sys
import time
from pathlib import Path

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

sys.path.insert(0, str(Path(__file__).resolve().parent))

import longd_speed  # noqa: E402
import search_speed  # noqa: E402

import segplan  # noqa: E402
from segplan.studies.progress import progress  # noqa: E402
from segplan.studies.verdicts import judge_claim  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
START, END = "<!-- benchmarks:start -->", "<!-- benchmarks:end -->"
COMMANDS_START, COMMANDS_END = "<!-- commands:start -->", "<!-- commands:end -->"
COMMANDS_JSON = ROOT / "benchmarks" / "results" / "readme_commands.json"
FLOORS = ("fig5_example1", "fig6_example2")


def block(runs: int = 9) -> str:
    """Measure and format the README block (Markdown)."""
    longd = longd_speed.main(["--n", "1000000", "--repeats", "3"])
    rate = {(r["method"], r["layer"], r["mode"]): r["evaluations_per_second"] for r in longd["rows"]}
    ratio = longd["cost_ratio_romberg_over_approx"]
    same = longd["same_max_error"]
    ratios = (same["evaluation_ratio"], same["time_ratio_scalar"])
    direction = judge_claim("formula2-cheaper", *ratios).word  # the registry's criteria, as in chapter 3
    size = judge_claim("formula2-saving-size", *ratios).word
    rows = []
    for name in progress(FLOORS, desc="planner speed", unit="floor"):
        scenario = segplan.load_scenario(name)
        for h in ("a", "b", "c"):
            rows.append(search_speed.bench(scenario, h, runs))
        refined = search_speed.bench(scenario, "a", runs, refine=True)  # beyond the paper
        refined["h"] = "a +refine"
        rows.append(refined)
    when = datetime.date.today().isoformat()
    cpu = platform.processor() or platform.machine()
    load = os.getloadavg()[0]  # other work on the machine slows every rate below
    lines = [
        f"Measured on {when}, {cpu}, {os.cpu_count()} cores, one core used, Python "
        f"{platform.python_version()}, numpy {longd['numpy']}, by `python benchmarks/readme.py`; "
        f"load average {load:.1f} at the end of the run ({'a quiet' if load < 1.5 else 'a shared'} machine).",
        "",
        "| cost LONGD | evaluations/s |",
        "| --- | --- |",
        f"| formula [2], `longd_approx` vectorised | {rate[('[2]', 'public', 'vectorised')]:.3g} |",
        f"| formula [2], `longd_approx` scalar calls | {rate[('[2]', 'public', 'scalar')]:.3g} |",
        f"| formula [1], `longd_exact` vectorised, rtol 1e-10 | "
        f"{rate[('Romberg rtol=1e-10', 'public', 'vectorised')]:.3g} |",
        f"| formula [1], `longd_exact` scalar calls, rtol 1e-10 | "
        f"{rate[('Romberg rtol=1e-10', 'public', 'scalar')]:.3g} |",
        "",
        "Cost of Romberg over [2] at the same maximum error (the paper: 2.5-3x on a MicroVAX, 'not too "
        "large a difference'), measured as chapter 3 of the book measures it, by the same helpers "
        "(`segplan.studies.romberg_cost.matched_cost_study` and `matched_cost_ratios`): [2]'s max error on "
        f"chapter 3's unions is {same['approx_max_error']:.2%}; Romberg from level 1 first matches it at "
        f"rtol {same['rtol']:g}, with {same['mean_evaluations']:.2f} integrand evaluations on average, "
        f"where [2] costs {same['approx_evaluations']:.1f}: Romberg costs {same['evaluation_ratio']:.1f}x "
        f"[2] in evaluations and {same['time_ratio_scalar']:.1f}x in time (scalar calls; both vary with "
        f"the machine). Judged as chapter 3 judges them: the direction of the paper's claim {direction}, "
        f"its size {size}. "
        "Against segplan's `longd_exact` (at least 17 evaluations): vectorised "
        f"{ratio['rtol=1e-10, public, vectorised']:.0f}x at rtol 1e-10; scalar calls "
        f"{ratio['rtol=1e-10, public, scalar']:.1f}x. Targets: >= 1e7 evaluations/s "
        f"({'met' if longd['targets_met']['rate_1e7'] else 'not met'}), >= 100x cheaper than "
        f"`longd_exact` ({'met' if longd['targets_met']['ratio_100x'] else 'not met'}).",
        "",
        "| planner, floor | h' | found | median CPU ms | expansions | LONGD m |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        lines.append(
            f"| {r['scenario']} ({r['obstacles']} obstacles) | {r['h']} | {r['found']} | "
            f"{r['median_ms']:.1f} | {r['expanded']} | {r['cost']:.2f} |"
        )
    worst = max(r["median_ms"] for r in rows if r["h"] == "a")
    worst_refined = max(r["median_ms"] for r in rows if r["h"] == "a +refine")
    lines += [
        "",
        f"Target: a ten-obstacle floor in under 50 ms median (h' a): worst {worst:.1f} ms. "
        f"`a +refine` is the search followed by `segplan.refine` (beyond the paper; target "
        f"under 100 ms): worst {worst_refined:.1f} ms.",
    ]
    return "\n".join(lines)


def quick_start_commands(readme: str) -> list[str]:
    """The README's Quick-start commands, as typed there (comments dropped)."""
    section = readme.split("## Quick start", 1)[1].split("##", 1)[0]
    found = re.search(r"```bash\n(.*?)```", section, re.S)
    if found is None:
        raise SystemExit("README.md: no bash block under '## Quick start'")
    return [line.split("#", 1)[0].strip() for line in found.group(1).splitlines() if line.strip()]


def _git(*args: str) -> str:
    out = subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=False)
    return out.stdout.strip()


def time_commands() -> dict:
    """Run the README's two Quick-start commands from the repository root; their times and provenance.

    Each command runs as the README types it (``bash -c``, without ``PYTHONPATH``), one after
    the other; its output goes to the terminal and is also kept to read
    ``.ci/build_book.sh``'s "book built in N s" and pytest's summary line. Fails
    (SystemExit) if a command fails: a failed run is not a time.
    """
    commands = quick_start_commands((ROOT / "README.md").read_text())
    record = {
        "measured_by": "python benchmarks/readme.py --commands",
        "started": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "commit": _git("rev-parse", "HEAD"),
        "uncommitted_changes": bool(_git("status", "--porcelain", "--untracked-files=no")),
        "machine": f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores",
        "python": platform.python_version(),
        "venv_existed": (ROOT / ".venv" / "bin" / "python").exists(),
        "commands": [],
    }
    # as on a fresh machine: no PYTHONPATH (this script may run with one, to import segplan)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    for command in commands:
        load_before = os.getloadavg()
        start = time.perf_counter()
        proc = subprocess.Popen(
            ["bash", "-c", command],
            cwd=ROOT,
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        lines = []
        for line in proc.stdout:
            sys.stdout.write(line)
            lines.append(line)
        code = proc.wait()
        seconds = time.perf_counter() - start
        if code != 0:
            raise SystemExit(f"{command!r} failed (exit {code}) after {seconds:.0f} s: no time stored")
        text = "".join(lines)
        entry = {
            "command": command,
            "seconds": round(seconds, 1),
            "load_average_before": [round(x, 2) for x in load_before],
            "load_average_after": [round(x, 2) for x in os.getloadavg()],
        }
        built = re.findall(r"book built in (\d+) s", text)
        if built:
            entry["book_build_seconds"] = int(built[-1])
        summary = re.findall(r"^=+ (.*\d+ passed.*) in [\d.]+s", text, re.M)
        if summary:
            entry["pytest_summary"] = summary[-1].strip()
        record["commands"].append(entry)
    record["finished"] = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    return record


def commands_block(record: dict) -> str:
    """The README's block on the two commands' times, from a stored :func:`time_commands` record."""
    build, tests = record["commands"]
    when = record["started"].replace("T", " ").replace("+00:00", " UTC")
    state = "an existing `.venv`" if record["venv_existed"] else "no `.venv` yet (everything installed)"
    parts = [
        f"Timed on {when} at commit `{record['commit'][:12]}`"
        + (" (with uncommitted changes)" if record["uncommitted_changes"] else "")
        + f", {record['machine']}, Python {record['python']}, {state}, by `{record['measured_by']}` "
        f"(stored in `benchmarks/results/readme_commands.json`):",
        "",
        "| command | wall time | load average before / after (1 min) |",
        "| --- | --- | --- |",
    ]
    for entry, what in ((build, "1. install and build"), (tests, "2. test command")):
        detail = []
        if "book_build_seconds" in entry:
            detail.append(f"book build {entry['book_build_seconds']} s")
        if "pytest_summary" in entry:
            detail.append(entry["pytest_summary"])
        parts.append(
            f"| {what}: `{entry['command']}` | {entry['seconds']:.0f} s"
            + (f" ({'; '.join(detail)})" if detail else "")
            + f" | {entry['load_average_before'][0]:.1f} / {entry['load_average_after'][0]:.1f} |"
        )
    parts += [
        "",
        "Target: the book built in under 3 minutes on this 2-core machine, every chapter executed "
        f"afresh: {'met' if build.get('book_build_seconds', 1e9) < 180 else 'not met'} in this run "
        "(a loaded machine is slower; the load average says how loaded).",
    ]
    return "\n".join(parts)


def replace_block(text: str, start: str, end: str, body: str) -> str:
    """``text`` with the part between the markers ``start`` and ``end`` replaced by ``body``."""
    pattern = re.compile(re.escape(start) + ".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        raise SystemExit(f"README.md has no {start} ... {end} block")
    return pattern.sub(lambda _: f"{start}\n{body}\n{end}", text)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--print", action="store_true", help="print the block, do not touch README.md")
    parser.add_argument("--runs", type=int, default=9, help="plans per scenario and h' (median)")
    parser.add_argument(
        "--commands", action="store_true", help="run and time the README's two commands (minutes), store them"
    )
    parser.add_argument(
        "--commands-block", action="store_true", help="rewrite the commands block from the stored run"
    )
    args = parser.parse_args(argv)
    readme = ROOT / "README.md"
    if args.commands or args.commands_block:
        if args.commands:
            record = time_commands()
            COMMANDS_JSON.parent.mkdir(parents=True, exist_ok=True)
            COMMANDS_JSON.write_text(json.dumps(record, indent=1) + "\n")
        record = json.loads(COMMANDS_JSON.read_text())
        text = commands_block(record)
        readme.write_text(replace_block(readme.read_text(), COMMANDS_START, COMMANDS_END, text))
        print(text)
        return 0
    text = block(args.runs)
    if args.print:
        print(text)
        return 0
    readme.write_text(replace_block(readme.read_text(), START, END, text))
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
