"""The ``movingai`` family: MovingAI-format grid maps with moving discs added.

The maps ship as package data (``data/*.map``, made for this package, not downloaded):
``warehouse`` (48 x 48 cells, eight shelves and their aisles) and ``rooms`` (40 x 40 cells, four
rooms joined by doorways, two pillars). They go through the existing loader
(:func:`mawdo.planning.world.rasters.from_movingai_map`), so blocked cells become exact polygons. A
cell is ``size / max(rows, cols)`` pixels. Start and goal are centres of free cells at least
``robot_radius + clearance`` from every blocked cell and at least half the map's diagonal apart;
moving discs start in free space and move with constant velocity (reflecting at the map border,
passing over walls: the scenario motion models know no walls).
"""

from __future__ import annotations

import functools
import math
from importlib import resources

import numpy as np
from scipy.ndimage import distance_transform_edt

from mawdo.planning.scenes.base import Family, Param, Redraw
from mawdo.planning.scenes.shapes import circle
from mawdo.planning.world.rasters import from_movingai_map, read_movingai_grid

__all__ = ["MAPS", "MOVINGAI", "map_grid"]

#: Names of the shipped maps (``data/<name>.map``).
MAPS = ("warehouse", "rooms")


def _map_file(name: str):
    return resources.files("mawdo.planning.scenes").joinpath("data", f"{name}.map")


@functools.cache
def map_grid(name: str) -> np.ndarray:
    """Blocked cells of a shipped map (read-only bool array, row 0 at the top)."""
    with resources.as_file(_map_file(name)) as path:
        grid = read_movingai_grid(path)
    grid.setflags(write=False)
    return grid


@functools.cache
def _free_distance(name: str) -> np.ndarray:
    """Per cell, a lower bound on the distance (cells) from its centre to the nearest blocked
    cell or the map border (the map is padded with a ring of blocked cells)."""
    grid = np.pad(map_grid(name), 1, constant_values=True)
    d = distance_transform_edt(~grid) - math.sqrt(0.5)  # centre-to-centre minus half a diagonal
    d[grid] = -1.0
    d = d[1:-1, 1:-1].copy()
    d.setflags(write=False)
    return d


def _cell_centre(rc, rows: int, cell: float) -> np.ndarray:
    r, c = rc
    return np.array([(c + 0.5) * cell, (rows - r - 0.5) * cell])


def _endpoints(rng, p: dict, cell: float) -> tuple[np.ndarray, np.ndarray]:
    grid = map_grid(p["map"])
    rows, cols = grid.shape
    need = (p["robot_radius"] + p["clearance"] + 1e-6) / cell
    free = np.argwhere(_free_distance(p["map"]) > need)
    if len(free) < 2:
        raise Redraw("no free cell is wide enough for the robot")
    start = _cell_centre(free[rng.integers(len(free))], rows, cell)
    centres = np.column_stack([(free[:, 1] + 0.5) * cell, (rows - free[:, 0] - 0.5) * cell])
    far = np.hypot(*(centres - start).T) >= 0.5 * math.hypot(rows * cell, cols * cell)
    if not np.any(far):
        raise Redraw("no free cell far enough from the start for the goal")
    goal = centres[np.flatnonzero(far)[rng.integers(np.count_nonzero(far))]]
    return start, goal


def _movers(rng, p: dict, cell: float, start, goal) -> list[dict]:
    rows, _ = map_grid(p["map"]).shape
    dist = _free_distance(p["map"])
    out = []
    for _ in range(p["n"]):
        rad = float(rng.uniform(p["rmin"], p["rmax"]))
        speed = float(rng.uniform(p["speed_min"], p["speed_max"]) * p["robot_speed"])
        cand = np.argwhere(dist > rad / cell)
        for _ in range(40):
            c = _cell_centre(cand[rng.integers(len(cand))], rows, cell) if len(cand) else None
            keep = rad + p["robot_radius"] + p["clearance"] + 10.0 * speed
            if c is not None and min(math.dist(c, start), math.dist(c, goal)) > keep:
                break
        else:
            raise Redraw("no free room for a moving disc away from start and goal")
        ang = rng.uniform(0.0, 2.0 * np.pi)
        vel = [speed * math.cos(ang), speed * math.sin(ang)]
        out.append(circle(c, rad, {"model": "constant_velocity", "velocity": vel}))
    return out


def _draw_movingai(rng: np.random.Generator, p: dict) -> dict:
    rows, cols = map_grid(p["map"]).shape
    cell = p["size"] / max(rows, cols)
    start, goal = _endpoints(rng, p, cell)
    with resources.as_file(_map_file(p["map"])) as path:
        static = from_movingai_map(
            path,
            start=start,
            goal=goal,
            cell=cell,
            robot_radius=p["robot_radius"],
            robot_speed=p["robot_speed"],
        )
    data = static.to_dict()
    data["obstacles"] = data["obstacles"] + _movers(rng, p, cell, start, goal)
    return data


def _check(p: dict) -> None:
    for lo, hi in (("rmin", "rmax"), ("speed_min", "speed_max")):
        if p[lo] > p[hi]:
            raise ValueError(f"{lo} = {p[lo]:g} must be <= {hi} = {p[hi]:g}")


MOVINGAI = Family(
    "movingai",
    "a MovingAI-format grid map (shipped: warehouse, rooms) with moving discs",
    (
        Param("map", "warehouse", choices=MAPS, doc="shipped map"),
        Param("n", 4, 0, 30, integer=True, doc="moving discs"),
        Param("rmin", 5.0, 2.0, 20.0, doc="smallest disc radius, pixels"),
        Param("rmax", 9.0, 2.0, 20.0, doc="largest disc radius, pixels"),
        Param("speed_min", 0.2, 0.0, 2.0, doc="slowest disc speed / robot speed"),
        Param("speed_max", 0.6, 0.0, 2.0, doc="fastest disc speed / robot speed"),
    ),
    _draw_movingai,
    moving=True,
    check=_check,
)
