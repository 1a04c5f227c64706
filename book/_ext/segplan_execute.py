"""Sphinx extension of the segplan book: execute the chapters two at a time, afresh at every build.

Loaded through ``sphinx.local_extensions`` in ``book/_config.yml``. jupyter-book 1.x runs one
notebook after the other (it passes no ``-j`` to myst-nb), which leaves one of this machine's
two cores idle for the whole build. With ``execute.execute_notebooks: cache`` myst-nb takes a
notebook's outputs from a jupyter-cache when the cache holds a notebook with the same code
(and executes it itself, as in ``force`` mode, when it does not). This extension fills that
cache just before Sphinx reads the documents (event ``env-before-read-docs``):

* the cache (``_build/.jupyter_cache``) is deleted first, so nothing executed in an earlier
  build is ever used: every notebook Sphinx reads is executed in this build, in a fresh
  kernel (a clean build, such as ``.ci/build_book.sh``, executes every chapter);
* the notebooks among the documents to read are executed ``segplan_execute_jobs`` at a time
  (default: 2, at most the number of cores), the documents named in ``segplan_execute_first``
  (the slowest chapters) first, then the others in name order, each in its own process and
  kernel, in its own
  directory as in ``force`` mode (``run_in_temp: false``), with the same timeout and
  ``allow_errors`` as ``execute:`` in ``_config.yml``, by the function myst-nb itself uses
  (``jupyter_cache.executors.utils.single_nb_execution``);
* a notebook that fails is not cached: myst-nb then executes it again itself and reports
  the error (the build fails under ``raise_on_error``).

The executed notebooks are stored only in ``_build``; the notebooks in ``notebooks/`` (whose
stored outputs ``pytest --nbval`` checks) are not touched. Each notebook's execution time
is logged (``segplan: executed ... in N s``).
"""

from __future__ import annotations

import os
import resource
import shutil
import time
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

from sphinx.application import Sphinx
from sphinx.util import logging

logger = logging.getLogger(__name__)


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def execute_one(
    path: str, timeout: int | None, allow_errors: bool
) -> tuple[str, str, float, float, str | None]:
    """Execute the notebook ``path`` in a fresh kernel in its own directory.

    Returns ``(path, executed notebook as JSON, wall seconds, kernel CPU seconds, traceback
    or None)``; the kernel's CPU time (the finished kernel process, from ``getrusage``) does
    not depend on what else the machine runs. Runs in a worker process; the parent stores
    the result in the cache.
    """
    import nbformat
    from jupyter_cache.executors.utils import single_nb_execution

    nb = nbformat.read(path, as_version=4)
    cpu = _children_cpu()
    result = single_nb_execution(
        nb, cwd=str(Path(path).parent), timeout=timeout, allow_errors=allow_errors, meta_override=True
    )
    cpu = _children_cpu() - cpu
    return path, nbformat.writes(result.nb), result.time, cpu, result.exc_string if result.err else None


def jobs(app: Sphinx) -> int:
    """How many notebooks run at a time: ``segplan_execute_jobs``, at most the cores, at least 1."""
    wanted = int(app.config.segplan_execute_jobs)
    if wanted < 1:
        raise ValueError(f"segplan_execute_jobs must be >= 1, got {wanted}")
    return max(1, min(wanted, os.cpu_count() or 1))


def pre_execute(app: Sphinx, env, docnames: list[str]) -> None:
    """Execute the notebooks among ``docnames`` in parallel into a fresh jupyter-cache."""
    config = getattr(env, "mystnb_config", None)
    if config is None or config.execution_mode != "cache":
        return
    import nbformat
    from jupyter_cache import get_cache
    from jupyter_cache.base import CacheBundleIn

    cache_path = Path(config.execution_cache_path)
    shutil.rmtree(cache_path, ignore_errors=True)  # nothing from an earlier build is reused
    first = [d for d in app.config.segplan_execute_first if d in docnames]
    order = first + sorted(d for d in docnames if d not in first)
    paths = [str(Path(env.doc2path(d))) for d in order]
    paths = [p for p in paths if p.endswith(".ipynb")]
    if not paths:
        return
    cache = get_cache(str(cache_path))
    n_jobs = min(jobs(app), len(paths))
    logger.info(f"segplan: executing {len(paths)} notebooks, {n_jobs} at a time")
    start = time.perf_counter()
    with ProcessPoolExecutor(max_workers=n_jobs) as pool:
        futures = [
            pool.submit(execute_one, p, config.execution_timeout, config.execution_allow_errors)
            for p in paths
        ]
        cpu_total = 0.0
        for future in as_completed(futures):
            path, text, seconds, cpu, error = future.result()
            name = Path(path).name
            cpu_total += cpu
            if error is not None:  # myst-nb executes it again and reports the error
                logger.info(f"segplan: {name} failed after {seconds:.1f} s (myst-nb re-runs it)")
                continue
            cache.cache_notebook_bundle(
                CacheBundleIn(nbformat.reads(text, as_version=4), path, data={"execution_seconds": seconds}),
                check_validity=False,
                overwrite=True,
            )
            logger.info(f"segplan: executed {name} in {seconds:.1f} s (kernel CPU {cpu:.1f} s)")
    logger.info(
        f"segplan: {len(paths)} notebooks executed in {time.perf_counter() - start:.1f} s "
        f"(kernel CPU {cpu_total:.1f} s; load average {os.getloadavg()[0]:.2f})"
    )


def setup(app: Sphinx) -> dict:
    app.add_config_value("segplan_execute_jobs", 2, "env", int)
    app.add_config_value("segplan_execute_first", [], "env", list)
    app.connect("env-before-read-docs", pre_execute)
    return {"version": "1.0", "parallel_read_safe": True, "parallel_write_safe": True}
