"""The validators of the planners' numeric options and search limits.

One rule for every number a planner takes (:class:`segplan.planning.options.PaperOptions`
and its siblings, :class:`segplan.planning.schedule.Schedule`, the lattice search's keyword
arguments): a finite number above a bound, an integer where a count is meant, with a
``ValueError`` naming the argument. At the bottom of the planning layers, so that the
options, the schedule and the plan that records them all use it
(:mod:`segplan.planning.plan` re-exports both names, their earlier home).
"""

from __future__ import annotations

import math

__all__ = ["check_limits", "check_option"]


def check_option(
    value, name: str, lo: float, *, integer: bool = False, allow_none: bool = False, lo_ok: bool = False
):
    """A search option: a finite number above ``lo`` (at least ``lo`` with ``lo_ok``),
    an integer if ``integer``, or None if ``allow_none``. Returns it as int or float.

    The one validator of the planners' numeric options (:func:`segplan.plan_scenario`,
    :func:`segplan.planning.lattice.search.lattice_search`). Raises ValueError naming ``name``.
    """
    if value is None and allow_none:
        return None
    ok = not isinstance(value, bool) and isinstance(value, int | float) and math.isfinite(value)
    ok = ok and (value >= lo if lo_ok else value > lo)
    if ok and integer:
        ok = int(value) == value
    if not ok:
        kind = "an integer" if integer else "a finite number"
        raise ValueError(f"{name} must be {kind} {'>=' if lo_ok else '>'} {lo}, got {value!r}")
    return int(value) if integer else float(value)


def check_limits(max_expansions, time_limit) -> tuple[int | None, float]:
    """The search limits of every planner: ``max_expansions`` an integer >= 1 (or None: the
    planner's default), ``time_limit`` a positive number of seconds. Raises ValueError
    naming the argument (:func:`check_option`)."""
    return (
        check_option(max_expansions, "max_expansions", 1, integer=True, allow_none=True, lo_ok=True),
        check_option(time_limit, "time_limit", 0.0),
    )
