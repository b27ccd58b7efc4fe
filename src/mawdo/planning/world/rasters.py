"""Scenarios from raster maps: occupancy images (PNG etc.) and MovingAI ``.map`` files.

Blocked cells become static polygon obstacles: each row's runs of blocked cells become boxes,
shapely merges the boxes into connected regions, and each region's outer ring is one polygon
(holes inside a region are filled: they cannot be reached from outside it). Cell ``(row, col)``
with row 0 at the top covers ``x in [col, col + 1] * cell``, ``y in [rows - row - 1, rows - row] *
cell`` (map y points up). Diagonally touching cells are separate regions.

By default only collinear vertices are removed (``simplify_tolerance = 0``), so obstacles are
exactly the blocked cells; a positive tolerance gives fewer vertices (faster cost kernel) but may
shave up to that many pixels off an obstacle.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

from mawdo.planning.world.scenario import (
    SCHEMA_VERSION,
    Scenario,
    ScenarioError,
    scenario_from_dict,
)

__all__ = ["MOVINGAI_BLOCKED", "from_movingai_map", "from_occupancy_image", "grid_to_polygons"]

#: MovingAI terrain characters that block the robot (out of bounds, trees, water).
MOVINGAI_BLOCKED = frozenset("@OTW")
_MOVINGAI_FREE = frozenset(".GS")


def grid_to_polygons(
    blocked, cell: float = 1.0, simplify_tolerance: float = 0.0
) -> list[shapely.Polygon]:
    """Polygons (pixels) covering the connected regions of blocked cells.

    Parameters
    ----------
    blocked : array_like of bool, shape (rows, cols)
        Occupancy, row 0 at the top.
    cell : float
        Cell size (pixels), > 0.
    simplify_tolerance : float
        Douglas-Peucker tolerance (pixels); 0 removes collinear vertices only.
    """
    blocked = np.asarray(blocked, dtype=bool)
    rows = blocked.shape[0]
    boxes = []
    for i, row in enumerate(blocked):
        # runs of True: +1 where a run starts, -1 one past where it ends
        edges = np.diff(np.concatenate([[0], row.astype(np.int8), [0]]))
        starts = np.nonzero(edges == 1)[0]
        ends = np.nonzero(edges == -1)[0]
        y0, y1 = (rows - i - 1) * cell, (rows - i) * cell
        boxes.extend(
            shapely.box(s * cell, y0, e * cell, y1) for s, e in zip(starts, ends, strict=True)
        )
    if not boxes:
        return []
    merged = shapely.union_all(boxes)
    out = []
    for poly in getattr(merged, "geoms", [merged]):
        filled = shapely.Polygon(poly.exterior)
        filled = filled.simplify(simplify_tolerance, preserve_topology=True)
        if not filled.is_empty and filled.area > 0:
            out.append(shapely.geometry.polygon.orient(filled, 1.0))
    return out


def _scenario_from_polygons(
    polygons, width, height, start, goal, name, robot_radius, robot_speed, source
) -> Scenario:
    data = {
        "schema_version": SCHEMA_VERSION,
        "name": name,
        "width": width,
        "height": height,
        "start": list(map(float, start)),
        "goal": list(map(float, goal)),
        "robot": {"radius": robot_radius, "speed": robot_speed},
        "obstacles": [
            {"shape": "polygon", "vertices": np.asarray(p.exterior.coords)[:-1].tolist()}
            for p in polygons
        ],
    }
    return scenario_from_dict(data, source=source)


def from_occupancy_image(
    path,
    *,
    start,
    goal,
    threshold: float = 0.5,
    cell: float = 1.0,
    robot_radius: float = 4.0,
    robot_speed: float = 4.0,
    simplify_tolerance: float = 0.0,
    name: str | None = None,
) -> Scenario:
    """A static scenario from an occupancy image: dark pixels are obstacles.

    Parameters
    ----------
    path : str or Path
        Image file (anything Pillow reads; PNG recommended).
    start, goal : array_like, shape (2,)
        Start and goal (pixels, map coordinates with y up).
    threshold : float
        A pixel is blocked when its grey level is below ``threshold * 255``.
    cell : float
        Map pixels per image pixel.
    robot_radius, robot_speed : float
        Robot disc radius (pixels) and speed (pixels per time step).
    simplify_tolerance : float
        See :func:`grid_to_polygons`.
    name : str, optional
        Scenario name (default the file stem).

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    ScenarioError
        If the file cannot be read as an image, or the scenario is invalid (e.g. start inside
        a dark region).
    """
    from PIL import Image, UnidentifiedImageError

    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such image file: {str(path)!r}")
    try:
        with Image.open(path) as img:
            grey = np.asarray(img.convert("L"), dtype=float)
    except (OSError, UnidentifiedImageError, ValueError) as exc:
        raise ScenarioError([("", f"cannot read image: {exc}")], str(path)) from None
    if not 0.0 < threshold <= 1.0:
        raise ValueError(f"threshold must be in (0, 1], got {threshold!r}")
    if not cell > 0:
        raise ValueError(f"cell must be > 0, got {cell!r}")
    polygons = grid_to_polygons(grey < threshold * 255.0, cell, simplify_tolerance)
    rows, cols = grey.shape
    return _scenario_from_polygons(
        polygons,
        cols * cell,
        rows * cell,
        start,
        goal,
        name or path.stem,
        robot_radius,
        robot_speed,
        str(path),
    )


def read_movingai_grid(path) -> np.ndarray:
    """Blocked cells of a MovingAI ``.map`` file (bool, shape (height, width), row 0 at top).

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    ScenarioError
        If the file cannot be read or is not in the MovingAI format.
    """
    path = Path(path)
    src = str(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such map file: {src!r}")
    try:
        lines = path.read_text(encoding="ascii").splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise ScenarioError([("", f"cannot read map file: {exc}")], src) from None
    header: dict[str, str] = {}
    i = 0
    while i < len(lines) and lines[i].strip().lower() != "map":
        parts = lines[i].split()
        if len(parts) != 2:
            raise ScenarioError([(f"line {i + 1}", f"expected 'key value', got {lines[i]!r}")], src)
        header[parts[0].lower()] = parts[1]
        i += 1
    if i == len(lines):
        raise ScenarioError([("", "missing the 'map' line that ends the header")], src)
    for key in ("type", "height", "width"):
        if key not in header:
            raise ScenarioError([("", f"header has no {key!r} line")], src)
    try:
        height, width = int(header["height"]), int(header["width"])
    except ValueError:
        raise ScenarioError([("", "height and width must be integers")], src) from None
    if height <= 0 or width <= 0:
        raise ScenarioError([("", f"height and width must be > 0, got {height} x {width}")], src)
    rows = [ln.rstrip("\r\n") for ln in lines[i + 1 :]]
    rows = [r for r in rows if r.strip()]
    if len(rows) != height:
        raise ScenarioError([("", f"expected {height} map rows, found {len(rows)}")], src)
    grid = np.zeros((height, width), dtype=bool)
    for r, row in enumerate(rows):
        if len(row) != width:
            raise ScenarioError(
                [(f"line {i + 2 + r}", f"expected {width} characters, found {len(row)}")], src
            )
        unknown = set(row) - MOVINGAI_BLOCKED - _MOVINGAI_FREE
        if unknown:
            raise ScenarioError(
                [(f"line {i + 2 + r}", f"unknown terrain {''.join(sorted(unknown))!r}")], src
            )
        grid[r] = [ch in MOVINGAI_BLOCKED for ch in row]
    return grid


def from_movingai_map(
    path,
    *,
    start,
    goal,
    cell: float = 1.0,
    robot_radius: float = 4.0,
    robot_speed: float = 4.0,
    simplify_tolerance: float = 0.0,
    name: str | None = None,
) -> Scenario:
    """A static scenario from a MovingAI benchmark ``.map`` file.

    The format is a header (``type octile``, ``height H``, ``width W``, ``map``) and ``H`` rows of
    ``W`` characters; ``@ O T W`` are blocked, ``. G S`` are free.

    Parameters
    ----------
    path : str or Path
        The ``.map`` file.
    start, goal : array_like, shape (2,)
        Start and goal (pixels, map coordinates with y up).
    cell : float
        Map pixels per grid cell.
    robot_radius, robot_speed, simplify_tolerance, name
        As for :func:`from_occupancy_image`.

    Raises
    ------
    ScenarioError
        If the file is malformed or the scenario is invalid.
    """
    if not cell > 0:
        raise ValueError(f"cell must be > 0, got {cell!r}")
    grid = read_movingai_grid(path)
    polygons = grid_to_polygons(grid, cell, simplify_tolerance)
    rows, cols = grid.shape
    return _scenario_from_polygons(
        polygons,
        cols * cell,
        rows * cell,
        start,
        goal,
        name or Path(path).stem,
        robot_radius,
        robot_speed,
        str(path),
    )
