"""One helper for the tests that exercise a script outside the package (the book's Sphinx
extensions, the benchmark scripts): import a file as a module."""

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

#: The repository's root.
ROOT = Path(__file__).resolve().parent.parent


def load_file(path: Path, name: str) -> ModuleType:
    """The module of the file ``path``, imported as ``name`` and registered in
    ``sys.modules`` (dataclasses and pickle look a module up by its name)."""
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module
