"""segplan.viz.progress.ProgressLine: what it writes, plain and as a bar."""

from __future__ import annotations

import io

import pytest

from segplan.planning.context import Progress
from segplan.viz.progress import ProgressLine


def test_plain_lines_one_per_stage_and_a_running_search_at_most_every_so_often():
    out = io.StringIO()
    show = ProgressLine(out, every=0.5, bar=False)
    events = [
        Progress("lattice", "start", 0.0, 10.0),
        Progress("lattice", "expanded", 0.1, 10.0, 64),  # within 0.5 s of the last line: skipped
        Progress("lattice", "expanded", 0.7, 10.0, 128),
        Progress("lattice", "expanded", 0.9, 10.0, 192),  # skipped
        Progress("lattice", "done", 1.0, 10.0, 200, 12.5),
        Progress("refine", "done", 1.2, 10.0, 0, None),
    ]
    for e in events:
        show(e)
    show.close()
    assert out.getvalue().splitlines() == [
        "segplan:   0.00 s of 10  lattice: started",
        "segplan:   0.70 s of 10  lattice: 128 expansions",
        "segplan:   1.00 s of 10  lattice: done (LONGD 12.500 m, 200 expansions)",
        "segplan:   1.20 s of 10  refine: done (no plan)",
    ]


def test_a_bar_where_asked_and_bad_input():
    pytest.importorskip("tqdm")
    out = io.StringIO()
    show = ProgressLine(out, bar=True)
    show(Progress("paper", "start", 0.0, 2.0))
    show(Progress("lattice", "expanded", 1.0, 2.0, 64))
    show.close()
    text = out.getvalue()
    assert "of the time limit" in text and "lattice expanded, 64 expanded" in text
    assert ProgressLine(io.StringIO()).use_bar is False  # not a terminal: plain lines
    with pytest.raises(ValueError, match="every must be"):
        ProgressLine(out, every=0)
