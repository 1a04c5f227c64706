"""The fitted constants: stored data equal to a refit, pinned to golden values (issue 15).

Three guards, each catching what the others cannot:

* the refit (:func:`segplan.fit.store.compute`) equals the data file, so the stored
  constants cannot drift from the fitting code;
* the stored constants are pinned to literal values, so a change in the fitting code (or
  in formula [2], which the fit would absorb into ``k_alpha`` and the domain) that is
  then written with ``python -m segplan.fit`` fails here;
* formula [2] is pinned to values computed by hand, so a consistent error in all the code
  paths of [2] (which the error-bound tests do not see after a refit) fails here.
"""

import math

import numpy as np
import pytest

import segplan
from segplan.fit import store
from segplan.fit.store import (
    FRAME_ATOL,
    RTOL,
    compute,
    compute_primitives,
    differences,
    frame_check_grid,
    frame_difference,
    main,
)
from segplan.model import constants
from segplan.model.cost import APPROX_DOMAIN, K_COEF, S2_CAP, k_alpha, longd_approx_intrinsic
from segplan.model.frame import heuristic_alpha, heuristic_coefficients
from segplan.model.pose import intrinsic

DEG = math.pi / 180.0


# -- the stored data equal a refit (fixture refit: conftest) ---------------------------
def test_refit_equals_the_stored_constants(refit):
    # tolerances (segplan.fit.store): RTOL = 1e-9 relative on every number but the case-b
    # coefficients, which are compared by the frames they give (FRAME_ATOL radians); integers
    # and lists exactly. On any processor: tests/test_processors.py runs this under others.
    assert RTOL == 1e-9 and FRAME_ATOL == 1e-6
    assert differences(refit, constants.load()) == []


def test_the_case_b_fit_is_compared_by_its_frames():
    stored = constants.load()
    coef = np.array(stored["heuristic_frame"]["coef"])

    def with_coef(c):
        return {**stored, "heuristic_frame": {**stored["heuristic_frame"], "coef": [float(v) for v in c]}}

    # a change of one coefficient by 1e-7 relative (what another processor's rounding does
    # through the fit's condition number 2.4e6) moves the frames by far less than FRAME_ATOL
    nudged = coef.copy()
    nudged[30] *= 1 + 1e-7
    assert frame_difference(with_coef(nudged)["heuristic_frame"], stored["heuristic_frame"]) < 1e-8
    assert differences(with_coef(nudged), stored) == []
    # a change that moves the frames is reported, with the size of the move
    moved = coef.copy()
    moved[0] += 1e-3
    out = differences(with_coef(moved), stored)
    assert len(out) == 1 and out[0].startswith("/heuristic_frame/coef: frames differ by up to ")
    assert frame_difference(with_coef(moved)["heuristic_frame"], stored["heuristic_frame"]) > FRAME_ATOL
    # a different number of coefficients is a different fit
    assert differences(with_coef(coef[:-1]), stored) == [
        "/heuristic_frame/coef: 33 coefficients != stored 34"
    ]
    # the other entries of the fit are still compared to RTOL
    rms = {
        **stored,
        "heuristic_frame": {**stored["heuristic_frame"], "rms_z": stored["heuristic_frame"]["rms_z"] * 1.01},
    }
    assert [line.split(":")[0] for line in differences(rms, stored)] == ["/heuristic_frame/rms_z"]


def test_the_frame_check_grid_covers_the_fitted_box():
    p0, p1, dl = frame_check_grid()
    assert len(p0) == 73200 and np.all(p1 <= p0)
    assert (
        np.degrees(p0.max()) == pytest.approx(80.0)
        and dl.min() == pytest.approx(0.25)
        and dl.max() == pytest.approx(100.0)
    )


def test_differences_sees_a_change(refit):
    changed = {**refit, "formula2": {**refit["formula2"], "k_coef": [K_COEF[0] * (1 + 1e-6), K_COEF[1]]}}
    assert differences(changed, constants.load()) == [
        f"/formula2/k_coef[0]: {K_COEF[0] * (1 + 1e-6)!r} != stored {K_COEF[0]!r}"
    ]


def test_check_command_passes_on_the_stored_file(capsys, monkeypatch, refit, recomputed):
    # the fits main() would compute are the session's (the same deterministic functions,
    # each compared with the stored data above and in test_primitives_data): not twice
    assert store.compute is compute and store.compute_primitives is compute_primitives
    monkeypatch.setattr(store, "compute", lambda: refit)
    monkeypatch.setattr(store, "compute_primitives", lambda: recomputed)
    assert main(["--check"]) == 0
    out = capsys.readouterr().out
    assert "matches the fits" in out and "matches the computed primitives" in out


def test_provenance_is_recorded():
    prov = constants.load()["provenance"]
    assert prov["command"] == "python -m segplan.fit"
    assert {"date", "package_version", "numpy", "python"} <= set(prov)
    grid = constants.formula2()["grid"]
    assert grid["alpha_deg"][-1] == 45 and grid["seed"] is None


# -- golden constants ------------------------------------------------------------------
def test_k_alpha_coefficients_are_the_golden_ones():
    assert K_COEF == pytest.approx((0.9068557738624596, -1.4481414659366536), rel=1e-9)
    assert S2_CAP == pytest.approx(0.5, rel=1e-15)  # sin^2(45 deg)
    assert k_alpha(0.0) == pytest.approx(0.9068557738624596, rel=1e-9)
    assert k_alpha(math.pi / 3) == pytest.approx(0.9068557738624596 - 0.5 * 1.4481414659366536, rel=1e-9)


def test_domain_of_formula2_is_the_golden_one():
    # per band of d/L from 1, 1.5, 2, 3, 4, 6, 10: |alpha| max and |phi_i| max, degrees
    assert APPROX_DOMAIN.band_lower == (1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 10.0)
    assert np.degrees(APPROX_DOMAIN.alpha_max) == pytest.approx([45, 35, 45, 45, 40, 15, 20], abs=1e-9)
    assert np.degrees(APPROX_DOMAIN.phi_max) == pytest.approx([5, 10, 10, 15, 20, 45, 45], abs=1e-9)
    err = constants.formula2()["errors"]
    assert err["n_inside"] == 13626 and err["n_grid"] == 84656 and err["iterations"] == 5
    assert err["max_error"] == pytest.approx(0.022006412261325964, rel=1e-6)
    assert err["mean_error"] == pytest.approx(0.002519862661567503, rel=1e-6)


def test_heuristic_frame_coefficients_are_the_golden_ones():
    fit = heuristic_coefficients()
    assert fit.degree == 5 and fit.coef.size == 34 and fit.n_problems == 396
    assert fit.phi_max == pytest.approx(80 * DEG, rel=1e-15)
    assert fit.log_ratio_range == pytest.approx((math.log(0.25), math.log(100.0)), rel=1e-15)
    assert fit.coef[:4] == pytest.approx(
        [-0.2640874606439932, 0.7627398473044291, -0.7383788109762309, -0.10997331711363084], rel=1e-7
    )
    assert float(np.sum(fit.coef**2)) == pytest.approx(362.15619492630225, rel=1e-7)
    assert fit.rms_z == pytest.approx(0.008401329139899381, rel=1e-6)
    # the frames it gives (case b, case a with the case-b candidate, a short link)
    for (d, p0, p1), alpha in (
        ((3.0, 0.5, 0.2), -0.6050983050396598),
        ((1.5, 0.9, 0.1), -0.9696386690964298),
        ((10.0, -0.3, -0.6), 0.9792040277439932),
        ((2.0, 0.6, -0.1), -0.6732828001495526),
        ((0.5, 0.2, 0.2), -1.2540963399744707),
    ):
        assert heuristic_alpha(d, p0, p1, 1.0) == pytest.approx(alpha, rel=1e-8)


# -- formula [2] against hand-computed values ------------------------------------------
def plain_formula2(p0, p1, alpha, L, k):
    """The paper's [2] written out with ``math`` alone (no segplan), intrinsic frame by hand."""
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    d, psi = math.hypot(dx, dy), math.atan2(dy, dx)
    m0 = math.tan(p0[2] - psi + alpha) - math.tan(alpha)
    m1 = math.tan(p1[2] - psi + alpha) - math.tan(alpha)
    q1 = m0 * m0 + m1 * m1 - m0 * m1 / 2
    q2 = m0 * m0 + m1 * m1 + m0 * m1
    c = math.cos(alpha)
    return d * (1 + k * c * c * q1 / 15) + 2 * L * L / (d * c) * (1 / (c * c) + 2 * q1 / 15) ** -2.5 * q2


#: (p0, p1, alpha, L), [2] with the golden k_alpha, [2] with k = 0.5. The values were
#: computed once with :func:`plain_formula2` (Python floats; k_alpha = 0.9068557738624596
#: - 1.4481414659366536 min(sin^2 alpha, 1/2)) and typed in.
HAND = (
    (((0, 0, 0.3), (4, 1, -0.2), 0.1, 1.0), 4.261642274949354, 4.237369045300364),
    (((1, 2, 0.5), (7, 3, 0.4), -0.2, 0.8), 6.172848942523703, 6.155039211669462),
    (((0, 0, -0.4), (3, -2, -0.9), 0.3, 1.2), 3.6887395726397245, 3.677181786647691),
    (((0, 0, 0.2), (10, 0, 0.6), 0.0, 1.0), 10.378246379521807, 10.258957939435085),
)
GOLDEN_C0, GOLDEN_C1 = 0.9068557738624596, -1.4481414659366536


@pytest.mark.parametrize(("case", "with_k", "with_half"), HAND)
def test_formula2_equals_hand_computed_values(case, with_k, with_half):
    p0, p1, alpha, L = case
    k = GOLDEN_C0 + GOLDEN_C1 * min(math.sin(alpha) ** 2, 0.5)
    assert plain_formula2(p0, p1, alpha, L, k) == pytest.approx(with_k, rel=1e-13)  # the typed values
    assert plain_formula2(p0, p1, alpha, L, 0.5) == pytest.approx(with_half, rel=1e-13)
    # segplan's [2]: public (scalar and array), intrinsic with the stored or a given k
    assert segplan.longd_approx(p0, p1, alpha, L) == pytest.approx(with_k, rel=1e-12)
    many = segplan.longd_approx(np.array([p0, p0], float), np.array([p1, p1], float), alpha, L)
    np.testing.assert_allclose(many, with_k, rtol=1e-12)
    g = intrinsic(p0, p1)
    assert longd_approx_intrinsic(g.d, g.phi0, g.phi1, alpha, L, k=0.5) == pytest.approx(with_half, rel=1e-12)
    arr = longd_approx_intrinsic(np.array([g.d]), g.phi0, g.phi1, alpha, L, k=0.5)
    np.testing.assert_allclose(arr, with_half, rtol=1e-12)
