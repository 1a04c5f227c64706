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


def test_reverse_study_compares_with_both_ompl_spaces():
    """segplan with reverse gear on one bay-out floor, against fake OMPL tables: the floor
    needs reverse when Reeds-Shepp solves it and Dubins does not; ratio and cusps as stated."""
    import pandas as pd

    from segplan.studies import reverse_study as rs
    from segplan.studies import robustness as rb

    sc = rf.reverse_floor("bay-out", 0)
    rev = rs.with_reverse(sc)
    assert rev.robot.reverse and not sc.robot.reverse and len(rev.obstacles) == len(sc.obstacles)
    seg = rs.run_segplan(["bay-out"], 1)
    assert seg.loc[0, "floor_key"] == floor_key(sc) and seg.loc[0, "solved"] and seg.loc[0, "valid"]

    def ompl(solved: bool, front: float, reversals: int) -> pd.DataFrame:
        row = dict.fromkeys(rb.OMPL_COLUMNS, float("nan"))
        row.update(group="bay-out", floor=sc.name, floor_key=floor_key(sc), planner="BITstar", budget=5.0)
        row.update(seed=1, solved=solved, valid=solved, simplified_valid=solved, front_length=front)
        row.update(simplified_front_length=front, reversals=reversals)
        return pd.DataFrame([row])

    front = float(seg.loc[0, "front_length"])
    table = rs.compare(seg, ompl(True, 2 * front, 3), ompl(False, float("nan"), 0))
    assert table.loc[0, "needs_reverse"] and table.loc[0, "ratio"] == pytest.approx(0.5)
    s = rs.summary(table).iloc[0]
    assert (s["needs_reverse"], s["solved_of_those"], s["invalid"], s["ompl_cusps_median"]) == (1, 1, 0, 3.0)
    assert s["cusps_median"] == seg.loc[0, "cusps"]
    table = rs.compare(seg, ompl(True, front, 3), ompl(True, front, 0))
    assert not table.loc[0, "needs_reverse"]
    with pytest.raises(ValueError, match="scenario"):
        rs.with_reverse("bay-out-000")
