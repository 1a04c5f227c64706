"""ROS ``map_server`` maps: the YAML file and its image, read as a :class:`segplan.Floor`.

Beyond the paper (issue 27). A ``map_server`` map (ROS 1 ``map_server``, ROS 2
``nav2_map_server``) is a YAML file of flat ``key: value`` lines naming an image::

    image: office.pgm             # path relative to the YAML file
    resolution: 0.05              # metres per cell
    origin: [-10.0, -5.0, 0.0]    # the lower-left corner of the bottom-left pixel: x, y, yaw
    negate: 0                     # 1: white is occupied
    occupied_thresh: 0.65         # optional here (defaults shown)
    free_thresh: 0.196
    mode: trinary                 # trinary (default), scale or raw

Required keys: ``image``, ``resolution``, ``origin``. Another key is ignored (tools add
their own), unless it is a near-miss of a known one (``occupied_tresh``), which is an error.
A non-zero yaw is refused (the map's walls would not be parallel to the axes).

Pixels to cells, as ``map_server`` does: ``p`` is the pixel's grey level over its maximum
(the mean of R, G, B for a colour image; its alpha apart), ``occ = 1 - p`` (``p`` with
``negate``); occupied if ``occ > occupied_thresh``, free if ``occ < free_thresh``, unknown
otherwise. ``scale`` mode: a pixel not fully opaque is unknown as well (nav2); in our
binary view its in-between values are unknown, as in ``trinary``. ``raw`` mode: the grey
level (after ``negate``, as ROS 1) is the occupancy in percent, above 100 unknown, and the
same thresholds apply to it over 100. With the defaults the usual map colours read
254 free, 0 occupied, 205 unknown (``occ = 50/255 = 0.19608 > 0.196``).

Images: PGM (``P5`` binary, 8 or 16 bits, and ``P2`` plain text) are read here (Pillow
13 reads a 16-bit ``P5`` with its bytes swapped); PNG and the other formats Pillow
reads through Pillow. The YAML is parsed by PyYAML (``yaml.safe_load``).
"""

from __future__ import annotations

import difflib
import math
from pathlib import Path

import numpy as np

from .maps import Floor

__all__ = ["MAP_KEYS", "MODES", "load_ros_map", "map_cells", "read_image", "read_map_yaml", "read_pgm"]

#: The keys of a map YAML file and their defaults (None: required).
MAP_KEYS = {
    "image": None,
    "resolution": None,
    "origin": None,
    "negate": 0,
    "occupied_thresh": 0.65,
    "free_thresh": 0.196,
    "mode": "trinary",
}
#: ``mode`` values of ``map_server``.
MODES = ("trinary", "scale", "raw")


def load_ros_map(path, *, unknown_is_occupied: bool = True, tolerance: float | None = None) -> Floor:
    """Load a ROS ``map_server`` map (YAML and image) as a :class:`segplan.Floor`.

    Parameters
    ----------
    path : str or Path
        The map's YAML file (the module docstring gives the format); its image is read
        relative to it.
    unknown_is_occupied : bool
        Unknown cells are obstacles (default, conservative) or free space.
    tolerance : float, optional
        How far (m) the convex pieces may reach beyond the blocked cells, see
        :meth:`segplan.Floor.from_occupancy` (default: two cells).

    Returns
    -------
    Floor
        Bounds: the map's extent; obstacles: convex pieces covering every blocked cell.

    Raises
    ------
    ValueError
        One line naming the file: unreadable or malformed YAML, a missing or bad key,
        thresholds outside ``0 <= free_thresh < occupied_thresh <= 1``, a non-zero yaw, an
        unreadable image, a map without a free cell.

    Examples
    --------
    >>> import math, segplan  # doctest: +SKIP
    >>> floor = segplan.load_ros_map("office.yaml")  # doctest: +SKIP
    >>> plan = segplan.plan((1, 2, 0), (9, 4, math.pi / 2), floor, 1.2, half_width=0.35)  # doctest: +SKIP
    """
    p = Path(path)
    meta = read_map_yaml(p)
    image = meta["image"]
    values, maxval, alpha = read_image(image, f"{p}: image {meta['image_name']!r}")
    cells = map_cells(values, maxval, alpha, meta)
    return Floor.from_occupancy(
        cells,
        meta["resolution"],
        meta["origin"],
        unknown_is_occupied=unknown_is_occupied,
        tolerance=tolerance,
        source=str(p),
    )


def read_map_yaml(path) -> dict:
    """The checked keys of a map YAML file (``image`` resolved against the file's folder).

    Returns a dict with every key of :data:`MAP_KEYS` (defaults filled in; ``negate`` a
    bool, ``origin`` ``(x, y, yaw)`` floats, ``image`` a Path) and ``image_name`` (as
    written). Raises ValueError naming the file and the key.
    """
    import yaml

    p = Path(path)
    try:
        text = p.read_bytes()
    except OSError as exc:
        raise ValueError(f"{p}: cannot read: {exc.strerror or exc}") from None
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" (line {mark.line + 1}, column {mark.column + 1})" if mark is not None else ""
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise ValueError(f"{p}: invalid YAML: {problem}{where}") from None
    if not isinstance(data, dict):
        raise ValueError(f"{p}: a map file is 'key: value' lines (image, resolution, origin, ...)")
    for key in data:
        if key not in MAP_KEYS:
            near = difflib.get_close_matches(str(key), list(MAP_KEYS), n=1, cutoff=0.8)
            if near:
                raise ValueError(f"{p}: unknown key {str(key)[:40]!r}; did you mean {near[0]!r}?")
    missing = [k for k, v in MAP_KEYS.items() if v is None and k not in data]
    if missing:
        raise ValueError(f"{p}: missing key {missing[0]!r} (required: image, resolution, origin)")
    out = {k: data.get(k, default) for k, default in MAP_KEYS.items()}
    name = out["image"]
    if not isinstance(name, str) or not name.strip():
        raise ValueError(f"{p}: image must be a file name, got {name!r}")
    out["image_name"] = name
    out["image"] = p.parent / name.strip()
    out["resolution"] = _number(out["resolution"], f"{p}: resolution")
    if out["resolution"] <= 0.0:
        raise ValueError(f"{p}: resolution must be > 0 (metres per cell), got {out['resolution']:g}")
    origin = out["origin"]
    if not isinstance(origin, list) or len(origin) not in (2, 3):
        raise ValueError(f"{p}: origin must be [x, y, yaw], got {origin!r}")
    origin = [_number(v, f"{p}: origin[{i}]") for i, v in enumerate(origin)]
    if len(origin) == 3 and origin[2] != 0.0:
        raise ValueError(
            f"{p}: origin yaw {origin[2]:g} rad is not supported (the map would be rotated and "
            "its walls not parallel to the axes); rotate the image and set yaw to 0"
        )
    out["origin"] = (origin[0], origin[1], 0.0)
    negate = out["negate"]
    if isinstance(negate, bool) or negate in (0, 1):
        out["negate"] = bool(negate)
    else:
        raise ValueError(f"{p}: negate must be 0 or 1, got {negate!r}")
    for key in ("occupied_thresh", "free_thresh"):
        out[key] = _number(out[key], f"{p}: {key}")
    lo, hi = out["free_thresh"], out["occupied_thresh"]
    if not 0.0 <= lo < hi <= 1.0:
        raise ValueError(
            f"{p}: thresholds must satisfy 0 <= free_thresh < occupied_thresh <= 1, "
            f"got free_thresh={lo:g}, occupied_thresh={hi:g}"
        )
    if out["mode"] not in MODES:
        raise ValueError(f"{p}: mode must be one of {', '.join(MODES)}, got {out['mode']!r}")
    return out


def _number(value, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ValueError(f"{where} must be a number, got {value!r}")
    x = float(value)
    if not math.isfinite(x):
        raise ValueError(f"{where} must be finite, got {value!r}")
    return x


def map_cells(values: np.ndarray, maxval: int, alpha: np.ndarray | None, meta: dict) -> np.ndarray:
    """Cells of a map image as ``nav_msgs/OccupancyGrid`` values: 100 occupied, 0 free, -1 unknown.

    ``values``: grey levels (2-D, row 0 the top row) of maximum ``maxval``; ``alpha``: the
    alpha channel or None; ``meta``: :func:`read_map_yaml`'s keys (``negate``,
    ``occupied_thresh``, ``free_thresh``, ``mode``). The rules are the module docstring's.
    """
    v = values.astype(np.float64)
    if meta["negate"]:
        v = maxval - v
    unknown = np.zeros(v.shape, dtype=bool)
    if meta["mode"] == "raw":
        occ = v / 100.0
        unknown |= v > 100.0
    else:
        occ = (maxval - v) / maxval
        if meta["mode"] == "scale" and alpha is not None:  # not fully opaque: unknown (nav2)
            unknown |= alpha < np.iinfo(alpha.dtype).max
    out = np.full(v.shape, -1, dtype=np.int8)
    out[occ < meta["free_thresh"]] = 0
    out[occ > meta["occupied_thresh"]] = 100
    out[unknown] = -1
    return out


def read_image(path, where: str) -> tuple[np.ndarray, int, np.ndarray | None]:
    """Grey levels (2-D, row 0 the top row), their maximum and the alpha channel (or None).

    PGM by :func:`read_pgm`; other formats by Pillow, colours averaged (R, G, B), a palette
    expanded. ``where`` names the image in error messages (ValueError).
    """
    p = Path(path)
    try:
        with open(p, "rb") as f:
            head = f.read(2)
    except OSError as exc:
        raise ValueError(f"{where}: cannot read: {exc.strerror or exc}") from None
    if head in (b"P2", b"P5"):
        values, maxval = read_pgm(p, where)
        return values, maxval, None
    try:
        from PIL import Image, UnidentifiedImageError
    except ImportError:  # pragma: no cover - Pillow comes with matplotlib
        raise ValueError(f"{where}: reading this image needs Pillow (pip install pillow)") from None
    try:
        with Image.open(p) as im:
            im.load()
            if im.mode == "P":
                im = im.convert("RGBA")
            elif im.mode not in ("1", "L", "LA", "RGB", "RGBA", "I", "I;16", "I;16B", "I;16L"):
                im = im.convert("RGB")
            mode = im.mode
            a = np.asarray(im)
    except (UnidentifiedImageError, OSError, ValueError) as exc:
        raise ValueError(f"{where}: not an image Pillow can read ({exc})") from None
    alpha = None
    if mode == "1":
        return a.astype(np.uint8), 1, None
    if mode in ("LA", "RGBA"):
        alpha = a[..., -1]
        a = a[..., :-1]
    if a.ndim == 3:
        a = a.mean(axis=2)
    maxval = 255 if mode in ("L", "LA", "RGB", "RGBA") else 65535
    return a, maxval, alpha


def read_pgm(path, where: str = "image") -> tuple[np.ndarray, int]:
    """A PGM image (``P5`` binary, 8 or 16 bits big-endian, or ``P2`` plain): grey levels and maxval.

    Row 0 is the top row. Comments (``#`` to the end of a line) are allowed in the header
    (and in a ``P2`` body). ValueError naming ``where`` for a malformed file.
    """
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise ValueError(f"{where}: cannot read: {exc.strerror or exc}") from None
    magic = data[:2]
    fields, pos = [], 2
    while len(fields) < 3:  # width, height, maxval
        while pos < len(data) and data[pos : pos + 1].isspace():
            pos += 1
        if data[pos : pos + 1] == b"#":
            while pos < len(data) and data[pos : pos + 1] not in (b"\n", b"\r"):
                pos += 1
            continue
        start = pos
        while pos < len(data) and data[pos : pos + 1].isdigit():
            pos += 1
        if start == pos:
            raise ValueError(f"{where}: malformed PGM header (expected width, height and maxval)")
        fields.append(int(data[start:pos]))
    width, height, maxval = fields
    if width < 1 or height < 1 or not 1 <= maxval <= 65535:
        raise ValueError(f"{where}: PGM header width={width}, height={height}, maxval={maxval} out of range")
    n = width * height
    if magic == b"P5":
        dtype = np.dtype(np.uint8) if maxval < 256 else np.dtype(">u2")
        body = data[pos + 1 :]  # a single whitespace ends the header
        if len(body) < n * dtype.itemsize:
            need = n * dtype.itemsize
            raise ValueError(
                f"{where}: PGM holds {len(body)} bytes of pixels, {width} x {height} need {need}"
            )
        values = np.frombuffer(body, dtype=dtype, count=n).reshape(height, width)
        values = values.astype(np.uint8 if maxval < 256 else np.uint16)
    else:
        lines = [line.split(b"#", 1)[0] for line in data[pos:].splitlines()]
        try:
            flat = np.array(b" ".join(lines).split(), dtype=np.int64)
        except ValueError:
            raise ValueError(f"{where}: PGM P2 body holds something other than integers") from None
        if flat.size < n:
            raise ValueError(f"{where}: PGM holds {flat.size} pixels, {width} x {height} need {n}")
        values = flat[:n].reshape(height, width)
    if int(values.max()) > maxval:
        raise ValueError(f"{where}: a pixel exceeds maxval={maxval}")
    return values, maxval
