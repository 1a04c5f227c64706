"""The union of two nodes: a cubic in an alpha reference system.

Section "Generation of the trajectory of union between two nodes": the rear-axle point A
follows ``y = f(x)``, the unique cubic that matches both positions and both headings in a
given alpha reference system. With ``X = d cos(alpha)``, ``t = tan(alpha)`` and the end
slopes relative to the chord ``mbar_i = tan(phi_i + alpha) - tan(alpha)`` (the paper's
"m bar"), the cubic is the chord plus a Hermite bump that vanishes at both ends::

    f(x) = t x + X [mbar0 h10(x/X) + mbar1 h11(x/X)],
    h10(s) = s^3 - 2 s^2 + s,   h11(s) = s^3 - s^2,

that is ``f(x) = c1 x + c2 x^2 + c3 x^3`` with ``c1 = tan(phi0 + alpha)``,
``c2 = -(2 mbar0 + mbar1) / X`` and ``c3 = (mbar0 + mbar1) / X^2``.

The front wheel B is ``A + L (1, f') / sqrt(1 + f'^2)`` (the robot is tangent to the
rear path: "the robot orientation ... is always tangent to trajectories").
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from .pose import Pose, as_pose, check_alpha, check_length, intrinsic

__all__ = [
    "Union",
    "chord_slopes",
    "cubic_coefficients",
    "curvature_polynomials",
    "curvature_samples",
    "exceeds_curvature",
    "max_curvatures",
    "peak_curvature",
]


def chord_slopes(phi0, phi1, alpha):
    """End slopes relative to the chord, the paper's ``mbar_i = m_i - tan(alpha)``.

    Vectorised over all arguments. ``m_i = tan(phi_i + alpha)`` is the slope of the
    heading in the alpha frame; the caller keeps ``alpha`` inside the feasible interval.
    """
    return _slopes(phi0, phi1, alpha)[1:]


def _slopes(phi0, phi1, alpha):
    """``tan(alpha)`` and :func:`chord_slopes` (``tan(alpha)`` computed once)."""
    t = np.tan(alpha)
    return t, np.tan(np.add(phi0, alpha)) - t, np.tan(np.add(phi1, alpha)) - t


def cubic_coefficients(d, phi0, phi1, alpha, each: bool = False):
    """Span and coefficients of the union's cubic in the alpha frame (vectorised).

    Parameters
    ----------
    d, phi0, phi1, alpha : float or array_like
        Chord length, intrinsic headings and the frame's alpha (they broadcast).
    each : bool
        Square each span as a call for that union alone does (``X**2`` of a scalar is the C
        library's ``pow``, of an array a product, and the two may differ in the last bit):
        every value that of a call for each union alone, to the last bit (numpy's ``cos``
        and ``tan`` give an array's elements a scalar's values: measured).

    Returns
    -------
    X, c1, c2, c3 : float or ndarray
        ``f(x) = c1 x + c2 x^2 + c3 x^3`` on ``[0, X]``, ``X = d cos(alpha)``.
    """
    X = np.multiply(d, np.cos(alpha))
    t, m0, m1 = _slopes(phi0, phi1, alpha)
    c1 = t + m0  # f'(0) = tan(phi0 + alpha)
    c2 = -(2.0 * m0 + m1) / X  # from f(X) = X tan(alpha), f'(X) = tan(phi1 + alpha)
    if each and np.ndim(X) > 0:
        c3 = (m0 + m1) / np.array([x**2 for x in np.ravel(X)]).reshape(np.shape(X))  # each scalar's pow
    else:
        c3 = (m0 + m1) / X**2
    return X, c1, c2, c3


# -- the rear path's curvature: its polynomials, and samples --------------------------------
def curvature_polynomials(c1: float, c2: float, c3: float):
    """The polynomials in ``x`` behind the rear path's curvature and its derivative.

    With ``f(x) = c1 x + c2 x^2 + c3 x^3`` (:func:`cubic_coefficients`) the curvature is
    ``kappa = f'' / (1 + f'^2)^(3/2)`` (:func:`peak_curvature`) and its derivative
    ``d kappa / dx = N / (1 + f'^2)^(5/2)`` with ``N = f''' (1 + f'^2) - 3 f' f''^2``, a
    quartic: its real roots are the stationary points of the curvature
    (:meth:`Union.max_curvature`). Along the arc length ``s`` of the rear path
    (``ds / dx = (1 + f'^2)^(1/2)``), ``d kappa / ds = N / (1 + f'^2)^3``.

    Returns
    -------
    fp, fpp, crit : numpy.polynomial.Polynomial
        ``f'``, ``f''`` and ``N`` (:func:`_quartic`).
    """
    p1 = np.polynomial.Polynomial([c1, 2 * c2, 3 * c3])  # f'
    p2 = np.polynomial.Polynomial([2 * c2, 6 * c3])  # f''
    return p1, p2, np.polynomial.Polynomial(_quartic(c1, c2, c3))


def _trim(c: np.ndarray) -> np.ndarray:
    """``c`` without its trailing zero coefficients (one kept), as ``numpy.polynomial`` trims."""
    n = len(c)
    while n > 1 and c[n - 1] == 0:
        n -= 1
    return c[:n]


def _quartic(c1: float, c2: float, c3: float) -> np.ndarray:
    """Coefficients (lowest first, trailing zeros trimmed) of the quartic
    ``N = f''' (1 + f'^2) - 3 f' f''^2`` of :func:`curvature_polynomials`.

    The operations of ``numpy.polynomial``'s arithmetic on ``Polynomial`` objects
    (``6 c3 (1 + p1**2) - 3 p1 p2**2``), in its order, on plain arrays: the same values to the
    last bit, without the objects' overhead.
    """
    p1 = _trim(np.array([c1, 2 * c2, 3 * c3]))  # f'
    p2 = _trim(np.array([2 * c2, 6 * c3]))  # f''
    w = _trim(np.convolve(p1, p1))  # f'^2
    w[0] += 1.0  # 1 + f'^2
    a = _trim(np.convolve(_trim(w), np.array([6 * c3])))  # f''' (1 + f'^2)
    b = _trim(np.convolve(_trim(np.convolve(p1, np.array([3.0]))), _trim(np.convolve(p2, p2))))  # 3 f' f''^2
    if len(a) > len(b):
        out = a
        out[: len(b)] -= b
    else:
        out = -b
        out[: len(a)] += a
    return _trim(out)


def _roots(c: np.ndarray) -> np.ndarray:
    """Roots of the polynomial of trimmed coefficients ``c`` (lowest first), as
    ``numpy.polynomial.polynomial.polyroots`` finds them: the eigenvalues of its companion
    matrix, sorted. Rows ``c`` ``(m, k)`` of polynomials of one degree give rows of roots,
    each that of a call for it alone (LAPACK's ``geev`` on each matrix; complex where any
    row's roots are, real where all are)."""
    k = c.shape[-1]
    if k < 2:
        return np.zeros((*c.shape[:-1], 0), dtype=c.dtype)
    if k == 2:
        return -c[..., :1] / c[..., 1:]
    n = k - 1
    mat = np.zeros((*c.shape[:-1], n, n), dtype=c.dtype)
    mat.reshape(-1, n * n)[:, n :: n + 1] = 1
    mat[..., -1] -= c[..., :-1] / c[..., -1:]
    r = np.linalg.eigvals(mat)
    r.sort(axis=-1)
    return r


def _stationary(c1, c2, c3, x_end) -> list[list[float]]:
    """:meth:`Union.curvature_stationary` of each cubic ``(c1[k], c2[k], c3[k])`` on
    ``[0, x_end[k]]`` (sequences of float): the roots of the quartics of one degree in one
    call of :func:`_roots`, filtered as that method filters one union's (which keeps its own
    few lines: through this function a single call took 1.3-1.7 times as long, measured)."""
    crits = [_quartic(a, b, c) for a, b, c in zip(c1, c2, c3, strict=True)]
    out: list[list[float]] = [[] for _ in crits]
    by_degree: dict[int, list[int]] = {}
    for k, crit in enumerate(crits):
        if crit.any():  # N does not vanish identically
            by_degree.setdefault(len(crit), []).append(k)
    for group in by_degree.values():
        roots = _roots(np.array([crits[k] for k in group]))
        inside = (
            (np.abs(roots.imag) < 1e-9)
            & (0.0 < roots.real)
            & (roots.real < np.array([x_end[k] for k in group])[:, None])
        )
        for k, r, real in zip(group, roots.real, inside, strict=True):
            out[k] = r[real].tolist()
    return out


def max_curvatures(x_end, c1, c2, c3) -> np.ndarray:
    """:meth:`Union.max_curvature` of many unions, each value that of the method to the last bit.

    Each union's stationary points are those of :meth:`Union.curvature_stationary`; the
    curvature at them and at the ends is evaluated for all the unions at once, elementwise
    (:func:`curvature_samples` and :func:`peak_curvature`: the same operations as
    :meth:`Union.curvature`; each row padded with its start, which leaves its maximum as it is).

    Parameters
    ----------
    x_end, c1, c2, c3 : sequence of float
        Each union's span and cubic coefficients (:func:`cubic_coefficients`).

    Returns
    -------
    ndarray
        The largest ``|curvature|`` of each union's rear path.
    """
    cols = [np.asarray(v, dtype=float).ravel() for v in (x_end, c1, c2, c3)]
    X, *coefficients = (v.tolist() for v in cols)
    rows = [[0.0, x, *roots] for x, roots in zip(X, _stationary(*coefficients, X), strict=True)]
    width = max(map(len, rows), default=2)
    x = np.array([row + [0.0] * (width - len(row)) for row in rows]).reshape(-1, width)
    _, fp, fpp = curvature_samples(x, *(v[:, None] for v in cols[1:]), 1.0)  # at x itself
    return peak_curvature(fp, fpp, axis=1)


def curvature_samples(X, c1, c2, c3, s):
    """Abscissae ``x = X s`` and the cubic's ``f'(x)``, ``f''(x)`` there (vectorised).

    The one sampling kernel of the steering limit's screens: :func:`peak_curvature` and
    :func:`exceeds_curvature` reduce its output. The rear point A follows
    ``f(x) = c1 x + c2 x^2 + c3 x^3`` (:func:`cubic_coefficients`); the planners sample it
    at fractions ``s`` of its span ``X`` (17, 33, 7 frames x 17, 49 or 9 abscissae, each
    caller its own). ``X, c1, c2, c3`` broadcast against ``s`` as the caller shapes them
    (``X[:, None]`` against ``s`` of shape ``(m,)`` samples each of ``n`` cubics at ``m``
    abscissae); the arithmetic, in this order, is every planner's, to the last bit.

    Returns
    -------
    x, fp, fpp : ndarray
        ``x = X s``, ``f'(x)`` and ``f''(x)``.
    """
    x = X * s
    fp = c1 + (2.0 * c2 + 3.0 * c3 * x) * x  # f'(x) = c1 + 2 c2 x + 3 c3 x^2
    fpp = 2.0 * c2 + 6.0 * c3 * x  # f''(x) = 2 c2 + 6 c3 x
    return x, fp, fpp


def peak_curvature(fp, fpp, axis=-1):
    """Largest sampled ``|kappa|`` of the rear path, from :func:`curvature_samples`.

    The curvature of a graph ``y = f(x)`` is ``kappa = f'' / (1 + f'^2)^(3/2)``: the
    heading is ``theta = arctan f'``, so ``d theta / dx = f'' / (1 + f'^2)``, and the arc
    length grows as ``ds / dx = (1 + f'^2)^(1/2)``; ``kappa = d theta / ds`` is their
    quotient. Section "Mobile robot modelling": the robot is tangent to the rear path
    ("the robot orientation ... is always tangent to trajectories"), a bicycle whose
    front wheel steers by ``arctan(L kappa)``; a steering angle at most ``max_steer``
    bounds ``|kappa|`` by ``tan(max_steer) / L`` (:attr:`segplan.floor.scenario.Robot.max_curvature`).
    That limit is ours (the paper's robot has none); the planners keep every union within
    it. A sampled maximum is a lower bound of the true one (:meth:`Union.max_curvature`).

    Returns
    -------
    ndarray
        ``max |f''| / (1 + f'^2)^(3/2)`` over ``axis``.
    """
    return np.max(np.abs(fpp) / (1.0 + fp * fp) ** 1.5, axis=axis)  # max |kappa|


def exceeds_curvature(fp, fpp, kappa_max, axis=-1):
    """Does a sample break the steering limit, ``|kappa| > kappa_max``? (a certain failure).

    The same test as ``peak_curvature(fp, fpp) > kappa_max`` without the division:
    ``|f''| > kappa_max (1 + f'^2)^(3/2)`` (see :func:`peak_curvature`), which may differ
    from it in the last bit; planners that screened this way keep doing so.

    Returns
    -------
    bool or ndarray
        ``any(|f''| > kappa_max (1 + f'^2)^(3/2))`` over ``axis``.
    """
    return np.any(np.abs(fpp) > kappa_max * (1.0 + fp * fp) ** 1.5, axis=axis)


class Union:
    """The cubic union of two nodes in the alpha reference system (immutable).

    Parameters
    ----------
    p0, p1 : Pose or sequence (x, y, theta)
        Start and end nodes: rear-axle point and heading (radians).
    alpha : float
        Angle of the chord in the reference system (radians); the frame's x-axis is at
        world angle ``psi - alpha`` with ``psi`` the chord's angle.
    L : float
        Robot length, rear axle to front wheel (> 0).

    Raises
    ------
    ValueError
        Coincident points, non-finite input, ``L <= 0``, or ``alpha`` outside the
        interval where the cubic exists (``|alpha| < pi/2``, ``|phi_i + alpha| < pi/2``);
        the message names the quantity.

    Notes
    -----
    Section "Description of the method of interpolation". The frame coordinates ``x`` run
    over ``[0, x_end]``; every sampling method returns world coordinates.
    """

    __slots__ = ("p0", "p1", "alpha", "L", "d", "psi", "phi0", "phi1", "x_end", "coefficients")

    def __init__(self, p0: Sequence[float] | Pose, p1: Sequence[float] | Pose, alpha: float, L: float):
        ends = (as_pose(p0, "p0"), as_pose(p1, "p1"))
        L = check_length(L)
        geo = intrinsic(*ends)
        alpha = check_alpha(alpha, geo.phi0, geo.phi1)
        X, c1, c2, c3 = cubic_coefficients(geo.d, geo.phi0, geo.phi1, alpha)
        for name, value in zip(
            ("p0", "p1", "alpha", "L", "d", "psi", "phi0", "phi1", "x_end", "coefficients"),
            (*ends, alpha, L, *geo, float(X), (0.0, float(c1), float(c2), float(c3))),
            strict=True,
        ):
            object.__setattr__(self, name, value)

    @classmethod
    def from_intrinsic(
        cls, p0: Pose, p1: Pose, alpha: float, L: float, d: float, psi: float, phi0: float, phi1: float
    ) -> Union:
        """Build a union from parameters the caller has already validated (no checks).

        A fast path for the planner, which builds thousands of unions and has computed
        the intrinsic parameters (``segplan.model.pose.intrinsic(p0, p1)``) and checked
        ``alpha`` and ``L`` itself. Equal to ``Union(p0, p1, alpha, L)`` up to rounding
        (scalar ``math`` instead of numpy), for the search's speed.
        """
        t = math.tan(alpha)
        m0 = math.tan(phi0 + alpha) - t  # mbar0
        m1 = math.tan(phi1 + alpha) - t  # mbar1
        X = d * math.cos(alpha)
        coefficients = (0.0, t + m0, -(2.0 * m0 + m1) / X, (m0 + m1) / (X * X))
        self = object.__new__(cls)
        for name, value in zip(
            ("p0", "p1", "alpha", "L", "d", "psi", "phi0", "phi1", "x_end", "coefficients"),
            (
                Pose(*p0),
                Pose(*p1),
                float(alpha),
                float(L),
                float(d),
                float(psi),
                float(phi0),
                float(phi1),
                X,
                coefficients,
            ),
            strict=True,
        ):
            object.__setattr__(self, name, value)
        return self

    def __setattr__(self, name, value):
        raise AttributeError("Union is immutable")

    def __repr__(self) -> str:
        return f"Union(p0={tuple(self.p0)}, p1={tuple(self.p1)}, alpha={self.alpha:.6g}, L={self.L:.6g})"

    # -- a value: equality, hashing, its state -------------------------------------------
    def _values(self) -> tuple:
        return tuple(getattr(self, name) for name in Union.__slots__)

    def __eq__(self, other) -> bool:
        """Equal unions hold equal values in every slot (ends, ``alpha``, ``L``, the intrinsic
        parameters, span and coefficients): two unions that sample alike to the last bit."""
        if not isinstance(other, Union):
            return NotImplemented
        return self._values() == other._values()

    def __hash__(self) -> int:
        return hash(self._values())

    def __reduce__(self):
        return (_restore, (self._values(),))

    def state(self) -> dict:
        """Every value the union holds, as plain floats (JSON-ready; ``repr`` round-trips them).

        ``Union.from_state(u.state()) == u`` bit for bit, whichever way ``u`` was built
        (``Union(...)`` with numpy, :meth:`from_intrinsic` with ``math``: the two may differ
        in the last bit, and a plan's cost and sampling depend on the values it holds).
        Keys: ``p0``, ``p1`` (lists ``[x, y, theta]``), ``alpha``, ``L``, ``d``, ``psi``,
        ``phi0``, ``phi1``, ``x_end`` and ``coefficients`` (``[c1, c2, c3]``, ``c0 = 0``).
        """
        return {
            "p0": [float(v) for v in self.p0],
            "p1": [float(v) for v in self.p1],
            **{name: float(getattr(self, name)) for name in _SCALARS},
            "coefficients": [float(c) for c in self.coefficients[1:]],
        }

    @classmethod
    def from_state(cls, state: Mapping) -> Union:
        """The union of a :meth:`state`, its values kept exactly, after a check.

        The ends, ``alpha`` and ``L`` are validated as by ``Union(p0, p1, alpha, L)``, and
        each stored derived value (``d``, ``psi``, ``phi0``, ``phi1``, ``x_end``, the
        coefficients) must agree with the one that constructor computes to ``1e-9`` of its
        scale (lengths: ``x_end``; angles: 1; ``c_k``: ``M x_end^(1 - k)`` with ``M`` the
        largest of 1 and ``|c_k| x_end^(k - 1)``, the size of the slope's terms): rounding
        passes, an edited or corrupted state does not.

        Raises
        ------
        ValueError
            A missing or malformed value, or one that disagrees with the ends and ``alpha``,
            named.
        """
        if not isinstance(state, Mapping):
            raise ValueError(f"a union's state must be a mapping, got {type(state).__name__}")
        names = ("p0", "p1", "alpha", "L", "d", "psi", "phi0", "phi1", "x_end", "coefficients")
        missing = [n for n in names if n not in state]
        if missing:
            raise ValueError(f"a union's state lacks {', '.join(missing)}")
        ref = cls(state["p0"], state["p1"], state["alpha"], state["L"])  # validates ends, alpha, L
        coefficients = state["coefficients"]
        if not (isinstance(coefficients, Sequence) and len(coefficients) == 3):
            raise ValueError(f"a union's coefficients must be [c1, c2, c3], got {coefficients!r}")
        X = ref.x_end
        M = max(1.0, *(abs(c) * X ** (k - 1) for k, c in enumerate(ref.coefficients[1:], start=1)))
        scales = {"d": X, "psi": 1.0, "phi0": 1.0, "phi1": 1.0, "x_end": X}
        derived = {name: state[name] for name in scales}
        for k, c in enumerate(coefficients, start=1):
            name = f"c{k}"
            scales[name], derived[name] = M * X ** (1 - k), c
        expected = {n: getattr(ref, n) for n in ("d", "psi", "phi0", "phi1", "x_end")}
        expected.update(zip(("c1", "c2", "c3"), ref.coefficients[1:], strict=True))
        for name, value in derived.items():
            if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
                raise ValueError(f"a union's {name} must be a finite number, got {value!r}")
            if abs(value - expected[name]) > 1e-9 * scales[name]:
                raise ValueError(
                    f"a union's stored {name}={value!r} disagrees with its ends and alpha "
                    f"({expected[name]!r})"
                )
        return _restore(
            (
                ref.p0,
                ref.p1,
                ref.alpha,
                ref.L,
                *(float(derived[n]) for n in ("d", "psi", "phi0", "phi1", "x_end")),
                (0.0, *(float(c) for c in coefficients)),
            )
        )

    # -- the cubic in its own frame ------------------------------------------------
    @property
    def frame_angle(self) -> float:
        """World angle of the alpha frame's x-axis, ``psi - alpha``."""
        return self.psi - self.alpha

    def f(self, x):
        """Rear-path ordinate ``f(x)`` in the alpha frame."""
        _, c1, c2, c3 = self.coefficients
        x = np.asarray(x, dtype=float)
        return ((c3 * x + c2) * x + c1) * x

    def slope(self, x):
        """``f'(x)`` in the alpha frame."""
        _, c1, c2, c3 = self.coefficients
        x = np.asarray(x, dtype=float)
        return (3.0 * c3 * x + 2.0 * c2) * x + c1

    def second_derivative(self, x):
        """``f''(x)`` in the alpha frame."""
        _, _, c2, c3 = self.coefficients
        return 6.0 * c3 * np.asarray(x, dtype=float) + 2.0 * c2

    def curvature(self, x):
        """Signed curvature of the rear path, ``f'' / (1 + f'^2)^(3/2)`` (1/length)."""
        return self.second_derivative(x) / (1.0 + self.slope(x) ** 2) ** 1.5

    def max_curvature(self) -> float:
        """Largest ``|curvature|`` of the rear path over the union, found exactly.

        Interior extrema solve ``f''' (1 + f'^2) - 3 f' f''^2 = 0``, a quartic in x
        (:meth:`curvature_stationary`); :func:`max_curvatures` of many unions at once (the
        same values; one union is faster here).
        """
        xs = [0.0, self.x_end, *self.curvature_stationary()]
        return float(np.max(np.abs(self.curvature(np.array(xs)))))

    def curvature_stationary(self) -> list[float]:
        """Frame abscissae in ``(0, x_end)`` where the rear path's curvature is stationary.

        The real roots of the quartic ``N = f''' (1 + f'^2) - 3 f' f''^2``
        (:func:`curvature_polynomials`; imaginary parts below 1e-9 count as real), in
        numpy's order; none if ``N`` vanishes identically (a straight union). The
        curvature's extrema over any sub-interval lie at its ends or at these points.
        """
        _, c1, c2, c3 = self.coefficients
        crit = _quartic(c1, c2, c3)
        if not np.any(crit != 0):
            return []
        roots = _roots(crit)
        return [r.real for r in roots if abs(r.imag) < 1e-9 and 0.0 < r.real < self.x_end]

    # -- world coordinates ---------------------------------------------------------
    def xs(self, n: int = 101) -> np.ndarray:
        """``n >= 2`` equally spaced frame abscissae over ``[0, x_end]``."""
        if int(n) != n or n < 2:
            raise ValueError(f"n must be an integer >= 2, got {n!r}")
        return np.linspace(0.0, self.x_end, int(n))

    def to_world(self, x, y) -> np.ndarray:
        """Map alpha-frame coordinates to world coordinates, ``(..., 2)``."""
        c, s = math.cos(self.frame_angle), math.sin(self.frame_angle)
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        return np.stack((self.p0.x + c * x - s * y, self.p0.y + s * x + c * y), axis=-1)

    def heading(self, x):
        """World heading of the robot (A->B) at frame abscissa ``x``."""
        return self.frame_angle + np.arctan(self.slope(x))

    def rear(self, n: int = 101) -> np.ndarray:
        """``(n, 2)`` world samples of the rear-axle path A."""
        x = self.xs(n)
        return self.to_world(x, self.f(x))

    def front(self, n: int = 101) -> np.ndarray:
        """``(n, 2)`` world samples of the front-wheel path B = A + L (cos h, sin h)."""
        x = self.xs(n)
        h = self.heading(x)
        return self.to_world(x, self.f(x)) + self.L * np.stack((np.cos(h), np.sin(h)), axis=-1)


#: The scalar slots of a union's :meth:`Union.state`, in order.
_SCALARS = ("alpha", "L", "d", "psi", "phi0", "phi1", "x_end")


def _restore(values: tuple) -> Union:
    """A union holding ``values`` in its slots' order, unchecked (pickle; :meth:`Union.from_state`)."""
    u = object.__new__(Union)
    for name, value in zip(Union.__slots__, values, strict=True):
        object.__setattr__(u, name, value)
    return u
