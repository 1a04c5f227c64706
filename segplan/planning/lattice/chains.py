"""Chains of kept motion primitives: does one reach a lattice state within a budget?

The pruning of :func:`segplan.planning.lattice.primitives.compute_primitive_set` (the pruning
of Pivtoraiko and Kelly's state lattices): a candidate primitive is skipped if a chain of at
most three kept primitives from its start state ``(0, 0, h0)`` reaches its end state for no
more than a budget. A chain's cost is the sum of its primitives' LONGD, added in its order
(``(c1 + c2) + c3``).

The selection tries the chains breadth first (one step, two, three) where it notes how
close each cost it compares comes to the budget (``_reaches`` in that module, for
:func:`~segplan.planning.lattice.primitives.selection_margins`). :meth:`Chains.reaches` looks
the same answer up: :class:`Chains` indexes the kept primitives as they are added, with the
least cost of the chains of at most two steps from each start heading to each state, and a
query tries only the kept primitives into the target's heading as the last step. The two
answer alike: costs are positive, so a chain over the budget stays over it whatever
follows, and a rounded sum does not decrease when a term grows, so the cheapest prefix to a
state decides whether any chain through it keeps the budget.
"""

from __future__ import annotations

import math

from .frame import NH

__all__ = ["Chains"]

#: Start headings of the chains :meth:`Chains.reaches` indexes (the candidates' start headings).
STARTS = 4


def _least(table: dict, state: tuple, cost: float) -> None:
    if cost < table.get(state, math.inf):
        table[state] = cost


class Chains:
    """The kept primitives of a lattice, by start and end heading, and their short chains.

    Attributes
    ----------
    kept : list of list of tuple
        ``kept[h]``: ``(di, dj, h1, cost)`` of the kept primitives from heading ``h``, in the
        order added.
    """

    def __init__(self) -> None:
        self.kept: list[list[tuple[int, int, int, float]]] = [[] for _ in range(NH)]
        #: ``(h0, di, dj, cost)`` of the kept primitives by end heading.
        self._into: list[list[tuple[int, int, int, float]]] = [[] for _ in range(NH)]
        #: ``[h0][h1]``: ``(di, dj, cost)`` of the kept primitives from ``h0 < STARTS`` to ``h1``.
        self._ending: list[list[list]] = [[[] for _ in range(NH)] for _ in range(STARTS)]
        #: ``[h0]``: the least cost of the chains of at most two kept primitives from
        #: ``(0, 0, h0)`` to each state (none: ``(0, 0, h0)`` itself, for 0.0).
        self._prefix: list[dict] = [{(0, 0, h0): 0.0} for h0 in range(STARTS)]

    def add(self, h0: int, di: int, dj: int, h1: int, cost: float) -> None:
        """Keep the primitive from ``(0, 0, h0)`` to ``(di, dj, h1)`` of LONGD ``cost`` (> 0)."""
        self.kept[h0].append((di, dj, h1, cost))
        self._into[h1].append((h0, di, dj, cost))
        if h0 < STARTS:  # the new chains that start with it
            self._ending[h0][h1].append((di, dj, cost))
            prefix = self._prefix[h0]
            _least(prefix, (di, dj, h1), cost)
            for di2, dj2, h2, c2 in self.kept[h1]:
                _least(prefix, (di + di2, dj + dj2, h2), cost + c2)
        for s in range(STARTS):  # those that end with it
            for di1, dj1, c1 in self._ending[s][h0]:
                _least(self._prefix[s], (di1 + di, dj1 + dj, h1), c1 + cost)

    def reaches(self, h0: int, target: tuple, budget: float) -> bool:
        """Does a chain of at most three kept primitives from ``(0, 0, h0)`` (``h0 < 4``) reach
        ``target`` ``(i, j, h1)`` for at most ``budget``? (The breadth-first search's answer.)"""
        ti, tj, th = target
        prefix = self._prefix[h0]
        for h, di, dj, c in self._into[th]:  # the last step, after the cheapest prefix to its start
            least = prefix.get((ti - di, tj - dj, h))
            if least is not None and not least + c > budget:
                return True
        return False
