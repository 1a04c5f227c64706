"""Computed primitive sets against a reference: the same selection, the same numbers.

:func:`segplan.planning.lattice.primitives.compute_primitive_set` for many steering limits
and resolutions (unit ``L``), written to or compared with an ``.npz`` file. Made to check
that a faster computation selects the same primitives as the one before it: write the
sets with the old code on ``PYTHONPATH``, compare them with the new code's.

Samples (``--sample``):

* ``wide``: steering limits 5-80 deg every 2.5 deg, every 0.1 deg over 30-31 deg, 40 more
  drawn on the 0.1 deg grid of the robots floors (30-60 deg) and 15 over 5-80 deg, each at
  ``L / 2``, ``L / 4``, ``L / 8`` and ``L / 16`` where ``R / resolution`` is at most 64 (the
  lattice's retry of a robot turning wider than ``4 L``:
  :attr:`segplan.planning.schedule.Schedule.wide_turn_cells`), and at ``R / 32`` and
  ``R / 64`` (the resolutions the lattice gives such a robot) below 14 deg.
* ``test``: a few dozen of those with ``R / resolution`` at most 32 (the lattice's first
  resolution), each at least ``1e-9`` from flipping a decision
  (:func:`~segplan.planning.lattice.primitives.selection_margins`), with the fields that the
  selection decides (:data:`TEST_FIELDS`: the integers, cost, alpha, peak curvature, delta)
  and two points of each primitive (:data:`TEST_POINTS`): ``tests/data/primitive_sets.npz``
  (``tests/test_primitives_identity.py``). The other fields follow from the integers.

Usage::

    PYTHONPATH=<old tree> python benchmarks/primitives_identity.py --write old.npz --sample wide
    PYTHONPATH=<new tree> python benchmarks/primitives_identity.py --compare old.npz
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

from segplan.planning.lattice.primitives import (
    FIELDS,
    compute_primitive_set,
    primitive_arrays,
    selection_margins,
)

#: Fields of the ``test`` sample.
TEST_FIELDS = ("h0", "h1", "di", "dj", "cost", "alpha", "peak_curvature", "delta")
#: Points of a primitive kept by the ``test`` sample (of 13 x 7: the middle of the rear
#: path and the front wheel at the end).
TEST_POINTS = (42, 90)
#: Fields compared as integers.
INTEGERS = ("h0", "h1", "di", "dj")


def _cells(steer_deg: float, most: float = 64.0) -> list[float]:
    """``L / resolution`` of the sets of one steering limit, ``R / resolution`` at most ``most``
    (module docstring)."""
    R = 1.0 / math.tan(math.radians(steer_deg))
    out = [float(n) for n in (2, 4, 8, 16) if R * n <= most]
    if R > 4.0:
        out += [n / R for n in (32.0, 64.0) if n <= most]
    return out


def wide_sample() -> list[tuple[float, float]]:
    """``(steer_deg, L / resolution)`` of the ``wide`` sample."""
    rng = np.random.default_rng(25)
    steers = [5.0 + 2.5 * k for k in range(31)]
    steers += [30.0 + 0.1 * k for k in range(1, 10)]
    steers += (rng.integers(300, 601, 40) / 10.0).tolist()
    steers += (rng.integers(50, 801, 15) / 10.0).tolist()
    return [(s, n) for s in sorted(set(steers)) for n in _cells(s)]


def test_sample() -> list[tuple[float, float]]:
    """``(steer_deg, L / resolution)`` of the ``test`` sample (before the margin filter)."""
    steers = (5.0, 9.9, 14.1, 20.0, 27.5, 30.0, 33.3, 36.7, 41.2, 45.1, 48.6, 52.1, 55.5, 60.0, 67.3, 80.0)
    pairs = []
    for k, s in enumerate(steers):
        cells = _cells(s, 32.0)
        pairs += [(s, cells[k % len(cells)]), (s, cells[-1])]
    return sorted(set(pairs))


def label(steer_deg: float, cells: float) -> str:
    return f"{steer_deg:.1f}/{cells!r}"


def compute(pairs, fields=FIELDS, points=None, min_margin: float = 0.0) -> dict[str, np.ndarray]:
    """The sets of ``pairs`` as arrays keyed ``"<label>/<field>"``: ``fields``, the points
    (all, or those of index ``points``) and the time (``"<label>/seconds"``); without the
    sets less than ``min_margin`` from flipping a decision."""
    out: dict[str, np.ndarray] = {}
    for steer, cells in pairs:
        if min_margin > 0.0:
            m = selection_margins(1.0, math.radians(steer), 1.0 / cells)
            if min(m.values()) < min_margin:
                print(f"  {label(steer, cells)}: a margin of {min(m.values()):.3g}, left out", flush=True)
                continue
        t0 = time.perf_counter()
        a = primitive_arrays(compute_primitive_set(1.0, math.radians(steer), 1.0 / cells))
        seconds = time.perf_counter() - t0
        key = label(steer, cells)
        for f in fields:
            out[f"{key}/{f}"] = a[f]
        out[f"{key}/points"] = a["points"] if points is None else a["points"][:, list(points)]
        out[f"{key}/seconds"] = np.array(seconds)
        print(f"  {key}: {len(a['cost'])} primitives, {1e3 * seconds:.0f} ms", flush=True)
    return out


def sets_of(data) -> list[str]:
    return sorted({k.rsplit("/", 1)[0] for k in data.keys()}, key=lambda s: tuple(map(float, s.split("/"))))


def differences(new, old) -> tuple[list[str], dict[str, float], int]:
    """Sets whose integers or shapes differ, the largest relative difference per float field
    of the others (the fields in ``old``; angles relative to 1 radian at least), and the
    number of sets equal bit for bit."""
    present = [f for f in (*FIELDS, "points") if any(k.endswith(f"/{f}") for k in old)]
    bad, worst, same = [], dict.fromkeys(present, 0.0), 0
    for s in sets_of(old):
        pairs = [(new[f"{s}/{f}"], old[f"{s}/{f}"]) for f in present]
        if any(a.shape != b.shape for a, b in pairs) or any(
            not np.array_equal(a, b) for f, (a, b) in zip(present, pairs, strict=True) if f in INTEGERS
        ):
            bad.append(s)
            continue
        for f, (a, b) in zip(present, pairs, strict=True):
            scale = np.maximum(np.abs(b), 1.0 if f in ("alpha", "phi0", "phi1") else 0.0)
            with np.errstate(invalid="ignore", divide="ignore"):
                rel = np.where(a == b, 0.0, np.abs(a - b) / scale)
            worst[f] = max(worst[f], float(rel.max(initial=0.0)))
        same += all(np.array_equal(a, b) for a, b in pairs)
    return bad, worst, same


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--write", type=Path, help="compute the sample's sets and write them here")
    ap.add_argument("--compare", type=Path, help="compute the sets of this file and compare")
    ap.add_argument("--sample", choices=("wide", "test"), default="wide")
    args = ap.parse_args(argv)
    if args.write is not None:
        if args.sample == "test":
            data = compute(test_sample(), TEST_FIELDS, TEST_POINTS, min_margin=1e-9)
        else:
            data = compute(wide_sample())
        np.savez_compressed(args.write, **data)
        print(f"{len(sets_of(data))} sets written to {args.write}")
        return 0
    if args.compare is not None:
        with np.load(args.compare) as z:
            old = {k: z[k] for k in z.files}
        test = old[next(k for k in old if k.endswith("/points"))].shape[1] == len(TEST_POINTS)
        pairs = [tuple(map(float, s.split("/"))) for s in sets_of(old)]
        new = compute(pairs, TEST_FIELDS, TEST_POINTS) if test else compute(pairs)
        bad, worst, same = differences(new, old)
        t_old = sum(float(old[f"{s}/seconds"]) for s in sets_of(old))
        t_new = sum(float(new[f"{s}/seconds"]) for s in sets_of(old))
        print(f"{len(pairs)} sets: {same} equal bit for bit; integers differ in {len(bad)}: {bad}")
        print("largest relative difference: " + ", ".join(f"{f} {v:.2g}" for f, v in worst.items()))
        print(f"time: {t_new:.2f} s against {t_old:.2f} s ({t_old / t_new:.1f}x)")
        return 1 if bad or max(worst.values()) > 1e-12 else 0
    ap.error("give --write or --compare")
    return 2


if __name__ == "__main__":
    sys.exit(main())
