"""Tangent visibility graph among polygons, compiled: the exact oracle's fast core.

A shortest path among polygonal obstacles bends only at convex obstacle corners (reflex vertices
of the free space), and at such a corner it is *tangent* to the obstacle: both ring neighbours of
the corner lie on one side of each path segment through it. So the graph keeps only edges that
are tangent at both corner ends (the "reduced" or tangent visibility graph; it keeps every
shortest path) and are visible: the segment does not meet the obstacles shrunk by ``tol``. Between
two convex obstacles that leaves about four edges instead of every vertex pair, so a map with 30
polygons builds in a few milliseconds.

Limits: the candidate pairs are enumerated (no dense matrix is stored; memory grows with the edge
count), so the build is quadratic in the number of corner nodes. Above ``MAX_NODES`` corners
:func:`build` raises a ``ValueError`` naming the count and the ways out.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from mawdo.planning.guide.visgraph_kernels import (
    csr_dijkstra,
    segment_visible,
    tangent_edges,
    visible_from_point,
)

__all__ = ["MAX_NODES", "VisGraph", "build", "csr_dijkstra", "visible_from_point"]

#: Most corner nodes a graph may have: the build enumerates ``n^2 / 2`` pairs (2.3 s of CPU for
#: the 27 600 corners of 1000 polygons on a 1000 px map, about 5 s at the limit); beyond it the
#: caller must simplify the obstacles.
MAX_NODES = 40_000


def _ring_table(geom):
    """Every ring of a (multi)polygon, oriented with the polygon's inside on the left (exteriors
    counter-clockwise, holes clockwise), vectorised over rings.

    Returns ``(v, prev, nxt, ring)``: the vertices ``(k, 2)`` (closing vertices dropped), the index
    of each vertex's predecessor and successor on its ring, and its ring number.
    """
    polys = [p for p in shapely.get_parts(geom) if p.geom_type == "Polygon" and not p.is_empty]
    if not polys:
        e = np.empty(0, np.int64)
        return np.empty((0, 2)), e, e, e
    rings, owner = shapely.get_rings(np.array(polys, dtype=object), return_index=True)
    exterior = np.r_[True, owner[1:] != owner[:-1]]
    flip = shapely.is_ccw(rings) != exterior
    coords, ring = shapely.get_coordinates(rings, return_index=True)
    count = np.bincount(ring, minlength=len(rings))
    start = np.r_[0, np.cumsum(count)[:-1]]
    pos = np.arange(len(coords)) - start[ring]
    keep = pos < count[ring] - 1  # drop each ring's closing vertex
    coords, ring, pos = coords[keep], ring[keep], pos[keep]
    length = count - 1
    start = np.r_[0, np.cumsum(length)[:-1]]
    src = np.where(flip[ring], start[ring] + length[ring] - 1 - pos, start[ring] + pos)
    v = coords[src]
    L, s0 = length[ring], start[ring]
    prev = s0 + (pos - 1) % L
    nxt = s0 + (pos + 1) % L
    return v, prev, nxt, ring


def component_labels(n: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Connected components of the undirected graph on ``n`` vertices with edges ``a[k]-b[k]``.

    Labels ``0, 1, ...`` in the order of each component's lowest vertex, as
    ``scipy.sparse.csgraph.connected_components`` numbers them (by union-find here: importing
    scipy's sparse graphs cost a command 0.3-0.6 s for a graph of a few dozen obstacles).
    """
    parent = np.arange(n)

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]  # path halving
            i = parent[i]
        return i

    for i, j in zip(a.tolist(), b.tolist(), strict=True):
        ri, rj = root(i), root(j)
        if ri != rj:
            parent[max(ri, rj)] = min(ri, rj)  # the lowest vertex is its component's root
    roots = np.array([root(i) for i in range(n)], dtype=np.int64)
    _, label = np.unique(roots, return_inverse=True)  # roots ascending: lowest vertex first
    return label.astype(np.int32)


def _union(obstacles: list):
    """Union of the obstacles; only groups that touch are merged (shapely's union is the slow
    step when nothing overlaps, the usual case)."""
    if not obstacles:
        return shapely.Polygon()
    geoms = np.array(obstacles, dtype=object)
    a, b = shapely.STRtree(geoms).query(geoms, predicate="intersects")
    label = component_labels(len(geoms), a, b)
    parts = []
    for c in np.unique(label):
        group = geoms[label == c]
        merged = group[0] if len(group) == 1 else shapely.union_all(group)
        parts.extend(shapely.get_parts(merged))
    parts = [p for p in parts if p.geom_type == "Polygon" and not p.is_empty]
    return shapely.MultiPolygon(parts) if len(parts) != 1 else parts[0]


def _corners(free) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Reflex vertices of the free space with their ring neighbours."""
    v, prev, nxt, _ = _ring_table(free)
    a, b = v - v[prev], v[nxt] - v
    reflex = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0] < 0  # free space on the left
    return v[reflex], v[prev[reflex]], v[nxt[reflex]]


def _blocking_edges(blocked) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Edges ``(x0, y0, x1, y1)`` grouped by ring, ring pointers and ring bounding boxes."""
    v, _, nxt, ring = _ring_table(blocked)
    if not len(v):
        return np.empty((0, 4)), np.zeros(1, np.int64), np.empty((0, 4))
    edges = np.ascontiguousarray(np.hstack([v, v[nxt]]))
    count = np.bincount(ring)
    ptr = np.r_[0, np.cumsum(count)].astype(np.int64)
    lo = np.column_stack([np.minimum.reduceat(v[:, k], ptr[:-1]) for k in range(2)])
    hi = np.column_stack([np.maximum.reduceat(v[:, k], ptr[:-1]) for k in range(2)])
    return edges, ptr, np.ascontiguousarray(np.hstack([lo, hi]))


def _relative(neigh: np.ndarray, nodes: np.ndarray) -> np.ndarray:
    """Neighbours relative to their node, with squared lengths: ``(dx, dy, dx^2 + dy^2)``."""
    d = neigh - nodes
    return np.ascontiguousarray(np.column_stack([d, (d**2).sum(axis=1)]))


@dataclass
class VisGraph:
    """A built tangent visibility graph (see :func:`build`).

    Attributes
    ----------
    nodes : numpy.ndarray, shape (n, 2)
        Node positions (pixels): the extra points given to :func:`build` first, then the corners.
    indptr, indices, weights : numpy.ndarray
        The undirected graph in CSR form (edge lengths in pixels).
    union : shapely geometry
        Union of the obstacles (for inside tests and homotopy reference points).
    blocked : shapely geometry
        The obstacles shrunk by ``tol`` (prepared): what a segment may not meet.
    """

    nodes: np.ndarray
    prev: np.ndarray
    nxt: np.ndarray
    corner: np.ndarray
    edges: np.ndarray
    ring_ptr: np.ndarray
    ring_box: np.ndarray
    indptr: np.ndarray
    indices: np.ndarray
    weights: np.ndarray
    union: object
    blocked: object
    bounds: tuple
    eps2: float

    def visible_from(self, p) -> np.ndarray:
        """Indices of nodes a free point ``p`` sees along a segment tangent at the node."""
        p = np.ascontiguousarray(p, dtype=float)
        return visible_from_point(
            p,
            self.nodes,
            self.prev,
            self.nxt,
            self.corner,
            self.edges,
            self.ring_ptr,
            self.ring_box,
            self.eps2,
        )

    def sees(self, p, q) -> bool:
        """The segment ``pq`` stays out of the (shrunk) obstacles."""
        return bool(
            segment_visible(p[0], p[1], q[0], q[1], self.edges, self.ring_ptr, self.ring_box)
        )

    def dijkstra(self, init_nodes, init_dist):
        """Distances (pixels) and predecessors from a virtual source (see ``csr_dijkstra``)."""
        return csr_dijkstra(
            self.indptr,
            self.indices,
            self.weights,
            np.asarray(init_nodes, np.int64),
            np.asarray(init_dist, float),
        )

    def inside(self, p) -> bool:
        """``p`` lies in an obstacle's interior (deeper than ``tol``)."""
        return bool(self.blocked.intersects(shapely.Point(p)))


def build(obstacles, bounds, points=(), tol: float = 1e-7, max_nodes: int = MAX_NODES) -> VisGraph:
    """Build the tangent visibility graph of the free space ``box(bounds) - union(obstacles)``.

    Parameters
    ----------
    obstacles : sequence of shapely geometries
        Obstacles (already inflated for a disc robot).
    bounds : tuple of float
        Map box ``(xmin, ymin, xmax, ymax)`` (pixels).
    points : sequence of (x, y)
        Extra free nodes (start, goal), without the tangent constraint; they come first.
    tol : float
        Obstacles are shrunk by this much (pixels) for the visibility test, so segments may slide
        along edges and through corners.
    max_nodes : int
        Most corner nodes accepted (the build is quadratic in them).

    Raises
    ------
    ValueError
        More than ``max_nodes`` corners.
    """
    box = shapely.box(*bounds)
    obstacles = list(obstacles)
    union = _union(obstacles)
    corners, prv, nxt = _corners(box.difference(union) if not union.is_empty else box)
    if len(corners) > max_nodes:
        raise ValueError(
            f"visibility graph: {len(corners)} obstacle corners exceed the limit of {max_nodes} "
            "(the build is quadratic in corners): use fewer obstacles, or fewer vertices "
            "(merge touching obstacles, simplify polygons); from Python, "
            "mawdo.planning.guide.visgraph.build and oracle.shortest_path take a larger max_nodes"
        )
    blocked = union.buffer(-tol, join_style="mitre") if not union.is_empty else union
    shapely.prepare(blocked)
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    nodes = np.ascontiguousarray(np.vstack([pts, corners]))
    prev = _relative(np.vstack([pts, prv]), nodes)
    nx = _relative(np.vstack([pts, nxt]), nodes)
    corner = np.r_[np.zeros(len(pts), bool), np.ones(len(corners), bool)]
    edges, ring_ptr, ring_box = _blocking_edges(blocked)
    eps2 = 1e-18  # (1e-9 rad)^2: neighbours this close to the line count as on it
    i, j, w = tangent_edges(nodes, prev, nx, corner, edges, ring_ptr, ring_box, eps2)
    n = len(nodes)
    # csr by hand: both directions, sorted by source
    src, dst, ww = np.r_[i, j], np.r_[j, i], np.r_[w, w]
    order = np.argsort(src, kind="stable")
    indptr = np.zeros(n + 1, np.int64)
    np.add.at(indptr, src + 1, 1)
    return VisGraph(
        nodes=nodes,
        prev=prev,
        nxt=nx,
        corner=corner,
        edges=edges,
        ring_ptr=ring_ptr,
        ring_box=ring_box,
        indptr=np.cumsum(indptr),
        indices=dst[order].astype(np.int64),
        weights=ww[order].astype(float),
        union=union,
        blocked=blocked,
        bounds=tuple(bounds),
        eps2=eps2,
    )


def trace(pred: np.ndarray, v: int) -> list[int]:
    """Node indices from the tree's root side to ``v`` (following ``pred`` until ``-1``)."""
    out = [v]
    while pred[out[-1]] >= 0:
        out.append(int(pred[out[-1]]))
    return out[::-1]
