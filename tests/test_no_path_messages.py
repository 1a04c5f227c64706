"""A failure says what happened, and no more than is known.

The paper's search says what its node generation found (it knows nothing of the floor beyond
its sparse graph, so it never suggests an enclosed goal); the lattice says when the start is a
dead end for a robot that drives forward only (a bay walled on three sides, nose in).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import segplan
from segplan.cli import EXIT_NO_PATH, main
from segplan.planning.lattice.dead_end import DEAD_END_TURN, goal_way_out, start_dead_end

#: A 20 x 12 m floor with a bay at its east wall, 3 m wide (2.1 m after the enlargement) and
#: 7 m deep; the robot (L 1.5 m, half-width 0.45 m, turning radius 1.5 m) starts in it nose in.
BAY = [[(13, 3.9), (20, 3.9), (20, 4.5), (13, 4.5)], [(13, 7.5), (20, 7.5), (20, 8.1), (13, 8.1)]]
ROBOT = segplan.Robot(1.5, 0.45, math.radians(45))


def _bay(start, goal) -> segplan.Scenario:
    return segplan.make_scenario(ROBOT, start, goal, BAY, (0, 0, 20, 12), name="bay")


NOSE_IN = _bay((16.0, 6.0, 0.0), (3.0, 6.0, math.pi))


def test_a_nose_in_start_in_a_bay_is_a_dead_end_for_a_forward_only_robot():
    with pytest.raises(segplan.NoPathError) as info:
        segplan.plan_scenario(NOSE_IN)
    exc = info.value
    message = str(exc)
    assert exc.reason == "exhausted"
    assert "the start looks like a dead end" in message and "drives forward only" in message
    assert "no reverse gear" in message and "cannot turn around in the space ahead of it" in message
    assert "enclosed" not in message
    assert "not a proof that no path exists" in message  # the lattice's exhaustion is not one


def test_the_paper_search_says_what_its_node_generation_found():
    """After one expansion, with the goal in the open: what the node generation found, not a
    question about an enclosed goal that nothing established."""
    with pytest.raises(segplan.NoPathError) as info:
        segplan.plan_scenario(NOSE_IN, planner="paper")
    exc = info.value
    assert exc.reason == "exhausted" and exc.expanded == exc.generated == 1
    message = str(exc)
    assert "the paper's node generation" in message
    assert "found no collision-free successor of the start" in message and "enclosed" not in message
    # after more expansions: how many, and still no claim about the floor
    nose_out_goal = _bay((3.0, 6.0, 0.0), (16.0, 6.0, math.pi))
    with pytest.raises(segplan.NoPathError) as info:
        segplan.plan_scenario(nose_out_goal, planner="paper")
    exc = info.value
    assert exc.reason == "exhausted" and exc.expanded > 1
    assert f"found no new collision-free successor after {exc.expanded} expansions" in str(exc)
    assert "enclosed" not in str(exc) and "not a proof that no path exists" in str(exc)


def test_no_dead_end_where_the_robot_turned():
    """The note needs every try to have stayed within DEAD_END_TURN of the start's heading."""
    stayed = [(0.2, "exhausted", 0, (2.0, math.radians(27))), (0.1, "exhausted", 0, (2.2, DEAD_END_TURN))]
    note = start_dead_end(stayed)
    assert "within 2.2 m of the start" in note and "at most 90 deg" in note
    turned = [stayed[0], (0.1, "exhausted", 0, (2.2, math.radians(117)))]
    assert start_dead_end(turned) is None


def test_the_command_says_it_in_one_line(tmp_path, capsys):
    path = segplan.save_scenario(NOSE_IN, tmp_path / "bay.json")
    assert main(["plan", str(path)]) == EXIT_NO_PATH
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith("segplan: no path: ") and "drives forward only" in err[0]
    assert main(["plan", str(path), "--json"]) == EXIT_NO_PATH
    data = json.loads(capsys.readouterr().out)
    assert data["reason"] == "exhausted" and "no reverse gear" in data["message"]


def test_tight_arc_searches_cut_by_the_expansion_limit_say_so():
    """large-001 of the kind floors: the lattice from the start runs out at once (a start the
    lattice cannot leave), the searches between tight arcs at the ends would join (the
    planner's own limit solves it) but 1000 expansions stop them after two: the reason is the
    limit, not "exhausted", and the message says to raise it."""
    from segplan.studies import floor_kinds

    sc = floor_kinds.kind_floor("large", 1)
    with pytest.raises(segplan.NoPathError) as info:
        segplan.plan_scenario(sc, max_expansions=1000, time_limit=60)
    assert info.value.reason == "expansions" and info.value.expanded == 1000
    assert "max_expansions=1000 was reached before the rest were tried" in str(info.value)


def test_a_search_between_arcs_stopped_by_the_enclosure_limit_does_not_blame_max_expansions():
    """clutter-001 of the kind floors with chapter 12's rectangular body: the goal looks
    enclosed, the one search between tight arcs stops at the lattice's own enclosure limit
    after a few hundred expansions, far below ``max_expansions``: the message names that
    limit and does not say that ``max_expansions`` was reached (it said so before)."""
    from dataclasses import replace

    from segplan.studies import floor_kinds

    base = floor_kinds.kind_floor("clutter", 1)
    robot = replace(base.robot, front_overhang=0.2, rear_overhang=0.3, rectangle=True)
    sc = segplan.make_scenario(robot, base.start, base.goal, base.outlines, base.bounds)
    with pytest.raises(segplan.NoPathError) as info:
        segplan.plan_scenario(sc, max_expansions=20_000, time_limit=120.0)
    message = str(info.value)
    assert info.value.expanded < 20_000
    assert "max_expansions=20000 was reached" not in message
    assert "stopped at the lattice's own limit (its goal looked enclosed" in message


#: The bay's goal nose out (facing the bay's open side): a forward-only robot enters the bay
#: facing in and cannot turn round in it, so the lattice runs to its limit.
NOSE_OUT_GOAL = _bay((3.0, 6.0, 0.0), (16.0, 6.0, math.pi))
WAY_OUT = "the goal looks like the way out of a dead end"


def test_a_goal_facing_out_of_a_bay_is_named_when_the_lattice_stops_at_its_limit():
    """The expansion limit: the message says which limit, then what the lattice laid out at
    the goal showed (every state that reaches the goal faces the bay's way out)."""
    with pytest.raises(segplan.NoPathError) as info:
        segplan.plan_scenario(NOSE_OUT_GOAL, max_expansions=2000)
    exc = info.value
    message = str(exc)
    assert exc.reason == "expansions" and exc.expanded == 2000
    assert "the expansion limit max_expansions=2000 was reached" in message
    assert WAY_OUT in message and "drives forward only" in message and "no reverse gear" in message
    assert "as far as the lattice shows" in message and message.endswith("expanded 2000 states")
    turn = float(message.split("face at most ")[1].split(" deg")[0])
    assert turn <= math.degrees(DEAD_END_TURN)


def test_the_time_limit_keeps_what_the_lattice_said_about_the_goal():
    """A time-out's message names the call's time limit (``default._named_limits``) and keeps
    the lattice's note about the goal."""
    with pytest.raises(segplan.NoPathError) as info:
        segplan.plan_scenario(NOSE_OUT_GOAL, time_limit=0.5)
    exc = info.value
    message = str(exc)
    assert exc.reason == "time" and "the time limit time_limit=0.5 s was reached" in message
    assert WAY_OUT in message and message.endswith(f"expanded {exc.expanded} states")


def test_no_way_out_note_for_an_open_goal_or_a_robot_that_reverses():
    """An open goal (reached from every side) cut short by the limit, and the bay's goal for a
    robot with reverse gear: the limit only, no claim about the goal."""
    open_goal = _bay((3.0, 6.0, math.pi), (8.0, 9.0, 0.5 * math.pi))
    with pytest.raises(segplan.NoPathError) as info:
        segplan.plan_scenario(open_goal, max_expansions=40)
    assert info.value.reason == "expansions" and WAY_OUT not in str(info.value)
    reversing = segplan.make_scenario(
        segplan.Robot(1.5, 0.45, math.radians(45), reverse=True),
        (3.0, 6.0, 0.0), (16.0, 6.0, math.pi), BAY, (0, 0, 20, 12), name="bay",
    )  # fmt: skip
    try:
        segplan.plan_scenario(reversing, max_expansions=50)
    except segplan.NoPathError as e:
        assert WAY_OUT not in str(e)


class _Approach:
    """The parts of a goal's approach tree that :func:`goal_way_out` reads (one that ran out
    of states: its own states are those that reach the goal)."""

    keys = [(0, 0, 0)]
    exhausted = True

    def __init__(self, goal, poses):
        self.goal, self.poses = goal, np.asarray(poses, dtype=float).reshape(-1, 3)


def test_the_way_out_note_needs_every_state_that_reaches_the_goal_to_face_its_way():
    goal = (5.0, 2.0, math.pi)  # facing west: the states that reach it lie east of it
    behind = [(5.0 + d, 2.0, math.pi + t) for d, t in ((0.5, 0.1), (1.5, -0.4), (3.0, 0.2))]
    note = goal_way_out(_Approach(goal, behind))
    assert note is not None and "the 3 states" in note and "within 3 m" in note and "at most 23 deg" in note
    turned = behind + [(6.0, 3.0, math.pi + DEAD_END_TURN + 0.05)]  # one faces round further
    assert goal_way_out(_Approach(goal, turned)) is None
    edge = behind + [(6.0, 3.0, math.pi - DEAD_END_TURN)]  # exactly the bound: still a way out
    assert goal_way_out(_Approach(goal, edge)) is not None
    assert goal_way_out(_Approach(goal, [])) is None  # nothing reaches it: not this note
