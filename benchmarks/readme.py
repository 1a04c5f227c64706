"""Write the README's measured-speed block from the benchmark scripts (never typed by hand).

Runs ``benchmarks/longd_speed.py`` (the cost LONGD, formulas [1] and [2]) and the planner
timing of ``benchmarks/search_speed.py`` on this machine, one core, and replaces the text
between ``<!-- benchmarks:start -->`` and ``<!-- benchmarks:end -->`` in README.md with the
results, the date and the machine they were measured on.

Usage::

    python benchmarks/readme.py            # rewrite README.md
    python benchmarks/readme.py --print    # only print the block
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import re
import sys
from pathlib import Path

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

sys.path.insert(0, str(Path(__file__).resolve().parent))

import longd_speed  # noqa: E402
import search_speed  # noqa: E402

import segplan  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
START, END = "<!-- benchmarks:start -->", "<!-- benchmarks:end -->"
FLOORS = ("fig5_example1", "fig6_example2")


def block(runs: int = 9) -> str:
    """Measure and format the README block (Markdown)."""
    longd = longd_speed.main(["--n", "1000000", "--repeats", "3"])
    rate = {(r["method"], r["layer"], r["mode"]): r["evaluations_per_second"] for r in longd["rows"]}
    ratio = longd["cost_ratio_romberg_over_approx"]
    same = longd["same_max_error"]
    rows = []
    for name in FLOORS:
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
        "Cost of Romberg over [2] at the same maximum error (the paper: 2.5-3x on a MicroVAX), "
        "measured as chapter 3 of the book measures it (`segplan.studies.romberg_cost.matched_cost_study`): "
        f"[2]'s max error on chapter 3's unions is {same['approx_max_error']:.2%}; Romberg from level 1 "
        f"first matches it at rtol {same['rtol']:g}, with {same['mean_evaluations']:.2f} integrand "
        f"evaluations on average, and then costs {same['time_ratio_scalar']:.1f}x [2] in time (scalar "
        "calls). Against segplan's `longd_exact` (at least 17 evaluations): vectorised "
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


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--print", action="store_true", help="print the block, do not touch README.md")
    parser.add_argument("--runs", type=int, default=9, help="plans per scenario and h' (median)")
    args = parser.parse_args(argv)
    text = block(args.runs)
    if args.print:
        print(text)
        return 0
    readme = ROOT / "README.md"
    old = readme.read_text()
    pattern = re.compile(re.escape(START) + ".*?" + re.escape(END), re.S)
    if not pattern.search(old):
        raise SystemExit(f"README.md has no {START} ... {END} block")
    readme.write_text(pattern.sub(lambda _: f"{START}\n{text}\n{END}", old))
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
