"""A planning call's progress shown as it goes: the command line's ``--progress``.

:func:`segplan.plan_scenario` hands its ``progress`` callback a
:class:`segplan.planning.context.Progress` (stage, event, seconds, time limit, expansions,
cost) when a stage starts and ends and every 64 lattice expansions. :class:`ProgressLine`
shows them: on a terminal with tqdm installed (the ``study`` extra), one bar over the call's
time limit; otherwise one line per stage's start and end, and at most one line every
``every`` seconds while the lattice search runs. It only watches: the plan is the same with
or without it.
"""

from __future__ import annotations

import sys
from typing import TextIO

__all__ = ["ProgressLine"]


class ProgressLine:
    """Show a planning call's progress on ``stream`` (module docstring); pass it as
    ``progress=`` and :meth:`close` it after the call.

    Parameters
    ----------
    stream : text stream
        Where to write (default ``sys.stderr``).
    every : float
        Seconds between two lines of a running search (plain lines only; > 0).
    bar : bool or None
        Use a tqdm bar: None (default) where tqdm is installed and ``stream`` is a terminal.
    """

    def __init__(self, stream: TextIO | None = None, every: float = 0.5, bar: bool | None = None):
        if not (isinstance(every, int | float) and every > 0):
            raise ValueError(f"every must be a number of seconds > 0, got {every!r}")
        self.stream = sys.stderr if stream is None else stream
        self.every = float(every)
        self._last = -float("inf")
        self._bar = None
        if bar is None:
            bar = _has_tqdm() and bool(getattr(self.stream, "isatty", lambda: False)())
        self.use_bar = bool(bar)

    def __call__(self, p) -> None:
        if self.use_bar:
            self._show_bar(p)
        else:
            self._show_line(p)

    def _show_line(self, p) -> None:
        if p.event == "expanded":
            if p.seconds - self._last < self.every:
                return
            what = f"{p.expanded} expansions"
        elif p.event == "start":
            what = "started"
        else:
            cost = "no plan" if p.cost is None else f"LONGD {p.cost:.3f} m"
            what = f"done ({cost}" + (f", {p.expanded} expansions)" if p.expanded else ")")
        self._last = p.seconds
        print(f"segplan: {p.seconds:6.2f} s of {p.limit:g}  {p.stage}: {what}", file=self.stream, flush=True)

    def _show_bar(self, p) -> None:
        if self._bar is None:
            from tqdm import tqdm

            self._bar = tqdm(total=p.limit, unit="s", file=self.stream, leave=False, bar_format=_BAR)
        self._bar.n = min(p.seconds, p.limit)
        self._bar.set_postfix_str(f"{p.stage} {p.event}" + (f", {p.expanded} expanded" if p.expanded else ""))

    def close(self) -> None:
        """End the bar (plain lines need nothing)."""
        if self._bar is not None:
            self._bar.close()
            self._bar = None


#: The bar: seconds used of the time limit, and the stage.
_BAR = "{desc}{percentage:3.0f}% of the time limit |{bar}| {n:.2f}/{total:g} s {postfix}"


def _has_tqdm() -> bool:
    try:
        import tqdm  # noqa: F401
    except ImportError:
        return False
    return True
