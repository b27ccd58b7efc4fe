"""The space-time optimum ``T*`` of a scenario: the earliest arrival at the goal.

``T*`` is the safe-interval search (:class:`~mawdo.planning.guide.sipp.guide.SafeIntervalGuide`)
from the start at ``t = 0``, with no clearance beyond the robot radius (touching allowed, as
the checker allows it), a fine polygon for the inflated corners and the scene's waiting spots.

When it is exact
----------------
Take the class of timed routes that drive straight at the robot's full speed between vertices
of the roadmap (the tangent visibility graph of the inflated static obstacles, plus start, goal
and waiting spots, each free point joined to every vertex it sees) and wait only at those
vertices. For obstacles whose motion is piecewise linear in time and known (constant velocity
with border reflections, patrols with or without stops, and random walks taken as the seeded
walk), ``T*`` is the earliest arrival of that class, exactly (no time sampling):

* every vertex's safe intervals and every edge's colliding departures are computed in closed
  form (:mod:`mawdo.planning.guide.sipp.geometry`), so the search loses no departure time;
* within one safe interval of a vertex the robot may wait as long as it likes, so arriving
  earlier in the interval dominates arriving later (what a later arrival can do, an earlier
  one can do after waiting): keeping only each interval's earliest arrival loses no route;
* the heuristic (static distance over the same graph at full speed) never overestimates, so
  A* stops at the earliest goal arrival.

Outside that class a route can only be as early or earlier, so ``T*`` is an upper bound of the
true continuous optimum: the robot could wait at points that are not vertices, drive slower
than full speed, or skirt a mover away from any static corner. And ``L* / v`` (the static
optimum's time) is a lower bound. Two more small margins make ``T*`` conservative: the static
obstacles are inflated by a circumscribed ``segments``-gon (routes longer by at most
``rho (1 / cos(pi / segments) - 1)`` px per corner, 0.005 ``rho`` at 32 sides) plus the static
guide's 0.05 px slack. Random walkers are by default taken as discs growing at their top speed
(``walkers="reachable"``): then ``T*`` is the earliest arrival that is safe whatever the walk
does; ``walkers="known"`` judges against the seeded walk instead.

Which waiting spots: the more vertices, the closer the class comes to free space. The scene
families give their bays, a lattice of free points and :func:`dodge_spots` along the static
optimum (the point and points beside it every few robot radii): without the latter, a robot
that must step aside from a faster mover reaches the goal up to 14 % later on the roadmap than
the planner does in free space (chaser scenes, seed 0).

The tests check it against a brute-force search on a fine time grid (shapely checker on every
wait and move; :mod:`tests.planning.sipp_reference`): the same earliest arrival within the grid
step times the route's moves.

Units: the scenario's time step is the time unit (there are no seconds in a scenario).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from mawdo.planning.guide.sipp.guide import SafeIntervalGuide, TimedRoute
from mawdo.planning.world.scenario import Scenario
from mawdo.planning.world.scenario_schema import CircleObstacle

__all__ = ["TIME_SEGMENTS", "TimeOptimum", "dodge_spots", "scenario_time_optimum"]

#: Sides of the polygon standing in for the inflated corners when ``T*`` is computed.
TIME_SEGMENTS = 32
#: Dodge spots along a route: spacing and side offsets, in robot radii (see :func:`dodge_spots`).
DODGE_STEP = 6.0
DODGE_OFFSETS = (2.5, 6.0)


@dataclass(frozen=True)
class TimeOptimum:
    """The earliest arrival of a scenario (see the module docstring).

    Attributes
    ----------
    reachable : bool
        A timed route reaches the goal within the horizon.
    t_star : float
        Earliest arrival (time steps from ``t = 0``; ``inf`` when not reachable).
    route : TimedRoute or None
        The earliest-arrival route (positions, times, waits).
    horizon : float
        Time steps searched.
    reason : str
        Why there is no route (empty when there is one).
    """

    reachable: bool
    t_star: float
    route: TimedRoute | None
    horizon: float
    reason: str = ""

    @property
    def steps(self) -> int:
        """Whole time steps to arrive: ``ceil(t_star)`` (a run's positions are at integer
        steps); ``-1`` when not reachable."""
        return int(math.ceil(self.t_star - 1e-9)) if self.reachable else -1

    @property
    def waiting(self) -> float:
        """Time the optimal route stands still (time steps; 0 when not reachable)."""
        return self.route.waiting if self.route is not None else 0.0


def dodge_spots(
    path, scenario: Scenario, step: float = DODGE_STEP, offsets=DODGE_OFFSETS
) -> np.ndarray:
    """Waiting spots along a route and beside it, where a timed route may step aside.

    Every ``step`` robot radii along the polyline ``path``: the point itself and the points
    ``offsets`` robot radii to either side, kept when free (at least the robot radius + 1 px
    from the map's border and from every static obstacle).

    Parameters
    ----------
    path : array_like, shape (k, 2)
        A route (pixels), e.g. the static optimum.
    scenario : Scenario
    step : float
        Spacing along the route (robot radii, > 0).
    offsets : sequence of float
        Side distances (robot radii, > 0).

    Returns
    -------
    numpy.ndarray, shape (j, 2)
        The free spots (pixels).
    """
    path = np.asarray(path, dtype=float).reshape(-1, 2)
    r = scenario.robot_radius
    gap = max(step * r, 1.0)
    out = []
    for a, b in zip(path[:-1], path[1:], strict=True):
        length = float(np.hypot(*(b - a)))
        if length == 0.0:
            continue
        u = (b - a) / length
        n = np.array([-u[1], u[0]])
        for d in np.arange(gap, length, gap):
            c = a + d * u
            out += [c] + [c + side * o * r * n for o in offsets for side in (-1.0, 1.0)]
    pts = np.reshape(np.asarray(out, dtype=float), (-1, 2))
    need = r + 1.0
    inside = (pts >= need) & (pts <= np.array([scenario.width, scenario.height]) - need)
    pts = pts[np.all(inside, axis=1)]
    statics = [scenario.obstacles[i].shape for i in scenario.static_indices]
    if statics and len(pts):
        pts = pts[_static_distance(statics, pts) > need]
    return pts


def _static_distance(statics, pts: np.ndarray) -> np.ndarray:
    """Per point, the smallest ``shape.distance(point)`` over ``statics`` (pixels): the same
    numbers, a polygon's to all points in one GEOS call (one Python call per point and shape
    took 11 s for the ~1200 spots of a 1000 x 1000 px map)."""
    points = shapely.points(pts)
    out = np.full(len(pts), np.inf)
    for ob in statics:
        if isinstance(ob, CircleObstacle):  # (math.dist, as CircleObstacle.distance)
            d = np.array([max(math.dist(q, ob.center) - ob.radius, 0.0) for q in pts.tolist()])
        else:
            d = shapely.distance(shapely.Polygon(ob.vertices), points)
        out = np.minimum(out, d)
    return out


def scenario_time_optimum(
    scenario: Scenario,
    spots=(),
    horizon: float | None = None,
    walkers: str = "reachable",
    segments: int = TIME_SEGMENTS,
) -> TimeOptimum:
    """Earliest arrival ``T*`` at the goal from the start at ``t = 0``.

    Parameters
    ----------
    scenario : Scenario
    spots : sequence of (x, y)
        Waiting spots (pixels) added to the roadmap: bays, pockets.
    horizon : float, optional
        Time steps searched (> 0); default twice the static route's time plus 60 steps.
    walkers : {"reachable", "known"}
        Random walkers as growing reachable sets (default) or as their seeded walk.
    segments : int
        Sides (>= 3) of the polygons replacing the inflated corners (see the module docstring).

    Returns
    -------
    TimeOptimum
        ``reachable`` False (with the reason) when the start is hit at ``t = 0`` or no timed
        route arrives within the horizon.

    Raises
    ------
    ValueError
        A bad argument, or a start, goal or spot outside the map or inside a static obstacle.
    """
    guide = SafeIntervalGuide(
        scenario, clearance=0.0, spots=spots, horizon=horizon, walkers=walkers, segments=segments
    )
    span = guide.t_end - guide.t0
    try:
        routes = guide.routes(k=1)
    except ValueError as exc:  # the start inside a mover at t = 0
        return TimeOptimum(False, math.inf, None, span, str(exc))
    if not routes:
        why = f"no timed route reaches the goal within the horizon ({span:.6g} time steps)"
        return TimeOptimum(False, math.inf, None, span, why)
    return TimeOptimum(True, routes[0].arrival, routes[0], span)
