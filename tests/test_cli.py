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
    assert main(["plan", SINGLE, "--out", str(out), "--cost", "distance", "--frames", "a"]) == 0
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
    monkeypatch.setattr(cli, "_draw", lambda path, scenario, unions, title: titles.append(title))
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
