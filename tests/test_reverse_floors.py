"""The floors that need reverse gear (issue 26; segplan.studies.reverse_floors).

- deterministic (pinned keys of floor 0 of each kind), valid scenarios with free start and goal;
- their geometry as the docstring states it, measured with shapely as an independent oracle:
  the bay start is nose-in (front wheel close to the back wall, walls on both sides), the
  reverse-park goal is backed in (its rear close to the back wall, heading out), the dead-end
  bay is narrower than the robot's turning circle, the k-turn corridor narrower than a U-turn;
- bad kinds and indices are refused.
"""

import math

import numpy as np
import pytest
import shapely

from segplan.studies import reverse_floors as rf
from segplan.studies.floors import floor_key

#: floor_key of floor 0 of each kind at GENERATOR_VERSION 1: a change of any floor must bump
#: the version (stored OMPL runs name it) and update these.
PINNED = {
    "bay-out": "bca4b74cb608",
    "reverse-park": "23e2958d3df2",
    "dead-end": "a08480e7d821",
    "k-turn": "c8418d3eca70",
}
N_TEST = 12


@pytest.fixture(scope="module")
def floors():
    return {kind: [rf.reverse_floor(kind, i) for i in range(N_TEST)] for kind in rf.REVERSE_KINDS}


def test_pinned_and_deterministic(floors):
    assert {k: floor_key(v[0]) for k, v in floors.items()} == PINNED
    assert floor_key(rf.reverse_floor("k-turn", 5)) == floor_key(floors["k-turn"][5])


def test_free_named_and_inside(floors):
    for kind, scs in floors.items():
        for i, sc in enumerate(scs):
            assert sc.name == f"{kind}-{i:03d}"
            assert "reverse_floors v1" in sc.description
            assert sc.is_free(sc.start) and sc.is_free(sc.goal)


def _ahead(sc, pose, sign: float) -> float:
    """Free distance (m, model) ahead of the front wheel (sign 1) or behind the rear point
    (sign -1) along the heading, by shapely on the enlarged obstacles and the shrunk walls."""
    x, y, th = pose
    L = sc.robot.L
    u = np.array([math.cos(th), math.sin(th)])
    p = np.array([x, y]) + (L * u if sign > 0 else 0.0)
    ray = shapely.LineString([p, p + sign * 50.0 * u])
    fb = sc.free_bounds
    solid = shapely.union_all([shapely.Polygon(q) for q in sc.enlarged] + [shapely.box(*fb).exterior])
    hit = ray.intersection(solid)
    return shapely.Point(p).distance(hit)


def test_bay_poses(floors):
    for sc in floors["bay-out"]:
        assert _ahead(sc, sc.start, 1.0) < 0.35 * sc.robot.L  # nose-in: 0.1-0.3 L (+ a bisection step)
    for sc in floors["reverse-park"]:
        assert _ahead(sc, sc.goal, -1.0) < 0.35 * sc.robot.L  # backed in, heading out
    for sc in floors["dead-end"]:
        assert sc.robot == rf.DEAD_END_ROBOT
        assert _ahead(sc, sc.start, 1.0) < 0.35 * sc.robot.L
        x, y, th = sc.start
        side = np.array([-math.sin(th), math.cos(th)])
        mid = np.array([x, y]) + 0.5 * sc.robot.L * np.array([math.cos(th), math.sin(th)])
        walls = shapely.union_all([shapely.Polygon(q) for q in sc.obstacles])
        across = sum(
            shapely.Point(mid).distance(walls.intersection(shapely.LineString([mid, mid + s * 5.0 * side])))
            for s in (1.0, -1.0)
        )
        # walls on both sides, closer than a turning circle's diameter
        assert across < 2.0 * sc.robot.min_turning_radius


def test_corridor(floors):
    for sc in floors["k-turn"]:
        w = sc.bounds[3] - sc.bounds[1]
        assert rf.CORRIDOR_WIDTH[0] <= w <= rf.CORRIDOR_WIDTH[1]
        assert not sc.obstacles
        assert math.cos(sc.start[2]) > 0.9 and math.cos(sc.goal[2]) < -0.9
        assert sc.start[0] < sc.goal[0]


@pytest.mark.parametrize("kind, index", [("bays", 0), ("k-turn", -1), ("k-turn", 1.5)])
def test_bad_input(kind, index):
    with pytest.raises(ValueError):
        rf.reverse_floor(kind, index)
