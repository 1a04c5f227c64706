"""segplan.studies.model: free space of the segment model against the enclosing circle."""

from pathlib import Path

import pytest

import segplan
from segplan.studies.model import free_space_comparison

SCENARIOS = Path(__file__).resolve().parent.parent / "scenarios"


def test_narrow_passage_doorway_closed_to_the_circle_open_to_the_segment():
    floor = segplan.load_scenario(SCENARIOS / "narrow_passage.json")
    fs = free_space_comparison(floor)
    doorway = [
        (a, b, w) for (a, b, w) in fs["passages"] if a.startswith("obstacle") and b.startswith("obstacle")
    ]
    assert len(doorway) == 1 and doorway[0][2] == pytest.approx(1.2)  # 4.6 - 3.4 in the file
    assert fs["R"] == pytest.approx(0.5 * 1.2 + 0.35)
    assert fs["circle_free"] < fs["segment_free"] < fs["floor_free"]


def test_empty_room_areas_by_hand():
    floor = segplan.make_scenario(segplan.Robot(1.0, 0.25), (1, 1, 0), (8, 4, 0), bounds=(0, 0, 10, 5))
    fs = free_space_comparison(floor)
    assert fs["floor_free"] == pytest.approx(50.0)
    assert fs["segment_free"] == pytest.approx(9.5 * 4.5)
    assert fs["circle_free"] == pytest.approx(8.5 * 3.5)  # R = 0.75
    assert fs["passages"] == []


def test_unbounded_floor_is_refused():
    floor = segplan.make_scenario(segplan.Robot(1.0), (0, 0, 0), (5, 0, 0))
    with pytest.raises(ValueError, match="bounds"):
        free_space_comparison(floor)
