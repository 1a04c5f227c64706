"""One planning call's shared state: the scenario, its one validity checker, the deadline, counters.

:func:`segplan.plan_scenario` makes one :class:`PlanningContext` per call, after checking
its options and doing the off-line work (the paper: "the processing of the model of the
surroundings ... is performed off-line"), and hands it to the stages (the paper's search,
the lattice, the refinement). The context's clock starts when it is made: the
:class:`Deadline` of the call's ``time_limit`` counts from there, and the plan's
``seconds`` is measured once, by the entry point, from the same start.
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass

from ..floor.scenario import Scenario
from .links import LinkModel
from .validity import Workspace

__all__ = ["Deadline", "PlanningContext", "Progress", "workspace_of"]


def workspace_of(scenario: Scenario) -> Workspace:
    """The validity checker of a scenario: its enlarged obstacles, the robot's length,
    overhangs and steering limit, the walls moved in by ``half_width`` (:class:`Workspace`);
    a rectangular body's exact tests (:attr:`segplan.Scenario.body`)."""
    robot = scenario.robot
    return Workspace(
        scenario.enlarged, robot.L, scenario.free_bounds, robot.max_curvature,
        rear=robot.rear_overhang, front=robot.front_overhang, body=scenario.body,
    )  # fmt: skip


class Deadline:
    """``limit`` seconds of wall time from ``start`` (``time.perf_counter()``, monotonic).

    Parameters
    ----------
    limit : float
        Seconds (> 0; checked by the options).
    start : float, optional
        ``time.perf_counter()`` at the start; default now.
    """

    def __init__(self, limit: float, start: float | None = None):
        self.limit = float(limit)
        self.start = time.perf_counter() if start is None else float(start)

    @property
    def at(self) -> float:
        """The deadline itself, on the ``time.perf_counter()`` clock."""
        return self.start + self.limit

    def elapsed(self) -> float:
        """Seconds since the start."""
        return time.perf_counter() - self.start

    def left(self) -> float:
        """Seconds left (negative once past)."""
        return self.limit - (time.perf_counter() - self.start)

    def expired(self) -> bool:
        """True once more than ``limit`` seconds have passed (the searches' own test)."""
        return time.perf_counter() - self.start > self.limit

    def __repr__(self) -> str:
        return f"Deadline(limit={self.limit:g} s, left={self.left():.3g} s)"


@dataclass(frozen=True)
class Progress:
    """What a planning call is doing, as handed to its ``progress`` callback
    (:func:`segplan.plan_scenario`).

    Attributes
    ----------
    stage : str
        ``"paper"`` (the paper's search), ``"lattice"`` or ``"refine"``.
    event : str
        ``"start"``, ``"expanded"`` (the lattice search, every
        :attr:`segplan.planning.schedule.Schedule.deadline_every` expansions) or ``"done"``.
    seconds : float
        Since the call's start.
    limit : float
        The call's ``time_limit`` (s).
    expanded : int
        States expanded so far by the stage's current search (0 at ``"start"``).
    cost : float or None
        At ``"done"``: the LONGD of the stage's plan (None: no plan).
    """

    stage: str
    event: str
    seconds: float
    limit: float
    expanded: int = 0
    cost: float | None = None


class PlanningContext:
    """The state of one planning call (module docstring).

    Attributes
    ----------
    scenario : Scenario
        The scenario planned on (with the call's clearance applied).
    options : PaperOptions or DefaultOptions or None
        The call's options (:mod:`segplan.planning.options`).
    deadline : Deadline
        The call's ``time_limit``, from the moment the context was made.
    workspace : Workspace
        The scenario's one validity checker, built once per call and shared by the stages
        (on a large floor its set-up is a large share of the planning time), or the one
        handed in (:class:`segplan.Planner` keeps one per floor: it must be the scenario's,
        :func:`workspace_of`); its counters (``stats``) add up over the stages.
    progress : callable or None
        The call's ``progress`` callback (:meth:`report`).
    counters : collections.Counter
        What the stages did: ``"<stage>_runs"``, ``"<stage>_plans"``, ``"<stage>_expanded"``
        for the stages ``paper``, ``lattice``, ``refine``; ``"stopped_by_time"`` where the
        time limit cut the lattice short after the paper's search found a plan
        (``Plan.stopped``).
    """

    def __init__(
        self,
        scenario: Scenario,
        time_limit: float,
        options=None,
        workspace: Workspace | None = None,
        progress: Callable[[Progress], object] | None = None,
    ):
        if not isinstance(scenario, Scenario):
            raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
        self.scenario = scenario
        self.options = options
        self.deadline = Deadline(time_limit)
        self.workspace = workspace_of(scenario) if workspace is None else workspace
        self.counters: Counter = Counter()
        self.progress = progress

    def report(self, stage: str, event: str, expanded: int = 0, cost: float | None = None) -> None:
        """Hand a :class:`Progress` to the call's ``progress`` callback, if any (it only
        watches: the plan does not depend on it; an exception it raises ends the call)."""
        if self.progress is not None:
            d = self.deadline
            self.progress(Progress(stage, event, d.elapsed(), d.limit, expanded, cost))

    def link_model(
        self, alpha_method: str = "heuristic", steer_fallback: bool = True, observer=None
    ) -> LinkModel:
        """A :class:`LinkModel` (unions and their costs, cached) of the context's workspace."""
        return LinkModel(self.workspace, alpha_method, steer_fallback, observer)

    def count(self, stage: str, plan=None, expanded: int = 0) -> None:
        """Count one run of ``stage``: with its plan (or None) and its expansions."""
        self.counters[f"{stage}_runs"] += 1
        self.counters[f"{stage}_plans"] += plan is not None
        self.counters[f"{stage}_expanded"] += expanded
