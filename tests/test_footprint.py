"""Footprints (issue 26) wired through: the robot, scenario files, the planners, refinement,
metrics, the command line and the drawings. The oracle of every plan: the robot's body
(:meth:`segplan.Robot.footprint`; the round body as shapely's buffer of the axis segment)
placed at poses 1 cm apart along the plan, against the *raw* obstacles and the walls."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest
import shapely

import segplan
from segplan.cli import main
from segplan.floor.scenario import FOOTPRINT_KEYS, scenario_from_dict
from segplan.viz.metrics import measure_scenario_path, plan_clearance, plan_poses


def body_hits(robot: segplan.Robot, poses: np.ndarray, scenario: segplan.Scenario) -> int:
    """Poses at which the body touches a raw obstacle or is not strictly inside the walls."""
    U = np.column_stack((np.cos(poses[:, 2]), np.sin(poses[:, 2])))
    if robot.rectangle:
        fp = robot.footprint()
        c, s = U[:, :1], U[:, 1:]
        xy = np.stack(
            (poses[:, :1] + c * fp[:, 0] - s * fp[:, 1], poses[:, 1:2] + s * fp[:, 0] + c * fp[:, 1]), -1
        )
        bodies = shapely.polygons(xy)
    else:
        R = poses[:, :2] - robot.rear_overhang * U
        F = poses[:, :2] + (robot.L + robot.front_overhang) * U
        bodies = shapely.buffer(shapely.linestrings(np.stack((R, F), 1)), robot.half_width, quad_segs=32)
    hits = np.zeros(len(poses), dtype=bool)
    if scenario.outlines:
        hits |= shapely.intersects(bodies, shapely.union_all([shapely.Polygon(o) for o in scenario.outlines]))
    if scenario.bounds is not None:
        hits |= ~shapely.within(bodies, shapely.box(*scenario.bounds))
    return int(hits.sum())


def with_robot(sc: segplan.Scenario, **body) -> segplan.Scenario:
    return segplan.make_scenario(replace(sc.robot, **body), sc.start, sc.goal, sc.outlines, sc.bounds)


# -- the robot -----------------------------------------------------------------------------------
def test_defaults_are_the_paper_robot():
    r = segplan.Robot(1.2, 0.35)
    assert r == segplan.Robot(1.2, 0.35, math.radians(45), 0.0, 0.0, False)
    assert r.axis == (0.0, 1.2)
    fp = r.footprint()
    t = np.clip(fp[:, 0], 0.0, 1.2)  # every vertex half_width from A->B: the round body
    np.testing.assert_allclose(np.hypot(fp[:, 0] - t, fp[:, 1]), 0.35, rtol=1e-12)
    assert shapely.Polygon(fp).is_valid and shapely.Polygon(fp).exterior.is_ccw


def test_the_footprints():
    r = segplan.Robot(1.5, 0.45, front_overhang=0.3, rear_overhang=0.6, rectangle=True)
    assert r.axis == (-0.6, 1.8)
    np.testing.assert_array_equal(r.footprint(), [[-0.6, -0.45], [1.8, -0.45], [1.8, 0.45], [-0.6, 0.45]])
    round_body = shapely.Polygon(replace(r, rectangle=False).footprint(65))
    assert round_body.bounds == pytest.approx((-1.05, -0.45, 2.25, 0.45))
    # the round body the planner checks holds the rectangle
    assert (
        shapely.LineString([(-0.6, 0), (1.8, 0)])
        .buffer(0.45 + 1e-12)
        .contains(shapely.Polygon(r.footprint()))
    )


@pytest.mark.parametrize(
    "body, message",
    [
        ({"front_overhang": -0.1}, "front_overhang must be >= 0 (the body must contain the segment A->B)"),
        ({"rear_overhang": -1e-9}, "rear_overhang must be >= 0"),
        ({"front_overhang": math.nan}, "front_overhang must be finite"),
        ({"rear_overhang": math.inf}, "rear_overhang must be finite"),
        ({"front_overhang": "a"}, "front_overhang must be a finite number"),
        ({"rectangle": 1}, "rectangle must be True or False"),
    ],
)
def test_bad_bodies_are_refused_naming_the_argument(body, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        segplan.Robot(1.0, 0.3, **body)


# -- scenario files ------------------------------------------------------------------------------
def test_files_round_trip_and_default_files_unchanged(tmp_path):
    sc = segplan.load_scenario("l_shaped_rack")
    assert not set(FOOTPRINT_KEYS) & set(sc.to_dict())  # the paper's robot: no new key
    body = {"front_overhang": 0.25, "rear_overhang": 0.5, "rectangle": True}
    sc2 = with_robot(sc, **body)
    d = sc2.to_dict()
    assert {k: d[k] for k in FOOTPRINT_KEYS} == body
    back = segplan.load_scenario(segplan.save_scenario(sc2, tmp_path / "f.json"))
    assert back.robot == sc2.robot
    assert {k: v for k, v in back.to_dict().items() if k != "name"} == {
        k: v for k, v in d.items() if k != "name"
    }


@pytest.mark.parametrize(
    "key, value, message",
    [
        ("front_overhang", -0.5, "front_overhang must be >= 0"),
        ("rear_overhang", "x", "rear_overhang must be a number"),
        ("rectangle", 1, "rectangle must be true or false"),
        ("rear_overhang", 2e6, "rear_overhang=2000000.0 exceeds"),
    ],
)
def test_bad_body_keys(key, value, message):
    d = segplan.load_scenario("turn_around").to_dict() | {key: value}
    with pytest.raises(segplan.ScenarioError, match=message):
        scenario_from_dict(d, "f.json")


def test_a_start_that_only_the_overhang_touches_is_refused():
    sc = segplan.load_scenario("single_obstacle")
    with pytest.raises(
        segplan.ScenarioError, match="out of bounds: its segment of length L=.* with overhangs"
    ):
        with_robot(sc, rear_overhang=5.0)


# -- the planners -------------------------------------------------------------------------------
@pytest.mark.parametrize("rectangle", [False, True])
def test_default_planner_and_refinement_honour_the_body(rectangle):
    """On the L-shaped rack the paper robot's plan would scrape the rack with this body; the
    plan for the body is clear of it at every centimetre, refined or not."""
    sc = segplan.load_scenario("l_shaped_rack")
    body = {"front_overhang": 0.5 * sc.L, "rear_overhang": 0.4 * sc.L, "rectangle": rectangle}
    robot = replace(sc.robot, **body)
    assert body_hits(robot, plan_poses(segplan.plan_scenario(sc), 0.01), sc) > 0
    sc2 = with_robot(sc, **body)
    for refine in (False, True):
        plan = segplan.plan_scenario(sc2, refine=refine)
        assert body_hits(robot, plan_poses(plan, 0.01), sc2) == 0


def test_paper_search_honours_the_body_or_says_no_path():
    """The paper's search tests every union with the same workspace: its plans are clear of the
    body; its node generation knows only the segment, so it may find none."""
    found = 0
    for name in ("fig6_example2", "turn_around", "l_shaped_rack"):
        sc = segplan.load_scenario(name)
        body = {"front_overhang": 0.3 * sc.L, "rear_overhang": 0.2 * sc.L}
        sc2 = with_robot(sc, **body)
        try:
            plan = segplan.plan_scenario(sc2, planner="paper", time_limit=5.0)
        except segplan.NoPathError:
            continue
        found += 1
        assert body_hits(sc2.robot, plan_poses(plan, 0.01), sc2) == 0
    assert found >= 1


def test_planner_clearance_keeps_the_body():
    sc = segplan.load_scenario("turn_around")
    robot = replace(sc.robot, front_overhang=0.2, rear_overhang=0.3)
    planner = segplan.Planner(sc.outlines, robot, sc.bounds, clearance=0.05)
    assert planner.floor.robot.front_overhang == 0.2 and planner.floor.robot.rear_overhang == 0.3
    plan = planner.plan(sc.start, sc.goal)
    assert body_hits(replace(robot, half_width=robot.half_width + 0.05), plan_poses(plan, 0.01), sc) == 0
    grown = segplan.floor.scenario.with_clearance(with_robot(sc, front_overhang=0.2), 0.01)
    assert grown.robot.front_overhang == 0.2


# -- metrics and drawings ----------------------------------------------------------------------
def test_clearance_is_of_the_extended_segment():
    sc = segplan.load_scenario("turn_around")
    plan = segplan.plan_scenario(sc)
    poses = plan_poses(plan, 0.01)
    sc2 = with_robot(sc, front_overhang=0.2, rear_overhang=0.1)
    m = measure_scenario_path(poses, sc2)
    U = np.column_stack((np.cos(poses[:, 2]), np.sin(poses[:, 2])))
    lines = shapely.linestrings(np.stack((poses[:, :2] - 0.1 * U, poses[:, :2] + (sc.L + 0.2) * U), 1))
    xmin, ymin, xmax, ymax = sc2.free_bounds
    ends = np.concatenate((poses[:, :2] - 0.1 * U, poses[:, :2] + (sc.L + 0.2) * U))
    walls = min(
        (ends[:, 0] - xmin).min(),
        (xmax - ends[:, 0]).min(),
        (ends[:, 1] - ymin).min(),
        (ymax - ends[:, 1]).min(),
    )
    obstacles = shapely.union_all([shapely.Polygon(p) for p in sc2.enlarged])
    expect = min(float(shapely.distance(lines, obstacles).min()), walls) if sc2.enlarged else walls
    assert m.clearance == pytest.approx(expect, abs=1e-12)
    assert plan_clearance(plan, sc2) < plan_clearance(plan, sc)
    assert m.front_length == measure_scenario_path(poses, sc).front_length  # B's path, unchanged


def test_the_animation_draws_the_footprint():
    from segplan.viz import animate

    sc = with_robot(
        segplan.load_scenario("turn_around"), front_overhang=0.3, rear_overhang=0.2, rectangle=True
    )
    plan = segplan.plan_scenario(sc)
    anim = animate.animate_plan(plan, sc, frames=4)
    poses = plan_poses(plan)
    idx = animate._frame_indices(poses, sc.L, 4)
    for k in (0, 2):
        body = anim._func(k)[2]
        x, y, th = poses[idx[k]]
        c, s = math.cos(th), math.sin(th)
        expect = sc.robot.footprint() @ np.array([[c, s], [-s, c]]) + (x, y)
        np.testing.assert_allclose(body.get_xy()[: len(expect)], expect, atol=1e-12)
    assert "overhangs 0.3 m front, 0.2 m rear (rectangle)" in body.get_label()


def test_the_figure_draws_the_body_at_start_and_goal():
    from matplotlib.patches import Polygon as PolygonPatch

    from segplan.viz import plot

    sc = with_robot(segplan.load_scenario("turn_around"), front_overhang=0.3, rectangle=True)
    fig = plot.plan_figure(sc, ())
    patches = [p for p in fig.axes[0].patches if isinstance(p, PolygonPatch)]
    bodies = [p.get_xy()[:4] for p in patches if len(p.get_xy()) == 5]  # closed 4-gons: the rectangles
    x, y, th = sc.start
    c, s = math.cos(th), math.sin(th)
    start = sc.robot.footprint() @ np.array([[c, s], [-s, c]]) + (x, y)
    assert any(np.allclose(b, start) for b in bodies)
    import matplotlib.pyplot as plt

    plt.close(fig)


# -- the command line --------------------------------------------------------------------------
def test_cli_plans_a_map_with_a_body(room_map, capsys, tmp_path):
    argv = ["plan", room_map, "--start", "1", "3", "0", "--goal", "8", "3", "0", "--L", "1.0"]
    argv += ["--half-width", "0.3", "--overhangs", "0.3", "0.2", "--rectangle", "--unknown-free", "--json"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["found"]
    assert (
        main(["draw", room_map, *argv[2:12], "--overhangs", "0.3", "0.2", "--out", str(tmp_path / "f.png")])
        == 0
    )
    assert (tmp_path / "f.png").exists()


def test_cli_body_errors(room_map, capsys):
    assert main(["plan", "turn_around", "--overhangs", "0.1", "0.1"]) == 2
    assert "--overhangs applies to a map" in capsys.readouterr().err
    argv = ["plan", room_map, "--start", "1", "3", "0", "--goal", "8", "3", "0", "--L", "1.0"]
    assert main([*argv, "--overhangs", "-0.1", "0"]) == 2
    assert "front_overhang must be >= 0" in capsys.readouterr().err


def test_cli_lists_a_body(tmp_path, capsys):
    sc = with_robot(segplan.load_scenario("turn_around"), front_overhang=0.3, rear_overhang=0.2)
    path = segplan.save_scenario(sc, tmp_path / "body.json")
    assert main(["draw", str(path), "--out", str(tmp_path / "b.png")]) == 0
    from segplan.cli import _floor_facts

    assert _floor_facts(sc)[2].endswith("overhangs 0.3 m front, 0.2 m rear")
    assert main(["plan", str(path)]) == 0
    assert "cost" in capsys.readouterr().out


def test_random_worlds_with_bodies_give_no_invalid_plan():
    """Random worlds (their start and goal kept clear of the body's axis segment), bodies of
    both shapes: every plan found, refined, is clear of the body at every centimetre."""
    plans = 0
    for seed in range(8):
        body = {
            "front_overhang": 0.1 + 0.06 * seed,
            "rear_overhang": 0.7 - 0.08 * seed,
            "rectangle": bool(seed % 2),
        }
        robot = segplan.Robot(1.2, 0.35, math.radians(40), **body)
        sc = segplan.random_world(seed, 12, (0, 0, 20, 12), robot=robot, radius=(0.5, 1.6))
        try:
            plan = segplan.plan_scenario(sc, refine=True)
        except segplan.NoPathError:
            continue
        plans += 1
        assert body_hits(robot, plan_poses(plan, 0.01), sc) == 0, seed
    assert plans >= 6


# -- saved plans, plan(), the shipped forklift ----------------------------------------------------
def test_saved_plans_keep_the_body_and_old_records_load(tmp_path, capsys):
    from segplan.planning.plan import Plan, plan_from_record, plan_record, saved_robot

    sc = segplan.load_scenario("forklift_aisle")
    plan = segplan.plan_scenario(sc)
    path = plan.save(tmp_path / "p.json", sc)
    record = json.loads(path.read_text())
    assert {k: record[k] for k in FOOTPRINT_KEYS} == {k: getattr(sc.robot, k) for k in FOOTPRINT_KEYS}
    assert Plan.load(path) == plan and saved_robot(path) == saved_robot(record) == sc.robot
    old = {k: v for k, v in plan_record(plan, sc).items() if k not in FOOTPRINT_KEYS}  # before footprints
    assert plan_from_record(old) == plan
    assert saved_robot(old) == replace(sc.robot, front_overhang=0.0, rear_overhang=0.0, rectangle=False)
    assert saved_robot(plan_record(plan)) is None  # saved without its floor: no robot
    with pytest.raises(ValueError, match="robot: front_overhang must be >= 0"):
        plan_from_record(record | {"front_overhang": -0.2})
    with pytest.raises(ValueError, match="robot: rectangle must be True or False"):
        saved_robot(record | {"rectangle": "yes"})
    assert main(["plan", "forklift_aisle", "--json"]) == 0  # --json: the body too, when there is one
    out = json.loads(capsys.readouterr().out)
    assert {k: out[k] for k in FOOTPRINT_KEYS} == {
        "front_overhang": 1.1,
        "rear_overhang": 0.5,
        "rectangle": True,
    }
    assert main(["plan", "turn_around", "--json"]) == 0
    assert not set(FOOTPRINT_KEYS) & set(json.loads(capsys.readouterr().out))


def test_plan_takes_the_body_at_the_door():
    sc = segplan.load_scenario("forklift_aisle")
    r = sc.robot
    args = (sc.start, sc.goal, sc.outlines, r.L, sc.bounds, r.half_width, r.max_steer)
    body = {"front_overhang": 1.1, "rear_overhang": 0.5, "rectangle": True}
    plan = segplan.plan(*args, **body)
    assert plan.nodes == segplan.plan_scenario(sc).nodes
    assert body_hits(r, plan_poses(plan, 0.01), sc) == 0
    with pytest.raises(ValueError, match="rear_overhang must be >= 0"):
        segplan.plan(*args, rear_overhang=-0.1)
    with pytest.raises(ValueError, match="rectangle must be True or False"):
        segplan.plan(*args, rectangle="no")
    with pytest.raises(segplan.ScenarioError, match="with overhangs"):  # the forks in the rack at the start
        segplan.plan((4.5, 6.3, math.pi / 2), *args[1:], front_overhang=1.1)


def test_the_forklift_needs_its_footprint():
    """The shipped forklift (forks 1.1 m ahead, counterweight 0.5 m behind, a rectangle): its
    plan is clear of the racks, the pillar and the walls at every centimetre; the plan made for
    the bare segment (same L, half_width, steering) drives the body into them."""
    sc = segplan.load_scenario("forklift_aisle")
    assert sc.robot.rectangle and sc.robot.axis == (-0.5, 1.4 + 1.1)
    plan = segplan.plan_scenario(sc)
    assert body_hits(sc.robot, plan_poses(plan, 0.01), sc) == 0
    bare = with_robot(sc, front_overhang=0.0, rear_overhang=0.0, rectangle=False)
    assert body_hits(sc.robot, plan_poses(segplan.plan_scenario(bare), 0.01), sc) > 0


def test_the_peers_validity_checks_the_body():
    """OMPL's state validity (``SegmentValidity``) and the study floors' pose test
    (``_FreeTest``) answer as ``Scenario.is_free`` on a robot with a body, and every pose they
    pass is clear of the body (the dense shapely oracle); the body closes poses the bare
    segment passes."""
    from segplan.studies.floors import _FreeTest
    from segplan.studies.ompl_runner import SegmentValidity

    sc = segplan.load_scenario("forklift_aisle")
    rng = np.random.default_rng(3)
    poses = rng.uniform((0.0, 0.0, -math.pi), (22.0, 12.0, math.pi), (2000, 3))
    for rectangle in (True, False):
        sc2 = with_robot(sc, rectangle=rectangle)
        check, free = SegmentValidity(sc2), _FreeTest(sc2.obstacles, sc2.bounds, sc2.robot)
        answers = [check(*p) for p in poses]
        assert answers == [sc2.is_free(p) for p in poses] == [free(tuple(p)) for p in poses]
        assert body_hits(sc2.robot, poses[np.array(answers)], sc2) == 0
    bare = SegmentValidity(with_robot(sc, front_overhang=0.0, rear_overhang=0.0, rectangle=False))
    assert sum(bare(*p) for p in poses) > sum(answers) > 200


def test_plan_drawings_show_the_body_at_the_robot_poses():
    """plot_plan / plot_union draw the footprint at every robot pose drawn, placed from the
    union's own rear and front points; for the paper's robot the drawing is unchanged (the same
    lines, no patch)."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon as PolygonPatch

    from segplan.viz import plot

    sc = segplan.load_scenario("forklift_aisle")
    plan = segplan.plan_scenario(sc)
    ax = plot.plot_plan(plan.unions, robots=3, robot=sc.robot)
    bodies = [p.get_xy()[:4] for p in ax.patches if isinstance(p, PolygonPatch)]
    assert len(bodies) == 3 * len(plan.unions)
    for u in plan.unions:
        for a, b in zip(u.rear(3), u.front(3), strict=True):
            th = math.atan2(b[1] - a[1], b[0] - a[0])
            c, s = math.cos(th), math.sin(th)
            expect = sc.robot.footprint() @ np.array([[c, s], [-s, c]]) + a
            assert any(np.allclose(q, expect, atol=1e-12) for q in bodies)
            assert shapely.Polygon(expect).distance(shapely.Point(a)) == 0  # A inside the body
    plt.close("all")
    paper = segplan.load_scenario("turn_around")
    unions = segplan.plan_scenario(paper).unions
    drawn = []
    for robot in (None, paper.robot):
        ax = plot.plot_plan(unions, robots=3, robot=robot)
        drawn.append(([ln.get_xydata().tolist() for ln in ax.lines], len(ax.patches)))
        plt.close("all")
    assert drawn[0] == drawn[1] and drawn[0][1] == 0
    with pytest.raises(ValueError, match="robot must be a segplan.Robot"):
        plot.plot_union(unions[0], robot="forklift")


# -- the rectangle swept exactly (segplan.floor.body) ---------------------------------------------
DOCK_WALLS = [[[9.5, 4.5], [12, 4.5], [12, 5.0], [9.5, 5.0]], [[9.5, 3.0], [12, 3.0], [12, 3.5], [9.5, 3.5]]]


@pytest.mark.parametrize("reverse", [False, True])
def test_the_rectangle_docks_where_the_round_ends_cannot(reverse):
    """Nose first into a charger bay, the front side 3 cm from the wall: the round-ended body
    cannot stand there (its cap reaches the wall); the rectangle is planned in, clear of the
    raw walls at every centimetre (both oracles: the test's and the metrics')."""
    body = {"front_overhang": 0.2, "rear_overhang": 0.3, "reverse": reverse}
    goal = (12 - 0.03 - 1.2, 4.0, 0.0)
    with pytest.raises(segplan.ScenarioError, match="out of bounds"):
        segplan.make_scenario(segplan.Robot(1.0, 0.4, **body), (2, 2, 1.0), goal, DOCK_WALLS, (0, 0, 12, 8))
    robot = segplan.Robot(1.0, 0.4, rectangle=True, **body)
    sc = segplan.make_scenario(robot, (2, 2, 1.0), goal, DOCK_WALLS, (0, 0, 12, 8))
    assert sc.body is not None and sc.body.depth == pytest.approx(0.4 + 0.0824 * 0.4 - 0.2, abs=1e-3)
    plan = segplan.plan_scenario(sc)
    poses = plan_poses(plan, 0.01)
    assert body_hits(robot, poses, sc) == 0
    m = measure_scenario_path(poses, sc)
    assert not m.collides and 0.0 < m.clearance < 0.03 + 0.01


def test_metrics_measure_the_rectangle_itself():
    """``measure_path(..., rectangle=w)``: collides and clearance of the rectangle against the
    raw obstacles and walls, as shapely measures the placed rectangles."""
    sc = with_robot(
        segplan.load_scenario("l_shaped_rack"), front_overhang=0.2, rear_overhang=0.1, rectangle=True
    )
    poses = plan_poses(segplan.plan_scenario(sc), 0.02)
    m = measure_scenario_path(poses, sc)
    r = sc.robot
    fp = r.footprint()
    c, s = np.cos(poses[:, 2])[:, None], np.sin(poses[:, 2])[:, None]
    xy = np.stack(
        (poses[:, :1] + c * fp[:, 0] - s * fp[:, 1], poses[:, 1:2] + s * fp[:, 0] + c * fp[:, 1]), -1
    )
    placed = shapely.polygons(xy)
    d = float(shapely.distance(placed, shapely.union_all([shapely.Polygon(o) for o in sc.outlines])).min())
    xmin, ymin, xmax, ymax = sc.bounds
    pts = xy.reshape(-1, 2)
    wall = min(
        (pts[:, 0] - xmin).min(), (xmax - pts[:, 0]).min(), (pts[:, 1] - ymin).min(), (ymax - pts[:, 1]).min()
    )
    assert m.clearance == pytest.approx(min(d, wall), abs=1e-12)
    assert not m.collides
    assert m.clearance > measure_scenario_path(poses, with_robot(sc, rectangle=False)).clearance - 1e-12


def test_rectangles_on_tight_random_worlds_give_no_invalid_plan():
    """Rectangles of many shapes, forward and reversing, on crowded random worlds: every plan is
    clear of the rectangle at every centimetre, and the rectangle solves at least what its
    round-ended hull solves."""
    plans = {True: 0, False: 0}
    for seed in range(10):
        kw = {"front_overhang": 0.05 * seed, "rear_overhang": 0.5 - 0.05 * seed, "reverse": bool(seed % 2)}
        for rectangle in (True, False):
            robot = segplan.Robot(1.0, 0.4, math.radians(40), rectangle=rectangle, **kw)
            sc = segplan.random_world(seed, 16, (0, 0, 16, 10), robot=robot, radius=(0.4, 1.2))
            try:
                plan = segplan.plan_scenario(sc, time_limit=20.0)
            except segplan.NoPathError:
                continue
            plans[rectangle] += 1
            assert body_hits(robot, plan_poses(plan, 0.01), sc) == 0, (seed, rectangle)
    assert plans[True] >= plans[False] >= 5
