"""segplan.viz.animate: frames by the path's length, the robot's body, the legend off the floor."""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import segplan  # noqa: E402
from segplan.viz import animate  # noqa: E402
from segplan.viz.plot import FRONT_LABEL, REAR_LABEL  # noqa: E402

# these tests look at an animation's frames without writing it out
pytestmark = pytest.mark.filterwarnings("ignore:Animation was deleted without rendering:UserWarning")


def _straight(length: float, n: int = 201) -> np.ndarray:
    """Poses along the x axis, heading 0, over ``length`` metres."""
    return np.column_stack((np.linspace(0.0, length, n), np.zeros(n), np.zeros(n)))


def _frames(anim) -> int:
    return len(list(anim.new_frame_seq()))


def test_frame_count_follows_the_length_within_its_bounds():
    L = 1.2
    step = animate.FRAME_STEP * L
    assert animate.frame_count(40 * step, L) == 41  # one frame per step, both ends
    assert animate.frame_count(80 * step, L) == 81  # twice the path, twice the frames
    assert animate.frame_count(0.0, L) == animate.MIN_FRAMES
    assert animate.frame_count(1e4, L) == animate.MAX_FRAMES
    assert animate.frame_count(40 * step, 2 * L) == animate.MIN_FRAMES  # in robot lengths
    assert _frames(animate.animate_path(_straight(40 * step), L)) == 41
    assert _frames(animate.animate_path(_straight(40 * step), L, frames=7)) == 7


def test_the_body_is_the_segment_widened_by_half_width():
    """Each vertex of the drawn body lies half_width from the segment A->B of its frame."""
    sc = segplan.load_scenario("single_obstacle")
    plan = segplan.plan_scenario(sc)
    anim = animate.animate_plan(plan, sc, frames=5)
    poses = segplan.plan_poses(plan)
    idx = animate._frame_indices(poses, sc.L, 5)
    hw = sc.robot.half_width
    for k in (0, 3):
        body = anim._func(k)[2]  # the frame's artists: rear, front, body, segment, wheel
        x, y, th = poses[idx[k]]
        a = np.array([x, y])
        u = np.array([math.cos(th), math.sin(th)])
        v = body.get_xy() - a
        t = np.clip(v @ u, 0.0, sc.L)
        dist = np.hypot(*(v - t[:, None] * u).T)
        np.testing.assert_allclose(dist, hw, rtol=1e-9)
        assert (v @ u).min() == pytest.approx(-hw)  # the round ends, behind A and before B
        assert (v @ u).max() == pytest.approx(sc.L + hw)
    assert body.get_visible() and f"half-width {hw:g} m" in body.get_label()
    bare = animate.animate_path(poses, sc.L, frames=2)  # no scenario: the segment alone
    assert not bare._func(0)[2].get_visible()


def test_the_legend_names_both_paths_beside_the_floor():
    sc = segplan.load_scenario("single_obstacle")
    anim = animate.animate_plan(segplan.plan_scenario(sc), sc, frames=2)
    fig = anim._fig
    ax = fig.axes[0]
    legend = ax.get_legend()
    texts = [t.get_text() for t in legend.get_texts()]
    assert REAR_LABEL in texts and FRONT_LABEL in texts
    fig.canvas.draw()
    assert legend.get_window_extent().x0 >= ax.get_window_extent().x1  # off the floor
    assert legend.get_window_extent().x1 <= fig.bbox.x1  # and inside the frame


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"frames": 1}, "frames must be an integer >= 2"),
        ({"frames": 2.0}, "frames must be an integer"),
        ({"fps": 0}, "fps must be an integer from 1 to 50"),
        ({"dpi": 1000}, "dpi must lie from 20 to 300"),
        ({"half_width": -0.1}, "half_width"),
    ],
)
def test_bad_options_raise_value_error(kwargs, match):
    with pytest.raises(ValueError, match=match):
        animate.animate_path(_straight(3.0), 1.0, **kwargs)


def test_a_reverse_plan_backs_up_pauses_at_its_cusp_and_says_so():
    """Issue 26: the dead-end bay's plan in driving order; CUSP_FRAMES more frames standing at
    the cusp; the reversing stretch of the rear path in its own legend entry."""
    sc = segplan.load_scenario("dead_end_bay")
    plan = segplan.plan_scenario(sc)
    poses, directions = segplan.viz.metrics.plan_pose_directions(plan)
    assert np.array_equal(poses, segplan.plan_poses(plan)) and len(plan.cusps) == 1
    anim = animate.animate_plan(plan, sc, frames=20)
    assert _frames(anim) == 20 + animate.CUSP_FRAMES
    cusp = np.flatnonzero(directions[:-1] != directions[1:])[0]
    node = plan.nodes[plan.cusps[0]]
    assert np.allclose(poses[cusp, :2], (node.x, node.y))
    standing = [
        k for k in range(_frames(anim)) if np.allclose(anim._func(k)[3].get_xydata()[0], poses[cusp, :2])
    ]
    assert len(standing) >= animate.CUSP_FRAMES  # the cusp's frames, consecutive
    assert standing == list(range(standing[0], standing[0] + len(standing)))
    rear, reversing = anim._func(_frames(anim) - 1)[0], anim._func(_frames(anim) - 1)[5]
    back = np.isfinite(reversing.get_xydata()[:, 0])
    ahead = np.isfinite(rear.get_xydata()[:, 0])
    assert back.any() and ahead.any() and (back | ahead).all()
    assert np.allclose(reversing.get_xydata()[back][0], (sc.start.x, sc.start.y))  # it backs out first
    texts = [t.get_text() for t in anim._fig.axes[0].get_legend().get_texts()]
    assert animate.REVERSE_LABEL in texts
    forward = animate.animate_plan(
        segplan.plan_scenario(segplan.load_scenario("single_obstacle")), sc, frames=3
    )
    assert animate.REVERSE_LABEL not in [t.get_text() for t in forward._fig.axes[0].get_legend().get_texts()]
    with pytest.raises(ValueError, match="directions"):
        animate.animate_path(_straight(3.0), 1.0, directions=[1, 2])
