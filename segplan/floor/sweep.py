"""The per-union data of the collision test: the swept segment of a union (:class:`Sweep`).

Section "Collision-detection algorithm" of Campoy et al. (1989): the inputs of the test
are "the trajectory of the reference point ... a cubic polynomial and limiting
abscissa". :class:`Sweep` holds what every polygon test of one union needs, computed
once: the frame box of the swept set, the paper's ``d_c`` polyline and ``M`` bound,
bounds on the curvature of the swept points, the level-0 grid of the certified sweep.
The tests themselves are in :mod:`segplan.floor.collision` (see its docstring for the method).
The polynomial root helpers on ``[0, 1]`` are shared by both.
"""

from __future__ import annotations

import math

import numpy as np

from ..model.union import Union
from .geometry import TOUCH_RTOL, ConvexPolygon

__all__ = [
    "Sweep",
    "as_sweep",
    "corners",
    "cubic_points",
    "hull_axes",
    "quadratic_points",
]

_DC_PIECES = 16  # pieces of the polyline used to bound d_c from below
_SWEEP_PIECES = 32  # level-0 pieces of the certified sweep
_THETA2 = 1.65  # > 1 + 2 * 3 sqrt(3) / 16 = 1.6495


# -- polynomials on [0, 1] ----------------------------------------------------------------------
def quadratic_points(a2, a1, a0):
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


def cubic_points(a3, a2, a1, a0):
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


def hull_axes(P4):
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


def corners(A_lo, B_lo, A_hi, B_hi):
    """Stack the four end points of pieces, ``(m, 4, 2)``."""
    P4 = np.empty((len(A_lo), 4, 2))
    P4[:, 0], P4[:, 1], P4[:, 2], P4[:, 3] = A_lo, B_lo, A_hi, B_hi
    return P4


_PAIR_I = np.array([0, 2, 0, 1, 0, 1])
_PAIR_J = np.array([1, 3, 2, 3, 3, 2])
_S_GRID = np.linspace(0.0, 1.0, _SWEEP_PIECES + 1)
_S_DC = np.linspace(0.0, 1.0, _DC_PIECES + 1)


class _Grid:
    """Level-0 positions of the certified sweep (per union, built on first use)."""

    __slots__ = ("s", "A", "B", "nseg", "oseg", "nrm", "qmin", "qmax", "kx", "dx", "e")


class Sweep:
    """Per-union data of the collision tests, computed once (read-only).

    Parameters
    ----------
    union : Union
    rear, front : float
        The robot's overhangs (>= 0, :class:`segplan.Robot`; beyond the paper): the swept
        segment is the axis segment ``P(x, t) = A(x) + t u(x)``, ``t`` in ``[t0, t1] =
        [-rear, L + front]``, instead of A->B (``[0, L]``, the default). Its points
        follow the robot's rigid motion, so every bound below holds with ``L`` replaced
        by ``reach = max(rear, L + front)``, the largest ``|t|`` (see
        :mod:`segplan.floor.collision`).

    Notes
    -----
    Frame quantities refer to the union's alpha frame (origin ``p0``, x-axis at world
    angle ``union.frame_angle``). ``box = (x_lo, x_hi, y_lo, y_hi)`` is a rectangle of that
    frame containing every position of the segment. Reusing one ``Sweep`` for all
    obstacles (as :func:`union_free` does) saves the per-union work. With ``rear = front
    = 0`` every float is the one of the paper's segment (the same decisions, bit for bit).
    """

    __slots__ = (
        "union", "L", "X", "c1", "c2", "c3", "x0", "y0", "cos", "sin", "box", "dc_end", "dc_margin",
        "K", "size", "mag", "_grid", "_dc", "_rot", "t0", "t1", "reach", "dc_start",
    )  # fmt: skip

    def __init__(self, union: Union, rear: float = 0.0, front: float = 0.0):
        if not isinstance(union, Union):
            raise ValueError(f"union must be a segplan.Union, got {type(union).__name__}")
        rear, front = float(rear), float(front)
        if not (0.0 <= rear < math.inf and 0.0 <= front < math.inf):
            raise ValueError(f"rear and front must be finite and >= 0, got rear={rear}, front={front}")
        X = union.x_end
        t1 = union.L + front  # the front end's t (L: the front wheel B)
        L = max(rear, t1)  # the reach: every bound below that held with L for A->B
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
        # a point A + t u has frame abscissa x + t u_x in [-rear, X + t1] and height
        # f(x) + t u_y: t1 u_y below (u_y < 0) or above, -rear u_y the other way
        lo_t, hi_t = t1 * min(0.0, uy_lo), t1 * max(0.0, uy_hi)
        if rear:
            lo_t, hi_t = min(lo_t, -rear * max(0.0, uy_hi)), max(hi_t, -rear * min(0.0, uy_lo))
        box = (-rear if rear else 0.0, X + t1, min(fs) + lo_t, max(fs) + hi_t)
        # d_c: polyline of the cubic (M = reach), or of the cubic extended to [-rear, X + t1]
        # (M = reach^2 max|f''| / 2: the point at t has abscissa x + h, |h| <= |t|)
        f2 = max(abs(2.0 * c2), abs(2.0 * c2 + 6.0 * c3 * X))
        f2e = max(abs(2.0 * c2), abs(2.0 * c2 + 6.0 * c3 * (X + t1)))
        if rear:
            f2e = max(f2e, abs(2.0 * c2 - 6.0 * c3 * rear))
        m_ext = 0.5 * L * L * f2e
        x_start, x_end, margin, f2c = (-rear, X + t1, m_ext, f2e) if m_ext < L else (0.0, X, L, f2)
        margin += f2c * ((x_end - x_start) / _DC_PIECES) ** 2 / 8.0  # chord error of the polyline
        # |B''| bound over [0, X] (x units), then in s = x / X units
        k_x = f2 + L * (6.0 * abs(c3) + _THETA2 * f2 * f2)
        values = (
            union, union.L, X, c1, c2, c3, union.p0.x, union.p0.y, cb, sb, box, x_end, margin,
            k_x * X * X, t1 + rear + X, max(abs(union.p0.x), abs(union.p0.y)), None, None, None,
            -rear, t1, L, x_start,
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
        """Frame front ends of the swept segment at ``s``, ``(n, 2)``: the front wheels ``B``
        without a front overhang."""
        return self.point(s, self.t1)

    def point(self, s, t: float) -> np.ndarray:
        """Frame points ``A + t u`` at ``s``, ``(n, 2)`` (``t = L``: the front wheel ``B``)."""
        x, fx, ux, uy = self.segment(s)
        return np.stack((x + t * ux, fx + t * uy), axis=-1)

    def ends(self, s) -> tuple[np.ndarray, np.ndarray]:
        """Frame end points of the swept segment at ``s``, rear and front, ``(n, 2)`` each
        (``A`` itself without a rear overhang)."""
        x, fx, ux, uy = self.segment(s)
        front = np.stack((x + self.t1 * ux, fx + self.t1 * uy), axis=-1)
        if self.t0 == 0.0:
            return np.stack((x, fx), axis=-1), front
        return np.stack((x + self.t0 * ux, fx + self.t0 * uy), axis=-1), front

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

    def bend(self, s_lo, s_hi, reach: float | None = None) -> np.ndarray:
        """Bound on ``|P''(x)|`` (x units) over each ``[s_lo, s_hi]``, for every point ``P``
        of the segment (``P = A + t u``, ``t0 <= t <= t1``; ``|P''| <= |A''| + reach |u''|``).

        ``reach``: another bound of the points' distance from A (default :attr:`reach`); the
        rectangular body's farthest corner (:mod:`segplan.floor.body`)."""
        c2, c3, X = self.c2, self.c3, self.X
        f2 = np.maximum(np.abs(2.0 * c2 + 6.0 * c3 * X * s_lo), np.abs(2.0 * c2 + 6.0 * c3 * X * s_hi))
        return f2 + (self.reach if reach is None else reach) * (6.0 * abs(c3) + _THETA2 * f2 * f2)

    def grid(self) -> _Grid:
        """Positions, hull axes and chord bounds of the level-0 sweep (cached)."""
        g = self._grid
        if g is not None:
            return g
        g = _Grid()
        g.s = s = _S_GRID
        x, fx, ux, uy = self.segment(s)
        g.A = A = np.empty((len(s), 2))  # the rear ends (A without a rear overhang)
        A[:, 0], A[:, 1] = (x, fx) if self.t0 == 0.0 else (x + self.t0 * ux, fx + self.t0 * uy)
        g.B = B = np.empty_like(A)  # the front ends
        B[:, 0], B[:, 1] = x + self.t1 * ux, fx + self.t1 * uy
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
            a = self.dc_start
            px = self.dc_end * _S_DC if a == 0.0 else a + (self.dc_end - a) * _S_DC
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


def as_sweep(union: Union | Sweep) -> Sweep:
    """Return ``union``'s :class:`Sweep` (a new one for a :class:`Union`; no hidden cache).

    Callers that test one union against several polygons build its sweep once
    (:func:`segplan.floor.collision.union_free` and :class:`segplan.planning.validity.Workspace` do).
    """
    return union if isinstance(union, Sweep) else Sweep(union)
