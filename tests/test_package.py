"""segplan as its users meet it: the shipped scenarios as package data, ``--version``,
``python -m segplan``, the animation, and a wheel that installs and plans in a clean venv."""

import json
import os
import re
import shutil
import subprocess
import sys
import venv
import zipfile
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import segplan
from segplan.cli import main

ROOT = Path(__file__).resolve().parents[1]


def test_shipped_scenarios_are_the_repository_files():
    names = segplan.shipped_scenarios()
    files = {p.stem: p for p in (ROOT / "scenarios").glob("*.json")}
    files |= {p.stem: p for p in (ROOT / "scenarios" / "beyond_the_paper").glob("*.json")}
    assert names == tuple(sorted(files)) and "l_shaped_rack" in names
    for name in names:
        by_name = segplan.load_scenario(name)
        by_path = segplan.load_scenario(files[name])
        assert by_name.to_json() == by_path.to_json()


def test_unknown_scenario_name_is_a_clear_error():
    with pytest.raises(
        segplan.ScenarioError, match="'no_such_floor' is neither a file nor a shipped scenario"
    ):
        segplan.load_scenario("no_such_floor")


def test_version(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"segplan {segplan.__version__}"


def test_python_dash_m_segplan():
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    out = subprocess.run(
        [sys.executable, "-m", "segplan", "plan", "single_obstacle", "--json"],
        capture_output=True, text=True, env=env, timeout=300, check=True,
    ).stdout  # fmt: skip
    assert json.loads(out)["found"] is True


def test_animate_gif(tmp_path, capsys):
    """The default GIF: readable (at least 600 pixels wide), its frames by the path's length."""
    from segplan.viz import animate

    gif = tmp_path / "plan.gif"
    assert main(["plan", "single_obstacle", "--animate", str(gif)]) == 0
    assert f"animation   {gif}" in capsys.readouterr().out
    sc = segplan.load_scenario("single_obstacle")
    poses = segplan.plan_poses(segplan.plan_scenario(sc))
    frames = animate.frame_count(animate._front_arc_length(poses, sc.L)[-1], sc.L)
    assert animate.MIN_FRAMES < frames < animate.MAX_FRAMES  # neither bound: the length decides
    with Image.open(gif) as im:
        assert im.format == "GIF" and im.n_frames == frames
        assert im.size[0] >= 600 and im.info["duration"] == 1000 / animate.FPS


def test_animation_frames_follow_the_front_wheel():
    from segplan.viz import animate

    sc = segplan.load_scenario("single_obstacle")
    plan = segplan.plan_scenario(sc)
    poses = segplan.plan_poses(plan)
    idx = animate._frame_indices(poses, sc.L, 11)
    assert idx[0] == 0 and idx[-1] == len(poses) - 1 and np.all(np.diff(idx) > 0)
    B = poses[:, :2] + sc.L * np.column_stack((np.cos(poses[:, 2]), np.sin(poses[:, 2])))
    s = np.r_[0.0, np.cumsum(np.hypot(*np.diff(B, axis=0).T))]
    gaps = np.diff(s[idx])
    assert gaps.max() - gaps.min() < 0.05 * gaps.mean()  # equal steps of the front wheel (1 cm samples)
    html = animate.to_html(animate.animate_plan(plan, sc, frames=4))
    assert html.count("data:image/png;base64") == 4
    assert "font-awesome" not in html and "fa fa-" not in html  # the CDN stylesheet and its icons
    assert not re.search(r"(?:src|href)\s*=\s*[\"']?(?:https?:)?//", html)
    with pytest.raises(ValueError, match="frames"):
        animate.animate_path(poses, sc.L, frames=1)
    with pytest.raises(ValueError, match="poses"):
        animate.animate_path(poses[:, :2], sc.L)


def test_html_animation_frames_are_small_palette_pngs():
    import base64
    import io

    from PIL import Image

    from segplan.viz import animate

    sc = segplan.load_scenario("single_obstacle")
    anim = animate.animate_plan(segplan.plan_scenario(sc), sc, frames=3)
    frames = re.findall(r'"data:image/png;base64,([^"]+)"', animate.to_html(anim))
    assert len(frames) == 3
    for b64 in frames:
        with Image.open(io.BytesIO(base64.b64decode(b64.replace("\\\n", "")))) as im:
            assert im.format == "PNG" and im.mode == "P" and len(im.getcolors()) <= animate.HTML_COLORS
            w, h = im.size  # animate_path's figsize x dpi, to a pixel
            (fw, fh), dpi = animate.FIGSIZE, animate.DPI
            assert abs(w - fw * dpi) <= 1 and abs(h - fh * dpi) <= 1


def test_license_and_citation():
    assert (ROOT / "LICENSE").read_text().startswith("MIT License")
    import tomllib

    import yaml

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert project["license"] == "MIT" and project["license-files"] == ["LICENSE"]  # PEP 639
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    assert cff["license"] == "MIT" and cff["version"] == segplan.__version__
    paper = cff["references"][0]
    assert paper["year"] == 1989 and [a["family-names"] for a in paper["authors"]] == [
        "Campoy", "Bobadilla", "Aracil", "Salichs", "Moreno",
    ]  # fmt: skip


def _offline_build_possible() -> bool:
    try:
        import build  # noqa: F401
        import setuptools  # noqa: F401
    except ImportError:
        return False
    return True


@pytest.mark.skipif(
    not _offline_build_possible(), reason="python -m build (package 'build') is not installed"
)
def test_wheel_installs_in_a_clean_venv_and_plans(tmp_path):
    """`python -m build` makes a wheel (from the sdist) that carries the shipped scenarios:
    installed by pip (offline, --no-deps) in a fresh venv (dependencies seen from this
    environment), `segplan plan fig5_example1` plans from any directory."""
    src = tmp_path / "src"
    shutil.copytree(
        ROOT, src, symlinks=True,
        ignore=shutil.ignore_patterns(".git", ".venv", "_build", "*.egg-info", "__pycache__", "dist"),
    )  # fmt: skip
    proc = subprocess.run(
        [sys.executable, "-m", "build", "--no-isolation", "--outdir", str(tmp_path / "dist"), str(src)],
        capture_output=True, text=True, timeout=600, check=False,
    )  # fmt: skip
    if proc.returncode != 0 and "No module named" in proc.stderr + proc.stdout:
        pytest.skip(f"cannot build offline: {proc.stderr[-500:]}")
    assert proc.returncode == 0, proc.stdout[-2000:] + proc.stderr[-2000:]
    wheel = next((tmp_path / "dist").glob("segplan-*.whl"))
    with zipfile.ZipFile(wheel) as zf:
        assert "segplan/scenarios/fig5_example1.json" in zf.namelist()
        assert "segplan/scenarios/beyond_the_paper/l_shaped_rack.json" in zf.namelist()
        assert "segplan/py.typed" in zf.namelist()  # typed (PEP 561)
        meta = zf.read(next(n for n in zf.namelist() if n.endswith(".dist-info/METADATA"))).decode()
    # the core requirements are what planning imports; the studies' are an extra (issue 27)
    requires = [line for line in meta.splitlines() if line.startswith("Requires-Dist:")]
    core = [r for r in requires if "extra ==" not in r]
    assert not any(name in r for r in core for name in ("sympy", "pandas", "tqdm", "jupyter"))
    assert any("sympy" in r and 'extra == "study"' in r for r in requires)
    assert "License-Expression: MIT" in meta
    env_dir = tmp_path / "venv"
    # the dependencies (numpy, scipy, ...) from this environment, without its own segplan
    # (a plain path line: the .pth files there, e.g. an editable segplan, are not processed)
    deps = [p for p in sys.path if p.endswith("site-packages") and Path(p, "numpy").is_dir()]
    # this environment's pip, seen through those paths, runs in the new venv's interpreter and
    # installs into it: no pip bootstrapped there (ensurepip took ~8 s of CPU), one pip
    # start-up (``pip --python`` starts pip twice, ~1 s); else a venv with its own pip
    pip_here = any(Path(p, "pip").is_dir() for p in deps)
    venv.EnvBuilder(with_pip=not pip_here).create(env_dir)
    py = env_dir / "bin" / "python"
    site = subprocess.run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                          capture_output=True, text=True, check=True).stdout.strip()  # fmt: skip
    Path(site, "deps-from-test-env.pth").write_text("\n".join(deps) + "\n")
    pip = [py, "-m", "pip"]
    subprocess.run([*pip, "install", "-q", "--no-index", "--no-deps", str(wheel)],
                   capture_output=True, text=True, timeout=300, check=True)  # fmt: skip
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    run = subprocess.run(
        [env_dir / "bin" / "segplan", "plan", "fig5_example1", "--json"],
        capture_output=True, text=True, cwd=tmp_path, env=env, timeout=300, check=False,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-2000:]
    out = json.loads(run.stdout)
    assert out["found"] is True and out["scenario"] == "fig5_example1"
    # the installed copy runs (not this tree), and plans a scenario from the package's
    # beyond_the_paper folder: one interpreter for both (each start-up imports segplan, ~1 s)
    code = (
        "import sys, segplan, segplan.cli; print(segplan.__file__); "
        "sys.exit(segplan.cli.main(['plan', 'l_shaped_rack', '--json']))"
    )
    rack = subprocess.run(
        [py, "-c", code], capture_output=True, text=True, cwd=tmp_path, env=env, timeout=300, check=False
    )
    assert rack.returncode == 0, rack.stderr[-2000:]
    where, _, rack_json = rack.stdout.partition("\n")
    assert where.startswith(site), where  # the installed copy, not this tree
    assert json.loads(rack_json)["found"] is True


def test_import_segplan_needs_only_the_core_requirements():
    """Planning imports none of the studies' packages (issue 27: a 523 MB venv for a planner)."""
    code = (
        "import sys, math, segplan; "
        "segplan.plan((0, 0, 0), (6, 1, 0.2), [], 1.0, bounds=(-2, -3, 9, 4), half_width=0.2); "
        "print(sorted(m for m in ('sympy', 'pandas', 'tqdm') if m in sys.modules))"
    )
    run = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True
    )
    assert run.stdout.strip() == "[]"
