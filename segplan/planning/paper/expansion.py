"""Graph expansion: the successors of a node toward the goal, with intermediate nodes.

Section "Graph expansion method. Generation of intermediate nodes" of Campoy et al.
(1989). The search graph is built on-line: a node (a pose) is joined to the goal by the
cubic union of section III in its optimal reference system. If that union is free, the
goal is the node's only successor. If it collides with an obstacle, "a suitable
intermediate state near the vertex is chosen ... along the bisectrix of the
correspondent angle of the polygon. ... The slope is a weighted average between the one
at right angles with the bisectrix and the one that would appear naturally using clamped
spline interpolation for the three points involved. Though the algorithm is iterative,
until no collision appears, two or three iterates at the most are normally needed."

Our reconstruction (the paper gives no formulas for this section)
-----------------------------------------------------------------
*Which obstacles, which vertex.* The first obstacle along the direct union that it
touches gets candidates (the paper's single-obstacle setting; ``all_obstacles=True``:
every obstacle it touches, slower and in our tests no more successful). The path can pass
a convex polygon on either side, so each side gives one candidate: two successors per
obstacle. On side ``s`` (``+1``: the
obstacle stays on the robot's right, ``-1``: on its left) the vertex is the *tangent
vertex seen from the node*: the polygon's extreme vertex in the direction of ``s`` as
seen from the node's rear point (the first vertex a shortest path around the obstacle
touches, :func:`segplan.planning.paper.bisectrix.tangent_vertices`). If the tangent vertex seen backwards
from the goal is the same vertex, one intermediate node passes the obstacle and we
iterate, as the paper does, until *both* new unions are free of it (a "complete" candidate). Otherwise
(a long obstacle, such as a rack) one node cannot pass it: only the first union must be
free of it, and the next expansion, from the new node, passes the next vertex.

*First estimate.* Position ``P = v + r0 b`` with ``v`` the vertex, ``b`` the outward
unit bisectrix of its angle (:func:`segplan.planning.paper.bisectrix.outward_bisectors`) and
``r0 = 0.3 L``. Heading ``theta = theta_perp + w wrap(theta_spline - theta_perp)``
(:func:`segplan.planning.paper.bisectrix.iterate_pose`): ``theta_perp`` at right angles with the
bisectrix, oriented in the direction of travel (clockwise around the obstacle on side
``+1``); ``theta_spline`` the tangent at ``P`` of the parametric clamped cubic spline
through start, ``P`` and goal (:func:`segplan.planning.paper.bisectrix.clamped_spline_tangent`);
``w = 0.5``.

*Iterates* (at most ``max_iterations = 4``; the paper: "two or three iterates at the most
are normally needed"), by the reason the last one failed:

* the robot at ``P`` touches an obstacle or a wall: first "readjust the orientation"
  (the paper's words for difficult cases) to the direction of the obstacle's edge that
  leaves ``v`` in the direction of travel (``w = 0``: the robot lies along that edge, a
  *tight spot* such as a doorway); then move ``P`` closer to the vertex
  (``r /= growth``). In a tight spot every other failure slides ``P`` along the edge by
  ``0.5 L``, deeper into the passage, keeping the edge's direction;
* a new union touches the offending obstacle: move ``P`` outward (``r *= growth``,
  ``growth = 1.7``);
* the union from the node does not exist or breaks the steering limit (too sharp a
  turn, ``P`` too close): slide ``P`` along that edge by ``0.5 L`` and take the edge
  direction with more spline weight (``w = (1 + w) / 2``);
* the union to the goal (complete candidates only) does not exist or is too curved:
  ``w = (1 + w) / 2`` and ``r *= growth``;
* the union from the node is free of the offending obstacle but hits another one or a
  wall: slide along the edge (deeper into a passage). If no later iterate succeeds, the
  first such iterate is returned and :meth:`Expander.successors` generates intermediate
  nodes for the obstacle in its way (``recursion`` levels), aiming at that iterate as a
  subgoal (without the requirement on the union from it).

Every candidate records its iterate count (``ExpansionStats.iterations``).

*Reference systems* (Fig. 4). ``version="b"`` (the paper's choice): each piece gets its
own optimal reference system (:func:`segplan.model.frame.optimal_alpha_intrinsic`).
``version="a"``: both pieces of an intermediate node share one frame, "estimated as close
to the optimum": the optimal frame of the direct union node->goal (its chord's frame if
that union does not exist).

*Steering limit* (not in the paper). Every union must keep the rear path's curvature
within ``tan(max_steer) / L``. When the optimal frame's cubic breaks it, version "b"
tries the frame of least peak curvature instead (:meth:`segplan.planning.links.LinkModel._steer`).

*Difficult cases* (section III: "great changes of slope, or even orientations opposing
the direction in which a natural trajectory would be traversed ... can be solved ... by
using a suitable intermediate state"). When the direct union does not exist (no
feasible alpha, e.g. a goal behind the start), breaks the steering limit or leaves the
bounds, or when no vertex candidate works, the successors are *turn states*
(:meth:`Expander.turn_states`): poses reached from the node along circular arcs of
radius ``turn_radius = 1.6`` times the minimum turning radius, turning by 90 and 45
degrees to either side (a quarter-circle cubic has a peak curvature of about 1.4 / radius,
below the limit at 1.6 radii), and the goal's *approach states*
(:meth:`Expander.approach_states`), the mirror image: poses from which such an arc (or a
straight run of ``2 L``) ends at the goal. A chain of them lets a forward-only robot turn
around; the search bounds the length of such chains.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ...model.pose import HALF_PI, Pose, arc_end, wrap_fmod
from ...model.union import Union
from ..links import LinkModel
from ..validity import ExpansionStats, Workspace
from .bisectrix import iterate_pose, outward_bisectors, tangent_vertices

__all__ = ["Candidate", "Expander", "Successor"]


@dataclass(frozen=True)
class Candidate:
    """An intermediate node generated near a vertex (or a failed attempt).

    Attributes
    ----------
    pose : Pose
        The last iterate.
    polygon, vertex : int
        Obstacle index and vertex index.
    side : int
        ``+1``: the obstacle stays on the robot's right; ``-1``: on its left.
    iterations : int
        Iterates used (1 = the first estimate was accepted).
    ok : bool
        Whether the iteration converged.
    complete : bool
        Whether both new unions were required (and found) free of the obstacle.
    union_in, union_out : Union or None
        start->pose and pose->goal of the last iterate.
    reason : str
        Why the last iterate failed ("" when ok).
    """

    pose: Pose
    polygon: int
    vertex: int
    side: int
    iterations: int
    ok: bool
    complete: bool
    union_in: Union | None
    union_out: Union | None
    reason: str = ""


@dataclass(frozen=True)
class Successor:
    """A successor of a node: the new pose and the free union that reaches it.

    Attributes
    ----------
    pose : Pose
    union : Union
        Collision-free, in bounds, within the steering limit.
    kind : str
        ``"goal"``, ``"vertex"`` (intermediate node near an obstacle vertex), ``"turn"``
        or ``"approach"`` (intermediate states of a difficult case, see
        :meth:`Expander.turn_states` and :meth:`Expander.approach_states`).
    key : tuple
        Identifies equivalent nodes for the search's closed set.
    candidate : Candidate or None
        The vertex candidate that produced it.
    """

    pose: Pose
    union: Union
    kind: str
    key: tuple
    candidate: Candidate | None = None


class Expander:
    """Successors of nodes toward a goal (section "Generation of intermediate nodes").

    Parameters
    ----------
    workspace : Workspace
    version : {"b", "a"}
        Fig. 4: ``"b"`` an optimal reference system per piece (the paper's choice), ``"a"``
        one reference system shared by the two pieces of an intermediate node.
    alpha_method : {"heuristic", "exact"}
        Passed to :func:`segplan.model.frame.optimal_alpha_intrinsic`.
    max_iterations : int
        Iterates per vertex candidate.
    r0 : float
        First distance of a candidate from its vertex along the bisectrix, in units of ``L``.
    growth : float
        Factor applied to the distance when an iterate fails.
    spline_weight : float
        First weight ``w`` of the clamped-spline heading, in ``[0, 1]``.
    turn_radius : float
        Radius of the arcs to turn states, in units of the minimum turning radius (> 1).
    turn_angles : tuple of float
        Arc angles (radians, in ``(0, pi/2]``) of the turn states, on each side.
    recursion : int
        Levels of intermediate nodes generated for a candidate's own union when that
        union hits another obstacle.
    steer_fallback : bool
        When the optimal reference system's cubic breaks the steering limit, use the
        frame of least peak curvature instead (:meth:`segplan.planning.links.LinkModel._steer`).
    slide : float
        Step along the obstacle's edge (units of ``L``) of the sliding iterates.
    all_obstacles : bool
        Candidates for every obstacle the direct union touches, not only the first.
    links : LinkModel, optional
        The link model (unions and their cost); by default one of ``workspace`` with
        ``alpha_method`` and ``steer_fallback`` (which it then overrides).

    Notes
    -----
    All lengths scale with ``L``. The paper gives no values; the defaults were chosen by
    trials on the shipped scenarios and on random worlds.
    """

    def __init__(
        self,
        workspace: Workspace,
        version: str = "b",
        alpha_method: str = "heuristic",
        max_iterations: int = 4,
        r0: float = 0.3,
        growth: float = 1.7,
        spline_weight: float = 0.5,
        turn_radius: float = 1.6,
        turn_angles: tuple[float, ...] = (HALF_PI, 0.25 * math.pi),
        recursion: int = 1,
        steer_fallback: bool = True,
        slide: float = 0.5,
        all_obstacles: bool = False,
        links: LinkModel | None = None,
    ):
        if version not in ("a", "b"):
            raise ValueError(
                f"version must be 'a' (one shared reference system) or 'b' (one per piece), got {version!r}"
            )
        if isinstance(max_iterations, bool) or int(max_iterations) != max_iterations or max_iterations < 1:
            raise ValueError(f"max_iterations must be an integer >= 1, got {max_iterations!r}")
        for name, value, lo in (("r0", r0, 0.0), ("growth", growth, 1.0), ("turn_radius", turn_radius, 1.0)):
            if not (math.isfinite(value) and value > lo):
                raise ValueError(f"{name} must be a finite number > {lo}, got {value!r}")
        if not 0.0 <= spline_weight <= 1.0:
            raise ValueError(f"spline_weight must lie in [0, 1], got {spline_weight!r}")
        if not turn_angles or not all(0.0 < a <= HALF_PI for a in turn_angles):
            raise ValueError(f"turn_angles must be angles in (0, pi/2] radians, got {turn_angles!r}")
        if links is None:
            links = LinkModel(workspace, alpha_method, steer_fallback)
        elif links.ws is not workspace:
            raise ValueError("links must be a LinkModel of the same workspace")
        self.ws = workspace
        self.links = links
        self.version = version
        self.alpha_method = links.alpha_method
        self.max_iterations = int(max_iterations)
        self.r0 = float(r0) * workspace.L
        self.growth = float(growth)
        self.spline_weight = float(spline_weight)
        kappa = workspace.max_curvature
        R = 1.0 / kappa if 0.0 < kappa < math.inf else workspace.L  # minimum turning radius
        self.turn_radius = float(turn_radius) * R
        self.turn_angles = tuple(float(a) for a in turn_angles)
        self.recursion = int(recursion)
        self.steer_fallback = links.steer_fallback
        self.slide = float(slide) * workspace.L
        self.all_obstacles = bool(all_obstacles)
        self._bisectors = [outward_bisectors(p) for p in workspace.polygons]
        self._setup_cache: dict = {}
        self._tangent_cache: dict = {}
        self._approach: tuple | None = None

    @property
    def stats(self) -> ExpansionStats:
        return self.ws.stats

    def reset_stats(self) -> None:
        self.ws.stats = ExpansionStats()

    # -- intermediate nodes --------------------------------------------------------------
    def shared_frame(self, start: Pose, goal: Pose) -> float:
        """Version "a": the optimal frame of the direct union, else its chord's angle."""
        u = self.links.union(start, goal)
        if u is not None:
            return u.frame_angle
        return math.atan2(goal[1] - start[1], goal[0] - start[0])

    def _tangents(self, polygon: int, point) -> tuple[int, int]:
        """:func:`segplan.planning.paper.bisectrix.tangent_vertices` of obstacle ``polygon`` seen from
        ``point`` (cached)."""
        key = (polygon, point[0], point[1])
        out = self._tangent_cache.get(key)
        if out is None:
            if len(self._tangent_cache) > 100_000:
                self._tangent_cache.clear()
            out = self._tangent_cache[key] = tangent_vertices(self.ws.polygons[polygon], point)
        return out

    def _setup(self, start: Pose, goal: Pose, polygon: int, side: int, subgoal: bool):
        """Vertex, completeness, bisectrix and reference headings of a candidate (cached:
        :meth:`first_estimate` and :meth:`intermediate` ask for the same one)."""
        key = (start, goal, polygon, side, subgoal)
        out = self._setup_cache.get(key)
        if out is None:
            if len(self._setup_cache) > 100_000:
                self._setup_cache.clear()
            out = self._setup_cache[key] = self._make_setup(start, goal, polygon, side, subgoal)
        return out

    def _make_setup(self, start: Pose, goal: Pose, polygon: int, side: int, subgoal: bool):
        poly = self.ws.polygons[polygon]
        ccw_s, cw_s = self._tangents(polygon, start)
        ccw_g, cw_g = self._tangents(polygon, goal)
        vertex = ccw_s if side > 0 else cw_s
        complete = not subgoal and vertex == (cw_g if side > 0 else ccw_g)
        v = poly[vertex]
        bx, by = self._bisectors[polygon][vertex]
        # perpendicular to the bisectrix, clockwise around the obstacle for side +1
        theta_perp = math.atan2(-bx, by) if side > 0 else math.atan2(bx, -by)
        # direction of the edge that leaves the vertex in the direction of travel
        nxt = poly[(vertex - 1) % len(poly)] if side > 0 else poly[(vertex + 1) % len(poly)]
        theta_edge = math.atan2(nxt[1] - v[1], nxt[0] - v[0])
        return vertex, complete, v, (float(bx), float(by)), theta_perp, theta_edge

    def first_estimate(self, start: Pose, goal: Pose, polygon: int, side: int, subgoal: bool = False) -> Pose:
        """The first iterate of :meth:`intermediate` (the paper's "good initial estimate")."""
        _, _, v, (bx, by), theta_perp, _ = self._setup(start, goal, polygon, side, subgoal)
        return iterate_pose(
            start, goal, v[0] + self.r0 * bx, v[1] + self.r0 * by, theta_perp, self.spline_weight
        )

    def intermediate(
        self, start: Pose, goal: Pose, polygon: int, side: int, subgoal: bool = False
    ) -> Candidate:
        """Generate an intermediate node passing obstacle ``polygon`` on ``side``.

        Iterates (at most ``max_iterations``) until the union start->P is free of the
        obstacle, exists and keeps the steering limit, and so does P->goal (free of the
        obstacle too when one node passes it, see the module docstring).

        Parameters
        ----------
        start, goal : Pose
        polygon : int
            Index of the offending obstacle.
        side : {+1, -1}
            ``+1``: pass with the obstacle on the robot's right.
        subgoal : bool
            ``goal`` is an intermediate node that another obstacle blocks (recursion),
            not the goal of the search: P->goal is then not required, since the next
            expansion from P aims at the search's goal.
        """
        vertex, complete, v, (bx, by), theta_perp, theta_edge = self._setup(
            start, goal, polygon, side, subgoal
        )
        frame = self.shared_frame(start, goal) if self.version == "a" else None
        ex, ey = math.cos(theta_edge), math.sin(theta_edge)
        r, w, base, slide, tight = self.r0, self.spline_weight, theta_perp, 0.0, False
        pose, u_in, u_out, reason = start, None, None, ""
        fallback = None
        for it in range(1, self.max_iterations + 1):
            pose = iterate_pose(start, goal, v[0] + r * bx + slide * ex, v[1] + r * by + slide * ey, base, w)
            u_in = u_out = None
            reason = self._check_candidate(start, goal, pose, polygon, complete, frame)
            if isinstance(reason, tuple):
                u_in, u_out, blocked = reason
                if not blocked:
                    self.stats.iterations.append((it, True, complete))
                    return Candidate(pose, polygon, vertex, side, it, True, complete, u_in, u_out)
                if fallback is None:
                    fallback = Candidate(
                        pose, polygon, vertex, side, it, True, complete, u_in, u_out, "blocked"
                    )
                reason = "blocked"
            if reason == "pose" and not tight:
                # readjust an unreasonable orientation: along the next edge (a tight spot)
                base, w, tight = theta_edge, 0.0, True
            elif reason == "pose":
                # the robot at P still touches something (a narrow gap): closer to the vertex
                r /= self.growth
            elif tight:
                # the robot fits only along the edge: slide along it, deeper into the passage
                slide += self.slide
            elif reason == "collision":
                r *= self.growth
            elif reason in ("infeasible_in", "curvature_in", "blocked"):
                # too sharp a turn from the start, or another obstacle on the way in: slide
                # along the next edge, with a smoother heading
                slide += self.slide
                if reason != "blocked":
                    base, w = theta_edge, 0.5 * (1.0 + w)
            else:  # the union to the goal does not exist or is too curved
                w = 0.5 * (1.0 + w)
                r *= self.growth
        if fallback is not None:
            # free of the offending obstacle but blocked by another: the caller generates
            # intermediate nodes for that one (recursion)
            self.stats.iterations.append((fallback.iterations, True, complete))
            return fallback
        self.stats.iterations.append((self.max_iterations, False, complete))
        return Candidate(
            pose, polygon, vertex, side, self.max_iterations, False, complete, u_in, u_out, reason
        )

    def _check_candidate(self, start, goal, pose, polygon, complete, frame):
        """Check one iterate.

        Returns ``(u_in, u_out, blocked)`` if start->pose exists, keeps the steering limit
        and is free of the offending obstacle, and, for a complete candidate, so is
        pose->goal (``u_out`` is None otherwise: the next expansion deals with it);
        ``blocked`` tells whether start->pose hits another obstacle or a wall. Otherwise a
        reason string: ``"pose"``, ``"infeasible_in"``, ``"curvature_in"``,
        ``"collision"``, ``"infeasible_out"``, ``"curvature_out"``.
        """
        if not self.ws.pose_free(pose):
            return "pose"
        u_in = self.links.union(start, pose, frame)
        if u_in is None:
            return "infeasible_in"
        if not self.ws.curvature_ok(u_in):
            return "curvature_in"
        if self.ws.colliding(u_in, only=(polygon,)):
            return "collision"
        u_out = None
        if complete:
            u_out = self.links.union(pose, goal, frame)
            if u_out is None:
                return "infeasible_out"
            if not self.ws.curvature_ok(u_out):
                return "curvature_out"
            if self.ws.colliding(u_out, only=(polygon,)):
                return "collision"
        # start->pose is free of ``polygon`` (above): it hits another obstacle iff it hits any
        blocked = not self.ws.in_bounds(u_in) or bool(self.ws.colliding(u_in))
        return u_in, u_out, blocked

    def turn_states(self, node: Pose) -> list[Pose]:
        """Turn states of a difficult case: ends of arcs of radius ``turn_radius`` from ``node``."""
        x, y, th = node
        R = self.turn_radius
        out = []
        for beta in self.turn_angles:
            for side in (1.0, -1.0):
                ax, ay, t = arc_end(x, y, th, R, side, beta)
                out.append(Pose(ax, ay, wrap_fmod(t)))
        return out

    def approach_states(self, goal: Pose) -> list[tuple[Pose, Union]]:
        """Approach states of the goal, with their free unions to it (cached per goal).

        The mirror image of :meth:`turn_states`: poses from which the robot reaches the
        goal along an arc of radius ``turn_radius`` turning by ``turn_angles`` to either
        side, or straight along the goal's heading from ``2 L`` behind it. They are the
        "suitable intermediate states" of a difficult final approach (a goal near a wall
        or heading against the direction of arrival).
        """
        if self._approach is not None and self._approach[0] == goal:
            return self._approach[1]
        back = Pose(goal.x, goal.y, wrap_fmod(goal.theta + math.pi))
        poses = [Pose(p.x, p.y, wrap_fmod(p.theta + math.pi)) for p in self.turn_states(back)]
        c, s = math.cos(goal.theta), math.sin(goal.theta)
        poses.append(Pose(goal.x - 2.0 * self.ws.L * c, goal.y - 2.0 * self.ws.L * s, goal.theta))
        out = []
        self.links.prefetch([(p, goal) for p in poses])
        for pose in poses:
            if not self.ws.pose_free(pose):
                continue
            u = self.links.union(pose, goal)
            if u is not None and self.ws.union_free(u):
                out.append((pose, u))
        self._approach = (goal, out)
        return out

    # -- successors --------------------------------------------------------------------
    def direct(self, node: Pose, goal: Pose) -> Union | None:
        """The direct union node->goal in its optimal reference system (cached)."""
        return self.links.union(node, goal)

    def successors(self, node: Pose, goal: Pose, turns: bool = True) -> list[Successor]:
        """Successors of ``node`` in the on-line graph, toward ``goal``.

        The goal itself if the direct union is free; otherwise intermediate nodes near the
        first offending obstacle (both sides); turn states for the difficult cases.
        Every returned union is free, in bounds and within the steering limit.
        """
        u = self.direct(node, goal)
        out: list[Successor] = []
        if u is not None and self.ws.curvature_ok(u):
            hit = self.ws.colliding(u, first=not self.all_obstacles)
            inside = self.ws.in_bounds(u)
            if not hit and inside:
                return [Successor(goal, u, "goal", ("goal",))]
            if hit:
                # obstacles: intermediate nodes near their vertices; turn states only if
                # none works
                seen = set()
                for polygon in hit:
                    for succ in self._around(node, goal, polygon, self.recursion):
                        if succ.key not in seen:
                            seen.add(succ.key)
                            out.append(succ)
                if out:
                    return out
        # a difficult case: approach states of the goal, and turn states of the node
        return self._approaches(node, goal) + (self._turns(node) if turns else [])

    def _around(self, node: Pose, target: Pose, polygon: int, depth: int, subgoal=False) -> list[Successor]:
        if self.version == "b":
            # both sides' first estimates (usually accepted) in one vectorised batch
            firsts = [self.first_estimate(node, target, polygon, side, subgoal) for side in (1, -1)]
            self.links.prefetch([(node, p) for p in firsts] + [(p, target) for p in firsts])
        out = []
        for side in (1, -1):
            cand = self.intermediate(node, target, polygon, side, subgoal)
            if not cand.ok:
                continue
            u = cand.union_in
            if not self.ws.in_bounds(u):
                continue
            hit = self.ws.colliding(u)
            if not hit:
                key = ("vertex", polygon, cand.vertex, side, round(cand.pose.theta / (math.pi / 6)))
                out.append(Successor(cand.pose, u, "vertex", key, cand))
            elif depth > 0:
                out += self._around(node, cand.pose, hit[0], depth - 1, subgoal=True)
        return out

    def _approaches(self, node: Pose, goal: Pose) -> list[Successor]:
        out = []
        states = self.approach_states(goal)
        self.links.prefetch([(node, p) for p, _ in states])
        for i, (pose, _) in enumerate(states):
            if pose == node:
                continue
            u = self.links.union(node, pose)
            if u is not None and self.ws.union_free(u):
                out.append(Successor(pose, u, "approach", ("approach", i)))
        return out

    def _turns(self, node: Pose) -> list[Successor]:
        out = []
        q = 0.25 * self.ws.L
        states = self.turn_states(node)
        self.links.prefetch([(node, p) for p in states])
        for pose in states:
            if not self.ws.pose_free(pose):
                continue
            u = self.links.union(node, pose)
            if u is None or not self.ws.union_free(u):
                continue
            key = ("turn", round(pose.x / q), round(pose.y / q), round(pose.theta / (math.pi / 8)))
            out.append(Successor(pose, u, "turn", key))
        return out
