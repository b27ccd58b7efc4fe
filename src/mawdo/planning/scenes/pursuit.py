"""Timed scene families in the open: ``chaser`` (faster than the robot) and ``crowd``.

Speeds are relative to the robot's speed, sizes to its radius or to the map, so the families
scale. Every scene is kept only if its earliest arrival ``T*`` exists (``Family.timed``).
"""

from __future__ import annotations

import math

import numpy as np

from mawdo.planning.scenes.base import Family, Param, Redraw, draft
from mawdo.planning.scenes.shapes import circle, diagonal_endpoints
from mawdo.planning.scenes.timing import (
    TIME_PARAMS,
    lattice_spots,
    orient,
    speed_params,
    timing_margin,
)
from mawdo.planning.scenes.traffic import moving_disc, range_check, static_polygons

__all__ = ["CHASER", "CROWD"]


def _finish(rng, p: dict, start, goal, obs: list[dict]) -> dict:
    data = draft(p, start, goal, obs)
    data["_spots"] = lattice_spots(p, obs, p["lattice"])
    return orient(rng, data, p["size"])


def _line_endpoints(rng, p: dict):
    """Start and goal 45-75 % of the map apart on a line in a random direction through the
    middle of the map, so there is room behind the start (pixels; and the unit direction)."""
    s, m = p["size"], timing_margin(p)
    length = rng.uniform(0.45, 0.75) * s
    ang = rng.uniform(0.0, 2.0 * math.pi)
    d = np.array([math.cos(ang), math.sin(ang)])
    mid = 0.5 * s + rng.uniform(-0.08, 0.08, 2) * s
    start, goal = mid - 0.5 * length * d, mid + 0.5 * length * d
    if not all(np.all((q >= m) & (q <= s - m)) for q in (start, goal)):
        raise Redraw("start or goal too close to the border")
    return start, goal, d


def _chaser(rng, p: dict, start, goal, d) -> dict:
    """A disc faster than the robot, coming from behind along the start-goal line: it would
    catch a robot driving straight at full speed at 15-60 % of the way (bouncing at the border
    afterwards)."""
    s, r, v = p["size"], p["robot_radius"], p["robot_speed"]
    dist = float(np.hypot(*(goal - start)))
    n = np.array([-d[1], d[0]])
    for _ in range(40):
        rad = r * rng.uniform(p["rmin"], p["rmax"])
        k = rng.uniform(p["speed_min"], p["speed_max"])
        t_catch = rng.uniform(0.15, 0.6) * dist / v
        side = rng.uniform(-0.5, 0.5) * (rad + r)  # off the line by less than a hit
        c = start - (k - 1.0) * v * t_catch * d + side * n
        keep = rad + r + p["clearance"] + 1.0
        if not np.all((c >= rad) & (c <= s - rad)) or math.dist(c, start) <= keep:
            continue
        return circle(c, rad, {"model": "constant_velocity", "velocity": (k * v * d).tolist()})
    raise Redraw("no room behind the start for the chaser")


def _draw_chaser(rng: np.random.Generator, p: dict) -> dict:
    start, goal, d = _line_endpoints(rng, p)
    obs = static_polygons(rng, p, int(rng.integers(0, p["statics"] + 1)), start, goal)
    obs += [_chaser(rng, p, start, goal, d) for _ in range(int(rng.integers(1, p["n"] + 1)))]
    return _finish(rng, p, start, goal, obs)


CHASER = Family(
    "chaser",
    "discs faster than the robot that come from behind it along its line, among a few statics",
    (
        Param("n", 1, 1, 4, integer=True, doc="most chasers (at least one)"),
        Param("rmin", 1.5, 0.25, 10.0, doc="smallest chaser radius, robot radii"),
        Param("rmax", 3.0, 0.25, 10.0, doc="largest chaser radius, robot radii"),
        *speed_params(1.2, 2.0, "chaser", low=1.01),
        Param("statics", 4, 0, 12, integer=True, doc="most static convex polygons"),
        *TIME_PARAMS,
    ),
    _draw_chaser,
    moving=True,
    check=range_check(("rmin", "rmax"), ("speed_min", "speed_max")),
    timed=True,
)


def _draw_crowd(rng: np.random.Generator, p: dict) -> dict:
    start, goal = diagonal_endpoints(rng, p, timing_margin(p))
    obs = static_polygons(rng, p, int(rng.integers(0, p["statics"] + 1)), start, goal)
    r = p["robot_radius"]
    # small discs at random constant velocities (the dense family's movers, no walkers)
    q = {**p, "rmin": r * p["rmin"], "rmax": r * p["rmax"], "walkers": 0.0}
    n = int(rng.integers(p["n_min"], p["n_max"] + 1))
    obs += [moving_disc(rng, q, start, goal) for _ in range(n)]
    return _finish(rng, p, start, goal, obs)


CROWD = Family(
    "crowd",
    "30-60 small discs at random constant velocities (bouncing at the border)",
    (
        Param("n_min", 30, 1, 200, integer=True, doc="fewest moving discs"),
        Param("n_max", 60, 1, 200, integer=True, doc="most moving discs"),
        Param("rmin", 0.5, 0.1, 5.0, doc="smallest disc radius, robot radii"),
        Param("rmax", 1.25, 0.1, 5.0, doc="largest disc radius, robot radii"),
        *speed_params(0.2, 0.8, "disc", low=0.0),
        Param("statics", 2, 0, 12, integer=True, doc="most static convex polygons"),
        *TIME_PARAMS,
    ),
    _draw_crowd,
    moving=True,
    check=range_check(("n_min", "n_max"), ("rmin", "rmax"), ("speed_min", "speed_max")),
    timed=True,
)
