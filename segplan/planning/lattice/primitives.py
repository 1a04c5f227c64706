"""Motion primitives out of cubic unions: short unions between the states of a lattice.

Beyond the paper (issue 12). A symmetric cubic union that turns the robot by a small
angle is close to a circular arc (turning by 30 deg its curvature peaks about 3.5 % above
the circle's), so chains of short unions follow a circle close to the minimum turning
radius ``R = L / tan(max_steer)``, which one long union cannot do (chapter 8).

The lattice (:class:`PrimitiveSet`) has square cells of side ``resolution`` and the 16
*grid-aligned* headings of the vectors ``(1, 0), (2, 1), (1, 1), (1, 2), (0, 1), ...``
(0, 26.6, 45, 63.4, 90 deg, ...), so that a straight step along any heading ends on a
lattice point. A primitive joins the state ``(0, 0, k)`` to a state ``(i, j, k')`` of the
lattice by the paper's cubic union (section III) in its optimal reference system
(:func:`segplan.model.frame.heuristic_alpha`; the frame of least peak curvature when that one
breaks the steering limit); it is kept only if its rear path's curvature stays within
``tan(max_steer) / L`` everywhere (exact maximum, :meth:`segplan.Union.max_curvature`).
Its cost is the exact LONGD, formula [1] (Romberg).

Which primitives: from each heading, the unit straight step, and for every turn by one or
two heading steps (about 22.5 or 45 deg) the cheapest lattice end points, fewest first,
skipping one whose end state a chain of at most three kept primitives already reaches
at no more than ``1 + PRUNE`` times its cost (the pruning of Pivtoraiko and Kelly's
state lattices).

The set of heading ``k + 4`` is the set of ``k`` turned by 90 deg (exact in integers). A
union's shape and cost do not change under a rigid motion, so the set is made once per
``(L, max_steer, resolution)`` (:func:`primitive_set`, kept in an explicit least-recently-
used cache) and reused by every plan. The sets of the default lattice (45 deg steering,
resolutions ``L / 2`` to ``L / 16``: :data:`STORED_CELLS`) are package data for a unit ``L``
(``primitives.npz``, written with its provenance by ``python -m segplan.fit``, which
recomputes them with :func:`compute_primitive_set`), scaled to ``L`` when read: a fresh
process does not compute them (about 0.06 s of CPU for the four).

The selection is the same on every processor. Many candidates tie exactly (a turn and its
mirror image about a diagonal or an axis of the lattice have the same chord, turn and
LONGD), and their estimates then differ only in the last bits, which vectorised maths and
BLAS kernels round differently from one processor to the next (up to 5e-16 relative,
measured between OpenBLAS's Haswell, SkylakeX, Sandybridge, Prescott and Nehalem kernels
and numpy's AVX-512, AVX2 and baseline code paths). Candidates are therefore ranked by
their estimate rounded to :data:`RANK_DECIMALS` decimals of ``L``, ties broken by their
integers ``(h0, h1, i, j)`` (:func:`_rank`). Every other decision of the selection (a
chain's cost against its budget, a peak curvature against the limit, a sample against the
reach bound) keeps a margin ten orders of magnitude above the rounding differences on the
stored sets (:func:`selection_margins`; ``tests/test_primitives_data.py``).

Every primitive also carries points of its swept segment (rear point A, front wheel B and
points between them, at abscissae along the union) relative to its start, and ``delta``:
every point of the swept segment lies within ``delta`` of one of them. A planner screens
a primitive by these points (:mod:`segplan.planning.lattice.astar`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ...model.cost import longd_exact_intrinsic, longd_gauss_intrinsic
from ...model.frame import heuristic_alpha
from ...model.pose import alpha_interval, wrap
from ...model.union import Union, cubic_coefficients, curvature_samples, max_curvatures, peak_curvature
from .chains import Chains
from .frame import HEADING_VECTORS, NH, LatticeFrame, heading_angles

__all__ = [
    "DATA_PATH",
    "FIELDS",
    "STORED_CELLS",
    "STORED_STEER",
    "Primitive",
    "PrimitiveSet",
    "compute_primitive_set",
    "from_arrays",
    "max_reach",
    "primitive_arrays",
    "primitive_set",
    "selection_margins",
    "stored_sets",
]

#: A primitive is dropped if a chain of kept ones reaches its end state within this factor.
PRUNE = 0.03
#: Turns (heading steps) of the turning primitives.
TURNS = (-2, -1, 1, 2)
#: Turning primitives kept per start heading and turn, at most.
PER_TURN = 3
#: Decimals (of ``L``) to which a candidate's estimated LONGD is rounded before ranking
#: (:func:`_rank`): 1e-9 L merges exact ties that rounding split by up to 5e-16 relative,
#: and only those (the closest distinct estimates of the stored sets are 7e-6 L apart:
#: :func:`selection_margins`, ``tests/test_primitives_data.py``); a tie straddles a rounding
#: boundary with probability about 1e-15 / 1e-9 per pair.
RANK_DECIMALS = 9
#: Abscissae (fractions of the frame span) and positions along the segment of the samples.
SAMPLE_S = np.linspace(0.0, 1.0, 13)
SAMPLE_T = np.linspace(0.0, 1.0, 7)
#: The finer samples of :meth:`PrimitiveSet.fine_points` (a tighter screen near obstacles).
FINE_S = np.linspace(0.0, 1.0, 49)
FINE_T = np.linspace(0.0, 1.0, 25)
_STEER_ALPHAS = 15
_PEAK_S = np.linspace(0.0, 1.0, 49)
#: The ends of :data:`_PEAK_S` (:func:`_peaks`' screen), one row each.
_ENDS_S = _PEAK_S[[0, -1], None]


@dataclass(frozen=True)
class Primitive:
    """One motion primitive from the lattice state ``(0, 0, h0)``.

    Attributes
    ----------
    h0, h1 : int
        Start and end heading indices (0..15).
    di, dj : int
        End point in lattice cells.
    cost : float
        Exact LONGD [1] (front-wheel path length, m).
    alpha : float
        The union's alpha (radians), in its intrinsic system (rigid-motion invariant).
    d, phi0, phi1 : float
        Chord length and intrinsic headings.
    peak_curvature : float
        Largest rear-path curvature (1/m).
    points : ndarray (n, 2)
        Points of the swept segment relative to the start point, lattice axes.
    delta : float
        Every point of the swept segment lies within ``delta`` of ``points``.
    """

    h0: int
    h1: int
    di: int
    dj: int
    cost: float
    alpha: float
    d: float
    phi0: float
    phi1: float
    peak_curvature: float
    points: np.ndarray
    delta: float


_ANGLES = heading_angles()


@dataclass(frozen=True)
class PrimitiveSet:
    """The primitives of every lattice heading, for one robot and resolution.

    Attributes
    ----------
    L, max_steer, resolution : float
    by_heading : tuple of tuple of Primitive
        ``by_heading[h]``: the primitives that start at heading ``h``.
    """

    L: float
    max_steer: float
    resolution: float
    by_heading: tuple
    #: What :meth:`fine_points` and :meth:`heading_tables` computed for this set (kept while
    #: the set lives; not part of its value).
    _derived: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def min_turning_radius(self) -> float:
        """``R = L / tan(max_steer)``."""
        return self.L / math.tan(self.max_steer)

    def turning_radii(self) -> np.ndarray:
        """Radius of the circle through each turning primitive's ends, tangent to its start.

        ``d / (2 sin(|dtheta| / 2))`` for a turn by ``dtheta`` over a chord ``d``: the radius of
        the circle that a chain of such primitives follows on average (relative to nothing:
        metres).
        """
        out = []
        for p in self.by_heading[0] + self.by_heading[1] + self.by_heading[2] + self.by_heading[3]:
            turn = abs(float(wrap(_ANGLES[p.h1] - _ANGLES[p.h0])))
            if turn > 0:
                out.append(p.d / (2.0 * math.sin(0.5 * turn)))
        return np.array(out)

    def count(self) -> int:
        """Primitives per heading, on average."""
        return sum(len(b) for b in self.by_heading) // NH

    def fine_points(self) -> tuple[tuple[np.ndarray, np.ndarray], ...]:
        """Per heading ``h``: finer swept-segment points of the primitives ``by_heading[h]``
        (array ``(m, n, 2)``, relative to the start, lattice axes; :data:`FINE_S` x :data:`FINE_T`)
        and their covering radii ``(m,)``, smaller than :attr:`Primitive.delta`.

        A planner screens a primitive by these where its coarse points are not conclusive
        (close to an obstacle), before the certified test. Computed once per set.
        """
        out = self._derived.get("fine")
        if out is None:
            frame = LatticeFrame((0.0, 0.0, 0.0), self.resolution, self.L)
            base = []
            for h in range(4):
                g = _geometry([frame.union((0, 0, h), p) for p in self.by_heading[h]])
                base.append((_points(g, self.L, FINE_S, FINE_T), _covering(g, self.L, FINE_S, FINE_T)))
            out = []
            for h in range(NH):
                pts, dl = base[h % 4]
                for _ in range(h // 4):
                    pts = np.stack((-pts[..., 1], pts[..., 0]), axis=-1)
                out.append((np.ascontiguousarray(pts), dl))
            out = self._derived["fine"] = tuple(out)
        return out

    def heading_tables(self, cell: float) -> tuple:
        """Per heading, the tables the lattice search (:mod:`segplan.planning.lattice.astar`) expands with.

        Parameters
        ----------
        cell : float
            The clearance grid's cell size (metres).

        Returns
        -------
        tuple
            ``(points, cells, delta, step, cost)``, each a list over the headings: the
            primitives' sampled points, their cells ``(i, j)`` relative to the start's cell,
            covering radii (plus 1e-9), steps ``(di, dj, h1)`` and LONGD costs [1]. Computed
            once per cell.
        """
        key = ("tables", float(cell))
        out = self._derived.get(key)
        if out is None:
            points, cells, delta, step, cost = [], [], [], [], []
            for prims in self.by_heading:
                pts = np.stack([p.points for p in prims])
                points.append(pts)
                cells.append(tuple(np.floor(pts[..., k] / cell).astype(np.int64) for k in (0, 1)))
                delta.append(np.array([p.delta for p in prims]) + 1e-9)
                step.append([(p.di, p.dj, p.h1) for p in prims])
                cost.append([p.cost for p in prims])
            out = self._derived[key] = (points, cells, delta, step, cost)
        return out


def _all_headings(base: list[list[Primitive]]) -> tuple[tuple[Primitive, ...], ...]:
    """The primitives of every heading from those of headings 0..3: heading ``h`` holds those
    of ``h % 4`` turned by ``h // 4`` quarter turns (exact: integers swapped and negated, the
    points' coordinates too)."""
    out = [tuple(b) for b in base]
    for h in range(4, NH):
        q, prims = h // 4, base[h % 4]
        pts = np.stack([p.points for p in prims])
        x, y = pts[..., 0], pts[..., 1]
        if q == 1:
            pts = np.stack((-y, x), axis=-1)
        elif q == 2:
            pts = -pts
        else:
            pts = np.stack((y, -x), axis=-1)
        turned = []
        for p, points in zip(prims, pts, strict=True):
            di, dj = ((-p.dj, p.di), (-p.di, -p.dj), (p.dj, -p.di))[q - 1]
            h0, h1 = (p.h0 + 4 * q) % NH, (p.h1 + 4 * q) % NH
            turned.append(
                Primitive(
                    h0, h1, di, dj, p.cost, p.alpha, p.d, p.phi0, p.phi1, p.peak_curvature, points, p.delta
                )
            )
        out.append(tuple(turned))
    return tuple(out)


def _chord_reach(r: float, R: float) -> float:
    """Longest chord of a turning primitive: a 50 deg turn at 1.7 R, plus two cells."""
    return 2.0 * 1.7 * R * math.sin(math.radians(25.0)) + 2.0 * r


def max_reach(L: float, max_steer: float, resolution: float) -> float:
    """A bound of ``|points|`` of every primitive of :func:`primitive_set` (kept by construction)."""
    return 1.25 * _chord_reach(float(resolution), float(L) / math.tan(max_steer)) + float(L)


def _candidates(h0: int, r: float, R: float):
    """Lattice end states ``(i, j, h1)`` of turning unions from ``(0, 0, h0)`` that a cubic joins.

    Returns arrays ``i, j, h1, d, phi0, phi1, lo, hi`` (``lo, hi``: the feasible alpha interval).
    """
    th0 = _ANGLES[h0]
    reach = _chord_reach(r, R)
    m = int(math.ceil(reach / r))
    g = np.arange(-m, m + 1)
    I, J = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    d = np.hypot(I, J) * r
    psi = np.arctan2(J, I)
    phi0 = wrap(th0 - psi)
    ahead = (d > 0) & (d <= reach) & (np.abs(phi0) < 0.5 * math.pi)  # the end points, then their turns
    I, J, d, psi, phi0 = (np.repeat(v[ahead], len(TURNS)) for v in (I, J, d, psi, phi0))
    H1 = (h0 + np.tile(np.array(TURNS), len(I) // len(TURNS))) % NH
    phi1 = wrap(_ANGLES[H1] - psi)
    lo, hi = alpha_interval(phi0, phi1)
    ok = hi - lo > 1e-6
    return I[ok], J[ok], H1[ok], d[ok], phi0[ok], phi1[ok], lo[ok], hi[ok]


#: Candidates whose LONGD [1] the selection computes and which it makes in one batch
#: (:func:`_exact`, :func:`_make`): the one it makes and the next that it may keep (no chain
#: reaching them yet, no more of a turn than it has room for), most of which it keeps (8, 16,
#: 24, 32 and 48 measured: 24 about the fastest at L / 2 and L / 8).
_AHEAD = 24
#: Unions per block of :func:`_peaks` (its temporaries stay in the CPU's caches).
_PEAK_BLOCK = 4096


def _peaks(d, phi0, phi1, alpha, kmax: float | None = None) -> np.ndarray:
    """Largest rear-path curvature sampled at 49 abscissae, vectorised over unions (arrays
    that broadcast to one shape; in blocks of rows of about :data:`_PEAK_BLOCK` unions: the
    same values, less memory traffic).

    With ``kmax``: ``inf`` for the unions whose curvature at one of their ends (the first and
    last of the 49 samples, the same values to the last bit: the start's first, where
    :func:`~segplan.model.union.curvature_samples`' terms in ``x`` vanish, the end's of the
    unions it leaves) already exceeds ``kmax``, their other samples not computed;
    ``peak <= kmax`` is then decided as without ``kmax`` (the samples are finite: alphas
    inside their intervals), and the least of several peaks is the same wherever it is at
    most ``kmax``.
    """
    args = np.broadcast_arrays(*(np.atleast_1d(np.asarray(v, dtype=float)) for v in (d, phi0, phi1, alpha)))
    out = np.empty(args[0].shape)
    rows = max(1, _PEAK_BLOCK // max(1, math.prod(out.shape[1:])))  # blocks of whole rows: views, not copies
    for k in range(0, len(out), rows):
        sl = slice(k, k + rows)
        X, c1, c2, c3 = (
            np.asarray(v, dtype=float).ravel() for v in cubic_coefficients(*(v[sl] for v in args))
        )
        block = out[sl].reshape(-1)
        if kmax is not None:  # the start, then the end of the unions it leaves (one row each)
            start = peak_curvature(c1[None], 2.0 * c2[None], axis=0)  # x = 0: f' = c1, f'' = 2 c2
            rest = np.flatnonzero(~(start > kmax))
            _, fp, fpp = curvature_samples(X[rest], c1[rest], c2[rest], c3[rest], _ENDS_S[1:])
            rest = rest[~(np.maximum(start[rest], peak_curvature(fp, fpp, axis=0)) > kmax)]
            block[:] = math.inf
            X, c1, c2, c3 = X[rest], c1[rest], c2[rest], c3[rest]
        else:
            rest = slice(None)
        _, fp, fpp = curvature_samples(X[:, None], c1[:, None], c2[:, None], c3[:, None], _PEAK_S)
        block[rest] = peak_curvature(fp, fpp)
    return out


def _best_alphas(parts: list[tuple], L, kmax, margins: dict | None = None) -> list[np.ndarray]:
    """Per union: the optimal frame's alpha if its cubic keeps the steering limit (sampled),
    else the alpha of least sampled peak curvature among ``_STEER_ALPHAS`` if that keeps it,
    else NaN; ``parts``: each start heading's candidates (:func:`_candidates`), one array of
    alphas each. ``margins``: see :func:`selection_margins` (every peak is then computed;
    without, the unions whose ends already break the limit are not sampled further:
    :func:`_peaks`).

    The optimal frames one heading at a time (:func:`segplan.model.frame.heuristic_alpha`'s
    product with its fit's coefficients rounds by a row's place in the array), the peaks of
    all the headings' unions at once (elementwise: the same values).
    """
    screen = kmax if margins is None else None
    d, phi0, phi1, lo, hi = (np.concatenate([p[k] for p in parts]) for k in range(3, 8))
    a = np.concatenate(
        [
            np.clip(np.asarray(heuristic_alpha(*p[3:6], L), dtype=float), p[6] + 1e-9, p[7] - 1e-9)
            for p in parts
        ]
    )
    peak = _peaks(d, phi0, phi1, a, screen)
    bad = ~(peak <= kmax)
    checked = [peak]
    if bad.any():
        f = (np.arange(1, _STEER_ALPHAS + 1) / (_STEER_ALPHAS + 1))[None, :]
        grid = lo[bad, None] + (hi[bad] - lo[bad])[:, None] * f
        pk = _peaks(d[bad, None], phi0[bad, None], phi1[bad, None], grid, screen)
        k = np.argmin(pk, axis=1)
        best = grid[np.arange(len(k)), k]
        least = pk[np.arange(len(k)), k]
        a[bad] = np.where(least <= kmax, best, np.nan)
        checked.append(least)
        if margins is not None and pk.shape[1] > 1:
            two = np.sort(pk, axis=1)[:, :2]
            _note(margins, "frame", np.min((two[:, 1] - two[:, 0]) / two[:, 0]))
    if margins is not None:
        _note(margins, "steer", np.min(np.abs(np.concatenate(checked) - kmax)) / kmax)
    return np.split(a, np.cumsum([len(p[3]) for p in parts])[:-1])


def _geometry(unions: list[Union]) -> tuple[np.ndarray, ...]:
    """Per union, as columns ``(m, 1)``: start point ``x0, y0``, frame angle ``fa`` with its
    cosine and sine (``math``'s, as :meth:`segplan.Union.to_world` takes them), span ``X`` and
    coefficients ``c1, c2, c3``."""
    rows = []
    for u in unions:
        fa = u.frame_angle
        rows.append((u.p0.x, u.p0.y, fa, math.cos(fa), math.sin(fa), u.x_end, *u.coefficients[1:]))
    return _columns(rows)


def _columns(rows: list[tuple]) -> tuple[np.ndarray, ...]:
    """The columns ``(m, 1)`` of :func:`_geometry` from its rows, one union's values each."""
    return tuple(np.array(col)[:, None] for col in zip(*rows, strict=True))


def _rear(g: tuple[np.ndarray, ...], x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """World coordinates ``x, y`` of the rear point A and headings, each ``(m, n)``, at frame
    abscissae ``x`` ``(m, n)`` of the unions of :func:`_geometry` ``g``: :meth:`segplan.Union.f`,
    :meth:`~segplan.Union.to_world` and :meth:`~segplan.Union.heading` vectorised over
    unions, their arithmetic in their order (the same bits)."""
    x0, y0, fa, c, s, _, c1, c2, c3 = g
    y = ((c3 * x + c2) * x + c1) * x  # f(x)
    heading = fa + np.arctan((3.0 * c3 * x + 2.0 * c2) * x + c1)  # frame angle + arctan f'(x)
    return x0 + c * x - s * y, y0 + s * x + c * y, heading


def _points(g: tuple[np.ndarray, ...], L: float, S: np.ndarray, T: np.ndarray) -> np.ndarray:
    """Swept-segment points ``(m, len(S) len(T), 2)`` of the unions of :func:`_geometry` ``g``
    relative to their starts: at abscissae ``S`` (fractions of the span) the rear point A and
    the points at fractions ``T`` of the segment from A to the front wheel B."""
    ax, ay, h = _rear(g, g[5] * S)
    A = np.stack((ax, ay), axis=-1) - np.stack((g[0], g[1]), axis=-1)
    U = np.stack((np.cos(h), np.sin(h)), axis=-1)
    return (A[:, :, None, :] + L * T[None, None, :, None] * U[:, :, None, :]).reshape(len(A), -1, 2)


def _covering(g: tuple[np.ndarray, ...], L: float, S: np.ndarray, T: np.ndarray) -> np.ndarray:
    """Covering radius ``delta`` ``(m,)`` of :func:`_points`: every point of a union's swept
    segment lies within ``delta`` of one of them.

    Half the longest move of A or B between consecutive abscissae (measured along a dense
    sampling: path length, not chord) plus half the spacing along the segment.
    """
    per = 24
    ax, ay, h = _rear(g, g[5] * np.linspace(0.0, 1.0, (len(S) - 1) * per + 1))
    bx, by = ax + L * np.cos(h), ay + L * np.sin(h)  # the front wheel B
    runs = []
    for px, py in ((ax, ay), (bx, by)):
        steps = np.hypot(np.diff(px, axis=1), np.diff(py, axis=1))
        runs.append(steps.reshape(len(px), -1, per).sum(axis=-1).max(axis=-1))
    return 0.5 * np.maximum(*runs) * 1.02 + 0.5 * L * (T[1] - T[0])


def _exact(rows: list[tuple], L: float) -> list[float]:
    """LONGD [1] (Romberg, ``rtol = 1e-10``) of candidates ``(..., alpha, d, phi0, phi1)``: one
    batch, each value that of a call for it alone to the last bit (``each``)."""
    alpha, d, phi0, phi1 = (np.array(col, dtype=float) for col in list(zip(*rows, strict=True))[-4:])
    return np.atleast_1d(longd_exact_intrinsic(d, phi0, phi1, alpha, L, rtol=1e-10, each=True)).tolist()


def _make(rows: list[tuple], r: float, L: float) -> list[tuple[Primitive, tuple]]:
    """Primitives of candidates ``(h0, h1, i, j, alpha, d, phi0, phi1, cost)`` (``cost``: their
    LONGD [1], :func:`_exact`), their covering radii still NaN (:func:`_covered` sets them),
    each with its union's row of :func:`_geometry`.

    One vectorised pass, each value that of the union ``Union((0, 0, theta0), (i r, j r,
    theta1), alpha, L)`` made alone, to the last bit: its intrinsic parameters from the end
    poses (numpy's ``hypot`` and ``arctan2``, :func:`segplan.model.pose.wrap`), its cubic
    (:func:`segplan.model.union.cubic_coefficients` with ``each``), its exact peak curvature
    (:func:`segplan.model.union.max_curvatures`) and points (:func:`_points`). The candidates'
    alphas lie inside their feasible intervals by ``1e-9`` (:func:`_best_alphas`), so the
    union's checks hold.
    """
    h0, h1, i, j, alpha = (np.array(col) for col in list(zip(*rows, strict=True))[:5])
    x1, y1 = i * r, j * r  # the end point (the start is the origin)
    d = np.hypot(x1, y1)
    psi = np.arctan2(y1, x1)
    X, c1, c2, c3 = cubic_coefficients(d, wrap(_ANGLES[h0] - psi), wrap(_ANGLES[h1] - psi), alpha, each=True)
    fa = (psi - alpha).tolist()  # the frame angle
    geometry = list(
        zip(
            *([0.0] * len(rows),) * 2,
            fa,
            map(math.cos, fa),
            map(math.sin, fa),
            *(v.tolist() for v in (X, c1, c2, c3)),
            strict=True,
        )
    )
    pts = _points(_columns(geometry), L, SAMPLE_S, SAMPLE_T)
    peaks = max_curvatures(X, c1, c2, c3).tolist()
    out = []
    for row, g, points, peak in zip(rows, geometry, pts, peaks, strict=True):
        h0_, h1_, i_, j_, a, dd, p0, p1, cost = row
        out.append((Primitive(h0_, h1_, i_, j_, cost, a, dd, p0, p1, peak, points, math.nan), g))
    return out


def _covered(base: list[list[tuple[Primitive, tuple]]], L: float) -> list[list[Primitive]]:
    """The primitives of :func:`_make` (lists of them) with their covering radii (one
    vectorised pass, each union's radius that of a pass for it alone)."""
    made = [m for b in base for m in b]
    deltas = iter(_covering(_columns([g for _, g in made]), L, SAMPLE_S, SAMPLE_T).tolist())
    return [[replace(p, delta=next(deltas)) for p, _ in b] for b in base]


def _rank(estimate: float, key: tuple[int, int, int, int], L: float) -> tuple:
    """Rank of a candidate primitive: its estimated LONGD rounded to :data:`RANK_DECIMALS`
    decimals of ``L``, then its integers ``key = (h0, h1, i, j)`` (module docstring: the
    same order on every processor)."""
    return (round(estimate / L, RANK_DECIMALS), key)


def _steps(p: Primitive) -> list[tuple[int, int, int, int, float]]:
    """``(h0, di, dj, h1, cost)`` of ``p`` and of its three quarter-turned copies (integers only)."""
    out, di, dj = [], p.di, p.dj
    for q in range(4):
        out.append(((p.h0 + 4 * q) % NH, di, dj, (p.h1 + 4 * q) % NH, p.cost))
        di, dj = -dj, di
    return out


def _reaches(
    kept: list, h0: int, target: tuple, budget: float, depth: int = 3, margins: dict | None = None
) -> bool:
    """Does a chain of at most ``depth`` kept primitives reach ``target`` for at most ``budget``?

    ``kept[h]``: ``(di, dj, h1, cost)`` of the kept primitives from heading ``h``. With
    ``margins`` (a dict), the smallest ``|cost - budget| / budget`` of the chains compared is
    kept under the key ``"budget"`` (:func:`selection_margins`); the selection asks
    :meth:`~segplan.planning.lattice.chains.Chains.reaches` otherwise (the same answer).
    """
    frontier = [(0, 0, h0, 0.0)]
    for _ in range(depth):
        nxt = []
        for i, j, h, c in frontier:
            for di, dj, h1, cost in kept[h]:
                c2 = c + cost
                if margins is not None:
                    _note(margins, "budget", abs(c2 - budget) / budget)
                if c2 > budget:
                    continue
                s = (i + di, j + dj, h1)
                if s == target:
                    return True
                nxt.append((*s, c2))
        frontier = nxt
    return False


def _validate(L, max_steer, resolution) -> None:
    for name, v in (("L", L), ("resolution", resolution)):
        if isinstance(v, bool) or not isinstance(v, int | float) or not (math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {v!r}")
    if not (isinstance(max_steer, int | float) and 0.0 < max_steer < 0.5 * math.pi):
        raise ValueError(f"max_steer must lie in (0, pi/2) radians, got {max_steer!r}")
    if resolution > L:
        raise ValueError(f"resolution must be at most L={L} (a turn needs several cells), got {resolution!r}")


@functools.lru_cache(maxsize=8)
def primitive_set(L: float, max_steer: float, resolution: float) -> PrimitiveSet:
    """The motion primitives for a robot and a lattice resolution (module docstring).

    The default sets (:data:`STORED_STEER`, ``L / resolution`` in :data:`STORED_CELLS`)
    are read from the package data (:data:`DATA_PATH`, written by ``python -m segplan.fit``)
    and scaled by ``L``: a union's shape and LONGD scale with ``L`` and the steering test is
    invariant under the scaling, so the set of any ``L`` is the unit set scaled. Other sets
    are computed (:func:`compute_primitive_set`: 6-25 ms of CPU for steering limits of 30-60
    deg at ``L / 2`` to ``L / 8``, up to 70 ms at ``L / 16``, more for a robot turning wider).
    Either way a set is kept (least-recently-used cache of 8 sets:
    :func:`primitive_set.cache_clear` empties it).

    Parameters
    ----------
    L : float
        Robot length (> 0).
    max_steer : float
        Steering limit, radians in ``(0, pi/2)``.
    resolution : float
        Cell size of the lattice (m, > 0, at most ``L``).

    Raises
    ------
    ValueError
        Naming the argument.
    """
    _validate(L, max_steer, resolution)
    cells = float(L) / float(resolution)
    if max_steer == STORED_STEER and DATA_PATH.exists():
        for n in STORED_CELLS:
            if abs(cells - n) <= 1e-12 * n:
                return from_arrays(stored_sets()[n], float(L), float(max_steer), float(resolution))
    return compute_primitive_set(L, max_steer, resolution)


#: The package data of the default primitive sets (unit ``L``), written by ``python -m segplan.fit``.
DATA_PATH = Path(__file__).with_name("primitives.npz")
#: Steering limit of the stored sets (radians: 45 deg).
STORED_STEER = math.radians(45.0)
#: ``L / resolution`` of the stored sets: the lattice's default resolution, its retry, and the
#: coarser lattice of large floors (L / 4), and the coarse lattice of the cost-to-go (L / 2,
#: :mod:`segplan.planning.lattice.guide`).
STORED_CELLS = (2, 4, 8, 16)
#: The per-primitive scalar fields of :func:`primitive_arrays` (``points`` apart).
FIELDS = ("h0", "h1", "di", "dj", "cost", "alpha", "d", "phi0", "phi1", "peak_curvature", "delta")
_INT_FIELDS = ("h0", "h1", "di", "dj")
_LENGTHS = ("cost", "d", "delta")  # scale with L (points too; peak_curvature with 1 / L)


def primitive_arrays(ps: PrimitiveSet) -> dict[str, np.ndarray]:
    """The primitives of headings 0..3 of ``ps`` as arrays (the others are quarter turns of them).

    Keys :data:`FIELDS` (one entry per primitive) and ``points`` (primitives x samples x 2).
    """
    base = [p for h in range(4) for p in ps.by_heading[h]]
    out = {
        f: np.array([getattr(p, f) for p in base], dtype=np.int64 if f in _INT_FIELDS else float)
        for f in FIELDS
    }
    out["points"] = np.stack([p.points for p in base])
    return out


def from_arrays(a: dict, L: float, max_steer: float, resolution: float) -> PrimitiveSet:
    """The :class:`PrimitiveSet` of a unit-``L`` set's arrays (:func:`primitive_arrays`), scaled to ``L``."""
    scale = {f: L for f in _LENGTHS} | {"peak_curvature": 1.0 / L}
    cols = [a[f].tolist() if f in _INT_FIELDS else (a[f] * scale.get(f, 1.0)).tolist() for f in FIELDS]
    pts = a["points"] * L
    base: list[list[Primitive]] = [[] for _ in range(4)]
    for k, row in enumerate(zip(*cols, strict=True)):
        kw = dict(zip(FIELDS, row, strict=True))
        base[kw["h0"]].append(Primitive(**kw, points=np.ascontiguousarray(pts[k])))
    return PrimitiveSet(L, max_steer, resolution, _all_headings(base))


@functools.cache
def stored_sets() -> dict[int, dict[str, np.ndarray]]:
    """The stored unit-``L`` sets by ``L / resolution`` (read once per process), and their
    provenance (key ``"provenance"``: a JSON string)."""
    with np.load(DATA_PATH, allow_pickle=False) as z:
        out: dict = {n: {k: z[f"{n}/{k}"] for k in (*FIELDS, "points")} for n in STORED_CELLS}
        out["provenance"] = str(z["provenance"])
    return out


def _note(margins: dict, key: str, value: float) -> None:
    margins[key] = min(margins.get(key, math.inf), float(value))


def selection_margins(L: float, max_steer: float, resolution: float) -> dict[str, float]:
    """How close each kind of decision of :func:`compute_primitive_set` came to going the other way.

    The selection is the same on every processor if no decision is closer to its threshold
    than the rounding differences between processors (about 5e-16 relative; module
    docstring). Exact ties of the ranking are not decisions: they are broken on integers.

    Returns
    -------
    dict
        Smallest relative margins: ``"rank"``, the closest two distinct rounded estimates
        (in units of ``L``); ``"budget"``, a chain's cost against the pruning budget;
        ``"frame"``, the least and the next least sampled peak curvature of the frames tried
        where the optimal frame breaks the steering limit; ``"steer"``, a sampled or exact
        peak curvature against the limit; ``"reach"``, a primitive's farthest sample against
        :func:`max_reach`.
    """
    margins: dict[str, float] = {}
    compute_primitive_set(L, max_steer, resolution, margins=margins)
    return margins


def compute_primitive_set(
    L: float, max_steer: float, resolution: float, margins: dict | None = None
) -> PrimitiveSet:
    """:func:`primitive_set` computed, never read from the stored sets (module docstring).

    ``margins``: a dict that receives the decisions' smallest margins
    (:func:`selection_margins`), or None.

    Raises
    ------
    ValueError
        Naming the argument.
    """
    _validate(L, max_steer, resolution)
    L, r = float(L), float(resolution)
    kmax = math.tan(max_steer) / L
    R = 1.0 / kmax
    bound = max_reach(L, max_steer, r)
    straight = [
        (h0, h0, *HEADING_VECTORS[h0], 0.0, math.hypot(*HEADING_VECTORS[h0]) * r, 0.0, 0.0) for h0 in range(4)
    ]
    cands = []
    parts = [_candidates(h0, r, R) for h0 in range(4)]
    for h0, part, a in zip(
        range(4), parts, _best_alphas(parts, L, kmax * (1.0 - 1e-6), margins), strict=True
    ):
        I, J, H1, d, phi0, phi1, _, _ = part
        ok = np.isfinite(a)
        est = longd_gauss_intrinsic(d[ok], phi0[ok], phi1[ok], a[ok], L)
        cols = (est, I[ok], J[ok], H1[ok], a[ok], d[ok], phi0[ok], phi1[ok])
        for e, i, j, h1, al, dd, p0, p1 in zip(*(np.asarray(c).tolist() for c in cols), strict=True):
            cands.append((e, h0, h1, i, j, al, dd, p0, p1))
    cands.sort(key=lambda c: _rank(c[0], c[1:5], L))
    if margins is not None:
        ranks = np.unique([_rank(c[0], c[1:5], L)[0] for c in cands])
        _note(margins, "rank", np.diff(ranks).min() if len(ranks) > 1 else math.inf)

    chains = Chains()  # the kept primitives, every heading's
    per: dict = {}  # primitives kept per turn (h0, h1 - h0)
    full = 0  # turns whose PER_TURN primitives are kept: the rest is skipped
    made: dict[int, tuple[Primitive, tuple]] = {}  # the candidates made (and others, ahead)
    reached: set[int] = set()  # candidates a chain already reaches (and always will: kept only grows)

    def pruned(m: int, notes: dict | None = None) -> bool:
        """Does a chain of kept primitives reach candidate ``m`` within its budget? With ``notes``
        (the margins) every chain compared is noted (:func:`_reaches`); without, the answer is
        looked up (:meth:`Chains.reaches`) and a yes remembered (primitives are only added)."""
        est, h0, h1, i, j = cands[m][:5]
        target, budget = (i, j, h1), est * (1.0 + PRUNE)
        if notes is not None:
            return _reaches(chains.kept, h0, target, budget, margins=notes)
        if m not in reached and chains.reaches(h0, target, budget):
            reached.add(m)
        return m in reached

    def ahead(n: int) -> list[int]:
        """Candidate ``n`` and the next that may be kept, :data:`_AHEAD` in all: not made, no
        chain reaching them, no more of a turn than it has room for."""
        out, room = [], {}
        for m in range(n, len(cands)):
            if len(out) == _AHEAD:
                break
            c = cands[m]
            turn = (c[1], (c[2] - c[1]) % NH)
            left = room.get(turn, PER_TURN - per.get(turn, 0))
            if left > 0 and m not in made and not pruned(m):
                out.append(m)
                room[turn] = left - 1
        return out

    def make(batch: list[int], also: tuple = ()) -> list[tuple[Primitive, tuple]]:
        """Make the candidates ``batch`` (:func:`_exact`, :func:`_make`), and the rows ``also``,
        whose primitives it returns."""
        rows = [*also, *(cands[m][1:] for m in batch)]
        out = _make([(*c, cost) for c, cost in zip(rows, _exact(rows, L), strict=True)], r, L)
        made.update(zip(batch, out[len(also) :], strict=True))
        return out[: len(also)]

    base = [[step] for step in make(ahead(0), straight)]  # the unit steps, with the cheapest candidates
    for b in base:
        for p, _ in b:
            for step in _steps(p):
                chains.add(*step)
    for n, (_, h0, h1, *_) in enumerate(cands):
        if full == 4 * len(TURNS):
            break
        key = (h0, (h1 - h0) % NH)
        if per.get(key, 0) >= PER_TURN or pruned(n, margins):  # margins: every chain compared
            continue
        if n not in made:  # this one and the next that may be kept, in one batch
            make(ahead(n))
        p, g = made[n]
        if margins is not None:
            _note(margins, "steer", abs(p.peak_curvature - kmax) / kmax)
            _note(margins, "reach", abs(np.abs(p.points).max() - bound) / bound)
        if p.peak_curvature > kmax or np.abs(p.points).max() > bound:
            continue
        base[h0].append((p, g))
        per[key] = per.get(key, 0) + 1
        full += per[key] == PER_TURN
        for step in _steps(p):
            chains.add(*step)
    return PrimitiveSet(L, float(max_steer), r, _all_headings(_covered(base, L)))
