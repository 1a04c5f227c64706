"""Study helpers for the book's chapters on formula [2] (chapters 2 and 3).

Section "Approximate computation of cost function": a "statistical study of errors" of
the closed approximation [2] against the exact LONGD [1] (Romberg integration). These
helpers draw the cases (:func:`sample_domain`, :func:`sample_wide`), measure [2] case by
case (:func:`error_study`), compare forms of ``k_alpha`` (:func:`k_by_alpha`,
:func:`k_basis_comparison`) and the OCR-literal variants of [2]
(:func:`variant_comparison`, :func:`variant_terms`, :func:`variant_domains`), split the
exact cost into its terms (:func:`exact_split`, :func:`term_study`) and record the links
the planner evaluates (:func:`planner_links`); Romberg's work at the same error is
:mod:`segplan.studies.romberg_cost`.
They use the stored constants of [2] (:data:`segplan.model.cost.K_COEF`,
:data:`segplan.model.cost.APPROX_DOMAIN`) and the fitting procedures of
:mod:`segplan.fit.formula2`; nothing here is part of the stable API.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from ..fit.formula2 import ALPHA_GRID_DEG, calibration_grid, fit_k, grid_inside, k_basis, run_calibration
from ..model.cost import (
    APPROX_DOMAIN,
    K_COEF,
    Domain,
    exact_values,
    k_from_coef,
    longd_approx_intrinsic,
)
from ..model.union import chord_slopes

__all__ = [
    "error_study",
    "exact_split",
    "k_basis_comparison",
    "k_by_alpha",
    "k_uncapped_limit",
    "planner_links",
    "sample_domain",
    "sample_wide",
    "term_study",
    "variant_comparison",
    "variant_calibration",
    "variant_domains",
    "variant_error_study",
    "variant_terms",
]


def sample_domain(n: int, seed: int = 0, domain: Domain | None = None, d_over_L_max: float = 100.0):
    """``n`` cases drawn uniformly inside the domain (deterministic).

    ``d / L`` is log-uniform over the non-empty bands (the last band up to
    ``d_over_L_max``); alpha and the headings are uniform in the band's box.

    Returns
    -------
    d_over_L, phi0, phi1, alpha : ndarray
        Radians; ``L = 1``.
    """
    dom = APPROX_DOMAIN if domain is None else domain
    rng = np.random.default_rng(seed)
    lower = np.asarray(dom.band_lower)
    upper = np.append(lower[1:], d_over_L_max)
    live = np.asarray(dom.phi_max) > 0
    lo, hi = np.log(lower[live]), np.log(upper[live])
    widths = hi - lo
    band = rng.choice(widths.size, size=n, p=widths / widths.sum())
    dl = np.exp(lo[band] + widths[band] * rng.random(n))
    a_max = np.asarray(dom.alpha_max)[live][band]
    p_max = np.asarray(dom.phi_max)[live][band]
    alpha = a_max * rng.uniform(-1.0, 1.0, n)
    phi0 = p_max * rng.uniform(-1.0, 1.0, n)
    phi1 = p_max * rng.uniform(-1.0, 1.0, n)
    return dl, phi0, phi1, alpha


def sample_wide(
    n: int,
    seed: int = 0,
    alpha_max_deg: float = 60.0,
    phi_max_deg: float = 75.0,
    d_over_L: tuple[float, float] = (1.0, 20.0),
    frame_cap_deg: float = 80.0,
):
    """``n`` cases drawn uniformly over a wide range (deterministic, rejection sampling).

    Alpha and the headings are uniform, ``d / L`` log-uniform; cases with a frame heading
    ``|phi_i + alpha|`` above ``frame_cap_deg`` (near-vertical end slopes, where the cubic
    barely exists) are redrawn.

    Returns
    -------
    d_over_L, phi0, phi1, alpha : ndarray
        Radians; ``L = 1``.
    """
    rng = np.random.default_rng(seed)
    cap = math.radians(frame_cap_deg)
    parts, have = [], 0
    while have < n:
        m = 2 * (n - have) + 16
        alpha = math.radians(alpha_max_deg) * rng.uniform(-1.0, 1.0, m)
        phi0 = math.radians(phi_max_deg) * rng.uniform(-1.0, 1.0, m)
        phi1 = math.radians(phi_max_deg) * rng.uniform(-1.0, 1.0, m)
        dl = np.exp(rng.uniform(math.log(d_over_L[0]), math.log(d_over_L[1]), m))
        ok = (np.abs(phi0 + alpha) <= cap) & (np.abs(phi1 + alpha) <= cap)
        parts.append(np.stack((dl, phi0, phi1, alpha))[:, ok])
        have += int(ok.sum())
    dl, phi0, phi1, alpha = np.concatenate(parts, axis=1)[:, :n]
    return dl, phi0, phi1, alpha


def _error_table(dl, phi0, phi1, alpha, exact, approx, domain):
    """One row per union: its parameters, end slopes, [1], [2] and the relative error of [2]."""
    import pandas as pd

    m0, m1 = chord_slopes(phi0, phi1, alpha)
    rel = approx / exact - 1.0
    return pd.DataFrame(
        {
            "d_over_L": dl,
            "alpha_deg": np.degrees(alpha),
            "phi0_deg": np.degrees(phi0),
            "phi1_deg": np.degrees(phi1),
            "mbar0": m0,
            "mbar1": m1,
            "exact": exact,
            "approx": approx,
            "rel_error": rel,
            "abs_error": np.abs(rel),
            "in_domain": domain.contains(dl, phi0, phi1, alpha, 1.0),
        }
    )


def error_study(d_over_L, phi0, phi1, alpha, k=None):
    """Exact [1] against [2] case by case, as a pandas DataFrame.

    Parameters
    ----------
    d_over_L, phi0, phi1, alpha : array_like
        Cases with ``L = 1`` (radians), e.g. from :func:`sample_wide` or
        :func:`sample_domain`.
    k : float or ndarray, optional
        ``k_alpha``; the fitted one by default.

    Returns
    -------
    pandas.DataFrame
        Columns ``d_over_L, alpha_deg, phi0_deg, phi1_deg, mbar0, mbar1, exact, approx,
        rel_error`` (signed, ``approx / exact - 1``), ``abs_error`` and ``in_domain``.
    """

    dl, phi0, phi1, alpha = (
        np.ravel(v).astype(float) for v in np.broadcast_arrays(d_over_L, phi0, phi1, alpha)
    )
    exact = exact_values(dl, phi0, phi1, alpha, 1.0)
    approx = longd_approx_intrinsic(dl, phi0, phi1, alpha, 1.0, k=k)
    return _error_table(dl, phi0, phi1, alpha, exact, approx, APPROX_DOMAIN)


def k_by_alpha():
    """``k`` fitted separately on each grid value of ``|alpha|`` (inside the domain) vs the smooth fit.

    Returns
    -------
    pandas.DataFrame
        Columns ``alpha_deg, n, k_bin, k_alpha``.
    """
    import pandas as pd

    g = calibration_grid()
    inside = grid_inside(g, APPROX_DOMAIN)
    d, alpha = g["d_over_L"], np.radians(g["alpha_deg"])
    rows = []
    for a in ALPHA_GRID_DEG:
        m = inside & (g["alpha_deg"] == a)
        if not np.any(m):
            continue
        k_bin = fit_k(d[m], alpha[m], g["exact"][m], g["rear"][m], g["front"][m], basis=_const_basis)[0]
        rows.append((a, int(m.sum()), float(k_bin), float(k_from_coef(K_COEF, math.radians(a)))))
    return pd.DataFrame(rows, columns=["alpha_deg", "n", "k_bin", "k_alpha"])


def _const_basis(alpha):
    return np.ones((np.size(alpha), 1))


def k_basis_comparison():
    """Error of [2] inside the domain (calibration grid) for several forms of ``k(alpha)``.

    Each form is fitted by least squares on the same points. Returns a DataFrame with
    columns ``form, parameters, mean_abs_error, rms_error, max_abs_error``.
    """
    import pandas as pd

    g = calibration_grid()
    inside = grid_inside(g, APPROX_DOMAIN)
    d, alpha = g["d_over_L"][inside], np.radians(g["alpha_deg"][inside])
    exact, rear, front = g["exact"][inside], g["rear"][inside], g["front"][inside]
    forms = {
        "constant": _const_basis,
        "c cos^2(alpha)": lambda a: (np.cos(a) ** 2)[:, None],
        "c0 + c1 sin^2(alpha) (used)": k_basis,
        "c0 + c1 sin^2 + c2 sin^4": lambda a: np.stack(
            (np.ones_like(a), np.sin(a) ** 2, np.sin(a) ** 4), axis=-1
        ),
        "one k per grid alpha": lambda a: (
            np.round(np.degrees(a))[:, None] == np.asarray(ALPHA_GRID_DEG)
        ).astype(float),
    }
    rows = []
    for name, basis in forms.items():
        coef = fit_k(d, alpha, exact, rear, front, basis=basis)
        err = np.abs((d * (1.0 + (basis(alpha) @ coef) * rear) + front - exact) / exact)
        rows.append((name, coef.size, err.mean(), np.sqrt(np.mean(err**2)), err.max()))
    return pd.DataFrame(rows, columns=["form", "parameters", "mean_abs_error", "rms_error", "max_abs_error"])


def variant_comparison(n_wide: int = 20000, seed: int = 0):
    """Formula [2] against its OCR-literal alternatives, each with its own fitted ``k(alpha)``.

    Every variant of :func:`segplan.model.derivation.variants` is evaluated (lambdified sympy
    expression) on the calibration grid; ``k(alpha)`` (same two-parameter form) is fitted
    for each variant inside the domain of the derived [2], and the errors are measured
    there and over a wide sample (:func:`sample_wide`).

    Returns
    -------
    pandas.DataFrame
        One row per variant: ``variant, rear, cross, exponent, k_c0, k_c1, mean_domain,
        max_domain, mean_wide, p95_wide``, sorted by ``mean_domain``.
    """
    import pandas as pd

    from ..model import derivation

    g = calibration_grid()
    inside = grid_inside(g, APPROX_DOMAIN)
    gd, ga = g["d_over_L"][inside], np.radians(g["alpha_deg"][inside])
    gp0, gp1, ge = np.radians(g["phi0_deg"][inside]), np.radians(g["phi1_deg"][inside]), g["exact"][inside]
    wd, wp0, wp1, wa = sample_wide(n_wide, seed)
    we = exact_values(wd, wp0, wp1, wa, 1.0)
    rows = []
    for name in derivation.variants():
        f = derivation.lambdified(name)

        def split(dl, p0, p1, a, f=f):
            m0, m1 = chord_slopes(p0, p1, a)
            base = f(dl, a, m0, m1, 1.0, 0.0)  # k = 0: d + front
            return base, f(dl, a, m0, m1, 1.0, 1.0) - base  # and d * rear

        base, dr = split(gd, gp0, gp1, ga)
        coef = fit_k(gd, ga, ge, dr / gd, base - gd)
        err_d = np.abs((base + k_from_coef(coef, ga) * dr - ge) / ge)
        wbase, wdr = split(wd, wp0, wp1, wa)
        err_w = np.abs((wbase + k_from_coef(coef, wa) * wdr - we) / we)
        rear, cross, exponent = (part.split("=")[-1] for part in name.split("|"))
        rows.append(
            (
                name,
                rear,
                cross,
                exponent,
                *coef,
                err_d.mean(),
                err_d.max(),
                err_w.mean(),
                np.quantile(err_w, 0.95),
            )
        )
    cols = [
        "variant",
        "rear",
        "cross",
        "exponent",
        "k_c0",
        "k_c1",
        "mean_domain",
        "max_domain",
        "mean_wide",
        "p95_wide",
    ]
    return pd.DataFrame(rows, columns=cols).sort_values("mean_domain", ignore_index=True)


def _parse_variant(name: str) -> tuple[str, str, str]:
    """``"rule|cross=c|exp=e"`` -> ``(rule, c, e)``."""
    rule, cross, exponent = (part.split("=")[-1] for part in name.split("|"))
    return rule, cross, exponent


def variant_terms(name: str, d_over_L, phi0, phi1, alpha):
    """The rear excess (before ``k``) and the front excess of a variant of [2] (``L = 1``).

    ``name`` is a key of :func:`segplan.model.derivation.variants`; the variant reads
    ``LONGD ~ d (1 + k rear) + front``.
    """
    from ..model import derivation

    if name not in derivation.variants():
        raise ValueError(f"name must be a variant of segplan.model.derivation.variants(), got {name!r}")
    rule, cross, exponent = _parse_variant(name)
    m0, m1 = chord_slopes(phi0, phi1, alpha)
    rear = derivation.rear_lambdified(rule)(alpha, m0, m1)
    front = derivation.front_lambdified(cross, exponent)(d_over_L, alpha, m0, m1, 1.0)
    return np.broadcast_to(rear, np.shape(front)), front


def variant_domains():
    """Each variant of [2] calibrated on its own: ``k(alpha)`` and the domain where the bounds hold.

    :func:`variant_comparison` measures every variant inside the domain fitted for the
    derived [2], which favours it. Here each variant of
    :func:`segplan.model.derivation.variants` goes through the whole calibration
    (:func:`run_calibration` with the variant's terms), so each gets the largest domain
    where *its* errors meet the paper's bounds on the grid; a larger domain is a better
    formula.

    Returns
    -------
    pandas.DataFrame
        One row per variant: ``variant, rear, cross, exponent, k_c0, k_c1, n_inside,
        share_inside`` (of the grid points), ``max_error, mean_error`` (inside its domain),
        sorted by ``n_inside`` (largest first).
    """
    import pandas as pd

    from ..model import derivation

    g = calibration_grid()
    args = (g["d_over_L"], np.radians(g["phi0_deg"]), np.radians(g["phi1_deg"]), np.radians(g["alpha_deg"]))
    rows = []
    for name in derivation.variants():
        try:
            c = run_calibration(terms=variant_terms(name, *args))
            row = (*c.k_coef, c.n_inside, c.n_inside / c.n_grid, c.max_error, c.mean_error)
        except RuntimeError:  # no domain at all
            row = (math.nan, math.nan, 0, 0.0, math.nan, math.nan)
        rows.append((name, *_parse_variant(name), *row))
    cols = ["variant", "rear", "cross", "exponent", "k_c0", "k_c1", "n_inside", "share_inside"]
    cols += ["max_error", "mean_error"]
    df = pd.DataFrame(rows, columns=cols)
    return df.sort_values(["n_inside", "mean_error"], ascending=[False, True], ignore_index=True)


def exact_split(d_over_L, phi0, phi1, alpha, rtol: float = 1e-10):
    """Exact LONGD [1] and the exact rear-path length of many cases (``L = 1``).

    The rear length is [1] with ``L = 0`` (``int sqrt(1 + f'^2) dx``); LONGD minus it is
    the front-wheel excess that the last term of [2] approximates, and ``rear / d - 1``
    is the rear excess that ``k_alpha`` times the first term approximates.

    Returns
    -------
    longd, rear_length : ndarray
    """
    longd = exact_values(d_over_L, phi0, phi1, alpha, 1.0, rtol=rtol)
    rear = exact_values(d_over_L, phi0, phi1, alpha, 0.0, rtol=rtol)
    return longd, rear


def term_study(
    d_over_L,
    phi0,
    phi1,
    alpha,
    rules=("exact", "simpson", "second_order"),
    fronts=(("-1/2", "-5/2"), ("1/2", "-5/2")),
):
    """Each term of [2] against its exact counterpart, case by case, with no ``k`` fitted.

    Parameters
    ----------
    d_over_L, phi0, phi1, alpha : array_like
        Cases with ``L = 1`` (radians).
    rules : sequence of str
        Rear rules (:func:`segplan.model.derivation.rear_term`).
    fronts : sequence of (cross, exponent)
        Front terms (:func:`segplan.model.derivation.front_term`), rationals as strings.

    Returns
    -------
    pandas.DataFrame
        Columns ``d_over_L, alpha_deg, phi0_deg, phi1_deg, longd, rear_excess`` (exact
        ``rear length / d - 1``), ``front_excess`` (exact ``LONGD - rear length``); for
        each rule ``k_ideal|<rule>`` (the ``k`` that would make the first term exact:
        ``rear_excess / term``); for each front term ``front|cross=<c>|exp=<e>`` (its
        value).
    """
    import pandas as pd

    from ..model import derivation

    dl, p0, p1, a = (np.ravel(v).astype(float) for v in np.broadcast_arrays(d_over_L, phi0, phi1, alpha))
    longd, rear = exact_split(dl, p0, p1, a)
    m0, m1 = chord_slopes(p0, p1, a)
    out = {
        "d_over_L": dl,
        "alpha_deg": np.degrees(a),
        "phi0_deg": np.degrees(p0),
        "phi1_deg": np.degrees(p1),
        "longd": longd,
        "rear_excess": rear / dl - 1.0,
        "front_excess": longd - rear,
    }
    with np.errstate(divide="ignore", invalid="ignore"):  # a zero term (straight union) gives nan
        for rule in rules:
            out[f"k_ideal|{rule}"] = out["rear_excess"] / derivation.rear_lambdified(rule)(a, m0, m1)
    for cross, exponent in fronts:
        out[f"front|cross={cross}|exp={exponent}"] = derivation.front_lambdified(cross, exponent)(
            dl, a, m0, m1, 1.0
        )
    return pd.DataFrame(out)


def planner_links(scenarios, **options):
    """Every LONGD evaluation the planner makes while solving ``scenarios``, recorded.

    Each scenario is planned with the paper's search (``options`` passed on);
    meanwhile every call of the planner's link cost (:class:`segplan.planning.links.LinkModel`, seen through
    :func:`segplan.planning.api.plan_scenario_observed`; which uses
    [2] inside the domain and [1] outside: :func:`segplan.model.cost.longd`) is recorded, for
    links (``g``) and heuristic estimates (``h'`` (a)) alike. The unions are the ones the
    search builds: in their optimal reference system
    (:func:`segplan.optimal_alpha_intrinsic`), or the steering fallback's frame.
    Instrumentation only: the planner runs unchanged.

    Parameters
    ----------
    scenarios : dict of str to Scenario
        Named scenarios.

    Returns
    -------
    pandas.DataFrame
        One row per evaluation: ``scenario, d_over_L, phi0_deg, phi1_deg, alpha_deg,
        in_plan`` (the union belongs to the plan found) and ``in_domain``. Scenarios
        without a plan (:class:`segplan.NoPathError`) contribute their evaluations with
        ``in_plan`` False.
    """
    import pandas as pd

    from ..planning.api import plan_scenario_observed
    from ..planning.plan import NoPathError

    record = []
    rows = []
    for name, scenario in scenarios.items():
        record.clear()
        try:
            plan = plan_scenario_observed(scenario, lambda u, _cost: record.append(u), **options)
            unions = {id(u) for u in plan.unions}
        except NoPathError:
            unions = set()
        rows += [(name, u.d / u.L, u.phi0, u.phi1, u.alpha, id(u) in unions) for u in record]
    cols = ["scenario", "d_over_L", "phi0", "phi1", "alpha", "in_plan"]
    df = pd.DataFrame(rows, columns=cols)
    dl, p0, p1, a = (df[c].to_numpy(dtype=float) for c in ("d_over_L", "phi0", "phi1", "alpha"))
    df["in_domain"] = np.asarray(APPROX_DOMAIN.contains(dl, p0, p1, a, 1.0), dtype=bool)
    for col in ("phi0", "phi1", "alpha"):
        df[col] = np.degrees(df[col])
    return df.rename(columns={"phi0": "phi0_deg", "phi1": "phi1_deg", "alpha": "alpha_deg"})


def k_uncapped_limit(coef=K_COEF) -> float:
    """Largest ``|alpha|`` (radians) up to which ``c0 + c1 sin^2(alpha)`` stays in (0, 1) uncapped.

    The stored ``k_alpha`` holds ``sin^2`` at its 45 deg value beyond the calibration grid
    (:data:`segplan.model.cost.S2_CAP`); without that cap the fitted form leaves (0, 1) where it
    crosses 0 (``c1 < 0``) or 1 (``c1 > 0``). Returns ``pi / 2`` when it never does.

    Raises
    ------
    ValueError
        If ``c0`` itself is not in (0, 1).
    """
    c0, c1 = (float(v) for v in coef)
    if not 0.0 < c0 < 1.0:
        raise ValueError(f"coef[0] must lie in (0, 1), got {c0}")
    edge = 0.0 if c1 < 0 else 1.0
    s2 = (edge - c0) / c1 if c1 != 0 else math.inf
    return math.asin(math.sqrt(s2)) if 0.0 < s2 < 1.0 else 0.5 * math.pi


def variant_calibration(name: str):
    """A variant of [2] calibrated on its own (:func:`run_calibration` with its terms).

    ``name`` is a key of :func:`segplan.model.derivation.variants`, e.g. the scan read literally,
    ``"simpson|cross=1/2|exp=-5/2"``. Returns the :class:`segplan.fit.formula2.Calibration`.
    """
    return _variant_calibration(name)


@functools.cache
def _variant_calibration(name):
    g = calibration_grid()
    args = (g["d_over_L"], np.radians(g["phi0_deg"]), np.radians(g["phi1_deg"]), np.radians(g["alpha_deg"]))
    return run_calibration(terms=variant_terms(name, *args))


def variant_error_study(name: str, d_over_L, phi0, phi1, alpha, calibration=None):
    """:func:`error_study` for a variant of [2], with its own ``k(alpha)`` and domain.

    Returns the same columns as :func:`error_study`; ``in_domain`` is the variant's own
    domain (``calibration.domain``, by default :func:`variant_calibration`).
    """

    cal = variant_calibration(name) if calibration is None else calibration
    dl, p0, p1, a = (np.ravel(v).astype(float) for v in np.broadcast_arrays(d_over_L, phi0, phi1, alpha))
    rear, front = variant_terms(name, dl, p0, p1, a)
    exact = exact_values(dl, p0, p1, a, 1.0)
    approx = dl * (1.0 + k_from_coef(cal.k_coef, a) * rear) + front
    return _error_table(dl, p0, p1, a, exact, approx, cal.domain)
