"""Every option of ``segplan plan`` reaches the planner or the output (issue 24).

One test per argument of the ``plan`` sub-command, each showing that the option changes the
plan or what is printed or written; :data:`OPTION_TESTS` maps each argument (its argparse
``dest``) to its test, and :func:`test_every_option_has_a_test` reads the arguments from the
parser itself, so an option added without a test fails the suite. tests/test_cli.py covers
the command's messages and exit statuses; here each option is shown to *act*.

``main`` runs in-process on shipped floors (each call takes milliseconds); a spy on
``segplan.cli.plan_scenario`` records what the command handed the planner and what it got
back, where the printed output alone cannot show an option's effect.
"""

import json
import math
import sys

import numpy as np
import pytest

import segplan
import segplan.cli as cli
from segplan.cli import EXIT_BAD_INPUT, EXIT_NO_PATH, build_parser, main
from segplan.floor.scenario import load_scenario, with_clearance
from segplan.planning.trajectory import POSE_COLUMNS, TRAJECTORY_COLUMNS
from segplan.viz.metrics import measure_scenario_path, plan_poses

#: Each argument of ``segplan plan`` (argparse ``dest``) and the test that shows it acts.
OPTION_TESTS = {
    "scenario": "test_scenario_argument_picks_the_floor",
    "planner": "test_planner_paper_vs_lattice",
    "reverse": "test_reverse_lets_the_robot_back_up",
    "clearance": "test_clearance_moves_the_plan_away_from_obstacles",
    "heuristic": "test_heuristic_changes_the_search",
    "cost": "test_cost_changes_the_search",
    "node_frames": "test_node_frames_change_the_plan",
    "refine": "test_refine_and_no_refine",
    "out": "test_out_draws_the_plan_found",
    "animate": "test_animate_writes_a_gif",
    "frames": "test_animation_options_make_the_gif",
    "fps": "test_animation_options_make_the_gif",
    "dpi": "test_animation_options_make_the_gif",
    "json": "test_json_output_fields",
    "progress": "test_progress_shows_the_stages_on_stderr_and_changes_nothing",
    "max_expansions": "test_max_expansions_limits_every_search",
    "time_limit": "test_time_limit_fails_with_reason_time",
    # a ROS map as SCENARIO (issue 27)
    "start": "test_map_start_and_goal_are_the_plans_ends",
    "goal": "test_map_start_and_goal_are_the_plans_ends",
    "L": "test_map_robot_options_make_the_robot",
    "half_width": "test_map_robot_options_make_the_robot",
    "max_steer_deg": "test_map_robot_options_make_the_robot",
    "unknown_free": "test_map_unknown_free_opens_the_unknown_cells",
    "overhangs": "test_map_body_options_make_the_body",
    "rectangle": "test_map_body_options_make_the_body",
}


def _plan_actions():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")  # the sub-parsers action
    return [a for a in sub.choices["plan"]._actions if a.dest != "help"]


def test_every_option_has_a_test():
    dests = {a.dest for a in _plan_actions()}
    assert dests == set(OPTION_TESTS), (
        f"options without a test: {sorted(dests - set(OPTION_TESTS))}; "
        f"tests of options that no longer exist: {sorted(set(OPTION_TESTS) - dests)}"
    )
    module = sys.modules[__name__]
    for name in OPTION_TESTS.values():
        assert callable(getattr(module, name, None)), name


@pytest.fixture
def spy(monkeypatch):
    """Records the keyword arguments ``main`` hands ``plan_scenario`` and the plans returned."""
    calls = []

    def recording(scenario, **kwargs):
        call = {"scenario": scenario, **kwargs}
        calls.append(call)
        call["plan"] = plan = segplan.plan_scenario(scenario, **kwargs)
        return plan

    monkeypatch.setattr(cli, "plan_scenario", recording)
    return calls


def run_json(capsys, *args):
    """``segplan plan ARGS --json``: the exit status and the parsed JSON object."""
    status = main(["plan", *args, "--json"])
    out = capsys.readouterr().out
    return status, (json.loads(out) if out.strip() else None)


def test_scenario_argument_picks_the_floor(capsys):
    status, by_name = run_json(capsys, "single_obstacle", "--planner", "paper")
    assert status == 0 and by_name["scenario"] == "single_obstacle"
    sc = load_scenario("single_obstacle")
    assert by_name["nodes"][0][:2] == [sc.start.x, sc.start.y]
    _, other = run_json(capsys, "turn_around", "--planner", "paper")
    assert other["scenario"] == "turn_around" and other["cost"] != by_name["cost"]


def test_planner_paper_vs_lattice(capsys, spy):
    status, paper = run_json(capsys, "turn_around", "--planner", "paper")
    assert status == 0 and paper["version"] == "b" and paper["heuristic"] == "a"
    status, lattice = run_json(capsys, "turn_around", "--planner", "lattice")
    assert status == 0 and lattice["version"] == "lattice" and lattice["heuristic"] == "dubins"
    assert lattice["cost"] < 0.5 * paper["cost"]  # the lattice turns in the room; the paper's goes round
    assert [c["planner"] for c in spy] == ["paper", "lattice"]


def test_clearance_moves_the_plan_away_from_obstacles(capsys, spy):
    margin = 0.3
    status, plain = run_json(capsys, "fig5_example1")
    assert status == 0
    status, safe = run_json(capsys, "fig5_example1", "--clearance", str(margin))
    assert status == 0 and safe["cost"] > plain["cost"] and safe["nodes"] != plain["nodes"]
    assert [c["clearance"] for c in spy] == [0.0, margin]
    # the plan found keeps the margin: measured on the floor enlarged by half_width + margin
    sc = load_scenario("fig5_example1")
    poses = plan_poses(spy[1]["plan"], step=0.01)
    assert not measure_scenario_path(poses, with_clearance(sc, margin)).collides
    assert not measure_scenario_path(plan_poses(spy[0]["plan"]), sc).collides
    assert measure_scenario_path(poses, sc).clearance > 0.9 * margin
    # a margin the goal cannot keep is refused, not ignored
    assert main(["plan", "single_obstacle", "--clearance", str(margin)]) == EXIT_BAD_INPUT
    assert "clearance" in capsys.readouterr().err


def test_heuristic_changes_the_search(capsys, spy):
    runs = {h: run_json(capsys, "turn_around", "--planner", "paper", "--heuristic", h)[1] for h in "abc"}
    assert [runs[h]["heuristic"] for h in "abc"] == ["a", "b", "c"]
    assert [c["heuristic"] for c in spy] == ["a", "b", "c"]
    expanded = {h: runs[h]["expanded"] for h in "abc"}
    assert len(set(expanded.values())) == 3, expanded  # three searches, three orders of expansion
    assert runs["b"]["cost"] != runs["a"]["cost"]
    # within the default planner, h' steers its first stage (the paper's search)
    _, a = run_json(capsys, "fig5_example1", "--heuristic", "a", "--no-refine")
    _, b = run_json(capsys, "fig5_example1", "--heuristic", "b", "--no-refine")
    assert (a["heuristic"], b["heuristic"]) == ("a", "b") and a["expanded"] != b["expanded"]


def test_cost_changes_the_search(capsys, spy):
    _, longd = run_json(capsys, "turn_around", "--planner", "paper", "--cost", "longd")
    _, dist = run_json(capsys, "turn_around", "--planner", "paper", "--cost", "distance")
    assert (longd["cost_kind"], dist["cost_kind"]) == ("longd", "distance")
    assert dist["expanded"] != longd["expanded"]
    assert dist["search_cost"] != longd["search_cost"]  # g by distance, the printed cost LONGD
    assert [c["cost"] for c in spy] == ["longd", "distance"]


def test_node_frames_change_the_plan(capsys, spy):
    _, b = run_json(capsys, "single_obstacle", "--planner", "paper", "--node-frames", "b")
    _, a = run_json(capsys, "single_obstacle", "--planner", "paper", "--node-frames", "a")
    assert (a["version"], b["version"]) == ("a", "b")
    assert a["cost"] != b["cost"] and a["alphas_deg"] != b["alphas_deg"]
    # on Fig. 5 one shared frame (Fig. 4 a) leaves the paper's search without a path
    status, failed = run_json(capsys, "fig5_example1", "--planner", "paper", "--node-frames", "a")
    assert status == EXIT_NO_PATH and failed["found"] is False
    assert [c["version"] for c in spy] == ["b", "a", "a"]


def test_refine_and_no_refine(capsys, spy):
    _, default = run_json(capsys, "fig5_example1")
    _, off = run_json(capsys, "fig5_example1", "--no-refine")
    _, on = run_json(capsys, "fig5_example1", "--planner", "paper", "--refine")
    _, paper = run_json(capsys, "fig5_example1", "--planner", "paper")
    assert default["refinement"] is not None and off["refinement"] is None  # lattice: on by default
    assert default["cost"] < off["cost"] and "refined" in default["kinds"]
    assert on["refinement"] is not None and paper["refinement"] is None  # paper: off by default
    assert on["cost"] < paper["cost"]
    assert [c["refine"] for c in spy] == [None, False, True, None]


def test_out_draws_the_plan_found(tmp_path, capsys):
    pngs = {}
    for planner in ("paper", "lattice"):
        pngs[planner] = tmp_path / f"{planner}.png"
        assert main(["plan", "turn_around", "--planner", planner, "--out", str(pngs[planner])]) == 0
        assert f"figure      {pngs[planner]}" in capsys.readouterr().out
    data = {k: p.read_bytes() for k, p in pngs.items()}
    assert all(d[:8] == b"\x89PNG\r\n\x1a\n" and len(d) > 1000 for d in data.values())
    assert data["paper"] != data["lattice"]  # the figure shows the plan, not only the floor
    assert main(["plan", "turn_around", "--planner", "paper"]) == 0
    assert "figure" not in capsys.readouterr().out
    assert sorted(p.name for p in tmp_path.iterdir()) == ["lattice.png", "paper.png"]


def test_animate_writes_a_gif(tmp_path, capsys):
    from PIL import Image

    gif = tmp_path / "plan.gif"
    assert main(["plan", "single_obstacle", "--planner", "paper", "--animate", str(gif)]) == 0
    assert f"animation   {gif}" in capsys.readouterr().out
    assert gif.read_bytes()[:6] == b"GIF89a"
    with Image.open(gif) as im:
        assert im.n_frames > 1


def test_animation_options_make_the_gif(tmp_path, capsys):
    """--frames, --fps and --dpi: the GIF's frame count, delay and width."""
    from PIL import Image

    from segplan.viz import animate

    sizes = {}
    for frames, fps, dpi in ((5, 20, 80), (7, 4, 100)):
        gif = tmp_path / f"plan{frames}.gif"
        argv = ["plan", "turn_around", "--animate", str(gif), "--frames", str(frames)]
        assert main([*argv, "--fps", str(fps), "--dpi", str(dpi)]) == 0
        with Image.open(gif) as im:
            assert im.n_frames == frames and im.info["duration"] == 1000 / fps
            sizes[dpi] = im.size
    assert sizes[80] == (round(animate.FIGSIZE[0] * 80), round(animate.FIGSIZE[1] * 80))
    assert sizes[100][0] == round(animate.FIGSIZE[0] * 100) >= 600
    capsys.readouterr()


@pytest.mark.parametrize(
    "args, message",
    [
        (["--frames", "1"], "--frames must be an integer >= 2, got 1"),
        (["--fps", "0"], "--fps must be an integer from 1 to 50, got 0"),
        (["--fps", "60"], "--fps must be an integer from 1 to 50, got 60"),
        (["--dpi", "5"], "--dpi must lie from 20 to 300, got 5"),
        (["--dpi", "nan"], "--dpi must be finite"),
        (["--frames", "x"], "argument --frames: expected a whole number, got 'x'"),
        (["--frames", "a"], "--node-frames a|b"),
        (["--fps", "2.5"], "argument --fps: invalid int value"),
    ],
)
def test_bad_animation_options_are_one_line_before_planning(tmp_path, capsys, monkeypatch, args, message):
    def no_planning(*args, **kwargs):
        raise AssertionError("planned before refusing the animation options")

    monkeypatch.setattr(cli, "plan_scenario", no_planning)
    gif = tmp_path / "plan.gif"
    try:
        status = main(["plan", "turn_around", "--animate", str(gif), *args])
    except SystemExit as exit:  # argparse's own errors (not a whole number)
        status = exit.code
    assert status == EXIT_BAD_INPUT
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and message in err[0] and "Traceback" not in err[0], err
    assert not gif.exists()


def test_animation_options_need_an_animation(capsys, monkeypatch):
    monkeypatch.setattr(cli, "plan_scenario", None)  # never reached
    assert main(["plan", "turn_around", "--fps", "5"]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert err == "segplan: error: --fps applies to --animate, and no animation is asked for\n"


def test_json_output_fields(capsys):
    status, data = run_json(capsys, "fig5_example1", "--planner", "paper")
    assert status == 0
    expected = set(segplan.plan_scenario(load_scenario("fig5_example1"), planner="paper").to_dict())
    assert set(data) == {"scenario", "found", "plan_facts"} | expected  # plan_facts: the CLI's (issue 27)
    assert data["found"] is True and data["scenario"] == "fig5_example1"
    assert data["planner"] == "paper" and data["options"]["max_expansions"] == 3000  # what made it
    assert len(data["nodes"]) == len(data["kinds"]) == len(data["alphas_deg"]) + 1
    assert data["nodes"][-1] == [28.0, 12.9, 0.0]
    # a failure is a JSON object too, with the reason
    status, failed = run_json(capsys, "fig5_example1", "--max-expansions", "1")
    assert status == EXIT_NO_PATH
    assert failed["found"] is False and failed["reason"] == "expansions"
    assert {"message", "expanded", "generated", "seconds"} <= set(failed)
    # without --json the output is the text table, not JSON
    assert main(["plan", "fig5_example1", "--planner", "paper"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("scenario    fig5_example1") and "cost        " in text


def test_progress_shows_the_stages_on_stderr_and_changes_nothing(capsys):
    assert main(["plan", "turn_around", "--json"]) == 0
    quiet = json.loads(capsys.readouterr().out)
    assert main(["plan", "turn_around", "--json", "--progress"]) == 0
    captured = capsys.readouterr()
    shown = json.loads(captured.out)
    assert shown["nodes"] == quiet["nodes"] and shown["cost"] == quiet["cost"]
    lines = captured.err.splitlines()  # not a terminal: plain lines, one per stage's start and end
    stages = [line.split("  ")[-1].split(":")[0] for line in lines if "started" in line]
    assert stages == ["paper", "lattice", "refine"] or stages == ["paper", "refine"], lines
    assert all(line.startswith("segplan: ") and " s of 10 " in line for line in lines)
    assert f"LONGD {quiet['cost']:.3f} m" in lines[-1]


@pytest.mark.parametrize(
    "scenario, planner",
    [("fig5_example1", "paper"), ("fig6_example2", "lattice"), ("turn_around", "lattice")],
)
def test_max_expansions_limits_every_search(capsys, scenario, planner):
    status, ok = run_json(capsys, scenario, "--planner", planner)
    assert status == 0 and ok["expanded"] > 5
    status, failed = run_json(capsys, scenario, "--planner", planner, "--max-expansions", "5")
    assert status == EXIT_NO_PATH
    assert failed["reason"] == "expansions" and failed["expanded"] == 5
    assert "max_expansions=5" in failed["message"]


@pytest.mark.parametrize(
    "scenario, planner",
    [("fig5_example1", "paper"), ("fig6_example2", "lattice"), ("turn_around", "lattice")],
)
def test_time_limit_fails_with_reason_time(capsys, scenario, planner):
    status, failed = run_json(capsys, scenario, "--planner", planner, "--time-limit", "1e-6")
    assert status == EXIT_NO_PATH
    assert failed["found"] is False and failed["reason"] == "time"
    status, _ = run_json(capsys, scenario, "--planner", planner, "--time-limit", "10")
    assert status == 0


def test_time_limit_bounds_the_refinement(capsys, monkeypatch):
    """A slow refinement (each of its link costs made 50 ms slower) stops at the deadline (issue 24)."""
    import time

    refine_module = sys.modules["segplan.planning.refine"]
    gauss = refine_module.longd_gauss_intrinsic

    def slow(*args, **kwargs):
        time.sleep(0.05)
        return gauss(*args, **kwargs)

    monkeypatch.setattr(refine_module, "longd_gauss_intrinsic", slow)
    limit = 0.3  # the search takes about 10 ms; the slowed refinement about 24 x 50 ms
    status, data = run_json(capsys, "single_obstacle", "--time-limit", str(limit))
    if status == EXIT_NO_PATH:
        assert data["reason"] == "time"
    else:
        assert status == 0 and data["seconds"] <= limit + 0.2, data["seconds"]
        assert data["refinement"]["stopped"] is True


def test_time_limit_message_names_the_users_limit(capsys):
    """The default planner's time-out names the limit given, not the lattice's share of it."""
    status, failed = run_json(capsys, "fig6_example2", "--time-limit", "1e-6")
    assert status == EXIT_NO_PATH and failed["reason"] == "time"
    assert "time_limit=1e-06" in failed["message"], failed["message"]


# -- trajectories out (issue 27): the options of --poses and --trajectory --------------------------
OPTION_TESTS.update(
    {
        "poses": "test_poses_writes_the_samples",
        "trajectory": "test_trajectory_writes_the_time_law_and_prints_its_time",
        "step": "test_step_sets_the_spacing",
        "v_max": "test_v_max_caps_the_speed",
        "a_max": "test_a_max_caps_the_acceleration",
        "a_lat_max": "test_a_lat_max_caps_the_lateral_acceleration",
        "steer_rate_max": "test_steer_rate_max_sets_the_re_steering_time",
        "nav_path": "test_nav_path_writes_the_time_laws_poses_stamped",
    }
)


def _law(capsys, tmp_path, *args):
    """``segplan plan fig5_example1 --trajectory FILE ARGS --json``: the JSON and the CSV table."""
    path = tmp_path / "law.csv"
    status, data = run_json(capsys, "fig5_example1", "--trajectory", str(path), *args)
    assert status == 0
    return data, np.genfromtxt(path, delimiter=",", names=True)


def test_poses_writes_the_samples(capsys, tmp_path):
    path = tmp_path / "poses.csv"
    status, data = run_json(capsys, "fig5_example1", "--poses", str(path))
    table = np.genfromtxt(path, delimiter=",", names=True)
    assert status == 0 and table.dtype.names == POSE_COLUMNS
    assert data["poses"]["samples"] == table.size and "trajectory" not in data
    assert np.all(np.diff(table["s"]) <= 0.05 + 1e-12)


def test_trajectory_writes_the_time_law_and_prints_its_time(capsys, tmp_path):
    data, table = _law(capsys, tmp_path)
    assert table.dtype.names == TRAJECTORY_COLUMNS
    law = data["trajectory"]
    assert (
        law["total_time"] == table["t"][-1] and 0 < law["dwell_time"] < law["jump_time"] < law["total_time"]
    )
    assert main(["plan", "fig5_example1", "--trajectory", str(tmp_path / "b.csv")]) == 0
    out = capsys.readouterr().out
    assert f"{law['total_time']:.2f} s from rest to rest, of which {law['jump_time']:.2f} s" in out


def test_step_sets_the_spacing(capsys, tmp_path):
    coarse, fine = (_law(capsys, tmp_path, "--step", step)[1] for step in ("0.2", "0.02"))
    assert fine.size > 5 * coarse.size
    assert np.diff(fine["s"]).max() <= 0.02 + 1e-12 < np.diff(coarse["s"]).max() <= 0.2 + 1e-12


def test_v_max_caps_the_speed(capsys, tmp_path):
    slow, table = _law(capsys, tmp_path, "--v-max", "0.3")
    fast, _ = _law(capsys, tmp_path, "--v-max", "2")
    assert table["v"].max() <= 0.3 * (1 + 1e-12) and slow["trajectory"]["limits"]["v_max"] == 0.3
    assert slow["trajectory"]["total_time"] > fast["trajectory"]["total_time"]


def test_a_max_caps_the_acceleration(capsys, tmp_path):
    data, table = _law(capsys, tmp_path, "--a-max", "0.1")
    assert np.abs(table["a"]).max() <= 0.1 * (1 + 1e-9) and data["trajectory"]["limits"]["a_max"] == 0.1


def test_a_lat_max_caps_the_lateral_acceleration(capsys, tmp_path):
    _, table = _law(capsys, tmp_path, "--a-lat-max", "0.05", "--v-max", "5")
    assert np.max(table["v"] ** 2 * np.abs(table["kappa"])) <= 0.05 * (1 + 1e-9)
    _, loose = _law(capsys, tmp_path, "--a-lat-max", "5", "--v-max", "5")
    assert np.max(loose["v"] ** 2 * np.abs(loose["kappa"])) > 0.05


def test_steer_rate_max_sets_the_re_steering_time(capsys, tmp_path):
    """Re-steering standing takes sum |jump| / rate: half the rate, twice the dwell."""
    quick, _ = _law(capsys, tmp_path, "--steer-rate-max", "60")
    slow, _ = _law(capsys, tmp_path, "--steer-rate-max", "30")
    assert slow["trajectory"]["dwell_time"] == pytest.approx(2 * quick["trajectory"]["dwell_time"], rel=1e-12)
    assert slow["trajectory"]["limits"]["steer_rate_max_deg"] == 30


@pytest.mark.parametrize("suffix", [".yaml", ".json"])
def test_nav_path_writes_the_time_laws_poses_stamped(capsys, tmp_path, suffix):
    """The file is segplan.planning.export.nav_path of the --trajectory table's poses and times
    (frame 'map'), as YAML or JSON; without --trajectory the same law stamps it."""
    import yaml

    from segplan.planning.export import nav_path

    path = tmp_path / f"path{suffix}"
    data, table = _law(capsys, tmp_path, "--nav-path", str(path), "--v-max", "0.8")
    message = yaml.safe_load(path.read_text()) if suffix == ".yaml" else json.loads(path.read_text())
    assert message == nav_path(table["x"], table["y"], table["theta"], table["t"], frame_id="map")
    assert data["nav_path"] == {
        "file": str(path), "poses": len(message["poses"]), "frame_id": "map",
        "total_time": data["trajectory"]["total_time"],
    }  # fmt: skip
    last = message["poses"][-1]["header"]["stamp"]
    assert last["sec"] + 1e-9 * last["nanosec"] == pytest.approx(table["t"][-1], abs=1e-9)
    alone = tmp_path / f"alone{suffix}"
    status, only = run_json(capsys, "fig5_example1", "--nav-path", str(alone), "--v-max", "0.8")
    assert status == 0 and "trajectory" not in only and alone.read_bytes() == path.read_bytes()
    assert main(["plan", "fig5_example1", "--nav-path", str(alone)]) == 0
    assert f"nav path    {alone} ({len(message['poses'])} poses in frame 'map'" in capsys.readouterr().out


def test_reverse_lets_the_robot_back_up(capsys, spy):
    status, _ = run_json(capsys, "single_obstacle", "--planner", "paper")
    assert status == 0 and spy[-1]["scenario"].robot.reverse is False
    status, _ = run_json(capsys, "single_obstacle", "--planner", "paper", "--reverse")
    assert status == 0 and spy[-1]["scenario"].robot.reverse is True


# -- a ROS map as SCENARIO (issue 27) ------------------------------------------------------
MAP_POSES = ["--start", "1", "1", "0", "--goal", "8.5", "4", "90"]


def test_map_start_and_goal_are_the_plans_ends(capsys, room_map):
    status, data = run_json(capsys, room_map, *MAP_POSES, "--L", "0.8", "--unknown-free")
    assert status == 0 and data["found"] is True
    assert data["nodes"][0] == [1.0, 1.0, 0.0]
    assert data["nodes"][-1] == pytest.approx([8.5, 4.0, 90.0])


def test_map_robot_options_make_the_robot(capsys, spy, room_map):
    robot = ["--L", "0.9", "--half-width", "0.25", "--max-steer-deg", "30", "--unknown-free"]
    status, _ = run_json(capsys, room_map, *MAP_POSES, *robot)
    assert status == 0
    r = spy[-1]["scenario"].robot
    assert (r.L, r.half_width) == (0.9, 0.25) and r.max_steer == pytest.approx(math.radians(30))
    status, _ = run_json(capsys, room_map, *MAP_POSES, "--L", "0.9", "--unknown-free")
    r = spy[-1]["scenario"].robot
    assert status == 0 and (r.half_width, r.max_steer) == (0.0, pytest.approx(math.radians(45)))


def test_map_body_options_make_the_body(capsys, spy, room_map):
    robot = [
        "--L",
        "0.9",
        "--half-width",
        "0.25",
        "--overhangs",
        "0.3",
        "0.2",
        "--rectangle",
        "--unknown-free",
    ]
    status, _ = run_json(capsys, room_map, *MAP_POSES, *robot)
    r = spy[-1]["scenario"].robot
    assert status == 0 and (r.front_overhang, r.rear_overhang, r.rectangle) == (0.3, 0.2, True)
    status, _ = run_json(capsys, room_map, *MAP_POSES, "--L", "0.9", "--unknown-free")
    r = spy[-1]["scenario"].robot
    assert status == 0 and (r.front_overhang, r.rear_overhang, r.rectangle) == (0.0, 0.0, False)


def test_map_unknown_free_opens_the_unknown_cells(capsys, room_map):
    status, _ = run_json(capsys, room_map, *MAP_POSES, "--L", "0.8")  # the unknown block is a wall
    assert status == EXIT_NO_PATH
    status, data = run_json(capsys, room_map, *MAP_POSES, "--L", "0.8", "--unknown-free")
    assert status == 0 and data["found"] is True
