"""The space-time optimum ``T*`` of a scenario: the earliest arrival at the goal (issue 27).

``T*`` is the safe-interval search (:class:`~mawdo.planning.sipp.guide.SafeIntervalGuide`)
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
  form (:mod:`mawdo.planning.sipp.geometry`), so the search loses no departure time;
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

The tests check it against a brute-force search on a fine time grid (shapely checker on every
wait and move; :mod:`tests.planning.sipp_reference`): the same earliest arrival within the grid
step times the route's moves.

Units: the scenario's time step is the time unit (there are no seconds in a scenario).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from mawdo.planning.scenario import Scenario
from mawdo.planning.sipp.guide import SafeIntervalGuide, TimedRoute

__all__ = ["TIME_SEGMENTS", "TimeOptimum", "scenario_time_optimum"]

#: Sides of the polygon standing in for the inflated corners when ``T*`` is computed.
TIME_SEGMENTS = 32


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
