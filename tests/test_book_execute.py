"""The book executes its chapters two at a time into a jupyter-cache that no later build reuses.

``book/_ext/segplan_execute.py`` fills myst-nb's cache (``execute_notebooks: cache``) just
before Sphinx reads the documents; these tests run it on a two-notebook toy book: each
notebook executes in a fresh kernel in its own directory, myst-nb's lookup finds the
outputs, a second build empties the cache first, and a failing notebook is left to myst-nb.
"""

import os
import types
from pathlib import Path

import pytest
import yaml
from load_file import load_file

ROOT = Path(__file__).resolve().parents[1]
EXT = ROOT / "book" / "_ext" / "segplan_execute.py"
nbformat = pytest.importorskip("nbformat")
jupyter_cache = pytest.importorskip("jupyter_cache")
pytest.importorskip("sphinx")


def load_ext():
    return load_file(EXT, "segplan_execute")  # registered: its worker function is pickled by name


def write_notebook(path: Path, *sources: str) -> Path:
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(s) for s in sources])
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nbformat.write(nb, path)
    return path


def fake_app(srcdir: Path, cache: Path, jobs: int = 2):
    config = types.SimpleNamespace(segplan_execute_jobs=jobs, segplan_execute_first=["b"])
    mystnb = types.SimpleNamespace(
        execution_mode="cache",
        execution_cache_path=str(cache),
        execution_timeout=60,
        execution_allow_errors=False,
    )

    def doc2path(docname):  # Sphinx's: the document's source file, whatever its suffix
        return next(p for p in (srcdir / f"{docname}.ipynb", srcdir / f"{docname}.md") if p.exists())

    env = types.SimpleNamespace(mystnb_config=mystnb, doc2path=doc2path)
    return types.SimpleNamespace(config=config), env


def test_the_book_uses_the_extension_with_the_cache():
    config = yaml.safe_load((ROOT / "book" / "_config.yml").read_text())
    assert config["execute"]["execute_notebooks"] == "cache"
    assert "segplan_execute" in config["sphinx"]["local_extensions"]
    assert config["sphinx"]["config"]["segplan_execute_jobs"] == 2


def test_notebooks_execute_afresh_into_the_cache(tmp_path):
    ext = load_ext()
    (tmp_path / "src").mkdir()
    a = write_notebook(tmp_path / "src" / "a.ipynb", "import os\nprint(os.getcwd())", "print(6 * 7)")
    b = write_notebook(tmp_path / "src" / "b.ipynb", "print('b', os.getpid() if 'os' in dir() else 'fresh')")
    (tmp_path / "src" / "intro.md").write_text("# Intro\n")
    cache_dir = tmp_path / "_build" / ".jupyter_cache"
    app, env = fake_app(tmp_path / "src", cache_dir)
    ext.pre_execute(app, env, ["a", "b", "intro"])  # "intro" is not a notebook: ignored
    cache = jupyter_cache.get_cache(str(cache_dir))
    _, merged = cache.merge_match_into_notebook(nbformat.read(a, as_version=4))  # myst-nb's lookup
    texts = ["".join(o.get("text", "") for o in c.outputs) for c in merged.cells]
    assert texts == [f"{os.path.realpath(a.parent)}\n", "42\n"]  # cells run in the notebook's folder
    _, merged_b = cache.merge_match_into_notebook(nbformat.read(b, as_version=4))
    assert merged_b.cells[0].outputs[0]["text"] == "b fresh\n"  # a fresh kernel: nothing from a.ipynb
    # the next build starts from an empty cache: an edited notebook is executed, nothing is reused
    write_notebook(a, "print('edited')")
    ext.pre_execute(app, env, ["a"])
    cache = jupyter_cache.get_cache(str(cache_dir))
    assert len(cache.list_cache_records()) == 1
    _, merged = cache.merge_match_into_notebook(nbformat.read(a, as_version=4))
    assert merged.cells[0].outputs[0]["text"] == "edited\n"


def test_a_failing_notebook_is_left_to_mystnb(tmp_path):
    ext = load_ext()
    (tmp_path / "src").mkdir()
    bad = write_notebook(tmp_path / "src" / "a.ipynb", "raise ValueError('boom')")
    app, env = fake_app(tmp_path / "src", tmp_path / "cache", jobs=1)
    ext.pre_execute(app, env, ["a"])
    with pytest.raises(KeyError):  # not cached: myst-nb executes it again and reports the error
        jupyter_cache.get_cache(str(tmp_path / "cache")).match_cache_notebook(
            nbformat.read(bad, as_version=4)
        )


def test_other_execution_modes_and_bad_jobs():
    ext = load_ext()
    app, env = fake_app(Path("/nonexistent"), Path("/nonexistent/cache"))
    env.mystnb_config.execution_mode = "force"
    ext.pre_execute(app, env, ["a"])  # nothing to do, nothing touched
    app.config.segplan_execute_jobs = 0
    with pytest.raises(ValueError, match="segplan_execute_jobs"):
        ext.jobs(app)
    app.config.segplan_execute_jobs = 64
    assert ext.jobs(app) == os.cpu_count()
