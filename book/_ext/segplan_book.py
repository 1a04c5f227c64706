"""Sphinx extension of the segplan book: the built HTML must stand alone, with no network.

Loaded through ``sphinx.local_extensions`` in ``book/_config.yml``. It

* stops the build with a clear message when the offline MathJax (the Python package
  ``sphinx-mathjax-offline``, which ships MathJax 3.2.2 and copies it into
  ``_build/html/_static/mathjax``) is missing or ``mathjax_path`` names a file it does not
  ship, instead of producing pages whose math silently fails to render;
* drops sphinx-thebe's scripts from every page: the book has no live-code button
  (``launch_buttons.thebe: false``), yet jupyter-book 1.0.4 always loads sphinx-thebe, whose
  inline ``const THEBE_JS_URL = "https://unpkg.com/..."`` is emitted twice per page and
  throws a SyntaxError in the browser;
* stops the build when notebooks are taken from a jupyter-cache (``execute_notebooks:
  cache``) without ``_ext/segplan_execute.py``, which empties that cache and executes every
  chapter afresh at every build;
* warns (an error under ``-W``) for every script or stylesheet a page would load from
  another host (a CDN, analytics), so a theme or extension update cannot bring one in
  unnoticed.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

from sphinx.application import Sphinx
from sphinx.errors import ConfigError
from sphinx.util import logging

logger = logging.getLogger(__name__)


def _is_remote(url: str) -> bool:
    return "://" in url or url.startswith("//")


def mathjax_dir() -> Path | None:
    """The MathJax files of the ``sphinx-mathjax-offline`` package, or None without it."""
    spec = importlib.util.find_spec("sphinx-mathjax-offline")
    if spec is None or spec.origin is None:
        return None
    return Path(spec.origin).parent / "static" / "mathjax"


def check_mathjax(app: Sphinx) -> None:
    """``mathjax_path`` names a file that ``sphinx-mathjax-offline`` ships (offline math)."""
    if app.builder.format != "html":
        return
    path = str(app.config.mathjax_path)
    if _is_remote(path):
        raise ConfigError(f"mathjax_path must name a file shipped with the book (offline), got {path!r}")
    if "sphinx-mathjax-offline" not in app.config.extensions:
        raise ConfigError("the book needs the extension sphinx-mathjax-offline (sphinx.extra_extensions)")
    folder = mathjax_dir()
    if folder is None:
        raise ConfigError(
            "MathJax not found: the Python package sphinx-mathjax-offline is not installed "
            "(pip install -r environment.txt, or pip install -e '.[book]')"
        )
    name = path.removeprefix("mathjax/")
    if not (folder / name).is_file():
        raise ConfigError(f"mathjax_path {path!r}: sphinx-mathjax-offline ships no {name!r} in {folder}")


def check_execution(app: Sphinx) -> None:
    """``execute_notebooks: cache`` only with ``_ext/segplan_execute.py``, which empties the cache
    at every build: without it, myst-nb would reuse outputs executed in an earlier build."""
    if app.config.nb_execution_mode == "cache" and "segplan_execute" not in app.config.extensions:
        raise ConfigError(
            "execute_notebooks: cache needs the local extension segplan_execute (sphinx.local_extensions), "
            "which executes every chapter afresh at every build; without it use execute_notebooks: force"
        )


def _is_thebe(asset) -> bool:
    name = str(getattr(asset, "filename", "") or "")
    body = str(getattr(asset, "attributes", {}).get("body", ""))
    return name.endswith("sphinx-thebe.js") or "THEBE_JS_URL" in body


def check_assets(app: Sphinx, pagename: str, templatename: str, context: dict, doctree) -> None:
    """Drop sphinx-thebe's scripts; warn about scripts and stylesheets loaded from another host."""
    if "script_files" in context:
        context["script_files"][:] = [js for js in context["script_files"] if not _is_thebe(js)]
    for kind in ("script_files", "css_files"):
        for asset in context.get(kind, ()):
            url = str(getattr(asset, "filename", asset) or "")
            if _is_remote(url):
                logger.warning(
                    f"page {pagename!r} would load {url!r} from the network (the book must be offline)"
                )


def setup(app: Sphinx) -> dict:
    app.connect("builder-inited", check_mathjax)
    app.connect("builder-inited", check_execution)
    app.connect("html-page-context", check_assets, priority=900)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
