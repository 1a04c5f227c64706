"""The shared verdict function: a changed number changes the verdict, the criterion is printed.

Also: the project's targets are "met / not met" and kept apart from the paper's claims; a
"partly" band says where it comes from; a claim judged by several chapters has one criterion.
"""

import math

import pytest

from segplan.studies.verdicts import (
    PAPER_CLAIMS,
    TARGET_WORDS,
    UNDECIDED,
    VERDICTS,
    Criterion,
    PaperClaim,
    Target,
    Verdict,
    claims_table,
    judge,
    judge_claim,
    judge_interval,
    meet,
    tally,
    targets_table,
    worst,
)

MAX_ERR = Criterion("max |error|", "<", 0.025, partly=0.05, fmt="{:.2%}")


@pytest.mark.parametrize(
    ("value", "word"),
    [
        (0.0, "reproduced"),
        (0.0249, "reproduced"),
        (0.025, "partly reproduced"),
        (0.049, "partly reproduced"),
        (0.05, "not reproduced"),
        (1.0, "not reproduced"),
        (math.nan, "not reproduced"),
    ],
)
def test_upper_bound_with_partly_band(value, word):
    assert judge(value, MAX_ERR).word == word


@pytest.mark.parametrize(
    ("value", "word"), [(3.0, "reproduced"), (2.0, "reproduced"), (1.9, "not reproduced")]
)
def test_lower_bound_without_band(value, word):
    assert judge(value, Criterion("share", ">=", 2.0)).word == word


def test_lower_bound_with_band():
    c = Criterion("improvement", ">", 0.0, partly=-0.01, fmt="{:+.2%}")
    assert [judge(v, c).word for v in (0.001, -0.005, -0.02)] == list(VERDICTS)


def test_boolean_check():
    c = Criterion("constraints met to 1e-12", "==", True)
    assert judge(True, c).word == "reproduced"
    assert judge(False, c).word == "not reproduced"
    assert judge(False, c).criterion == "constraints met to 1e-12 equal to True; measured False"


def test_criterion_text_names_quantity_bounds_and_value():
    v = judge(0.0312, MAX_ERR)
    assert v.criterion == "max |error| below 2.50% (partly: below 5.00%, our band); measured 3.12%"
    assert str(v) == "partly reproduced" and v.value == pytest.approx(0.0312)


def test_worst_of_several():
    v = worst([judge(0.01, MAX_ERR), judge(0.03, MAX_ERR)])
    assert v.word == "partly reproduced"
    assert v.criterion.count("measured") == 2
    with pytest.raises(ValueError, match="verdicts"):
        worst([])


@pytest.mark.parametrize(
    "kwargs",
    [
        dict(op="~"),
        dict(threshold=math.inf),
        dict(partly=0.01),
        dict(op="==", partly=0.05),
        dict(quantity=""),
    ],
)
def test_bad_criteria_are_refused(kwargs):
    base = dict(quantity="q", op="<", threshold=0.025, partly=None)
    with pytest.raises(ValueError):
        Criterion(**(base | kwargs))


def test_bad_inputs_are_refused():
    with pytest.raises(ValueError, match="criterion"):
        judge(0.1, "< 2.5 %")
    with pytest.raises(ValueError, match="value"):
        judge("low", MAX_ERR)


def test_claims_table_columns_and_numbering():
    rows = [dict(claim="c", paper="p", ours="o", verdict=judge(0.01, MAX_ERR), why="w")]
    t = claims_table(rows)
    assert list(t.columns) == ["claim", "paper", "ours", "criterion", "verdict", "why"]
    assert list(t.index) == [1] and t.loc[1, "verdict"] == "reproduced"
    with pytest.raises(ValueError, match="Verdict"):
        claims_table([dict(claim="c", paper="p", ours="o", verdict="reproduced", why="w")])
    with pytest.raises(ValueError, match="misses"):
        claims_table([dict(claim="c")])
    assert isinstance(judge(1, Criterion("n", ">", 0)), Verdict)


def test_timing_criterion_hides_the_varying_value_but_judges_it():
    c = Criterion("heuristic time / one scalar [2]", "<=", 0.1, partly=1.0, fmt="{:.1f}", varies=True)
    fast, slow = judge(0.05, c), judge(5.3, c)
    assert (fast.word, slow.word) == ("reproduced", "not reproduced")
    assert fast.criterion == slow.criterion and "5.3" not in slow.criterion


# -- where a band comes from -----------------------------------------------------------------
def test_band_anchored_in_the_papers_words_says_so():
    c = Criterion("share within 3 iterates", ">=", 0.9, partly=0.5, fmt="{:.0%}", band_from="'normally'")
    assert (
        c.text() == "share within 3 iterates at least 90% (partly: at least 50%, from the paper's 'normally')"
    )
    assert "our band" in MAX_ERR.text() and "our band" not in Criterion("q", "<", 1.0).text()


@pytest.mark.parametrize("kwargs", [dict(band_from="'most'"), dict(partly=0.05, band_from=" ")])
def test_band_origin_without_a_band_or_empty_is_refused(kwargs):
    with pytest.raises(ValueError, match="band_from"):
        Criterion("q", "<", 0.025, **kwargs)


# -- targets: met / not met, apart from the claims ----------------------------------------------
def test_targets_are_met_or_not_never_reproduced():
    t = Target("lines of user code", "<", 20)
    assert [judge(v, t).word for v in (12, 20, math.nan)] == ["met", "not met", "not met"]
    assert meet(12, t).kind == "target" and judge(12, Criterion("n", "<", 20)).kind == "claim"
    assert meet(12, t).criterion == "lines of user code below 20; measured 12"
    assert set(TARGET_WORDS).isdisjoint(VERDICTS)
    with pytest.raises(ValueError, match="partly"):
        Target("q", "<", 1.0, partly=2.0)
    with pytest.raises(ValueError, match="Target"):
        meet(12, Criterion("n", "<", 20))


def test_worst_of_targets_and_no_mixing():
    t = Target("ms", "<", 100.0)
    assert worst([meet(50, t), meet(150, t)]).word == "not met"
    assert worst([meet(50, t), meet(60, t)]).kind == "target"
    with pytest.raises(ValueError, match="mix"):
        worst([meet(50, t), judge(0.01, MAX_ERR)])


def test_claims_and_targets_tables_refuse_each_other():
    claim = dict(claim="c", paper="p", ours="o", verdict=judge(0.01, MAX_ERR), why="w")
    target = dict(target="t", ours="o", verdict=meet(3, Target("n", "<", 20)), why="w")
    tt = targets_table([target])
    assert list(tt.columns) == ["target", "ours", "criterion", "verdict", "why"]
    assert tt.loc[1, "verdict"] == "met"
    with pytest.raises(ValueError, match="targets_table"):
        claims_table([claim, target | dict(claim="t", paper="p")])
    with pytest.raises(ValueError, match="claims_table"):
        targets_table([claim | dict(target="c")])


def test_tally_counts_claims_and_targets_apart():
    claims = claims_table(
        [
            dict(claim="c", paper="p", ours="o", verdict=judge(v, MAX_ERR), why="w")
            for v in (0.01, 0.03, 0.1, 0.2)
        ]
    )
    assert tally(claims) == "4 claims of the paper: 1 reproduced, 1 partly reproduced, 2 not reproduced"
    targets = targets_table([dict(target="t", ours="o", verdict=meet(3, Target("n", "<", 20)), why="w")])
    assert tally(targets) == "1 target of ours: 1 met"
    with pytest.raises(ValueError, match="claims_table"):
        tally([1, 2])


# -- a value known within an interval ----------------------------------------------------------
@pytest.mark.parametrize(
    ("low", "high", "word"),
    [
        (1.01, 1.08, "reproduced"),
        (1.05, 1.20, UNDECIDED),
        (1.19, 1.40, "not reproduced"),
        (1.10, 1.10, "reproduced"),
        (math.nan, 1.0, "not reproduced"),
    ],
)
def test_interval_is_judged_on_both_ends(low, high, word):
    c = Criterion("plan over the optimum", "<=", 1.10, fmt="{:.3f}")
    v = judge_interval(low, high, c)
    assert v.word == word
    if not math.isnan(low):
        assert v.criterion.endswith(f"measured between {low:.3f} and {high:.3f}")


def test_interval_with_band_and_refusals():
    c = Criterion("q", ">=", 2.0, partly=1.0)
    assert judge_interval(1.2, 1.8, c).word == "partly reproduced"
    assert judge_interval(1.5, 2.5, c).word == UNDECIDED
    assert judge_interval(1.5, 2.5, c).value == 1.5  # the pessimistic end of a lower bound
    assert worst([judge_interval(1.5, 2.5, c), judge(1.5, c)]).word == UNDECIDED
    assert worst([judge_interval(1.5, 2.5, c), judge(0.5, c)]).word == "not reproduced"
    with pytest.raises(ValueError, match="low"):
        judge_interval(2.0, 1.0, c)
    with pytest.raises(ValueError, match="op"):
        judge_interval(0, 1, Criterion("b", "==", True))
    with pytest.raises(ValueError, match="criterion"):
        judge_interval(0, 1, Target("t", "<", 2))


# -- one criterion per paper claim ---------------------------------------------------------------
def test_registry_holds_the_papers_words_and_one_criterion_per_claim():
    assert {"on-line", "near-optimal", "improves-on-distance", "search-quicker"} <= set(PAPER_CLAIMS)
    for key, claim in PAPER_CLAIMS.items():
        assert isinstance(claim, PaperClaim) and claim.words and claim.why, key
        for c in claim.criteria:
            assert not isinstance(c, Target), key
            # a band is anchored in the paper's words, or there is none
            assert c.partly is None or c.band_from is not None, key
    with pytest.raises(TypeError):
        PAPER_CLAIMS["new"] = PAPER_CLAIMS["on-line"]


def test_on_line_is_judged_on_the_slowest_plan():
    (c,) = PAPER_CLAIMS["on-line"].criteria
    assert "slowest" in c.quantity and c.varies
    assert judge_claim("on-line", 0.3).word == "reproduced"
    assert judge_claim("on-line", 1.3).word == "not reproduced"


def test_judge_claim_takes_one_value_per_criterion():
    assert judge_claim("search-quicker", 0.5, 0.8).word == "reproduced"
    assert judge_claim("search-quicker", 0.5, 1.09).word == "not reproduced"
    assert judge_claim("search-quicker", 0.5, 0.93).word == "reproduced"  # 'quicker': no margin
    assert judge_claim("search-quicker", 0.5, 1.0).word == "not reproduced"
    assert judge_claim("search-quicker", 1.0, 0.8).word == "not reproduced"
    assert judge_claim("formula2-cheaper", 11.9, 9.4).word == "reproduced"
    assert judge_claim("formula2-saving-size", 11.9, 9.4).word == "not reproduced"
    with pytest.raises(ValueError, match="one per criterion"):
        judge_claim("search-quicker", 0.5)
    with pytest.raises(ValueError, match="key"):
        judge_claim("no such claim", 1.0)
    with pytest.raises(ValueError, match="criteria"):
        PaperClaim("w", "s", (Target("t", "<", 1),), "why")


def test_a_claim_applied_to_one_case_keeps_its_thresholds():
    claim = PAPER_CLAIMS["search-quicker"]
    at = claim.at("forward worlds")
    assert [c.quantity for c in at] == [f"{c.quantity}, forward worlds" for c in claim.criteria]
    assert [(c.op, c.threshold, c.partly, c.varies) for c in at] == [
        (c.op, c.threshold, c.partly, c.varies) for c in claim.criteria
    ]
    v = judge_claim("search-quicker", 0.5, 0.8, where="forward worlds")
    assert v.criterion.count("forward worlds") == 2
    with pytest.raises(ValueError, match="where"):
        claim.at(" ")
