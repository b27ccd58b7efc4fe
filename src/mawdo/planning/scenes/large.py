"""Timed scene families at scale: ``crowd-large`` and ``warehouse-large``.

Worlds of 1000-2000 px with 100-500 movers, the size a robot meets in a warehouse, a station
or a street (the other families are about 366 px with at most a few dozen movers). Mover
sizes are relative to the robot's radius, speeds to the robot's speed, as in the other timed
families; every scene is turned by one of the map's eight symmetries
(:func:`~mawdo.planning.scenes.timing.orient`).

Every scene is kept only if its earliest arrival ``T*`` exists (``Family.timed``): the exact
safe-interval search stays cheap at this size because the movers are piecewise linear (constant
velocity with reflections, back-and-forth patrols; no random walkers) and the roadmap only has
the inflated static corners and the waiting spots (generation times in ``docs/planning.md``,
the large families).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from mawdo.planning.scenes.base import COMMON_PARAMS, Family, Param, Redraw, draft
from mawdo.planning.scenes.shapes import box, circle, diagonal_endpoints
from mawdo.planning.scenes.timing import (
    TIME_PARAMS,
    lattice_spots,
    orient,
    speed_params,
    timing_margin,
)
from mawdo.planning.scenes.traffic import crosser, moving_disc, range_check, static_polygons

__all__ = ["CROWD_LARGE", "LARGE_SIZE", "WAREHOUSE_LARGE", "LargeFamily", "patrol_disc"]

#: The map side of the large families: 1000 px by default, up to the schema's 2000 px.
LARGE_SIZE = Param("size", 1000.0, 1000.0, 2000.0, doc="map side, pixels")


@dataclasses.dataclass(frozen=True)
class LargeFamily(Family):
    """A :class:`~mawdo.planning.scenes.base.Family` whose common ``size`` parameter is
    :data:`LARGE_SIZE` (default 1000 px, range [1000, 2000]) instead of the paper's 366 px."""

    def __post_init__(self) -> None:
        common = tuple(LARGE_SIZE if q.name == "size" else q for q in COMMON_PARAMS)
        object.__setattr__(self, "all_params", (*common, *self.params))


#: The movers of both families: how many, their radii and speeds (relative to the robot's).
_MOVER_PARAMS = (
    Param("n", 200, 100, 500, integer=True, doc="moving discs"),
    Param("rmin", 0.75, 0.25, 5.0, doc="smallest disc radius, robot radii"),
    Param("rmax", 2.0, 0.25, 5.0, doc="largest disc radius, robot radii"),
    *speed_params(0.2, 0.8, "disc"),
)


def _large_family(name: str, description: str, params: tuple, draw, check) -> LargeFamily:
    """A timed family with moving obstacles: the movers' parameters, the family's own, then
    the timed families' (``lattice``)."""
    params = (*_MOVER_PARAMS, *params, *TIME_PARAMS)
    return LargeFamily(name, description, params, draw, moving=True, check=check, timed=True)


def patrol_disc(rng: np.random.Generator, p: dict, a, b, rad: float) -> dict:
    """A disc of radius ``rad`` going back and forth between the points ``a`` and ``b``
    (pixels) at a speed drawn from ``speed_min .. speed_max`` times the robot's, starting at a
    uniformly drawn point between them."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    c = a + rng.uniform() * (b - a)
    motion = {
        "model": "patrol",
        "waypoints": [(a - c).tolist(), (b - c).tolist()],
        "speed": float(rng.uniform(p["speed_min"], p["speed_max"]) * p["robot_speed"]),
        "cycle": "back_and_forth",
    }
    return circle(c, rad, motion)


def _keep_clear(ob: dict, start, goal, p: dict) -> bool:
    """A mover starts farther from start and goal than its radius + the robot's + clearance
    + 10 steps of its own motion (pixels; the same margin as the dense family's movers)."""
    motion = ob["motion"]
    speed = motion.get("speed", math.hypot(*motion.get("velocity", (0.0, 0.0))))
    keep = ob["radius"] + p["robot_radius"] + p["clearance"] + 10.0 * speed
    return min(math.dist(ob["center"], start), math.dist(ob["center"], goal)) > keep


def _mover_counts(p: dict, shares: tuple[str, ...]) -> list[int]:
    """How many of the ``n`` movers go to each share: ``floor(n * share)``, and the rest to
    one more group (last)."""
    counts = [int(p["n"] * p[s]) for s in shares]
    return [*counts, p["n"] - sum(counts)]


# --- crowd-large: an open world whose traffic crosses the robot's corridor ------------------


def _reach(c: np.ndarray, u: np.ndarray, lo: float, hi: float) -> float:
    """The largest ``t`` with both ``c + t u`` and ``c - t u`` in ``[lo, hi]^2`` (pixels;
    negative when ``c`` itself is outside)."""
    room = np.minimum(hi - c, c - lo)
    return float(np.min(np.where(u != 0.0, room / np.where(u != 0.0, np.abs(u), 1.0), np.inf)))


def _cross_patrol(rng, p: dict, start, goal, rad: float) -> dict:
    """A disc patrolling across the straight start-goal line: through a point 10-90 % of the
    way, up to 30 degrees off perpendicular, 3-12 (radius + robot radius) to either side
    (less where the map ends: the patrol stays symmetric about the line's point)."""
    s, r = p["size"], p["robot_radius"]
    d = (goal - start) / math.dist(start, goal)
    for _ in range(40):
        mid = start + rng.uniform(0.1, 0.9) * (goal - start)
        ang = rng.uniform(-math.pi / 6, math.pi / 6)
        u = math.cos(ang) * np.array([-d[1], d[0]]) + math.sin(ang) * d
        half = min(rng.uniform(3.0, 12.0) * (rad + r), _reach(mid, u, rad, s - rad))
        if half <= 0.0:
            continue
        ob = patrol_disc(rng, p, mid - half * u, mid + half * u, rad)
        if _keep_clear(ob, start, goal, p):
            return ob
    raise Redraw("no room for a patrol across the robot's line away from start and goal")


def _draw_crowd_large(rng: np.random.Generator, p: dict) -> dict:
    start, goal = diagonal_endpoints(rng, p, timing_margin(p))
    obs = static_polygons(
        rng, p, int(rng.integers(p["statics"] // 2, p["statics"] + 1)), start, goal
    )
    r, dist = p["robot_radius"], math.dist(start, goal)
    q = {**p, "rmin": r * p["rmin"], "rmax": r * p["rmax"], "walkers": 0.0}
    aimed, patrols, free = _mover_counts(p, ("aimed", "patrols"))
    obs += [crosser(rng, q, start, (goal - start) / dist, dist) for _ in range(aimed)]
    for _ in range(patrols):
        obs.append(_cross_patrol(rng, p, start, goal, float(rng.uniform(q["rmin"], q["rmax"]))))
    obs += [moving_disc(rng, q, start, goal) for _ in range(free)]
    data = draft(p, start, goal, obs)
    data["_spots"] = lattice_spots(p, obs, p["lattice"])
    return orient(rng, data, p["size"])


def _check_crowd_large(p: dict) -> None:
    range_check(("rmin", "rmax"), ("speed_min", "speed_max"))(p)
    if p["aimed"] + p["patrols"] > 1.0:
        raise ValueError(
            f"aimed + patrols = {p['aimed'] + p['patrols']:g} must be <= 1 "
            "(they are shares of the n movers)"
        )


CROWD_LARGE = _large_family(
    "crowd-large",
    "an open 1000-2000 px world: 100-500 discs crossing the robot's corridor (some timed to "
    "meet it, some patrolling across it, the rest at random constant velocities), "
    "small static polygons",
    (
        Param("aimed", 0.1, 0.0, 1.0, doc="share of discs timed to meet the robot on its line"),
        Param("patrols", 0.3, 0.0, 1.0, doc="share of discs patrolling across its line"),
        Param(
            "statics",
            12,
            0,
            60,
            integer=True,
            doc="most static convex polygons, 15-35 px (at least half as many)",
        ),
    ),
    _draw_crowd_large,
    _check_crowd_large,
)


# --- warehouse-large: shelving rows, aisles and cross-aisles, patrolling movers --------------


def _layout(p: dict):
    """The shelving of a ``size x size`` map, shelves along x: rows of shelves
    ``shelf`` robot diameters deep, separated by aisles at least ``aisle`` diameters wide
    (also along the two borders); each row cut into ``blocks`` shelves by cross-aisles
    ``cross`` diameters wide (also along the two borders).

    Returns
    -------
    ys : numpy.ndarray
        The rows' lower edges (pixels).
    xs : numpy.ndarray
        The shelves' left edges (pixels).
    depth, length, aisle, cross : float
        Shelf depth and length, aisle and cross-aisle widths (pixels).
    """
    s, dia = p["size"], 2.0 * p["robot_radius"]
    depth, aisle, cross, b = p["shelf"] * dia, p["aisle"] * dia, p["cross"] * dia, p["blocks"]
    rows = int((s - aisle) // (depth + aisle))
    aisle = (s - rows * depth) / (rows + 1)  # the spare height widens every aisle alike
    length = (s - (b + 1) * cross) / b
    ys = aisle + (depth + aisle) * np.arange(rows)
    xs = cross + (length + cross) * np.arange(b)
    return ys, xs, depth, length, aisle, cross


def _aisle_point(rng, lanes, x_lo: float, x_hi: float) -> np.ndarray:
    """A point on the centre line of a random aisle of ``lanes`` (heights), ``x`` uniform in
    ``[x_lo, x_hi]`` (pixels)."""
    return np.array([rng.uniform(x_lo, x_hi), lanes[rng.integers(len(lanes))]])


def _warehouse_movers(rng, p: dict, aisles, crosses, start, goal) -> list[dict]:
    """Discs patrolling along aisle centre lines (``x`` varies) and cross-aisle centre lines
    (``y`` varies), each over 10-50 % of the map side, on the centre line."""
    s, r = p["size"], p["robot_radius"]
    along, across = _mover_counts(p, ("cross_share",))[::-1]
    out = []
    for lanes, count, vertical in ((aisles, along, False), (crosses, across, True)):
        for _ in range(count):
            for _ in range(40):
                rad = r * float(rng.uniform(p["rmin"], p["rmax"]))
                span = rng.uniform(0.1, 0.5) * (s - 2 * rad)
                lo = rng.uniform(rad, s - rad - span)
                c = lanes[rng.integers(len(lanes))]
                a, b = ((c, lo), (c, lo + span)) if vertical else ((lo, c), (lo + span, c))
                ob = patrol_disc(rng, p, a, b, rad)
                if _keep_clear(ob, start, goal, p):
                    out.append(ob)
                    break
            else:
                raise Redraw("no room for a patrolling mover away from start and goal")
    return out


def _draw_warehouse_large(rng: np.random.Generator, p: dict) -> dict:
    s = p["size"]
    ys, xs, depth, length, aisle, cross = _layout(p)
    obs = [box(x, y, x + length, y + depth) for y in ys for x in xs]
    aisles = np.r_[ys - 0.5 * aisle, ys[-1] + depth + 0.5 * aisle]  # centre lines
    crosses = np.r_[xs - 0.5 * cross, xs[-1] + length + 0.5 * cross]
    k = max(1, len(aisles) // 4)  # start in the lowest quarter of aisles, goal in the highest
    m = p["robot_radius"] + p["clearance"] + 1.0
    start = _aisle_point(rng, aisles[:k], m, 0.25 * s)
    goal = _aisle_point(rng, aisles[-k:], 0.75 * s, s - m)
    obs += _warehouse_movers(rng, p, aisles, crosses, start, goal)
    data = draft(p, start, goal, obs)
    # waiting spots: the aisle crossings (free by the check) and the free lattice points
    grid = np.stack(np.meshgrid(crosses, aisles), axis=-1).reshape(-1, 2)
    data["_spots"] = np.vstack([grid, lattice_spots(p, obs, p["lattice"])])
    return orient(rng, data, s)


def _check_warehouse_large(p: dict) -> None:
    range_check(("rmin", "rmax"), ("speed_min", "speed_max"))(p)
    r, c = p["robot_radius"], p["clearance"]
    if r <= 0.0:
        raise ValueError(
            "warehouse-large measures its aisles in robot diameters: robot_radius must be > 0"
        )
    for name in ("aisle", "cross"):
        if p[name] * r <= r + c or p[name] * r < r + 1.0:
            raise ValueError(
                f"warehouse-large {name} = {p[name]:g} robot diameters ({2 * p[name] * r:g} px) "
                f"leaves no room for the robot on its centre line: half of it must exceed "
                f"robot_radius + clearance ({r + c:g} px) and robot_radius + 1 px"
            )
        if p["rmax"] > p[name]:
            raise ValueError(
                f"warehouse-large rmax = {p['rmax']:g} robot radii is wider than the {name} "
                f"({p[name]:g} robot diameters): a mover would overlap the shelves"
            )
    dia, s = 2.0 * r, p["size"]
    if s - p["aisle"] * dia < (p["shelf"] + p["aisle"]) * dia:
        raise ValueError(
            "warehouse-large: no row of shelves fits; a larger size or narrower aisles"
        )
    if (s - (p["blocks"] + 1) * p["cross"] * dia) / p["blocks"] < dia:
        raise ValueError(
            f"warehouse-large: {p['blocks']} blocks and cross-aisles of {p['cross']:g} robot "
            "diameters leave shelves shorter than the robot: fewer blocks or narrower cross-aisles"
        )


WAREHOUSE_LARGE = _large_family(
    "warehouse-large",
    "a 1000-2000 px warehouse: rows of shelves cut by cross-aisles, 100-500 discs patrolling "
    "the aisles and cross-aisles",
    (
        Param("cross_share", 0.3, 0.0, 1.0, doc="share of discs on the cross-aisles"),
        Param("aisle", 4.0, 1.5, 20.0, doc="narrowest aisle between rows, robot diameters"),
        Param("cross", 4.0, 1.5, 20.0, doc="cross-aisle width, robot diameters"),
        Param("shelf", 4.0, 1.0, 40.0, doc="shelf depth, robot diameters"),
        Param("blocks", 4, 1, 12, integer=True, doc="shelves per row (cross-aisles between)"),
    ),
    _draw_warehouse_large,
    _check_warehouse_large,
)
