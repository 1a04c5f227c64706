"""Refinement of a found plan (beyond the paper): shortcuts and local moves of its nodes.

The paper's search returns the best chain of unions *in the graph it built*: its nodes
are the start, the goal, intermediate nodes placed off obstacle vertices and turn states.
A shorter chain usually exists nearby. :func:`refine` looks for it with the paper's own
pieces (cubic unions in their optimal reference system, the LONGD cost, the on-line
collision test), in three steps repeated ``rounds`` times:

1. **Shortcuts.** Every pair of nodes ``i < j`` of the chain at most ``max_chord * L``
   apart may be joined directly (and every pair whose link was checked before); the
   cheapest chain over those links (a shortest path in a small acyclic graph) is kept.
   Links are screened by their cost in the heuristic frame, vectorised, and only the
   links of a best chain are checked (union, steering limit, walls, obstacles), until a
   best chain is made of checked links.
2. **Splits.** A union whose chord is longer than ``split * L`` gets a new node at its
   middle (the pose of the rear point half way along the cubic's frame abscissa): the
   chain's shape, so far one cubic, becomes two.
3. **Local moves** (a pattern search, our choice). Each interior node in turn tries
   ``len(MOVES)`` moves in its own frame: forward/back, left/right, turning left/right
   and the four combinations of a sideways move with a turn. The two unions of every
   move are screened at once (vectorised); the cheapest screened moves are checked
   exactly, and the first that is free and lowers the node's two link costs is taken.
   A node that cannot improve halves its step; the search stops when every step is below
   ``min_step * L`` or after ``max_sweeps`` sweeps.

Links are compared by [1] integrated with a fixed Gauss-Legendre rule (formula [2] is no
guide here: most short, turning links lie outside its validated domain); a local move is
taken only if it lowers its node's two link costs by at least ``MIN_GAIN * L``. The
returned plan's ``cost`` is the exact LONGD [1] of its unions (Romberg), like every
plan, and is never above the input's: if the refined chain is not shorter, the input's
chain is returned. The result is deterministic (no random moves, a fixed order). It is a
local improvement: the chain keeps the corridor the search chose.

Its tuning values are the fields of :class:`segplan.planning.options.RefineOptions`. Under a
deadline (:func:`segplan.plan_scenario`'s ``time_limit``) it starts no new work once the
deadline has passed and returns the chain so far (``Refinement.stopped``).
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from ..floor.scenario import Scenario
from ..model.cost import chain_longd, longd_gauss_intrinsic
from ..model.frame import heuristic_alpha
from ..model.pose import Pose, alpha_interval, wrap
from ..model.union import cubic_coefficients, curvature_samples, exceeds_curvature
from .certified import FreeScreen
from .context import Deadline, workspace_of
from .links import ALPHA_MARGIN, LinkModel
from .options import RefineOptions
from .plan import PLAN_RTOL, Plan, Refinement, unions_longd
from .validity import Workspace

__all__ = ["certain_failures", "polish_cusps", "refine", "refine_with"]

#: The default moves of a node (:attr:`RefineOptions.moves`), as an array.
MOVES = np.array(RefineOptions.moves, dtype=float)
#: The default least gain of a local move (:attr:`RefineOptions.min_gain`, units of L).
MIN_GAIN = RefineOptions.min_gain
#: The default screened moves checked per node update (:attr:`RefineOptions.checks_per_update`).
CHECKS_PER_UPDATE = RefineOptions.checks_per_update
#: Fractions of a link's frame span sampled by :func:`certain_failures`.
SAMPLES = np.linspace(0.0, 1.0, 9)


def refine(
    plan,
    scenario: Scenario,
    *,
    rounds: int = 1,
    split: float = 3.0,
    first_step: float = 0.5,
    min_step: float = 1.0 / 16.0,
    max_sweeps: int = 6,
):
    """A shorter plan near ``plan``: shortcuts, splits and local moves of its nodes.

    Beyond the paper (see the module docstring). Keeps the paper's pieces: every link is
    a cubic union in the optimal reference system (heuristic method here; through
    ``plan_scenario(..., refine=True)`` the search's own method, so ``alpha_method="exact"``
    makes the refinement far slower), free of the enlarged obstacles, inside the walls and
    within the steering limit.

    Parameters
    ----------
    plan : segplan.Plan
        A plan of ``scenario`` (from :func:`segplan.plan_scenario`).
    scenario : Scenario
        The scenario the plan was made for.
    rounds : int
        Rounds of shortcuts, splits and local moves (0: shortcuts only).
    split : float
        Chords longer than ``split * L`` get a middle node in each round.
    first_step, min_step : float
        First and smallest step of a node's local moves, units of ``L`` (turns: the
        same numbers in radians).
    max_sweeps : int
        Sweeps over the nodes per round, at most.

    Returns
    -------
    segplan.Plan
        With ``nodes``, ``unions``, ``kinds`` (new nodes: ``"refined"``), ``cost`` (exact
        LONGD [1]) and ``seconds`` (search plus refinement) updated and ``refinement``
        set (:class:`Refinement`).

    Raises
    ------
    ValueError
        Bad options, a plan that does not belong to the scenario (other start, goal or
        robot, or a union that is not free there), or a plan that is already refined.

    Notes
    -----
    Inside the refinement, links are compared by [1] integrated with a fixed 24-point
    Gauss-Legendre rule (:func:`segplan.model.cost.longd_gauss_intrinsic`), both when screened
    and when checked: one objective, so that a screened improvement is a real one. The
    returned ``cost`` is Romberg's [1], as for every plan.
    """
    if not isinstance(plan, Plan):
        raise ValueError(f"plan must be a segplan.Plan, got {type(plan).__name__}")
    if not isinstance(scenario, Scenario):
        raise ValueError(f"scenario must be a segplan.Scenario, got {type(scenario).__name__}")
    if plan.nodes[0] != Pose(*scenario.start) or plan.nodes[-1] != Pose(*scenario.goal):
        raise ValueError("plan does not go from the scenario's start to its goal")
    if any(abs(u.L - scenario.robot.L) > 1e-12 * scenario.robot.L for u in plan.unions):
        raise ValueError("plan was made for another robot length than the scenario's")
    options = RefineOptions(
        rounds=rounds, split=split, first_step=first_step, min_step=min_step, max_sweeps=max_sweeps
    )
    ws = workspace_of(scenario)
    for i, u in enumerate(plan.unions):
        if not ws.union_free(u):
            raise ValueError(f"plan's union {i} is not free in this scenario (a plan of another scenario?)")
    return refine_with(plan, LinkModel(ws), options)


def refine_with(
    plan, links: LinkModel, options: RefineOptions | None = None, deadline: Deadline | None = None
):
    """:func:`refine` with the search's own link model (its caches are reused), these
    options (default ``RefineOptions()``), until ``deadline``.

    Past the deadline no new work starts (no further link check, split, node update or
    round); the chain so far is returned, every link of it checked, and
    ``refinement.stopped`` says so. With time left the deadline changes nothing.
    """
    options = RefineOptions() if options is None else options
    if not isinstance(options, RefineOptions):
        raise ValueError(f"options must be RefineOptions, got {options!r}")
    if plan.refinement is not None:
        raise ValueError("plan is already refined")
    if plan.directions:  # a chain of forward unions only (issue 26: the default planner refines by runs)
        raise ValueError("plan has reverse links: refine each run of one direction (lattice.reverse.by_runs)")
    t0 = time.perf_counter()
    r = _Refiner(links, options, deadline)
    nodes = list(plan.nodes)
    kinds = list(plan.kinds)
    n0 = len(nodes)
    original = set(nodes)
    if r.stop():  # past the deadline already: the search's chain as found
        unions, cost = plan.unions, plan.cost
    else:
        for u in plan.unions:  # the search checked them: known free
            r.known[(u.p0, u.p1)] = (u, r.cost(u))
        nodes, kinds = r.shortcut(nodes, kinds)
        for _ in range(options.rounds):
            if r.stop():
                break
            nodes, kinds = r.split(nodes, kinds, options.split * links.L)
            nodes = r.polish(nodes, options.first_step, options.min_step, options.max_sweeps)
            kinds = [k if nodes[i] in original else "refined" for i, k in enumerate(kinds)]
            nodes, kinds = r.shortcut(nodes, kinds)
        unions = tuple(r.known[(a, b)][0] for a, b in zip(nodes[:-1], nodes[1:], strict=True))
        cost = chain_longd(unions, PLAN_RTOL, from_poses=True)
    if not cost < plan.cost:  # not shorter by [1]: keep the search's chain
        nodes, kinds, unions, cost = list(plan.nodes), list(plan.kinds), plan.unions, plan.cost
    seconds = time.perf_counter() - t0
    info = Refinement(
        cost_before=plan.cost,
        cost_after=cost,
        nodes_before=n0,
        nodes_after=len(nodes),
        shortcuts=r.removed,
        splits=r.added,
        moves=r.moves,
        updates=r.updates,
        checked=r.checked,
        seconds=seconds,
        stopped=r.stopped,
    )
    return dataclasses.replace(
        plan,
        nodes=tuple(nodes),
        unions=unions,
        cost=cost,
        kinds=tuple(kinds),
        seconds=plan.seconds + seconds,
        refinement=info,
    )


class _Refiner:
    """The state of one refinement: checked links and counters."""

    def __init__(self, links: LinkModel, options: RefineOptions, deadline: Deadline | None = None):
        self.links = links
        self.ws = links.ws
        self.free = FreeScreen(links.ws)  # the exact test's answers, most of them cheaper
        self.L = links.L
        self.options = options
        self.moves_table = np.array(options.moves, dtype=float)
        self.deadline = deadline
        self.stopped = False  # the deadline passed: no new work
        self.known: dict = {}  # (p0, p1) -> (union, cost) of a checked free link, or (None, inf)
        self.removed = self.added = self.moves = self.updates = self.checked = 0

    def stop(self) -> bool:
        """True once the deadline has passed (then for good): start no new work."""
        if not self.stopped and self.deadline is not None and self.deadline.expired():
            self.stopped = True
        return self.stopped

    # -- links ---------------------------------------------------------------------------
    def link(self, a: Pose, b: Pose) -> float:
        """Cost of the checked link a -> b (``inf`` if no free union joins them)."""
        out = self.known.get((a, b))
        if out is None:
            self.checked += 1
            u = self.links.union(a, b)
            if u is None or not self.free.union_free(u):
                out = (None, math.inf)
            else:
                out = (u, self.cost(u))
            self.known[(a, b)] = out
        return out[1]

    @staticmethod
    def cost(u) -> float:
        """The refinement's link cost: [1] by Gauss-Legendre (:func:`longd_gauss_intrinsic`)."""
        return float(longd_gauss_intrinsic(u.d, u.phi0, u.phi1, u.alpha, u.L))

    def screen(self, A: np.ndarray, B: np.ndarray, need=None) -> np.ndarray:
        """The link cost in the heuristic frame for links ``A[k] -> B[k]``, vectorised.

        ``inf`` where no cubic joins the poses or where the link surely fails: a sampled
        curvature above the steering limit, or a sampled point of the swept segment
        outside the walls or strictly inside an obstacle (:func:`certain_failures`).
        Screening only: a finite value is no proof that the link is free.

        ``need``, optional: a function of the costs (before failures, ``inf`` where no cubic
        joins the poses) that returns the links whose certain failures matter to the caller;
        the others are not looked for inside the obstacles (their value may then be finite
        where a failure would make it ``inf``). Every value is computed on the whole batch as
        without ``need`` (the vectorised functions' last bits depend on the batch), so the
        links that matter get the same values.
        """
        A, B = np.broadcast_arrays(A, B)
        dx, dy = B[..., 0] - A[..., 0], B[..., 1] - A[..., 1]
        d = np.hypot(dx, dy)
        psi = np.arctan2(dy, dx)
        phi0, phi1 = wrap(A[..., 2] - psi), wrap(B[..., 2] - psi)
        lo, hi = alpha_interval(phi0, phi1)
        ok = (d > 1e-9 * self.L) & (hi - lo > 2.0 * ALPHA_MARGIN)
        out = np.full(d.shape, math.inf)
        if np.any(ok):
            dd, p0, p1 = d[ok], phi0[ok], phi1[ok]
            alpha = np.atleast_1d(heuristic_alpha(dd, p0, p1, self.L))
            cost = longd_gauss_intrinsic(dd, p0, p1, alpha, self.L)
            only = None
            if need is not None:
                out[ok] = cost
                only = need(out)[ok]
            bad = certain_failures(
                self.ws, A[ok], psi[ok] - alpha, *cubic_coefficients(dd, p0, p1, alpha), only=only
            )
            out[ok] = np.where(bad, math.inf, cost)
        return out

    # -- shortcuts -----------------------------------------------------------------------
    def shortcut(self, nodes: list, kinds: list) -> tuple[list, list]:
        """The cheapest chain over direct links between the nodes (order kept)."""
        n = len(nodes)
        if n < 3 or self.stop():
            return nodes, kinds
        P = np.array(nodes, dtype=float)
        I, J = np.triu_indices(n, k=2)
        if self.options.max_chord is not None:
            near = np.hypot(P[J, 0] - P[I, 0], P[J, 1] - P[I, 1]) <= self.options.max_chord * self.L
            I, J = I[near], J[near]
        screened = self.screen(P[I], P[J])
        finite = np.isfinite(screened)
        guess = dict(
            zip(
                zip(I[finite].tolist(), J[finite].tolist(), strict=True),
                screened[finite].tolist(),
                strict=True,
            )
        )
        # the links into each node that may join a chain: screened finite, or checked (a
        # checked link's cost replaces its screen); one of cost inf never lowers a chain's, so
        # the shortest chain over these is the one over all the links (ties: the lowest i)
        at: dict = {}
        for k, p in enumerate(nodes):
            at.setdefault(p, []).append(k)
        pairs = set(guess)
        pairs.update((i, j) for a, b in self.known for i in at.get(a, ()) for j in at.get(b, ()) if i < j)
        into: list = [[] for _ in range(n)]
        for i, j in sorted(pairs):
            into[j].append(i)
        while True:
            best = [0.0] + [math.inf] * (n - 1)
            prev = [-1] * n
            for j in range(1, n):
                for i in into[j]:
                    key = (nodes[i], nodes[j])
                    c = self.known[key][1] if key in self.known else guess[(i, j)]
                    if best[i] + c < best[j]:
                        best[j], prev[j] = best[i] + c, i
            chain = [n - 1]
            while chain[-1] != 0:
                chain.append(prev[chain[-1]])
            chain.reverse()
            todo = [
                (i, j)
                for i, j in zip(chain[:-1], chain[1:], strict=True)
                if (nodes[i], nodes[j]) not in self.known
            ]
            if not todo:
                break
            for i, j in todo:
                if self.stop():  # the chain so far: every link of it checked
                    return nodes, kinds
                self.link(nodes[i], nodes[j])
        self.removed += n - len(chain)
        return [nodes[k] for k in chain], [kinds[k] for k in chain]

    # -- splits --------------------------------------------------------------------------
    def split(self, nodes: list, kinds: list, longest: float) -> tuple[list, list]:
        """A middle node on every union whose chord is longer than ``longest``."""
        out, out_kinds = [nodes[0]], [kinds[0]]
        for a, b, k in zip(nodes[:-1], nodes[1:], kinds[1:], strict=True):
            u = self.known[(a, b)][0]
            if u.d > longest and not self.stop():
                x = 0.5 * u.x_end
                px, py = u.to_world(x, u.f(x)).tolist()
                m = Pose(px, py, wrap(float(u.heading(x))))
                c0, c1 = self.link(a, m), self.link(m, b)
                if math.isfinite(c0 + c1):  # the halves of a free cubic are, in general, free
                    out.append(m)
                    out_kinds.append("refined")
                    self.added += 1
            out.append(b)
            out_kinds.append(k)
        return out, out_kinds

    # -- local moves ---------------------------------------------------------------------
    def polish(self, nodes: list, first_step: float, min_step: float, max_sweeps: int) -> list:
        """Pattern search on the interior nodes (module docstring, step 3).

        A sweep takes the odd interior nodes, then the even ones: nodes of one parity
        share no link, so their moves are screened in one vectorised call.
        """
        nodes = list(nodes)
        L = self.L
        steps = [first_step * L] * len(nodes)
        floor = min_step * L
        gain = self.options.min_gain * L
        moves = self.moves_table
        m = len(moves)
        checks = self.options.checks_per_update
        for _ in range(max_sweeps):
            active = False
            for parity in (1, 2):
                idx = [i for i in range(parity, len(nodes) - 1, 2) if steps[i] >= floor]
                if not idx:
                    continue
                if self.stop():
                    return nodes
                active = True
                self.updates += len(idx)
                P = np.array([nodes[i] for i in idx], dtype=float)
                s = np.array([steps[i] for i in idx])[:, None]
                c, sn = np.cos(P[:, 2:3]), np.sin(P[:, 2:3])
                fwd, left, turn = moves[:, 0] * s, moves[:, 1] * s, moves[:, 2] * (s / L)
                Q = np.stack(
                    (P[:, :1] + c * fwd - sn * left, P[:, 1:2] + sn * fwd + c * left, wrap(P[:, 2:3] + turn)),
                    axis=-1,
                )
                prev = np.array([nodes[i - 1] for i in idx], dtype=float)[:, None, :]
                after = np.array([nodes[i + 1] for i in idx], dtype=float)[:, None, :]
                k = len(idx) * m
                # a move is checked only if its screened cost is below its node's
                # ``now - gain`` (below): for the others, no need to look for failures
                limit = np.repeat([self._limit(nodes[i - 1], nodes[i], nodes[i + 1], gain) for i in idx], m)

                def need(cost, limit=limit, k=k):
                    below = cost[:k] + cost[k:] < limit
                    return np.concatenate((below, below))

                both = self.screen(
                    np.concatenate((np.broadcast_to(prev, Q.shape).reshape(k, 3), Q.reshape(k, 3))),
                    np.concatenate((Q.reshape(k, 3), np.broadcast_to(after, Q.shape).reshape(k, 3))),
                    need,
                )
                guess = (both[:k] + both[k:]).reshape(len(idx), m)
                for row, i in enumerate(idx):
                    if self.stop():
                        return nodes
                    a, p, b = nodes[i - 1], nodes[i], nodes[i + 1]
                    now = self.link(a, p) + self.link(p, b)
                    moved = False
                    for j in np.argsort(guess[row], kind="stable")[:checks]:
                        if not guess[row, j] < now - gain:
                            break
                        q = Pose(*Q[row, j].tolist())
                        if self.link(a, q) + self.link(q, b) < now - gain:
                            nodes[i] = q
                            self.moves += 1
                            moved = True
                            break
                    if not moved:
                        steps[i] *= 0.5
            if not active:
                break
        return nodes

    def _limit(self, a: Pose, p: Pose, b: Pose, gain: float) -> float:
        """``now - gain`` of node ``p`` between ``a`` and ``b`` (:meth:`polish`), from its checked
        links (the same floating-point operations); ``inf`` if one is not checked yet.

        A move whose screened cost is at least this is never checked: the moves are tried
        in increasing order of that cost and the first at least ``now - gain`` ends the
        node's update. Its certain failures would only raise its cost (``inf``), so they
        need not be looked for (:meth:`screen`'s ``need``)."""
        ka, kb = self.known.get((a, p)), self.known.get((p, b))
        if ka is None or kb is None:
            return math.inf
        return ka[1] + kb[1] - gain


def polish_cusps(
    plan: Plan,
    links: LinkModel,
    options: RefineOptions,
    reverse_factor: float,
    deadline: Deadline | None = None,
) -> tuple[Plan, int]:
    """Local moves of a plan's cusps (a robot that may reverse; beyond the paper): ``(plan,
    moves taken)``.

    The refinement works on each same-direction run of a reverse plan with its ends fixed
    (:func:`segplan.planning.lattice.reverse.by_runs`), so a cusp stays where the lattice put
    it, on the lattice's coarse headings. Here each cusp in turn tries the local moves of
    step 3 (:attr:`RefineOptions.moves`, from ``first_step`` down to ``min_step`` times
    ``L``, at most ``max_sweeps`` halvings) on its two links, one driven each way (a reverse
    link is the forward union from its far node to its near one): a move is taken when both
    links are free (the certified test) and the search's cost of the two, LONGD [1] by the
    refinement's rule, times ``reverse_factor`` for the reverse one, drops by at least
    ``min_gain * L``. The returned plan's ``cost`` is its exact LONGD [1]; ``plan`` itself
    if no move was taken.
    """
    cusps = plan.cusps
    if not cusps:
        return plan, 0
    r = _Refiner(links, options, deadline)
    nodes = list(plan.nodes)
    dirs = plan.link_directions
    L = r.L
    gain = options.min_gain * L

    def ends(i: int, c: Pose, k: int) -> tuple:  # the stored union's ends of link k at node i = c
        a, b = (nodes[k], c) if k == i - 1 else (c, nodes[k + 1])
        return (a, b) if dirs[k] > 0 else (b, a)

    def cost(i: int, c: Pose) -> float:
        total = 0.0
        for k in (i - 1, i):
            w = 1.0 if dirs[k] > 0 else reverse_factor
            total += w * r.link(*ends(i, c, k))
        return total

    taken = 0
    for i in cusps:
        step = options.first_step * L
        for _ in range(options.max_sweeps):
            if step < options.min_step * L or r.stop():
                break
            p = nodes[i]
            now = cost(i, p)
            c, sn = math.cos(p.theta), math.sin(p.theta)
            for fwd, left, turn in r.moves_table:
                f, lt = fwd * step, left * step
                q = Pose(p.x + c * f - sn * lt, p.y + sn * f + c * lt, float(wrap(p.theta + turn * step / L)))
                if cost(i, q) < now - gain:
                    nodes[i] = q
                    taken += 1
                    break
            else:
                step *= 0.5
    if not taken:
        return plan, 0
    unions = list(plan.unions)  # a link whose nodes stayed keeps its (checked) union
    for k in range(len(dirs)):
        if (nodes[k], nodes[k + 1]) != (plan.nodes[k], plan.nodes[k + 1]):
            a, b = (nodes[k], nodes[k + 1]) if dirs[k] > 0 else (nodes[k + 1], nodes[k])
            unions[k] = r.known[(a, b)][0]  # checked free by the move that put the node there
    kinds = list(plan.kinds)
    for i in cusps:
        kinds[i] = "refined" if nodes[i] != plan.nodes[i] else kinds[i]
    out = dataclasses.replace(
        plan, nodes=tuple(nodes), unions=tuple(unions), kinds=tuple(kinds), cost=unions_longd(unions)
    )
    return out, taken


def certain_failures(
    ws: Workspace, A: np.ndarray, frame: np.ndarray, X, c1, c2, c3, only: np.ndarray | None = None
) -> np.ndarray:
    """Links that surely break a rule, from samples (vectorised; screening only).

    A link fails for certain if its rear path's curvature, sampled at ``SAMPLES``
    abscissae, exceeds the steering limit, or if a sampled point of the swept segment
    (rear point, middle, front wheel) lies outside the free bounds or strictly inside an
    enlarged obstacle (:meth:`segplan.planning.validity.Workspace.inside`), deeper than
    the workspace's ``depth`` for a rectangular body. The converse
    does not hold: a link with no certain failure must still be checked
    (:meth:`segplan.planning.validity.Workspace.union_free`).

    Parameters
    ----------
    ws : Workspace
    A : ndarray (n, 3)
        Start poses of the links.
    frame : ndarray (n,)
        World angles of the links' alpha frames (``psi - alpha``).
    X, c1, c2, c3 : ndarray (n,)
        The cubics (:func:`segplan.model.union.cubic_coefficients`).
    only : ndarray of bool (n,), optional
        Look for sampled points inside obstacles only on these links (the others may then
        be reported False although a point of theirs lies inside one). Links already failing
        (curvature, walls) are not looked at either: they fail whatever else is found. The
        points are computed on the whole batch and the test is exact arithmetic point by
        point, so the links looked at get the same answers as without ``only``.
    """
    x, fp, fpp = curvature_samples(X[:, None], c1[:, None], c2[:, None], c3[:, None], SAMPLES)
    bad = exceeds_curvature(fp, fpp, ws.max_curvature, axis=1)
    fx = ((c3[:, None] * x + c2[:, None]) * x + c1[:, None]) * x  # f
    h = frame[:, None] + np.arctan(fp)  # heading
    cf, sf = np.cos(frame)[:, None], np.sin(frame)[:, None]
    rx, ry = A[:, :1] + cf * x - sf * fx, A[:, 1:2] + sf * x + cf * fx  # rear point, world
    ux, uy = np.cos(h), np.sin(h)
    L = ws.L
    wx = np.concatenate((rx, rx + 0.5 * L * ux, rx + L * ux), axis=1)
    wy = np.concatenate((ry, ry + 0.5 * L * uy, ry + L * uy), axis=1)
    if ws.bounds is not None:
        xmin, ymin, xmax, ymax = ws.bounds
        d = ws.depth  # 0; a rectangular body: how far beyond a moved wall is a certain failure
        bad |= np.any((wx <= xmin - d) | (wx >= xmax + d) | (wy <= ymin - d) | (wy >= ymax + d), axis=1)
    look = ~bad if only is None else only & ~bad
    if look.any():
        bad[look] = np.any(ws.inside(wx[look], wy[look]), axis=1)
    return bad
