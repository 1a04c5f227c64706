"""The planners' options: one frozen dataclass per planner, validated once, every tuning value a field.

:func:`segplan.plan_scenario` turns its keyword arguments into one of these at the door
(:class:`PaperOptions` for ``planner="paper"``, :class:`DefaultOptions` for the default
planner) and hands it to the planner; the :class:`segplan.Plan` returned records it
(``Plan.options``). Each field's documentation says where its default comes from: the
measurement that set it, or "set by hand in <commit>; not measured" where the history
records none. Bad values raise a ``ValueError`` naming the field, when the object is made.

The validators are the package's: :func:`segplan.planning.plan.check_option` (numbers),
:func:`check_choice` (one of a few strings) and :func:`check_flag` (True or False).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass

from .checks import check_option
from .schedule import SCHEDULE, Schedule

__all__ = [
    "ALPHA_METHODS",
    "COSTS",
    "HEURISTICS",
    "VERSIONS",
    "DefaultOptions",
    "LatticeOptions",
    "PaperOptions",
    "RefineOptions",
    "check_choice",
    "check_flag",
    "options_from_dict",
    "refine_options",
]

#: ``heuristic`` of the paper's search: ``h'`` (a), (b) or (c).
HEURISTICS = ("a", "b", "c")
#: ``cost`` of the paper's search: LONGD (the method) or the distance (the paper's baseline).
COSTS = ("longd", "distance")
#: ``version`` of the paper's search: Fig. 4's reference systems of intermediate nodes.
VERSIONS = ("b", "a")
#: ``alpha_method``: the optimal reference system's method.
ALPHA_METHODS = ("heuristic", "exact")


def check_choice(value, choices, name: str):
    """``value`` if it is one of ``choices``; else ValueError naming ``name`` and the choices."""
    if not isinstance(value, str) or value not in choices:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, choices))}, got {value!r}")
    return value


def check_flag(value, name: str) -> bool:
    """``value`` if it is True or False; else ValueError naming ``name``."""
    if not isinstance(value, bool):
        raise ValueError(f"{name} must be True or False, got {value!r}")
    return value


def _check_expansions(value) -> int:
    """A search's ``max_expansions``: an integer >= 1 (:func:`segplan.planning.plan.check_limits`'s rule)."""
    return check_option(value, "max_expansions", 1, integer=True, lo_ok=True)


def _fields_of(cls, data, name: str) -> dict:
    """``data`` (a ``to_dict()`` read back) as keyword arguments of ``cls``: a mapping with no
    unknown key, else ValueError naming ``name`` and the key."""
    if not isinstance(data, Mapping):
        raise ValueError(f"{name} must be a mapping of {cls.__name__} fields, got {type(data).__name__}")
    known = {f.name for f in dataclasses.fields(cls)}
    unknown = sorted(set(data) - known)
    if unknown:
        raise ValueError(f"{name} has no field {', '.join(map(repr, unknown))} ({cls.__name__})")
    return dict(data)


def _set(obj, name: str, value) -> None:
    """Store a validated (normalised) value on a frozen dataclass, in ``__post_init__``."""
    object.__setattr__(obj, name, value)


@dataclass(frozen=True)
class RefineOptions:
    """Options of the refinement beyond the paper (:func:`segplan.refine`).

    Attributes
    ----------
    rounds : int
        Rounds of splits and local moves, each followed by shortcuts (0: shortcuts only).
        1: set by hand in 9b77417; not measured.
    split : float
        Chords longer than ``split * L`` get a middle node in each round. 3: set by hand in
        2eed598; not measured.
    first_step, min_step : float
        First and smallest step of a node's local moves, units of ``L`` (turns: the same
        numbers in radians). 1/2 and 1/16: set by hand in 2eed598; not measured.
    max_sweeps : int
        Sweeps over the nodes per round, at most. 6 for :func:`segplan.refine` and the
        paper's planner: set by hand in 9b77417 (about 35 ms of refinement on Fig. 6); the
        default planner uses 3 (:class:`DefaultOptions`).
    min_gain : float
        Least decrease of a node's two link costs (units of ``L``) for a local move to be
        taken. 1e-3: set by hand in 2eed598; not measured.
    checks_per_update : int
        Screened moves checked exactly per node update. 1: set by hand in 9b77417 ("one
        exact check per node update"); not measured.
    moves : tuple of (forward, left, turn)
        Moves of a node in its own frame, in units of its step (turns in units of
        ``step / L`` radians): forward/back, left/right, turning left/right and the four
        combinations of a sideways move with a turn. Set by hand in 2eed598; not measured.
    max_chord : float or None
        Shortcuts consider the links between nodes at most ``max_chord * L`` apart (and
        every link checked before, whatever its length); None: every pair of nodes. 64:
        measured on 2026-12-03 (stress floors by ``benchmarks/stress_floor.py``'s floors, the
        others by the default planner with a 300 s limit, each plan's refinements under
        bounds of 16-64 L and None): on the 1 km stress floors 0-2 without a bound the
        refinement checked 2397-2792 links, 1156 of those of floor 0 longer than 80 L and
        none of them free (the longest free link of its shortcuts: 66 L), in 3.1-4.2 s of
        CPU; with 64 L 1188-1360 links in 0.52-0.71 s, the plans the same or at most
        0.00013 % longer (32 L: up to 0.02 %, 16 L: up to 0.1 %). On 10 large sites
        (``floor_kinds`` "large" 0-11; 8 and 10 have no plan) and 6 floors of 160 x 96 m
        with 512 obstacles (``plan_speed.py --large`` seeds 0-5) the refined plans were the
        same lengths with 48 L and 64 L (32 L: up to 0.17 % longer, 16 L: up to 5.7 %); on
        the 490 floors of ``benchmarks/same_plans.py`` (diagonals of 33 L at most) the bound
        never acts: every plan is the same, bit for bit.
    """

    rounds: int = 1
    split: float = 3.0
    first_step: float = 0.5
    min_step: float = 1.0 / 16.0
    max_sweeps: int = 6
    min_gain: float = 1e-3
    checks_per_update: int = 1
    moves: tuple = (
        (1, 0, 0),
        (-1, 0, 0),
        (0, 1, 0),
        (0, -1, 0),
        (0, 0, 1),
        (0, 0, -1),
        (0, 1, 1),
        (0, 1, -1),
        (0, -1, 1),
        (0, -1, -1),
    )
    max_chord: float | None = 64.0

    def __post_init__(self):
        _set(self, "rounds", check_option(self.rounds, "rounds", 0, integer=True, lo_ok=True))
        _set(self, "max_sweeps", check_option(self.max_sweeps, "max_sweeps", 0, integer=True, lo_ok=True))
        for name in ("split", "min_step", "first_step"):
            _set(self, name, check_option(getattr(self, name), f"{name} (units of L)", 0.0))
        if self.min_step > self.first_step:
            raise ValueError(f"min_step ({self.min_step!r}) must not exceed first_step ({self.first_step!r})")
        _set(self, "min_gain", check_option(self.min_gain, "min_gain (units of L)", 0.0, lo_ok=True))
        _set(self, "max_chord", check_option(self.max_chord, "max_chord (units of L)", 0.0, allow_none=True))
        _set(
            self,
            "checks_per_update",
            check_option(self.checks_per_update, "checks_per_update", 1, integer=True, lo_ok=True),
        )
        moves = self.moves
        if not (
            isinstance(moves, tuple | list)
            and moves
            and all(isinstance(m, tuple | list) and len(m) == 3 for m in moves)
        ):
            raise ValueError(f"moves must be a non-empty sequence of (forward, left, turn), got {moves!r}")
        for m in moves:
            for v in m:
                check_option(v, "moves (each component)", -math.inf)
        _set(self, "moves", tuple(tuple(m) for m in moves))

    def to_dict(self) -> dict:
        """Plain-JSON form."""
        out = dataclasses.asdict(self)
        out["moves"] = [list(m) for m in self.moves]
        return out

    @classmethod
    def from_dict(cls, data) -> RefineOptions:
        """The options of a :meth:`RefineOptions.to_dict` read back from JSON:
        ``from_dict(o.to_dict()) == o``."""
        return cls(**_fields_of(cls, data, "refine options"))


def refine_options(refine, default: RefineOptions | None) -> RefineOptions | None:
    """``refine`` of :func:`segplan.plan_scenario` (None, a bool, a dict or RefineOptions) as
    RefineOptions or None (no refinement); ``default`` is the planner's (for None and True)."""
    if refine is None:
        return default
    if refine is True:
        return default or RefineOptions()
    if refine is False:
        return None
    if isinstance(refine, RefineOptions):
        return refine
    if isinstance(refine, dict):
        return RefineOptions(**refine)
    raise ValueError(f"refine must be True, False or a dict of refine() options, got {refine!r}")


@dataclass(frozen=True)
class PaperOptions:
    """Options of the paper's search (``planner="paper"``; also the first stage of the default planner).

    Attributes
    ----------
    heuristic : {"a", "b", "c"}
        ``h'``: (a) LONGD of the direct union, (b) distance, (c) their weighted average
        (the paper's three choices). "a": set by hand in bb220de; not measured.
    cost : {"longd", "distance"}
        Link cost: LONGD (the method) or the distance between node points (the paper's
        baseline).
    version : {"b", "a"}
        Reference systems of intermediate nodes (Fig. 4); "b", one per piece, the paper's
        choice.
    ds : float or None
        Characteristic dimension of the surroundings for heuristic (c), m; None:
        :func:`segplan.planning.paper.problem.characteristic_dimension` of the enlarged
        obstacles (the paper's off-line step).
    alpha_method : {"heuristic", "exact"}
        Optimal reference system method (section "Optimal reference system").
    max_expansions : int
        Expansions before giving up. 3000: set by hand in bb220de; not measured.
    time_limit : float
        Seconds before giving up. 10: set by hand in bb220de; not measured. In
        :class:`DefaultOptions` derived: ``paper_share * time_limit``.
    max_turn_chain : int
        Longest chain of consecutive turn states (difficult cases): four quarter turns make
        a full circle (bb220de).
    expander : tuple of (name, value)
        Overrides of :class:`segplan.planning.paper.expansion.Expander`'s keyword arguments
        (``max_iterations``, ``r0``, ...; given as a dict); their defaults and checks are
        the Expander's ("chosen by trials on the shipped scenarios and on random worlds"),
        applied when the search builds it.
    refine : RefineOptions or None
        Refine the plan found (beyond the paper); None (the default): the search's plan as
        found.
    clearance : float
        Safety margin (m, >= 0) beyond ``half_width`` (0: the paper's model).
    """

    heuristic: str = "a"
    cost: str = "longd"
    version: str = "b"
    ds: float | None = None
    alpha_method: str = "heuristic"
    max_expansions: int = 3000
    time_limit: float = 10.0
    max_turn_chain: int = 4
    expander: tuple = ()
    refine: RefineOptions | None = None
    clearance: float = 0.0

    def __post_init__(self):
        check_choice(self.heuristic, HEURISTICS, "heuristic")
        check_choice(self.cost, COSTS, "cost")
        if self.version not in VERSIONS:  # the Expander's words
            raise ValueError(
                "version must be 'a' (one shared reference system) or 'b' (one per piece), "
                f"got {self.version!r}"
            )
        check_choice(self.alpha_method, ALPHA_METHODS, "alpha_method")
        _set(self, "ds", check_option(self.ds, "ds", 0.0, lo_ok=True, allow_none=True))
        _set(self, "max_expansions", _check_expansions(self.max_expansions))
        _set(self, "time_limit", check_option(self.time_limit, "time_limit", 0.0))
        _set(
            self,
            "max_turn_chain",
            check_option(self.max_turn_chain, "max_turn_chain", 0, integer=True, lo_ok=True),
        )
        expander = self.expander
        if isinstance(expander, Mapping):
            expander = tuple(expander.items())
        pairs = isinstance(expander, tuple) and all(isinstance(kv, tuple) and len(kv) == 2 for kv in expander)
        if not pairs:
            raise ValueError(f"expander must be a dict of Expander options, got {self.expander!r}")
        for name, _ in expander:
            if name in ("version", "alpha_method", "links") or not isinstance(name, str):
                raise ValueError(
                    f"expander may not set {name!r}: version and alpha_method are options of their own"
                )
        _set(self, "expander", expander)
        if self.refine is not None and not isinstance(self.refine, RefineOptions):
            raise ValueError(f"refine must be RefineOptions or None, got {self.refine!r}")
        _set(self, "clearance", check_option(self.clearance, "clearance (m)", 0.0, lo_ok=True))

    @property
    def expander_options(self) -> dict:
        """:attr:`expander` as keyword arguments."""
        return dict(self.expander)

    def to_dict(self) -> dict:
        """Plain-JSON form."""
        out = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        out["expander"] = {k: list(v) if isinstance(v, tuple) else v for k, v in self.expander}
        out["refine"] = None if self.refine is None else self.refine.to_dict()
        return out

    @classmethod
    def from_dict(cls, data) -> PaperOptions:
        """The options of a :meth:`PaperOptions.to_dict` read back from JSON:
        ``from_dict(o.to_dict()) == o`` (an expander value given as a list comes back a tuple,
        as :meth:`PaperOptions.to_dict` wrote it)."""
        kw = _fields_of(cls, data, "paper options")
        if isinstance(kw.get("expander"), Mapping):
            kw["expander"] = {k: tuple(v) if isinstance(v, list) else v for k, v in kw["expander"].items()}
        if kw.get("refine") is not None:
            kw["refine"] = RefineOptions.from_dict(kw["refine"])
        return cls(**kw)


@dataclass(frozen=True)
class LatticeOptions:
    """Options of the lattice search (:func:`segplan.planning.lattice.search.lattice_search`).

    The defaults are ``lattice_search``'s (a test pins them to its signature and to
    :data:`segplan.planning.lattice.search.LATTICE_MAX_EXPANSIONS`); the lattice's time is
    the rest of the call's (:class:`segplan.planning.context.Deadline`).

    Attributes
    ----------
    resolution : float or None
        Lattice cell size (m); None: ``L / 8``, then ``L / 16`` if ``retry`` (coarser on
        large floors). Set by hand in 4a98571; not measured.
    weight : float
        Factor on the admissible ``h'`` (>= 1; 1: the cheapest plan over the lattice). 2:
        set by hand in 4a98571 ("trades length, which the refinement wins back in part,
        for far fewer expansions"); not measured.
    retry : bool
        After an exhausted lattice, search once more at half the cell size.
    analytic_every : int
        Far from the goal, try the direct union every this many expansions. 8: set by hand
        in 4a98571; not measured.
    goal_radius : float or None
        Within this distance (m) of the goal every expanded state tries the direct union;
        None: ``2 R + L`` (:data:`segplan.planning.lattice.search.GOAL_RADIUS`; 8ae9308,
        was ``4 R + 2 L``: on 2 x 29 random floors the same lengths but one, +0.7 %, and the
        95th percentile of the plan time about halved).
    cell : float or None
        Cell size (m) of the clearance grid; None: half the finest resolution, not below
        ``L / 16``, coarser on large floors.
    escapes : bool
        Tight arcs out of the start and into the goal (:mod:`segplan.planning.lattice.escape`).
    max_expansions : int
        Expansions before giving up (200000, ``LATTICE_MAX_EXPANSIONS``): set by hand in
        4a98571 (the lattice's first cut). Measured on 2026-12-07 by
        ``benchmarks/expansions_needed.py`` (stored in
        ``benchmarks/results/expansions_needed/``; each call with this limit and a 60 s
        time limit, so that the counts are the same on any machine): the planned floors
        needing the most were, of the 500 30 x 20 m floor kinds, rooms-055 with 14 625
        (OMPL's BIT* solves it; 2.0 s) and warehouse-042 with 5 858; of chapter 9's 410
        random floors and hard cases, any-061 with 113 933 (8.8 s; BIT* at 5 s does not
        solve it); of the first 30 large sites, large-026 181 536 and large-022 156 024
        (BIT* solves neither) and large-006 64 879 (BIT* solves it); of 100 reverse floors
        (25 per kind, reverse gear), k-turn-006 3 305. The five 30 x 20 m floors that end at
        this limit (warehouse-027, 036, 071, 083, 092: goals facing out of a closed aisle
        end, BIT* solves none) take 15-31 s to it, so with the default ``time_limit`` of
        10 s they end by the time limit (about 140 000 expansions). A limit low enough to
        end them within a second (6 000-13 000 expansions there) would lose rooms-055, which
        BIT* solves, and the large sites; no single count separates the floors that plan
        from those that do not. Kept.
    schedule : Schedule
        When each of the lattice's mechanisms starts and how much it does
        (:class:`segplan.planning.schedule.Schedule`, each field with its provenance);
        default :data:`segplan.planning.schedule.SCHEDULE`.
    reverse_factor : float
        A robot that may reverse (``Robot(..., reverse=True)``, issue 26; unused otherwise):
        a reverse link costs this times its LONGD in the search (> 0; ``h'`` is scaled by
        ``min(1, reverse_factor)`` so that it stays a lower bound). 1.15 with
        ``cusp_penalty`` 0.5 since 2026-12-07 (the last walk below; 1.25 before). 1.25 was
        first measured on 2026-12-03 by ``benchmarks/reverse_defaults.py``
        (16 floors: the dead-end bay, 3 reverse parkings into it, 2 K-turns in corridors
        about two turning radii wide, chapter 9's natural floors 0-9; every pair of
        ``reverse_factor`` 1, 1.25, 1.5 and ``cusp_penalty`` 0.5, 2, 4 L; all 16 solved by
        every pair). The pairs with penalty 0.5 L gave the shortest plans (front-wheel
        lengths 169.8 m in all, against 171.4-183.5 m with 2 or 4 L; 10 cusps against 7-9)
        and the least CPU time (largest per plan 2.1-2.4 s, the K-turns, against 3.5-7.0
        s); of those, 1.25 the least (median 0.034 s, largest 2.06 s; 1.5 the same
        lengths; 1, free reversing, 0.8 % longer and a fifth of the length driven
        backwards). The bay: 11.85 m, one cusp. Walked again on 2026-12-03 over the
        reverse study's 400 floors (``benchmarks/reverse_costs.py``: pairs compared on the
        even floors of each kind, the best checked on the odd ones, lengths against OMPL's
        Reeds-Shepp BIT*): ``reverse_factor`` 1 or 1.1 made dead-ends longer (worst 1.22-1.25
        against 1.20), 1.5 bay-outs and K-turns (worst 1.29, 1.33); with 1.25, ``cusp_penalty``
        0.25 shortened the worst even K-turn (1.39 to 1.25) and changed nothing else beyond
        1 % (odd floors: the same success, cusps and worst, 1.38), but generated 23 % more
        states on the bay (757 against 615); 0.1 and 0 no shorter. Kept. Walked once more
        on 2026-12-03 after the K-turns' turn-arounds were searched over leg lengths and starts
        (the even floors, ``cusp_penalty`` 0.5): ``reverse_factor`` 1, 1.1, 1.15, 1.25 gave the
        same worst K-turn, 1.210 (k-turn-014, the same plan), k-turn medians 1.039, 1.042,
        1.049, 1.049, bay-out worst 1.168, 1.131, 1.131, 1.131 and dead-end worst 1.222, 1.200,
        1.200, 1.199; every floor solved alike. Kept. Walked again on 2026-12-07, after the
        turn-arounds may stop short of the goal's heading (``IMPROVE_NEAR`` of
        :mod:`segplan.planning.lattice.escape`), over the 400 floors with
        ``benchmarks/reverse_costs.py`` (``cusp_penalty`` 0.5 unless said; the rule: fewest
        floors over the 1.15 target on the even floors, then the lowest mean of the four
        kinds' median ratios; both halves were run at once and read before the rule was
        written down, so the odd floors confirm rather than test it). Even floors,
        ``reverse_factor`` 1, 1.05, 1.1, 1.15, 1.25 and 1 with ``cusp_penalty`` 0.25: floors
        over 1.15 2, 2, 1, 1, 2, 2 (dead-end-022, 1.20-1.25, in every walk); k-turn median
        1.021, 1.022, 1.022, 1.022, 1.035, 1.019 and worst 1.108, 1.108, 1.132, 1.132,
        1.176, 1.108; bay-out worst 1.168, 1.168, 1.112, 1.112, 1.131, 1.136; dead-end worst
        1.222, 1.222, 1.200, 1.200, 1.199, 1.247; mean of the medians 1.0046, 1.0022,
        1.0021, 1.0015, 1.0015, 1.0027: 1.15 (1.25's equal mean comes with k-turn-042 over
        1.15). On the odd floors 1.15 has no floor over
        1.15 (1.25: one, k-turn-043 at 1.165), k-turn median 1.021 (1.033) and worst 1.127
        (1.165), bay-out median 0.991 (0.987) and worst 1.116 (1.078), reverse-park worst
        1.079 and dead-end worst 1.086 (1.082); every floor solved alike, no plan invalid,
        median cusps at most OMPL's. Over all 400: k-turn median 1.034 to 1.021 and worst
        1.176 to 1.132; the worst floor is dead-end-022 (1.199 to 1.200).
    cusp_penalty : float
        A robot that may reverse: the cost of each change of direction, units of ``L``
        (>= 0), in the search and when the default planner compares its plans. 0.5: see
        ``reverse_factor`` (a larger penalty took out one cusp in 16 floors, at 1.4 % more
        length and 1.7 times the largest CPU time).
    """

    resolution: float | None = None
    weight: float = 2.0
    retry: bool = True
    analytic_every: int = 8
    goal_radius: float | None = None
    cell: float | None = None
    escapes: bool = True
    max_expansions: int = 200_000
    schedule: Schedule = SCHEDULE
    reverse_factor: float = 1.15
    cusp_penalty: float = 0.5

    def __post_init__(self):
        # the checks of lattice_options() that need no scenario (it adds resolution <= L)
        _set(self, "resolution", check_option(self.resolution, "resolution", 0.0, allow_none=True))
        _set(self, "weight", check_option(self.weight, "weight", 1.0, lo_ok=True))
        check_flag(self.retry, "retry")
        check_flag(self.escapes, "escapes")
        _set(
            self,
            "analytic_every",
            check_option(self.analytic_every, "analytic_every", 1, integer=True, lo_ok=True),
        )
        _set(self, "goal_radius", check_option(self.goal_radius, "goal_radius", 0.0, allow_none=True))
        _set(self, "cell", check_option(self.cell, "cell", 0.0, allow_none=True))
        _set(self, "reverse_factor", check_option(self.reverse_factor, "reverse_factor", 0.0))
        _set(self, "cusp_penalty", check_option(self.cusp_penalty, "cusp_penalty", 0.0, lo_ok=True))
        _set(self, "max_expansions", _check_expansions(self.max_expansions))
        if not isinstance(self.schedule, Schedule):
            raise ValueError(
                f"schedule must be a segplan.planning.schedule.Schedule, got {type(self.schedule).__name__}"
            )

    def search_options(self) -> dict:
        """The keyword arguments of ``lattice_options`` (those of ``lattice_search`` but the
        limits and the schedule)."""
        out = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        del out["max_expansions"], out["schedule"]
        return out

    def to_dict(self) -> dict:
        """Plain-JSON form."""
        return dataclasses.asdict(self)

    @classmethod
    def from_dict(cls, data) -> LatticeOptions:
        """The options of a :meth:`LatticeOptions.to_dict` read back from JSON:
        ``from_dict(o.to_dict()) == o``."""
        kw = _fields_of(cls, data, "lattice options")
        if "schedule" in kw:
            schedule = _fields_of(Schedule, kw["schedule"], "schedule")
            for name in ("grid_margin", "guide_window"):  # JSON lists, the schedule's tuples
                if isinstance(schedule.get(name), list):
                    schedule[name] = tuple(schedule[name])
            kw["schedule"] = Schedule(**schedule)
        return cls(**kw)


@dataclass(frozen=True)
class DefaultOptions:
    """Every value of the default planner (``planner="lattice"``, beyond the paper).

    The paper's search first (fast where it succeeds), then the lattice, then the
    refinement of the shorter plan found (:func:`segplan.planning.default.default_pipeline`).

    Attributes
    ----------
    paper : PaperOptions
        The first stage: the paper's search with these settings, at most
        ``paper.max_expansions`` expansions (40) and ``paper.time_limit`` seconds
        (derived: ``paper_share * time_limit``). Its ``alpha_method`` must be "heuristic"
        (the lattice's primitives and the refinement's screen are built in the heuristic
        frame; ``planner="paper"`` honours "exact"), its ``refine`` None and its
        ``clearance`` 0 (the pipeline's own ``refine`` and ``clearance`` apply). 40
        expansions (19e3c64, was 64): on the 400 random floors of chapter 9 every plan the
        paper's search found took at most 34 expansions, while its failures ran up to 141
        (up to 0.2 s) before the lattice began; 40 gave the same plans on those floors, 100
        tight floors and 80 varied robots, and 3 % less time (ABBA).
    paper_share : float
        Share of ``time_limit`` given to the paper's search, in (0, 1]. 0.2: set by hand in
        f93489c; not measured.
    lattice : LatticeOptions
        The second stage. Its ``max_expansions`` applies when the paper's search found no
        plan.
    lattice_after_paper : int
        Expansions the lattice may spend looking for a shorter plan once the paper's search
        has found one (a count, not a time share: the plan does not depend on the machine).
        400 (5fdf5b3, was 2000 before the coarse cost-to-go guided the lattice): on the 400
        random floors of chapter 9 the same lengths in less time.
    near_lower_bound : float
        The lattice is skipped when the paper's plan costs at most this factor times a
        lower bound of any plan's LONGD (the Dubins length of the rear point). 1.3
        (5fdf5b3, was 1.05): on the 400 random floors of chapter 9 (refined plans against
        BIT*) the median and the largest length ratio stayed as they were and the median
        plan time fell by a quarter; the refinement wins back what the lattice would have.
    refine : RefineOptions or None
        The refinement of each plan found (the paper's and the lattice's, the shorter kept);
        None: none. ``RefineOptions()`` (issue 25, was ``max_sweeps=3`` of the shorter plan
        alone since 2fb6ec4): with 3 sweeps of the shorter plan, ``segplan.refine`` of the
        paper's plan (6 sweeps), which a user can type, was shorter on 60 of 127 floors (the
        7 shipped floors, the first 60 random floors of each kind of chapter 9; on Fig. 5
        31.299 m against 31.488 m); refining both plans with 6 sweeps it is shorter on none,
        the median plan 0.3 % shorter (at most 6 %), the median plan time 16 -> 24 ms and the
        95th percentile unchanged (161 ms) on this 2-core machine under load (2026-12-03;
        upper bounds).
    time_limit : float
        Seconds for the whole call (search and refinement). 10: set by hand in bb220de;
        not measured.
    clearance : float
        Safety margin (m, >= 0) beyond ``half_width`` (0: the paper's model).
    """

    paper: PaperOptions = PaperOptions(max_expansions=40, time_limit=2.0)
    paper_share: float = 0.2
    lattice: LatticeOptions = LatticeOptions()
    lattice_after_paper: int = 400
    near_lower_bound: float = 1.3
    refine: RefineOptions | None = RefineOptions()
    time_limit: float = 10.0
    clearance: float = 0.0

    def __post_init__(self):
        if not isinstance(self.paper, PaperOptions):
            raise ValueError(f"paper must be PaperOptions, got {self.paper!r}")
        if not isinstance(self.lattice, LatticeOptions):
            raise ValueError(f"lattice must be LatticeOptions, got {self.lattice!r}")
        if self.refine is not None and not isinstance(self.refine, RefineOptions):
            raise ValueError(f"refine must be RefineOptions or None, got {self.refine!r}")
        if self.paper.alpha_method != "heuristic":
            raise ValueError(
                f"alpha_method={self.paper.alpha_method!r} is honoured by the paper's search alone: "
                "pass planner='paper' (the default planner's lattice primitives and its refinement "
                "are built in the heuristic reference system)"
            )
        if self.paper.refine is not None:
            raise ValueError("paper.refine must be None: the default planner refines once, by its own refine")
        if self.paper.clearance != 0.0:
            raise ValueError("paper.clearance must be 0: the default planner's clearance applies")
        _set(self, "time_limit", check_option(self.time_limit, "time_limit", 0.0))
        share = check_option(self.paper_share, "paper_share", 0.0)
        if share > 1.0:
            raise ValueError(f"paper_share must be at most 1, got {share!r}")
        _set(self, "paper_share", share)
        _set(
            self,
            "lattice_after_paper",
            check_option(self.lattice_after_paper, "lattice_after_paper", 0, integer=True, lo_ok=True),
        )
        _set(
            self, "near_lower_bound", check_option(self.near_lower_bound, "near_lower_bound", 0.0, lo_ok=True)
        )
        _set(self, "clearance", check_option(self.clearance, "clearance (m)", 0.0, lo_ok=True))
        # the first stage's time: a share of the call's
        paper_time = self.paper_share * float(self.time_limit)
        if self.paper.time_limit != paper_time:
            _set(self, "paper", dataclasses.replace(self.paper, time_limit=paper_time))

    def to_dict(self) -> dict:
        """Plain-JSON form."""
        out = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        out["paper"] = self.paper.to_dict()
        out["lattice"] = self.lattice.to_dict()
        out["refine"] = None if self.refine is None else self.refine.to_dict()
        return out

    @classmethod
    def from_dict(cls, data) -> DefaultOptions:
        """The options of a :meth:`DefaultOptions.to_dict` read back from JSON:
        ``from_dict(o.to_dict()) == o``."""
        kw = _fields_of(cls, data, "default options")
        if "paper" in kw:
            kw["paper"] = PaperOptions.from_dict(kw["paper"])
        if "lattice" in kw:
            kw["lattice"] = LatticeOptions.from_dict(kw["lattice"])
        if kw.get("refine") is not None:
            kw["refine"] = RefineOptions.from_dict(kw["refine"])
        return cls(**kw)


def options_from_dict(data) -> PaperOptions | DefaultOptions:
    """A planner's options from their ``to_dict()`` form: :class:`DefaultOptions` (it has the
    field ``paper``) or :class:`PaperOptions`. The inverse of ``to_dict`` on JSON read back, so
    a saved plan's options plan again (:meth:`segplan.Plan.load`)."""
    if isinstance(data, Mapping) and "paper" in data:
        return DefaultOptions.from_dict(data)
    return PaperOptions.from_dict(data)
