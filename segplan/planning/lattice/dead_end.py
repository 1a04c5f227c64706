"""What a forward-only robot's failed lattice search says about its ends (beyond the paper).

A robot without reverse gear cannot turn round in a pocket narrower than its turns: a start
facing into one (a bay walled on three sides, nose in) cannot be left, a goal facing out of one
(the closed end of an aisle, nose out) cannot be reached. When the lattice fails, these notes
say so in the :class:`segplan.planning.plan.NoPathError`'s message, as far as the lattice shows
(never a proof: a union may still get where the lattice's primitives do not), with the hint that
reverse gear (``Robot(..., reverse=True)``) would let the default planner back out or in.
:func:`start_dead_end` reads an exhausted lattice's reach
(:func:`segplan.planning.lattice.search.lattice_search`), :func:`goal_way_out` the goal's
approach tree of a search stopped by a limit (:class:`segplan.planning.lattice.approach.GoalApproach`).
"""

from __future__ import annotations

import math

import numpy as np

from ...model.pose import wrap_floor

__all__ = ["DEAD_END_TURN", "GOAL_DEAD_END_STATES", "goal_way_out", "start_dead_end"]

#: The largest turn from the start's heading (radians) of every state an exhausted lattice
#: reached, at or below which the start is reported as a dead end for a forward-only robot:
#: it never faced sideways, let alone back the way it came.
DEAD_END_TURN = 0.5 * math.pi


def start_dead_end(proofs: list) -> str | None:
    """What an exhausted lattice says first when no state it reached (at every resolution
    tried, ``proofs``) turned more than :data:`DEAD_END_TURN` from the start's heading: the
    robot drives forward only and cannot turn around in the space ahead of its start (a bay
    walled on three sides, nose in). None otherwise."""
    distance = max(p[3][0] for p in proofs)
    turn = max(p[3][1] for p in proofs)
    if turn > DEAD_END_TURN:
        return None
    return (
        "the start looks like a dead end: the robot drives forward only (no reverse gear: "
        "Robot(..., reverse=True) or segplan plan --reverse lets the default planner back out) "
        "and cannot turn around in the space ahead of it, as far as the lattice "
        f"shows: every state it reached lies within {distance:.3g} m of the start and faces at most "
        f"{math.degrees(turn):.0f} deg away from the start's heading; a start facing into a dead "
        "end (a bay walled on three sides, nose in) needs reversing out"
    )


#: States of the goal's lattice up to which :func:`goal_way_out` counts those that reach the
#: goal (more, and it says nothing). Set by hand from the five warehouse floors of
#: :mod:`segplan.studies.floor_kinds` that end at the expansion limit (BIT* solves none),
#: measured on 2026-12-07 after a 1.5 s time limit: 2306, 939, 3573 and 627 states reach the
#: goals of 027, 036, 071 and 083 (the flood fill 0.02-0.12 s), 11 236 that of 092 (the
#: screen-only fill gets past its rack end; 0.07 s to give up); not tuned.
GOAL_DEAD_END_STATES = 4000


def goal_way_out(approach) -> str | None:
    """What a forward robot's lattice that ran to a limit says about its goal when the goal
    looks like a dead end seen from the other side: every state of the lattice laid out at the
    goal from which a chain of primitives reaches it
    (:meth:`segplan.planning.lattice.approach.GoalApproach.reach_all`, at most
    :data:`GOAL_DEAD_END_STATES`; its tree's states if it ran out of them) faces at most
    :data:`DEAD_END_TURN` away from the goal's heading: the goal faces out of a pocket (the
    closed end of an aisle, nose out), which a forward-only robot enters facing the other
    way and cannot turn round in. None otherwise (no tree built yet, more states, or one that
    faces further round). As far as the lattice shows, like :func:`start_dead_end`: a union from
    the start's lattice may still reach the goal."""
    if approach.keys is None:
        return None
    poses = approach.poses if approach.exhausted else approach.reach_all(GOAL_DEAD_END_STATES)
    if poses is None or not len(poses):
        return None
    goal = np.asarray(approach.goal, dtype=float)
    turn = float(np.abs(wrap_floor(poses[:, 2] - goal[2])).max())
    if turn > DEAD_END_TURN:
        return None
    distance = float(np.hypot(poses[:, 0] - goal[0], poses[:, 1] - goal[1]).max())
    return (
        "the goal looks like the way out of a dead end: the robot drives forward only (no "
        "reverse gear: Robot(..., reverse=True) or segplan plan --reverse lets the default "
        f"planner back in), and the {len(poses)} states of the lattice laid out at the goal "
        f"that reach it lie within {distance:.3g} m of it and face at most "
        f"{math.degrees(turn):.0f} deg away from its heading, as far as the lattice shows; a "
        "goal facing out of a pocket (the closed end of an aisle, nose out) cannot be reached "
        "by a robot that enters the pocket facing in and cannot turn round there"
    )
