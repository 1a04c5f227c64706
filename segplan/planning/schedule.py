"""The lattice planner's expansion schedule: when each of its mechanisms starts, and how much it does.

Beyond the paper (issue 12; gathered in one record by issue 24). The A* of
:mod:`segplan.planning.lattice.astar` runs plain weighted A* first; mechanisms for the hard
floors join it after so many expansions without a plan: the goal's approach tree and its
enclosure test (:mod:`segplan.planning.lattice.approach`), the coarse cost-to-go
(:mod:`segplan.planning.lattice.guide`); after a search, the tight arcs
(:mod:`segplan.planning.lattice.escape`) and the shortcuts of a found plan
(:mod:`segplan.planning.lattice.search`). Every count and limit that decides when and how much
is a field of :class:`Schedule`, documented with the measurement that set it, or with the
commit that set it by hand where none is recorded. :data:`SCHEDULE` is the default, the values
every plan of the package is made with.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from .checks import check_option

__all__ = ["SCHEDULE", "Schedule"]


@dataclass(frozen=True)
class Schedule:
    """Expansion counts and limits of the lattice planner (module docstring).

    Counts of expansions are those of one search (one resolution); "at ``L / 8``" means the
    value at the default resolution, scaled where noted.

    Attributes
    ----------
    approach_after : int
        Expansions before the goal's approach tree is built (the search may reach the goal
        by a direct union alone). Set by hand in 5ef841b; not measured.
    approach_limit : int
        States of the approach tree when first built. Set by hand in 5ef841b; not measured.
    approach_tries : int
        Unions built from an expanded state near the goal to the most promising approach
        states (after :attr:`approach_candidates` are screened by
        :func:`segplan.planning.lattice.approach.steerable`); 0: none (the tree serves the
        enclosure test only). Set by hand in 5ef841b; not measured.
    approach_candidates : int
        Approach states, the most promising first by ``g`` + Dubins length + their cost,
        screened by ``steerable`` before the :attr:`approach_tries` unions. Set by hand in
        755f729; not measured.
    steer_slack : float
        ``steerable`` keeps a pose whose sampled peak curvature is below ``steer_slack`` times
        the steering limit (the coarse samples misjudge some unions; a heuristic that only
        orders the tries). Set by hand in 755f729; not measured.
    enclosure_after : int
        Expansions without a plan after which the goal's enclosure test counts the states
        that reach the goal and the approach tree grows (:attr:`approach_growth`). Set by
        hand in 755f729; not measured.
    enclosure_limit : int
        States (at ``L / 8``; times 4 per halving of the resolution and ``(R / L)^2`` for a
        robot turning wider than ``L``, 621d5a3) up to which the enclosure test counts: more,
        and the goal does not look enclosed. Set by hand in 755f729. 3000 tried (issue 25,
        2026-12-06, not adopted): of the 500 30 x 20 m floors of
        :mod:`segplan.studies.floor_kinds` with the planner's own limits, three warehouses
        whose goal faces the closed end of an aisle (027, 036, 083; 627-2306 states reach
        their goals, OMPL's BIT* solves none) failed in 0.4-0.7 s instead of at the 10 s
        time limit, no plan changed; but the robots probe's robot-58 (``benchmarks/robots.py``),
        which plans after 85 078 expansions in 29 s, looked enclosed (1084 states) and failed
        (``benchmarks/same_plans.py``). Each state counted costs a union from the start when
        the goal looks enclosed (:meth:`segplan.planning.lattice.approach.GoalApproach.start_joins`:
        about 0.35 ms each, 4 s for the 11 236 of warehouse-092).
    approach_growth : int
        States the approach tree grows to at :attr:`enclosure_after` (at ``L / 8``; scaled
        as :attr:`enclosure_limit`). Measured (621d5a3, was 300): on the 400 random floors
        of chapter 9, growing it to 300 found no plan that 120 did not.
    enclosed_expansions : int
        Expansions the search goes on once the goal looks enclosed, before it stops (not a
        proof: a union from the start's lattice may still reach the goal). Measured
        (4d8cc7e, was 512): on chapter 9's 400 random floors, 100 floors with walls close
        ahead and 80 floors of varied robots, the plans found after the goal looked enclosed
        came 34 and 125 expansions later; the same successes and lengths, failures end
        sooner (median 461 -> 296 ms on the 400 floors).
    guide_after : int
        Expansions without a plan after which the coarse cost-to-go
        (:class:`segplan.planning.lattice.guide.HeadingField`) is built and re-ranks the open
        list. Measured (5fdf5b3, was 200): on the 400 random floors, median plan time of the
        solved floors about 67 -> 52 ms, the same median and worst length ratio; any-164
        (1444 expansions with the guide at 64) no longer solved within 1000.
    guided_weight : float
        The weight on ``h'`` once the guide is built (at most the search's own: a closer
        estimate needs less weight). Set with the guide in 4f681d4, whose measurement is of the
        guide as a whole (400 random floors: any headings 137 -> 149 of OMPL's 149 solved);
        this value alone not measured. A weight of its own for guides built over a window
        (:attr:`guide_window`) was tried and not kept (issue 25, 2026-12-07, two runs at a
        time on this project's 2-core machine, the default limits): at 1.4 on the first 100
        "large" sites of :mod:`segplan.studies.floor_kinds` 42 instead of 40 of the 43 floors
        OMPL's BIT* solves planned (none lost), the 100 calls took 159 instead of 186 s and
        the plans' mean length was unchanged; but on the held-out large sites 100-199 it
        planned the same 89 floors, 44 plans longer and 22 shorter (mean +0.57 %, largest
        +24.6 %), 160 instead of 170 s. (1.6 and 2.0 for every guide, on the first 50 floors of
        each 30 x 20 m kind: no faster median, longer worst plans, rooms 1.365 -> 1.462.)
    escalate_every : int
        Expansions without a plan, once the guide is built, after which the weight on ``h'``
        is multiplied by :attr:`escalate_factor` and the open list re-ranked (again at each
        multiple; a forward robot only, as the guide). Where the guide's estimate times the
        weight is about the fine lattice's cost-to-go, ``g + h'`` is about the same over a
        wide band of states and the search floods it (issue 25, large-071: the estimate at
        0.84 of the found chain's cost-to-go along it, 239 k states generated). Set above the
        most expansions any planned 30 x 20 m floor of :mod:`segplan.studies.floor_kinds`
        needed (rooms-055, 14 625, ``benchmarks/results/expansions_needed/``), so no plan
        found there within it changes; chapters 9 and 11 stop far below it
        (:data:`segplan.studies.robustness.MAX_EXPANSIONS`).
    escalate_factor : float
        The factor of :attr:`escalate_every` (1: the weight stays). Measured (issue 25,
        2026-12-07, this project's 2-core machine, two runs at a time, the default limits,
        ``time_limit`` 10 s) on the "large" sites of :mod:`segplan.studies.floor_kinds`
        against the tree without it: on the first 100, 1.15 planned 90 and 1.3 planned 91
        instead of 87 (1.3: 022, 044, 071, 098 gained, none lost; of the 43 floors OMPL's BIT*
        solves, 071 gained), no plan found both ways changed; chosen there, 1.3. On the
        held-out sites 100-199: 88 instead of 85 (152, 154, 157, 162 gained; 105, planned
        after 35 744 expansions in 8.1 s, lost at the time limit), of the 84 plans found both
        ways two changed (124 4.0 % shorter, 170 5.1 % longer), 1.15 planned 87.
        ``benchmarks/same_plans.py --kinds 10`` (540 floors): one plan changed, any-061 (113 k
        expansions), 17.561 -> 18.014 m. Not yet stored as a run of its own.
    guide_window : (float, float, float)
        ``(a, b, c)``: where the coarse cost-to-go over the whole grid would exceed
        :data:`segplan.planning.lattice.guide.MAX_STATES` states (floors of more than about
        100 x 100 m for ``L`` = 1.5 m), it is built over the cells (and their neighbours)
        through which the rear point's shortest route over the free cells
        (:meth:`segplan.planning.lattice.clearance.DistanceField.corridor`) grows by at most
        ``a L + b R + c D`` (``D`` that route's length); until 2026-12-07 over their box, which
        held 1.4-2.3 times the corridor's states on the first 8 large sites (see
        :data:`segplan.planning.lattice.guide.MAX_BOX_STATES`). Measured (issue 25) on the "large"
        sites of :mod:`segplan.studies.floor_kinds` (111-185 x 75-125 m, ``D`` 30-150 m):
        without a guide 4 of the first 10 were solved within the 10 s time limit; with the
        guide over the window all 10 (figures in ``benchmarks/results/floor_kinds_*``); a
        window of ``(4, 4, 0.1)`` holds every plan found with the whole grid's guide (built
        there for the measurement, 0.6-2 s a floor) and builds in a fraction of that time.
    deadline_every : int
        Expansions between two looks at the clock (the time limit). Set by hand in 4a98571;
        not measured.
    grid_margin : (float, float)
        ``(a, b)``: on floors without walls the clearance grid covers the obstacles, start and
        goal with a margin of ``a L + b R`` (beyond it every point counts as that far from any
        obstacle), also the margin of the grid's size estimate. Set by hand in 4a98571; not
        measured.
    max_escapes : int
        Searches at most between the inner poses of tight arcs when the lattice fails. Set by
        hand in 4f681d4; not measured.
    improve_gap : float
        A found plan is worth improving by tight arcs when it costs more than this many times
        the Dubins length of its ends. Set by hand in 4f681d4; not measured.
    wide_turn_cells : int
        A robot turning wider than usual gets a coarser lattice: the default resolution is
        ``R / wide_turn_cells`` where that exceeds ``L / 8`` (at most ``L``), so its
        primitives (about ``(R / resolution)^2`` candidate end cells) stay as many as those
        of a robot with ``R = wide_turn_cells L / 8`` (4 L: steering limit 14 deg). 32
        (issue 25): on Fig. 5's floor with a 5 deg (3 deg) steering limit the primitives
        took 9 s (23 s) and 164 MB (323 MB) at ``L / 8`` before the search began (measured
        before the primitive sets were computed 3-4x faster in issue 25: about 1.7 s of CPU
        for the 5 deg set at ``L / 8`` since; the measurement was not repeated); every
        robot of the book, the robots probe (25-60 deg) and chapter 9 turns tighter than
        4 L and keeps ``L / 8``.
    shortcut_window : int
        Nodes ahead that the greedy shortcuts of a found plan try to reach by one union. Set
        by hand in aff5201; not measured.
    """

    approach_after: int = 32
    approach_limit: int = 60
    approach_tries: int = 2
    approach_candidates: int = 8
    steer_slack: float = 1.1
    enclosure_after: int = 256
    enclosure_limit: int = 300
    approach_growth: int = 120
    enclosed_expansions: int = 192
    guide_after: int = 64
    guided_weight: float = 1.2
    escalate_every: int = 20_000
    escalate_factor: float = 1.3
    guide_window: tuple[float, float, float] = (4.0, 4.0, 0.1)
    deadline_every: int = 64
    grid_margin: tuple[float, float] = (4.0, 4.0)
    max_escapes: int = 16
    improve_gap: float = 1.3
    shortcut_window: int = 16
    wide_turn_cells: int = 32

    def __post_init__(self):
        # float fields: (the bound, whether it is allowed)
        floats = {"steer_slack": (0.0, False), "guided_weight": (1.0, True), "improve_gap": (0.0, False)}
        floats["escalate_factor"] = (1.0, True)
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in ("grid_margin", "guide_window"):
                n = 2 if f.name == "grid_margin" else 3
                if not (isinstance(value, tuple) and len(value) == n):
                    what = "a pair (a, b)" if n == 2 else "a triple (a, b, c)"
                    raise ValueError(f"{f.name} must be {what} of numbers >= 0, got {value!r}")
                for v in value:
                    check_option(v, f.name, 0.0, lo_ok=True)
            elif f.name in floats:
                lo, lo_ok = floats[f.name]
                check_option(value, f.name, lo, lo_ok=lo_ok)
            else:
                check_option(value, f.name, 0 if f.name == "approach_tries" else 1, integer=True, lo_ok=True)
                if not isinstance(value, int):
                    raise ValueError(f"{f.name} must be an integer >= 1, got {value!r}")

    def guide_box(self, field, L: float, R: float, scale: float = 1.0):
        """The window of the coarse cost-to-go (:attr:`guide_window`, its slack times ``scale``)
        from the lattice's origin, the start: ``field``'s corridor
        (:class:`segplan.planning.lattice.clearance.Corridor`), or None."""
        a, b, c = self.guide_window
        return field.corridor((0.0, 0.0), scale * (a * L + b * R), scale * c)

    def margin(self, L: float, R: float) -> float:
        """The clearance grid's margin on floors without walls: ``a L + b R`` (:attr:`grid_margin`)."""
        a, b = self.grid_margin
        return a * L + b * R


#: The default schedule: every plan of the package is made with it.
SCHEDULE = Schedule()
