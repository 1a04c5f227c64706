"""Record every plan of the default planner on a fixed floor set, bit for bit, and compare two records.

For changes that must not change a single plan (issue 24's redesign, a bug fix such as
dubins_length's): run it before the change with ``--out before.json``, after it with
``--out after.json``, then ``--compare before.json after.json``. A plan is recorded as its
front-wheel length and its nodes, every float by ``float.hex`` (exact, not rounded); a
failure as its reason. The floors: chapter 9's 400 random floors (200 of each kind), its
hard cases, and the robots probe's 80 floors (``benchmarks/robots.py``): 490 in all, about
two to three minutes of CPU.

Every plan is asked for with a time limit of :data:`TIME_LIMIT` (120 s) instead of the
planner's default 10 s, so that the record does not depend on the machine's speed or load:
measured on this project's machine (AMD EPYC, 2 cores, 2026-12-03), two floors are close to
10 s (any-61 plans in 10.2-11.3 s, a time-out under load; robot-58 plans in 34 s, a time-out
at 10 s), every other one finishes in under 10 s. A record also stores the limit it used;
records made with different limits are not compared.

    python benchmarks/same_plans.py --out /tmp/before.json
    python benchmarks/same_plans.py --compare /tmp/before.json /tmp/after.json
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import sys
from pathlib import Path

import segplan
from segplan.studies.floor_kinds import kind_floor
from segplan.studies.floors import hard_cases, random_floors

HERE = Path(__file__).resolve().parent
#: Seconds per plan (module docstring): far above the slowest floor's 34 s, so that no
#: outcome depends on the processor's speed or load.
TIME_LIMIT = 120.0


def floors(kinds: int = 0) -> list[tuple[str, segplan.Scenario]]:
    """The fixed floor set, by name (module docstring); with ``kinds`` > 0 also the first
    ``kinds`` floors of each 30 x 20 m kind of :mod:`segplan.studies.floor_kinds` (warehouse,
    rooms, parking, clutter, robots: the floors issue 25's speed work must not change)."""
    spec = importlib.util.spec_from_file_location("robots", HERE / "robots.py")
    robots = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(robots)
    out = [(f"{kind}-{i}", sc) for kind in ("any", "natural") for i, sc in enumerate(random_floors(kind))]
    out += list(hard_cases().items())
    out += [(f"robot-{i}", sc) for i in range(1, 81) if (sc := robots.robot_floor(i)) is not None]
    for kind in ("warehouse", "rooms", "parking", "clutter", "robots"):
        out += [(f"{kind}-{i:03d}", kind_floor(kind, i)) for i in range(kinds)]
    return out


def record(time_limit: float = TIME_LIMIT, kinds: int = 0) -> dict[str, list]:
    """Each floor's plan (``["plan", cost hex, nodes as hex]``) or failure (``["fail", reason]``),
    and the time limit under the key ``"time_limit"``; ``kinds`` as in :func:`floors`."""
    out: dict[str, list] = {"time_limit": [time_limit]}
    for name, sc in floors(kinds):
        try:
            p = segplan.plan_scenario(sc, time_limit=time_limit)
        except segplan.NoPathError as err:
            out[name] = ["fail", err.reason]
        else:
            out[name] = ["plan", float(p.cost).hex(), [[float(v).hex() for v in n] for n in p.nodes]]
    return out


def compare(before: dict, after: dict) -> list[str]:
    """The floors whose record differs (with both lengths where both planned)."""
    lines = []
    for name in sorted(set(before) | set(after)):
        a, b = before.get(name), after.get(name)
        if a == b:
            continue
        if a and b and a[0] == b[0] == "plan":
            x, y = float.fromhex(a[1]), float.fromhex(b[1])
            lines.append(f"{name}: {x:.6f} m -> {y:.6f} m ({y / x - 1:+.3%})")
        else:
            lines.append(f"{name}: {a and a[:2]} -> {b and b[:2]}")
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, help="write the record of this tree's plans (JSON)")
    parser.add_argument(
        "--compare", nargs=2, type=Path, metavar=("BEFORE", "AFTER"), help="compare two records"
    )
    parser.add_argument(
        "--time-limit", type=float, default=TIME_LIMIT, help="seconds per plan (default %(default)s)"
    )
    parser.add_argument(
        "--kinds",
        type=int,
        default=0,
        metavar="N",
        help="also the first N floors of each 30 x 20 m floor kind (default %(default)s)",
    )
    args = parser.parse_args(argv)
    if args.compare:
        before, after = (json.loads(p.read_text()) for p in args.compare)
        limits = before.get("time_limit"), after.get("time_limit")
        if limits[0] != limits[1]:
            print(f"records made with different time limits ({limits[0]}, {limits[1]}): not compared")
            return 2
        lines = compare(before, after)
        print("\n".join(lines) or f"the same {len(before) - 1} plans and failures, bit for bit")
        return 1 if lines else 0
    if not args.out:
        parser.error("give --out FILE or --compare BEFORE AFTER")
    data = record(args.time_limit, args.kinds)
    args.out.write_text(json.dumps(data) + "\n")
    plans = sum(v[0] == "plan" for v in data.values())
    print(f"{len(data) - 1} floors: {plans} plans (time limit {args.time_limit:g} s); wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
