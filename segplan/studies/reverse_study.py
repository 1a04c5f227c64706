"""The reverse-gear study (issue 26; beyond the paper): segplan with reverse gear against OMPL's
Reeds-Shepp BIT* on the floors that need it.

The floors are :mod:`segplan.studies.reverse_floors`. Per floor the study has

* **OMPL** (stored, ``benchmarks/reverse_floors.py``): BIT* 5 s, seed 1, at full CPU, on the
  Reeds-Shepp space (forward and reverse; the oracle and the length reference) and on the
  Dubins space (forward only). A floor **needs reverse** when the Reeds-Shepp run finds a
  valid path and the Dubins run does not (an oracle's answer within 5 s, not a proof).
* **segplan**: the default planner with the floor's robot given reverse gear
  (:func:`with_reverse`; ``reverse_factor`` and ``cusp_penalty`` at their defaults), each plan
  sampled in driving order (:func:`segplan.viz.metrics.plan_poses`) and checked by the dense
  oracle (:func:`segplan.studies.robustness.solve_segplan`); ``cusps`` counts its changes of
  direction. OMPL's cusps are its raw path's measured reversals (its simplified path's are
  not stored).

:func:`compare` joins them; :func:`summary` gives per kind the success on the floors that
need reverse, invalid plans, the front-wheel length over OMPL's (simplified path, as the
floor-kinds study) and the cusps of both, in the median.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import pandas as pd

from ..floor.scenario import Scenario, make_scenario
from . import reverse_floors as rf
from . import robustness as rb
from .floors import floor_key

__all__ = ["compare", "run_segplan", "summary", "with_reverse"]


def with_reverse(scenario: Scenario) -> Scenario:
    """The scenario with its robot given reverse gear (``Robot.reverse = True``), all else the same."""
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    robot = dataclasses.replace(scenario.robot, reverse=True)
    return make_scenario(
        robot, scenario.start, scenario.goal, scenario.outlines, scenario.bounds,
        name=scenario.name, description=scenario.description, source=scenario.name,
    )  # fmt: skip


def run_segplan(
    kinds: Sequence[str] = rf.REVERSE_KINDS,
    n: int = rf.N_PER_KIND,
    options: dict | None = None,
    progress=None,
    indices: Sequence[int] | None = None,
) -> pd.DataFrame:
    """segplan with reverse gear on the first ``n`` floors of each of ``kinds`` (or the floors
    ``indices`` of each): the rows of :func:`segplan.studies.robustness.run_segplan` with
    ``cusps`` (changes of direction of the plan; NaN without one) and ``floor_key`` the
    forward-only floor's (the key of OMPL's input, so that :func:`compare` matches the
    stored runs)."""
    if indices is None:
        floors = [(k, sc) for k in kinds for sc in rf.reverse_floors(k, n)]
    else:
        floors = [(k, rf.reverse_floor(k, int(i))) for k in kinds for i in indices]
    table, plans = rb.run_segplan([(k, with_reverse(sc)) for k, sc in floors], options, progress)
    table["floor_key"] = [floor_key(sc) for _, sc in floors]
    table["cusps"] = [math.nan if plans[sc.name] is None else len(plans[sc.name].cusps) for _, sc in floors]
    return table


def compare(seg: pd.DataFrame, reeds_shepp: pd.DataFrame, dubins: pd.DataFrame) -> pd.DataFrame:
    """:func:`segplan.studies.robustness.compare` of segplan's rows against OMPL's Reeds-Shepp
    runs, with ``ompl_cusps`` (the reversals of OMPL's raw path at 5 s), ``dubins_solved``
    (OMPL's forward-only run found a valid path) and ``needs_reverse`` (Reeds-Shepp solved,
    Dubins not)."""
    out = rb.compare(seg, reeds_shepp)
    rs = reeds_shepp[reeds_shepp["budget"] == rb.REFERENCE_BUDGET].set_index("floor")
    out["ompl_cusps"] = out["floor"].map(rs["reversals"])
    ok = dubins["solved"].astype(bool) & (
        dubins["valid"].astype(bool) | dubins["simplified_valid"].astype(bool)
    )
    forward = dict(zip(dubins["floor"], ok, strict=True))
    out["dubins_solved"] = out["floor"].map(forward).astype(object).fillna(False).astype(bool)
    out["needs_reverse"] = out["ompl_solved"] & ~out["dubins_solved"]
    return out


def summary(table: pd.DataFrame) -> pd.DataFrame:
    """Per kind of :func:`compare`'s table: ``floors``, ``rs_solved`` (OMPL Reeds-Shepp),
    ``dubins_solved`` (OMPL forward only), ``needs_reverse``, ``solved_of_those`` (segplan's
    valid plans on them), ``invalid``, ``ratio_median`` and ``ratio_worst`` (front-wheel
    length over OMPL's, floors both solve), ``cusps_median`` and ``ompl_cusps_median`` (on
    those floors), ``time_median_ms`` and ``time_p95_ms`` (every floor)."""
    rows = []
    for kind, t in table.groupby("group", sort=False):
        good = t["solved"].astype(bool) & t["valid"].astype(bool)
        need = t["needs_reverse"]
        r = t["ratio"].dropna()
        both = t[good & t["ompl_solved"]]
        rows.append(
            {
                "kind": kind,
                "floors": len(t),
                "rs_solved": int(t["ompl_solved"].sum()),
                "dubins_solved": int(t["dubins_solved"].sum()),
                "needs_reverse": int(need.sum()),
                "solved_of_those": int((good & need).sum()),
                "invalid": int((t["solved"].astype(bool) & ~t["valid"].astype(bool)).sum()),
                "ratio_median": float(r.median()) if len(r) else math.nan,
                "ratio_worst": float(r.max()) if len(r) else math.nan,
                "cusps_median": float(both["cusps"].median()) if len(both) else math.nan,
                "ompl_cusps_median": float(both["ompl_cusps"].median()) if len(both) else math.nan,
                "time_median_ms": 1e3 * float(t["seconds"].median()),
                "time_p95_ms": 1e3 * float(t["seconds"].quantile(0.95)),
            }
        )
    return pd.DataFrame(rows)
