"""The lattice frame: lattice states and world poses, and a primitive's union from a state (beyond the paper).

A lattice (issue 12) has square cells of side ``r`` and the 16 *grid-aligned* headings of
:data:`HEADING_VECTORS`. Laid out at a world pose ``(x0, y0, theta0)`` (the start's, for the
search of :mod:`segplan.planning.lattice.astar`; the goal's, for the approach tree of
:mod:`segplan.planning.lattice.approach`), its state ``(i, j, h)`` is the rear point

    ``(x0, y0) + rot(theta0) (i r, j r)``  heading ``theta0 + angle(h)``

(:meth:`LatticeFrame.pose`). A motion primitive (:class:`segplan.planning.lattice.primitives.Primitive`)
from state ``(i, j, h)`` ends at ``(i + di, j + dj, h1)``; its union is the paper's cubic
(section "Union of two nodes") between the two states' world poses, in the primitive's
stored intrinsic frame (its alpha, chord and headings: a union's shape does not change under
a rigid motion), :meth:`LatticeFrame.union`. Every part of the lattice planner makes its
poses and unions here.
"""

from __future__ import annotations

import math

import numpy as np

from ...model.pose import Pose
from ...model.union import Union

__all__ = ["HEADING_VECTORS", "NH", "LatticeFrame", "heading_angles"]

#: The 16 grid-aligned headings, as integer direction vectors (counter-clockwise from +x).
HEADING_VECTORS = (
    (1, 0), (2, 1), (1, 1), (1, 2), (0, 1), (-1, 2), (-1, 1), (-2, 1),
    (-1, 0), (-2, -1), (-1, -1), (-1, -2), (0, -1), (1, -2), (1, -1), (2, -1),
)  # fmt: skip
#: The number of lattice headings.
NH = len(HEADING_VECTORS)


def heading_angles() -> np.ndarray:
    """World angles (radians, in ``(-pi, pi]``) of the 16 lattice headings (in a frame laid out at
    heading 0)."""
    return np.array([math.atan2(y, x) for x, y in HEADING_VECTORS])


_ANGLES = heading_angles()


class LatticeFrame:
    """A lattice of cell ``r`` laid out at the world pose ``origin`` (module docstring).

    Parameters
    ----------
    origin : (x, y, theta)
        World pose of the state ``(0, 0, 0)``.
    r : float
        Cell size (m).
    L : float
        Robot length (m): the unions' segment.
    """

    def __init__(self, origin, r: float, L: float):
        self.x, self.y, self.theta = origin
        self.c, self.s = math.cos(self.theta), math.sin(self.theta)
        self.r, self.L = r, L

    def pose(self, key) -> tuple[float, float, float]:
        """World pose of lattice state ``key = (i, j, h)`` (``h`` modulo :data:`NH`: the search
        of a robot that may reverse marks a state reached backwards by ``h + NH``,
        :mod:`segplan.planning.lattice.reverse`)."""
        i, j, h = key
        x, y = i * self.r, j * self.r
        return (
            self.x + self.c * x - self.s * y,
            self.y + self.s * x + self.c * y,
            self.theta + float(_ANGLES[h % NH]),  # h + NH: the same heading after a reverse link
        )

    @staticmethod
    def end(key, p) -> tuple[int, int, int]:
        """The state primitive ``p`` reaches from state ``key``."""
        return (key[0] + p.di, key[1] + p.dj, p.h1)

    def union(self, key, p) -> Union:
        """The union of primitive ``p`` from state ``key``, between the two states' world poses."""
        P0 = Pose(*self.pose(key))
        P1 = Pose(*self.pose((key[0] + p.di, key[1] + p.dj, p.h1)))
        psi = math.atan2(P1.y - P0.y, P1.x - P0.x)
        return Union.from_intrinsic(P0, P1, p.alpha, self.L, p.d, psi, p.phi0, p.phi1)
