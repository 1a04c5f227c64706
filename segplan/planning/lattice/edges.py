"""Deferred edge checks of the lattice search (beyond the paper; lazy collision checking).

The lattice search (:mod:`segplan.planning.lattice.search`) screens every primitive of an expanded state
on the clearance grid at once. A primitive the grid cannot clear (close to an obstacle)
needs a finer screen and maybe the certified test, yet most of the states it leads to are
never expanded: the weighted A* ends first. So such an edge enters the open list
*unchecked* and is checked only when its state is taken out of it, before the state is
expanded (lazy collision checking, as in Bohlin and Kavraki's lazy PRM and Cohen, Phillips
and Likhachev's lazy weighted A*). If it fails, the state is *repaired*: it gets the
cheapest edge into it from an expanded state that passes the check, and goes back into the
open list (or, without one, waits for a future parent). A state is expanded only through
a checked edge, so every expanded state, the plan included, is reached by edges that
passed the same test as before, and a state reachable through checked edges still enters
the open list: the search stays complete on the lattice. The goal's approach tree
(:mod:`segplan.planning.lattice.approach`) defers its checks the same way, until a state is settled.

Measured (same process, floors alternated): the same plans on the 400 random floors of
chapter 9, 100 floors with walls close ahead and 80 floors of varied robots; the 400
floors' total time down by 12 % (search) and a further 5 % (approach tree).
"""

from __future__ import annotations

import heapq
import math

__all__ = ["DeferredChecks"]


class DeferredChecks:
    """Mixin of the lattice search: unchecked edges and the repair of a state whose edge fails.

    Uses the search's ``into_steps`` (:meth:`into_tables`), ``step``, ``cost``, ``offsets``,
    ``delta``, ``fine``, ``grid``, ``q``, ``r``, ``start``, ``g``, ``parent``, ``heap``,
    ``banned``, :meth:`union` and :meth:`certified`.
    """

    def into_tables(self) -> list:
        """Per heading ``h1``: ``(h0, m, di, dj)`` of the primitives that end at heading ``h1``."""
        into: list = [[] for _ in self.step]
        for h0, steps in enumerate(self.step):
            for m, (di, dj, h1) in enumerate(steps):
                into[h1].append((h0, m, di, dj))
        return into

    def edge_free(self, key, m: int) -> bool:
        """The finer screen and, if still unsure, the certified test of primitive ``m`` from
        state ``key``."""
        i, j, h = key
        fp, fd = self.fine[h]
        world = (fp[m] + (i * self.r, j * self.r)) @ self.grid.rot.T + (self.start.x, self.start.y)
        return self.certified(lambda: self.union(key, m), world, fd[m] + 1e-9)

    def repair(self, key, closed: set, failed: set, h: float, counter: int) -> int:
        """State ``key``'s edge failed its check: give it the cheapest edge from an expanded
        state (in ``closed``) that passes (grid screen, then :meth:`edge_free`), not in
        ``failed`` nor banned, and push it again with ``h'`` = ``h``; without one, forget its
        ``g``. Returns the next heap counter."""
        i, j, h1 = key
        lower = self.grid.lower_blocked_flat
        options = []
        for h0, m, di, dj in self.into_steps[h1]:
            prev = (i - di, j - dj, h0)
            if prev not in closed or (prev, m) in failed or (prev, m) in self.banned:
                continue
            options.append((self.g[prev] + self.cost[h0][m], prev, m))
        options.sort()
        for ng, prev, m in options:
            b = self.grid.base(prev[0] * self.q, prev[1] * self.q)
            if b is None:
                continue
            least = lower[self.offsets[prev[2]][m] + b].min()
            if least == -math.inf:
                continue
            if least > self.delta[prev[2]][m] or self.edge_free(prev, m):
                self.g[key], self.parent[key] = ng, (prev, m)
                heapq.heappush(self.heap, (ng + h, counter, key))
                return counter + 1
            failed.add((prev, m))
        del self.g[key], self.parent[key]
        return counter
