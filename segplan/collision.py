"""On-line collision detection of a union's swept segment with convex polygons.

Section "Collision-detection algorithm": "The inputs ... are the trajectory of the
reference point ... which includes a cubic polynomial and limiting abscissa, and the
obstacle modelled by a convex polygon. The output is a boolean variable which states if
there is collision or not, of some of the successive positions of the segment ... with
the polygon." The robot is the closed segment ``S(x) = [A(x), B(x)]``: the rear point
``A(x) = (x, f(x))`` on the union's cubic (alpha frame, ``x`` in ``[0, X]``) and the front
wheel ``B(x) = A(x) + L u(x)``, ``u = (1, f') / sqrt(1 + f'^2)``. Obstacles are closed
convex polygons; touching is a collision.

Quick checks (the paper's, applied first)
-----------------------------------------
* Box: the swept set lies in the frame rectangle ``[0, X + L] x [y_lo, y_hi]`` built from
  the extremes of ``f`` and of the direction ``u`` (closed forms: ``f'`` is a quadratic).
* ``d_c``: the paper's test "``d_c`` = minimum distance from the centre of the polygon to
  the cubic spline, ``r_max`` = maximum radius of the polygon, computed off-line, ``M`` =
  bound of the difference between the cubic and the trajectory of the front wheel ...
  (for ``M``, much better values than ``L`` can be found)". If ``d_c > r_max + M`` the
  polygon cannot be touched. The OCR prints ``d_c < r_max + M``; the inequality must be
  ``>`` for the sentence ("there can be no intersection") to hold, and that is what we
  implement. ``M = L`` is always valid (every point of ``S(x)`` is within ``L`` of
  ``A(x)``). The better value: a point ``A(x) + s u(x)`` (``0 <= s <= L``) has abscissa
  ``x + h`` with ``h = s / sqrt(1 + f'^2) <= L`` and its height differs from the cubic's
  at that abscissa by the Taylor remainder ``|f''(xi)| h^2 / 2``, so every point of the
  swept set is within ``M' = L^2 max|f''| / 2`` (max over ``[0, X + L]``) of the graph of
  the cubic *extended* to ``[0, X + L]``. We use the smaller of the two bounds with its
  curve. ``d_c`` itself is bounded from below by the distance to an inscribed polyline
  minus its chord error ``max|f''| dx^2 / 8``, so the test stays a rigorous rejection.

The exact test and why it is complete
-------------------------------------
The set ``{x : S(x) meets P}`` is closed (``S`` moves continuously, ``P`` is closed).
Suppose ``S(0)`` misses ``P`` but some ``S(x)`` meets it, and let ``x*`` be the first such
abscissa (``x* > 0``). ``S(x*)`` cannot contain a point of the *interior* of ``P``: the
interior is open, so slightly earlier positions would meet it too. A segment that meets
a convex polygon only on its boundary touches it either at one of its end points, or at
a polygon vertex, or lies along an edge, and then the contact set is a segment whose ends
are end points of ``S`` or vertices. Hence the first contact is one of

(i)   ``S(0)`` meets ``P`` (the start pose: one segment-polygon test);
(ii)  ``A(x*)`` on an edge: ``a_e(x) = n_e . A(x) - h_e = n_x x + n_y f(x) - h_e = 0``, a
      *cubic* in ``x`` for each edge ``e`` (outward unit normal ``n_e``, offset ``h_e``);
(iii) ``B(x*)`` on an edge: the front-wheel path meets ``P``;
(iv)  a vertex ``V`` on ``S(x*)``: ``V`` on the segment's line,
      ``cross(u, V - A) = 0``, i.e. ``h_V(x) = (V_y - f(x)) - f'(x) (V_x - x) = 0``, again a
      *cubic*; its derivative factors as ``h_V'(x) = (x - V_x) f''(x)``.

Each event is also sufficient for a collision, so: collision iff (i) or one of the events
happens at some ``x``. Identically vanishing event equations (a straight union lying on an
edge's line, or passing through a vertex) need no roots: the contact then starts at a
vertex, which is an event of an adjacent edge whose equation does not vanish, or at an end
point of the segment (events (ii), (iii)).

How we decide it: two stages
----------------------------
1. Certified sweep (fast, decides nearly every case). The positions at ``s = x / X`` on a
   grid of 32 pieces are tested exactly (separating axes); a touching position is a
   collision. Between two positions, every point ``P = A + t u`` of the segment
   (``P = (1 - t/L) A + (t/L) B``) moves on a curve within ``e = K dx^2 / 8`` of its chord,
   ``K`` a rigorous bound of ``|P''|`` on the piece and ``dx`` its length in ``x``, and
   that chord lies in the convex hull of the two segments. So the swept set of the piece
   lies in the hull (four points) grown by ``e``: if the separating-axis gap between the
   hull and the polygon (a lower bound of their distance; axes: the polygon's edge normals
   and the normals of the six point pairs) exceeds ``e``, the piece is free. Undecided
   pieces are halved three times. The bound: ``|P''| <= |A''| + L |u''|`` with
   ``A'' = (0, f'')``, ``u'' = theta'' n - theta'^2 u``, ``theta' = f'' / (1 + f'^2)``,
   ``|theta''| <= |f'''| + 2 (3 sqrt(3) / 16) f''^2`` (``|t| / (1 + t^2)^2 <= 3 sqrt(3) / 16``),
   so ``K = max|f''| + L (6 |c3| + 1.65 max|f''|^2)`` over the piece.
2. Event test (exact; for the cases the sweep leaves undecided, i.e. near-touches).
   Events (ii) and (iv) are cubics: their real roots (eigenvalues of the companion
   matrices, polished by Newton; the real part of a complex pair, the abscissa of a
   near-double root, is kept too) and their stationary points (for (ii) the paper's
   "points of the curve where the derivative is equal to the slope of the segment", here
   of the edge; for (iv) ``x = V_x`` and the inflection point; all in closed form, so that
   a grazing contact, a double root, is located accurately) are candidate abscissae, with
   both end poses; one separating-axis test per candidate decides. Event (iii), the
   front-wheel path: squaring ``n . B = h`` gives a degree-10 polynomial with spurious
   roots; we use a certified subdivision of the path instead (a piece within ``e`` of its
   chord, same ``K``, whose chord is farther than ``e`` from the polygon is free; a sample
   of ``B`` inside is a collision; others are halved until ``e`` reaches the tolerance,
   where the answer is a conservative "collision").

Tolerance. Contacts are decided with a tiny conservative tolerance
``tol = TOUCH_RTOL * (L + X + r_max + |c| + |p0|)`` (``|c|``: distance of the polygon's
centre from the union's start ``p0``; ``|p0|``, its largest world coordinate, for the
rounding of the change of frame): a position within about ``tol`` of the polygon
(separating-axis sense) counts as a collision. Floating-point error at double roots thus turns into rare
false alarms (a contact closer than ``tol``), never into misses.

Counters
--------
Every query updates a :class:`CollisionStats` (the caller's ``stats=``, else the module's
``STATS``), so a benchmark can report checks per second: ``STATS.reset()``, run, then read
``STATS.calls`` (union-polygon queries), ``STATS.rejected`` (by a quick check),
``STATS.exact`` and ``STATS.events``.

Speed
-----
Per-polygon data (:class:`ConvexPolygon`: normals, offsets, centre, ``r_max``) and per-union
data (:class:`Sweep`: frame, box, ``M``, bounds, the level-0 positions) are computed once.
Array polygons are validated once per distinct content (a small cache keyed by the vertex
bytes) and the sweeps of recently seen unions are cached, so the planner may pass plain
arrays and unions; :func:`union_free` tests one union against many obstacles, quick checks
first.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .pose import as_pose, check_length
from .union import Union

TOUCH_RTOL = 1e-9
"""Relative tolerance of a touching contact (times the scene size ``L + X + r + |c| + |p0|``)."""

_DC_PIECES = 16  # pieces of the polyline used to bound d_c from below
_SWEEP_PIECES = 32  # level-0 pieces of the certified sweep
_SWEEP_LEVELS = 3  # refinements of the certified sweep before the event test
_FRONT_PIECES = 16  # initial pieces of the front-wheel subdivision
_FRONT_MAX_PIECES = 4096  # guard: beyond this many live pieces, answer "collision"
_THETA2 = 1.65  # > 1 + 2 * 3 sqrt(3) / 16 = 1.6495


# -- counters ------------------------------------------------------------------------------
@dataclass
class CollisionStats:
    """Counters of collision queries.

    Attributes
    ----------
    calls : int
        Union-polygon queries (:func:`collides`, and each obstacle of :func:`union_free`).
    rejected : int
        Queries answered by a quick check (box or ``d_c``).
    exact : int
        Queries that ran the exact test.
    events : int
        Exact tests that the certified sweep left undecided, decided by the event test.
    collisions : int
        Queries answered "collision".
    """

    calls: int = 0
    rejected: int = 0
    exact: int = 0
    events: int = 0
    collisions: int = 0

    def reset(self) -> None:
        """Set every counter to zero."""
        self.calls = self.rejected = self.exact = self.events = self.collisions = 0


STATS = CollisionStats()
"""Module-level counters, used when a function is not given ``stats``."""


# -- polygons -------------------------------------------------------------------------------
def validate_polygon(vertices, name: str = "polygon") -> np.ndarray:
    """Validate a convex polygon and return its vertices counter-clockwise, ``(k, 2)``.

    Parameters
    ----------
    vertices : array_like, shape (k, 2)
        Either orientation; the closing vertex is not repeated.
    name : str
        Used in error messages.

    Raises
    ------
    ValueError
        Fewer than 3 vertices, wrong shape, non-finite numbers, repeated consecutive
        vertices, three collinear consecutive vertices, a non-convex polygon (turns of both
        signs) or a self-intersecting one (all turns alike but winding more than once).
    """
    try:
        v = np.array(vertices, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a (k, 2) array of numbers, got {vertices!r}") from exc
    if v.ndim != 2 or v.shape[1] != 2:
        raise ValueError(f"{name} must have shape (k, 2), got {v.shape}")
    k = v.shape[0]
    if k < 3:
        raise ValueError(f"{name} needs at least 3 vertices, got {k}")
    bad = ~np.all(np.isfinite(v), axis=1)
    if np.any(bad):
        raise ValueError(f"{name} vertex {int(np.flatnonzero(bad)[0])} is not finite: {v[bad][0].tolist()}")
    e = np.roll(v, -1, axis=0) - v  # e[i] = v[i+1] - v[i]
    length = np.hypot(e[:, 0], e[:, 1])
    scale = max(1.0, float(np.abs(v).max()))
    short = length <= 1e-12 * scale
    if np.any(short):
        i = int(np.flatnonzero(short)[0])
        raise ValueError(f"{name} vertices {i} and {(i + 1) % k} coincide (degenerate polygon)")
    ep = np.roll(e, 1, axis=0)  # edge arriving at vertex i
    turn = ep[:, 0] * e[:, 1] - ep[:, 1] * e[:, 0]  # cross(e_{i-1}, e_i): turn at vertex i
    flat = np.abs(turn) <= 1e-12 * length * np.roll(length, 1)
    if np.any(flat):
        i = int(np.flatnonzero(flat)[0])
        raise ValueError(
            f"{name} vertices {(i - 1) % k}, {i}, {(i + 1) % k} are collinear (degenerate polygon; "
            "remove the middle vertex)"
        )
    if not (np.all(turn > 0) or np.all(turn < 0)):
        sign = np.sign(turn)
        major = 1.0 if np.count_nonzero(sign > 0) >= np.count_nonzero(sign < 0) else -1.0
        i = int(np.flatnonzero(sign != major)[0])
        raise ValueError(
            f"{name} is not convex (or is self-intersecting): the turn at vertex {i} has the opposite sign"
        )
    winding = float(np.sum(np.arctan2(turn, np.einsum("ij,ij->i", ep, e)))) / (2.0 * math.pi)
    if abs(abs(winding) - 1.0) > 1e-6:
        raise ValueError(
            f"{name} is self-intersecting: its boundary winds {abs(winding):.3g} times (a star polygon)"
        )
    return v if turn[0] > 0 else v[::-1].copy()


class ConvexPolygon:
    """A validated convex polygon with the data the tests need, computed once (immutable).

    Parameters
    ----------
    vertices : array_like, shape (k, 2)
        Either orientation.
    check : bool
        Validate (:func:`validate_polygon`). With ``check=False`` the caller guarantees a
        strictly convex, non-degenerate polygon; only the orientation is normalised.

    Attributes
    ----------
    vertices : ndarray (k, 2)
        Counter-clockwise, read-only.
    normals : ndarray (k, 2)
        Outward unit normal of edge ``i`` (from vertex ``i`` to ``i + 1``).
    offsets : ndarray (k,)
        ``normals[i] . p <= offsets[i]`` for every point of the polygon.
    centre : tuple of float
        Centre of the bounding box (the paper's "centre of the polygon").
    radius : float
        Largest distance from ``centre`` to a vertex (the paper's ``r_max``).
    """

    __slots__ = ("vertices", "normals", "offsets", "centre", "radius")

    def __init__(self, vertices, check: bool = True):
        if check:
            v = validate_polygon(vertices)
        else:
            v = np.array(vertices, dtype=float)
            nxt = np.concatenate((v[1:], v[:1]))  # np.roll(v, -1, axis=0), without its overhead
            area2 = float(np.sum(v[:, 0] * nxt[:, 1] - nxt[:, 0] * v[:, 1]))
            if area2 < 0:
                v = v[::-1].copy()
        e = np.concatenate((v[1:], v[:1])) - v  # v[i+1] - v[i]
        n = np.column_stack((e[:, 1], -e[:, 0])) / np.hypot(e[:, 0], e[:, 1])[:, None]
        h = np.einsum("ij,ij->i", n, v)
        lo, hi = v.min(axis=0), v.max(axis=0)
        c = 0.5 * (lo + hi)
        r = float(np.max(np.hypot(v[:, 0] - c[0], v[:, 1] - c[1])))
        for arr in (v, n, h):
            arr.flags.writeable = False
        for key, value in zip(self.__slots__, (v, n, h, (float(c[0]), float(c[1])), r), strict=True):
            object.__setattr__(self, key, value)

    def __setattr__(self, name, value):
        raise AttributeError("ConvexPolygon is immutable")

    def __repr__(self) -> str:
        return f"ConvexPolygon({self.vertices.tolist()})"

    def __len__(self) -> int:
        return len(self.vertices)


_POLYGONS: dict[bytes, ConvexPolygon] = {}  # validated polygons by content
_CACHE_SIZE = 256


def as_polygon(polygon, check: bool = True, name: str = "polygon") -> ConvexPolygon:
    """Return ``polygon`` as a :class:`ConvexPolygon` (no work if it already is one).

    Array polygons are prepared once per distinct content: a small cache keyed by the
    vertex bytes (not by identity, so a caller that mutates its array gets a fresh
    check) spares the planner repeated validation of the same obstacle.
    """
    if isinstance(polygon, ConvexPolygon):
        return polygon
    try:
        v = np.asarray(polygon, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be a (k, 2) array of numbers, got {polygon!r}") from exc
    key = v.tobytes() + repr(v.shape).encode()
    poly = _POLYGONS.get(key)
    if poly is None:
        poly = (
            ConvexPolygon(validate_polygon(v, name), check=False) if check else ConvexPolygon(v, check=False)
        )
        if check:  # only validated polygons are shared
            if len(_POLYGONS) >= _CACHE_SIZE:
                _POLYGONS.clear()
            _POLYGONS[key] = poly
    return poly


def _bounds(bounds) -> tuple[float, float, float, float]:
    try:
        b = tuple(float(v) for v in bounds)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"bounds must be (xmin, ymin, xmax, ymax), got {bounds!r}") from exc
    if len(b) != 4 or not all(math.isfinite(v) for v in b):
        raise ValueError(f"bounds must be four finite numbers (xmin, ymin, xmax, ymax), got {bounds!r}")
    if not (b[0] < b[2] and b[1] < b[3]):
        raise ValueError(f"bounds must have xmin < xmax and ymin < ymax, got {b}")
    return b


# -- polynomials on [0, 1] ----------------------------------------------------------------------
def _quadratic_points(a2, a1, a0):
    """Real roots of ``a2 s^2 + a1 s + a0`` (vectorised), ``(m, 2)``.

    A negative discriminant gives the real part of the complex pair (the vertex of the
    parabola) twice: the abscissa of a near-double root. Missing roots are ``nan``.
    """
    with np.errstate(all="ignore"):
        big = np.maximum(np.maximum(np.abs(a2), np.abs(a1)), np.abs(a0))
        big = np.where(big > 0, big, 1.0)
        a2, a1, a0 = a2 / big, a1 / big, a0 / big
        quad = np.abs(a2) > 1e-12
        disc = a1 * a1 - 4.0 * a2 * a0
        sq = np.sqrt(np.maximum(disc, 0.0))
        q = -0.5 * (a1 + np.where(a1 >= 0, sq, -sq))  # no cancellation
        r1 = np.where(disc >= 0, q / a2, -a1 / (2.0 * a2))
        r2 = np.where(disc >= 0, np.where(q != 0, a0 / q, r1), r1)
        lin = np.where(np.abs(a1) > 1e-12, -a0 / a1, np.nan)
        return np.stack((np.where(quad, r1, lin), np.where(quad, r2, lin)), axis=-1)


def _cubic_points(a3, a2, a1, a0):
    """Real parts of the roots of ``a3 s^3 + a2 s^2 + a1 s + a0`` (vectorised), ``(m, 3)``.

    Eigenvalues of the (balanced) companion matrices, which stay accurate when the cubic
    coefficient is tiny (a closed form loses up to 1e-2 there), then two Newton steps on
    the cubic, each kept only if small. The real part of a complex pair is the abscissa of
    a near-double root, so it is kept as a candidate. A vanishing cubic coefficient is
    replaced by ``1e-14`` of the largest one: on ``[0, 1]`` the cubic changes by less than
    that, and the extra root lies far outside.
    """
    big = np.maximum(np.maximum(np.abs(a3), np.abs(a2)), np.maximum(np.abs(a1), np.abs(a0)))
    big[big == 0.0] = 1.0
    a3, a2, a1, a0 = a3 / big, a2 / big, a1 / big, a0 / big
    lead = np.where(np.abs(a3) > 1e-14, a3, np.where(a3 < 0, -1e-14, 1e-14))
    comp = np.zeros((len(a3), 3, 3))
    comp[:, 1, 0] = comp[:, 2, 1] = 1.0
    comp[:, 0, 2], comp[:, 1, 2], comp[:, 2, 2] = -a0 / lead, -a1 / lead, -a2 / lead
    r = np.linalg.eigvals(comp).real
    a3, a2, a1, a0 = a3[:, None], a2[:, None], a1[:, None], a0[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        for _ in range(2):
            step = (((a3 * r + a2) * r + a1) * r + a0) / ((3.0 * a3 * r + 2.0 * a2) * r + a1)
            r = np.where(np.abs(step) < 1e-3, r - step, r)
    return r


# -- the swept segment of one union ----------------------------------------------------------
def _quadratic_roots(a: float, b: float, c: float) -> list[float]:
    """Real roots of ``a x^2 + b x + c`` (scalars; a double root once)."""
    if a == 0.0:
        return [] if b == 0.0 else [-c / b]
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return []
    q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
    return [q / a] if q == 0.0 else [q / a, c / q]


def _hull_axes(P4):
    """Unit normals of the six point pairs of ``P4 = (A_lo, B_lo, A_hi, B_hi)``, ``(m, 6, 2)``,
    and the extent ``(min, max)`` of the four points along each, ``(m, 6)`` each."""
    D = P4[:, _PAIR_J] - P4[:, _PAIR_I]
    ln = np.hypot(D[..., 0], D[..., 1])
    ln[ln == 0.0] = np.inf  # a degenerate pair gives a null axis (gap 0)
    nrm = np.empty_like(D)
    nrm[..., 0] = -D[..., 1] / ln
    nrm[..., 1] = D[..., 0] / ln
    q = nrm @ P4.transpose(0, 2, 1)  # (m, 6, 4)
    q0, q1, q2, q3 = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    return (
        nrm,
        np.minimum(np.minimum(q0, q1), np.minimum(q2, q3)),
        np.maximum(np.maximum(q0, q1), np.maximum(q2, q3)),
    )


def _corners(A_lo, B_lo, A_hi, B_hi):
    """Stack the four end points of pieces, ``(m, 4, 2)``."""
    P4 = np.empty((len(A_lo), 4, 2))
    P4[:, 0], P4[:, 1], P4[:, 2], P4[:, 3] = A_lo, B_lo, A_hi, B_hi
    return P4


_PAIR_I = np.array([0, 2, 0, 1, 0, 1])
_PAIR_J = np.array([1, 3, 2, 3, 3, 2])
_S_GRID = np.linspace(0.0, 1.0, _SWEEP_PIECES + 1)
_S_DC = np.linspace(0.0, 1.0, _DC_PIECES + 1)
_S_FRONT = np.linspace(0.0, 1.0, _FRONT_PIECES + 1)
_S_FRONT.flags.writeable = False


class _Grid:
    """Level-0 positions of the certified sweep (per union, built on first use)."""

    __slots__ = ("s", "A", "B", "nseg", "oseg", "nrm", "qmin", "qmax", "kx", "dx", "e")


class Sweep:
    """Per-union data of the collision tests, computed once (read-only).

    Parameters
    ----------
    union : Union

    Notes
    -----
    Frame quantities refer to the union's alpha frame (origin ``p0``, x-axis at world
    angle ``union.frame_angle``). ``box = (x_lo, x_hi, y_lo, y_hi)`` is a rectangle of that
    frame containing every position of the segment. Reusing one ``Sweep`` for all
    obstacles (as :func:`union_free` does) saves the per-union work.
    """

    __slots__ = (
        "union", "L", "X", "c1", "c2", "c3", "x0", "y0", "cos", "sin", "box", "dc_end", "dc_margin",
        "K", "size", "mag", "_grid", "_dc", "_rot",
    )  # fmt: skip

    def __init__(self, union: Union):
        if not isinstance(union, Union):
            raise ValueError(f"union must be a segplan.Union, got {type(union).__name__}")
        L, X = union.L, union.x_end
        _, c1, c2, c3 = union.coefficients
        beta = union.frame_angle
        cb, sb = math.cos(beta), math.sin(beta)
        # extremes of f on [0, X]: ends and roots of f' = c1 + 2 c2 x + 3 c3 x^2
        xs = [0.0, X] + [r for r in _quadratic_roots(3.0 * c3, 2.0 * c2, c1) if 0.0 < r < X]
        fs = [((c3 * x + c2) * x + c1) * x for x in xs]
        # extremes of f' on [0, X]: ends and the vertex of the parabola
        sl = [c1, c1 + (2.0 * c2 + 3.0 * c3 * X) * X]
        if c3 != 0.0 and 0.0 < -c2 / (3.0 * c3) < X:
            xv = -c2 / (3.0 * c3)
            sl.append(c1 + (2.0 * c2 + 3.0 * c3 * xv) * xv)
        # the direction's u_y = f' / sqrt(1 + f'^2) grows with f'
        uy_lo, uy_hi = (m / math.sqrt(1.0 + m * m) for m in (min(sl), max(sl)))
        box = (0.0, X + L, min(fs) + L * min(0.0, uy_lo), max(fs) + L * max(0.0, uy_hi))
        # d_c: polyline of the cubic (M = L), or of the cubic extended to X + L (M = L^2 max|f''| / 2)
        f2 = max(abs(2.0 * c2), abs(2.0 * c2 + 6.0 * c3 * X))
        f2e = max(abs(2.0 * c2), abs(2.0 * c2 + 6.0 * c3 * (X + L)))
        m_ext = 0.5 * L * L * f2e
        x_end, margin, f2c = (X + L, m_ext, f2e) if m_ext < L else (X, L, f2)
        margin += f2c * (x_end / _DC_PIECES) ** 2 / 8.0  # chord error of the polyline
        # |B''| bound over [0, X] (x units), then in s = x / X units
        k_x = f2 + L * (6.0 * abs(c3) + _THETA2 * f2 * f2)
        values = (
            union, L, X, c1, c2, c3, union.p0.x, union.p0.y, cb, sb, box, x_end, margin,
            k_x * X * X, L + X, max(abs(union.p0.x), abs(union.p0.y)), None, None, None,
        )  # fmt: skip
        for key, value in zip(self.__slots__, values, strict=True):
            object.__setattr__(self, key, value)

    def __setattr__(self, name, value):
        raise AttributeError("Sweep is read-only")

    # -- positions --------------------------------------------------------------------------
    def segment(self, s):
        """Frame rear point and unit direction at ``s = x / X``: ``(x, f(x), u_x, u_y)``."""
        x = self.X * s
        fx = ((self.c3 * x + self.c2) * x + self.c1) * x
        fp = (3.0 * self.c3 * x + 2.0 * self.c2) * x + self.c1
        ux = 1.0 / np.sqrt(1.0 + fp * fp)
        return x, fx, ux, fp * ux

    def front(self, s) -> np.ndarray:
        """Frame front-wheel points ``B`` at ``s``, ``(n, 2)``."""
        x, fx, ux, uy = self.segment(s)
        return np.stack((x + self.L * ux, fx + self.L * uy), axis=-1)

    @property
    def rot(self) -> np.ndarray:
        """Rotation world -> frame for row vectors: ``(q - p0) @ rot``."""
        if self._rot is None:
            object.__setattr__(self, "_rot", np.array([[self.cos, -self.sin], [self.sin, self.cos]]))
        return self._rot

    @property
    def p0(self) -> np.ndarray:
        """The union's start point (world)."""
        return np.array([self.x0, self.y0])

    def local(self, poly: ConvexPolygon):
        """The polygon in the frame: vertices, outward unit normals, offsets."""
        rot, p0 = self.rot, self.p0
        V = (poly.vertices - p0) @ rot
        N = poly.normals @ rot
        H = poly.offsets - poly.normals @ p0
        return V, N, H

    def bend(self, s_lo, s_hi) -> np.ndarray:
        """Bound on ``|P''(x)|`` (x units) over each ``[s_lo, s_hi]``, for every point ``P``
        of the segment (``P = A + t u``, ``0 <= t <= L``; ``|P''| <= |A''| + L |u''|``)."""
        c2, c3, X = self.c2, self.c3, self.X
        f2 = np.maximum(np.abs(2.0 * c2 + 6.0 * c3 * X * s_lo), np.abs(2.0 * c2 + 6.0 * c3 * X * s_hi))
        return f2 + self.L * (6.0 * abs(c3) + _THETA2 * f2 * f2)

    def grid(self) -> _Grid:
        """Positions, hull axes and chord bounds of the level-0 sweep (cached)."""
        g = self._grid
        if g is not None:
            return g
        g = _Grid()
        g.s = s = _S_GRID
        x, fx, ux, uy = self.segment(s)
        g.A = A = np.empty((len(s), 2))
        A[:, 0], A[:, 1] = x, fx
        g.B = B = np.empty_like(A)
        B[:, 0], B[:, 1] = x + self.L * ux, fx + self.L * uy
        g.nseg = nseg = np.empty_like(A)  # unit normal of the segment's line
        nseg[:, 0], nseg[:, 1] = -uy, ux
        g.oseg = ux * fx - uy * x
        g.nrm = g.qmin = g.qmax = None  # hull axes: built on first use (_sweep)
        g.kx = self.bend(s[:-1], s[1:])
        g.dx = self.X / _SWEEP_PIECES
        g.e = g.kx * (g.dx * g.dx / 8.0)
        object.__setattr__(self, "_grid", g)
        return g

    # -- quick checks -----------------------------------------------------------------------
    def quick_reject(self, poly: ConvexPolygon) -> tuple[bool, float]:
        """The paper's quick checks: ``(True, tol)`` if ``poly`` certainly cannot be touched.

        Box, then ``d_c > r_max + M`` (see the module docstring). Also returns the touching
        tolerance ``tol`` of this pair.
        """
        dx, dy = poly.centre[0] - self.x0, poly.centre[1] - self.y0
        cx, cy = self.cos * dx + self.sin * dy, self.cos * dy - self.sin * dx
        tol = TOUCH_RTOL * (self.size + poly.radius + math.hypot(cx, cy) + self.mag)
        r = poly.radius + tol
        x_lo, x_hi, y_lo, y_hi = self.box
        gx = max(x_lo - cx, 0.0, cx - x_hi)
        gy = max(y_lo - cy, 0.0, cy - y_hi)
        if gx * gx + gy * gy > r * r:
            return True, tol
        # d_c >= (distance to the polyline) - (chord error); reject if d_c > r_max + M
        if self._dc is None:
            px = self.dc_end * _S_DC
            py = ((self.c3 * px + self.c2) * px + self.c1) * px
            ex, ey = px[1:] - px[:-1], py[1:] - py[:-1]
            object.__setattr__(self, "_dc", (px[:-1], py[:-1], ex, ey, 1.0 / (ex * ex + ey * ey)))
        px, py, ex, ey, inv = self._dc
        wx, wy = cx - px, cy - py
        t = np.clip((wx * ex + wy * ey) * inv, 0.0, 1.0)
        wx -= t * ex
        wy -= t * ey
        d2 = float((wx * wx + wy * wy).min())
        lim = r + self.dc_margin
        return d2 > lim * lim, tol


_SWEEPS: dict[int, Sweep] = {}  # recent sweeps by id of their union (a Sweep keeps its union alive)


def as_sweep(union: Union | Sweep) -> Sweep:
    """Return the :class:`Sweep` of ``union`` (cached for recently seen unions)."""
    if isinstance(union, Sweep):
        return union
    sw = _SWEEPS.get(id(union))
    if sw is None or sw.union is not union:
        sw = Sweep(union)
        if len(_SWEEPS) >= _CACHE_SIZE:
            _SWEEPS.clear()
        _SWEEPS[id(union)] = sw
    return sw


# -- exact test ----------------------------------------------------------------------------------
def _touching(sw: Sweep, s, V, N, H, tol):
    """Segment-polygon separating-axis test at abscissae ``s``; index of the first hit or -1."""
    x, fx, ux, uy = sw.segment(s)
    gA = np.multiply.outer(x, N[:, 0]) + np.multiply.outer(fx, N[:, 1]) - H  # n . A - h
    gB = gA + sw.L * (np.multiply.outer(ux, N[:, 0]) + np.multiply.outer(uy, N[:, 1]))  # n . B - h
    sep = np.minimum(gA, gB).max(axis=1) > tol
    side = np.multiply.outer(ux, V[:, 1]) - np.multiply.outer(uy, V[:, 0]) + (uy * x - ux * fx)[:, None]
    sep |= (side.min(axis=1) > tol) | (side.max(axis=1) < -tol)
    hit = np.flatnonzero(~sep)
    return int(hit[0]) if hit.size else -1


def _hull_gaps(P4, V, N, H):
    """Separating-axis gap between the hull of each ``P4`` (``(m, 4, 2)``) and the polygon."""
    nrm, qmin, qmax = _hull_axes(P4)
    pv = nrm @ V.T  # (m, 6, k)
    gap = np.maximum(pv.min(axis=2) - qmax, qmin - pv.max(axis=2)).max(axis=1)
    g4 = P4 @ N.T - H  # (m, 4, k)
    return np.maximum(gap, g4.min(axis=1).max(axis=1))


def _sweep(sw: Sweep, V, N, H, tol):
    """Certified sweep: ``(x, None)`` on a contact, ``(None, None)`` if free, else
    ``(None, undecided)`` after :data:`_SWEEP_LEVELS` refinements.

    Between two positions ``s_lo < s_hi``, every point ``P = A + t u`` of the segment moves
    on a curve within ``e = |P''|_max dx^2 / 8`` of its chord (``dx = X (s_hi - s_lo)``),
    and that chord lies in the convex hull of the two segments; so the swept set lies in
    the hull grown by ``e``. A hull whose separating-axis gap to the polygon exceeds ``e``
    certifies the piece free; a sampled position that touches is a collision.
    """
    g = sw.grid()
    k = len(H)
    gA = g.A @ N.T - H
    gB = g.B @ N.T - H
    m = np.minimum(gA, gB)
    side = g.nseg @ V.T - g.oseg[:, None]
    touch = (m.max(axis=1) <= tol) & (side.min(axis=1) <= tol) & (side.max(axis=1) >= -tol)
    if touch.any():
        return float(g.s[np.argmax(touch)]) * sw.X, None
    # the gap is the larger of two lower bounds, along the polygon's edge normals and along
    # the hull's axes; a piece is live only if both are <= e, so when the first certifies
    # every piece (most pairs) the hull's axes are not needed
    gap_poly = np.minimum(m[:-1], m[1:]).max(axis=1)
    if not (gap_poly <= g.e).any():
        return None, None
    if g.nrm is None:
        nrm, g.qmin, g.qmax = _hull_axes(_corners(g.A[:-1], g.B[:-1], g.A[1:], g.B[1:]))
        g.nrm = nrm.reshape(-1, 2)
    pv = (g.nrm @ V.T).reshape(-1, 6, k)
    gap = np.maximum(pv.min(axis=2) - g.qmax, g.qmin - pv.max(axis=2)).max(axis=1)
    gap = np.maximum(gap, gap_poly)
    live = gap <= g.e
    if not live.any():
        return None, None
    s_lo, s_hi, kx = g.s[:-1][live], g.s[1:][live], g.kx[live]
    A_lo, B_lo, A_hi, B_hi = g.A[:-1][live], g.B[:-1][live], g.A[1:][live], g.B[1:][live]
    dx = g.dx
    for _ in range(_SWEEP_LEVELS):
        s_mid = 0.5 * (s_lo + s_hi)
        i = _touching(sw, s_mid, V, N, H, tol)
        if i >= 0:
            return float(s_mid[i]) * sw.X, None
        x, fx, ux, uy = sw.segment(s_mid)
        A_mid = np.stack((x, fx), axis=-1)
        B_mid = A_mid + sw.L * np.stack((ux, uy), axis=-1)
        s_lo, s_hi = np.concatenate((s_lo, s_mid)), np.concatenate((s_mid, s_hi))
        A_lo, A_hi = np.concatenate((A_lo, A_mid)), np.concatenate((A_mid, A_hi))
        B_lo, B_hi = np.concatenate((B_lo, B_mid)), np.concatenate((B_mid, B_hi))
        kx = np.concatenate((kx, kx))
        dx *= 0.5
        live = _hull_gaps(_corners(A_lo, B_lo, A_hi, B_hi), V, N, H) <= kx * (dx * dx / 8.0)
        if not live.any():
            return None, None
        s_lo, s_hi, kx = s_lo[live], s_hi[live], kx[live]
        A_lo, B_lo, A_hi, B_hi = A_lo[live], B_lo[live], A_hi[live], B_hi[live]
    return None, (s_lo, s_hi)


def _event_abscissae(sw: Sweep, V, N, H) -> np.ndarray:
    """Candidate ``s = x / X`` of the events (ii) and (iv) and the two end poses."""
    X, c1, c2, c3 = sw.X, sw.c1, sw.c2, sw.c3
    F1, F2, F3 = c1 * X, c2 * X * X, c3 * X**3  # f(X s) = F1 s + F2 s^2 + F3 s^3
    nx, ny = N[:, 0], N[:, 1]
    vx, vy = V[:, 0], V[:, 1]
    k = len(H)
    # (ii) a_e(s) = -h + (n_x X + n_y F1) s + n_y F2 s^2 + n_y F3 s^3
    # (iv) h_V(s) = (V_y - c1 V_x) - 2 c2 X V_x s + (c2 - 3 c3 V_x) X^2 s^2 + 2 c3 X^3 s^3
    roots = _cubic_points(
        np.concatenate((ny * F3, np.full(k, 2.0 * F3))),
        np.concatenate((ny * F2, (c2 - 3.0 * c3 * vx) * X * X)),
        np.concatenate((nx * X + ny * F1, -2.0 * c2 * X * vx)),
        np.concatenate((-H, vy - c1 * vx)),
    )
    # stationary points: a_e' = 0 where f' equals the edge's slope; h_V' = 0 at x = V_x, f'' = 0
    crit = _quadratic_points(3.0 * ny * F3, 2.0 * ny * F2, nx * X + ny * F1)
    extra = [vx / X, np.array([0.0, 1.0])]
    if c3 != 0.0:
        extra.append(np.array([-c2 / (3.0 * c3 * X)]))
    s = np.concatenate((roots.ravel(), crit.ravel(), *extra))
    s = s[np.isfinite(s)]
    return np.clip(s, 0.0, 1.0)


def _front_meets(sw: Sweep, V, N, H, tol) -> float | None:
    """Certified test of event (iii): does the front-wheel path meet the polygon?

    Returns an abscissa ``s`` of a (near-)contact, or ``None`` if the path is free.
    """
    s = _S_FRONT
    B = sw.front(s)
    g = B @ N.T - H
    inside = np.flatnonzero(np.all(g <= tol, axis=1))
    if inside.size:
        return float(s[inside[0]])
    s_lo, s_hi, B_lo, B_hi, g_lo, g_hi = s[:-1], s[1:], B[:-1], B[1:], g[:-1], g[1:]
    h = 1.0 / _FRONT_PIECES
    while True:
        e = sw.K * h * h / 8.0  # the piece of path stays within e of its chord
        gap = np.max(np.minimum(g_lo, g_hi), axis=1)  # polygon edge normals
        d = B_hi - B_lo
        ln = np.hypot(d[:, 0], d[:, 1])
        ok = ln > 0
        mx = np.where(ok, -d[:, 1] / np.where(ok, ln, 1.0), 0.0)
        my = np.where(ok, d[:, 0] / np.where(ok, ln, 1.0), 0.0)
        side = np.multiply.outer(mx, V[:, 0]) + np.multiply.outer(my, V[:, 1])
        side -= (mx * B_lo[:, 0] + my * B_lo[:, 1])[:, None]
        chord_gap = np.where(ok, np.maximum(side.min(axis=1), -side.max(axis=1)), -np.inf)
        live = np.maximum(gap, chord_gap) <= e
        if not np.any(live):
            return None
        if e <= tol or np.count_nonzero(live) > _FRONT_MAX_PIECES:
            # within ~tol of touching: conservative; report the closest sampled position
            cand = np.concatenate((s_lo[live], s_hi[live], 0.5 * (s_lo[live] + s_hi[live])))
            return float(cand[np.argmin((sw.front(cand) @ N.T - H).max(axis=1))])
        s_lo, s_hi, B_lo, B_hi, g_lo, g_hi = (a[live] for a in (s_lo, s_hi, B_lo, B_hi, g_lo, g_hi))
        s_mid = 0.5 * (s_lo + s_hi)
        B_mid = sw.front(s_mid)
        g_mid = B_mid @ N.T - H
        inside = np.flatnonzero(np.all(g_mid <= tol, axis=1))
        if inside.size:
            return float(s_mid[inside[0]])
        s_lo, s_hi = np.concatenate((s_lo, s_mid)), np.concatenate((s_mid, s_hi))
        B_lo, B_hi = np.concatenate((B_lo, B_mid)), np.concatenate((B_mid, B_hi))
        g_lo, g_hi = np.concatenate((g_lo, g_mid)), np.concatenate((g_mid, g_hi))
        h *= 0.5


def _events(sw: Sweep, V, N, H, tol: float) -> float | None:
    """The event test (module docstring): frame abscissa of a contact, or None."""
    s = _event_abscissae(sw, V, N, H)
    i = _touching(sw, s, V, N, H, tol)
    if i >= 0:
        return float(s[i]) * sw.X
    s_hit = _front_meets(sw, V, N, H, tol)
    return None if s_hit is None else s_hit * sw.X


def _exact(sw: Sweep, poly: ConvexPolygon, tol: float, stats: CollisionStats) -> float | None:
    """The exact test: frame abscissa ``x`` of a contact, or None (free)."""
    V, N, H = sw.local(poly)
    x, undecided = _sweep(sw, V, N, H, tol)
    if undecided is None:
        return x
    stats.events += 1
    return _events(sw, V, N, H, tol)


def _query(union, polygon, check, stats) -> float | None:
    stats = STATS if stats is None else stats
    sw = as_sweep(union)
    poly = as_polygon(polygon, check)
    stats.calls += 1
    reject, tol = sw.quick_reject(poly)
    if reject:
        stats.rejected += 1
        return None
    stats.exact += 1
    x = _exact(sw, poly, tol, stats)
    if x is not None:
        stats.collisions += 1
    return x


def collides(
    union: Union | Sweep, polygon, *, check: bool = True, stats: CollisionStats | None = None
) -> bool:
    """Does any position of the segment along ``union`` touch the convex ``polygon``?

    Section "Collision-detection algorithm": quick checks first (box, then the paper's
    ``d_c > r_max + M``), then the exact test of the module docstring: a certified sweep
    that decides nearly every case, and for near-touches the event test (start pose; rear
    point on an edge; vertex swept by the segment; front-wheel path against the polygon).
    Touching counts as collision (closed sets), with a tiny conservative tolerance
    (:data:`TOUCH_RTOL`): never a miss, rarely a false alarm closer than ~1e-9 of the scene.

    Parameters
    ----------
    union : Union or Sweep
        A :class:`Sweep` reuses the per-union data across polygons.
    polygon : ConvexPolygon or array_like (k, 2)
        Convex, either orientation. A :class:`ConvexPolygon` is not re-validated.
    check : bool
        Validate an array polygon (``ValueError`` if malformed); pass ``False`` for
        pre-validated obstacles.
    stats : CollisionStats, optional
        Counters to update (default: the module's :data:`STATS`).

    Returns
    -------
    bool
    """
    return _query(union, polygon, check, stats) is not None


def collision_witness(
    union: Union | Sweep, polygon, *, check: bool = True, stats: CollisionStats | None = None
) -> float | None:
    """Frame abscissa ``x`` in ``[0, union.x_end]`` of a position that touches ``polygon``.

    Like :func:`collides`, but returns where (not necessarily the first contact), or
    ``None`` when the union is free of the polygon.
    """
    return _query(union, polygon, check, stats)


def union_free(
    union: Union | Sweep,
    obstacles,
    bounds=None,
    *,
    check: bool = True,
    stats: CollisionStats | None = None,
) -> bool:
    """Is every position of the segment along ``union`` clear of all obstacles and walls?

    Quick rejections run for every obstacle first; then the bounds; then the exact tests
    of the obstacles that survived.

    Parameters
    ----------
    union : Union or Sweep
    obstacles : iterable of ConvexPolygon or (k, 2) arrays
    bounds : (xmin, ymin, xmax, ymax), optional
        See :func:`union_in_bounds`.
    check : bool
        Validate array polygons.
    stats : CollisionStats, optional
    """
    stats = STATS if stats is None else stats
    sw = as_sweep(union)
    near = []
    for i, p in enumerate(obstacles):
        poly = as_polygon(p, check, name=f"obstacles[{i}]")
        stats.calls += 1
        reject, tol = sw.quick_reject(poly)
        if reject:
            stats.rejected += 1
        else:
            near.append((poly, tol))
    if bounds is not None and not union_in_bounds(sw, bounds):
        return False
    for poly, tol in near:
        stats.exact += 1
        if _exact(sw, poly, tol, stats) is not None:
            stats.collisions += 1
            return False
    return True


# -- walls --------------------------------------------------------------------------------------
def _front_reaches(sw: Sweep, N, H, tol) -> bool:
    """Certified: does ``max_s n_j . B(s) - h_j >= -tol`` for some wall ``j``?"""
    s = _S_FRONT
    g = sw.front(s) @ N.T - H  # (n, m)
    if np.any(g >= -tol):
        return True
    s_lo, s_hi, g_lo, g_hi = s[:-1], s[1:], g[:-1], g[1:]
    h = 1.0 / _FRONT_PIECES
    while True:
        e = sw.K * h * h / 8.0
        live = np.any(np.maximum(g_lo, g_hi) + e >= -tol, axis=1)
        if not np.any(live):
            return False
        if e <= tol or np.count_nonzero(live) > _FRONT_MAX_PIECES:
            return True
        s_lo, s_hi, g_lo, g_hi = s_lo[live], s_hi[live], g_lo[live], g_hi[live]
        s_mid = 0.5 * (s_lo + s_hi)
        g_mid = sw.front(s_mid) @ N.T - H
        if np.any(g_mid >= -tol):
            return True
        s_lo, s_hi = np.concatenate((s_lo, s_mid)), np.concatenate((s_mid, s_hi))
        g_lo, g_hi = np.concatenate((g_lo, g_mid)), np.concatenate((g_mid, g_hi))
        h *= 0.5


def union_in_bounds(union: Union | Sweep, bounds) -> bool:
    """Does every position of the segment lie strictly inside the rectangle ``bounds``?

    The rectangle is convex, so a segment lies inside iff both end points do: the rear
    cubic (its extremes along each wall normal: ends and roots of a quadratic, exact) and
    the front-wheel path (certified subdivision, as for event (iii)). Touching a wall is
    leaving the bounds (walls are closed obstacles), with the tolerance of
    :func:`collides`. A quick sufficient test first: the corners of the union's frame box.

    Parameters
    ----------
    union : Union or Sweep
    bounds : (xmin, ymin, xmax, ymax)
    """
    checked = _bounds(bounds)  # checked before the union, as always
    return _union_in_bounds(as_sweep(union), checked)


def _union_in_bounds(sw: Sweep, bounds: tuple[float, float, float, float]) -> bool:
    """:func:`union_in_bounds` of a sweep, for bounds already checked by :func:`_bounds`."""
    xmin, ymin, xmax, ymax = bounds
    tol = TOUCH_RTOL * (sw.size + (xmax - xmin) + (ymax - ymin) + math.hypot(sw.x0, sw.y0))
    x_lo, x_hi, y_lo, y_hi = sw.box
    # the frame box in world coordinates: centre and half extents of its bounding rectangle
    mx, my, hw, hh = 0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi), 0.5 * (x_hi - x_lo), 0.5 * (y_hi - y_lo)
    wx, wy = sw.x0 + sw.cos * mx - sw.sin * my, sw.y0 + sw.sin * mx + sw.cos * my
    ex, ey = abs(sw.cos) * hw + abs(sw.sin) * hh, abs(sw.sin) * hw + abs(sw.cos) * hh
    if xmin + tol < wx - ex and wx + ex < xmax - tol and ymin + tol < wy - ey and wy + ey < ymax - tol:
        return True
    Nw = np.array([[-1.0, 0.0], [1.0, 0.0], [0.0, -1.0], [0.0, 1.0]])  # outward wall normals
    Hw = np.array([-xmin, xmax, -ymin, ymax])
    N = Nw @ sw.rot
    H = Hw - Nw @ sw.p0
    X, c1, c2, c3 = sw.X, sw.c1, sw.c2, sw.c3
    nx, ny = N[:, 0], N[:, 1]
    # rear: a_j(s) = n_x X s + n_y f(X s) - h, maximal at s in {0, 1} or a_j'(s) = 0
    crit = _quadratic_points(3.0 * ny * c3 * X**3, 2.0 * ny * c2 * X * X, nx * X + ny * c1 * X)
    s = np.concatenate((crit.ravel(), [0.0, 1.0]))
    s = np.clip(s[np.isfinite(s)], 0.0, 1.0)
    x, fx, _, _ = sw.segment(s)
    if np.any(np.multiply.outer(x, nx) + np.multiply.outer(fx, ny) - H >= -tol):
        return False
    return not _front_reaches(sw, N, H, tol)


# -- single poses ---------------------------------------------------------------------------------
def _pose_segment(pose, L):
    p = as_pose(pose)
    L = check_length(L)
    return p.x, p.y, L * math.cos(p.theta), L * math.sin(p.theta), L


def pose_collides(pose, L: float, polygon, *, check: bool = True) -> bool:
    """Does the robot's segment at ``pose`` (A and heading, radians) touch ``polygon``?

    Separating axes (the polygon's edge normals and the segment's normal); touching
    counts, with the tolerance of :func:`collides`.
    """
    ax, ay, dx, dy, L = _pose_segment(pose, L)
    poly = as_polygon(polygon, check)
    V = poly.vertices - (ax, ay)
    tol = TOUCH_RTOL * (
        L + poly.radius + math.hypot(poly.centre[0] - ax, poly.centre[1] - ay) + max(abs(ax), abs(ay))
    )
    gA = -(poly.offsets - poly.normals @ (ax, ay))
    gB = gA + poly.normals @ (dx, dy)
    if np.any(np.minimum(gA, gB) > tol):
        return False
    side = (dx * V[:, 1] - dy * V[:, 0]) / L
    return not (np.all(side > tol) or np.all(side < -tol))


def pose_in_bounds(pose, L: float, bounds) -> bool:
    """Does the robot's segment at ``pose`` lie strictly inside ``bounds`` (walls)?"""
    ax, ay, dx, dy, L = _pose_segment(pose, L)
    xmin, ymin, xmax, ymax = _bounds(bounds)
    tol = TOUCH_RTOL * (L + (xmax - xmin) + (ymax - ymin) + math.hypot(ax, ay))
    xs, ys = (ax, ax + dx), (ay, ay + dy)
    return xmin + tol < min(xs) and max(xs) < xmax - tol and ymin + tol < min(ys) and max(ys) < ymax - tol
