"""Issue 26, reverse motion, step 1: ``Robot(..., reverse=...)``, scenario files, the CLI's ``--reverse``."""

import dataclasses
import json
import math

import pytest

from segplan import Robot, ScenarioError, load_scenario
from segplan.floor.scenario import loads_scenario, with_clearance


def test_robot_is_forward_only_by_default():
    assert Robot(1.0).reverse is False
    assert Robot(1.0, 0.2, math.radians(40), reverse=True).reverse is True


@pytest.mark.parametrize("bad", [1, 0, "yes", None, 1.0])
def test_robot_reverse_must_be_a_bool(bad):
    with pytest.raises(ValueError, match="reverse"):
        Robot(1.0, reverse=bad)


def test_scenario_file_reverse_round_trip():
    sc = load_scenario("fig5_example1")
    assert sc.robot.reverse is False and "reverse" not in sc.to_dict()  # files of today unchanged
    data = sc.to_dict() | {"reverse": True}
    back = loads_scenario(json.dumps(data))
    assert back.robot.reverse is True and back.to_dict()["reverse"] is True
    assert loads_scenario(back.to_json()).robot == back.robot


@pytest.mark.parametrize("bad", [1, "true", None])
def test_scenario_file_reverse_must_be_a_bool(bad):
    data = load_scenario("fig5_example1").to_dict() | {"reverse": bad}
    with pytest.raises(ScenarioError, match="reverse must be true or false"):
        loads_scenario(json.dumps(data))


def test_clearance_keeps_reverse():
    sc = load_scenario("fig5_example1")
    sc = dataclasses.replace(sc, robot=dataclasses.replace(sc.robot, reverse=True))
    assert with_clearance(sc, 0.05).robot.reverse is True


def test_plan_takes_reverse():
    """segplan.plan(..., reverse=True) plans the dead-end bay with a cusp; forward only it has no path."""
    from pathlib import Path

    import segplan

    bay = segplan.load_scenario(
        Path(__file__).resolve().parents[1] / "scenarios/beyond_the_paper/dead_end_bay.json"
    )
    args = (tuple(bay.start), tuple(bay.goal), [o.tolist() for o in bay.outlines], bay.L, bay.bounds)
    kw = {"half_width": bay.robot.half_width, "max_steer": bay.robot.max_steer}
    assert segplan.plan(*args, **kw, reverse=True).cusps
    with pytest.raises(segplan.NoPathError):
        segplan.plan(*args, **kw)
    with pytest.raises(ValueError, match="reverse"):
        segplan.plan(*args, **kw, reverse="yes")
