"""Timed scene families in corridors and doors: ``corridor``, ``parked``, ``doorway``, ``slalom``.

Each is drawn with the traffic along +x, then turned by a random symmetry of the map
(:func:`~mawdo.planning.scenes.timing.orient`). Sizes are relative to the map side or to the
robot's radius, speeds to the robot's speed, so the families scale. Every scene is kept only if
its earliest arrival ``T*`` exists (``Family.timed``).
"""

from __future__ import annotations

import numpy as np

from mawdo.planning.scenes.base import Family, Param, Redraw, draft
from mawdo.planning.scenes.shapes import box, circle
from mawdo.planning.scenes.timing import (
    TIME_PARAMS,
    lattice_spots,
    orient,
    speed_params,
    timing_margin,
)
from mawdo.planning.scenes.traffic import range_check

__all__ = ["CORRIDOR", "DOORWAY", "PARKED", "SLALOM"]

#: Time a parked mover stays in its garage once it has left (time steps): longer than any run.
GARAGE_STAY = 1e6


def _ends(rng, p: dict, x0: float, x1: float):
    """Start left of ``x0``, goal right of ``x1`` (pixels), anywhere in height."""
    s, m = p["size"], timing_margin(p)
    need = p["robot_radius"] + p["clearance"] + 1.0
    if x0 - need < m or x1 + need > s - m:
        raise Redraw("no room for start or goal beside the walls")
    start = rng.uniform([m, m], [x0 - need, s - m])
    goal = rng.uniform([x1 + need, m], [s - m, s - m])
    return start, goal


def _finish(rng, p: dict, start, goal, obs: list[dict], spots) -> dict:
    data = draft(p, start, goal, obs)
    data["_spots"] = np.vstack([np.reshape(spots, (-1, 2)), lattice_spots(p, obs, p["lattice"])])
    return orient(rng, data, p["size"])


def _notches(rng, x0: float, x1: float, widths) -> list[tuple[float, int]]:
    """Non-overlapping notches ``(centre x, side +-1)`` of the given widths along ``[x0, x1]``."""
    out: list[tuple[float, int]] = []
    for w in widths:
        for _ in range(30):
            xc, side = rng.uniform(x0 + w, x1 - w), 1 if rng.random() < 0.5 else -1
            if all(abs(xc - xo) > 0.5 * (w + wo) + 2.0 for xo, _, wo in out):
                out.append((xc, side, w))
                break
        else:
            raise Redraw("the corridor's bays do not fit beside each other")
    return [(xc, side) for xc, side, _ in out]


def _slab(xa: float, xb: float, ya: float, yb: float) -> dict:
    lo, hi = sorted((ya, yb))
    return box(xa, lo, xb, hi)


def _walls(p: dict, lane, notches, widths, depths) -> list[dict]:
    """The two walls of a corridor ``lane = (x0, x1, yc, w)``, each from the corridor to the
    map's border, with rectangular notches (bays) of the given widths and depths cut in."""
    x0, x1, yc, w = lane
    obs = []
    for side in (1, -1):
        edge, far = yc + side * 0.5 * w, (p["size"] if side == 1 else 0.0)
        xa = x0
        for j in sorted(range(len(notches)), key=lambda j: notches[j][0]):
            xc, sd = notches[j]
            if sd != side:
                continue
            obs.append(_slab(xa, xc - 0.5 * widths[j], edge, far))
            obs.append(
                _slab(xc - 0.5 * widths[j], xc + 0.5 * widths[j], edge + side * depths[j], far)
            )
            xa = xc + 0.5 * widths[j]
        obs.append(_slab(xa, x1, edge, far))
    return obs


def _width(rng, p: dict) -> float:
    """A corridor width (px): ``width_min`` to ``width_max`` robot diameters."""
    return 2.0 * p["robot_radius"] * rng.uniform(p["width_min"], p["width_max"])


def _lane(rng, p: dict, depth: float, w: float):
    """A corridor ``(x0, x1, yc, w)`` of width ``w``: 45-70 % of the map long, with room for
    notches ``depth`` px deep on both sides."""
    s = p["size"]
    length = rng.uniform(0.45, 0.7) * s
    x0 = rng.uniform(0.12 * s, 0.88 * s - length)
    room = 0.5 * w + depth + 0.03 * s
    if room >= 0.5 * s:
        raise Redraw("the corridor and its bays do not fit in the map")
    yc = rng.uniform(max(room, 0.25 * s), min(s - room, 0.75 * s))
    return x0, x0 + length, yc, w


def _bays(rng, p: dict, count: int):
    """Widths and depths (px) of ``count`` bays deep enough to hide the robot from a mover
    filling the lane."""
    r = p["robot_radius"]
    return 2 * r * rng.uniform(1.4, 2.2, count) + 2.0, 2 * r * rng.uniform(1.2, 2.0, count) + 2.0


def _bay_spots(lane, notches, depths, r: float) -> np.ndarray:
    """The deepest free point of each bay (pixels): one robot radius + 1 px from its end."""
    _, _, yc, w = lane
    out = [
        (xc, yc + side * (0.5 * w + depths[j] - r - 1.0)) for j, (xc, side) in enumerate(notches)
    ]
    return np.reshape(np.asarray(out, float), (-1, 2))


def _draw_corridor(rng: np.random.Generator, p: dict) -> dict:
    r, v = p["robot_radius"], p["robot_speed"]
    widths, depths = _bays(rng, p, int(rng.integers(p["bays_min"], p["bays_max"] + 1)))
    lane = _lane(rng, p, float(depths.max()), _width(rng, p))
    x0, x1, yc, w = lane
    notches = _notches(rng, x0, x1, widths)
    obs = _walls(p, lane, notches, widths, depths)
    start, goal = _ends(rng, p, x0, x1)
    n = int(rng.integers(1, p["oncoming"] + 1))
    # oncoming discs fill the lane (a robot cannot pass beside one) and head for the start
    xs = np.sort(rng.uniform(x0 + 0.4 * (x1 - x0), 0.5 * (x1 + p["size"]), n))
    for x in xs:
        rad = max(0.5 * w - r * rng.uniform(0.3, 1.0), 1.0)
        speed = rng.uniform(p["speed_min"], p["speed_max"]) * v
        obs.append(circle((x, yc), rad, {"model": "constant_velocity", "velocity": [-speed, 0.0]}))
    return _finish(rng, p, start, goal, obs, _bay_spots(lane, notches, depths, r))


_LANE_PARAMS = (
    Param("width_min", 1.5, 1.05, 4.0, doc="narrowest corridor, robot diameters"),
    Param("width_max", 2.3, 1.05, 4.0, doc="widest corridor, robot diameters"),
    *speed_params(0.3, 0.9, "mover"),
)


CORRIDOR = Family(
    "corridor",
    "the only corridor, with oncoming discs that fill it and side bays to wait in",
    (
        *_LANE_PARAMS,
        Param("bays_min", 1, 1, 4, integer=True, doc="fewest side bays"),
        Param("bays_max", 3, 1, 4, integer=True, doc="most side bays"),
        Param("oncoming", 2, 1, 4, integer=True, doc="most oncoming discs (at least one)"),
        *TIME_PARAMS,
    ),
    _draw_corridor,
    moving=True,
    check=range_check(
        ("width_min", "width_max"), ("speed_min", "speed_max"), ("bays_min", "bays_max")
    ),
    timed=True,
)


def _draw_parked(rng: np.random.Generator, p: dict) -> dict:
    r, v = p["robot_radius"], p["robot_speed"]
    w = _width(rng, p)
    rad = max(0.5 * w - r * rng.uniform(0.3, 0.9), 1.0)  # fills the lane
    g_w, g_d = 2 * rad + 2.0 + r * rng.uniform(0.5, 1.5, 2)  # the garage it leaves into
    widths, depths = _bays(rng, p, int(rng.integers(0, p["bays"] + 1)))
    widths, depths = np.r_[g_w, widths], np.r_[g_d, depths]
    lane = _lane(rng, p, float(depths.max()), w)
    x0, x1, yc, _ = lane
    notches = _notches(rng, x0 + 0.2 * (x1 - x0), x1 - 0.2 * (x1 - x0), widths[:1])
    notches += _notches(rng, x0, x1, widths[1:]) if len(widths) > 1 else []
    if len(notches) > 1 and min(abs(notches[0][0] - xo) for xo, _ in notches[1:]) < g_w:
        raise Redraw("a bay overlaps the garage")
    obs = _walls(p, lane, notches, widths, depths)
    start, goal = _ends(rng, p, x0, x1)
    xg, side = notches[0]
    # parked across the lane until the robot would be there, and longer, then into the garage
    reach = float(np.hypot(xg - start[0], yc - start[1])) / v
    dwell = reach * rng.uniform(p["dwell_min"], p["dwell_max"])
    motion = {
        "model": "patrol",
        "waypoints": [[0.0, side * (0.5 * w + 0.5 * g_d)]],
        "speed": rng.uniform(p["speed_min"], p["speed_max"]) * v,
        "waits": [dwell, GARAGE_STAY],
    }
    obs.append(circle((xg, yc), rad, motion))
    return _finish(rng, p, start, goal, obs, _bay_spots(lane, notches[1:], depths[1:], r))


PARKED = Family(
    "parked",
    "a disc parked across the only corridor that drives off into a garage after a while",
    (
        *_LANE_PARAMS,
        Param("bays", 1, 0, 3, integer=True, doc="most side bays besides the garage"),
        Param("dwell_min", 1.1, 0.0, 10.0, doc="shortest stop / robot's time to reach it"),
        Param("dwell_max", 2.0, 0.0, 10.0, doc="longest stop / robot's time to reach it"),
        *TIME_PARAMS,
    ),
    _draw_parked,
    moving=True,
    check=range_check(
        ("width_min", "width_max"), ("speed_min", "speed_max"), ("dwell_min", "dwell_max")
    ),
    timed=True,
)


def _draw_doorway(rng: np.random.Generator, p: dict) -> dict:
    s, r = p["size"], p["robot_radius"]
    xw, t = rng.uniform(0.35, 0.65) * s, rng.uniform(0.03, 0.07) * s
    g = 2.0 * r * rng.uniform(p["door_min"], p["door_max"])
    yd = rng.uniform(0.2, 0.8) * s
    obs = [box(xw - 0.5 * t, 0.0, xw + 0.5 * t, yd - 0.5 * g)]
    obs.append(box(xw - 0.5 * t, yd + 0.5 * g, xw + 0.5 * t, s))
    start, goal = _ends(rng, p, xw - 0.5 * t, xw + 0.5 * t)
    rad = 0.5 * g + r * rng.uniform(0.5, 1.5)  # covers the door
    amp = rng.uniform(1.5, 3.0) * (rad + 0.5 * g)
    x = xw + rng.uniform(-1.0, 1.0) * (0.5 * t + 0.5 * rad)  # in the door or just before it
    obs.append(_up_and_down(rng, p, x, rad, max(yd - amp, rad + 1.0), min(yd + amp, s - rad - 1.0)))
    return _finish(rng, p, start, goal, obs, ())


def _up_and_down(rng, p: dict, x: float, rad: float, lo: float, hi: float) -> dict:
    """A disc patrolling the line ``x`` between heights ``lo`` and ``hi`` (pixels) at a drawn
    speed, from a drawn height at ``t = 0``."""
    y0 = rng.uniform(lo, hi)
    motion = {
        "model": "patrol",
        "waypoints": [[0.0, lo - y0], [0.0, hi - y0]],
        "speed": rng.uniform(p["speed_min"], p["speed_max"]) * p["robot_speed"],
    }
    return circle((x, y0), rad, motion)


DOORWAY = Family(
    "doorway",
    "a wall with one door and a disc patrolling across it",
    (
        Param("door_min", 1.2, 1.02, 4.0, doc="narrowest door, robot diameters"),
        Param("door_max", 2.0, 1.02, 4.0, doc="widest door, robot diameters"),
        *speed_params(0.3, 0.9, "patrol"),
        *TIME_PARAMS,
    ),
    _draw_doorway,
    moving=True,
    check=range_check(("door_min", "door_max"), ("speed_min", "speed_max")),
    timed=True,
)


def _slalom_walls(rng, p: dict, xs, t: float) -> tuple[list[dict], list[float]]:
    """Full-height walls at ``xs``, each with one gap ``2 r + slack`` px wide; the gaps
    alternate between the upper and the lower part of the map. Returns the walls and the
    gaps' centres (heights, px)."""
    s, r = p["size"], p["robot_radius"]
    parity, obs, ys = int(rng.integers(2)), [], []
    for j, x in enumerate(xs):
        gap = 2.0 * r + rng.uniform(p["slack_min"], p["slack_max"])
        band = (0.55, 0.9) if (j + parity) % 2 else (0.1, 0.45)
        y = rng.uniform(*band) * s
        obs.append(box(x - 0.5 * t, 0.0, x + 0.5 * t, y - 0.5 * gap))
        obs.append(box(x - 0.5 * t, y + 0.5 * gap, x + 0.5 * t, s))
        ys.append(y)
    return obs, ys


def _draw_slalom(rng: np.random.Generator, p: dict) -> dict:
    s, r = p["size"], p["robot_radius"]
    k = int(rng.integers(p["walls_min"], p["walls_max"] + 1))
    pitch = s / (k + 1)
    xs = pitch * np.arange(1, k + 1) + rng.uniform(-0.1, 0.1, k) * pitch
    t = rng.uniform(0.02, 0.05) * s
    obs, ys = _slalom_walls(rng, p, xs, t)
    start, goal = _ends(rng, p, xs[0] - 0.5 * t, xs[-1] + 0.5 * t)
    # patrols along a wall, across its gap, on either side: the robot times its passages
    for j in rng.permutation(k)[: int(rng.integers(1, p["movers"] + 1))]:
        rad = r * rng.uniform(1.0, 2.0)
        side = 1.0 if rng.random() < 0.5 else -1.0
        x = xs[j] + side * (0.5 * t + rad * rng.uniform(0.3, 1.0))
        amp = rng.uniform(1.5, 4.0) * (rad + r)
        lo, hi = max(ys[j] - amp, rad + 1.0), min(ys[j] + amp, s - rad - 1.0)
        obs.append(_up_and_down(rng, p, x, rad, lo, hi))
    return _finish(rng, p, start, goal, obs, ())


SLALOM = Family(
    "slalom",
    "walls with gaps at most 1 px wider than the robot, alternating sides, patrols across them",
    (
        Param("walls_min", 2, 2, 6, integer=True, doc="fewest walls"),
        Param("walls_max", 4, 2, 6, integer=True, doc="most walls"),
        Param("slack_min", 0.3, 0.05, 1.0, doc="narrowest gap beyond the robot diameter, px"),
        Param("slack_max", 1.0, 0.05, 1.0, doc="widest gap beyond the robot diameter, px"),
        Param("movers", 2, 1, 6, integer=True, doc="most gap patrols (at least one)"),
        *speed_params(0.2, 0.6, "patrol"),
        *TIME_PARAMS,
    ),
    _draw_slalom,
    moving=True,
    check=range_check(
        ("walls_min", "walls_max"), ("slack_min", "slack_max"), ("speed_min", "speed_max")
    ),
    timed=True,
)
