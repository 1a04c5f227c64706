"""segplan.viz.plot draws what segplan computes, on the given axes, with units and equal aspect."""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import segplan  # noqa: E402
from segplan.viz import plot  # noqa: E402

P0 = (0.0, 0.0, math.radians(30.0))
P1 = (4.0, 1.0, math.radians(-20.0))


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _lines(ax):
    return {line.get_label(): line for line in ax.lines}


def test_union_paths_are_the_union_samples():
    u = segplan.Union(P0, P1, 0.3, 1.2)
    ax = plot.plot_union(u, n=51, robots=5)
    lines = _lines(ax)
    np.testing.assert_array_equal(lines["rear path A"].get_xydata(), u.rear(51))
    np.testing.assert_array_equal(lines["front-wheel path B"].get_xydata(), u.front(51))
    assert ax.get_xlabel() == "x [m]" and ax.get_ylabel() == "y [m]"
    assert ax.get_aspect() == 1.0
    # three interior robot segments A->B of length L, plus the two end poses
    segments = [line.get_xydata() for line in ax.lines if len(line.get_xydata()) == 2]
    lengths = [np.hypot(*(s[1] - s[0])) for s in segments]
    assert len(lengths) == 5
    np.testing.assert_allclose(lengths, 1.2, rtol=1e-12)


def test_union_on_given_axes_with_label():
    fig, ax = plt.subplots()
    u = segplan.Union(P0, P1, 0.0, 1.0)
    assert plot.plot_union(u, ax, robots=0, ends=False, label="alpha = 0", color="C3") is ax
    labels = [line.get_label() for line in ax.lines]
    assert labels == ["alpha = 0", "_nolegend_"]
    assert ax.lines[0].get_color() == ax.lines[1].get_color()


def test_plan_obstacles_bounds():
    u1 = segplan.Union(P0, P1, 0.3, 1.0)
    u2 = segplan.Union(P1, (8.0, 0.0, 0.0), 0.0, 1.0)
    ax = plot.plot_plan([u1, u2], obstacles=[[(2, 2), (3, 2), (3, 3)]], bounds=(-1, -2, 10, 4), label="plan")
    assert [line.get_label() for line in ax.lines].count("plan") == 1
    assert len(ax.patches) == 2  # the obstacle and the bounds
    x0, x1 = ax.get_xlim()
    assert x0 <= -1 and x1 >= 10


def test_a_plan_has_both_paths_in_the_legend_beside_the_floor():
    """Without a label, a plan's rear path A and its dashed front-wheel path B each get one
    legend entry; legend_beside puts the legend right of the axes, off the floor."""
    u1 = segplan.Union(P0, P1, 0.3, 1.0)
    u2 = segplan.Union(P1, (8.0, 0.0, 0.0), 0.0, 1.0)
    ax = plot.plot_plan([u1, u2], obstacles=[[(2, 2), (3, 2), (3, 3)]], bounds=(-1, -2, 10, 4))
    legend = plot.legend_beside(ax)
    texts = [t.get_text() for t in legend.get_texts()]
    assert texts == ["obstacle", plot.REAR_LABEL, plot.FRONT_LABEL]
    front = _lines(ax)[plot.FRONT_LABEL]
    assert front.get_linestyle() == "--"
    np.testing.assert_array_equal(front.get_xydata(), u1.front(201))
    ax.figure.canvas.draw()
    assert legend.get_window_extent().x0 >= ax.get_window_extent().x1  # outside the axes


def test_floor_of_a_map_has_walls_and_obstacles_only():
    floor = segplan.Floor.from_polygons([[(4, 1), (6, 1), (5, 3)]], (0, 0, 10, 7))
    ax = plot.plot_floor(floor)
    assert [p.get_label() for p in ax.patches][1:] == ["obstacle"] and not ax.lines
    robot0 = segplan.make_scenario(segplan.Robot(1.0), (0.5, 0.5, 0.0), (8.0, 5.0, 0.5), floor)
    ax = plot.plot_floor(robot0)  # no half-width: no enlargement drawn over the obstacles
    assert "enlarged obstacle" not in [p.get_label() for p in ax.patches]


def test_floor_draws_walls_obstacles_and_poses():
    robot = segplan.Robot(1.0, half_width=0.3)
    obstacles = [[(4, 1), (6, 1), (5, 3)], [(2, 4), (3, 4), (3, 5), (2, 5)]]
    sc = segplan.make_scenario(robot, (0.5, 0.5, 0.0), (8.0, 5.0, 0.5), obstacles, (-1, -1, 10, 7))
    ax = plot.plot_floor(sc)
    # the walls, two enlarged obstacles, two obstacles
    assert len(ax.patches) == 5
    labels = [p.get_label() for p in ax.patches]
    assert labels.count("enlarged obstacle") == 1 and labels.count("obstacle") == 1
    enlarged = [p for p in ax.patches if p.get_label() == "enlarged obstacle"][0]
    assert np.allclose(enlarged.get_xy()[:-1], sc.enlarged[0])
    # start and goal: the segment A->B of each
    segments = [line for line in ax.lines if len(line.get_xdata()) == 2]
    ends = {(round(line.get_xdata()[0], 9), round(line.get_ydata()[0], 9)) for line in segments}
    assert ends == {(0.5, 0.5), (8.0, 5.0)}
    assert ax.get_xlabel() == "x [m]" and ax.get_aspect() == 1.0
    ax2 = plot.plot_floor(sc, bounds=False, poses=False)
    assert len(ax2.patches) == 4 and not ax2.lines
    with pytest.raises(ValueError, match="Scenario"):
        plot.plot_floor("fig5.json")


def test_longd_curve_is_formula_1():
    alphas = np.radians(np.linspace(-30.0, 60.0, 7))
    ax = plot.plot_longd(P0, P1, 1.0, alphas=alphas, mark_min=False, chord=False)
    x, y = ax.lines[0].get_xdata(), ax.lines[0].get_ydata()
    np.testing.assert_allclose(x, np.degrees(alphas))
    np.testing.assert_allclose(y, segplan.longd_exact(P0, P1, alphas, 1.0))
    assert ax.get_xlabel() == "alpha [deg]" and ax.get_ylabel() == "LONGD [m]"


def test_longd_default_grid_inside_feasible_interval():
    ax = plot.plot_longd(P0, P1, 1.0, n=21)
    x = np.radians(ax.lines[0].get_xdata())
    geo = segplan.model.pose.intrinsic(P0, P1)
    lo, hi = segplan.model.pose.feasible_alpha_interval(geo.phi0, geo.phi1)
    assert lo < x.min() and x.max() < hi and len(x) == 21


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: plot.plot_union("not a union"), "union"),
        (lambda: plot.plot_union(segplan.Union(P0, P1, 0.0, 1.0), robots=1), "robots"),
        (lambda: plot.plot_union(segplan.Union(P0, P1, 0.0, 1.0), n=1), "n must"),
        (lambda: plot.plot_plan([]), "unions"),
        (lambda: plot.plot_polygons([[(0, 0), (1, 1)]]), "polygons\\[0\\]"),
        (lambda: plot.plot_polygons([[(0, 0), (1, np.nan), (1, 0)]]), "finite"),
        (lambda: plot.plot_bounds((0, 0, -1, 1)), "bounds"),
        (lambda: plot.plot_pose(P0, 0.0), "L"),
        (lambda: plot.plot_longd(P0, P1, 1.0, margin=0.6), "margin"),
        (lambda: plot.plot_longd(P0, (-4.0, 0.0, 0.0), 1.0), "no alpha"),
        (lambda: plot.plot_union(segplan.Union(P0, P1, 0.0, 1.0), ax="axes"), "ax"),
    ],
)
def test_bad_input_raises_value_error(call, match):
    with pytest.raises(ValueError, match=match):
        call()
