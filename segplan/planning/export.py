"""Files for other tools: a table of samples as CSV, a path as a ``nav_msgs/Path`` message.

Beyond the paper (issue 27). Nothing here knows a union or a plan: the functions take
columns (name -> array) and the poses ``(x, y, theta)`` of the rear point A, so a path
sampled by :mod:`segplan.planning.trajectory` (or any other) leaves segplan without ROS.

- CSV: one header line of column names (no comment sign), then one line per sample,
  comma-separated; floats written by ``repr`` (the shortest text that reads back as the
  same double), integer columns as integers. ``numpy.genfromtxt(path, delimiter=",",
  names=True)`` and ``pandas.read_csv(path)`` read it as written.
- ``nav_msgs/Path`` (ROS 2 field names: ``builtin_interfaces/Time`` is ``{sec, nanosec}``;
  ROS 1 calls them ``secs``, ``nsecs`` and adds ``seq``): a ``header`` with ``frame_id``
  and ``stamp``, and ``poses``, a list of ``geometry_msgs/PoseStamped``, each with its own
  header (same frame, its stamp), ``position`` ``(x, y, 0)`` and the unit quaternion of the
  yaw ``theta`` about z: ``(0, 0, sin(psi / 2), cos(psi / 2))`` with ``psi = wrap(theta)`` in
  ``(-pi, pi]`` (:func:`segplan.model.pose.wrap`), so ``w >= 0`` and ``2 atan2(z, w) = psi``.
  A sample equal to the one before it in position, heading and stamp is left out (a node
  listed once per union that meets it); a node where the robot stands while it re-steers
  keeps both stamps. Written as JSON, or as YAML for a ``.yaml``/``.yml`` path (PyYAML,
  imported when needed), the shape ``ros2 topic pub`` and rosbridge read.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from ..model.pose import wrap

__all__ = ["nav_path", "ros_time", "write_csv", "write_nav_path"]


def write_csv(path, columns: Mapping[str, np.ndarray]) -> Path:
    """Write ``columns`` (name -> 1-d array, all of one length) to ``path`` as CSV (module docstring).

    Integer arrays are written as integers, every other column as floats by ``repr`` (exact
    on reading back). Returns the path written.

    Raises
    ------
    ValueError
        No columns, arrays not 1-d or of different lengths.
    """
    names = list(columns)
    if not names:
        raise ValueError("columns must name at least one column")
    arrays = [np.asarray(columns[n]) for n in names]
    if any(a.ndim != 1 for a in arrays) or len({a.size for a in arrays}) != 1:
        raise ValueError(f"columns must be 1-d arrays of one length, got shapes {[a.shape for a in arrays]}")
    text = [
        [str(int(v)) for v in a] if np.issubdtype(a.dtype, np.integer) else [repr(float(v)) for v in a]
        for a in arrays
    ]
    path = Path(path)
    with path.open("w", encoding="utf-8") as f:
        f.write(",".join(names) + "\n")
        f.writelines(",".join(row) + "\n" for row in zip(*text, strict=True))
    return path


def ros_time(seconds: float) -> dict:
    """``builtin_interfaces/Time`` of ``seconds >= 0``: ``{"sec": int, "nanosec": int}``
    (nanoseconds rounded to the nearest, carried into ``sec`` at 10^9)."""
    if not (math.isfinite(seconds) and seconds >= 0.0):
        raise ValueError(f"a stamp must be a finite number of seconds >= 0, got {seconds!r}")
    sec = math.floor(seconds)
    nanosec = round((seconds - sec) * 1e9)
    if nanosec >= 1_000_000_000:
        sec, nanosec = sec + 1, nanosec - 1_000_000_000
    return {"sec": int(sec), "nanosec": int(nanosec)}


def nav_path(x, y, theta, stamps=None, *, frame_id: str = "map", stamp: float = 0.0) -> dict:
    """A ``nav_msgs/Path``-shaped dict of the poses ``(x, y, theta)`` (module docstring).

    Parameters
    ----------
    x, y, theta : array_like
        Positions (m) and headings (radians, any branch) of the rear point A, in order.
    stamps : array_like, optional
        Time of each pose, seconds after ``stamp``; None: every pose stamped ``stamp``
        (a path without a time law).
    frame_id : str
        The frame of the poses (``"map"``, ``"odom"``, ...).
    stamp : float
        The header's time, seconds (>= 0).

    Returns
    -------
    dict
        ``{"header": {"stamp": ..., "frame_id": ...}, "poses": [PoseStamped, ...]}``.
    """
    if not isinstance(frame_id, str) or not frame_id:
        raise ValueError(f"frame_id must be a non-empty string, got {frame_id!r}")
    x, y, theta = (np.asarray(v, dtype=float) for v in (x, y, theta))
    t = np.zeros(x.shape) if stamps is None else np.asarray(stamps, dtype=float)
    if not (x.ndim == 1 and x.shape == y.shape == theta.shape == t.shape):
        raise ValueError("x, y, theta (and stamps) must be 1-d arrays of one length")
    psi = np.asarray(wrap(theta), dtype=float)  # in (-pi, pi]: w = cos(psi / 2) >= 0
    qz, qw = np.sin(0.5 * psi), np.cos(0.5 * psi)  # q = (0, 0, sin(psi/2), cos(psi/2))
    poses = []
    last = None
    for k in range(x.size):
        key = (x[k], y[k], psi[k], t[k])
        if key == last:
            continue  # the same pose at the same time: listed once
        last = key
        poses.append(
            {
                "header": {"stamp": ros_time(stamp + float(t[k])), "frame_id": frame_id},
                "pose": {
                    "position": {"x": float(x[k]), "y": float(y[k]), "z": 0.0},
                    "orientation": {"x": 0.0, "y": 0.0, "z": float(qz[k]), "w": float(qw[k])},
                },
            }
        )
    return {"header": {"stamp": ros_time(stamp), "frame_id": frame_id}, "poses": poses}


def write_nav_path(path, message: Mapping) -> Path:
    """Write a :func:`nav_path` message to ``path``: YAML for ``.yaml``/``.yml``, else JSON.

    Returns the path written. YAML needs PyYAML (``import yaml``); floats are written so
    that reading them back gives the same doubles in either format.
    """
    path = Path(path)
    if path.suffix.lower() in (".yaml", ".yml"):
        import yaml  # only this format needs it

        path.write_text(yaml.safe_dump(dict(message), sort_keys=False), encoding="utf-8")
    else:
        path.write_text(json.dumps(message, indent=1, allow_nan=False) + "\n", encoding="utf-8")
    return path
