"""The stored data hold on other processors (issue 23): other processors simulated on this one.

The fitted constants (``segplan/model/constants.json``) and the default motion primitives
(``segplan/planning/lattice/primitives.npz``) are recomputed, and chapter 4 (which refits the case-b
formula and compares it with the stored one) is re-executed, in fresh processes that round
differently from the default ones:

* OpenBLAS kernels of other processors (``OPENBLAS_CORETYPE``: the BLAS behind numpy's
  ``@`` and ``lstsq``), each confirmed by OpenBLAS's own report of the kernel it loaded;
* numpy limited to fewer SIMD code paths (``NPY_DISABLE_CPU_FEATURES``: numpy's vectorised
  ``sin``, ``exp``, ``log``, ... round differently with AVX-512, AVX2 and the baseline),
  confirmed by numpy's list of the features it then uses.

``python -m segplan.fit --check`` must pass in each (its tolerances: :mod:`segplan.fit.store`);
the primitive sets must be the same sets, in the same order. x86-64 only (the kernels and
features named are x86's); on another processor the suite's own refit tests are the check.
"""

from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.skipif(
    platform.machine().lower() not in ("x86_64", "amd64"),
    reason="the simulated kernels and SIMD levels are x86-64's",
)

#: OpenBLAS kernels of older or other x86-64 processors (any x86-64 processor runs them).
KERNELS = ("Haswell", "Sandybridge", "Nehalem")


def _numpy_features(env: dict[str, str]) -> list[str]:
    """The dispatched SIMD features numpy uses in a fresh process with ``env``."""
    code = (
        "import json; from numpy._core._multiarray_umath import __cpu_dispatch__ as d, "
        "__cpu_features__ as f; print(json.dumps([k for k in d if f.get(k)]))"
    )
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _environments() -> dict[str, dict[str, str]]:
    base = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES")}
    out = {f"OpenBLAS {k}": {**base, "OPENBLAS_CORETYPE": k} for k in KERNELS}
    found = _numpy_features(base)
    if found:  # numpy at its baseline, without any dispatched SIMD path
        out["numpy baseline SIMD"] = {**base, "NPY_DISABLE_CPU_FEATURES": " ".join(found)}
    wide = [k for k in found if k.startswith(("X86_V4", "AVX512"))]
    if wide and "X86_V3" in found:  # AVX2 on a processor with AVX-512 (or the other way round)
        out["numpy AVX2"] = {**base, "NPY_DISABLE_CPU_FEATURES": " ".join(wide)}
    return out


ENVIRONMENTS = _environments() if platform.machine().lower() in ("x86_64", "amd64") else {}


def _confirm(name: str, env: dict[str, str]) -> None:
    """The simulated processor is really in effect in a process started with ``env``."""
    if "OPENBLAS_CORETYPE" in env:
        code = "import numpy as np; np.ones((64, 64)) @ np.ones((64, 64))"
        out = subprocess.run(
            [sys.executable, "-c", code], env={**env, "OPENBLAS_VERBOSE": "2"}, capture_output=True, text=True
        )
        assert f"Core: {env['OPENBLAS_CORETYPE']}" in out.stdout + out.stderr, (name, out.stderr)
    if "NPY_DISABLE_CPU_FEATURES" in env:
        used = set(_numpy_features(env))
        assert not used & set(env["NPY_DISABLE_CPU_FEATURES"].split()), (name, used)


@pytest.mark.parametrize("name", sorted(ENVIRONMENTS))
def test_refit_and_primitives_agree_with_the_stored_data(name):
    env = ENVIRONMENTS[name]
    _confirm(name, env)
    out = subprocess.run(
        [sys.executable, "-m", "segplan.fit", "--check"], env=env, cwd=ROOT, capture_output=True, text=True
    )
    assert out.returncode == 0, (name, out.stdout, out.stderr)
    assert "matches the fits" in out.stdout and "matches the computed primitives" in out.stdout


@pytest.mark.parametrize(
    "name", [n for n in ("OpenBLAS Sandybridge", "numpy baseline SIMD") if n in ENVIRONMENTS]
)
def test_chapter_4_gives_its_stored_outputs(name):
    # the chapter refits the case-b formula and prints its comparison with the stored one
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "pytest",
            "-q",
            "-p",
            "no:cacheprovider",
            "--nbval",
            "notebooks/04_optimal_frame.ipynb",
        ],
        env=ENVIRONMENTS[name],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, (name, out.stdout[-3000:])
