"""The floor kinds of issue 25 (segplan.studies.floor_kinds, floor_layouts, kind_study).

- every kind's floors are deterministic (bit for bit, pinned keys), valid scenarios with free
  start and goal, inside their bounds;
- their geometry is what the docstrings state, measured with shapely as an independent
  oracle: aisle, rack and cross-aisle widths; walls, doors and the room left in front of
  them; the free bay between parked cars and the nose-in goal; clutter counts and gaps;
  the other robots' ranges; the large sites' roads; tight starts face something close
  ahead and can turn away;
- the study's summary and worst floors judge synthetic tables as stated, its OMPL side goes
  through the robustness study's run_ompl with this study's provenance, and
  ``benchmarks/floor_kinds.py`` runs (segplan side, one floor of two kinds).
"""

import json
import math
import subprocess
import sys
from itertools import pairwise
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import shapely

from segplan.floor.scenario import scenario_from_dict
from segplan.studies import floor_kinds as fk
from segplan.studies import floor_layouts as fl
from segplan.studies import kind_study as ks
from segplan.studies import robustness as rb
from segplan.studies.floors import ROBOT, floor_key

ROOT = Path(__file__).resolve().parents[1]
#: Floors drawn per kind in these tests (each kind's first ones).
N_TEST = {kind: 10 if kind == "large" else 12 for kind in fk.FLOOR_KINDS}
#: floor_key of floor 0 of each kind at GENERATOR_VERSION 1: a change of any floor must bump
#: the version (stored results name it) and update these.
PINNED = {
    "warehouse": "7c185523be0c",
    "rooms": "4c3de15adde9",
    "parking": "a4b7afe7639e",
    "clutter": "cc682c953c93",
    "robots": "73a1e797935b",
    "large": "a8b950fc20d7",
}
TOL = 1e-9


@pytest.fixture(scope="module")
def floors():
    """The first N_TEST floors of every kind (about 7 s of CPU)."""
    return {kind: [fk.kind_floor(kind, i) for i in range(n)] for kind, n in N_TEST.items()}


def _box(p) -> tuple:
    p = np.asarray(p)
    return (*p.min(axis=0), *p.max(axis=0))


def _within(x: float, lo_hi: tuple, tol: float = TOL) -> bool:
    return lo_hi[0] - tol <= x <= lo_hi[1] + tol


def _heading_off(theta: float, target: float) -> float:
    return abs((theta - target + math.pi) % (2 * math.pi) - math.pi)


def _front(pose, L: float) -> np.ndarray:
    return np.array([pose.x + L * math.cos(pose.theta), pose.y + L * math.sin(pose.theta)])


# -- every kind ---------------------------------------------------------------------------
def test_floors_are_deterministic_and_pinned():
    for kind in fk.FLOOR_KINDS:
        a, b = fk.kind_floor(kind, 0), fk.kind_floor(kind, 0)
        assert a.to_json() == b.to_json() and floor_key(a) == floor_key(b)
        assert floor_key(a) != floor_key(fk.kind_floor(kind, 1))
        assert floor_key(a) == PINNED[kind], f"{kind}-000 changed: bump GENERATOR_VERSION, update PINNED"
    assert [sc.name for sc in fk.kind_floors("parking", 3)] == ["parking-000", "parking-001", "parking-002"]


def test_arguments_are_checked():
    with pytest.raises(ValueError, match="kind"):
        fk.kind_floor("garden", 0)
    for bad in (-1, 1.0, True, "3"):
        with pytest.raises(ValueError, match="index"):
            fk.kind_floor("rooms", bad)
    with pytest.raises(ValueError, match="n must"):
        fk.kind_floors("rooms", -2)
    with pytest.raises(ValueError, match="size"):
        fk.stress_floor(0, size=10.0)
    with pytest.raises(ValueError, match="n_obstacles"):
        fk.stress_floor(0, size=100.0, n_obstacles=401)
    with pytest.raises(ValueError, match="robot"):
        fk.turn_excursion("robot")
    assert fk.turn_excursion(ROBOT) == pytest.approx(math.sqrt(2.0) - 1.0)
    # a door fits the book's robot with room to spare
    assert fl.DOOR_WIDTH[0] >= 2 * ROBOT.half_width + fl.DOOR_MARGIN - TOL


def test_every_floor_is_a_valid_scenario_inside_its_bounds(floors):
    for kind, scs in floors.items():
        for i, sc in enumerate(scs):
            assert sc.name == f"{kind}-{i:03d}"
            assert f"segplan.studies.floor_kinds v{fk.GENERATOR_VERSION}" in sc.description
            if i < 3:  # its file loads (headings in degrees)
                again = scenario_from_dict(json.loads(sc.to_json()))
                assert again.is_free(again.start) and again.is_free(again.goal)
                assert all(np.array_equal(p, q) for p, q in zip(again.outlines, sc.outlines, strict=True))
            assert sc.is_free(sc.start) and sc.is_free(sc.goal)
            if kind != "robots":
                assert sc.robot == ROBOT
            room = shapely.box(*sc.bounds)
            for p in sc.outlines:
                poly = shapely.Polygon(p)
                assert poly.is_valid and room.covers(poly), (sc.name, _box(p))
            assert np.array_equal(np.round(np.vstack(sc.outlines), 6), np.vstack(sc.outlines))


def test_tight_starts_face_something_close_ahead_and_can_turn_away(floors):
    """A tight start's front wheel is within ``e + 0.31 L`` of an enlarged obstacle or the
    shrunk walls straight ahead, farther than ``e`` from it, and a quarter circle at the
    smallest radius to one side is free: the segment every 1 cm of A's arc misses the
    enlarged obstacles and stays in the free bounds (shapely)."""
    n = 0
    for scs in floors.values():
        for sc in (s for s in scs if "tight start" in s.description):
            n += 1
            r, L, s = sc.robot, sc.L, sc.start
            R, e = r.min_turning_radius, fk.turn_excursion(r)
            u = np.array([math.cos(s.theta), math.sin(s.theta)])
            b = _front(s, L)
            near = shapely.Point(s.x, s.y).buffer(R + 2 * L)
            blocked = [q for q in (shapely.Polygon(p) for p in sc.enlarged) if q.intersects(near)]
            blocked = shapely.union_all(
                [*blocked, shapely.box(*sc.bounds).difference(shapely.box(*sc.free_bounds))]
            )
            ahead = shapely.LineString([b, b + (e + fk.TIGHT_MARGIN[1] * L + 0.011 * L) * u])
            assert ahead.intersects(blocked), sc.name
            assert not shapely.LineString([b, b + e * u]).intersects(blocked), sc.name
            psi = np.linspace(0.0, 0.5 * math.pi, max(10, math.ceil(0.5 * math.pi * R / 0.01)))
            turns = []
            for side in (1.0, -1.0):
                ax = s.x + R * (np.sin(psi) * u[0] - side * (1 - np.cos(psi)) * u[1])
                ay = s.y + R * (np.sin(psi) * u[1] + side * (1 - np.cos(psi)) * u[0])
                th = s.theta + side * psi
                swept = shapely.linestrings(
                    np.stack([ax, ay, ax + L * np.cos(th), ay + L * np.sin(th)], 1).reshape(-1, 2, 2)
                )
                turns.append(not shapely.intersects(swept, blocked).any())
            assert any(turns), sc.name
    assert n >= 12  # a quarter of the floors, or about


# -- warehouse ----------------------------------------------------------------------------
def test_warehouse_racks_aisles_and_cross_aisle(floors):
    for sc in floors["warehouse"]:
        assert sc.bounds == fl.WAREHOUSE_BOUNDS
        boxes = sorted(_box(p) for p in sc.outlines)
        rows = sorted({(b[1], b[3]) for b in boxes})
        assert 3 <= len(rows) <= 5 and len(boxes) == 2 * len(rows)
        assert _within(rows[0][0], fl.AISLE_WIDTH)  # the bottom wall aisle
        assert sc.bounds[3] - rows[-1][1] >= fl.AISLE_WIDTH[0] - TOL  # the top wall aisle
        for (_, top), (bottom, _) in pairwise(rows):
            assert _within(bottom - top, fl.AISLE_WIDTH)  # aisles between racks
        for lo, hi in rows:
            assert _within(hi - lo, fl.RACK_DEPTH)
        gaps = set()
        for lo, hi in rows:
            left, right = sorted(b for b in boxes if (b[1], b[3]) == (lo, hi))
            gaps.add((left[2], right[0]))
            ends = (left[0], sc.bounds[2] - right[2])
            assert all(e == 0.0 or _within(e, fl.END_AISLE_WIDTH) for e in ends) and max(ends) > 0
            assert (min(ends) == 0.0) == ("against the" in sc.description)
        (a, b), *others = gaps
        assert not others and _within(b - a, fl.CROSS_AISLE_WIDTH)  # one straight cross aisle
        for p in (sc.start, sc.goal):  # along or across the aisles
            assert min(_heading_off(p.theta, k * 0.5 * math.pi) for k in range(4)) < 1e-5
        assert math.dist(sc.start[:2], sc.goal[:2]) >= fk.MIN_DISTANCE
        if "goal across" in sc.description:  # nose to a rack, room behind to arrive
            assert min(_heading_off(sc.goal.theta, t) for t in (0.5 * math.pi, -0.5 * math.pi)) < 1e-5
            back = sc.goal.y - math.sin(sc.goal.theta) * (sc.robot.min_turning_radius + 0.05)
            assert sc.is_free((sc.goal.x, back, sc.goal.theta))
    assert any("goal across" in sc.description for sc in floors["warehouse"])
    assert any("against the" in sc.description for sc in floors["warehouse"])


# -- rooms --------------------------------------------------------------------------------
def _walls_and_furniture(sc):
    walls, furniture = [], []
    for p in sc.outlines:
        b = _box(p)
        thin = min(b[2] - b[0], b[3] - b[1]) <= fl.WALL_THICKNESS[1] + TOL and len(p) == 4
        (walls if thin else furniture).append(p)
    return walls, furniture


def _openings(parts, along: int, lo: float, hi: float) -> list[tuple[float, float]]:
    """The gaps between collinear wall parts along axis ``along``, from ``lo`` to ``hi``."""
    spans = sorted((b[along], b[along + 2]) for b in map(_box, parts))
    assert spans[0][0] == lo and spans[-1][1] == hi  # the line runs wall to wall
    return [(a[1], b[0]) for a, b in pairwise(spans) if b[0] > a[1]]


def test_rooms_walls_doors_and_furniture(floors):
    for sc in floors["rooms"]:
        assert sc.bounds == fl.ROOMS_BOUNDS
        walls, furniture = _walls_and_furniture(sc)
        vertical = [w for w in walls if np.ptp(w[:, 0]) < np.ptp(w[:, 1])]
        horizontal = [w for w in walls if np.ptp(w[:, 0]) > np.ptp(w[:, 1])]
        t = float(np.ptp(vertical[0][:, 0]))
        assert _within(t, fl.WALL_THICKNESS)
        assert all(math.isclose(min(np.ptp(w, axis=0)), t) for w in walls)  # one thickness
        xs = sorted({round(float(w[:, 0].mean()), 6) for w in vertical})
        ys = sorted({round(float(w[:, 1].mean()), 6) for w in horizontal})
        assert len(xs) == 2 and len(ys) == 1  # six rooms, 3 x 2
        doors = []  # (opening box, width)
        for x in xs:
            line = [w for w in vertical if math.isclose(w[:, 0].mean(), x)]
            for a, b in _openings(line, 1, 0.0, 12.0):
                doors.append((shapely.box(x - t / 2 - fl.DOOR_CLEAR, a, x + t / 2 + fl.DOOR_CLEAR, b), b - a))
        junctions = []
        for a, b in _openings(horizontal, 0, 0.0, 20.0):
            if math.isclose(b - a, t) and any(math.isclose(0.5 * (a + b), x) for x in xs):
                junctions.append(a)  # where a vertical wall crosses
            else:
                y = ys[0]
                doors.append((shapely.box(a, y - t / 2 - fl.DOOR_CLEAR, b, y + t / 2 + fl.DOOR_CLEAR), b - a))
        assert len(junctions) == 2 and len(doors) == 7  # one door in each wall between two rooms
        for zone, width in doors:
            assert _within(width, fl.DOOR_WIDTH) and width >= 2 * sc.robot.half_width + fl.DOOR_MARGIN - TOL
            assert not any(zone.intersects(shapely.Polygon(p)) for p in furniture)  # nothing in front
        polys = [shapely.Polygon(p) for p in furniture]
        for i, p in enumerate(polys):
            assert min(p.bounds[2] - p.bounds[0], p.bounds[3] - p.bounds[1]) >= 0.4 - TOL
            assert not any(p.intersects(shapely.Polygon(w)) for w in walls)
            assert all(p.distance(q) >= fl.FURNITURE_GAP - TOL for q in polys[i + 1 :])
        rooms = [
            (int(np.searchsorted(xs, c.x)), int(np.searchsorted(ys, c.y)))
            for c in (p.centroid for p in polys)
        ]
        assert max(rooms.count(r) for r in set(rooms)) <= fl.FURNITURE[1] if rooms else True

        start, goal = (
            (int(np.searchsorted(xs, p.x)), int(np.searchsorted(ys, p.y))) for p in (sc.start, sc.goal)
        )
        assert start != goal  # two rooms
    assert any(len(p) == 6 for sc in floors["rooms"] for p in sc.outlines)  # an L-shaped counter


# -- parking ------------------------------------------------------------------------------
def test_parking_rows_free_bay_and_nose_in_goal(floors):
    for sc in floors["parking"]:
        W, H = sc.bounds[2], sc.bounds[3]
        cars = [shapely.Polygon(p) for p in sc.outlines]
        assert len(cars) % 2 == 1 and 2 * fl.BAYS_PER_ROW[0] - 1 <= len(cars) <= 2 * fl.BAYS_PER_ROW[1] - 1
        for c in cars:
            e = np.asarray(c.exterior.coords)[:3]
            w, h = sorted((math.dist(e[0], e[1]), math.dist(e[1], e[2])))
            assert _within(w, fl.CAR_WIDTH, 1e-5) and _within(h, fl.CAR_LENGTH, 1e-5)
        g, L, r = sc.goal, sc.L, sc.robot.half_width
        bottom = g.theta < 0  # nose-in: heading into its row, to the wall
        assert _heading_off(g.theta, -0.5 * math.pi if bottom else 0.5 * math.pi) < 1e-5
        b = _front(g, L)
        to_wall = (b[1] - r) if bottom else (H - r - b[1])
        assert 0.1 * L - TOL <= to_wall <= 0.31 * L + TOL
        row = [c for c in cars if (c.centroid.y < 0.5 * H) == bottom]
        assert len(row) == len(cars) // 2  # the free bay's row lacks one car
        left = [c for c in row if c.centroid.x < g.x]
        right = [c for c in row if c.centroid.x > g.x]
        body = shapely.LineString([(g.x, g.y), tuple(b)]).buffer(r)
        assert not any(body.intersects(c) for c in cars)
        if left and right:  # the free bay between its neighbours
            lc = max(left, key=lambda c: c.centroid.x)
            rc = min(right, key=lambda c: c.centroid.x)
            assert lc.distance(rc) >= fl.BAY_PITCH[0] + 0.1 - 1e-6
            assert lc.bounds[2] < g.x < rc.bounds[0]
        assert math.dist(sc.start[:2], sc.goal[:2]) >= W / 3  # across the lot


# -- clutter and other robots -------------------------------------------------------------
def _check_clutter(sc, scale: float):
    polys = [shapely.Polygon(p) for p in sc.outlines]
    assert _within(len(polys), fl.CLUTTER_COUNT)
    inner = shapely.box(*sc.bounds).buffer(-1e-9)
    for i, p in enumerate(polys):
        assert inner.contains(p)
        assert all(p.distance(q) >= fl.CLUTTER_GAP * scale - 1e-5 for q in polys[i + 1 :])
    s, g = sc.start, sc.goal
    assert math.dist(s[:2], g[:2]) >= fk.MIN_DISTANCE * scale
    direction = math.atan2(g.y - s.y, g.x - s.x)
    assert _heading_off(g.theta, direction) <= fk.NATURAL_SPREAD + 1e-5
    if "tight start" not in sc.description:
        assert _heading_off(s.theta, direction) <= fk.NATURAL_SPREAD + 1e-5


def test_clutter_counts_gaps_and_headings(floors):
    for sc in floors["clutter"]:
        assert sc.bounds == fl.CLUTTER_BOUNDS
        _check_clutter(sc, 1.0)
    assert any(len(p) == 6 for sc in floors["clutter"] for p in sc.outlines)  # small L-shapes


def test_other_robots_and_their_scaled_clutter(floors):
    robots = [sc.robot for sc in floors["robots"]]
    for sc in floors["robots"]:
        r = sc.robot
        assert _within(r.L, fk.ROBOT_LENGTH) and round(r.L, 2) == r.L
        assert _within(math.degrees(r.max_steer), fk.ROBOT_STEER_DEG, 1e-9)
        assert _within(r.half_width / r.L, fk.ROBOT_HALF_WIDTH, 1e-3)
        assert sc.bounds == (0.0, 0.0, round(20 * r.L, 2), round(12 * r.L, 2))
        _check_clutter(sc, r.L)
    assert np.ptp([r.L for r in robots]) > 0.5 and np.ptp([r.max_steer for r in robots]) > math.radians(10)


# -- large sites and the stress floor -----------------------------------------------------
def test_large_sites_blocks_and_roads(floors):
    cx, cy = fl.SITE_CELL
    for sc in floors["large"]:
        nx, ny = sc.bounds[2] / cx, sc.bounds[3] / cy
        assert nx == int(nx) and ny == int(ny) and _within(nx, fl.SITE_BLOCKS) and _within(ny, fl.SITE_BLOCKS)
        assert 100 <= len(sc.outlines) <= 700
        for p in sc.outlines:  # every obstacle in one cell, 3 m clear of its edges: roads of 6 m
            x0, y0, x1, y1 = _box(p)
            i, j = math.floor(x0 / cx), math.floor(y0 / cy)
            assert x0 >= i * cx + 3.0 - TOL and x1 <= (i + 1) * cx - 3.0 + TOL, sc.name
            assert y0 >= j * cy + 3.0 - TOL and y1 <= (j + 1) * cy - 3.0 + TOL, sc.name
        cell = [(math.floor(p.x / cx), math.floor(p.y / cy)) for p in (sc.start, sc.goal)]
        assert cell[0] != cell[1]
        assert math.dist(sc.start[:2], sc.goal[:2]) >= fk.SITE_MIN_DISTANCE - 2 * math.hypot(cx, cy) / 2


def test_stress_floor_small():
    sc = fk.stress_floor(0, size=300.0, n_obstacles=1000)
    assert sc.name == "stress-300-1000-0" and len(sc.obstacles) == 1000 and sc.bounds == (0, 0, 300, 300)
    assert fk.stress_floor(0, size=300.0, n_obstacles=1000).to_json() == sc.to_json()
    cell = 300.0 / math.ceil(math.sqrt(1000))
    tree = shapely.STRtree([shapely.Polygon(p) for p in sc.obstacles])
    pairs = tree.query(
        [shapely.Polygon(p) for p in sc.obstacles], predicate="dwithin", distance=0.2 * cell - 1e-6
    )
    assert (pairs[0] == pairs[1]).all()  # no two rectangles closer than a fifth of a cell
    assert max(sc.start.x, sc.start.y) <= 30.0 and min(sc.goal.x, sc.goal.y) >= 270.0


# -- the study ----------------------------------------------------------------------------
def _table() -> pd.DataFrame:
    rows = [
        # group, floor, solved, valid, reason, ompl_solved, ompl_runs, ratio, seconds
        ("rooms", "rooms-000", True, True, "", True, 1, 1.10, 0.10),
        ("rooms", "rooms-001", False, False, "exhausted", True, 1, math.nan, 1.00),
        ("rooms", "rooms-002", True, False, "", False, 1, math.nan, 0.30),
        ("large", "large-000", True, True, "", True, 1, 1.30, 2.00),
        ("large", "large-001", True, True, "", False, 1, math.nan, 0.50),
        ("large", "large-002", False, False, "expansions", False, 0, math.nan, 0.70),
    ]
    cols = ["group", "floor", "solved", "valid", "reason", "ompl_solved", "ompl_runs", "ratio", "seconds"]
    t = pd.DataFrame(rows, columns=cols)
    t["ratio"] = t["ratio"].astype(object)  # as compare() gives it without OMPL results
    t["cpu_seconds"] = 0.5 * t["seconds"]
    return t


def test_summary_and_worst_floors():
    s = ks.summary(_table()).set_index("kind")
    assert list(s.columns) == list(ks.SUMMARY_COLUMNS[1:])
    rooms, large = s.loc["rooms"], s.loc["large"]
    assert (rooms.floors, rooms.ompl_solved, rooms.segplan_solved, rooms.solved_of_ompl) == (3, 2, 1, 1)
    assert (rooms.invalid, rooms.no_plan, rooms.ratio_worst) == (1, "exhausted: 1", 1.10)
    assert (large.ompl_runs, large.segplan_solved, large.segplan_only, large.ratio_floors) == (2, 2, 1, 1)
    assert large.time_max_ms == pytest.approx(2000.0) and large.cpu_median_ms == pytest.approx(350.0)
    assert rooms.time_median_ms == pytest.approx(300.0)
    w = ks.worst_floors(_table(), per_kind=1)
    assert list(zip(w.floor, w.why, strict=True)) == [
        ("rooms-001", "OMPL solves, segplan does not"),
        ("rooms-002", "invalid plan"),
        ("rooms-000", "largest length ratio"),
        ("large-002", "no plan; no OMPL run"),
        ("large-000", "largest length ratio"),
    ]
    with pytest.raises(ValueError, match="per_kind"):
        ks.worst_floors(_table(), per_kind=-1)


def test_ompl_side_goes_through_the_robustness_runner(tmp_path, monkeypatch):
    """Every kind in turn, BIT* 5 s seed 1; stored by rb.run_ompl with this study's provenance
    (fake runs: the runner and its executor are tested in test_robustness)."""
    groups = {k: fk.kind_floors(k, 2) for k in ("parking", "warehouse")}
    jobs = ks.ompl_jobs(groups)
    assert [(j[0], j[1].name, j[2], j[3], j[4]) for j in jobs] == [
        ("parking", "parking-000", "BITstar", 5.0, 1),
        ("warehouse", "warehouse-000", "BITstar", 5.0, 1),
        ("parking", "parking-001", "BITstar", 5.0, 1),
        ("warehouse", "warehouse-001", "BITstar", 5.0, 1),
    ]
    with pytest.raises(ValueError, match="kinds"):
        ks.kind_groups(1, ["garden"])

    def fake_record(job, resolution, space):
        assert space == "dubins"  # the default space of both studies
        group, sc, planner, budget, seed = job
        row = dict.fromkeys(rb.OMPL_COLUMNS, math.nan)
        row.update(group=group, floor=sc.name, floor_key=floor_key(sc), generator=-1, planner=planner)
        row.update(budget=budget, seed=seed, status="Exact solution", solved=True, valid=True)
        row.update(simplified_valid=True, seconds=budget, cpu_seconds=0.97 * budget, messages="")
        row.update(front_length=12.0, simplified_front_length=11.0, load_before=0.1, load_after=0.1)
        return {**row, "poses": [[0.0, 0.0, 0.0]], "simplified_poses": [[0.0, 0.0, 0.0]]}

    monkeypatch.setattr(rb, "ompl_record", fake_record)
    t = ks.run_ompl(groups, tmp_path / ks.OMPL_CSV_NAME, workers=1)
    assert len(t) == 4 and (t["generator"] == fk.GENERATOR_VERSION).all()
    prov = json.loads((tmp_path / "floor_kinds_ompl.json").read_text())
    assert prov["generator"] == "segplan.studies.floor_kinds" and prov["budgets"] == [5.0]
    assert prov["sessions"][-1]["fairness"]["min_share"] == 0.9
    row = dict.fromkeys(rb.SEGPLAN_COLUMNS, 0.0)
    row.update(group="parking", floor="parking-000", floor_key=floor_key(groups["parking"][0]))
    row.update(solved=True, valid=True, reason="", front_length=12.1)
    seg = pd.DataFrame([row])
    table = rb.compare(seg, t)
    assert table["ratio"].iloc[0] == pytest.approx(12.1 / 11.0)  # against BIT*'s simplified path


def test_harness_runs_the_segplan_side(tmp_path):
    out = subprocess.run(
        [
            sys.executable,
            str(ROOT / "benchmarks" / "floor_kinds.py"),
            "--n",
            "1",
            "--kinds",
            "parking",
            "warehouse",
        ]
        + ["--results", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=ROOT,
    )
    assert out.returncode == 0, out.stderr[-3000:]
    seg = ks.read_segplan(tmp_path / ks.SEGPLAN_CSV_NAME)
    assert (
        list(seg["floor"]) == ["parking-000", "warehouse-000"] and not (seg["solved"] & ~seg["valid"]).any()
    )
    meta = json.loads((tmp_path / "floor_kinds_segplan.json").read_text())
    assert (
        meta["generator_version"] == fk.GENERATOR_VERSION and "benchmarks/floor_kinds.py" in meta["command"]
    )
    assert len(meta["commit"]) == 40 and set(meta["cpu_share"]) == {"min", "median", "max"}
    summary = pd.read_csv(tmp_path / "floor_kinds_summary.csv")
    assert list(summary["kind"]) == ["parking", "warehouse"] and "time_p95_ms" in summary


def test_floors_draw_with_the_books_plot():
    """Chapter 9 draws the floors with segplan.viz.plot (one of each kind)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from segplan.viz.plot import plot_floor

    fig, axes = plt.subplots(2, 3)
    for ax, kind in zip(axes.flat, fk.FLOOR_KINDS, strict=True):
        plot_floor(fk.kind_floor(kind, 0), ax)
        assert ax.patches or ax.collections
    plt.close(fig)
