"""The book's API reference page is generated from ``segplan.__all__`` and refuses an unassigned name."""

from pathlib import Path

import pytest
from load_file import load_file

import segplan

EXT = Path(__file__).resolve().parents[1] / "book" / "_ext" / "segplan_api.py"
sphinx_errors = pytest.importorskip("sphinx.errors")


def load_ext():
    return load_file(EXT, "segplan_api")


def test_every_public_name_has_one_section():
    ext = load_ext()
    ext.check_groups(list(segplan.__all__))
    text = ext.page()
    for name in segplan.__all__:
        assert f":: {name}\n" in text, name


def test_an_unassigned_or_unknown_name_fails_loudly():
    ext = load_ext()
    with pytest.raises(sphinx_errors.ExtensionError, match="new_function"):
        ext.check_groups([*segplan.__all__, "new_function"])
    with pytest.raises(sphinx_errors.ExtensionError, match="lacks.*'Union'"):
        ext.check_groups([n for n in segplan.__all__ if n != "Union"])
