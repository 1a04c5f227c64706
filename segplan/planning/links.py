"""The link model: the cubic union of two poses in its optimal frame, and its cost.

Sections "Generation of the trajectory of union between two nodes", "Cost function" and
"Optimal reference system" of Campoy et al. (1989), as the planner uses them: two poses
are joined by the cubic union (:class:`segplan.Union`) in the optimal reference system
(:func:`segplan.model.frame.optimal_alpha_intrinsic`, heuristic or exact); its cost is LONGD,
formula [2] inside its validated domain and [1] by Romberg outside
(:func:`segplan.model.cost.longd`).

*Steering fallback* (not in the paper). When the optimal frame's cubic breaks the
steering limit, the frame of least peak curvature is taken instead, if it keeps the
limit (:meth:`LinkModel._steer`).

*Observer hook.* ``LinkModel(..., observer=f)`` calls ``f(union, cost)`` on every link
cost the planner asks for (``g`` of links and ``h'`` (a) alike): a study records the
link costs of a search without patching the planner
(:func:`segplan.planning.api.plan_scenario_observed`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..model.cost import longd_intrinsic_scalar
from ..model.frame import heuristic_alpha, optimal_alpha_intrinsic
from ..model.pose import Pose, intrinsic_interval, wrap_fmod
from ..model.romberg import RombergError
from ..model.union import Union, cubic_coefficients, curvature_samples, peak_curvature
from .validity import Workspace

__all__ = [
    "ALPHA_MARGIN",
    "LONGD_RTOL",
    "PREFETCH_MIN_HEURISTIC",
    "STEER_SAMPLES",
    "LinkModel",
]

#: Margin (radians) kept from the ends of the interval where the cubic exists.
ALPHA_MARGIN = 1e-9
#: Romberg tolerance of link costs outside the domain of formula [2] (the paper uses Romberg
#: with the same error bound as [2], 2.5 %; we keep far below it).
LONGD_RTOL = 1e-5
#: Alphas tried by the steering fallback of :meth:`LinkModel.union`.
STEER_SAMPLES = 15
_TAU = np.linspace(0.0, 1.0, 33)
#: Fewest pose pairs that :meth:`LinkModel.prefetch` sends to the array path of the
#: heuristic optimal frame (fewer: the scalar path, pair by pair, is faster).
PREFETCH_MIN_HEURISTIC = 12


class LinkModel:
    """Unions between poses (optimal frame, steering fallback) and their LONGD cost.

    Parameters
    ----------
    workspace : Workspace
        The validity checker (its steering limit decides the fallback; its counters
        ``unions``, ``infeasible``, ``batched`` are updated).
    alpha_method : {"heuristic", "exact"}
        Passed to :func:`segplan.model.frame.optimal_alpha_intrinsic`.
    steer_fallback : bool
        When the optimal reference system's cubic breaks the steering limit, use the
        frame of least peak curvature instead (see :meth:`_steer`).
    observer : callable, optional
        ``observer(union, cost)`` on every :meth:`link_cost` call.
    """

    def __init__(
        self,
        workspace: Workspace,
        alpha_method: str = "heuristic",
        steer_fallback: bool = True,
        observer: Callable[[Union, float], None] | None = None,
    ):
        if alpha_method not in ("heuristic", "exact"):
            raise ValueError(f"alpha_method must be 'heuristic' or 'exact', got {alpha_method!r}")
        if observer is not None and not callable(observer):
            raise ValueError(f"observer must be callable, got {observer!r}")
        self.ws = workspace
        self.L = workspace.L
        self.alpha_method = alpha_method
        self.steer_fallback = bool(steer_fallback)
        self.observer = observer
        self._cache: dict = {}
        self._alphas: dict = {}
        self._costs: dict = {}

    def union(self, p0: Pose, p1: Pose, frame_angle: float | None = None) -> Union | None:
        """The cubic union p0 -> p1, or None if no cubic exists.

        Parameters
        ----------
        frame_angle : float, optional
            World angle of the reference system's x-axis (version "a"); by default the
            optimal reference system (section "Optimal reference system"), cached per
            pose pair.
        """
        key = (p0, p1, frame_angle)
        if key in self._cache:
            return self._cache[key]
        u = self._make_union(p0, p1, frame_angle)
        if len(self._cache) > 200_000:
            self._cache.clear()
        self._cache[key] = u
        return u

    def prefetch(self, pairs) -> None:
        """Optimal reference systems of several pose pairs in one vectorised call.

        :func:`segplan.model.frame.optimal_alpha_intrinsic` costs far less per pair on arrays
        than on scalars for the exact method; the alphas are kept until :meth:`union` asks
        for them. Pairs without a cubic or already known are skipped. The heuristic
        method's scalar path is the faster one for fewer than
        :data:`PREFETCH_MIN_HEURISTIC` pairs (about 20 us a pair against 0.25-0.4 ms a
        call on arrays), so such batches are left to :meth:`union`, pair by pair. The two
        paths agree to rounding (a few 1e-15 rad).
        """
        if self.alpha_method == "heuristic" and len(pairs) < PREFETCH_MIN_HEURISTIC:
            return
        keys, geos = [], []
        for p0, p1 in pairs:
            if (p0, p1, None) in self._cache or (p0, p1) in self._alphas:
                continue
            geo = intrinsic_interval(p0, p1, ALPHA_MARGIN)
            if geo is not None:
                keys.append((p0, p1))
                geos.append(geo)
        if len(keys) < 2:
            return
        d, _, phi0, phi1, _, _ = (np.array(v) for v in zip(*geos, strict=True))
        try:
            alphas = self._optimal_alpha(d, phi0, phi1)
        except ValueError:
            return
        self.ws.stats.batched += len(keys)
        if len(self._alphas) > 10_000:
            self._alphas.clear()
        for key, a in zip(keys, np.atleast_1d(alphas), strict=True):
            self._alphas[key] = float(a)

    def _optimal_alpha(self, d, phi0, phi1):
        """:func:`segplan.model.frame.optimal_alpha_intrinsic` of pairs from
        :func:`segplan.model.pose.intrinsic_interval`.

        Those are valid by construction (``d > 0``, finite, a feasible interval wider than
        ``2 ALPHA_MARGIN``), so the heuristic method skips the re-validation (the same
        values: :func:`segplan.model.frame.heuristic_alpha` is what the method calls).
        """
        if self.alpha_method == "heuristic" and 0.0 < self.L < math.inf:
            return heuristic_alpha(d, phi0, phi1, self.L)
        return optimal_alpha_intrinsic(d, phi0, phi1, self.L, method=self.alpha_method)

    def _make_union(self, p0, p1, frame_angle):
        geo = intrinsic_interval(p0, p1, ALPHA_MARGIN)
        if geo is None:
            self.ws.stats.infeasible += 1
            return None
        d, psi, phi0, phi1, lo, hi = geo
        if frame_angle is None:
            alpha = self._alphas.pop((p0, p1), None)
            if alpha is None:
                try:
                    alpha = float(self._optimal_alpha(d, phi0, phi1))
                except ValueError:
                    self.ws.stats.infeasible += 1
                    return None
        else:
            alpha = wrap_fmod(psi - frame_angle)
        if not lo < alpha < hi:
            self.ws.stats.infeasible += 1
            return None
        self.ws.stats.unions += 1
        u = Union.from_intrinsic(p0, p1, alpha, self.L, d, psi, phi0, phi1)
        if frame_angle is None and self.steer_fallback and not self.ws.curvature_ok(u):
            u = self._steer(p0, p1, d, psi, phi0, phi1, lo, hi) or u
        return u

    def _steer(self, p0, p1, d, psi, phi0, phi1, lo, hi) -> Union | None:
        """Steering fallback: the frame of least sampled peak curvature, if it keeps the limit.

        The optimal reference system minimises LONGD, not curvature; when its cubic breaks
        the steering limit another alpha may keep it (our addition: the paper has no
        steering limit). ``STEER_SAMPLES`` alphas across the feasible interval are scored by
        their largest curvature on 33 abscissae (one vectorised evaluation); the best is
        checked exactly.
        """
        alphas = lo + (hi - lo) * (np.arange(1, STEER_SAMPLES + 1) / (STEER_SAMPLES + 1))
        X, c1, c2, c3 = cubic_coefficients(d, phi0, phi1, alphas)
        _, fp, fpp = curvature_samples(X[:, None], c1[:, None], c2[:, None], c3[:, None], _TAU)
        peak = peak_curvature(fp, fpp, axis=1)
        k = int(np.argmin(peak))
        if not peak[k] < self.ws.max_curvature:
            return None
        self.ws.stats.unions += 1
        u = Union.from_intrinsic(p0, p1, float(alphas[k]), self.L, d, psi, phi0, phi1)
        return u if self.ws.curvature_ok(u) else None

    def link_cost(self, u: Union) -> float:
        """LONGD of a union (formula [2] inside its domain, [1] outside: :func:`segplan.model.cost.longd`).

        ``inf`` for a near-singular cubic whose integral [1] cannot be brought to the
        error bound (such a union also breaks the steering limit). Kept per union (this
        model's own store). Every call is reported to the ``observer``, if any.
        """
        key = id(u)
        hit = self._costs.get(key)
        if hit is not None and hit[0] is u:
            cost = hit[1]
        else:
            try:
                cost = longd_intrinsic_scalar(u.d, u.phi0, u.phi1, u.alpha, u.L, LONGD_RTOL)
            except RombergError:
                cost = math.inf
            if len(self._costs) > 4096:
                self._costs.clear()
            self._costs[key] = (u, cost)  # keeps the union alive, so its id is not reused
        if self.observer is not None:
            self.observer(u, cost)
        return cost
