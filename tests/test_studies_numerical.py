"""Numerical study helpers behind chapters 2-4 (issue 13), against independent checks."""

import math

import numpy as np
import pytest

from segplan.model.cost import K_COEF, k_from_coef
from segplan.studies.approx import (
    k_uncapped_limit,
    sample_domain,
    variant_calibration,
    variant_error_study,
)
from segplan.studies.frames import case_a_boundary, paper_case_a_excess
from segplan.studies.romberg_cost import matched_cost_ratios, romberg_matched, romberg_work

DEG = math.pi / 180.0
PRINTED = "simpson|cross=1/2|exp=-5/2"


def test_k_uncapped_limit_is_where_the_uncapped_form_reaches_zero():
    a = k_uncapped_limit(K_COEF)
    c0, c1 = K_COEF
    assert c0 + c1 * math.sin(a) ** 2 == pytest.approx(0.0, abs=1e-12)
    assert 45 * DEG < a < 60 * DEG
    # the stored, capped k_alpha stays positive there and beyond
    assert k_from_coef(K_COEF, np.radians([a, 80.0])).min() > 0
    assert k_uncapped_limit((0.5, 0.1)) == pytest.approx(math.pi / 2)  # never leaves (0, 1)
    with pytest.raises(ValueError, match="coef"):
        k_uncapped_limit((1.5, -0.1))


def test_romberg_matched_keeps_the_loosest_tolerance_that_meets_the_error():
    cases = sample_domain(60, seed=5)
    out = romberg_matched(*cases, max_error=1e-3)
    assert out["max_error"] <= 1e-3
    looser = [t for t in out["tried"] if t[0] > out["rtol"]]
    assert all(err > 1e-3 for _, _, err in looser)  # every looser tolerance failed
    evals, _ = romberg_work(*cases, rtol=out["rtol"], min_levels=1)
    assert out["mean_evaluations"] == pytest.approx(evals.mean())
    assert math.isnan(romberg_matched(*cases, max_error=1e-300, rtols=(1e-2,))["rtol"])
    with pytest.raises(ValueError, match="max_error"):
        romberg_matched(*cases, max_error=0.0)


def test_printed_formula_calibrated_on_its_own_meets_the_bound_off_the_grid():
    cal = variant_calibration(PRINTED)
    assert 0 < cal.k_coef[0] < 1 and cal.max_error <= 0.0225
    chk = variant_error_study(PRINTED, *sample_domain(3000, seed=9, domain=cal.domain), calibration=cal)
    assert chk["in_domain"].all()
    assert chk["abs_error"].max() < 0.025


def test_case_a_boundary_brackets_the_failure():
    big, dl = 45.0 * DEG, 3.0
    b = case_a_boundary([big], [dl], iterations=8)
    row = b[b["side"] == "phi1 small"].iloc[0]
    t = row["threshold_deg"] * DEG
    step = big / 2**8
    assert 5 * DEG < t < 20 * DEG
    assert paper_case_a_excess(dl, big, -(t - 1.5 * step)) > 1e-8  # below: fails
    assert paper_case_a_excess(dl, big, -(t + 0.5 * step)) <= 1e-8  # above: exact
    with pytest.raises(ValueError, match="opposite"):
        paper_case_a_excess(dl, 0.3, 0.2)


def test_matched_cost_ratios_are_the_evaluation_count_over_the_approximations_cost():
    cases = sample_domain(40, seed=3)
    matched = romberg_matched(*cases, max_error=1e-3) | {"cases": cases}
    out = matched_cost_ratios(matched, n_scalar=20, n_vector=2000, repeats=1)
    assert set(out) == {
        "approx_evaluations",
        "evaluation_ratio",
        "romberg_us",
        "approx_us",
        "time_ratio_scalar",
    }
    assert out["evaluation_ratio"] == pytest.approx(matched["mean_evaluations"] / out["approx_evaluations"])
    assert out["time_ratio_scalar"] == pytest.approx(out["romberg_us"] / out["approx_us"])
    assert all(v > 0 and math.isfinite(v) for v in out.values())
    with pytest.raises(ValueError, match="matched"):
        matched_cost_ratios(matched | {"rtol": math.nan})
    with pytest.raises(ValueError, match="repeats"):
        matched_cost_ratios(matched, repeats=0)
