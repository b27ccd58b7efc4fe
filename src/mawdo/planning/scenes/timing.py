"""Helpers of the scene families where time decides: orientation and waiting spots.

Each family draws its layout in one frame (e.g. traffic along x); :func:`orient` then turns the
whole draft by one of the square map's eight symmetries, drawn from the scene's stream, so the
same family gives corridors in every direction. :func:`lattice_spots` adds free points of a
regular lattice as waiting spots for the earliest-arrival reference ``T*`` (more vertices where
the robot may stop or turn: ``T*`` closer to the continuous optimum).
"""

from __future__ import annotations

import numpy as np
import shapely

from mawdo.planning.scenes.base import Param

__all__ = ["TIME_PARAMS", "lattice_spots", "orient", "speed_params", "timing_margin"]

#: Parameters shared by the timed families (scale-free: relative to the map or the robot).
TIME_PARAMS = (
    Param("lattice", 6, 0, 12, integer=True, doc="waiting spots: a k x k lattice of free points"),
)


def speed_params(slow: float, fast: float, who: str, low: float = 0.05) -> tuple[Param, Param]:
    """``speed_min`` and ``speed_max`` of the family's ``who`` (relative to the robot's speed,
    in ``[low, 4]``), with the given defaults."""
    return (
        Param("speed_min", slow, low, 4.0, doc=f"slowest {who} speed / robot speed"),
        Param("speed_max", fast, low, 4.0, doc=f"fastest {who} speed / robot speed"),
    )


def timing_margin(p: dict) -> float:
    """Distance (px) of start and goal from the border: 4 % of the map, at least the robot's
    radius + clearance + 1."""
    return max(0.04 * p["size"], p["robot_radius"] + p["clearance"] + 1.0)


def _map_point(M: np.ndarray, c: float):
    return lambda q: (c + (np.asarray(q, float) - c) @ M.T).tolist()


def orient(rng: np.random.Generator, data: dict, size: float) -> dict:
    """The draft turned by a random symmetry of the ``size x size`` map (in place; returned).

    Points (start, goal, circle centres, polygon vertices, ``_spots``) turn about the map's
    centre, vectors (velocities, patrol offsets) by the same linear map.
    """
    k = int(rng.integers(4))
    rot = np.linalg.matrix_power(np.array([[0.0, -1.0], [1.0, 0.0]]), k)
    M = rot @ np.diag([1.0, -1.0]) if rng.random() < 0.5 else rot
    point, vec = _map_point(M, 0.5 * size), _map_point(M, 0.0)
    data["start"], data["goal"] = point(data["start"]), point(data["goal"])
    if "_spots" in data:
        data["_spots"] = point(np.reshape(data["_spots"], (-1, 2)))
    for ob in data["obstacles"]:
        if ob["shape"] == "circle":
            ob["center"] = point(ob["center"])
        else:
            ob["vertices"] = point(ob["vertices"])
        motion = ob.get("motion", {})
        if "velocity" in motion:
            motion["velocity"] = vec(motion["velocity"])
        if "waypoints" in motion:
            motion["waypoints"] = vec(motion["waypoints"])
    return data


def lattice_spots(p: dict, obstacles: list[dict], k: int) -> np.ndarray:
    """Points of a ``k x k`` lattice over the map (cell centres) that the robot may occupy:
    at least ``robot_radius + 1`` px from the border and from every static obstacle (pixels;
    shape ``(j, 2)``)."""
    if k == 0:
        return np.zeros((0, 2))
    s, need = p["size"], p["robot_radius"] + 1.0
    g = (np.arange(k) + 0.5) * s / k
    pts = np.stack(np.meshgrid(g, g), axis=-1).reshape(-1, 2)
    pts = pts[np.all((pts >= need) & (pts <= s - need), axis=1)]
    statics = [
        shapely.Point(ob["center"]).buffer(ob["radius"], 64)
        if ob["shape"] == "circle"
        else shapely.Polygon(ob["vertices"])
        for ob in obstacles
        if "motion" not in ob
    ]
    if not statics:
        return pts
    union = shapely.union_all(statics)
    free = shapely.distance(union, shapely.points(pts)) > need
    return pts[free]
