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
(:func:`mawdo.planning.geometry.inflate`, which contains the true inflated shape, so the result is
collision-free and at most a hair longer than the true optimum); :func:`scenario_optimum` does that.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra

from mawdo.planning.geometry import CIRCLE_SEGMENTS, inflated_obstacles
from mawdo.planning.scenario import Scenario

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


def _corner_nodes(free) -> np.ndarray:
    """Vertices of the free space's rings where the free space is reflex (obstacle corners)."""
    nodes = []
    for poly in getattr(free, "geoms", [free]):
        if poly.is_empty:
            continue
        # orient: exterior counter-clockwise, holes clockwise -> free space on the left
        poly = shapely.geometry.polygon.orient(poly, 1.0)
        for ring in [poly.exterior, *poly.interiors]:
            v = np.asarray(ring.coords)[:-1]
            prev = np.roll(v, 1, axis=0)
            nxt = np.roll(v, -1, axis=0)
            a = v - prev
            b = nxt - v
            cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
            nodes.append(v[cross < 0])  # right turn with free space on the left: reflex
    return np.concatenate(nodes) if nodes else np.empty((0, 2))


def shortest_path(start, goal, obstacles, bounds, tol: float = DEFAULT_TOL) -> OracleResult:
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

    Returns
    -------
    OracleResult
        Length (pixels) and vertex path, or ``inf``/``None`` and a reason.
    """
    start = np.asarray(start, dtype=float)
    goal = np.asarray(goal, dtype=float)
    box = shapely.box(*bounds)
    union = shapely.union_all(list(obstacles)) if len(obstacles) else shapely.Polygon()
    blocked = union.buffer(-tol) if not union.is_empty else union
    shapely.prepare(blocked)
    for name, p in (("start", start), ("goal", goal)):
        if not box.buffer(tol).covers(shapely.Point(p)):
            return _unreachable(f"{name} {tuple(p)} is outside the map {tuple(bounds)}")
        if blocked.intersects(shapely.Point(p)):
            return _unreachable(f"{name} {tuple(p)} is inside an obstacle")

    free = box.difference(union)
    corners = _corner_nodes(free)
    nodes = np.vstack([start, goal, corners])
    n = len(nodes)
    i, j = np.triu_indices(n, k=1)
    lines = shapely.linestrings(np.stack([nodes[i], nodes[j]], axis=1))
    visible = ~shapely.intersects(blocked, lines) if not blocked.is_empty else np.ones(len(i), bool)
    i, j = i[visible], j[visible]
    w = np.hypot(*(nodes[j] - nodes[i]).T)
    # csgraph treats an explicit zero weight as "no edge": coincident nodes get a tiny weight
    w = np.maximum(w, 1e-300)
    graph = coo_matrix((np.r_[w, w], (np.r_[i, j], np.r_[j, i])), shape=(n, n)).tocsr()
    dist, pred = dijkstra(graph, directed=True, indices=0, return_predecessors=True)
    if not np.isfinite(dist[1]):
        return _unreachable("the goal is not reachable from the start")
    order = [1]
    while order[-1] != 0:
        order.append(int(pred[order[-1]]))
    path = nodes[order[::-1]]
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
    """Optimum ``L*`` of a scenario, obstacles inflated by the robot radius (containing polygons).

    Parameters
    ----------
    scenario : Scenario
    t : float
        Time (time steps) at which moving obstacles are frozen (ignored if ``static_only``).
    static_only : bool
        Use only the static obstacles (a lower bound for the dynamic problem, SPEC 4.4);
        otherwise all obstacles frozen at ``t``.
    start : array_like, shape (2,), optional
        Start (pixels); default the scenario's start.
    n : int
        Sides of the polygon replacing discs (see :mod:`mawdo.planning.geometry`).
    tol : float
        Visibility tolerance (pixels).
    """
    idx = scenario.static_indices if static_only else None
    obstacles = inflated_obstacles(scenario, t, indices=idx, n=n)
    s = scenario.start if start is None else start
    return shortest_path(s, scenario.goal, obstacles, scenario.bounds, tol)
