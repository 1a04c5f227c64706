"""Many plans on one floor (issue 25, "reuse across calls"; beyond the paper).

A robot is sent from place to place on one map: many start and goal pairs on one floor.
:class:`segplan.Planner` keeps the floor's off-line work between its calls (the paper's
"processing of the model of the surroundings": the polygons checked, split and enlarged, and
the validity checker's arrays); :func:`segplan.plan_scenario` does it on every call. This
module measures what that saves, on the floor kinds of :mod:`segplan.studies.floor_kinds`.

**Queries** (:func:`floor_queries`): on each floor, from its start ``S`` and goal ``G`` (both
free, drawn by the generator), four trips: ``S -> G`` (as drawn), ``G~ -> S~`` (the way back;
``~`` is the same footprint facing the other way: A moved to B, the heading turned by pi, so
the pose is free exactly when the drawn one is), ``S~ -> G`` (the start turned round) and
``G~ -> S`` (back to the start). Each leaves from the drawn start or a turned goal and ends at
the drawn goal or a turned start, never the other way round: a goal drawn nose-in in a dead end
(a parking bay) cannot be left forwards, nor a start facing a wall a few centimetres away be
reached backwards-facing, by a forward-only robot. The trips are not checked feasible (no peer
ran on them): the study counts them solved or not.

**Measured** (:func:`run_reuse`): per floor one :class:`segplan.Planner` (its construction
timed), then per query, alternately, the plan with the floor prepared anew
(:func:`segplan.make_scenario`, then :func:`segplan.plan_scenario`: *fresh*, what a user types
without a Planner) and :meth:`segplan.Planner.plan` (*reused*), wall and CPU time of each call, and
whether both gave the same plan (the Planner's promise: the same unions, the same LONGD to
:data:`SAME_PLAN_RTOL`). The target is about the reused calls after a floor's first
(*further* queries): the first plan of a robot not seen before in the process also computes its
motion primitives (kept per process, :func:`segplan.planning.lattice.primitives.primitive_set`),
and the fresh call, made first, pays for them.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable
from functools import partial

import pandas as pd

from ..floor.scenario import Scenario, ScenarioError, make_scenario
from ..planning.api import plan_scenario
from ..planning.plan import NoPathError, Plan
from ..planning.planner import Planner
from .floor_kinds import _pose, _shift

__all__ = ["QUERIES", "REUSE_COLUMNS", "SAME_PLAN_RTOL", "floor_queries", "run_reuse", "turned"]

#: The names of :func:`floor_queries`' trips, in their order.
QUERIES = ("as drawn", "way back", "start turned", "back to the start")
#: Two plans are the same when they have the same number of unions and their LONGDs agree to
#: this relative tolerance: one process computes both from the same floats (the Planner's
#: floor is the one :func:`segplan.plan_scenario` prepares), so only summation order could
#: differ; 1e-9 is far above double rounding over a plan's few hundred terms and far below
#: any change a different plan makes (the lattice's cell is L / 8).
SAME_PLAN_RTOL = 1e-9
#: :func:`run_reuse`'s columns.
REUSE_COLUMNS = (
    "group",
    "floor",
    "query",
    "order",
    "build_seconds",
    "fresh_seconds",
    "fresh_cpu_seconds",
    "reused_seconds",
    "reused_cpu_seconds",
    "solved",
    "same_plan",
)


def turned(pose, L: float) -> tuple[float, float, float]:
    """The same footprint facing the other way: A moved to B (``L`` ahead), the heading turned
    by pi (rounded like the floors' poses, to a micrometre and a microradian)."""
    x, y, th = (float(v) for v in pose)
    bx, by, _ = _shift((x, y, th), L)
    return _pose(bx, by, th + math.pi)


def floor_queries(scenario: Scenario) -> list[tuple[str, tuple, tuple]]:
    """The trips :func:`run_reuse` plans on ``scenario``'s floor: ``(name, start, goal)`` in the
    order of :data:`QUERIES` (module docstring)."""
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    L = scenario.robot.L
    S, G = tuple(scenario.start), tuple(scenario.goal)
    trips = ((S, G), (turned(G, L), turned(S, L)), (turned(S, L), G), (turned(G, L), S))
    return [(name, a, b) for name, (a, b) in zip(QUERIES, trips, strict=True)]


def _timed(call: Callable[[], Plan]) -> tuple[Plan | None, float, float]:
    t0, c0 = time.perf_counter(), time.process_time()
    try:
        plan = call()
    except NoPathError:
        plan = None
    return plan, time.perf_counter() - t0, time.process_time() - c0


def _fresh(sc: Scenario, start, goal, options: dict) -> Plan:
    """A plan on ``sc``'s floor with the floor prepared anew: what a user types without a Planner."""
    return plan_scenario(make_scenario(sc.robot, start, goal, sc.outlines, sc.bounds), **options)


def _same(a: Plan | None, b: Plan | None) -> bool:
    if a is None or b is None:
        return a is None and b is None
    same_cost = math.isclose(a.cost, b.cost, rel_tol=SAME_PLAN_RTOL, abs_tol=0.0)
    return len(a.unions) == len(b.unions) and same_cost


def run_reuse(
    floors: Iterable[tuple[str, Scenario]],
    options: dict | None = None,
    progress: Callable[[str], None] | None = None,
) -> pd.DataFrame:
    """Plan :func:`floor_queries` on every ``(group, scenario)`` fresh and with one
    :class:`segplan.Planner` per floor (module docstring): one row per query
    (:data:`REUSE_COLUMNS`; ``order`` counts the planner's calls on its floor from 0,
    ``build_seconds`` is the floor's Planner construction, on every row of the floor). A
    query whose start or goal is not free is left out (the generator's poses are free, and so
    are their :func:`turned` poses, so none is expected)."""
    options = dict(options or {})
    rows = []
    for group, sc in floors:
        t0 = time.perf_counter()
        planner = Planner(sc.outlines, sc.robot, bounds=sc.bounds, **options)
        build = time.perf_counter() - t0
        order = 0
        for name, a, b in floor_queries(sc):
            try:
                planner.scenario(a, b)
            except ScenarioError:
                continue
            fresh, fw, fc = _timed(partial(_fresh, sc, a, b, options))
            reused, rw, rc = _timed(partial(planner.plan, a, b))
            rows.append(
                {
                    "group": group,
                    "floor": sc.name,
                    "query": name,
                    "order": order,
                    "build_seconds": build,
                    "fresh_seconds": fw,
                    "fresh_cpu_seconds": fc,
                    "reused_seconds": rw,
                    "reused_cpu_seconds": rc,
                    "solved": reused is not None,
                    "same_plan": _same(fresh, reused),
                }
            )
            order += 1
            if progress:
                progress(f"{group} {sc.name} {name}: fresh {1e3 * fw:.0f} ms, reused {1e3 * rw:.0f} ms")
    return pd.DataFrame(rows, columns=list(REUSE_COLUMNS))
