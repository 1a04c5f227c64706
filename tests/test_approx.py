"""LONGD: [1] against independent oracles, [2] inside its validated domain, the dispatch."""

import functools
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

import segplan
from segplan.fit.formula2 import (
    BAND_LOWER,
    BOUND_MAX,
    BOUND_MEAN,
    DESIGN_MAX,
    FRAME_CAP_DEG,
    calibration_grid,
    run_calibration,
)
from segplan.model.cost import (
    APPROX_DOMAIN,
    BLOCK,
    exact_values,
    in_domain,
    k_alpha,
    longd_approx_intrinsic,
    longd_exact_intrinsic,
    longd_intrinsic,
)
from segplan.studies.approx import (
    error_study,
    exact_split,
    k_basis_comparison,
    k_by_alpha,
    planner_links,
    sample_domain,
    sample_wide,
    term_study,
    variant_comparison,
    variant_domains,
    variant_terms,
)
from segplan.studies.romberg_cost import romberg_work

DEG = math.pi / 180


@functools.cache
def fitted():
    """The fit of k_alpha and the domain of [2], made here (the package reads stored constants)."""
    return run_calibration()


# -- helpers ---------------------------------------------------------------------------
def world_pair(x0, y0, beta, d, phi0, phi1):
    """Poses with chord length d at world angle beta and intrinsic headings phi0, phi1."""
    p0 = (x0, y0, beta + phi0)
    p1 = (x0 + d * math.cos(beta), y0 + d * math.sin(beta), beta + phi1)
    return p0, p1


@st.composite
def cases(draw, phi_max_deg=80.0, frame_cap_deg=85.0):
    """A valid case: poses in the world, alpha inside the feasible interval, L."""
    phi0 = draw(st.floats(-phi_max_deg, phi_max_deg)) * DEG
    phi1 = draw(st.floats(-phi_max_deg, phi_max_deg)) * DEG
    cap = frame_cap_deg * DEG
    lo = max(-math.pi / 2, -cap - min(phi0, phi1, 0.0))
    hi = min(math.pi / 2, cap - max(phi0, phi1, 0.0))
    assume(hi - lo > 0.02)
    alpha = lo + (hi - lo) * draw(st.floats(0.01, 0.99))
    d = draw(st.floats(0.2, 50.0))
    L = draw(st.floats(0.1, 5.0))
    x0, y0 = draw(st.floats(-100, 100)), draw(st.floats(-100, 100))
    beta = draw(st.floats(-math.pi, math.pi))
    p0, p1 = world_pair(x0, y0, beta, d, phi0, phi1)
    return p0, p1, alpha, L


def rigid(p, angle, tx, ty):
    c, s = math.cos(angle), math.sin(angle)
    return (c * p[0] - s * p[1] + tx, s * p[0] + c * p[1] + ty, p[2] + angle)


# -- formula [1] against independent oracles ---------------------------------------------
@settings(max_examples=60)
@given(cases())
def test_longd_exact_agrees_with_quad(case):
    p0, p1, alpha, L = case
    rtol = 1e-8
    u = segplan.Union(p0, p1, alpha, L)

    def integrand(x):  # [1] from the union's own derivatives
        fp, fpp = u.slope(x), u.second_derivative(x)
        w = 1.0 + fp * fp
        return math.sqrt(w + (L * fpp / w) ** 2)

    ref, ref_err = quad(integrand, 0.0, u.x_end, epsabs=0.0, epsrel=1e-13, limit=500)
    got = segplan.longd_exact(p0, p1, alpha, L, rtol=rtol)
    assert abs(got - ref) <= rtol * ref + ref_err


def test_longd_exact_is_the_front_wheel_path_length():
    for p0, p1, alpha, L in [
        ((0, 0, 0.3), (5, 1, -0.2), 0.1, 1.0),
        ((1, 2, 1.2), (-3, 6, 2.9), -0.2, 2.5),
        ((0, 0, 0.9), (2, 0, 0.9), -0.7, 0.5),
    ]:
        front = segplan.Union(p0, p1, alpha, L).front(200_001)
        polyline = np.sum(np.hypot(*np.diff(front, axis=0).T))
        assert segplan.longd_exact(p0, p1, alpha, L) == pytest.approx(polyline, rel=1e-8)


# -- formula [2] inside its validated domain -------------------------------------------
def test_calibration_is_deterministic_and_meets_its_bounds():
    c = fitted()
    again = run_calibration()
    assert again == c
    assert c.domain == APPROX_DOMAIN  # the stored domain is the fitted one
    assert c.max_error <= DESIGN_MAX < BOUND_MAX
    assert c.mean_error <= BOUND_MEAN
    a = np.linspace(0.0, math.pi / 2, 1001, endpoint=False)
    k = k_alpha(a)
    assert np.all((0.0 < k) & (k < 1.0))  # the paper: 0 < k_alpha < 1
    dom = c.domain
    assert any(p > 0 for p in dom.phi_max)
    for a_max, p_max in zip(dom.alpha_max, dom.phi_max, strict=True):
        assert a_max + p_max <= FRAME_CAP_DEG * DEG + 1e-12
    assert list(dom.band_lower) == sorted(dom.band_lower)


def test_error_inside_the_domain_on_a_large_random_sample():
    df = error_study(*sample_domain(60_000, seed=2024))  # not the calibration grid
    assert df["in_domain"].all()
    assert df["abs_error"].max() < BOUND_MAX
    assert df["abs_error"].mean() < BOUND_MEAN


def test_error_at_the_corners_of_every_box():
    dom = APPROX_DOMAIN
    upper = (*dom.band_lower[1:], 1e4)
    rows = []
    for lo, hi, a_max, p_max in zip(dom.band_lower, upper, dom.alpha_max, dom.phi_max, strict=True):
        if p_max <= 0:
            continue
        for dl in (lo, math.sqrt(lo * hi), hi * (1 - 1e-9)):
            for sa in (-1.0, 0.0, 1.0):
                for s0 in (-1.0, 0.0, 1.0):
                    for s1 in (-1.0, 0.0, 1.0):
                        rows.append((dl, s0 * p_max, s1 * p_max, sa * a_max))
    dl, phi0, phi1, alpha = np.array(rows).T
    df = error_study(dl, phi0, phi1, alpha)
    assert df["in_domain"].all()
    assert df["abs_error"].max() < BOUND_MAX


@settings(max_examples=80)
@given(st.integers(0, 2**31 - 1), st.floats(0.1, 5.0), st.floats(-math.pi, math.pi))
def test_public_longd_approx_inside_the_domain(seed, L, beta):
    dl, phi0, phi1, alpha = (float(v[0]) for v in sample_domain(1, seed=seed))
    p0, p1 = world_pair(3.0, -7.0, beta, dl * L, phi0, phi1)
    exact = segplan.longd_exact(p0, p1, alpha, L)
    approx = segplan.longd_approx(p0, p1, alpha, L)
    assert abs(approx / exact - 1.0) < BOUND_MAX
    assert segplan.longd(p0, p1, alpha, L) == approx


def test_in_domain_scalar_and_vector_paths_agree():
    rng = np.random.default_rng(5)
    n = 5000
    d = np.exp(rng.uniform(-1, 4, n))
    L = rng.uniform(0.2, 2, n)
    phi0, phi1, alpha = (rng.uniform(-1, 1, n) for _ in range(3))
    vec = in_domain(d, phi0, phi1, alpha, L)
    sca = [
        in_domain(float(d[i]), float(phi0[i]), float(phi1[i]), float(alpha[i]), float(L[i])) for i in range(n)
    ]
    assert vec.dtype == bool and vec.shape == (n,)
    assert np.array_equal(vec, np.array(sca))
    assert 0 < vec.mean() < 1
    assert isinstance(in_domain(4.0, 0.1, 0.1, 0.1, 1.0), bool)


# -- the dispatch longd ----------------------------------------------------------------
@settings(max_examples=60)
@given(cases(phi_max_deg=75.0, frame_cap_deg=80.0))
def test_longd_is_exact_outside_the_domain(case):
    p0, p1, alpha, L = case
    d, phi0, phi1 = (segplan.model.cost.checked_intrinsic(p0, p1, alpha, L)[i] for i in range(3))
    assume(not in_domain(float(d), float(phi0), float(phi1), alpha, L))
    assert segplan.longd(p0, p1, alpha, L) == segplan.longd_exact(p0, p1, alpha, L)


def test_longd_vectorised_mixes_both_paths():
    wide = sample_wide(3000, seed=11, frame_cap_deg=75.0)
    dom = sample_domain(1000, seed=12)
    dl, phi0, phi1, alpha = (np.concatenate(pair) for pair in zip(wide, dom, strict=True))
    L = 0.7
    rng = np.random.default_rng(3)
    beta = rng.uniform(-math.pi, math.pi, dl.size)
    p0 = np.stack((np.zeros_like(dl), np.ones_like(dl), beta + phi0), axis=-1)
    p1 = np.stack((dl * L * np.cos(beta), 1.0 + dl * L * np.sin(beta), beta + phi1), axis=-1)
    got = segplan.longd(p0, p1, alpha, L)
    inside = in_domain(dl * L, phi0, phi1, alpha, L)
    assert 0.1 < inside.mean() < 0.9
    np.testing.assert_array_equal(got[inside], segplan.longd_approx(p0[inside], p1[inside], alpha[inside], L))
    out = np.flatnonzero(~inside)[::20]
    single = [segplan.longd_exact(p0[i], p1[i], alpha[i], L) for i in out]
    np.testing.assert_allclose(got[out], single, rtol=1e-9)
    assert isinstance(segplan.longd(p0[0], p1[0], alpha[0], L), float)


# -- invariance, vectorisation -----------------------------------------------------------
@settings(max_examples=60)
@given(cases(), st.floats(-math.pi, math.pi), st.floats(-1e3, 1e3), st.floats(-1e3, 1e3))
def test_longd_invariant_under_rigid_motions(case, angle, tx, ty):
    p0, p1, alpha, L = case
    q0, q1 = rigid(p0, angle, tx, ty), rigid(p1, angle, tx, ty)
    for fn in (segplan.longd_exact, segplan.longd_approx):
        assert fn(q0, q1, alpha, L) == pytest.approx(fn(p0, p1, alpha, L), rel=1e-9)
    d0 = segplan.model.cost.checked_intrinsic(p0, p1, alpha, L)
    d1 = segplan.model.cost.checked_intrinsic(q0, q1, alpha, L)
    assume(in_domain(*map(float, d0)) == in_domain(*map(float, d1)))
    assert segplan.longd(q0, q1, alpha, L) == pytest.approx(segplan.longd(p0, p1, alpha, L), rel=1e-9)


def test_vectorised_longd_approx_matches_single_calls_and_keeps_shapes():
    rng = np.random.default_rng(1)
    n = 2 * BLOCK + 1000  # also exercises the blocked path
    dl, phi0, phi1, alpha = sample_wide(n, seed=4, frame_cap_deg=80.0)
    L = rng.uniform(0.3, 2.0, n)
    p0 = np.stack((np.zeros(n), np.zeros(n), phi0), axis=-1)
    p1 = np.stack((dl * L, np.zeros(n), phi1), axis=-1)
    got = segplan.longd_approx(p0, p1, alpha, L)
    np.testing.assert_allclose(got, longd_approx_intrinsic(dl * L, phi0, phi1, alpha, L), rtol=1e-13)
    for i in range(0, n, 2503):
        assert segplan.longd_approx(
            tuple(p0[i]), tuple(p1[i]), float(alpha[i]), float(L[i])
        ) == pytest.approx(got[i], rel=1e-13)
    # shapes: one start against a (2, m) grid of ends, alpha broadcast along the last axis
    m = 5
    ends = p1[: 2 * m].reshape(2, m, 3)
    a = np.full(m, 0.05)
    out = segplan.longd_approx((0.0, 0.0, 0.0), ends, a, 1.0)
    assert out.shape == (2, m)
    assert segplan.longd((0.0, 0.0, 0.0), ends, a, 1.0).shape == (2, m)


def test_intrinsic_layer_is_vectorised_and_scalar():
    d, phi0, phi1, alpha, L = 4.0, 0.2, -0.1, 0.05, 1.0
    s = longd_intrinsic(d, phi0, phi1, alpha, L)
    assert isinstance(s, float)
    v = longd_intrinsic(np.full(3, d), phi0, phi1, np.array([alpha, 1.0, -1.0]), L)
    assert v.shape == (3,) and v[0] == s
    assert v[1] == pytest.approx(longd_exact_intrinsic(d, phi0, phi1, 1.0, L), rel=1e-10)


# -- bad input -----------------------------------------------------------------------------
BAD = [
    ((0, 0, 0), (0, 0, 0.5), 0.0, 1.0, "coincident"),
    ((0, 0, math.nan), (1, 0, 0), 0.0, 1.0, "finite"),
    ((0, 0, 0), (1, math.inf, 0), 0.0, 1.0, "finite"),
    ((0, 0, 0), (1, 0, 0), math.nan, 1.0, "alpha"),
    ((0, 0, 0), (1, 0, 0), math.inf, 1.0, "alpha"),
    ((0, 0, 0), (1, 0, 0), 0.0, 0.0, "L"),
    ((0, 0, 0), (1, 0, 0), 0.0, -2.0, "L"),
    ((0, 0, 0), (1, 0, 0), 0.0, math.nan, "L"),
    ((0, 0, 0), (1, 0, 0), 1.6, 1.0, "alpha"),
    ((0, 0, -0.4), (1, 0, 0), -1.2, 1.0, "alpha"),
    ((0, 0, math.pi), (1, 0, math.pi), 0.0, 1.0, "alpha"),  # goal behind the start
    ((0, 0), (1, 0, 0), 0.0, 1.0, "p0"),
    ((0, 0, 0), "abc", 0.0, 1.0, "p1"),
]


@pytest.mark.parametrize("fn", [segplan.longd_approx, segplan.longd])
@pytest.mark.parametrize(("p0", "p1", "alpha", "L", "word"), BAD)
def test_bad_input_raises_value_error(fn, p0, p1, alpha, L, word):
    with pytest.raises(ValueError, match=word):
        fn(p0, p1, alpha, L)


@pytest.mark.parametrize("fn", [segplan.longd_approx, segplan.longd])
@pytest.mark.parametrize("n", [10, 2 * BLOCK + 7])
def test_bad_entry_in_arrays_raises_value_error(fn, n):
    p0 = np.zeros((n, 3))
    p1 = np.tile([2.0, 0.0, 0.1], (n, 1))
    alpha = np.full(n, 0.1)
    bad_alpha = alpha.copy()
    bad_alpha[n - 3] = 2.0
    with pytest.raises(ValueError, match=f"flat index {n - 3}"):
        fn(p0, p1, bad_alpha, 1.0)
    bad_p1 = p1.copy()
    bad_p1[n // 2, 1] = math.nan
    with pytest.raises(ValueError, match="finite"):
        fn(p0, bad_p1, alpha, 1.0)
    bad_p1 = p1.copy()
    bad_p1[1, :2] = 0.0
    with pytest.raises(ValueError, match="coincident"):
        fn(p0, bad_p1, alpha, 1.0)
    with pytest.raises(ValueError, match="L"):
        fn(p0, p1, alpha, np.where(np.arange(n) == 4, -1.0, 1.0))
    assert np.all(np.isfinite(fn(p0, p1, alpha, 1.0)))


@pytest.mark.parametrize("fn", [segplan.longd_approx, segplan.longd])
def test_large_malformed_arrays_get_the_clear_error(fn):
    """Above 2 BLOCK cases the input is validated block by block; a malformed pose array
    (last axis not 3) must still get the message naming it, not numpy's broadcast error."""
    n = 2 * BLOCK + 7
    with pytest.raises(ValueError, match=rf"p1 must have a last axis of length 3 .* shape \({n}, 2\)"):
        fn(np.zeros((n, 3)), np.ones((n, 2)), np.full(n, 0.1), 1.0)
    with pytest.raises(ValueError, match=r"p0 must have a last axis of length 3"):
        fn(np.zeros((n, 4)), np.ones((n, 3)), np.full(n, 0.1), 1.0)


def test_non_finite_alpha_is_named():
    with pytest.raises(ValueError, match=r"^alpha must be finite \(radians\)$"):
        segplan.longd_exact((0, 0, 0), (1, 0, 0), math.nan, 1.0)
    with pytest.raises(ValueError, match=r"^alpha must be finite \(radians\)$"):
        segplan.longd_approx(np.zeros((3, 3)), np.tile([1.0, 0.0, 0.0], (3, 1)), [0.0, math.inf, 0.0], 1.0)


# -- the studies the book uses ---------------------------------------------------------------
def test_study_tables():
    df = error_study(*sample_wide(500, seed=1))
    assert list(df.columns) == [
        "d_over_L",
        "alpha_deg",
        "phi0_deg",
        "phi1_deg",
        "mbar0",
        "mbar1",
        "exact",
        "approx",
        "rel_error",
        "abs_error",
        "in_domain",
    ]
    assert len(df) == 500 and np.all(np.isfinite(df[["exact", "approx"]].to_numpy()))
    kb = k_by_alpha()
    assert np.all(np.abs(kb["k_bin"] - kb["k_alpha"]) < 0.1)
    comp = k_basis_comparison().set_index("form")
    assert comp.loc["c0 + c1 sin^2(alpha) (used)", "rms_error"] <= 1.01 * comp["rms_error"].min()
    assert comp.loc["constant", "rms_error"] > comp.loc["c0 + c1 sin^2(alpha) (used)", "rms_error"]
    assert len(APPROX_DOMAIN.table()) == len(BAND_LOWER)


def test_variant_comparison_picks_the_derived_terms():
    v = variant_comparison(n_wide=2000).set_index("variant")
    derived = v.loc["exact|cross=-1/2|exp=-5/2"]
    assert derived["max_domain"] < BOUND_MAX
    # the OCR's Simpson first term is clearly worse, and so are the exponents -3/2 and -2
    assert v.loc["simpson|cross=-1/2|exp=-5/2", "mean_domain"] > 2 * derived["mean_domain"]
    assert v.loc["exact|cross=-1/2|exp=-3/2", "max_domain"] > 2 * derived["max_domain"]
    assert v.loc["exact|cross=-1/2|exp=-2", "max_domain"] > derived["max_domain"]


def test_run_calibration_with_the_derived_terms_is_the_calibration():
    g = calibration_grid()
    assert run_calibration(terms=(g["rear"], g["front"])) == fitted()
    args = (g["d_over_L"], np.radians(g["phi0_deg"]), np.radians(g["phi1_deg"]), np.radians(g["alpha_deg"]))
    rear, front = variant_terms("exact|cross=-1/2|exp=-5/2", *args)
    np.testing.assert_allclose(rear, g["rear"], rtol=1e-12)
    np.testing.assert_allclose(front, g["front"], rtol=1e-12)
    with pytest.raises(ValueError, match="name"):
        variant_terms("exact|cross=0|exp=-5/2", *args)


def test_variant_domains_rank_the_ocr_simpson_term_below_the_derived_one():
    v = variant_domains().set_index("variant")
    assert len(v) == 18
    derived, c = v.loc["exact|cross=-1/2|exp=-5/2"], fitted()
    assert derived["n_inside"] == c.n_inside
    assert (derived["k_c0"], derived["k_c1"]) == pytest.approx(c.k_coef, rel=1e-12)
    assert np.all(v["max_error"].dropna() <= DESIGN_MAX)
    assert np.all(v["mean_error"].dropna() <= BOUND_MEAN)
    simpson = v[v["rear"] == "simpson"]
    assert simpson["n_inside"].max() < 0.9 * derived["n_inside"]


def test_exact_split_against_quad():
    rng = np.random.default_rng(11)
    dl, phi0, phi1, alpha = rng.uniform(1, 10, 6), *rng.uniform(-0.6, 0.6, (3, 6))
    longd, rear = exact_split(dl, phi0, phi1, alpha)
    for i in range(dl.size):
        p0, p1 = world_pair(0.0, 0.0, 0.4, dl[i], phi0[i], phi1[i])
        u = segplan.Union(p0, p1, alpha[i], 1.0)
        ref = quad(lambda x, u=u: math.sqrt(1 + u.slope(x) ** 2), 0.0, u.x_end, epsabs=0, epsrel=1e-13)[0]
        assert rear[i] == pytest.approx(ref, rel=1e-9)
        assert longd[i] == pytest.approx(segplan.longd_exact(p0, p1, alpha[i], 1.0), rel=1e-9)
    assert np.all(longd > rear) and np.all(rear >= dl)


def test_term_study_columns_and_ideal_k():
    df = term_study(*sample_domain(400, seed=3))
    assert {"longd", "rear_excess", "front_excess", "k_ideal|exact", "front|cross=-1/2|exp=-5/2"} <= set(df)
    # the binomial rear term overestimates the rear excess: the ideal k lies in (0, 1]
    k = df["k_ideal|exact"].dropna()
    assert np.all((k > 0) & (k < 1 + 1e-6))
    # Simpson overestimates the exact integral (by 3/40 (mbar0 + mbar1)^2): smaller ideal k
    assert np.all(df["k_ideal|simpson"].dropna() <= k + 1e-9)
    np.testing.assert_allclose(df["longd"], df["d_over_L"] * (1 + df["rear_excess"]) + df["front_excess"])


def test_romberg_work_counts_points_and_meets_the_bound_with_four_levels():
    dl, phi0, phi1, alpha = sample_domain(200, seed=4)
    exact = exact_values(dl, phi0, phi1, alpha, 1.0, rtol=1e-12)
    ev, val = romberg_work(dl, phi0, phi1, alpha, rtol=BOUND_MAX)
    assert set(np.unique(ev)) <= {3, 5, 9, 17, 33}
    ev4, val4 = romberg_work(dl, phi0, phi1, alpha, rtol=BOUND_MAX, min_levels=4)
    assert np.all(ev4 >= 17) and np.all(ev4 >= ev)
    assert np.max(np.abs(val4 / exact - 1)) < BOUND_MAX
    ev_t, val_t = romberg_work(dl[:20], phi0[:20], phi1[:20], alpha[:20], rtol=1e-10)
    np.testing.assert_allclose(val_t, exact[:20], rtol=1e-9)


def test_planner_links_records_the_search_link_costs():
    sc = segplan.load_scenario(Path(__file__).parents[1] / "scenarios" / "single_obstacle.json")
    df = planner_links({"one": sc})
    plan = segplan.plan_scenario(sc, planner="paper")
    assert len(df) > 0 and set(df["scenario"]) == {"one"}
    assert df["in_plan"].sum() >= len(plan.unions)
    expected = in_domain(
        df["d_over_L"].to_numpy(), *np.radians(df[["phi0_deg", "phi1_deg", "alpha_deg"]].to_numpy().T), 1.0
    )
    np.testing.assert_array_equal(df["in_domain"].to_numpy(), expected)
    # the observer only watches: the plan is the one plan_scenario returns
    observed = segplan.planning.api.plan_scenario_observed(sc, lambda u, c: None)
    assert observed.cost == plan.cost and observed.nodes == plan.nodes
