"""One helper for the tests that hold our Dubins and Reeds-Shepp lengths against OMPL's: the
distance of OMPL's state space of radius ``R`` (skips the test without OMPL's bindings)."""

import pytest


def ompl_distance(space: str, R: float):
    """``distance(p, q)`` of OMPL's ``DubinsStateSpace`` (``space="dubins"``) or
    ``ReedsSheppStateSpace`` (``"reedsshepp"``) of radius ``R``; poses ``(x, y, yaw)``."""
    ob = pytest.importorskip("ompl.base")
    s = ob.DubinsStateSpace(R) if space == "dubins" else ob.ReedsSheppStateSpace(R)
    a, b = s.allocState(), s.allocState()

    def distance(p, q):
        a.setX(p[0]), a.setY(p[1]), a.setYaw(p[2])
        b.setX(q[0]), b.setY(q[1]), b.setYaw(q[2])
        return s.distance(a, b)

    return distance
