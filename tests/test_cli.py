"""The ``segplan`` command line (issue 3): ``segplan plan SCENARIO.json ...``."""

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from segplan.cli import EXIT_BAD_INPUT, EXIT_NO_PATH, main

SCENARIOS = Path(__file__).resolve().parent.parent / "scenarios"
SINGLE = str(SCENARIOS / "single_obstacle.json")


def test_plan_prints_cost_nodes_expansions_time(capsys):
    assert main(["plan", SINGLE]) == 0
    out = capsys.readouterr().out
    for word in ("cost", "nodes", "expansions", "time", "start", "goal"):
        assert word in out
    assert "planner     lattice" in out  # the plan says which planner made it


def test_plan_json(capsys):
    assert main(["plan", SINGLE, "--json", "--heuristic", "c", "--planner", "paper"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["found"] is True and data["heuristic"] == "c"
    assert data["planner"] == "paper" and data["options"]["heuristic"] == "c"  # what made the plan
    assert data["cost"] > 0 and data["expanded"] >= 1
    assert data["nodes"][0] == [*json.loads((SCENARIOS / "single_obstacle.json").read_text())["start"]]


def test_plan_refine(capsys):
    assert main(["plan", SINGLE, "--json", "--planner", "paper"]) == 0
    found = json.loads(capsys.readouterr().out)
    assert found["refinement"] is None
    assert main(["plan", SINGLE, "--json", "--refine", "--planner", "paper"]) == 0
    refined = json.loads(capsys.readouterr().out)
    r = refined["refinement"]
    assert r["cost_before"] == pytest.approx(found["cost"]) and r["cost_after"] == refined["cost"]
    assert refined["cost"] <= found["cost"] and "refined" in refined["kinds"]
    assert main(["plan", SINGLE, "--refine"]) == 0
    assert "refined     LONGD" in capsys.readouterr().out


def test_plan_draws_figure(tmp_path, capsys):
    out = tmp_path / "plan.png"
    assert main(["plan", SINGLE, "--out", str(out), "--cost", "distance", "--node-frames", "a"]) == 0
    assert out.stat().st_size > 1000
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_bad_file_is_a_clear_error(tmp_path, capsys):
    assert main(["plan", str(tmp_path / "missing.json")]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert "missing.json" in err and "Traceback" not in err
    bad = tmp_path / "bad.json"
    bad.write_text('{"L": 1.0, "start": [0, 0, 0], "goal": [5, 0, 0], "obstacles": [[[0, 0], [1, 1]]]}')
    assert main(["plan", str(bad)]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert "obstacles[0]" in err and "Traceback" not in err


def test_no_path_exit_status(tmp_path, capsys):
    walled = tmp_path / "walled.json"
    walled.write_text(
        json.dumps(
            {
                "L": 1.0,
                "start": [1, 3, 0],
                "goal": [8, 3, 0],
                "bounds": [0, 0, 10, 6],
                "obstacles": [[[4, 0.2], [5, 0.2], [5, 5.8], [4, 5.8]]],
            }
        )
    )
    out_png = tmp_path / "partial.png"
    assert main(["plan", str(walled), "--max-expansions", "50", "--out", str(out_png)]) == EXIT_NO_PATH
    err = capsys.readouterr().err
    assert "no path" in err and "Traceback" not in err
    assert out_png.exists()


def test_bad_option_values(capsys):
    with pytest.raises(SystemExit) as info:
        main(["plan", SINGLE, "--heuristic", "z"])
    assert info.value.code == EXIT_BAD_INPUT
    assert main(["plan", SINGLE, "--max-expansions", "0"]) == EXIT_BAD_INPUT
    assert "max_expansions" in capsys.readouterr().err


def test_help_explains_everything(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--help"])
    assert info.value.code == 0
    assert "plan" in capsys.readouterr().out
    with pytest.raises(SystemExit) as info:
        main(["plan", "--help"])
    assert info.value.code == 0
    text = capsys.readouterr().out
    for word in ("--heuristic", "--out", "--json", "LONGD", "exit status", "degrees"):
        assert word in text
    assert main([]) == EXIT_BAD_INPUT  # no command: help and a non-zero status


def test_console_script_entry_point():
    """The installed ``segplan`` script runs main() and exits with its status, no traceback.

    One start-up only: a plan through a console script is run by
    test_package::test_wheel_installs_in_a_clean_venv_and_plans (the wheel's script) and
    ``python -m segplan`` by test_package::test_python_dash_m_segplan; main()'s output is
    checked in-process above."""
    exe = shutil.which("segplan", path=str(Path(sys.executable).parent))
    cmd = [exe] if exe else [sys.executable, "-m", "segplan.cli"]
    run = subprocess.run([*cmd, "plan", "no/such/file.json"], capture_output=True, text=True, timeout=120)
    assert run.returncode == EXIT_BAD_INPUT
    assert "Traceback" not in run.stderr and "no/such/file.json" in run.stderr


# -- command-line hygiene (issue 27) ------------------------------------------------------------
@pytest.mark.parametrize(
    ("option", "name", "kinds"),
    [
        ("--out", "p.txt", ".png"),
        ("--animate", "p.mp4", ".gif, .html"),
        ("--animate", "p.png", ".gif"),
        ("--nav-path", "p.csv", ".yaml, .yml, .json"),
    ],
)
def test_a_wrong_output_type_is_one_line_before_planning(tmp_path, capsys, monkeypatch, option, name, kinds):
    """Before: a traceback and exit 1 (the "no path" code) after planning; --animate x.png wrote
    one frame. Now: one line, exit 2, and no planning."""
    import segplan.cli as cli

    def no_planning(*args, **kwargs):
        raise AssertionError("planned before refusing the output file")

    monkeypatch.setattr(cli, "plan_scenario", no_planning)
    assert main(["plan", SINGLE, option, str(tmp_path / name)]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"segplan: error: {option} ") and kinds in err[0]
    assert not (tmp_path / name).exists()


def test_an_animation_as_an_html_page(tmp_path, capsys):
    page = tmp_path / "plan.html"
    assert main(["plan", SINGLE, "--animate", str(page)]) == 0
    text = page.read_text(encoding="utf-8")
    assert "<script" in text and "data:image/png;base64" in text
    assert "<link" not in text and "http" not in text  # plays offline (segplan.viz.animate.to_html)


def test_ctrl_c_is_one_line_and_exit_130(capsys, monkeypatch):
    import segplan.cli as cli

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "plan_scenario", interrupted)
    assert main(["plan", SINGLE]) == cli.EXIT_INTERRUPTED == 130
    assert capsys.readouterr().err == "segplan: interrupted\n"


def test_a_closed_pipe_ends_quietly():
    """``segplan plan X | head -1``: before, a BrokenPipeError traceback."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "segplan", "plan", SINGLE, "--json"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        bufsize=0,
    )
    first = proc.stdout.read(1)  # the reader takes one byte and goes away
    proc.stdout.close()
    err = proc.stderr.read().decode()
    proc.wait(timeout=120)
    assert first == b"{"
    assert proc.returncode in (0, 141) and "Traceback" not in err and "BrokenPipe" not in err, err


def test_the_figure_title_names_the_planner(monkeypatch, tmp_path):
    import segplan.cli as cli

    titles = []
    monkeypatch.setattr(cli, "_draw", lambda path, scenario, unions, title, *_: titles.append(title))
    assert main(["plan", "turn_around", "--out", str(tmp_path / "a.png")]) == 0
    assert main(["plan", "turn_around", "--planner", "paper", "--out", str(tmp_path / "b.png")]) == 0
    assert "default planner (lattice)" in titles[0] and "the paper's search, heuristic a" in titles[1]


def test_the_output_says_what_the_plan_is(capsys):
    """Issue 27: which planner made it, both path lengths, the clearance, the curvature against
    the limit and the steering jumps, in the text and under --json (checked against the plan's
    own facts and the dense path measure)."""
    import segplan

    assert main(["plan", "fig5_example1", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    facts = data["plan_facts"]
    sc = segplan.load_scenario("fig5_example1")
    plan = segplan.plan_scenario(sc)
    assert facts["front_length"] == pytest.approx(plan.cost, rel=1e-8)  # LONGD, [1]
    measured = segplan.measure_scenario_path(segplan.plan_poses(plan, 0.01), sc)
    assert facts["rear_length"] == pytest.approx(measured.rear_length, rel=1e-3)
    assert facts["clearance"] == pytest.approx(measured.clearance, abs=1e-9) and facts["clearance"] >= 0
    assert facts["within_limit"] is True and facts["max_curvature"] <= facts["curvature_limit"]
    assert len(facts["steering_jumps_deg"]) == len(plan.nodes) - 2
    assert "the default planner" in facts["made_by"]
    assert main(["plan", "fig5_example1"]) == 0
    out = capsys.readouterr().out
    heads = ("made by", "paths       front wheel", "clearance", "curvature   at most", "steering    jumps")
    for head in heads:
        assert head in out, head


def test_the_figure_legend_names_every_path_beside_the_floor(monkeypatch, tmp_path):
    """--out: the rear path A and the dashed front-wheel path B each have a legend entry, and
    the legend lies right of the axes, where it cannot cover the floor."""
    from segplan.viz import plot

    figures = []
    real = plot.plan_figure
    monkeypatch.setattr(plot, "plan_figure", lambda *args: figures.append(real(*args)) or figures[-1])
    assert main(["plan", "single_obstacle", "--out", str(tmp_path / "plan.png")]) == 0
    ax = figures[0].axes[0]
    legend = ax.get_legend()
    texts = [t.get_text() for t in legend.get_texts()]
    assert texts == ["enlarged obstacle", "obstacle", "rear path A", "front-wheel path B", "start", "goal"]
    front = next(line for line in ax.lines if line.get_label() == "front-wheel path B")
    assert front.get_linestyle() == "--"
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(figures[0]).draw()  # the figure was saved and closed: lay it out again
    assert legend.get_window_extent().x0 >= ax.get_window_extent().x1


def test_importing_the_command_loads_no_matplotlib():
    """The animation options are checked before planning without loading matplotlib, so
    ``segplan plan`` without a figure starts as fast as before."""
    code = "import sys, segplan.cli; assert 'matplotlib' not in sys.modules, 'matplotlib loaded'"
    subprocess.run([sys.executable, "-c", code], check=True, timeout=120)


# -- segplan scenarios and segplan draw (issue 27) ------------------------------------------------
def test_scenarios_lists_every_shipped_floor_in_one_line(capsys):
    import segplan

    assert main(["scenarios"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split() == ["name", "floor", "obstacles", "robot"]
    names = segplan.shipped_scenarios()
    assert [line.split()[0] for line in lines[1:]] == list(names)
    rows = dict(zip(names, lines[1:], strict=True))
    assert (
        "30 x 20 m  10 obstacles" in rows["fig5_example1"]
        and "L 1.2 m, half-width 0.35 m" in rows["fig5_example1"]
    )
    assert "3 obstacles (6 convex pieces)" in rows["l_shaped_rack"]  # beyond_the_paper/ too


def test_scenarios_exports_one_to_edit_and_plan(tmp_path, capsys):
    import segplan

    mine = tmp_path / "mine.json"
    assert main(["scenarios", "turn_around", "--export", str(mine)]) == 0
    assert str(mine) in capsys.readouterr().out
    shipped, copy = segplan.load_scenario("turn_around"), segplan.load_scenario(mine)
    assert copy.to_dict() == shipped.to_dict()
    assert main(["scenarios", "turn_around"]) == 0  # the same file on stdout
    assert capsys.readouterr().out == mine.read_text()
    mine.write_text(mine.read_text().replace('"goal": [3.0, 6.5, 180.0]', '"goal": [9.0, 6.5, 90.0]'))
    assert main(["plan", str(mine), "--json"]) == 0  # edited, and planned on
    assert json.loads(capsys.readouterr().out)["nodes"][-1] == [9.0, 6.5, 90.0]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["scenarios", "nope"], "no shipped scenario 'nope'; the shipped ones: dead_end_bay, empty_room,"),
        (["scenarios", "--export", "x.json"], "--export needs the NAME"),
        (["scenarios", "turn_around", "--export", "{exists}"], "the file exists"),
        (["draw", "nope.json"], "nope.json: cannot read"),
        (["draw", "nope"], "'nope' is neither a file nor a shipped scenario"),
        (["draw", "turn_around", "--out", "floor.txt"], "--out floor.txt: cannot write a figure"),
        (["draw", "turn_around", "--L", "1"], "--L applies to a map"),
        (["draw", "{map}", "--start", "1", "1", "0"], "a map needs --goal, --L"),
        (["draw", "{map}", "--half-width", "0.3"], "a map needs --start, --goal, --L"),
    ],
)
def test_scenarios_and_draw_errors_are_one_line(tmp_path, capsys, monkeypatch, room_map, argv, message):
    monkeypatch.chdir(tmp_path)
    exists = tmp_path / "exists.json"
    exists.write_text("{}")
    argv = [a.format(exists=exists, map=room_map) for a in argv]
    assert main(argv) == EXIT_BAD_INPUT
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("segplan: error: ") and message in err[0], err
    assert exists.read_text() == "{}" and not (tmp_path / "x.json").exists()
    assert not list(tmp_path.glob("*.png")) and not list(tmp_path.glob("*.txt"))


def test_draw_a_scenario_a_shipped_name_and_a_map(tmp_path, capsys, monkeypatch, room_map):
    """FLOOR as plan reads it: a file, a shipped name, a ROS map (bare, or with the robot)."""
    from segplan.viz import plot

    monkeypatch.chdir(tmp_path)
    figures = []
    real = plot.plan_figure
    monkeypatch.setattr(plot, "plan_figure", lambda *args: figures.append(args) or real(*args))
    assert main(["draw", "fig5_example1"]) == 0  # default file: the floor's name
    assert capsys.readouterr().out == "figure      fig5_example1.png\n"
    assert main(["draw", str(SINGLE), "--out", "single.pdf"]) == 0
    assert main(["draw", room_map, "--out", "room.png"]) == 0
    robot = ["--start", "1", "1", "0", "--goal", "8.5", "4", "90", "--L", "0.8", "--half-width", "0.2"]
    assert main(["draw", room_map, "--out", "robot.png", *robot]) == 0
    for name in ("fig5_example1.png", "room.png", "robot.png"):
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (tmp_path / "single.pdf").read_bytes()[:4] == b"%PDF"
    floors = [args[0] for args in figures]
    assert [type(f).__name__ for f in floors] == ["Scenario", "Scenario", "Floor", "Scenario"]
    assert all(args[1] == () for args in figures)  # floors only, nothing planned
    assert figures[0][2] == (
        "fig5_example1: 30 x 20 m, 10 obstacles; L 1.2 m, half-width 0.35 m, steering 45 deg"
    )
    assert figures[2][2].startswith("room: 10 x 6 m, ") and "half-width" not in figures[2][2]
    assert floors[3].robot.half_width == 0.2
