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
from numba import njit

from mawdo.planning.heap import heap_new, heap_pop, heap_push

__all__ = ["MAX_NODES", "VisGraph", "build", "csr_dijkstra", "visible_from_point"]

#: Most corner nodes a graph may have: the build enumerates ``n^2 / 2`` pairs (about 2e8 cheap
#: tangent tests here, a second or so); beyond it the caller must simplify the obstacles.
MAX_NODES = 20_000


@njit(cache=True)
def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


@njit(cache=True, inline="always")
def _tangent(ax, ay, px, py, p2, qx, qy, q2, bx, by, eps2):
    """Both ring neighbours of corner ``a`` on one side of the line from ``a`` to ``b``.

    ``(px, py)``, ``(qx, qy)`` are the neighbours relative to ``a``, ``p2``, ``q2`` their squared
    lengths. Sides are judged by the sine of the angle, so a neighbour within ``sqrt(eps2)`` rad
    of the line (a path sliding along an edge) counts as on it; squared comparisons keep square
    roots out of the quadratic loop.
    """
    dx, dy = bx - ax, by - ay
    s1 = dx * py - dy * px
    s2 = dx * qy - dy * qx
    if s1 * s2 >= 0.0:
        return True
    d2 = dx * dx + dy * dy
    return s1 * s1 <= eps2 * d2 * p2 or s2 * s2 <= eps2 * d2 * q2


@njit(cache=True)
def _seg_hits(px, py, qx, qy, ex0, ey0, ex1, ey1):
    """Closed segments pq and e0e1 intersect (touching counts)."""
    d1 = _cross(ex1 - ex0, ey1 - ey0, px - ex0, py - ey0)
    d2 = _cross(ex1 - ex0, ey1 - ey0, qx - ex0, qy - ey0)
    d3 = _cross(qx - px, qy - py, ex0 - px, ey0 - py)
    d4 = _cross(qx - px, qy - py, ex1 - px, ey1 - py)
    if ((d1 > 0 and d2 < 0) or (d1 < 0 and d2 > 0)) and (
        (d3 > 0 and d4 < 0) or (d3 < 0 and d4 > 0)
    ):
        return True
    # collinear / touching cases: an end point on the other segment
    if d1 == 0 and min(ex0, ex1) <= px <= max(ex0, ex1) and min(ey0, ey1) <= py <= max(ey0, ey1):
        return True
    if d2 == 0 and min(ex0, ex1) <= qx <= max(ex0, ex1) and min(ey0, ey1) <= qy <= max(ey0, ey1):
        return True
    if d3 == 0 and min(px, qx) <= ex0 <= max(px, qx) and min(py, qy) <= ey0 <= max(py, qy):
        return True
    if d4 == 0 and min(px, qx) <= ex1 <= max(px, qx) and min(py, qy) <= ey1 <= max(py, qy):
        return True
    return False


@njit(cache=True)
def _visible(px, py, qx, qy, edges, ring_ptr, ring_box):
    """The segment pq meets no blocking edge (rings pre-filtered by their bounding boxes)."""
    lo_x, hi_x = min(px, qx), max(px, qx)
    lo_y, hi_y = min(py, qy), max(py, qy)
    for r in range(len(ring_ptr) - 1):
        if (
            ring_box[r, 0] > hi_x
            or ring_box[r, 2] < lo_x
            or ring_box[r, 1] > hi_y
            or ring_box[r, 3] < lo_y
        ):
            continue
        for e in range(ring_ptr[r], ring_ptr[r + 1]):
            if max(edges[e, 0], edges[e, 2]) < lo_x or min(edges[e, 0], edges[e, 2]) > hi_x:
                continue
            if max(edges[e, 1], edges[e, 3]) < lo_y or min(edges[e, 1], edges[e, 3]) > hi_y:
                continue
            if _seg_hits(px, py, qx, qy, edges[e, 0], edges[e, 1], edges[e, 2], edges[e, 3]):
                return False
    return True


@njit(cache=True)
def _edges(nodes, prev, nxt, corner, edges, ring_ptr, ring_box, eps2):
    """Tangent, visible node pairs ``(i, j)``, ``i < j``, and their lengths."""
    n = len(nodes)
    ei, ej = [], []
    for i in range(n):
        ax, ay, ci = nodes[i, 0], nodes[i, 1], corner[i]
        px, py, p2, qx, qy, q2 = prev[i, 0], prev[i, 1], prev[i, 2], nxt[i, 0], nxt[i, 1], nxt[i, 2]
        for j in range(i + 1, n):
            bx, by = nodes[j, 0], nodes[j, 1]
            if ci and not _tangent(ax, ay, px, py, p2, qx, qy, q2, bx, by, eps2):
                continue
            if corner[j] and not _tangent(
                bx,
                by,
                prev[j, 0],
                prev[j, 1],
                prev[j, 2],
                nxt[j, 0],
                nxt[j, 1],
                nxt[j, 2],
                ax,
                ay,
                eps2,
            ):
                continue
            if _visible(ax, ay, bx, by, edges, ring_ptr, ring_box):
                ei.append(i)
                ej.append(j)
    a = np.array(ei, dtype=np.int64)
    b = np.array(ej, dtype=np.int64)
    w = np.sqrt((nodes[b, 0] - nodes[a, 0]) ** 2 + (nodes[b, 1] - nodes[a, 1]) ** 2)
    return a, b, w


@njit(cache=True)
def visible_from_point(p, nodes, prev, nxt, corner, edges, ring_ptr, ring_box, eps2):
    """Nodes visible from a free point ``p`` (pixels) along a segment tangent at the node.

    The arrays are a :class:`VisGraph`'s fields (:meth:`VisGraph.visible_from` passes them);
    a ``corner`` mask of all ``False`` drops the tangent rule, leaving visibility alone.
    Returns the node indices (int64, ascending).
    """
    out = []
    for j in range(len(nodes)):
        if corner[j] and not _tangent(
            nodes[j, 0],
            nodes[j, 1],
            prev[j, 0],
            prev[j, 1],
            prev[j, 2],
            nxt[j, 0],
            nxt[j, 1],
            nxt[j, 2],
            p[0],
            p[1],
            eps2,
        ):
            continue
        if _visible(p[0], p[1], nodes[j, 0], nodes[j, 1], edges, ring_ptr, ring_box):
            out.append(j)
    return np.array(out, dtype=np.int64)


@njit(cache=True)
def csr_dijkstra(indptr, indices, weights, init_nodes, init_dist):
    """Shortest distances over a CSR graph from a virtual source joined to ``init_nodes``.

    Parameters
    ----------
    indptr, indices, weights : numpy.ndarray
        The graph (CSR; int64 pointers and targets, edge lengths >= 0 in pixels).
    init_nodes : numpy.ndarray of int64
        Nodes the virtual source reaches, at distances ``init_dist`` (pixels).

    Returns
    -------
    dist : numpy.ndarray
        Distance per node (``inf``: unreachable).
    pred : numpy.ndarray of int64
        Predecessor per node: ``-1`` at a source node, ``-2`` unreached.
    """
    n = len(indptr) - 1
    dist = np.full(n, np.inf)
    pred = np.full(n, -2, dtype=np.int64)
    keys, ids, nh = heap_new()  # entries (distance, 0.0, node): heapq's (distance, node) order
    for k in range(len(init_nodes)):
        v = init_nodes[k]
        if init_dist[k] < dist[v]:
            dist[v] = init_dist[k]
            pred[v] = -1
            keys, ids, nh = heap_push(keys, ids, nh, init_dist[k], 0.0, v)
    done = np.zeros(n, dtype=np.bool_)
    while nh > 0:
        d, _, u, nh = heap_pop(keys, ids, nh)
        if done[u]:
            continue
        done[u] = True
        for e in range(indptr[u], indptr[u + 1]):
            v = indices[e]
            nd = d + weights[e]
            if nd < dist[v]:
                dist[v] = nd
                pred[v] = u
                keys, ids, nh = heap_push(keys, ids, nh, nd, 0.0, v)
    return dist, pred


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
        return bool(_visible(p[0], p[1], q[0], q[1], self.edges, self.ring_ptr, self.ring_box))

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
            "mawdo.planning.visgraph.build and oracle.shortest_path take a larger max_nodes"
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
    i, j, w = _edges(nodes, prev, nx, corner, edges, ring_ptr, ring_box, eps2)
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
