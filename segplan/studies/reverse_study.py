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

**Both ways in time** (a measurement, not the default planner: ``benchmarks/both_ways.py``,
book chapter 12). A robot that may reverse can drive any plan from the goal to the start
backwards in time: the same unions in the other order, each driven the other way (the same
poses, front-wheel length and swept area; :mod:`segplan.planning.lattice.reverse`). The floor
with start and goal swapped (:func:`swapped`), planned with ``reverse_factor`` ``1 / f`` and
``cusp_penalty`` ``p / f`` (:func:`mirrored_costs`), is searched for the same cost up to the
factor ``f``: its forward links are the real plan's reverse ones. :func:`run_both_ways` plans
each floor both ways and keeps the plan of lower search cost; :func:`both_ways_summary` sets
the three side by side.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import pandas as pd

from ..floor.scenario import Scenario, make_scenario
from ..planning.lattice.reverse import weighted_cost
from ..planning.options import LatticeOptions
from . import reverse_floors as rf
from . import robustness as rb
from .floors import floor_key

__all__ = [
    "both_ways_summary",
    "compare",
    "mirrored_costs",
    "run_both_ways",
    "run_segplan",
    "summary",
    "swapped",
    "with_reverse",
]


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
    return _planned(floors, options, progress)[0]


def _planned(floors: list, options: dict | None, progress, ends=None) -> tuple[pd.DataFrame, dict]:
    """:func:`run_segplan`'s rows of ``floors`` (``(kind, forward-only floor)``), each given
    reverse gear and then ``ends`` (None: as it is; :func:`swapped`), and the plans by name."""
    planned = [(k, with_reverse(sc)) for k, sc in floors]
    if ends is not None:
        planned = [(k, ends(sc)) for k, sc in planned]
    table, plans = rb.run_segplan(planned, options, progress)
    table["floor_key"] = [floor_key(sc) for _, sc in floors]
    table["cusps"] = [math.nan if plans[sc.name] is None else len(plans[sc.name].cusps) for _, sc in floors]
    return table, plans


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


def swapped(scenario: Scenario) -> Scenario:
    """The floor planned backwards in time (module docstring): start and goal swapped, the same name."""
    return dataclasses.replace(scenario, start=scenario.goal, goal=scenario.start)


def mirrored_costs(options: LatticeOptions | None = None) -> dict:
    """The lattice options of :func:`swapped` floors: ``reverse_factor`` ``1 / f`` and
    ``cusp_penalty`` ``p / f`` for ``options``' ``f`` and ``p`` (the defaults if None), so
    that a swapped plan's search cost is ``1 / f`` times the real plan's (module docstring)."""
    o = LatticeOptions() if options is None else options
    return {"reverse_factor": 1.0 / o.reverse_factor, "cusp_penalty": o.cusp_penalty / o.reverse_factor}


def run_both_ways(
    kinds: Sequence[str] = rf.REVERSE_KINDS, n: int = rf.N_PER_KIND, progress=None
) -> tuple[pd.DataFrame, pd.DataFrame, pd.DataFrame]:
    """The first ``n`` floors of each of ``kinds`` with reverse gear, planned by the default
    planner (the default costs) and again :func:`swapped` with :func:`mirrored_costs`, each
    plan checked by the dense oracle: ``(default, swapped, kept)``, each the rows of
    :func:`run_segplan` (the swapped plan's ``cusps``: the real plan's too) with
    ``search_cost`` (the real plan's, inf without a plan); ``kept``
    has per floor the valid plan of lower search cost (the default's on a tie), ``kept``
    naming it and ``seconds`` and ``cpu_seconds`` those of both calls."""
    lo = LatticeOptions()
    f, p = lo.reverse_factor, lo.cusp_penalty
    floors = [(k, sc) for k in kinds for sc in rf.reverse_floors(k, n)]
    default, plans = _planned(floors, None, progress)
    back, back_plans = _planned(floors, {"lattice": mirrored_costs()}, progress, swapped)
    costs: dict[str, list] = {"default": [], "swapped": []}
    for _, sc in floors:
        pen = p * sc.robot.L
        pa, pb = plans[sc.name], back_plans[sc.name]
        costs["default"].append(math.inf if pa is None else weighted_cost(pa, f, pen))
        costs["swapped"].append(math.inf if pb is None else f * weighted_cost(pb, 1.0 / f, pen / f))
    default = default.assign(search_cost=costs["default"])
    back = back.assign(search_cost=costs["swapped"])
    ok_a, ok_b = default["solved"] & default["valid"], back["solved"] & back["valid"]
    take = ok_b & (~ok_a | (back["search_cost"] < default["search_cost"]))
    kept = default.where(~take, back).assign(
        kept=["swapped" if t else "default" for t in take],
        seconds=default["seconds"] + back["seconds"],
        cpu_seconds=default["cpu_seconds"] + back["cpu_seconds"],
    )
    return default, back, kept


def both_ways_summary(
    default: pd.DataFrame, swapped_rows: pd.DataFrame, kept: pd.DataFrame, reeds_shepp: pd.DataFrame,
    dubins: pd.DataFrame,
) -> pd.DataFrame:  # fmt: skip
    """Per kind and for all floors (``"all"``): the front-wheel length over OMPL's
    (:func:`compare`, median and worst) and the invalid plans of the default, the swapped and
    the kept plans (:func:`run_both_ways`), the swapped plans kept, and the median times of
    the default and of both calls (s)."""
    tables = {
        name: compare(t, reeds_shepp, dubins)
        for name, t in (("default", default), ("swapped", swapped_rows), ("kept", kept))
    }
    rows = []
    for kind in [*kept["group"].unique(), "all"]:
        row: dict = {"kind": kind}
        for name, t in tables.items():
            g = t if kind == "all" else t[t["group"] == kind]
            r = g["ratio"].dropna()
            row[f"{name} median"], row[f"{name} worst"] = float(r.median()), float(r.max())
            row[f"{name} invalid"] = int((g["solved"] & ~g["valid"]).sum())
        k = kept if kind == "all" else kept[kept["group"] == kind]
        d = default if kind == "all" else default[default["group"] == kind]
        row["swapped kept"] = int((k["kept"] == "swapped").sum())
        row["time median, default (s)"] = float(d["seconds"].median())
        row["time median, both (s)"] = float(k["seconds"].median())
        rows.append(row)
    return pd.DataFrame(rows).set_index("kind")
