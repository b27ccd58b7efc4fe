"""Topological guidance: the shortest route and alternatives in distinct homotopy classes.

The static obstacles and the map's border, inflated by robot radius + clearance (+ a hair of
slack so that the cost kernel, which counts touching as a hit, sees the routes as free), give
one tangent visibility graph per scenario (:mod:`mawdo.planning.guide.visgraph`), built once with
the goal as a node and cached with the shortest-path tree toward the goal. For a robot position the
graph is re-rooted (the robot joins the nodes it sees, one Dijkstra). Every corner ``v`` then
gives the route ``robot -> v -> goal`` made of the two shortest-path trees; its class is told by its
*winding vector*: for each obstacle component, the total angle the route sweeps around a point
inside it (two routes with the same ends are in the same class iff every entry agrees, up to
rounding). Taking routes by increasing length and keeping the first of each class gives the
shortest route and ``k - 1`` alternatives in distinct classes. Moving obstacles are not in the
graph: the optimizer, in space-time, decides which class wins.
"""

from __future__ import annotations

import numpy as np
import shapely
from numba import njit

from mawdo.planning.guide.visgraph import VisGraph, build, trace
from mawdo.planning.world.geometry import centre_box, inflate
from mawdo.planning.world.scenario import Scenario
from mawdo.util.weak import WeakAttribute

__all__ = ["Guide", "winding"]

#: Sides of the polygon standing in for the rounded corners of the inflated obstacles: 8 keeps a
#: right-angle corner to two route vertices (few waypoints needed), 0.5 px outside the disc.
GUIDE_SEGMENTS = 8
#: Extra inflation (px) so that guide routes do not merely touch the cost's inflated obstacles.
SLACK = 0.05


def winding(path: np.ndarray, refs: np.ndarray) -> np.ndarray:
    """Total signed angle (rad) a polyline sweeps around each reference point, shape ``(R,)``."""
    a = path[:-1, None, :] - refs[None]
    b = path[1:, None, :] - refs[None]
    cross = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    dot = (a * b).sum(axis=-1)
    return np.arctan2(cross, dot).sum(axis=0)


@njit(cache=True)
def _tree_winding(order, pred, nodes, root, refs, toward_root):
    """Winding vector of each node's tree path (root to node, or node to root), in tree order."""
    n, r = len(nodes), len(refs)
    out = np.zeros((n, r))
    for v in order:
        p = pred[v]
        if p == -2:
            continue
        ax, ay = (root[0], root[1]) if p == -1 else (nodes[p, 0], nodes[p, 1])
        bx, by = nodes[v, 0], nodes[v, 1]
        if toward_root:  # the path runs v -> parent
            ax, ay, bx, by = bx, by, ax, ay
        for k in range(r):
            ux, uy = ax - refs[k, 0], ay - refs[k, 1]
            wx, wy = bx - refs[k, 0], by - refs[k, 1]
            ang = np.arctan2(ux * wy - uy * wx, ux * wx + uy * wy)
            out[v, k] = ang + (out[p, k] if p >= 0 else 0.0)
    return out


class Guide:
    """Shortest route and alternatives in distinct homotopy classes, re-rooted at the robot.

    Parameters
    ----------
    scenario : Scenario
    clearance : float
        Margin (px) added to the robot radius for the inflation, >= 0.
    k : int
        Most routes returned by :meth:`routes` (the shortest included), >= 1.
    max_ratio : float
        Alternatives longer than ``max_ratio`` times the shortest are dropped.
    """

    # held weakly: the per-scenario cache must not keep its scenario alive
    scenario = WeakAttribute()

    def __init__(
        self, scenario: Scenario, clearance: float = 0.5, k: int = 6, max_ratio: float = 2.5
    ):
        self.scenario, self.k, self.max_ratio = scenario, int(k), float(max_ratio)
        rho = scenario.robot_radius + clearance + SLACK
        obstacles = [
            inflate(scenario.obstacles[i].shape, rho, n=GUIDE_SEGMENTS)
            for i in scenario.static_indices
        ]
        # the map's border is inflated like the obstacles
        box = centre_box(scenario, rho)
        self.graph: VisGraph = build(obstacles, box, points=[scenario.goal])
        # a map without static obstacles has an empty union, whose one part has no point
        parts = [p for p in shapely.get_parts(self.graph.union) if not p.is_empty]
        refs = [p.representative_point() for p in parts]
        self.refs = np.array([[p.x, p.y] for p in refs]).reshape(-1, 2)
        self.dist_g, self.pred_g = self.graph.dijkstra([0], [0.0])
        order = np.argsort(self.dist_g, kind="stable")
        self.wind_g = _tree_winding(
            order, self.pred_g, self.graph.nodes, scenario.goal, self.refs, True
        )

    def query(self, pos):
        """Distances and predecessors from ``pos`` over the graph (``inf`` where unreachable)."""
        pos = np.asarray(pos, dtype=float)
        if self.graph.inside(pos):
            n = len(self.graph.nodes)
            return np.full(n, np.inf), np.full(n, -2, np.int64)
        seen = self.graph.visible_from(pos)
        d0 = np.hypot(*(self.graph.nodes[seen] - pos).T)
        return self.graph.dijkstra(seen, d0)

    def shortest(self, pos) -> float:
        """Length (px) of the shortest route from ``pos`` to the goal (``inf`` if none)."""
        return float(self.query(pos)[0][0])

    def routes(self, pos) -> list[np.ndarray]:
        """Up to ``k`` routes ``(j, 2)`` from ``pos`` to the goal, shortest first, in distinct
        homotopy classes; empty if the goal cannot be reached around the static obstacles."""
        pos = np.asarray(pos, dtype=float)
        dist_s, pred_s = self.query(pos)
        total = dist_s + self.dist_g
        ok = np.isfinite(total)
        if not ok[0]:
            return []
        order = np.argsort(dist_s, kind="stable")
        wind_s = _tree_winding(order, pred_s, self.graph.nodes, pos, self.refs, False)
        wind = wind_s + self.wind_g
        best = total[0]
        cand = np.nonzero(ok & (total <= self.max_ratio * best + 1e-9))[0]
        cand = cand[np.argsort(total[cand], kind="stable")]
        # every candidate's class key in one array operation (elementwise, so the same
        # numbers as one candidate at a time), rows read back as tuples in the loop
        keys = np.round((wind[cand] - wind[0]) / (2 * np.pi)).astype(int)
        seen, out = set(), []
        for v, row in zip(cand, keys, strict=True):
            key = tuple(row)
            if key in seen:
                continue
            seen.add(key)
            head = trace(pred_s, int(v))
            tail = []
            u = int(self.pred_g[v])
            while u >= 0:
                tail.append(u)
                u = int(self.pred_g[u])
            idx = head + tail
            out.append(np.vstack([pos, self.graph.nodes[idx]]))
            if len(out) == self.k:
                break
        return out
