"""The tangent visibility graph's compiled kernels (:mod:`mawdo.planning.guide.visgraph` builds the
graph around them): the tangency and visibility tests, the edge enumeration, a point's visible
corners and Dijkstra over the graph's CSR arrays.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from mawdo.planning.guide.heap import heap_new, heap_pop, heap_push

__all__ = ["csr_dijkstra", "segment_visible", "tangent_edges", "visible_from_point"]


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
def segment_visible(px, py, qx, qy, edges, ring_ptr, ring_box):
    """The segment pq meets no blocking edge (rings pre-filtered by their bounding boxes)."""
    lo_x, hi_x = min(px, qx), max(px, qx)
    lo_y, hi_y = min(py, qy), max(py, qy)
    # the line through pq, as n . (x - p) with n normal to it, and a margin of 1e-6 px in
    # those units: far above the rounding of the corners' sides (1e-10 at 1e4 px)
    nx, ny = py - qy, qx - px
    tol = 1e-6 * (abs(nx) + abs(ny))
    for r in range(len(ring_ptr) - 1):
        x0, y0, x1, y1 = ring_box[r, 0], ring_box[r, 1], ring_box[r, 2], ring_box[r, 3]
        if x0 > hi_x or x1 < lo_x or y0 > hi_y or y1 < lo_y:
            continue
        # a box wholly on one side of the line holds no edge the segment can touch (the
        # ring's box holds its edges): its edges need no test (a long segment's box overlaps
        # many rings its line misses)
        c0, c1 = nx * (x0 - px) + ny * (y0 - py), nx * (x1 - px) + ny * (y0 - py)
        c2, c3 = nx * (x0 - px) + ny * (y1 - py), nx * (x1 - px) + ny * (y1 - py)
        if min(c0, c1, c2, c3) > tol or max(c0, c1, c2, c3) < -tol:
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
def tangent_edges(nodes, prev, nxt, corner, edges, ring_ptr, ring_box, eps2):
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
            if segment_visible(ax, ay, bx, by, edges, ring_ptr, ring_box):
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
        if segment_visible(p[0], p[1], nodes[j, 0], nodes[j, 1], edges, ring_ptr, ring_box):
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
