"""Legs along tight circles: the chains of short unions that the lattice's escapes are made of.

Beyond the paper (issues 12 and 26). The lattice's tightest primitives turn at about ``1.12
R`` (:mod:`segplan.planning.lattice.primitives`); a chain of short symmetric unions along a
circle turns much tighter: a union that turns by :data:`STEP` (11.25 deg) peaks less than 1 %
above the circle's curvature, so the chain keeps the steering limit on a circle of radius
:data:`RADIUS_FACTORS` ``x R``. Such a chain, driven one way from a pose on one side of it, is a
*leg*; the unions of a leg are congruent (each the first one's frame, moved along the circle).
The tight arcs, the turn-arounds and the hops' neighbours of
:mod:`segplan.planning.lattice.escape` are legs and chains of legs.

:class:`Legs` drives each leg once per planning call: the escapes, the improvement of a found
plan and every tolerance of its turn-arounds ask for the same legs again and again, with other
stops and lengths.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ...model.pose import Pose, arc_end, intrinsic_interval, wrap_ieee
from ...model.union import Union
from ..links import LinkModel
from ..plan import union_longd

__all__ = ["LEG_STEPS", "RADIUS_FACTORS", "STEP", "Legs", "circle_pose"]

#: Turn of one union of a leg (radians).
STEP = math.radians(11.25)
#: Radii tried (times ``R``): the smallest whose union keeps the steering limit is used.
RADIUS_FACTORS = (1.01, 1.03, 1.06, 1.1)
#: Unions of one leg at most (a leg of 32 x :data:`STEP` turns a full circle).
LEG_STEPS = 32


def circle_pose(p: Pose, rho: float, side: int, turn: float) -> Pose:
    """:func:`segplan.model.pose.arc_end` of ``p`` as a Pose, its heading in ``[-pi, pi]``."""
    x, y, th = arc_end(p.x, p.y, p.theta, rho, side, turn)
    return Pose(x, y, wrap_ieee(th))


@dataclass
class _Leg:
    """One leg as far as it was driven: its start, side, direction and radius (None: no radius
    of :data:`RADIUS_FACTORS` keeps the steering limit), its ``(union, pose)`` so far, whether
    it ended at a union that is not free, and its first union's LONGD once asked for."""

    start: Pose
    side: int
    direction: int
    rho: float | None
    got: list = field(default_factory=list)
    ended: bool = False
    piece: float | None = None

    def __post_init__(self):
        self.ended = self.ended or self.rho is None


class Legs:
    """The free legs along tight circles driven so far in one planning call, each driven once.

    A leg (:meth:`leg`) is the chain of congruent unions along the tight circle on one side of
    a pose, driven one way; the same leg is asked for many times over (the turn-arounds of
    every tolerance of :data:`segplan.planning.lattice.escape.IMPROVE_NEAR`, share of
    :data:`segplan.planning.lattice.escape.IMPROVE_SHARES` and start, the
    escapes' and the improvement's arcs: 1663 requests of 566 legs on the reverse study's
    k-turn-004), with other stops and lengths. Each is kept by where it starts, its side and
    its direction, with whether it ended at a union that is not free; a request is answered
    from it (cut where its own ``stop`` holds or after its own ``steps``) and driven further
    only beyond what was driven: every answer is the one a leg driven afresh gives, union for
    union. Made by the caller for one scenario and link model (``links``, ``R``) and passed
    on; caching is the caller's choice (a fresh one per call gives the same arcs).
    """

    @staticmethod
    def checked(legs: Legs | None, links: LinkModel, R: float) -> Legs:
        """``legs``, checked to be of ``links`` and ``R`` (ValueError otherwise); a new
        :class:`Legs` if None."""
        if legs is None:
            return Legs(links, R)
        if legs.links is not links or legs.R != float(R):
            raise ValueError("legs were driven with another link model or turning radius")
        return legs

    def __init__(self, links: LinkModel, R: float):
        self.links, self.R = links, float(R)
        self._known: dict[tuple, _Leg] = {}  # by (pose, side, direction)

    def leg(self, p: Pose, side: int, direction: int, stop, steps: int = LEG_STEPS) -> list[tuple]:
        """``(union, pose)`` of the free unions along the tight circle on ``side`` of ``p``
        (the smallest radius of :data:`RADIUS_FACTORS` whose first union keeps the steering
        limit: the shape is the same all along), each turning by :data:`STEP`, driven
        ``direction``, at most ``steps`` of them, until one is not free or ``stop(pose)``; each
        union stored as a plan stores its link (:attr:`segplan.Plan.directions`: a reverse
        link is the forward union from its far node to its near one)."""
        kept = self._kept(p, side, direction)
        out: list = []
        while len(out) < steps and (len(out) < len(kept.got) or self._drive(kept)):
            out.append(kept.got[len(out)])
            if stop(out[-1][1]):
                break
        return out

    def piece(self, p: Pose, side: int, direction: int) -> float:
        """LONGD [1] of the first union of a leg asked for before (every union of it is
        congruent: it stands for each); 0 for a leg without one."""
        kept = self._known[(p, side, direction)]
        if kept.piece is None:
            kept.piece = union_longd(kept.got[0][0]) if kept.got else 0.0
        return kept.piece

    def _kept(self, p: Pose, side: int, direction: int) -> _Leg:
        """The kept leg of ``p``, ``side`` and ``direction``, none of its unions driven yet if new."""
        key = (p, side, direction)
        kept = self._known.get(key)
        if kept is None:
            kept = self._known[key] = _Leg(p, side, direction, self._radius(p, side, direction))
        return kept

    def _drive(self, kept: _Leg) -> bool:
        """Drive ``kept`` one union further; False (and the leg ended) if that union is not free."""
        if kept.ended:
            return False
        links, p, side = self.links, kept.start, kept.side
        k = len(kept.got) + 1
        q = circle_pose(p, kept.rho, side, (1.0 if kept.direction > 0 else -1.0) * k * STEP)
        cur = kept.got[-1][1] if kept.got else p
        a, b = (cur, q) if kept.direction > 0 else (q, cur)
        u1 = (
            kept.got[0][0] if kept.got else None
        )  # every later union is congruent to it (its frame, moved along)
        geo = None if u1 is None else intrinsic_interval(a, b)
        if geo is not None and geo[4] < u1.alpha < geo[5]:
            d, psi, phi0, phi1, _, _ = geo
            u = Union.from_intrinsic(a, b, u1.alpha, u1.L, d, psi, phi0, phi1)
        else:
            u = links.union(a, b)
        if u is None or not links.ws.union_free(u):
            kept.ended = True
            return False
        kept.got.append((u, q))
        return True

    def _radius(self, p: Pose, side: int, direction: int) -> float | None:
        """The smallest radius of :data:`RADIUS_FACTORS` times ``R`` whose first union keeps
        the steering limit; None if none does."""
        links, sign = self.links, 1.0 if direction > 0 else -1.0
        for f in RADIUS_FACTORS:
            q = circle_pose(p, f * self.R, side, sign * STEP)
            u = links.union(p, q) if direction > 0 else links.union(q, p)
            if u is not None and links.ws.curvature_ok(u):
                return f * self.R
        return None
