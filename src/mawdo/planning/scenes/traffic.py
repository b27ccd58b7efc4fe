"""Scene families with moving obstacles: crossing (timed to meet the robot) and dense traffic.

Obstacle speeds are relative to the robot's speed (``0.5`` = half as fast). Static obstacles of
these families are convex polygons; ``L*`` only sees them (a lower bound for the dynamic
problem).
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from mawdo.planning.scenes.base import Family, Param, Redraw, draft
from mawdo.planning.scenes.shapes import circle, convex_polygon, diagonal_endpoints, place, polygon

__all__ = ["CROSSING", "DENSE", "crosser", "moving_disc", "range_check", "static_polygons"]


def _margin(p: dict) -> float:
    return max(0.04 * p["size"], p["robot_radius"] + p["clearance"] + 1.0)


def range_check(*pairs):
    """A family check: for each ``(lo, hi)`` pair of parameter names, ``p[lo] <= p[hi]``."""

    def check(p: dict) -> None:
        for lo, hi in pairs:
            if p[lo] > p[hi]:
                raise ValueError(f"{lo} = {p[lo]:g} must be <= {hi} = {p[hi]:g}")

    return check


def static_polygons(rng, p: dict, count: int, start, goal) -> list[dict]:
    """``count`` static convex polygons (circumradius 15-35 px) clear of start and goal."""
    s = p["size"]
    keep = [(pt, p["robot_radius"] + p["clearance"] + 1.0) for pt in (start, goal)]

    def one(rng):
        v = convex_polygon(rng, rng.uniform(0.1 * s, 0.9 * s, 2), rng.uniform(15.0, 35.0))
        shape = shapely.Polygon(v)
        return polygon(v), lambda pt: shape.distance(shapely.Point(pt))

    return [place(rng, one, keep) for _ in range(count)]


def _inside(c, rad: float, s: float) -> bool:
    return bool(np.all(c - rad >= 0.0) and np.all(c + rad <= s))


def crosser(rng, p: dict, start, d, dist: float) -> dict:
    """A disc that reaches the straight start-goal line exactly when the robot does there.

    Along the line the robot is at ``start + v t d``; the disc aims at the point at fraction
    ``u`` and arrives at ``T = u dist / v``. It starts at ``P - w T`` and moves in a straight line
    inside the map until then (no border reflection before the meeting).
    """
    s, v = p["size"], p["robot_speed"]
    n = np.array([-d[1], d[0]])
    keep = p["robot_radius"] + p["clearance"] + 1.0
    for _ in range(40):
        u = rng.uniform(0.2, 0.8)
        rad = float(rng.uniform(p["rmin"], p["rmax"]))
        speed = rng.uniform(p["speed_min"], p["speed_max"]) * v
        side = 1.0 if rng.random() < 0.5 else -1.0
        ang = rng.uniform(-np.pi / 4, np.pi / 4)  # up to 45 degrees off perpendicular
        heading = side * (math.cos(ang) * n + math.sin(ang) * d)
        meet = start + u * dist * d
        t_meet = u * dist / v
        c0 = meet - heading * speed * t_meet
        if not (_inside(c0, rad, s) and _inside(meet, rad, s)):
            continue
        if min(math.dist(c0, start), math.dist(c0, start + dist * d)) <= rad + keep:
            continue
        return circle(
            c0, rad, {"model": "constant_velocity", "velocity": (heading * speed).tolist()}
        )
    raise Redraw("no crossing obstacle fits in the map (speeds too low or radii too large)")


def _draw_crossing(rng: np.random.Generator, p: dict) -> dict:
    start, goal = diagonal_endpoints(rng, p, _margin(p))
    d = goal - start
    dist = float(np.hypot(*d))
    d /= dist
    obs = [crosser(rng, p, start, d, dist) for _ in range(p["n"])]
    obs += static_polygons(rng, p, p["statics"], start, goal)
    return draft(p, start, goal, obs)


_SPEEDS = (
    Param("speed_min", 0.3, 0.05, 2.0, doc="slowest obstacle speed / robot speed"),
    Param("speed_max", 0.8, 0.05, 2.0, doc="fastest obstacle speed / robot speed"),
)

CROSSING = Family(
    "crossing",
    "discs that cross the straight start-goal line exactly when the robot gets there",
    (
        Param("n", 4, 1, 16, integer=True, doc="crossing discs"),
        Param("rmin", 8.0, 2.0, 40.0, doc="smallest disc radius, pixels"),
        Param("rmax", 16.0, 2.0, 40.0, doc="largest disc radius, pixels"),
        *_SPEEDS,
        Param("statics", 0, 0, 10, integer=True, doc="static convex polygons"),
    ),
    _draw_crossing,
    moving=True,
    check=range_check(("rmin", "rmax"), ("speed_min", "speed_max")),
)


def moving_disc(rng, p: dict, start, goal) -> dict:
    """A disc with a constant velocity or a random walk, kept away from start and goal at t = 0
    by its radius + the robot's + clearance + 10 steps of its own motion."""
    s, v = p["size"], p["robot_speed"]
    for _ in range(40):
        rad = float(rng.uniform(p["rmin"], p["rmax"]))
        speed = float(rng.uniform(p["speed_min"], p["speed_max"]) * v)
        c = rng.uniform(rad, s - rad, 2)
        keep = rad + p["robot_radius"] + p["clearance"] + 10.0 * speed
        if min(math.dist(c, start), math.dist(c, goal)) <= keep:
            continue
        if rng.random() < p["walkers"]:
            motion = {
                "model": "bounded_random_walk",
                "step": speed,
                "hold": int(rng.integers(5, 21)),
            }
        else:
            ang = rng.uniform(0.0, 2.0 * np.pi)
            motion = {
                "model": "constant_velocity",
                "velocity": [speed * math.cos(ang), speed * math.sin(ang)],
            }
        return circle(c, rad, motion)
    raise Redraw("no room for a moving disc away from start and goal")


def _draw_dense(rng: np.random.Generator, p: dict) -> dict:
    start, goal = diagonal_endpoints(rng, p, _margin(p))
    obs = static_polygons(rng, p, p["statics"], start, goal)
    obs += [moving_disc(rng, p, start, goal) for _ in range(p["n"])]
    return draft(p, start, goal, obs)


DENSE = Family(
    "dense",
    "dense traffic: many moving discs (constant velocity or random walk) and a few statics",
    (
        Param("n", 24, 2, 100, integer=True, doc="moving discs"),
        Param("rmin", 5.0, 2.0, 30.0, doc="smallest disc radius, pixels"),
        Param("rmax", 10.0, 2.0, 30.0, doc="largest disc radius, pixels"),
        Param("speed_min", 0.15, 0.0, 2.0, doc="slowest obstacle speed / robot speed"),
        Param("speed_max", 0.5, 0.0, 2.0, doc="fastest obstacle speed / robot speed"),
        Param("walkers", 0.3, 0.0, 1.0, doc="fraction of discs on a random walk"),
        Param("statics", 3, 0, 20, integer=True, doc="static convex polygons"),
    ),
    _draw_dense,
    moving=True,
    check=range_check(("rmin", "rmax"), ("speed_min", "speed_max")),
)
