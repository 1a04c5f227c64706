"""The layers of the package (issue 11): every import points down, imports inside functions too.

Runs import-linter's ``layers`` contract of ``pyproject.toml`` (``[tool.importlinter]``) on
the package, so an import cycle or an upward dependency fails the test suite. A second
test checks that the contract is not vacuous: an upward import (a numerical module importing
the planner) is reported as broken.
"""

import ast
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def lint_imports(config: Path, cwd: Path) -> subprocess.CompletedProcess:
    code = (
        "import sys; from importlinter.cli import lint_imports; "
        f"sys.exit(lint_imports(config_filename={str(config)!r}, no_cache=True, no_logo=True))"
    )
    env = dict(os.environ, PYTHONPATH=str(cwd))
    return subprocess.run([sys.executable, "-c", code], cwd=cwd, env=env, capture_output=True, text=True)


def test_layers_contract_is_kept():
    out = lint_imports(ROOT / "pyproject.toml", ROOT)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "7 kept, 0 broken" in out.stdout


def _copy_with(tmp_path: Path, module: str, code: str) -> subprocess.CompletedProcess:
    """Lint a copy of the package where ``module`` (a path under segplan/) ends with ``code``."""
    pkg = tmp_path / "segplan"
    for src in (ROOT / "segplan").rglob("*.py"):
        dst = pkg / src.relative_to(ROOT / "segplan")
        dst.parent.mkdir(parents=True, exist_ok=True)
        dst.write_text(src.read_text(encoding="utf-8"), encoding="utf-8")
    target = pkg / module
    target.write_text(target.read_text(encoding="utf-8") + textwrap.dedent(code), encoding="utf-8")
    config = tmp_path / "pyproject.toml"
    config.write_text((ROOT / "pyproject.toml").read_text(encoding="utf-8"), encoding="utf-8")
    return lint_imports(config, tmp_path)


@pytest.mark.parametrize(
    ("module", "target", "expected"),
    [
        # the floor imports the planner: an upward import between sub-packages
        ("floor/geometry.py", "..planning.api", "segplan.floor.geometry -> segplan.planning.api"),
        # the paper's mathematics imports the floor
        ("model/union.py", "..floor.collision", "segplan.model.union -> segplan.floor.collision"),
        # the two planners are siblings: the lattice may not use the paper's search
        (
            "planning/lattice/shortcut.py",
            "..paper.search",
            "segplan.planning.lattice.shortcut -> segplan.planning.paper.search",
        ),
        # the paper's search may not use the lattice (the independence contract, too)
        (
            "planning/paper/expansion.py",
            "..lattice.frame",
            "segplan.planning.paper.expansion -> segplan.planning.lattice.frame",
        ),
        # inside a sub-package: the union may not know the cost
        ("model/union.py", ".cost", "segplan.model.union -> segplan.model.cost"),
    ],
)
def test_layers_contract_catches_an_upward_import(tmp_path, module, target, expected):
    """A copy of the package with one forbidden import (inside a function) breaks a contract."""
    code = f"""

        def _upward():
            from {target} import __name__ as name  # forbidden, inside a function

            return name
        """
    out = _copy_with(tmp_path, module, code)
    assert out.returncode != 0
    assert "BROKEN" in out.stdout and expected in out.stdout, out.stdout


def test_every_module_declares_its_exports():
    """Each module has an ``__all__`` of names it defines (or imports for re-export in ``__init__``)."""
    import importlib
    import pkgutil

    import segplan

    names = [m.name for m in pkgutil.walk_packages(segplan.__path__, "segplan.")]
    assert len(names) > 20
    for name in names:
        if name.endswith("__main__"):
            continue
        module = importlib.import_module(name)
        exported = getattr(module, "__all__", None)
        assert isinstance(exported, list | tuple), f"{name} declares no __all__"
        for item in exported:
            assert hasattr(module, item), f"{name}.__all__ names {item!r}, which it does not define"
            assert not item.startswith("_"), f"{name}.__all__ exports the private {item!r}"


def test_no_module_exceeds_800_lines():
    """A smoke alarm, not a rule (issue 24): a module is one idea, split where a concept ends,
    never to fit a number; a module over 800 lines is the place to look for two ideas."""
    lines = {
        str(path.relative_to(ROOT)): len(path.read_text(encoding="utf-8").splitlines())
        for path in sorted((ROOT / "segplan").rglob("*.py"))
    }
    assert len(lines) > 20
    too_long = {name: n for name, n in lines.items() if n > 800}
    assert not too_long, too_long


def _notebook_sources():
    import json

    for path in sorted((ROOT / "notebooks").glob("*.ipynb")):
        cells = json.loads(path.read_text())["cells"]
        code = "\n".join(
            "".join(line for line in c["source"] if not line.lstrip().startswith(("%", "!")))
            for c in cells
            if c["cell_type"] == "code"
        )
        yield path.name, code


def private_uses(code: str) -> list[str]:
    """Leading-underscore names a piece of code takes from segplan: imported
    (``from segplan.x import _y``) or reached through an imported segplan name
    (``segplan.x._y``, ``mod._y`` after ``from segplan import mod``)."""
    tree = ast.parse(code)
    bound = set()  # local names bound to segplan modules or objects
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.split(".")[0] == "segplan":
                    bound.add((a.asname or a.name).split(".")[0])
        elif isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "segplan":
            for a in node.names:
                if a.name.startswith("_"):
                    found.append(f"from {node.module} import {a.name}")
                bound.add(a.asname or a.name)
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and node.attr.startswith("_") and not node.attr.startswith("__"):
            root = node.value
            while isinstance(root, ast.Attribute):
                root = root.value
            if isinstance(root, ast.Name) and root.id in bound:
                found.append(ast.unparse(node))
    return found


def test_private_use_detector_finds_both_forms():
    code = (
        "import segplan\nfrom segplan.model import frame as fr\nfrom segplan.model.cost import _x\n"
        "fr._y\nsegplan.model.pose._z\n"
    )
    assert private_uses(code) == ["from segplan.model.cost import _x", "fr._y", "segplan.model.pose._z"]
    assert private_uses("import numpy as np\nnp._NoValue\nfrom segplan import plan\n") == []


def test_notebooks_use_no_private_segplan_name():
    """Notebooks may study a module's exported names, never a leading-underscore one (issue 11)."""
    bad = {name: uses for name, code in _notebook_sources() if (uses := private_uses(code))}
    assert not bad, bad
