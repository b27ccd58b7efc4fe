"""ROS ``map_server`` maps in and out: a YAML file and its occupancy image.

The YAML file names the image (relative to the YAML file), its ``resolution`` (metres per
cell), ``origin`` (``[x, y, yaw]``: the ROS world pose of the image's lower-left corner),
``negate``, ``occupied_thresh`` and ``free_thresh``, and optionally ``mode`` (``trinary``, the
default, ``scale`` or ``raw``). The image is an 8-bit PGM (binary ``P5`` or ASCII ``P2``) or
any image Pillow reads (PNG ...); its first row is the top of the map.

Each cell is read as ROS 2's ``nav2_map_server`` reads it: ``shade`` is the mean of the pixel's
colour channels over 255 (in ``trinary`` mode an alpha channel's opacity is averaged in too), and
the cell's occupancy is ``p = 1 - shade`` (``p = shade`` when ``negate``). The cell is
*occupied* when ``p > occupied_thresh``, *free* when ``p < free_thresh``, and *unknown*
otherwise. ``scale`` mode reads the same, except that a transparent pixel is unknown and a value
between the thresholds is a partial occupancy; ``raw`` mode reads the grey value ``v`` (0..255,
``negate`` ignored) as the occupancy in percent, ``p = v / 100``, and ``v > 100`` as unknown.

The planner knows free space and obstacles only, so **every cell that is not free is an
obstacle**: occupied, unknown (a map's unexplored outside included) and, in ``scale`` and
``raw`` modes, partially occupied cells. The obstacle cells become polygons with
:func:`~mawdo.planning.world.rasters.grid_to_polygons`, exactly the cells' union.

Coordinates: the scenario is in metres (``units = "m"``, ``resolution`` the map's), its map box
``[0, cols * resolution] x [0, rows * resolution]`` starts at the image's lower-left corner, so
a ROS world point ``(x, y)`` is the scenario point ``(x - origin_x, y - origin_y)``
(:meth:`RosMap.to_scenario`, :meth:`RosMap.to_ros`). A rotated map (``yaw != 0``) is refused.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

from mawdo.planning.world.rasters import grid_to_polygons
from mawdo.planning.world.scenario import (
    SCHEMA_VERSION,
    Scenario,
    ScenarioError,
    scenario_from_dict,
)

__all__ = ["MODES", "RosMap", "load_ros_map", "read_pgm", "read_ros_map", "save_ros_map"]

#: The map modes of ``map_server``.
MODES = ("trinary", "scale", "raw")
#: What :func:`save_ros_map` writes: ``map_saver``'s grey levels and thresholds.
OCCUPIED_GREY, FREE_GREY = 0, 254
SAVE_OCCUPIED_THRESH, SAVE_FREE_THRESH = 0.65, 0.196
_REQUIRED = ("image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh")


@dataclass(frozen=True)
class RosMap:
    """A ``map_server`` map as read: which cells are obstacles, and where the map lies.

    Attributes
    ----------
    blocked : numpy.ndarray of bool, shape (rows, cols)
        True for every cell that is not free (occupied or unknown); row 0 is the image's first
        row, the top of the map.
    resolution : float
        Cell size (metres), > 0.
    origin : tuple of float
        ROS world position ``(x, y)`` (metres) of the image's lower-left corner.
    yaml_path, image_path : Path
        The files read.
    """

    blocked: np.ndarray
    resolution: float
    origin: tuple[float, float]
    yaml_path: Path
    image_path: Path

    @property
    def size(self) -> tuple[float, float]:
        """Map width and height (metres): ``cols * resolution``, ``rows * resolution``."""
        rows, cols = self.blocked.shape
        return cols * self.resolution, rows * self.resolution

    def to_scenario(self, xy) -> np.ndarray:
        """ROS world metres -> the scenario's metres: ``xy - origin`` (any shape ``(..., 2)``)."""
        return np.asarray(xy, dtype=float) - np.asarray(self.origin)

    def to_ros(self, xy) -> np.ndarray:
        """The scenario's metres -> ROS world metres: ``xy + origin``."""
        return np.asarray(xy, dtype=float) + np.asarray(self.origin)


# --------------------------------------------------------------------------------------------
# reading


def read_ros_map(yaml_path) -> RosMap:
    """Read a ``map_server`` YAML file and its image (see the module docstring for the rules).

    Parameters
    ----------
    yaml_path : str or Path
        The map's YAML file.

    Raises
    ------
    FileNotFoundError
        If the YAML file or the image it names does not exist.
    ScenarioError
        If a field is missing or out of range (thresholds outside ``[0, 1]`` or
        ``occupied_thresh <= free_thresh``, an unknown ``mode``, ``yaw != 0`` ...), or the image
        cannot be read.
    ImportError
        Without PyYAML (``pip install 'mawdo[rosmap]'``).
    """
    yaml_path = Path(yaml_path)
    meta = _read_yaml(yaml_path)
    src = str(yaml_path)
    image = Path(meta["image"])
    image = image if image.is_absolute() else yaml_path.parent / image
    if not image.is_file():
        raise FileNotFoundError(
            f"{src}: its image {meta['image']!r} is not there (looked for {str(image)!r}; a "
            "relative path is relative to the YAML file's folder)"
        )
    shade, alpha, n_colour = _read_image(image)
    p, unknown = _occupancy(shade, alpha, n_colour, meta)
    free = (p < meta["free_thresh"]) & ~unknown
    return RosMap(~free, meta["resolution"], meta["origin"], yaml_path, image)


def _read_yaml(path: Path) -> dict:
    try:
        import yaml
    except ImportError:
        raise ImportError("reading a ROS map needs PyYAML: pip install 'mawdo[rosmap]'") from None
    src = str(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such map file: {src!r}")
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as exc:
        raise ScenarioError([("", f"cannot read the map's YAML: {exc}")], src) from None
    if not isinstance(data, dict):
        raise ScenarioError([("", "expected 'key: value' lines (image, resolution ...)")], src)
    errors = [(k, "required (see the ROS map_server map format)") for k in _REQUIRED
              if k not in data]  # fmt: skip
    if errors:
        raise ScenarioError(errors, src)
    meta, errors = _check_meta(data)
    if errors:
        raise ScenarioError(errors, src)
    return meta


def _number(v) -> float | None:
    ok = isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
    return float(v) if ok else None


def _check_meta(data: dict) -> tuple[dict, list[tuple[str, str]]]:
    errors, meta = [], {"image": data["image"]}
    if not isinstance(data["image"], str) or not data["image"]:
        errors.append(("image", f"must be the image's file name, got {data['image']!r}"))
    res = _number(data["resolution"])
    if res is None or res <= 0:
        errors.append(("resolution", f"must be metres per cell, > 0, got {data['resolution']!r}"))
    meta["resolution"] = res
    origin = data["origin"]
    xyz = [_number(v) for v in origin] if isinstance(origin, list) else []
    if len(xyz) != 3 or None in xyz:
        errors.append(("origin", f"must be [x, y, yaw] (metres, radians), got {origin!r}"))
    elif xyz[2] != 0.0:
        errors.append(("origin", f"yaw {xyz[2]:g} rad: rotated maps are not supported; rotate "
                       "the image to be axis-aligned and give yaw 0"))  # fmt: skip
    meta["origin"] = tuple(xyz[:2])
    negate = data["negate"]
    if negate not in (0, 1) or isinstance(negate, float):  # True/False are 1/0
        errors.append(("negate", f"must be 0 or 1, got {negate!r}"))
    meta["negate"] = bool(negate)
    for key in ("occupied_thresh", "free_thresh"):
        v = meta[key] = _number(data[key])
        if v is None or not 0.0 <= v <= 1.0:
            errors.append((key, f"must be a probability in [0, 1], got {data[key]!r}"))
    occ, free = meta["occupied_thresh"], meta["free_thresh"]
    if occ is not None and free is not None and 0 <= free <= 1 and 0 <= occ <= 1 and occ <= free:
        errors.append(("occupied_thresh", f"{occ:g} must be greater than free_thresh {free:g} "
                       "(e.g. 0.65 and 0.196)"))  # fmt: skip
    mode = meta["mode"] = data.get("mode", "trinary")
    if mode not in MODES:
        errors.append(("mode", f"unknown mode {mode!r}: use one of {', '.join(MODES)}"))
    return meta, errors


def _occupancy(shade, alpha, n_colour, meta) -> tuple[np.ndarray, np.ndarray]:
    """Occupancy probability of each cell, and which cells are unknown whatever it is."""
    mode = meta["mode"]
    if mode == "raw":
        v = np.rint(shade * 255.0)
        return v / 100.0, v > 100
    if mode == "trinary" and alpha is not None:  # nav2 averages the opacity in
        shade = (shade * n_colour + alpha) / (n_colour + 1)
    p = shade if meta["negate"] else 1.0 - shade
    unknown = np.zeros(p.shape, dtype=bool)
    if mode == "scale" and alpha is not None:
        unknown = alpha < 1.0
    return p, unknown


def _read_image(path: Path) -> tuple[np.ndarray, np.ndarray | None, int]:
    """``(shade, opacity, n)``: the mean of the ``n`` colour channels and the opacity, in
    [0, 1], shape (rows, cols); opacity None without an alpha channel."""
    if path.suffix.lower() == ".pgm":
        return read_pgm(path), None, 1
    from PIL import Image, UnidentifiedImageError

    try:
        with Image.open(path) as img:
            if img.mode == "P":
                img = img.convert("RGBA" if "transparency" in img.info else "RGB")
            if img.mode not in ("1", "L", "LA", "RGB", "RGBA"):
                raise ValueError(f"an 8-bit grey or colour image is needed, got mode {img.mode}")
            pixels = np.asarray(img.convert("L") if img.mode == "1" else img, dtype=float)
    except (OSError, UnidentifiedImageError, ValueError) as exc:
        raise ScenarioError([("image", f"cannot read image: {exc}")], str(path)) from None
    pixels = pixels.reshape(pixels.shape[0], pixels.shape[1], -1) / 255.0
    has_alpha = pixels.shape[2] in (2, 4)
    colour = pixels[..., :-1] if has_alpha else pixels
    alpha = pixels[..., -1] if has_alpha else None
    return colour.mean(axis=2), alpha, colour.shape[2]


_PGM_TOKEN = re.compile(rb"\s*(?:#[^\n]*\n\s*)*(\S+)")


def read_pgm(path) -> np.ndarray:
    """An 8-bit PGM image (binary ``P5`` or ASCII ``P2``) as grey levels in [0, 1], shape
    (rows, cols), row 0 the image's first row.

    Raises
    ------
    ScenarioError
        If the file is not an 8-bit PGM, or holds fewer or more pixels than its header says.
    """
    path = Path(path)
    data = path.read_bytes()

    def bad(message: str) -> ScenarioError:
        return ScenarioError([("image", message)], str(path))

    header, pos = [], 0
    for _ in range(4):
        m = _PGM_TOKEN.match(data, pos)
        if m is None:
            raise bad("not a PGM file: its header is incomplete")
        header.append(m.group(1))
        pos = m.end()
    magic = header[0]
    if magic not in (b"P5", b"P2"):
        raise bad(f"not a grey PGM (P5 or P2): starts with {magic[:8]!r}; convert it to an "
                  "8-bit grey PGM or a PNG")  # fmt: skip
    try:
        cols, rows, maxval = (int(t) for t in header[1:])
    except ValueError:
        raise bad("PGM width, height and maxval must be integers") from None
    if cols <= 0 or rows <= 0 or not 0 < maxval < 256:
        raise bad(f"PGM of {cols} x {rows} with maxval {maxval}: only 8-bit images (maxval "
                  "1..255) of positive size are read")  # fmt: skip
    if magic == b"P5":
        values = np.frombuffer(data[pos + 1 :], dtype=np.uint8)  # one whitespace ends the header
    else:
        try:
            values = np.array(data[pos:].split(), dtype=np.int64)
        except ValueError:
            raise bad("P2 pixel values must be integers") from None
    if values.size != rows * cols:
        raise bad(f"the header says {cols} x {rows} = {rows * cols} pixels, the file holds "
                  f"{values.size}: a truncated or damaged image")  # fmt: skip
    if values.min() < 0 or values.max() > maxval:
        raise bad(f"pixel values must be in 0..{maxval}")
    return values.reshape(rows, cols).astype(float) / maxval


# --------------------------------------------------------------------------------------------
# a scenario


def load_ros_map(
    yaml_path,
    start,
    goal,
    robot_radius: float = 0.3,
    robot_speed: float = 1.0,
    dt: float = 0.25,
    name: str | None = None,
) -> Scenario:
    """A static metre scenario from a ROS ``map_server`` map.

    Parameters
    ----------
    yaml_path : str or Path
        The map's YAML file.
    start, goal : array_like, shape (2,)
        Start and goal in ROS world coordinates (metres).
    robot_radius : float
        Robot disc radius (metres), > 0; CrowdNav's 0.3 by default.
    robot_speed : float
        Robot speed (metres per second), > 0.
    dt : float
        Seconds per planner time step, > 0.
    name : str, optional
        Scenario name (default the YAML file's stem).

    Returns
    -------
    Scenario
        ``units = "m"``, ``resolution`` the map's, the map box from the image's lower-left
        corner: a ROS point ``(x, y)`` is the scenario point ``(x, y) - origin``
        (:meth:`RosMap.to_scenario`; :func:`read_ros_map` gives the map's origin).

    Raises
    ------
    FileNotFoundError, ScenarioError
        As for :func:`read_ros_map`; ``ScenarioError`` also for a start or goal outside the
        map or on an obstacle.
    """
    m = read_ros_map(yaml_path)
    width, height = m.size
    polygons = grid_to_polygons(m.blocked, m.resolution)
    data = {
        "schema_version": SCHEMA_VERSION,
        "name": name or Path(yaml_path).stem,
        "units": "m",
        "dt": float(dt),
        "resolution": m.resolution,
        "width": width,
        "height": height,
        "start": m.to_scenario(np.asarray(start, dtype=float).reshape(2)).tolist(),
        "goal": m.to_scenario(np.asarray(goal, dtype=float).reshape(2)).tolist(),
        "robot": {"radius": float(robot_radius), "speed": float(robot_speed)},
        "obstacles": [
            {"shape": "polygon", "vertices": np.asarray(p.exterior.coords)[:-1].tolist()}
            for p in polygons
        ],
    }
    return scenario_from_dict(data, source=str(yaml_path))


# --------------------------------------------------------------------------------------------
# writing


def save_ros_map(scenario: Scenario, yaml_path, resolution=None, origin=(0.0, 0.0)) -> Path:
    """Write a metre scenario's static obstacles as a ``map_server`` map (YAML + PGM).

    A cell is occupied (grey 0) when its centre lies inside a static obstacle, free (grey 254)
    otherwise; the YAML says ``mode: trinary``, ``negate: 0``, ``occupied_thresh: 0.65``,
    ``free_thresh: 0.196`` (``map_saver``'s). A map read with :func:`load_ros_map` and written
    at its own resolution and origin is the same map, cell for cell.

    Parameters
    ----------
    scenario : Scenario
        A scenario in metres (``units = "m"``); moving obstacles are left out.
    yaml_path : str or Path
        The YAML file to write; the image goes beside it with the suffix ``.pgm``.
    resolution : float, optional
        Cell size (metres), > 0; default the scenario's ``resolution``.
    origin : (float, float)
        ROS world position (metres) of the map's lower-left corner: the scenario point
        ``(0, 0)``.

    Returns
    -------
    Path
        The YAML file.

    Raises
    ------
    ValueError
        For a pixel scenario (it has no metres) or a resolution that is not > 0.
    """
    units = scenario.units
    if units.is_pixels:
        raise ValueError(
            f"scenario {scenario.name!r} is in pixels; a ROS map is in metres: give the "
            'scenario file units = "m" with dt and resolution'
        )
    res = units.resolution if resolution is None else float(resolution)
    if not (math.isfinite(res) and res > 0):
        raise ValueError(f"resolution must be metres per cell, > 0, got {resolution!r}")
    width, height = units.length(scenario.width), units.length(scenario.height)
    cols, rows = (max(1, math.ceil(s / res - 1e-9)) for s in (width, height))
    blocked = rasterise(scenario, res, rows, cols)
    yaml_path = Path(yaml_path)
    yaml_path.parent.mkdir(parents=True, exist_ok=True)
    image = yaml_path.with_suffix(".pgm")
    grey = np.where(blocked, OCCUPIED_GREY, FREE_GREY).astype(np.uint8)
    header = f"P5\n# {scenario.name}: mawdo, {res!r} m per cell\n{cols} {rows}\n255\n"
    image.write_bytes(header.encode("ascii") + grey.tobytes())
    ox, oy = (float(v) for v in origin)
    yaml_path.write_text(
        f"image: {image.name}\nmode: trinary\nresolution: {res!r}\n"
        f"origin: [{ox!r}, {oy!r}, 0.0]\nnegate: 0\n"
        f"occupied_thresh: {SAVE_OCCUPIED_THRESH}\nfree_thresh: {SAVE_FREE_THRESH}\n",
        encoding="utf-8",
    )
    return yaml_path


def rasterise(scenario: Scenario, res: float, rows: int, cols: int) -> np.ndarray:
    """Cells (row 0 at the top) whose centre lies inside a static obstacle of ``scenario``
    (its metres), cells ``res`` metres wide."""
    L = scenario.units.length
    x = (np.arange(cols) + 0.5) * res
    y = (rows - np.arange(rows) - 0.5) * res
    xx, yy = np.meshgrid(x, y)
    blocked = np.zeros((rows, cols), dtype=bool)
    for ob in scenario.obstacles:
        if not ob.is_static:
            continue
        if ob.is_circle:
            cx, cy = L(np.asarray(ob.shape.center, dtype=float))
            blocked |= np.hypot(xx - cx, yy - cy) < L(ob.shape.radius)
        else:
            poly = shapely.Polygon(L(np.asarray(ob.shape.vertices, dtype=float)))
            blocked |= shapely.contains_xy(poly, xx, yy)
    return blocked
