"""Static scene families: open, forest, rooms, maze (u_trap and narrow: :mod:`.traps`).

Every family draws on a ``size x size`` map (pixels) and returns a scenario draft; the common
machinery (:mod:`mawdo.planning.scenes.base`) validates it and computes ``L*``.
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from mawdo.planning.scenes.base import Family, Param, Redraw, draft
from mawdo.planning.scenes.shapes import (
    box,
    circle,
    convex_polygon,
    diagonal_endpoints,
    place,
    polygon,
)

__all__ = ["FOREST", "MAZE", "OPEN", "ROOMS"]


def _margin(p: dict) -> float:
    """Distance of the endpoints from the map border (pixels)."""
    return max(0.04 * p["size"], p["robot_radius"] + p["clearance"] + 1.0)


def _clear_of(points, p: dict, extra: float = 1.0) -> list:
    return [(pt, p["robot_radius"] + p["clearance"] + extra) for pt in points]


def _range_check(p: dict, lo: str, hi: str) -> None:
    if p[lo] > p[hi]:
        raise ValueError(f"{lo} = {p[lo]:g} must be <= {hi} = {p[hi]:g}")


# --- open: scattered convex polygons --------------------------------------------------------


def _draw_open(rng: np.random.Generator, p: dict) -> dict:
    start, goal = diagonal_endpoints(rng, p, _margin(p))
    s = p["size"]

    def one(rng):
        v = convex_polygon(rng, rng.uniform(0.1 * s, 0.9 * s, 2), rng.uniform(p["rmin"], p["rmax"]))
        shape = shapely.Polygon(v)
        return polygon(v), lambda pt: shape.distance(shapely.Point(pt))

    keep = _clear_of([start, goal], p)
    return draft(p, start, goal, [place(rng, one, keep) for _ in range(p["n"])])


OPEN = Family(
    "open",
    "scattered random convex polygons (4-8 vertices) between opposite corners",
    (
        Param("n", 6, 1, 30, integer=True, doc="number of polygons"),
        Param("rmin", 20.0, 5.0, 150.0, doc="smallest circumradius, pixels"),
        Param("rmax", 45.0, 5.0, 150.0, doc="largest circumradius, pixels"),
    ),
    _draw_open,
    check=lambda p: _range_check(p, "rmin", "rmax"),
)


# --- forest: many small discs ---------------------------------------------------------------


def _draw_forest(rng: np.random.Generator, p: dict) -> dict:
    start, goal = diagonal_endpoints(rng, p, _margin(p))
    s = p["size"]

    def one(rng):
        c, rad = rng.uniform(0.0, s, 2), float(rng.uniform(p["rmin"], p["rmax"]))
        return circle(c, rad), lambda pt: math.dist(pt, c) - rad

    keep = _clear_of([start, goal], p)
    return draft(p, start, goal, [place(rng, one, keep) for _ in range(p["n"])])


FOREST = Family(
    "forest",
    "many small static discs (trees) scattered uniformly",
    (
        Param("n", 30, 5, 200, integer=True, doc="number of trees"),
        Param("rmin", 4.0, 1.0, 30.0, doc="smallest tree radius, pixels"),
        Param("rmax", 10.0, 1.0, 30.0, doc="largest tree radius, pixels"),
    ),
    _draw_forest,
    check=lambda p: _range_check(p, "rmin", "rmax"),
)


# --- rooms: a grid of rooms, doors on a random spanning tree plus extra doors ---------------


def _spanning_doors(rng: np.random.Generator, rows: int, cols: int, extra: float) -> set:
    """Walls (pairs of adjacent rooms) that get a door: a random spanning tree + extras."""
    walls = [((i, j), (i, j + 1)) for i in range(rows) for j in range(cols - 1)]
    walls += [((i, j), (i + 1, j)) for i in range(rows - 1) for j in range(cols)]
    order = rng.permutation(len(walls))
    parent = {(i, j): (i, j) for i in range(rows) for j in range(cols)}

    def root(a):
        while parent[a] != a:
            a = parent[a]
        return a

    doors = set()
    for k in order:  # Kruskal with random order: a uniform-ish random spanning tree
        a, b = walls[k]
        ra, rb = root(a), root(b)
        if ra != rb:
            parent[ra] = rb
            doors.add(walls[k])
        elif rng.random() < extra:
            doors.add(walls[k])
    return doors


def _wall_with_door(lo, hi, fixed, t, door, has_door, rng, vertical) -> list[dict]:
    """Boxes of one wall segment along ``[lo, hi]`` at ``fixed``, minus a door if any."""
    spans = [(lo, hi)]
    if has_door:
        d0 = rng.uniform(lo + t, hi - t - door)
        spans = [(lo, d0), (d0 + door, hi)]
    out = []
    for a, b in spans:
        if vertical:
            out.append(box(fixed - t / 2, a, fixed + t / 2, b))
        else:
            out.append(box(a, fixed - t / 2, b, fixed + t / 2))
    return out


def _draw_rooms(rng: np.random.Generator, p: dict) -> dict:
    rows, cols, t, s = p["rows"], p["cols"], p["thickness"], p["size"]
    cw, ch = s / cols, s / rows
    doors = _spanning_doors(rng, rows, cols, p["extra_doors"])
    obs = []
    for i in range(rows):
        for j in range(cols):
            if j + 1 < cols:  # vertical wall east of room (i, j)
                has = ((i, j), (i, j + 1)) in doors
                obs += _wall_with_door(
                    i * ch, (i + 1) * ch, (j + 1) * cw, t, p["door"], has, rng, True
                )
            if i + 1 < rows:  # horizontal wall north of room (i, j)
                has = ((i, j), (i + 1, j)) in doors
                obs += _wall_with_door(
                    j * cw, (j + 1) * cw, (i + 1) * ch, t, p["door"], has, rng, False
                )
    m = t / 2 + p["robot_radius"] + p["clearance"] + 1.0
    start = rng.uniform([m, m], [cw - m, ch - m])
    goal = s - rng.uniform([m, m], [cw - m, ch - m])
    return draft(p, start, goal, obs)


def _check_rooms(p: dict) -> None:
    if p["door"] <= 2 * p["robot_radius"]:
        raise ValueError(
            f"rooms door = {p['door']:g} px must be wider than the robot "
            f"(2 x robot_radius = {2 * p['robot_radius']:g} px)"
        )
    room = p["size"] / max(p["rows"], p["cols"])
    need = p["thickness"] + 2 * (p["robot_radius"] + p["clearance"] + 1.0)
    if need >= room:
        raise ValueError(
            f"rooms of {room:g} px leave no room for the robot beside the walls ({need:g} px): "
            "fewer rooms, thinner walls or a larger size"
        )
    if p["door"] + 2 * p["thickness"] >= room:
        raise ValueError(
            f"rooms door + 2 x thickness = {p['door'] + 2 * p['thickness']:g} px must be "
            f"smaller than a room side ({room:g} px): fewer rooms or a larger size"
        )


ROOMS = Family(
    "rooms",
    "a grid of rooms; walls with doors on a random spanning tree plus extra doors",
    (
        Param("rows", 3, 2, 6, integer=True, doc="rooms per column"),
        Param("cols", 3, 2, 6, integer=True, doc="rooms per row"),
        Param("thickness", 6.0, 2.0, 20.0, doc="wall thickness, pixels"),
        Param("door", 28.0, 4.0, 100.0, doc="door width, pixels"),
        Param("extra_doors", 0.3, 0.0, 1.0, doc="probability of a door in a non-tree wall"),
    ),
    _draw_rooms,
    check=_check_rooms,
)


# --- maze: serpentine walls with alternating gaps -------------------------------------------


def _draw_maze(rng: np.random.Generator, p: dict) -> dict:
    k, t, gap, s = p["walls"], p["thickness"], p["gap"], p["size"]
    pitch = s / (k + 1)
    ys = pitch * np.arange(1, k + 1) + rng.uniform(-0.2, 0.2, k) * pitch
    first_right = rng.random() < 0.5
    obs = []
    for n, y in enumerate(ys):
        gap_right = (n % 2 == 0) == first_right
        x0, x1 = (0.0, s - gap) if gap_right else (gap, s)
        obs.append(box(x0, y - t / 2, x1, y + t / 2))
    m, need = _margin(p), t / 2 + p["robot_radius"] + p["clearance"] + 1.0
    if ys[0] - need < m or ys[-1] + need > s - m:
        raise Redraw("no room for start or goal beyond the outer walls")
    start = rng.uniform([m, m], [s - m, ys[0] - need])
    goal = rng.uniform([m, ys[-1] + need], [s - m, s - m])
    return draft(p, start, goal, obs)


def _check_maze(p: dict) -> None:
    if p["gap"] <= 2 * p["robot_radius"]:
        raise ValueError(
            f"maze gap = {p['gap']:g} px must be wider than the robot "
            f"(2 x robot_radius = {2 * p['robot_radius']:g} px)"
        )
    pitch = p["size"] / (p["walls"] + 1)
    need = p["thickness"] + 2 * (p["robot_radius"] + p["clearance"]) + 2
    if 0.6 * pitch <= need:
        raise ValueError(
            f"maze walls = {p['walls']} leave corridors of ~{0.6 * pitch:.0f} px, too narrow for "
            f"the robot and walls ({need:.0f} px): fewer walls or a larger size"
        )


MAZE = Family(
    "maze",
    "serpentine: horizontal walls with gaps on alternating sides",
    (
        Param("walls", 4, 1, 12, integer=True, doc="number of walls"),
        Param("thickness", 8.0, 2.0, 30.0, doc="wall thickness, pixels"),
        Param("gap", 34.0, 4.0, 150.0, doc="width of each wall's gap, pixels"),
    ),
    _draw_maze,
    check=_check_maze,
)
