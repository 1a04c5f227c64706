"""Progress bars for the long runs of the studies and benchmarks (tqdm), shown on a terminal only.

One helper for every long loop: the studies (``segplan.studies``) and the scripts in
``benchmarks/``. The bar goes to stderr and only when stderr is a terminal (tqdm's
``disable=None``): a book build, pytest and a log file see nothing, so a chapter's stderr
(which fails the book's ``-W`` build) stays empty.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable

from tqdm import tqdm

__all__ = ["progress", "say"]


def progress(iterable: Iterable | None = None, total: int | None = None, desc: str = "", unit: str = "run"):
    """A tqdm bar over ``iterable`` (or a manual bar of ``total`` steps), silent off a terminal.

    Parameters
    ----------
    iterable : iterable, optional
        Iterated through the bar (``for x in progress(items, desc=...)``); without it,
        call ``bar.update()`` on the returned bar, best as a context manager.
    total : int, optional
        Number of steps (default: ``len(iterable)`` where it has one).
    desc : str
        The bar's label.
    unit : str
        What one step is ("run", "floor", "case").

    Returns
    -------
    tqdm.tqdm
        Disabled (a plain pass-through) when stderr is not a terminal; the bar is
        removed when done (``leave=False``).
    """
    return tqdm(iterable, total=total, desc=desc, unit=unit, disable=None, leave=False)


def say(line: str) -> None:
    """Print ``line`` to stderr, above any :func:`progress` bar on the terminal (tqdm.write)."""
    tqdm.write(line, file=sys.stderr)
