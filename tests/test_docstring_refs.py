"""Every Sphinx cross-reference in segplan's docstrings and ``#:`` comments names something
that exists (issue 24: after the move into sub-packages, references to old homes such as
``segplan.search.Plan`` must follow the code).

A reference ``:func:`name``` (also ``:class:``, ``:mod:``, ``:data:``, ``:meth:``,
``:attr:``, ``:exc:``, ``:obj:``) resolves as Sphinx would look for it: as written (a dotted
path from an importable module), then inside the enclosing classes, the module and each
parent package; class attributes include dataclass and NamedTuple fields, ``__slots__``,
annotations and instance attributes set in the class's code (``self.name = ...``).
"""

from __future__ import annotations

import ast
import builtins
import importlib
import inspect
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "segplan"
ROLE = re.compile(r":(?:py:)?(func|class|mod|data|meth|attr|exc|obj|const):`([^`]+)`")

#: References known not to resolve, ``(file, reference)``: none (the last three, in the lattice's
#: former mixins, went with them in issue 24). An entry that resolves fails too.
KNOWN_BAD: set[tuple[str, str]] = set()


def _has(obj, name: str) -> bool:
    if hasattr(obj, name):
        return True
    if not inspect.isclass(obj):
        return False
    for cls in obj.__mro__:
        if name in getattr(cls, "__dataclass_fields__", {}) or name in getattr(cls, "_fields", ()):
            return True
        if name in getattr(cls, "__annotations__", {}) or name in getattr(cls, "__slots__", ()):
            return True
        try:
            source = inspect.getsource(cls)
        except (OSError, TypeError):
            continue
        if re.search(rf"\bself\.{re.escape(name)}\s*(?::[^=\n]*)?=(?!=)", source):
            return True
    return False


def _resolves(dotted: str) -> bool:
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for p in parts[i:]:
            if not _has(obj, p):
                return False
            obj = getattr(obj, p, None)
        return True
    return False


def _candidates(target: str, module: str, classes: list[str]):
    if target.endswith(">") and "<" in target:  # :func:`title <target>`
        target = target[target.index("<") + 1 : -1]
    t = target.lstrip("~!.").removesuffix("()")
    yield t
    for k in range(len(classes), 0, -1):
        yield ".".join([module, *classes[:k], t])
    pkg = module
    while pkg:
        yield f"{pkg}.{t}"
        pkg = pkg.rpartition(".")[0]


def _references():
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        module = rel.removesuffix(".py").replace("/", ".").removesuffix(".__init__")
        text = path.read_text(encoding="utf-8")
        spans = [
            (n.lineno, n.end_lineno, n.name) for n in ast.walk(ast.parse(text)) if isinstance(n, ast.ClassDef)
        ]
        for lineno, line in enumerate(text.splitlines(), start=1):
            for m in ROLE.finditer(line):
                classes = [name for a, b, name in sorted(spans) if a <= lineno <= b]
                yield rel, lineno, module, classes, m.group(2)


def _resolved(target: str, module: str, classes: list[str]) -> bool:
    if any(_resolves(c) for c in _candidates(target, module, classes)):
        return True
    return hasattr(builtins, target.lstrip("~!"))


REFS = list(_references())


def test_there_are_references():
    assert len(REFS) > 200


def test_every_reference_resolves():
    bad = sorted(
        {(rel, target) for rel, _, module, classes, target in REFS if not _resolved(target, module, classes)}
    )
    unexpected = [
        f"{rel}:{line}: {target}"
        for rel, line, module, classes, target in REFS
        if (rel, target) in set(bad) - KNOWN_BAD
    ]
    assert not unexpected, "references to nothing:\n" + "\n".join(unexpected)
    fixed = sorted(KNOWN_BAD - set(bad))
    assert not fixed, f"these known-bad references resolve now; remove them from KNOWN_BAD: {fixed}"


@pytest.mark.parametrize(
    ("target", "ok"),
    [
        ("segplan.planning.validity.Workspace", True),
        ("segplan.expansion.Workspace", False),
        ("segplan.search.Plan", False),
        ("Union.max_curvature", True),
    ],
)
def test_the_resolver_tells_old_homes_from_new(target, ok):
    assert _resolved(target, "segplan.model.union", []) is ok
