"""The shared verdict function: a changed number changes the verdict, the criterion is printed."""

import math

import pytest

from segplan.studies.verdicts import VERDICTS, Criterion, Verdict, claims_table, judge, worst

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
    assert v.criterion == "max |error| below 2.50% (partly: below 5.00%); measured 3.12%"
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
