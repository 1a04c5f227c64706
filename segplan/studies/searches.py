"""Study helpers for the book's search chapters (Figs. 5 and 6; the choices of ``h'``).

Section "Results. Graph-search" of Campoy et al. (1989) compares plans by their cost,
LONGD (formula [1]: the length of the front wheel's path), and by the effort of the
search. This module adds what those comparisons need and the planner does not compute:

- :func:`rear_length`, :func:`plan_rear_length`: the length of the rear point's path
  A, ``integral of sqrt(1 + f'(x)^2) dx`` (formula [1] without its ``L^2`` term), by
  Romberg integration;
- :func:`run_searches`: one scenario, several search settings, one record each (a plan's
  cost and effort, or why no plan was found);
- :func:`relative_changes`, :func:`best_change`, :func:`versus_baseline` and
  :func:`improvement_criterion`: the method's plans against those of the paper's baseline,
  "a search algorithm where the cost function is based upon the distance between points",
  and the one criterion by which chapters 6 and 7 judge "the improvement [...] clearly
  seen" (:data:`CLEAR_IMPROVEMENT`; changes within :data:`EQUAL_WITHIN` count as equal);
- :func:`shortest_point_path` and :func:`point_lower_bounds`: a lower bound on any
  plan's cost. The whole segment A-B stays clear of the enlarged obstacles and strictly
  inside the walls shrunk by the half-width, so the front wheel B travels from the
  start's B to the goal's B through that free space, and its path (of length LONGD) is
  at least the shortest path of a *point* between those two points among the same
  polygons; likewise for A and the rear length. That shortest path is found exactly on
  the visibility graph of the polygon vertices (Lozano-Perez and Wesley, 1979).

- :func:`best_known_plans` and :func:`optimum_interval`: an upper bound on the optimal
  cost, the shortest feasible plan of any planner of the book (the paper's search, refined
  or not, segplan's default planner, OMPL's stored runs), which with the point-path lower
  bound brackets the optimum from both sides.

Nothing here plans: the search is :func:`segplan.planning.api.plan_scenario`.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..floor.geometry import pose_segment
from ..floor.scenario import Scenario
from ..model.romberg import romberg
from ..model.union import Union
from ..planning.api import plan_scenario
from ..planning.plan import NoPathError, Plan
from .progress import progress
from .verdicts import PAPER_CLAIMS, Criterion

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "CLEAR_IMPROVEMENT",
    "EQUAL_WITHIN",
    "best_change",
    "best_known_plans",
    "improvement_criterion",
    "optimum_interval",
    "plan_rear_length",
    "point_lower_bounds",
    "rear_length",
    "relative_changes",
    "run_searches",
    "search_cpu_seconds",
    "search_table",
    "shortest_point_path",
    "versus_baseline",
]

#: Relative LONGD changes within this fraction (0.1 %) count as equal: two searches that
#: return the same route differ by no more than the integration tolerance of [1].
EQUAL_WITHIN = 1e-3

#: A relative LONGD change at most this (-1 %) is an improvement "clearly seen" (Results,
#: Figs. 5 and 6): a front-wheel path shorter by a hundredth, the smallest difference a
#: reader would see in a drawn plan of tens of metres.
CLEAR_IMPROVEMENT = -0.01


# -- lengths of a plan --------------------------------------------------------------------
def rear_length(union: Union, rtol: float = 1e-10) -> float:
    """Length of the rear point's path over a union, by Romberg integration.

    ``integral_0^{x_end} sqrt(1 + f'(x)^2) dx`` in the union's alpha frame: formula [1]
    without the ``L^2 f''^2 / (1 + f'^2)^2`` term, so it never exceeds the union's LONGD.

    Raises
    ------
    ValueError
        ``union`` is not a :class:`segplan.Union`, or a bad ``rtol``.
    """
    if not isinstance(union, Union):
        raise ValueError(f"union must be a segplan.Union, got {type(union).__name__}")
    if not (isinstance(rtol, int | float) and 0.0 < rtol < 1.0):
        raise ValueError(f"rtol must lie in (0, 1), got {rtol!r}")
    # |dA/dx| = sqrt(1 + f'^2)
    value, _ = romberg(lambda x: np.sqrt(1.0 + union.slope(x) ** 2), 0.0, union.x_end, rtol=rtol)
    return float(value)


def plan_rear_length(plan: Plan, rtol: float = 1e-10) -> float:
    """Length of the rear point's path over a whole plan (sum of :func:`rear_length`)."""
    if not isinstance(plan, Plan):
        raise ValueError(f"plan must be a segplan.Plan, got {type(plan).__name__}")
    return float(sum(rear_length(u, rtol) for u in plan.unions))


# -- several searches on one scenario -------------------------------------------------------
def run_searches(scenario: Scenario, searches: Mapping[str, Mapping], **common) -> list[dict]:
    """Run :func:`segplan.plan_scenario` once per setting and summarise each outcome.

    Parameters
    ----------
    scenario : Scenario
    searches : mapping of label -> keyword arguments
        For example ``{"h'=a": {"heuristic": "a"}, "distance": {"cost": "distance"}}``.
    **common
        Keyword arguments given to every search (``max_expansions``, ``time_limit``, ...).
        The searches are the paper's (``planner="paper"``) unless ``planner`` says otherwise.

    Returns
    -------
    list of dict
        One record per setting, in order: ``search`` (the label), ``solved``, ``reason``
        (``"solved"`` or :attr:`NoPathError.reason`), ``cost`` (exact LONGD [1] of the
        plan, m), ``rear`` (:func:`plan_rear_length`, m), ``nodes`` (poses of the plan,
        start and goal included), ``expanded``, ``generated``, ``seconds`` (planning
        time), and ``plan`` (the :class:`Plan`). Without a plan, ``cost``, ``rear``,
        ``nodes`` and ``plan`` are None; ``expanded``, ``generated`` and ``seconds``
        are those of the failed search.

    Raises
    ------
    ValueError
        Bad arguments (also those :func:`plan_scenario` rejects).
    """
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    if not isinstance(searches, Mapping) or not searches:
        raise ValueError("searches must be a non-empty mapping of label -> keyword arguments")
    records = []
    for label, kwargs in searches.items():
        if not isinstance(kwargs, Mapping):
            raise ValueError(f"searches[{label!r}] must be a mapping of keyword arguments, got {kwargs!r}")
        try:
            p = plan_scenario(scenario, **{"planner": "paper", **common, **kwargs})
        except NoPathError as exc:
            records.append(
                {
                    "search": label,
                    "solved": False,
                    "reason": exc.reason,
                    "cost": None,
                    "rear": None,
                    "nodes": None,
                    "expanded": exc.expanded,
                    "generated": exc.generated,
                    "seconds": exc.seconds,
                    "plan": None,
                }
            )
            continue
        records.append(
            {
                "search": label,
                "solved": True,
                "reason": "solved",
                "cost": p.cost,
                "rear": plan_rear_length(p),
                "nodes": len(p.nodes),
                "expanded": p.expanded,
                "generated": p.generated,
                "seconds": p.seconds,
                "plan": p,
            }
        )
    return records


def search_table(cases, searches: Mapping[str, Mapping], desc: str = "searches", **common) -> list[dict]:
    """:func:`run_searches` on many scenarios: one record per case and search, plans dropped.

    The long loops of the search chapters (49 orientation pairs, 100 random worlds), with a
    progress bar on a terminal (:func:`segplan.studies.progress.progress`; quiet in the book
    and under pytest).

    Parameters
    ----------
    cases : iterable of (dict, Scenario)
        Each case's labels (for example ``{"seed": 3}``) and its scenario.
    searches, **common
        As in :func:`run_searches`.
    desc : str
        The progress bar's label.

    Returns
    -------
    list of dict
        For every case, in order, the records of :func:`run_searches` without ``plan``,
        each preceded by the case's labels.
    """
    cases = list(cases)
    records = []
    for labels, scenario in progress(cases, desc=desc, unit="floor"):
        if not isinstance(labels, Mapping):
            raise ValueError(f"cases must hold (labels dict, Scenario) pairs, got labels {labels!r}")
        for r in run_searches(scenario, searches, **common):
            r.pop("plan")
            records.append({**labels, **r})
    return records


def search_cpu_seconds(
    cases, searches: Mapping[str, Mapping], repeats: int = 3, desc: str = "timing", **common
) -> pd.DataFrame:
    """CPU time of each search on each case, the best of ``repeats`` runs (a timing: it varies).

    A search chapter's times for judging "the search is quicker": on a shared machine one
    wall-clock run per search is noisy, so every search is run ``repeats`` times, in the
    order of ``searches`` on even repeats and in the reverse order on odd ones (so that no
    search always runs first, on cold caches), and the least CPU time
    (``time.process_time``) of its runs is kept. A search that finds no plan is timed too.

    Parameters
    ----------
    cases : iterable of (dict, Scenario)
        As in :func:`search_table`.
    searches, **common
        As in :func:`run_searches`.
    repeats : int
        Runs per case and search (>= 1).

    Returns
    -------
    DataFrame
        One row per case and search: the case's labels, ``search`` and ``cpu seconds``.

    Raises
    ------
    ValueError
        Bad ``repeats``, ``cases`` or ``searches``.
    """
    import time

    import pandas as pd

    if isinstance(repeats, bool) or not isinstance(repeats, int) or repeats < 1:
        raise ValueError(f"repeats must be an integer >= 1, got {repeats!r}")
    if not isinstance(searches, Mapping) or not searches:
        raise ValueError("searches must be a non-empty mapping of label -> keyword arguments")
    labels_order = list(searches)
    rows = []
    for labels, scenario in progress(list(cases), desc=desc, unit="floor"):
        if not isinstance(labels, Mapping) or not isinstance(scenario, Scenario):
            raise ValueError("cases must hold (labels dict, Scenario) pairs")
        best = dict.fromkeys(labels_order, math.inf)
        for k in range(repeats):
            for label in labels_order if k % 2 == 0 else labels_order[::-1]:
                t0 = time.process_time()
                try:
                    plan_scenario(scenario, **{"planner": "paper", **common, **searches[label]})
                except NoPathError:
                    pass
                best[label] = min(best[label], time.process_time() - t0)
        rows += [{**labels, "search": label, "cpu seconds": best[label]} for label in labels_order]
    return pd.DataFrame(rows)


# -- the method against the paper's baseline --------------------------------------------------
def _cost_table(cost, baseline: str):
    import pandas as pd

    if not isinstance(cost, pd.DataFrame):
        raise ValueError(
            f"cost must be a pandas DataFrame (one column per search), got {type(cost).__name__}"
        )
    if baseline not in cost.columns:
        raise ValueError(
            f"baseline must be a column of cost, got {baseline!r} (columns {list(cost.columns)})"
        )
    if len(cost.columns) < 2:
        raise ValueError("cost must hold the baseline and at least one other search")
    table = cost.astype(float)
    if (table <= 0.0).to_numpy().any():
        raise ValueError("cost must hold positive LONGD values (NaN where no plan was found)")
    return table.dropna()


def relative_changes(cost, baseline: str):
    """Relative change of each search's LONGD against the baseline's, case by case.

    ``(LONGD - LONGD of the baseline) / LONGD of the baseline``: negative where the search
    drives the shorter front-wheel path (formula [1]).

    Parameters
    ----------
    cost : pandas.DataFrame
        One row per case (a figure, a world), one column per search, LONGD in metres; NaN
        where a search found no plan. Rows with a NaN are left out.
    baseline : str
        The column of the baseline search.

    Returns
    -------
    pandas.DataFrame
        The columns of ``cost`` but the baseline, on the rows every search solved.

    Raises
    ------
    ValueError
        If ``cost`` is not a DataFrame with ``baseline`` and another column, or holds a
        LONGD that is not positive.
    """
    table = _cost_table(cost, baseline)
    return table.drop(columns=baseline).div(table[baseline], axis=0) - 1.0


def best_change(cost, baseline: str):
    """The best (most negative) relative LONGD change of any search against the baseline, per case.

    The quantity of :func:`improvement_criterion`: does any of the method's searches (its
    choices of ``h'``) drive a clearly shorter front-wheel path than the baseline?

    Parameters and errors as :func:`relative_changes`; returns a pandas Series, one value
    per case every search solved.
    """
    return relative_changes(cost, baseline).min(axis=1).rename("best change")


def versus_baseline(cost, baseline: str, tol: float = EQUAL_WITHIN):
    """Each search against the baseline over the cases every search solved.

    Parameters
    ----------
    cost, baseline
        As :func:`relative_changes`.
    tol : float
        Changes within ``+-tol`` count as equal (default :data:`EQUAL_WITHIN`).

    Returns
    -------
    pandas.DataFrame
        One row per search (the columns of ``cost`` but the baseline): ``cases``, ``better``
        (change below ``-tol``), ``equal``, ``worse`` (above ``tol``), ``mean change``,
        ``best`` (the most negative change, 0 if none is negative) and ``worst`` (the
        largest, 0 if none is positive), the last three as fractions.

    Raises
    ------
    ValueError
        As :func:`relative_changes`, or ``tol`` not in [0, 1).
    """
    import pandas as pd

    if isinstance(tol, bool) or not isinstance(tol, int | float) or not 0.0 <= tol < 1.0:
        raise ValueError(f"tol must be a number in [0, 1), got {tol!r}")
    change = relative_changes(cost, baseline)
    rows = {
        search: {
            "cases": len(c),
            "better": int((c < -tol).sum()),
            "equal": int((c.abs() <= tol).sum()),
            "worse": int((c > tol).sum()),
            "mean change": float(c.mean()) if len(c) else math.nan,
            "best": min(float(c.min()), 0.0) if len(c) else math.nan,
            "worst": max(float(c.max()), 0.0) if len(c) else math.nan,
        }
        for search, c in change.items()
    }
    table = pd.DataFrame.from_dict(rows, orient="index")
    table.index.name = "search"
    return table


def improvement_criterion(where: str) -> Criterion:
    """The criterion for "the improvement [...] versus a search [by] distance [...] clearly seen".

    Reproduced when the best relative LONGD change of a LONGD search against the distance
    baseline (:func:`best_change`) is at most :data:`CLEAR_IMPROVEMENT` (-1 %); partly
    reproduced when it is at most ``-EQUAL_WITHIN`` (better, but by less than 1 %); not
    reproduced when no LONGD search is better than the baseline by more than the 0.1 %
    that counts as equal. A chapter judges each case (each figure, each family of worlds)
    with it and requires all (:func:`segplan.studies.verdicts.worst`). It is the criterion
    of ``PAPER_CLAIMS["improves-on-distance"]`` (:mod:`segplan.studies.verdicts`), the
    case named in its quantity: one criterion for the claim in every chapter.

    Parameters
    ----------
    where : str
        The case the value comes from, appended to the quantity ("Fig. 5", "mean over the
        forward worlds").

    Raises
    ------
    ValueError
        If ``where`` is not a non-empty string (:meth:`PaperClaim.at
        <segplan.studies.verdicts.PaperClaim.at>` checks it).
    """
    (criterion,) = PAPER_CLAIMS["improves-on-distance"].at(where)
    return criterion


# -- shortest path of a point among convex polygons ------------------------------------------
def _half_planes(polygons: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Unit outward normals ``(P, K, 2)`` and offsets ``(P, K)`` of counter-clockwise polygons.

    A point ``x`` is inside polygon ``p`` iff ``n[p, k] . x - c[p, k] < 0`` for every ``k``.
    Polygons with fewer edges are padded with the half-plane ``0 . x - 1 < 0``, always true.
    """
    K = max(len(p) for p in polygons)
    n = np.zeros((len(polygons), K, 2))
    c = np.ones((len(polygons), K))
    for i, p in enumerate(polygons):
        e = np.roll(p, -1, axis=0) - p
        normal = np.column_stack((e[:, 1], -e[:, 0]))  # outward for counter-clockwise
        normal /= np.hypot(normal[:, 0], normal[:, 1])[:, None]
        n[i, : len(p)] = normal
        c[i, : len(p)] = np.einsum("ij,ij->i", normal, p)
    return n, c


def _crosses_interior(a: np.ndarray, b: np.ndarray, n: np.ndarray, c: np.ndarray, tol: float) -> np.ndarray:
    """Does segment ``a[s]``-``b[s]`` enter some polygon's interior deeper than ``tol``? ``(S,)``.

    Cyrus-Beck clipping: on ``p(t) = a + t (b - a)``, ``t`` in ``[0, 1]``, each signed
    distance ``s_k(t) = n_k . p(t) - c_k`` is linear in ``t``; the segment is inside the
    polygon shrunk by ``tol`` for the ``t`` with ``s_k(t) < -tol`` for every ``k``, an
    interval ``(t_lo, t_hi)``, non-empty iff the segment crosses the interior. Touching a
    vertex or running along an edge does not count.
    """
    s0 = np.einsum("sd,pkd->spk", a, n) - c  # (S, P, K)
    s1 = np.einsum("sd,pkd->spk", b, n) - c
    ds = s1 - s0
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (-tol - s0) / ds  # where s_k(t) = -tol
    rising, falling = ds > 0.0, ds < 0.0
    t_hi = np.minimum(1.0, np.where(rising, t, np.inf).min(axis=2))
    t_lo = np.maximum(0.0, np.where(falling, t, -np.inf).max(axis=2))
    flat_out = np.any((ds == 0.0) & (s0 >= -tol), axis=2)  # parallel to an edge, not inside it
    return np.any((t_lo < t_hi) & ~flat_out, axis=1)


def _check_point(value, name: str) -> np.ndarray:
    try:
        p = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a point (x, y), got {value!r}") from exc
    if p.shape != (2,) or not np.all(np.isfinite(p)):
        raise ValueError(f"{name} must be a finite point (x, y), got {value!r}")
    return p


def shortest_point_path(
    start, goal, polygons, bounds: Sequence[float] | None = None
) -> tuple[float, np.ndarray]:
    """Shortest path of a point from ``start`` to ``goal`` avoiding the interiors of convex polygons.

    The exact shortest path in the closure of the free space bends only at polygon
    vertices, so it is the shortest path on the visibility graph of ``start``, ``goal``
    and the vertices that lie in no polygon's interior and inside ``bounds`` (Dijkstra).
    A segment is visible unless it crosses a polygon's interior by more than ``1e-9``
    times the scene's size (touching a vertex or sliding along an edge is allowed), so
    the length returned is a lower bound on the length of any path through the open free
    space: the use made of it in the book.

    Parameters
    ----------
    start, goal : (x, y)
        Points outside every polygon's interior and inside ``bounds``.
    polygons : sequence of (k, 2) arrays
        Convex polygons, counter-clockwise (as :attr:`segplan.Scenario.enlarged`); they
        may overlap each other and the walls.
    bounds : (xmin, ymin, xmax, ymax), optional
        A rectangle the path stays in (closed).

    Returns
    -------
    length : float
        ``math.inf`` if the goal cannot be reached.
    path : ndarray (m, 2)
        The polyline from ``start`` to ``goal`` (empty ``(0, 2)`` if unreachable).

    Raises
    ------
    ValueError
        Malformed points, polygons or bounds, or ``start`` / ``goal`` inside a polygon or
        outside ``bounds``.
    """
    a, b = _check_point(start, "start"), _check_point(goal, "goal")
    polys = []
    for i, p in enumerate(polygons):
        q = np.asarray(p, dtype=float)
        if q.ndim != 2 or q.shape[1] != 2 or q.shape[0] < 3 or not np.all(np.isfinite(q)):
            raise ValueError(f"polygons[{i}] must be a finite (k, 2) array with k >= 3, got shape {q.shape}")
        polys.append(q)
    points = [a, b] + polys
    if bounds is not None:
        try:
            box = np.array([float(v) for v in bounds])
        except (TypeError, ValueError) as exc:
            raise ValueError(f"bounds must be (xmin, ymin, xmax, ymax), got {bounds!r}") from exc
        if box.shape != (4,) or not np.all(np.isfinite(box)) or not (box[0] < box[2] and box[1] < box[3]):
            raise ValueError(f"bounds must be finite (xmin, ymin, xmax, ymax) with min < max, got {bounds!r}")
        points.append(box.reshape(2, 2))
    allpts = np.vstack(points)
    tol = 1e-9 * max(1.0, float(np.abs(allpts).max()))

    def inside_box(x: np.ndarray) -> np.ndarray:
        if bounds is None:
            return np.ones(len(x), dtype=bool)
        return np.all((x >= box[:2] - tol) & (x <= box[2:] + tol), axis=1)

    if polys:
        n, c = _half_planes(polys)

        def interior(x: np.ndarray) -> np.ndarray:  # inside some polygon by more than tol
            return np.any(np.all(np.einsum("sd,pkd->spk", x, n) - c < -tol, axis=2), axis=1)
    else:

        def interior(x: np.ndarray) -> np.ndarray:
            return np.zeros(len(x), dtype=bool)

    for name, p in (("start", a), ("goal", b)):
        if interior(p[None])[0] or not inside_box(p[None])[0]:
            raise ValueError(f"{name} ({p[0]:g}, {p[1]:g}) lies inside a polygon or outside the bounds")
    if not polys or not _crosses_interior(a[None], b[None], n, c, tol)[0]:
        return float(np.hypot(*(b - a))), np.vstack((a, b))
    verts = np.vstack(polys)
    verts = verts[~interior(verts) & inside_box(verts)]
    nodes = np.vstack((a, b, verts))  # 0: start, 1: goal
    m = len(nodes)
    i, j = np.triu_indices(m, k=1)
    weight = np.full((m, m), np.inf)
    for lo in range(0, i.size, 4096):  # bounded memory: (chunk, P, K) arrays
        ii, jj = i[lo : lo + 4096], j[lo : lo + 4096]
        free = ~_crosses_interior(nodes[ii], nodes[jj], n, c, tol)
        w = np.hypot(*(nodes[jj] - nodes[ii]).T)
        weight[ii[free], jj[free]] = w[free]
        weight[jj[free], ii[free]] = w[free]
    # Dijkstra on the dense visibility graph
    dist = np.full(m, np.inf)
    prev = np.full(m, -1)
    dist[0] = 0.0
    done = np.zeros(m, dtype=bool)
    heap = [(0.0, 0)]
    while heap:
        du, u = heapq.heappop(heap)
        if done[u]:
            continue
        done[u] = True
        if u == 1:
            break
        better = ~done & (du + weight[u] < dist)
        for v in np.flatnonzero(better):
            dist[v] = du + weight[u, v]
            prev[v] = u
            heapq.heappush(heap, (dist[v], int(v)))
    if not math.isfinite(dist[1]):
        return math.inf, np.empty((0, 2))
    route = [1]
    while route[-1] != 0:
        route.append(int(prev[route[-1]]))
    return float(dist[1]), nodes[route[::-1]]


def point_lower_bounds(scenario: Scenario) -> dict:
    """Lower bounds on the front-wheel length (LONGD) and the rear length of any plan.

    The robot's segment stays clear of ``scenario.enlarged`` and inside
    ``scenario.free_bounds``, so B (A) cannot travel less than a point going from the
    start's B (A) to the goal's B (A) among the same polygons (module docstring).

    Returns
    -------
    dict
        ``front`` and ``rear`` (m; ``math.inf`` if unreachable even for a point), and the
        polylines ``front_path`` and ``rear_path`` ``(m, 2)``.
    """
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    L = scenario.robot.L
    (a0, b0), (a1, b1) = pose_segment(scenario.start, L), pose_segment(scenario.goal, L)
    front, front_path = shortest_point_path(b0, b1, scenario.enlarged, scenario.free_bounds)
    rear, rear_path = shortest_point_path(a0, a1, scenario.enlarged, scenario.free_bounds)
    return {"front": front, "rear": rear, "front_path": front_path, "rear_path": rear_path}


# -- the optimum bracketed from both sides ------------------------------------------------------
def best_known_plans(
    scenario: Scenario,
    ompl_csv: str | Path | None = None,
    plans: Mapping[str, Plan] | None = None,
    heuristics: Sequence[str] = ("a", "b", "c"),
) -> pd.DataFrame:
    """Every planner of the book on ``scenario``, each with its shortest feasible plan (LONGD).

    The shortest of them is an upper bound on the optimal LONGD (the optimum is at most any
    feasible plan's cost). The candidates:

    - ``plans``: plans the caller has made already (label -> :class:`segplan.Plan`), e.g.
      a chapter's searches;
    - the paper's search refined by :func:`segplan.refine` (beyond the paper), one per
      heuristic of ``heuristics``, and segplan's default planner (the lattice, refined),
      planned here (deterministic);
    - OMPL's runs stored by ``benchmarks/peers.py`` at ``ompl_csv`` (read with
      :func:`segplan.studies.peers.read_ompl_results`, never typed): per planner, the
      shortest exact Dubins solution that the dense collision oracle found valid, over every
      budget and seed, raw and, where stored, after OMPL's ``PathSimplifier``. Reeds-Shepp
      paths reverse, which the robot does not, and are left out. Their length is the
      front-wheel length measured on the stored path (:func:`segplan.viz.metrics.measure_path`),
      the same quantity as a plan's LONGD.

    Parameters
    ----------
    scenario : Scenario
    ompl_csv : str or Path, optional
        The stored OMPL results (``benchmarks/results/peers_ompl.csv``); ``None``: segplan only.
    plans : mapping of str to Plan, optional
    heuristics : sequence of {"a", "b", "c"}

    Returns
    -------
    DataFrame
        Columns ``planner``, ``LONGD [m]``, ``source``, shortest first; planners that found
        no plan are left out.

    Raises
    ------
    ValueError
        A bad ``scenario`` or ``plans``, or no stored results at ``ompl_csv``.
    """
    import pandas as pd

    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    rows = []
    for label, plan in (plans or {}).items():
        if not isinstance(plan, Plan):
            raise ValueError(f"plans[{label!r}] must be a segplan.Plan, got {type(plan).__name__}")
        rows.append({"planner": str(label), "LONGD [m]": float(plan.cost), "source": "this chapter"})
    made = {
        f"paper's search, h'={h}, refined": dict(planner="paper", heuristic=h, refine=True)
        for h in heuristics
    }
    made["segplan's default planner"] = {}
    for label, options in made.items():
        try:
            cost = float(plan_scenario(scenario, **options).cost)
        except NoPathError:
            continue
        rows.append({"planner": label, "LONGD [m]": cost, "source": "planned here"})
    if ompl_csv is not None:
        from .peers import SIMPLIFIED, read_ompl_results, simplified_rows

        table, _, meta = read_ompl_results(ompl_csv)
        runs = table[(table["scenario"] == scenario.name) & (table["space"] == "dubins")]
        runs = runs[~runs["method"].str.endswith(SIMPLIFIED)]
        both = pd.concat([runs, simplified_rows(runs)], ignore_index=True)
        ok = both[both["solved"].astype(bool) & both["valid"].astype(bool)]
        when = str(meta.get("date", "date not stored"))
        for method, g in ok.groupby("method", sort=True):
            best = g.loc[g["front_length"].idxmin()]
            rows.append(
                {
                    "planner": f"OMPL {method} (Dubins)",
                    "LONGD [m]": float(best["front_length"]),
                    "source": f"stored run, {best['budget']:g} s budget, seed {int(best['seed'])}, "
                    f"best of {len(g)} valid ({Path(ompl_csv).name}, {when})",
                }
            )
    out = pd.DataFrame(rows, columns=["planner", "LONGD [m]", "source"])
    return out.sort_values("LONGD [m]", kind="stable").reset_index(drop=True)


def optimum_interval(scenario: Scenario, known: pd.DataFrame) -> dict:
    """The optimal LONGD of ``scenario`` bracketed from both sides.

    ``low``: the point-path lower bound (:func:`point_lower_bounds`, front); ``high``: the
    shortest plan of ``known`` (:func:`best_known_plans`), by ``by``. The optimum lies in
    ``[low, high]``, so a plan of cost ``c`` is within ``[c / high, c / low]`` of it.

    Raises
    ------
    ValueError
        If ``known`` is empty (no feasible plan is known) or lacks its columns.
    """
    if not {"planner", "LONGD [m]"} <= set(getattr(known, "columns", ())) or len(known) == 0:
        raise ValueError("known must be a non-empty table of best_known_plans")
    best = known.loc[known["LONGD [m]"].idxmin()]
    low = float(point_lower_bounds(scenario)["front"])
    return {"low": low, "high": float(best["LONGD [m]"]), "by": str(best["planner"])}
