"""The robot in motion: an animation of the segment driving a plan.

Section "Mobile robot modelling" of Campoy et al. (1989): the robot is the oriented
segment from A (middle of the rear axle) to B (middle of the front wheel), of length
``L``; a plan is a chain of unions whose cost, formula [1], is the length of B's path.
:func:`animate_plan` shows exactly that: at each frame the segment A->B at its pose on
the plan, the trace of A (rear, solid) and of B (front wheel, dashed) behind it, over the
floor (obstacles, their enlargement by the robot's half-width, the walls, start and goal).

Frames are equally spaced in the *front wheel's* arc length, the paper's cost: the robot
moves at constant front-wheel speed, as the cost assumes (traversal time).

Outputs, both offline: :func:`to_html` (matplotlib's ``to_jshtml``: PNG frames and a
small player in one HTML string, no network) and :func:`save_gif` (Pillow, installed with
matplotlib). Like :mod:`segplan.viz.plot`, this module imports matplotlib; the algorithms do
not.
"""

from __future__ import annotations

import re
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import FuncAnimation, PillowWriter

from ..model.pose import check_length
from .metrics import plan_poses
from .plot import plot_bounds, plot_polygons, plot_pose

__all__ = ["animate_path", "animate_plan", "save_gif", "to_html"]

#: Default number of frames: enough for smooth motion, few enough for a small page.
FRAMES = 24


def _frame_indices(poses: np.ndarray, L: float, frames: int) -> np.ndarray:
    """Indices of ``frames`` poses equally spaced in front-wheel arc length (first and last kept)."""
    B = poses[:, :2] + L * np.column_stack((np.cos(poses[:, 2]), np.sin(poses[:, 2])))
    s = np.r_[0.0, np.cumsum(np.hypot(*np.diff(B, axis=0).T))]
    targets = np.linspace(0.0, s[-1], frames)
    idx = np.searchsorted(s, targets, side="left").clip(0, len(poses) - 1)
    idx[-1] = len(poses) - 1
    return idx


def animate_path(
    poses,
    L: float,
    scenario=None,
    *,
    frames: int = FRAMES,
    interval: int = 100,
    figsize: tuple[float, float] = (5.5, 3.8),
    dpi: int = 50,
    title: str | None = None,
) -> FuncAnimation:
    """An animation of the segment robot following ``poses``.

    Parameters
    ----------
    poses : array_like, shape (n, 3)
        Dense rear-axle poses ``(x, y, theta)`` along the path (A and the heading of A->B,
        radians), e.g. :func:`segplan.viz.metrics.plan_poses` of a plan, or an OMPL path.
    L : float
        Length of the segment A->B (m).
    scenario : segplan.Scenario, optional
        The floor drawn underneath (obstacles, their enlargement, walls, start and goal).
    frames : int
        Number of frames (>= 2), equally spaced in front-wheel arc length.
    interval : int
        Milliseconds between frames when played.
    figsize, dpi
        Size of each frame; the defaults keep an embedded HTML animation small.
    title : str, optional

    Returns
    -------
    matplotlib.animation.FuncAnimation
        Its figure is closed (not shown by notebooks); use :func:`to_html` or
        :func:`save_gif`.
    """
    P = np.asarray(poses, dtype=float)
    if P.ndim != 2 or P.shape[1] != 3 or len(P) < 2 or not np.isfinite(P).all():
        raise ValueError(f"poses must be a finite (n, 3) array with n >= 2, got shape {P.shape}")
    L = check_length(L, "L")
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 2:
        raise ValueError(f"frames must be an integer >= 2, got {frames!r}")
    if isinstance(interval, bool) or not isinstance(interval, int) or interval < 1:
        raise ValueError(f"interval must be a positive integer of milliseconds, got {interval!r}")
    A = P[:, :2]
    B = A + L * np.column_stack((np.cos(P[:, 2]), np.sin(P[:, 2])))
    idx = _frame_indices(P, L, frames)

    fig, ax = plt.subplots(figsize=figsize, dpi=dpi)
    if scenario is not None:
        if scenario.bounds is not None:
            plot_bounds(scenario.bounds, ax)
        if scenario.robot.half_width > 0:
            plot_polygons(scenario.enlarged, ax, facecolor="0.9", edgecolor="0.7", label=None)
        plot_polygons(scenario.outlines, ax)
        plot_pose(scenario.start, L, ax, color="tab:green")
        plot_pose(scenario.goal, L, ax, color="tab:red")
    points = np.vstack((A, B))
    lo, hi = points.min(axis=0), points.max(axis=0)
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
    (rear,) = ax.plot([], [], color="tab:blue", lw=1.5, label="rear A")
    (front,) = ax.plot([], [], color="tab:orange", lw=1.2, ls="--", label="front wheel B")
    (body,) = ax.plot([], [], color="k", lw=3.0, solid_capstyle="round")
    (wheel,) = ax.plot([], [], "o", color="tab:orange", ms=5)
    # the legend's "best" place, found once with the whole path drawn, then kept: it does not
    # jump between frames, and no frame pays for the search (it was most of a frame's time)
    rear.set_data(A[:, 0], A[:, 1])
    front.set_data(B[:, 0], B[:, 1])
    legend = ax.legend(loc="best", fontsize="x-small")
    fig.canvas.draw()
    corner = legend.get_window_extent().transformed(ax.transAxes.inverted())
    legend.remove()
    ax.legend(loc="lower left", bbox_to_anchor=(corner.x0, corner.y0), borderaxespad=0.0, fontsize="x-small")

    def draw(k: int):
        i = idx[k] + 1
        rear.set_data(A[:i, 0], A[:i, 1])
        front.set_data(B[:i, 0], B[:i, 1])
        j = i - 1
        body.set_data([A[j, 0], B[j, 0]], [A[j, 1], B[j, 1]])
        wheel.set_data([B[j, 0]], [B[j, 1]])
        return rear, front, body, wheel

    anim = FuncAnimation(fig, draw, frames=len(idx), interval=interval, blit=False)
    plt.close(fig)
    return anim


def animate_plan(plan, scenario, **kwargs) -> FuncAnimation:
    """:func:`animate_path` of a segplan :class:`~segplan.planning.plan.Plan` on its scenario.

    The poses are the plan's unions sampled every centimetre
    (:func:`segplan.viz.metrics.plan_poses`); ``kwargs`` go to :func:`animate_path`.
    """
    unions = list(getattr(plan, "unions", ()))
    if not unions:
        raise ValueError("plan must be a segplan.Plan with at least one union")
    return animate_path(plan_poses(plan), scenario.robot.L, scenario, **kwargs)


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

    ``fps`` defaults to the animation's own rate (1000 / interval).
    """
    if not isinstance(anim, FuncAnimation):
        raise ValueError(f"anim must be a matplotlib FuncAnimation, got {type(anim).__name__}")
    if fps is None:
        fps = max(1, round(1000.0 / anim._interval))
    if isinstance(fps, bool) or not isinstance(fps, int) or fps < 1:
        raise ValueError(f"fps must be a positive integer, got {fps!r}")
    p = Path(path)
    anim.save(p, writer=PillowWriter(fps=fps))
    return p
