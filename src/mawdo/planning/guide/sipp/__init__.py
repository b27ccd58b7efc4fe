"""Safe-interval guide (SIPP in continuous 2-D): earliest-arrival timed routes among movers.

Modules: :mod:`.geometry` (compiled: the departures at which a straight timed move meets a
disc, a convex piece or a reachable set, in closed form), :mod:`.intervals` (movers as tables,
forbidden departures, the exact re-check of a timed move, safe intervals of vertices),
:mod:`.search` (compiled A* over (vertex, safe interval) states), :mod:`.guide` (the public
:class:`SafeIntervalGuide` and :class:`TimedRoute`), :mod:`.exact` (the re-check's exact
point/segment/polygon tests), :mod:`.optimum` (a scenario's earliest arrival ``T*``),
:mod:`.explain` (why a query has no route).
"""

from mawdo.planning.guide.sipp.guide import SafeIntervalGuide, TimedRoute
from mawdo.planning.guide.sipp.optimum import TimeOptimum, scenario_time_optimum

__all__ = ["SafeIntervalGuide", "TimeOptimum", "TimedRoute", "scenario_time_optimum"]
