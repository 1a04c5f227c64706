"""A forward robot's last escape (issue 25): hops, single unions to poses off the lattice's
headings and offsets, tried where every pair of tight arcs failed
(:func:`segplan.planning.lattice.escape.hop_pairs`, :func:`segplan.planning.lattice.search._escape`).

The floors are the floor-kinds study's two that OMPL's BIT* solves and the default planner did
not before the hops (``segplan.studies.floor_kinds``): clutter-097 (the start runs along a wall
past an obstacle, the lattice exhausted after 29 expansions) and robots-086 (the goal looked
enclosed to the start's lattice)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_lattice_oracles import dense_collides

import segplan
from segplan.model.pose import Pose
from segplan.planning.context import workspace_of
from segplan.planning.lattice import escape
from segplan.planning.lattice import search as lattice
from segplan.planning.links import LinkModel
from segplan.studies import floor_kinds as fk
from segplan.viz.metrics import measure_scenario_path, plan_poses

FLOORS = [("clutter", 97), ("robots", 86)]


@pytest.mark.parametrize(("kind", "index"), FLOORS)
def test_hop_pairs_are_single_hops_free_and_cheapest_first(kind, index):
    sc = fk.kind_floor(kind, index)
    links = LinkModel(workspace_of(sc))
    pairs = escape.hop_pairs(sc, links)
    assert pairs
    estimates = [est for est, _, _ in pairs]
    assert estimates == sorted(estimates)
    kmax = sc.robot.max_curvature * (1 + 1e-6)
    for _, a, b in pairs:
        assert (a is None) != (b is None)  # one hop, at one end
        arc = a if a is not None else b
        (u,) = arc.unions
        assert arc.link_directions == (1,)
        end = Pose(*sc.start) if a is not None else Pose(*sc.goal)
        assert (arc.first if a is not None else arc.last) == end
        assert np.abs(u.curvature(u.xs(2001))).max() <= kmax
    chain = type("Chain", (), {"unions": tuple((a or b).unions[0] for _, a, b in pairs)})
    assert not dense_collides(chain, sc)  # the dense oracle: every hop is free


@pytest.mark.parametrize(("kind", "index"), FLOORS)
def test_hops_solve_the_floors_the_arcs_did_not(kind, index, monkeypatch):
    sc = fk.kind_floor(kind, index)
    plan = segplan.plan_scenario(sc)
    measured = measure_scenario_path(plan_poses(plan, 0.01), sc)
    assert not measured.collides
    assert measured.max_curvature <= sc.robot.max_curvature * (1 + 1e-6)
    assert math.isclose(plan.cost, measured.front_length, rel_tol=1e-3)
    monkeypatch.setattr(lattice, "HOP_ESCAPES", 0)  # without the hops: no plan
    with pytest.raises(segplan.NoPathError, match="searches between tight arcs"):
        segplan.plan_scenario(sc)
