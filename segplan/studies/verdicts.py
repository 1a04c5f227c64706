"""Verdicts of the book's claims tables, computed from a measured value and a stated criterion.

Every chapter of the book ends with a table that judges the paper's claims. A verdict is
never typed: the chapter states a criterion before it measures (what quantity, which
threshold, in which direction, and the looser band, if any, that earns "partly
reproduced"), and :func:`judge` turns the measured value into the word. A changed number
therefore changes the verdict, and the table prints the criterion beside the word, so a
reader sees what was asked of the measurement.

The three words, best first, are :data:`VERDICTS`.
"""

from __future__ import annotations

import math
import operator
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

__all__ = [
    "VERDICTS",
    "Criterion",
    "Verdict",
    "claims_table",
    "judge",
    "worst",
]

#: The verdict words, best first.
VERDICTS = ("reproduced", "partly reproduced", "not reproduced")

_OPS = {"<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge, "==": operator.eq}
_WORDS = {"<": "below", "<=": "at most", ">": "above", ">=": "at least", "==": "equal to"}


@dataclass(frozen=True)
class Criterion:
    """What a measurement must show for a claim to count as reproduced.

    Parameters
    ----------
    quantity : str
        The measured quantity, in words ("max |relative error| of [2] inside its domain").
    op : {"<", "<=", ">", ">=", "=="}
        Direction: the claim is reproduced when ``value op threshold``.
    threshold : float or bool
        The bound the paper states (or the one the chapter states for an unnumbered claim).
        For a yes/no check use ``op="=="`` and ``threshold=True``.
    partly : float, optional
        A looser bound in the same direction: ``value op partly`` (but not the threshold)
        earns "partly reproduced". ``None``: no band, the verdict is yes or no.
    fmt : str
        Format of the value and the bounds in the criterion's text (``"{:.2%}"``, ...).
    varies : bool
        The value is a timing that varies from run to run and machine to machine: the
        criterion's text then does not print it (the chapter prints it in a cell whose
        output the tests do not compare); the verdict is still computed from it.

    Raises
    ------
    ValueError
        If ``op`` is unknown, ``threshold`` or ``partly`` is not finite, or ``partly`` does
        not lie on the looser side of ``threshold``.
    """

    quantity: str
    op: str
    threshold: float
    partly: float | None = None
    fmt: str = "{:g}"
    varies: bool = False

    def __post_init__(self):
        if self.op not in _OPS:
            raise ValueError(f"op must be one of {sorted(_OPS)}, got {self.op!r}")
        if not isinstance(self.quantity, str) or not self.quantity:
            raise ValueError(f"quantity must be a non-empty string, got {self.quantity!r}")
        for name in ("threshold", "partly"):
            value = getattr(self, name)
            if value is None and name == "partly":
                continue
            if isinstance(value, bool):
                continue
            if not isinstance(value, int | float) or not math.isfinite(value):
                raise ValueError(f"{name} must be a finite number, got {value!r}")
        if self.partly is not None:
            if self.op == "==":
                raise ValueError("partly must be None when op is '=='")
            looser = (
                self.partly >= self.threshold if self.op in ("<", "<=") else self.partly <= self.threshold
            )
            if not looser:
                raise ValueError(
                    f"partly must be on the looser side of threshold for op {self.op!r}: "
                    f"got threshold {self.threshold!r}, partly {self.partly!r}"
                )

    def show(self, value) -> str:
        """``value`` formatted as the criterion prints it."""
        if isinstance(value, bool) or isinstance(self.threshold, bool):
            return str(bool(value))
        return self.fmt.format(value)

    def text(self) -> str:
        """The criterion in words, e.g. ``"max |error| below 2.50 % (partly: below 5.00 %)"``."""
        out = f"{self.quantity} {_WORDS[self.op]} {self.show(self.threshold)}"
        if self.partly is not None:
            out += f" (partly: {_WORDS[self.op]} {self.show(self.partly)})"
        return out


@dataclass(frozen=True)
class Verdict:
    """A verdict word, the criterion's text, and the measured value it was given."""

    word: str
    criterion: str
    value: float

    def __str__(self) -> str:
        return self.word


def judge(value, criterion: Criterion) -> Verdict:
    """The verdict of a measured ``value`` under ``criterion``.

    "reproduced" when ``value op threshold``; otherwise "partly reproduced" when the
    criterion has a ``partly`` band and ``value op partly``; otherwise "not reproduced".
    A NaN value (nothing measured) is "not reproduced".

    Raises
    ------
    ValueError
        If ``criterion`` is not a :class:`Criterion` or ``value`` is not a real number.
    """
    if not isinstance(criterion, Criterion):
        raise ValueError(f"criterion must be a Criterion, got {type(criterion).__name__}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"value must be a real number or a bool, got {value!r}") from None
    if isinstance(value, bool) or isinstance(criterion.threshold, bool):
        shown = criterion.show(value)
    else:
        shown = criterion.show(x)
    if criterion.varies:
        shown = "on the build machine (a timing: printed above, varies between runs)"
    text = f"{criterion.text()}; measured {shown}"
    holds = _OPS[criterion.op]
    if math.isnan(x):
        word = VERDICTS[2]
    elif holds(x, float(criterion.threshold)):
        word = VERDICTS[0]
    elif criterion.partly is not None and holds(x, float(criterion.partly)):
        word = VERDICTS[1]
    else:
        word = VERDICTS[2]
    return Verdict(word, text, x)


def worst(verdicts: Iterable[Verdict]) -> Verdict:
    """One verdict for a claim judged on several criteria: the worst word, every criterion.

    Raises
    ------
    ValueError
        If ``verdicts`` is empty.
    """
    verdicts = list(verdicts)
    if not verdicts:
        raise ValueError("verdicts must not be empty")
    word = max((v.word for v in verdicts), key=VERDICTS.index)
    return Verdict(word, "; and ".join(v.criterion for v in verdicts), math.nan)


def claims_table(rows: Iterable[Mapping]):
    """A chapter's claims table: columns ``claim, paper, ours, criterion, verdict, why``.

    Each row is a mapping with the keys ``claim, paper, ours, verdict, why``, where
    ``verdict`` is a :class:`Verdict` (from :func:`judge` or :func:`worst`); its word
    fills the ``verdict`` column and its criterion text the ``criterion`` column. Rows are
    numbered from 1.

    Raises
    ------
    ValueError
        If a row misses a key or its ``verdict`` is not a :class:`Verdict`.
    """
    import pandas as pd

    keys = ("claim", "paper", "ours", "verdict", "why")
    out = []
    for i, row in enumerate(rows, start=1):
        missing = [k for k in keys if k not in row]
        if missing:
            raise ValueError(f"rows[{i - 1}] misses {missing}")
        v = row["verdict"]
        if not isinstance(v, Verdict):
            raise ValueError(f"rows[{i - 1}]['verdict'] must be a Verdict (from judge), got {v!r}")
        out.append(
            {
                "claim": row["claim"],
                "paper": row["paper"],
                "ours": row["ours"],
                "criterion": v.criterion,
                "verdict": v.word,
                "why": row["why"],
            }
        )
    table = pd.DataFrame(out, columns=["claim", "paper", "ours", "criterion", "verdict", "why"])
    table.index = pd.RangeIndex(1, len(table) + 1)
    return table
