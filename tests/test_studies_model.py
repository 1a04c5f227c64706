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


def test_wasted_space_in_an_empty_room_is_the_walls_against_the_caps():
    import math

    import numpy as np

    from segplan.studies.model import wasted_space

    # empty room: a pose is lost only where a cap crosses a wall while the rectangle does not
    floor = segplan.make_scenario(segplan.Robot(1.0, 0.25), (1, 1, 0), (8, 4, 0), bounds=(0, 0, 10, 5))
    ws = wasted_space(floor, n=4000, seed=1)
    assert 0 < ws["sacrificed"] < 0.2
    assert ws["rear"] + ws["front"] == pytest.approx(1.0)
    assert 0.3 < ws["rear"] < 0.7  # the two caps are alike when poses are drawn in any heading
    assert ws["front_passed_anyway"] == pytest.approx(1.0)  # the front cap is swept by moving forward by w
    assert ws["forward_relevant"] == pytest.approx(ws["sacrificed"] * ws["rear"])
    assert ws["model_area_wasted"] == pytest.approx(math.pi * 0.25**2 / (2 * 0.25 + math.pi * 0.25**2))
    assert ws == wasted_space(floor, n=4000, seed=1)  # deterministic
    with pytest.raises(ValueError, match="half_width"):
        wasted_space(segplan.make_scenario(segplan.Robot(1.0), (1, 1, 0), (8, 4, 0), bounds=(0, 0, 10, 5)))
    with pytest.raises(ValueError, match="n must"):
        wasted_space(floor, n=0)
    assert np.isfinite(ws["sacrificed"])
