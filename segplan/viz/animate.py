"""The robot in motion: an animation of the robot driving a plan.

Section "Mobile robot modelling" of Campoy et al. (1989): the robot is the oriented
segment from A (middle of the rear axle) to B (middle of the front wheel), of length
``L``; its body is the set of points within ``half_width`` of that segment (the
"curved rectangle" of Fig. 2 as the planner models it), or beyond the paper the robot's
footprint (:meth:`segplan.Robot.footprint`: overhangs, a rectangle); a plan is a chain of unions whose
cost, formula [1], is the length of B's path. :func:`animate_plan` shows exactly that: at
each frame the body, the segment A->B at its pose on the plan, the trace of A (rear,
solid) and of B (front wheel, dashed) behind it, over the floor (obstacles, their
enlargement by the robot's half-width, the walls, start and goal), with the legend beside
the floor.

Frames are equally spaced in the *front wheel's* arc length, the paper's cost: the robot
moves at constant front-wheel speed, as the cost assumes (traversal time). By default
their number follows the path's length (:func:`frame_count`), so a long plan is not a
few jumps and a short one is not a slow crawl. A plan that reverses (beyond the paper,
issue 26) is driven in driving order, the robot backing up along its reverse links: frames
by the travelled length, :data:`CUSP_FRAMES` more at each cusp (the robot stands to change
direction), the rear trace of the reversing stretches in its own colour, named in the legend.

Outputs, both offline: :func:`to_html` (matplotlib's ``to_jshtml``: PNG frames and a
small player in one HTML string, no network) and :func:`save_gif` (Pillow, installed with
matplotlib). Like :mod:`segplan.viz.plot`, this module draws with matplotlib (the algorithms
do not), imported when an animation is made: its settings (:data:`FPS`, :func:`frame_count`,
:func:`check_animation`) load without it, so the command line checks them before planning
and starts as fast without an animation.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..floor.geometry import finite_number
from ..floor.scenario import Robot
from ..model.pose import check_length
from .metrics import plan_pose_directions

if TYPE_CHECKING:
    from matplotlib.animation import FuncAnimation

__all__ = [
    "CUSP_FRAMES",
    "DPI",
    "DPI_RANGE",
    "FIGSIZE",
    "FPS",
    "FRAME_STEP",
    "MAX_FPS",
    "MAX_FRAMES",
    "MIN_FRAMES",
    "animate_path",
    "body_label",
    "animate_plan",
    "check_animation",
    "frame_count",
    "save_gif",
    "to_html",
]

#: Size of a frame in inches and its resolution: 6.4 x 4 in at 100 dpi is 640 x 400 pixels,
#: wide enough for the floor beside its legend, and the text (10 pt) 14 pixels high.
FIGSIZE = (6.4, 4.0)
DPI = 100
#: Resolutions accepted: below 20 dpi the text is 3 pixels high; at 300 dpi a frame is 1920
#: pixels wide, and the GIF writer (matplotlib's PillowWriter) keeps every frame in memory,
#: 3 bytes a pixel, until it writes the file: 200 frames take 1.4 GB there.
DPI_RANGE = (20, 300)
#: Frames per second when played (a frame every 100 ms).
FPS = 10
#: Highest rate accepted: a GIF stores each frame's delay in hundredths of a second, and
#: browsers play a delay under 20 ms as 100 ms, so a faster GIF would play slower.
MAX_FPS = 50
#: Front-wheel travel between frames by default, in robot lengths ``L``: consecutive bodies
#: overlap by three quarters, so the eye follows one robot moving rather than a robot
#: jumping; at :data:`FPS` that is 2.5 robot lengths a second (3 m/s for the book's 1.2 m
#: robot).
FRAME_STEP = 0.25
#: Fewest frames by default: a short plan still plays 2.4 s at :data:`FPS`, long enough to
#: follow.
MIN_FRAMES = 24
#: Most frames by default: 20 s at :data:`FPS`. It bounds the time to draw (each frame is
#: drawn in full) and the file's size for a long plan on a large map; beyond it the frames
#: are spaced more widely.
MAX_FRAMES = 200
#: Frames added at each cusp of a reversing path, the robot standing there: 0.2 s at
#: :data:`FPS`, seen as a pause, not a stall. Set by hand (issue 26); not measured.
CUSP_FRAMES = 2
#: Legend label and colour of the rear path where the robot reverses.
REVERSE_LABEL = "rear path A, reversing"
REVERSE_COLOR = "tab:purple"


def _whole(value, name: str, low: int, high: int | None = None) -> int:
    """An integer within ``[low, high]``, else ValueError naming ``name``."""
    if (
        isinstance(value, bool)
        or not isinstance(value, int | np.integer)
        or value < low
        or (high is not None and value > high)
    ):
        within = f">= {low}" if high is None else f"from {low} to {high}"
        raise ValueError(f"{name} must be an integer {within}, got {value!r}")
    return int(value)


def check_animation(frames: int | None, fps: int, dpi: float, *, prefix: str = "") -> tuple:
    """Validate an animation's ``frames`` (None: by the path's length, else >= 2), ``fps``
    (1 to :data:`MAX_FPS`) and ``dpi`` (within :data:`DPI_RANGE`); returns them.

    ``prefix`` goes before each name in the messages (the command line's ``"--"``).

    Raises
    ------
    ValueError
        One line naming the value that is out of range.
    """
    if frames is not None:
        frames = _whole(frames, prefix + "frames", 2)
    fps = _whole(fps, prefix + "fps", 1, MAX_FPS)
    dpi = finite_number(dpi, prefix + "dpi")
    if not DPI_RANGE[0] <= dpi <= DPI_RANGE[1]:
        raise ValueError(f"{prefix}dpi must lie from {DPI_RANGE[0]} to {DPI_RANGE[1]}, got {dpi:g}")
    return frames, fps, dpi


def frame_count(front_length: float, L: float) -> int:
    """The default number of frames of a path whose front wheel travels ``front_length`` (m):
    one frame every :data:`FRAME_STEP` robot lengths ``L``, the first and last included,
    within :data:`MIN_FRAMES` and :data:`MAX_FRAMES`."""
    steps = math.ceil(finite_number(front_length, "front_length", 0.0) / (FRAME_STEP * check_length(L)))
    return min(max(steps + 1, MIN_FRAMES), MAX_FRAMES)


def _front_arc_length(poses: np.ndarray, L: float) -> np.ndarray:
    """Arc length of the front wheel B at each pose, from 0 at the first."""
    B = poses[:, :2] + L * np.column_stack((np.cos(poses[:, 2]), np.sin(poses[:, 2])))
    return np.r_[0.0, np.cumsum(np.hypot(*np.diff(B, axis=0).T))]


def _frame_indices(poses: np.ndarray, L: float, frames: int) -> np.ndarray:
    """Indices of ``frames`` poses equally spaced in front-wheel arc length (first and last kept)."""
    s = _front_arc_length(poses, L)
    targets = np.linspace(0.0, s[-1], frames)
    idx = np.searchsorted(s, targets, side="left").clip(0, len(poses) - 1)
    idx[-1] = len(poses) - 1
    return idx


def _trace(A: np.ndarray, steps: np.ndarray) -> np.ndarray:
    """The points ``A`` at either end of the ``steps`` (``steps[j]``: from point ``j`` to
    ``j + 1``), the others ``nan`` (a gap in the line drawn); ``A`` itself when every step is."""
    if steps.all():
        return A
    kept = np.r_[steps, False] | np.r_[False, steps]
    return np.where(kept[:, None], A, np.nan)


def body_label(robot: Robot) -> str:
    """Legend label of the robot's body: its half-width, and its overhangs and shape if set."""
    text = f"robot, half-width {robot.half_width:g} m"
    if robot.front_overhang or robot.rear_overhang:
        text += f", overhangs {robot.front_overhang:g} m front, {robot.rear_overhang:g} m rear"
    return text + (" (rectangle)" if robot.rectangle else "")


def animate_path(
    poses,
    L: float,
    scenario=None,
    *,
    half_width: float | None = None,
    frames: int | None = None,
    fps: int = FPS,
    dpi: float = DPI,
    figsize: tuple[float, float] = FIGSIZE,
    title: str | None = None,
    directions=None,
) -> FuncAnimation:
    """An animation of the robot following ``poses``.

    Parameters
    ----------
    poses : array_like, shape (n, 3)
        Dense rear-axle poses ``(x, y, theta)`` along the path (A and the heading of A->B,
        radians), e.g. :func:`segplan.viz.metrics.plan_poses` of a plan, or an OMPL path.
    L : float
        Length of the segment A->B (m).
    scenario : segplan.Scenario, optional
        The floor drawn underneath (obstacles, their enlargement, walls, start and goal).
    half_width : float, optional
        The body's half-width (m). Default: the scenario's robot's, 0 (the segment alone)
        without a scenario. The body drawn is the robot's footprint
        (:meth:`segplan.Robot.footprint`: the scenario's robot, its overhangs and shape, with
        this half-width; the points within it of A->B without a scenario).
    frames : int, optional
        Number of frames (>= 2), equally spaced in front-wheel arc length; default
        :func:`frame_count` of the path's front-wheel length.
    fps : int
        Frames per second when played (1 to :data:`MAX_FPS`).
    dpi : float
        Pixels per inch of a frame (within :data:`DPI_RANGE`); a frame is ``figsize``
        times ``dpi`` pixels (640 x 400 by default).
    figsize : (width, height)
        Size of a frame in inches.
    title : str, optional
    directions : array_like of int, shape (n,), optional
        ``1`` or ``-1`` per pose, the direction of the motion that reaches it
        (:func:`segplan.viz.metrics.plan_pose_directions`); default all forwards. Each cusp
        (a pose whose direction differs from the next one's) gets :data:`CUSP_FRAMES` more
        frames, and the reversing stretches of the rear path their own colour and legend entry.

    Returns
    -------
    matplotlib.animation.FuncAnimation
        Its figure is closed (not shown by notebooks); use :func:`to_html` or
        :func:`save_gif`.

    Raises
    ------
    ValueError
        Malformed ``poses``, ``L``, ``half_width`` or ``directions``, or ``frames``, ``fps``,
        ``dpi`` out of range (:func:`check_animation`).
    """
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation
    from matplotlib.patches import Polygon as PolygonPatch

    from .plot import FRONT_LABEL, REAR_LABEL, legend_beside, plot_floor, plot_pose

    P = np.asarray(poses, dtype=float)
    if P.ndim != 2 or P.shape[1] != 3 or len(P) < 2 or not np.isfinite(P).all():
        raise ValueError(f"poses must be a finite (n, 3) array with n >= 2, got shape {P.shape}")
    L = check_length(L, "L")
    D = np.ones(len(P), dtype=np.int64) if directions is None else np.asarray(directions)
    if D.shape != (len(P),) or not np.isin(D, (1, -1)).all():
        raise ValueError(f"directions must hold 1 or -1 for each of the {len(P)} poses")
    frames, fps, dpi = check_animation(frames, fps, dpi)
    if half_width is None:
        half_width = 0.0 if scenario is None else scenario.robot.half_width
    half_width = finite_number(half_width, "half_width", 0.0)
    robot = Robot(L, half_width) if scenario is None else replace(scenario.robot, half_width=half_width)
    outline = robot.footprint()
    shown = half_width > 0 or robot.front_overhang > 0 or robot.rear_overhang > 0
    A = P[:, :2]
    B = A + L * np.column_stack((np.cos(P[:, 2]), np.sin(P[:, 2])))
    if frames is None:
        frames = frame_count(_front_arc_length(P, L)[-1], L)
    idx = _frame_indices(P, L, frames)
    cusps = np.flatnonzero(D[:-1] != D[1:])  # the robot stands there: a pause
    idx = np.sort(np.concatenate((idx, np.repeat(cusps, CUSP_FRAMES))))
    back = D[1:] < 0  # the step from each pose to the next is driven backwards
    A_ahead, A_back = (_trace(A, steps) for steps in (~back, back))  # the rear path, split by direction

    fig, ax = plt.subplots(figsize=figsize, dpi=dpi, layout="constrained")
    if scenario is not None:
        plot_floor(scenario, ax, enlarged=("0.9", "0.7"), poses=False)
        plot_pose(scenario.start, L, ax, color="tab:green", label="start")
        plot_pose(scenario.goal, L, ax, color="tab:red", label="goal")
    points = np.vstack((A, B))
    reach = half_width + max(robot.front_overhang, robot.rear_overhang)
    lo, hi = points.min(axis=0) - reach, points.max(axis=0) + reach
    if scenario is not None and scenario.bounds is not None:
        xmin, ymin, xmax, ymax = scenario.bounds
        lo, hi = np.minimum(lo, (xmin, ymin)), np.maximum(hi, (xmax, ymax))
    pad = 0.05 * float(np.max(hi - lo)) + L * 0.1
    ax.set_aspect("equal", adjustable="box")  # fixed limits: the frame never rescales
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    if title:
        ax.set_title(title, fontsize="medium")
    (rear,) = ax.plot([], [], color="tab:blue", lw=1.5, label=REAR_LABEL)
    (front,) = ax.plot([], [], color="tab:orange", lw=1.2, ls="--", label=FRONT_LABEL)
    label = REVERSE_LABEL if back.any() else "_nolegend_"
    (reversing,) = ax.plot([], [], color=REVERSE_COLOR, lw=1.5, label=label)
    body = PolygonPatch(
        outline,
        closed=True,
        facecolor="0.3",
        edgecolor="k",
        alpha=0.45,
        label=body_label(robot) if shown else "_nolegend_",
        visible=shown,
    )
    ax.add_patch(body)
    (segment,) = ax.plot([], [], color="k", lw=2.0 if half_width > 0 else 3.0, solid_capstyle="round")
    (wheel,) = ax.plot([], [], "o", color="tab:orange", ms=5)
    legend_beside(ax, fontsize="x-small")
    # the layout is computed once (the legend beside the floor) and then kept: every frame
    # has the same axes, and no frame pays for the layout
    fig.canvas.draw()
    fig.set_layout_engine("none")

    def draw(k: int):
        i = idx[k] + 1
        rear.set_data(A_ahead[:i, 0], A_ahead[:i, 1])
        reversing.set_data(A_back[:i, 0], A_back[:i, 1])
        front.set_data(B[:i, 0], B[:i, 1])
        j = i - 1
        c, s = math.cos(P[j, 2]), math.sin(P[j, 2])
        body.set_xy(outline @ np.array([[c, s], [-s, c]]) + A[j])
        segment.set_data([A[j, 0], B[j, 0]], [A[j, 1], B[j, 1]])
        wheel.set_data([B[j, 0]], [B[j, 1]])
        segment.set_color(REVERSE_COLOR if j + 1 < len(P) and back[j] else "k")  # about to reverse
        return rear, front, body, segment, wheel, reversing

    anim = FuncAnimation(fig, draw, frames=len(idx), interval=1000.0 / fps, blit=False)
    plt.close(fig)
    return anim


def animate_plan(plan, scenario, **kwargs) -> FuncAnimation:
    """:func:`animate_path` of a segplan :class:`~segplan.planning.plan.Plan` on its scenario.

    The poses are the plan's unions sampled every centimetre in driving order, with their
    directions (:func:`segplan.viz.metrics.plan_pose_directions`); ``kwargs`` go to
    :func:`animate_path` (``frames``, ``fps``, ``dpi``, ``half_width``, ``figsize``, ``title``).
    """
    unions = list(getattr(plan, "unions", ()))
    if not unions:
        raise ValueError("plan must be a segplan.Plan with at least one union")
    poses, directions = plan_pose_directions(plan)
    return animate_path(poses, scenario.robot.L, scenario, directions=directions, **kwargs)


#: The player's Font Awesome icons (matplotlib links their stylesheet from a CDN) as plain
#: characters, so that the page needs no network.
_ICONS = {
    "fa fa-minus": "&minus;",
    "fa fa-fast-backward": "&#x23EE;",
    "fa fa-step-backward": "&#x23F4;&#x2503;",
    "fa fa-play fa-flip-horizontal": "&#x25C0;",
    "fa fa-pause": "&#x23F8;",
    "fa fa-play": "&#x25B6;",
    "fa fa-step-forward": "&#x2503;&#x23F5;",
    "fa fa-fast-forward": "&#x23ED;",
    "fa fa-plus": "+",
}


#: Colours of each embedded frame (a palette PNG): line art on a white floor needs few, and a
#: palette frame is about a third of matplotlib's RGBA one.
HTML_COLORS = 64

_FRAME = re.compile(r'("data:image/png;base64,)((?:[A-Za-z0-9+/=]|\\\n)+)(")')


def _palette_png(match: re.Match) -> str:
    """One embedded frame of ``to_jshtml`` re-encoded as a PNG of :data:`HTML_COLORS` colours."""
    import base64
    import io

    from PIL import Image

    data = base64.b64decode(match.group(2).replace("\\\n", ""))
    with Image.open(io.BytesIO(data)) as im:
        small = im.convert("RGB").quantize(colors=HTML_COLORS, method=Image.Quantize.MEDIANCUT)
    out = io.BytesIO()
    small.save(out, format="png", optimize=True)
    return match.group(1) + base64.b64encode(out.getvalue()).decode("ascii") + match.group(3)


def to_html(anim: FuncAnimation) -> str:
    """The animation as one HTML string that plays offline (PNG frames, JavaScript player).

    matplotlib's ``to_jshtml`` with its one network resource removed: the stylesheet of
    the buttons' icons (Font Awesome, from a CDN) is dropped and the icons are written as
    plain characters. Each frame is stored as a palette PNG of :data:`HTML_COLORS` colours
    (Pillow), about a third of the size of matplotlib's RGBA frames, so that a page (and a
    notebook that stores the animation) stays small.
    """
    from matplotlib.animation import FuncAnimation

    if not isinstance(anim, FuncAnimation):
        raise ValueError(f"anim must be a matplotlib FuncAnimation, got {type(anim).__name__}")
    html = anim.to_jshtml(default_mode="loop")
    html = _FRAME.sub(_palette_png, html)
    html = re.sub(r"<link[^>]*https?://[^>]*>", "", html)
    for icon, text in _ICONS.items():
        html = html.replace(f'<i class="{icon}"></i>', text)
    if re.search(r"(?:src|href)\s*=\s*[\"']?(?:https?:)?//", html):
        raise RuntimeError("the animation's HTML still loads a resource from the network")
    return html


def save_gif(anim: FuncAnimation, path, fps: int | None = None) -> Path:
    """Write the animation as a GIF (Pillow) and return the path.

    ``fps`` (1 to :data:`MAX_FPS`) defaults to the animation's own rate (the ``fps`` of
    :func:`animate_path`).
    """
    from matplotlib.animation import FuncAnimation, PillowWriter

    if not isinstance(anim, FuncAnimation):
        raise ValueError(f"anim must be a matplotlib FuncAnimation, got {type(anim).__name__}")
    if fps is None:
        fps = max(1, round(1000.0 / anim._interval))
    fps = _whole(fps, "fps", 1, MAX_FPS)
    p = Path(path)
    anim.save(p, writer=PillowWriter(fps=fps))
    return p
