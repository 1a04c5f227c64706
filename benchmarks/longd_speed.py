"""Speed of LONGD: the closed form [2] against Romberg on [1] (not a timed test).

The paper ("Approximate computation of cost function"): formula [2] "involves
computational cost which is 2/5 to 1/3 of exact computational cost (CPU: System Micro VAX
under VMS), using Romberg integration with the same maximum error bound", i.e. Romberg
costs 2.5-3x the closed form.

Measured here on one core (BLAS/OpenMP threads set to 1), on cases drawn inside the
validated domain of [2] (where the planner uses it), CPU time, best of ``--repeats``:

* ``longd_approx`` vectorised on large arrays (public API, validation included) and the
  intrinsic layer ``longd_approx_intrinsic``; scalar (a Python loop of single calls);
* ``longd_exact`` (Romberg) vectorised and scalar, with the default tight ``rtol=1e-10``
  and with ``rtol`` equal to [2]'s error bound (2.5 %), with the error Romberg actually
  reaches at that tolerance;
* "the same maximum error bound", measured as chapter 3 of the book measures it, with the
  same helpers on the same unions (:func:`segplan.studies.romberg_cost.matched_cost_study`,
  :func:`segplan.studies.romberg_cost.matched_cost_ratios`): Romberg from level 1 at the
  loosest tolerance whose maximum error does not exceed [2]'s, in integrand evaluations and
  in time (scalar calls of the intrinsic layer, both).

Targets: vectorised ``longd_approx`` >= 1e7 evaluations/s, and >= 100x cheaper
per evaluation than ``longd_exact``.

Usage::

    python benchmarks/longd_speed.py [--n 1000000] [--repeats 5] [--json out.json]
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

import segplan  # noqa: E402
from segplan.fit.formula2 import BOUND_MAX  # noqa: E402
from segplan.model.cost import longd_approx_intrinsic, longd_exact_intrinsic, longd_integrand  # noqa: E402
from segplan.studies.approx import sample_domain  # noqa: E402
from segplan.studies.progress import progress  # noqa: E402
from segplan.studies.romberg_cost import matched_cost_ratios, matched_cost_study  # noqa: E402


def cpu_rate(fn, n_evals: int, repeats: int) -> float:
    """Evaluations per CPU second of ``fn()`` (which does ``n_evals``), best of ``repeats``."""
    best = float("inf")
    for _ in range(repeats):
        t0 = time.process_time()
        fn()
        best = min(best, time.process_time() - t0)
    return n_evals / max(best, 1e-9)


def gauss_legendre(d, phi0, phi1, alpha, L, nodes: int = 400):
    """Independent reference for [1]: fixed Gauss-Legendre rule on the smooth integrand."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    return 0.5 * np.tensordot(w, longd_integrand(0.5 * (x + 1.0), d, phi0, phi1, alpha, L), axes=1)


def poses(n: int, seed: int):
    """``n`` pose pairs (world frame, random rigid motion) inside the domain, with alpha and L."""
    dl, phi0, phi1, alpha = sample_domain(n, seed=seed)
    rng = np.random.default_rng(seed + 1)
    L = 0.8
    beta = rng.uniform(-np.pi, np.pi, n)  # chord angle
    x0, y0 = rng.uniform(-50, 50, n), rng.uniform(-50, 50, n)
    d = dl * L
    p0 = np.stack((x0, y0, beta + phi0), axis=-1)
    p1 = np.stack((x0 + d * np.cos(beta), y0 + d * np.sin(beta), beta + phi1), axis=-1)
    return p0, p1, alpha, L, (d, phi0, phi1, alpha, L)


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1_000_000, help="cases for the vectorised [2]")
    parser.add_argument("--n-exact", type=int, default=20_000, help="cases for vectorised Romberg")
    parser.add_argument("--n-scalar", type=int, default=2_000, help="single calls of [2] in the scalar loops")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--json", metavar="PATH", help="also write the results as JSON")
    args = parser.parse_args(argv)

    p0, p1, alpha, L, intr = poses(args.n, seed=101)
    ne, m = min(args.n_exact, args.n), min(args.n_scalar, args.n)
    ms = max(50, m // 4)  # Romberg single calls (slower)
    e_intr = tuple(np.asarray(v)[:ne] if np.ndim(v) else v for v in intr)
    reference = gauss_legendre(*e_intr)
    sp0, sp1, salpha = p0[:m].tolist(), p1[:m].tolist(), alpha[:m].tolist()
    si = [tuple(float(np.asarray(v)[i]) if np.ndim(v) else v for v in intr) for i in range(m)]

    def public_loop(fn, count, **kw):
        return lambda: [fn(sp0[i], sp1[i], salpha[i], L, **kw) for i in range(count)]

    def intrinsic_loop(fn, count, **kw):
        return lambda: [fn(*si[i], **kw) for i in range(count)]

    def err(values):
        return float(np.max(np.abs(values / reference - 1.0)))

    rows = []  # (method, layer, mode, evaluations/s, max |relative error| on the ne cases)
    tight, loose = 1e-10, BOUND_MAX
    # 2 layers x ([2] vectorised, scalar + 2 tolerances x Romberg vectorised, scalar), dispatch,
    # the matched study and its 2 rates: a bar on a terminal only
    bar = progress(total=2 * 6 + 4, desc="LONGD speed", unit="measurement")

    def rate_of(fn, n_evals: int) -> float:
        value = cpu_rate(fn, n_evals, args.repeats)
        bar.update()
        return value

    approx_error = err(longd_approx_intrinsic(*e_intr))
    exact_error = {r: err(longd_exact_intrinsic(*e_intr, rtol=r)) for r in (tight, loose)}
    for layer, approx, exact, loop, args_v in (
        ("public", segplan.longd_approx, segplan.longd_exact, public_loop, (p0, p1, alpha, L)),
        ("intrinsic", longd_approx_intrinsic, longd_exact_intrinsic, intrinsic_loop, intr),
    ):
        head = tuple(np.asarray(v)[:ne] if np.ndim(v) else v for v in args_v)
        rows.append(("[2]", layer, "vectorised", rate_of(lambda f=approx, a=args_v: f(*a), args.n)))
        rows.append(("[2]", layer, "scalar", rate_of(loop(approx, m), m)))
        for r in (tight, loose):
            name = f"Romberg rtol={r:g}"
            rows.append(
                (
                    name,
                    layer,
                    "vectorised",
                    rate_of(lambda f=exact, a=head, r=r: f(*a, rtol=r), ne),
                )
            )
            rows.append((name, layer, "scalar", rate_of(loop(exact, ms, rtol=r), ms)))
    rows.append(("longd (dispatch)", "public", "scalar", rate_of(public_loop(segplan.longd, m), m)))
    # chapter 3's comparison at the same maximum error (same helper, same unions)
    matched = matched_cost_study(2_000, seed=11)
    bar.update()
    both = matched_cost_ratios(matched)  # the chapter's measurement, by the same helper
    bar.close()
    matched_out = {
        "approx_max_error": matched["approx_max_error"],
        "rtol": matched["rtol"],
        "mean_evaluations": matched["mean_evaluations"],
        "romberg_max_error": matched["max_error"],
        "approx_evaluations": both["approx_evaluations"],
        "evaluation_ratio": both["evaluation_ratio"],
        "time_ratio_scalar": both["time_ratio_scalar"],
    }
    rate = {(meth, layer, mode): v for meth, layer, mode, v in rows}
    errors = {"[2]": approx_error, **{f"Romberg rtol={r:g}": e for r, e in exact_error.items()}}

    print(f"LONGD on one core (Python {platform.python_version()}, numpy {np.__version__})")
    print(f"cases inside the validated domain of [2]; max |rel. error| against Gauss-Legendre on {ne} cases")
    print(f"{'method':24s} {'layer':10s} {'mode':11s} {'evaluations/s':>14s} {'max |error|':>12s}")
    for meth, layer, mode, v in rows:
        e = errors.get(meth)
        print(f"{meth:24s} {layer:10s} {mode:11s} {v:14.4g} {'' if e is None else f'{e:12.2e}'}")
    print()
    print("Romberg cost / [2] cost per evaluation (the paper: 2.5-3 at the same error bound)")
    ratios = {}
    for layer in ("public", "intrinsic"):
        for mode in ("vectorised", "scalar"):
            for r in (tight, loose):
                key = f"rtol={r:g}, {layer}, {mode}"
                ratios[key] = rate[("[2]", layer, mode)] / rate[(f"Romberg rtol={r:g}", layer, mode)]
                print(f"  {key:40s} {ratios[key]:8.1f}x")
    print()
    mo = matched_out
    print(
        f"same maximum error as [2] ({mo['approx_max_error']:.2%}, chapter 3's unions): Romberg from "
        f"level 1 at rtol {mo['rtol']:g}, {mo['mean_evaluations']:.2f} integrand evaluations: "
        f"{mo['evaluation_ratio']:.1f}x [2] in evaluations, {mo['time_ratio_scalar']:.1f}x in time "
        "(scalar calls)"
    )
    met_rate = rate[("[2]", "public", "vectorised")] >= 1e7
    met_ratio = ratios[f"rtol={tight:g}, public, vectorised"] >= 100
    print()
    print(f"target: vectorised longd_approx >= 1e7 evaluations/s: {'met' if met_rate else 'NOT met'}")
    print(
        f"target: >= 100x cheaper than longd_exact (vectorised, rtol={tight:g}): "
        f"{'met' if met_ratio else 'NOT met'}"
    )
    result = {
        "rows": [
            {"method": a, "layer": b, "mode": c, "evaluations_per_second": v, "max_rel_error": errors.get(a)}
            for a, b, c, v in rows
        ],
        "cost_ratio_romberg_over_approx": ratios,
        "same_max_error": matched_out,
        "targets_met": {"rate_1e7": met_rate, "ratio_100x": met_ratio},
        "n": args.n,
        "n_exact": ne,
        "n_scalar": m,
        "numpy": np.__version__,
        "python": platform.python_version(),
    }
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(result, fh, indent=2)
    return result


if __name__ == "__main__":
    main()
