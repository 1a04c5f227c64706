"""Many plans on one floor for one robot: the floor's off-line work done once.

Beyond the paper. The paper does "the processing of the model of the surroundings"
off-line; :func:`segplan.plan` does it on every call (the polygons checked and split into
convex pieces, enlarged by the half-width, the validity checker set up). A robot that
plans many start and goal pairs on one map does it once with a :class:`Planner`:

>>> import math, segplan
>>> planner = segplan.Planner([[(4, 2), (6, 2), (6, 6), (4, 6)]], segplan.Robot(1.0, 0.3, math.radians(45)),
...                           bounds=(0, 0, 10, 8))
>>> a = planner.plan((1, 1, 0), (8.3, 7, 0))
>>> b = planner.plan((1, 7, 0), (8.3, 1, 0))

Every plan is the plan :func:`segplan.plan_scenario` makes of the same scenario and
options: the planner keeps the :class:`segplan.floor.scenario.PreparedFloor` (checked,
split and enlarged obstacles) and the :class:`segplan.planning.validity.Workspace` (its
arrays of the obstacles: circles, boxes, vertices, edge normals), nothing that depends on
a start or goal. (The motion primitives and the fitted coefficients are kept per process
already, by every call.)
"""

from __future__ import annotations

import dataclasses
import math

from ..floor.scenario import Robot, Scenario, prepare_floor
from .api import _apply, _run, options_of
from .context import workspace_of
from .options import DefaultOptions, PaperOptions
from .plan import Plan

__all__ = ["Planner"]


class Planner:
    """Plans on one floor for one robot, its off-line work done once (module docstring).

    Parameters
    ----------
    obstacles : sequence of polygons, or a segplan.Floor
        As :func:`segplan.plan`'s (a map from :func:`segplan.load_ros_map` too).
    robot : segplan.Robot
    bounds : (xmin, ymin, xmax, ymax), optional
        The walls (a Floor's own bounds when None).
    heuristic, **options
        :func:`segplan.plan_scenario`'s, checked here, once (``clearance`` included: the
        obstacles are enlarged by ``half_width + clearance`` once).

    Raises
    ------
    ValueError
        Bad options, naming the argument; ``segplan.ScenarioError`` (a ``ValueError``) for a
        bad robot, bounds or polygon.

    Attributes
    ----------
    robot : segplan.Robot
    options : PaperOptions or DefaultOptions
        The checked options every plan is made with.
    floor : segplan.floor.scenario.PreparedFloor
        The obstacles checked, split and enlarged (by ``half_width + clearance``).
    """

    def __init__(self, obstacles, robot: Robot, bounds=None, heuristic: str = "a", **options):
        if not isinstance(robot, Robot):
            raise ValueError(f"robot must be a segplan.Robot, got {type(robot).__name__}")
        self.robot = robot
        self.options: PaperOptions | DefaultOptions = options_of(heuristic, **options)
        clearance = self.options.clearance
        grown = robot
        if clearance > 0:
            grown = dataclasses.replace(robot, half_width=robot.half_width + clearance)
        source = "Planner" if clearance == 0 else f"Planner (clearance={clearance:g})"
        self.floor = prepare_floor(grown, obstacles, bounds, source=source)
        self._workspace = None
        # the scenario's options: the clearance is already in the enlarged obstacles
        self._applied = dataclasses.replace(self.options, clearance=0.0)

    def scenario(self, start, goal, *, name: str = "") -> Scenario:
        """The scenario of ``start`` and ``goal`` on the planner's floor (radians), with its
        clearance applied (``segplan.ScenarioError`` for a pose that is not free)."""
        source = "Planner.plan"
        if self.options.clearance > 0:
            source += f" (clearance={self.options.clearance:g} m beyond half_width={self.robot.half_width:g})"
        return self.floor.scenario(start, goal, name=name, source=source)

    def plan(self, start, goal, progress=None) -> Plan:
        """The plan from ``start`` to ``goal`` (``(x, y, theta)``, radians): the plan of
        :func:`segplan.plan_scenario` on :meth:`scenario` with the planner's options
        (``progress``: its callback).

        Raises
        ------
        segplan.ScenarioError
            A start or goal that is malformed or not free.
        segplan.NoPathError
            No plan within the options' limits.
        """
        scenario = self.scenario(start, goal)
        scenario, applied = _apply(scenario, self._applied)
        ws = self._workspace
        if ws is None:
            ws = self._workspace = workspace_of(scenario)
        else:  # the counters describe one call
            ws.reset()
        plan = _run(scenario, applied, workspace=ws, progress=progress)
        return dataclasses.replace(plan, options=self.options)

    def __repr__(self) -> str:
        name = "paper" if isinstance(self.options, PaperOptions) else "default"
        steer = math.degrees(self.robot.max_steer)
        return (
            f"Planner({len(self.floor.enlarged)} convex obstacles, L={self.robot.L:g}, "
            f"half_width={self.robot.half_width:g}, max_steer={steer:g} deg, {name} planner)"
        )
