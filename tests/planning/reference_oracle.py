"""The first oracle (all node pairs, shapely visibility, scipy Dijkstra): a slow, independent
reference for the compiled tangent visibility graph of :mod:`mawdo.planning.guide.visgraph`."""

from __future__ import annotations

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra


def _corner_nodes(free) -> np.ndarray:
    nodes = []
    for poly in getattr(free, "geoms", [free]):
        if poly.is_empty:
            continue
        poly = shapely.geometry.polygon.orient(poly, 1.0)
        for ring in [poly.exterior, *poly.interiors]:
            v = np.asarray(ring.coords)[:-1]
            a = v - np.roll(v, 1, axis=0)
            b = np.roll(v, -1, axis=0) - v
            nodes.append(v[a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0] < 0])
    return np.concatenate(nodes) if nodes else np.empty((0, 2))


def brute_force_length(start, goal, obstacles, bounds, tol=1e-7) -> float:
    """Shortest path length (inf if unreachable), every node pair tested with shapely."""
    box = shapely.box(*bounds)
    union = shapely.union_all(list(obstacles)) if len(obstacles) else shapely.Polygon()
    blocked = union.buffer(-tol) if not union.is_empty else union
    nodes = np.vstack([start, goal, _corner_nodes(box.difference(union))])
    n = len(nodes)
    i, j = np.triu_indices(n, k=1)
    lines = shapely.linestrings(np.stack([nodes[i], nodes[j]], axis=1))
    vis = ~shapely.intersects(blocked, lines) if not blocked.is_empty else np.ones(len(i), bool)
    i, j = i[vis], j[vis]
    w = np.maximum(np.hypot(*(nodes[j] - nodes[i]).T), 1e-300)
    g = coo_matrix((np.r_[w, w], (np.r_[i, j], np.r_[j, i])), shape=(n, n)).tocsr()
    return float(dijkstra(g, indices=0)[1])
