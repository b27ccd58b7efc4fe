"""Exact shortest collision-free path for a point among polygons (visibility graph).

The shortest path between two points in a polygonal domain is a polyline whose interior vertices
are convex obstacle corners, i.e. vertices where the *free space* is reflex. So the graph has as
nodes the start, the goal and those corners, and an edge between every pair of nodes whose
straight segment stays in the free space (touching an obstacle's boundary is allowed, passing
through its interior is not). Dijkstra (``scipy.sparse.csgraph``) on it gives the optimum.

The free space is the map box minus the union of the obstacles, so overlapping obstacles, holes
in their union and obstacles leaving the map are all handled by shapely. A segment is accepted
when it does not meet the obstacles shrunk by a tolerance ``tol`` (pixels), which lets it slide
along an edge or through a vertex without being rejected by rounding.

For the robot disc, pass the obstacles inflated by the robot radius
(:func:`mawdo.planning.world.geometry.inflate`, which contains the true inflated shape, so the
result is collision-free and at most a hair longer than the true optimum) and the map shrunk by it
(:func:`mawdo.planning.world.geometry.centre_box`); :func:`scenario_optimum` does that.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from mawdo.planning.guide.visgraph import MAX_NODES, build, trace
from mawdo.planning.world.geometry import CIRCLE_SEGMENTS, centre_box, inflated_obstacles
from mawdo.planning.world.scenario import Scenario

__all__ = ["OracleResult", "scenario_optimum", "shortest_path"]

#: Default tolerance (pixels) by which obstacles are shrunk for the visibility test.
DEFAULT_TOL = 1e-7


@dataclass(frozen=True)
class OracleResult:
    """Outcome of :func:`shortest_path`.

    Attributes
    ----------
    length : float
        Length of the shortest path (pixels); ``inf`` if unreachable.
    path : numpy.ndarray or None
        Vertices ``(k, 2)`` from start to goal (pixels); ``None`` if unreachable.
    reason : str
        ``"ok"``, or why there is no path.
    """

    length: float
    path: np.ndarray | None
    reason: str = "ok"

    @property
    def reachable(self) -> bool:
        return self.path is not None


def _unreachable(reason: str) -> OracleResult:
    return OracleResult(np.inf, None, reason)


def shortest_path(
    start, goal, obstacles, bounds, tol: float = DEFAULT_TOL, max_nodes: int = MAX_NODES
) -> OracleResult:
    """Shortest path for a point from ``start`` to ``goal`` avoiding the obstacles' interiors.

    Parameters
    ----------
    start, goal : array_like, shape (2,)
        End points (pixels).
    obstacles : sequence of shapely geometries
        Obstacles (already inflated by the robot radius if the robot is a disc).
    bounds : tuple of float
        Map box ``(xmin, ymin, xmax, ymax)`` (pixels); the path stays inside it.
    tol : float
        Obstacles are shrunk by this much (pixels) for the visibility test.
    max_nodes : int
        Most obstacle corners accepted (:data:`mawdo.planning.guide.visgraph.MAX_NODES`; the build
        is quadratic in them); more raise a ``ValueError``.

    Returns
    -------
    OracleResult
        Length (pixels) and vertex path, or ``inf``/``None`` and a reason.
    """
    start = np.asarray(start, dtype=float)
    goal = np.asarray(goal, dtype=float)
    box = shapely.box(*bounds).buffer(tol, join_style="mitre")
    for name, p in (("start", start), ("goal", goal)):
        if not box.covers(shapely.Point(p)):
            return _unreachable(f"{name} {tuple(p)} is outside the map {tuple(bounds)}")
    graph = build(obstacles, bounds, points=[start, goal], tol=tol, max_nodes=max_nodes)
    for name, p in (("start", start), ("goal", goal)):
        if graph.inside(p):
            return _unreachable(f"{name} {tuple(p)} is inside an obstacle")
    dist, pred = graph.dijkstra([0], [0.0])
    if not np.isfinite(dist[1]):
        return _unreachable("the goal is not reachable from the start")
    path = graph.nodes[trace(pred, 1)]
    length = float(np.sum(np.hypot(*np.diff(path, axis=0).T)))
    return OracleResult(length, path)


def scenario_optimum(
    scenario: Scenario,
    t: float = 0.0,
    static_only: bool = True,
    start=None,
    n: int = CIRCLE_SEGMENTS,
    tol: float = DEFAULT_TOL,
) -> OracleResult:
    """Optimum ``L*`` of a scenario, obstacles inflated by the robot radius (containing polygons)
    and the robot's disc inside the map (its centre at least the radius from the border).

    Parameters
    ----------
    scenario : Scenario
    t : float
        Time (time steps) at which moving obstacles are frozen (ignored if ``static_only``).
    static_only : bool
        Use only the static obstacles (a lower bound for the dynamic problem,
        docs/deviations.md#d-gap);
        otherwise all obstacles frozen at ``t``.
    start : array_like, shape (2,), optional
        Start (pixels); default the scenario's start.
    n : int
        Sides of the polygon replacing discs (see :mod:`mawdo.planning.world.geometry`).
    tol : float
        Visibility tolerance (pixels).
    """
    idx = scenario.static_indices if static_only else None
    obstacles = inflated_obstacles(scenario, t, indices=idx, n=n)
    s = scenario.start if start is None else start
    # the border is a wall like the obstacles: the centre keeps the radius from it
    box = centre_box(scenario, scenario.robot_radius)
    return shortest_path(s, scenario.goal, obstacles, box, tol)
