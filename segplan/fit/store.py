"""Run the fits and write, or check, the data file of the fitted constants.

``python -m segplan.fit`` recomputes ``k_alpha`` and the domain of formula [2]
(:func:`segplan.fit.formula2.run_calibration`) and the case-b coefficients of the
heuristic frame (:func:`segplan.fit.heuristic.fit_heuristic`) and rewrites
``segplan/model/constants.json`` (:data:`segplan.model.constants.PATH`) with their provenance;
``--check`` only compares the recomputed values with the stored ones (exit status 1 on a
difference beyond :data:`RTOL`).

It also recomputes the default motion primitives of the lattice planner (beyond the paper:
unit ``L``, 45 deg steering, ``L / resolution`` in
:data:`segplan.planning.lattice.primitives.STORED_CELLS`;
:func:`segplan.planning.lattice.primitives.compute_primitive_set`,
which uses the heuristic frame just fitted) and rewrites (or checks)
``segplan/planning/lattice/primitives.npz`` (:data:`segplan.planning.lattice.primitives.DATA_PATH`), its
provenance stored
beside the arrays.
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import platform
import subprocess
import sys
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np

from ..model import constants
from ..model.frame import HeuristicFit, case_b_alpha
from ..planning.lattice import primitives
from . import formula2
from .heuristic import fit_heuristic

__all__ = [
    "COMMAND",
    "FRAME_ATOL",
    "RTOL",
    "compute",
    "compute_primitives",
    "differences",
    "frame_check_grid",
    "frame_difference",
    "main",
    "primitive_differences",
    "write",
    "write_primitives",
]

#: The command that writes the data file.
COMMAND = "python -m segplan.fit"
#: Relative tolerance of ``--check`` (and of the tests that refit) on every stored number
#: but the case-b coefficients: ``k_alpha``'s two coefficients, the domain of [2], the error
#: statistics of both fits. These agree to 1e-9 between the processors simulated by
#: ``tests/test_processors.py`` (OpenBLAS kernels Haswell to Prescott, numpy's baseline,
#: AVX2 and AVX-512 code paths): the largest difference seen is a few units of 1e-16.
RTOL = 1e-9
#: Tolerance of ``--check`` on the case-b fit, in the frames it gives (radians): the largest
#: ``|alpha_new - alpha_stored|`` over :func:`frame_check_grid` (:func:`frame_difference`).
#: The 34 coefficients are not compared one by one: the weighted design matrix has the
#: condition number 2.4e6, so a change of the fit's inputs in their last bits moves single
#: coefficients by up to 1e-7 relative (6.8e-8 measured between numpy's AVX2 and AVX-512
#: paths) while the fitted function moves by no more than its inputs do (a least-squares fit
#: is a projection, which does not amplify a change of its targets). The targets are exact
#: optima computed to ``rtol = 1e-8`` (:func:`segplan.fit.heuristic.fit_heuristic`), the
#: logit's sensitivity ``d alpha / dz <= (hi - lo) / 4 <= pi / 4``, and a vector's largest
#: entry is at most ``sqrt(n) = 20`` times its root mean square: 1e-8 x 20 x pi / 4 = 1.6e-7
#: rad, rounded up to 1e-6. Measured between those processors: 1.1e-9 rad at most. A frame
#: moved by 1e-6 rad changes LONGD by a relative 1e-12 at an optimum (a stationary point).
FRAME_ATOL = 1e-6


def _version() -> str:
    try:
        return metadata.version("segplan")
    except metadata.PackageNotFoundError:  # run from a source tree
        return "unknown"


def compute() -> dict[str, Any]:
    """Run both fits and return the constants (without provenance), as stored in the file."""
    cal = formula2.run_calibration()
    fit = fit_heuristic()
    return {
        "formula2": {
            "k_coef": [float(c) for c in cal.k_coef],
            "s2_cap": float(formula2.S2_CAP),
            "domain": {
                "band_lower": [float(v) for v in cal.domain.band_lower],
                "alpha_max": [float(v) for v in cal.domain.alpha_max],
                "phi_max": [float(v) for v in cal.domain.phi_max],
            },
            "errors": {
                "max_error": cal.max_error,
                "mean_error": cal.mean_error,
                "n_inside": cal.n_inside,
                "n_grid": cal.n_grid,
                "iterations": cal.iterations,
            },
            "grid": {
                "alpha_deg": list(formula2.ALPHA_GRID_DEG),
                "phi_deg": list(formula2.PHI_GRID_DEG),
                "d_over_L": list(formula2.DL_GRID),
                "frame_cap_deg": formula2.FRAME_CAP_DEG,
                "exact_rtol": formula2.EXACT_RTOL,
                "design_max": formula2.DESIGN_MAX,
                "mean_max": formula2.BOUND_MEAN,
                "seed": None,
            },
        },
        "heuristic_frame": {
            "coef": [float(c) for c in fit.coef],
            "degree": fit.degree,
            "phi_max": fit.phi_max,
            "log_ratio_range": list(fit.log_ratio_range),
            "n_problems": fit.n_problems,
            "rms_z": fit.rms_z,
            "grid": {
                "step_deg": 10.0,
                "phi_max_deg": 80.0,
                "d_over_L": [0.25, 100.0],
                "n_d_over_L": 9,
                "n_scan": 12,
                "seed": None,
            },
        },
    }


def _provenance() -> dict[str, Any]:
    return {
        "command": COMMAND,
        "date": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "package_version": _version(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "note": "grid fits, deterministic: no random seed is involved",
    }


def frame_check_grid() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Case-b problems ``(phi0, phi1, d_over_L)`` on which two case-b fits are compared.

    Headings 0.5 to 80 deg (60 values each, ``phi1 <= phi0``: the other orderings and signs
    follow by symmetry) times 40 values of d/L from 0.25 to 100 (geometric): 73,200
    problems, eight times as fine in each heading as the fit's own grid and between its
    points.
    """
    heads = np.radians(np.linspace(0.5, 80.0, 60))
    p0, p1, dl = np.meshgrid(heads, heads, np.geomspace(0.25, 100.0, 40), indexing="ij")
    keep = p1 <= p0
    return p0[keep], p1[keep], dl[keep]


def frame_difference(new: dict[str, Any], old: dict[str, Any]) -> float:
    """Largest ``|alpha_new - alpha_old|`` (radians) of two case-b fits over :func:`frame_check_grid`.

    ``new`` and ``old`` are ``"heuristic_frame"`` entries of the constants (as
    :func:`compute` returns them and the data file stores them), with the same degree.
    """
    grid = frame_check_grid()
    a = case_b_alpha(*grid, fit=HeuristicFit.from_values(new))
    b = case_b_alpha(*grid, fit=HeuristicFit.from_values(old))
    return float(np.max(np.abs(a - b)))


def differences(new: dict[str, Any], old: dict[str, Any], rtol: float = RTOL, path: str = "") -> list[str]:
    """Where two constant trees differ: numbers beyond ``rtol`` (relative), anything else exactly.

    The case-b coefficients (``heuristic_frame/coef``) are compared by the frames they give
    (:func:`frame_difference` beyond :data:`FRAME_ATOL`), not one by one (:data:`FRAME_ATOL`
    says why). The ``provenance`` entry is not compared.
    """
    if not path and isinstance(new, dict) and isinstance(old, dict):
        a, b = new.get("heuristic_frame"), old.get("heuristic_frame")
        if isinstance(a, dict) and isinstance(b, dict) and "coef" in a and "coef" in b:
            rest = (
                {**new, "heuristic_frame": {k: v for k, v in a.items() if k != "coef"}},
                {**old, "heuristic_frame": {k: v for k, v in b.items() if k != "coef"}},
            )
            out = differences(*rest, rtol)
            where = "/heuristic_frame/coef"
            if len(a["coef"]) != len(b["coef"]) or a.get("degree") != b.get("degree"):
                return out + [f"{where}: {len(a['coef'])} coefficients != stored {len(b['coef'])}"]
            gap = frame_difference(a, b)
            if not gap <= FRAME_ATOL:
                out.append(f"{where}: frames differ by up to {gap:.3g} rad (tolerance {FRAME_ATOL:g})")
            return out
    out: list[str] = []
    if isinstance(new, dict) and isinstance(old, dict):
        for key in sorted(set(new) | set(old)):
            if key == "provenance":
                continue
            if key not in new or key not in old:
                out.append(f"{path}/{key}: present in only one")
            else:
                out += differences(new[key], old[key], rtol, f"{path}/{key}")
    elif isinstance(new, list) and isinstance(old, list):
        if len(new) != len(old):
            out.append(f"{path}: length {len(new)} != {len(old)}")
        else:
            for i, (a, b) in enumerate(zip(new, old, strict=True)):
                out += differences(a, b, rtol, f"{path}[{i}]")
    elif isinstance(new, float | int) and isinstance(old, float | int) and not isinstance(new, bool):
        if not math.isclose(new, old, rel_tol=rtol, abs_tol=0.0):
            out.append(f"{path}: {new!r} != stored {old!r}")
    elif new != old:
        out.append(f"{path}: {new!r} != stored {old!r}")
    return out


def write(values: dict[str, Any], path: Path = constants.PATH) -> None:
    """Write ``values`` with their provenance to ``path`` (JSON; floats round-trip exactly)."""
    data = {"provenance": _provenance(), **values}
    path.write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")


def compute_primitives() -> dict[int, dict[str, np.ndarray]]:
    """The default primitive sets recomputed (unit ``L``), by ``L / resolution``."""
    return {
        n: primitives.primitive_arrays(
            primitives.compute_primitive_set(1.0, primitives.STORED_STEER, 1.0 / n)
        )
        for n in primitives.STORED_CELLS
    }


def primitive_differences(new: dict, old: dict, rtol: float = RTOL) -> list[str]:
    """Where two primitive data sets differ: integers and shapes exactly, floats beyond ``rtol``."""
    out: list[str] = []
    for n in primitives.STORED_CELLS:
        for key in (*primitives.FIELDS, "points"):
            a, b = np.asarray(new[n][key]), np.asarray(old[n][key])
            if a.shape != b.shape:
                out.append(f"/{n}/{key}: shape {a.shape} != stored {b.shape}")
            elif a.dtype.kind == "i" and not np.array_equal(a, b):
                out.append(f"/{n}/{key}: integers differ")
            elif not np.allclose(a, b, rtol=rtol, atol=rtol):
                out.append(f"/{n}/{key}: largest difference {np.max(np.abs(a - b)):.3g}")
    return out


def write_primitives(data: dict, path: Path = primitives.DATA_PATH) -> None:
    """Write the primitive sets ``data`` (:func:`compute_primitives`) with their provenance (npz)."""
    prov = {
        **_provenance(),
        "note": "unit L; sets by L / resolution; headings 0..3 (the others are quarter turns)",
        "max_steer_deg": math.degrees(primitives.STORED_STEER),
        "cells_per_L": list(primitives.STORED_CELLS),
    }
    arrays = {f"{n}/{k}": v for n, d in data.items() for k, v in d.items()}
    with path.open("wb") as f:
        np.savez_compressed(f, provenance=np.array(json.dumps(prov)), **arrays)


def main(argv: list[str] | None = None) -> int:
    """``python -m segplan.fit [--check]``: rewrite (or only compare) the stored constants."""
    parser = argparse.ArgumentParser(prog=COMMAND, description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="only compare with the stored constants")
    parser.add_argument(
        "--primitives", action="store_true", help="only rewrite the primitives (from the stored constants)"
    )
    args = parser.parse_args(argv)
    if args.primitives and not args.check:
        write_primitives(compute_primitives())
        print(f"wrote {primitives.DATA_PATH}")
        return 0
    values = compute()
    if args.check:
        diff = differences(values, constants.load())
        for line in diff:
            print(line, file=sys.stderr)
        print(f"{constants.PATH}: {'differs' if diff else 'matches the fits'}")
        pdiff = primitive_differences(compute_primitives(), primitives.stored_sets())
        for line in pdiff:
            print(line, file=sys.stderr)
        print(f"{primitives.DATA_PATH}: {'differs' if pdiff else 'matches the computed primitives'}")
        return 1 if diff or pdiff else 0
    write(values)
    print(f"wrote {constants.PATH}")
    # the primitives use the heuristic frame: a fresh process computes them from the
    # constants just written (this one read the old ones at import)
    subprocess.run([sys.executable, "-m", "segplan.fit", "--primitives"], check=True)
    return 0
