"""The goal's approach tree ranks its states by one Dubins length per state, one by one for a
small tree (:meth:`segplan.planning.lattice.approach.GoalApproach.connect`, issue 25: numpy's
per-call overhead made the vectorised call cost 185 us for a single state).

The two ways must rank alike: the scalar and the vectorised Dubins length agree to rounding
(``tests/test_lattice.py`` compares them on random poses), and a plan that goes through
many small-tree connections is the same either way. rooms-001 of the floor-kinds study
(``segplan.studies.floor_kinds``) calls ``connect`` over 200 times with at most 32 approach
states before it plans (counted when written)."""

from __future__ import annotations

import math

import numpy as np

import segplan
from segplan.planning.dubins import dubins_length, dubins_length_scalar
from segplan.planning.lattice import approach
from segplan.studies import floor_kinds as fk


def _plan_counting(monkeypatch):
    """rooms-001's plan, and how many ``connect`` calls saw a tree of at most
    :data:`approach._SCALAR_DUBINS` states."""
    seen = {"small": 0}
    connect = approach.GoalApproach.connect

    def counted(self, *args, **kwargs):
        seen["small"] += len(self.keys) <= approach._SCALAR_DUBINS
        return connect(self, *args, **kwargs)

    monkeypatch.setattr(approach.GoalApproach, "connect", counted)
    plan = segplan.plan_scenario(fk.kind_floor("rooms", 1), time_limit=120.0)
    return plan, seen["small"]


def test_a_small_tree_ranks_as_the_vectorised_call(monkeypatch):
    plan, small = _plan_counting(monkeypatch)
    assert small > 50  # the scalar path was taken, many times
    monkeypatch.setattr(approach, "_SCALAR_DUBINS", -1)  # always the vectorised call
    again, small_again = _plan_counting(monkeypatch)
    assert small_again == 0
    assert again.nodes == plan.nodes  # the same chain, node by node
    assert again.cost == plan.cost


def test_scalar_and_vectorised_dubins_agree_on_approach_like_poses():
    rng = np.random.default_rng(25)
    poses = rng.uniform((-3.0, -3.0, -math.pi), (3.0, 3.0, math.pi), size=(32, 3))
    vec = dubins_length(0.4, -0.2, 0.7, poses[:, 0], poses[:, 1], poses[:, 2], 1.3)
    one = [dubins_length_scalar(0.4, -0.2, 0.7, x, y, t, 1.3) for x, y, t in poses.tolist()]
    # the same formulas; math's and numpy's transcendental functions differ by an ulp or so
    np.testing.assert_allclose(one, vec, rtol=1e-13, atol=0.0)
