"""The fitted constants, read from the data file shipped with the package.

Two sets of constants are fitted empirically, as in the paper, and stored as data in
``segplan/model/constants.json`` (with their provenance: grid, seed, errors, date, command and
package version):

* formula [2] (section "Approximate computation of cost function"): the coefficients of
  ``k_alpha`` and the validated domain, fitted by :mod:`segplan.fit.formula2` and read by
  :mod:`segplan.model.cost`;
* the heuristic optimal reference system, case b (section "Heuristic Algorithm"): the
  coefficients of the closed formula, fitted by :mod:`segplan.fit.heuristic` and read by
  :mod:`segplan.model.frame`.

``python -m segplan.fit`` recomputes both and rewrites the file (``--check`` only
compares). Loading is one small JSON read, cached (tens of microseconds); no fitting code
is imported at run time.
"""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path
from typing import Any

__all__ = ["PATH", "formula2", "heuristic_frame", "load"]

#: The data file of the fitted constants.
PATH = Path(__file__).with_name("constants.json")


@cache
def load() -> dict[str, Any]:
    """The whole data file as a dict (read once per process).

    Raises
    ------
    FileNotFoundError
        If the package was installed without its data file.
    """
    with PATH.open(encoding="utf-8") as f:
        return json.load(f)


def formula2() -> dict[str, Any]:
    """The constants of formula [2]: ``k_coef``, ``s2_cap``, ``domain`` (radians), errors, grid."""
    return load()["formula2"]


def heuristic_frame() -> dict[str, Any]:
    """The case-b coefficients of the heuristic frame: ``coef``, ``degree``, ``phi_max``, ..."""
    return load()["heuristic_frame"]
