"""Compiled A* over (vertex, safe interval) states on arrival time.

A state is one safe interval of one graph vertex (its global index in the interval arrays);
its value is the earliest arrival in it. Expanding a state reached at ``a`` tries every graph
edge ``u -> v`` (driven straight at full speed, duration ``T``): the departures that collide
are :func:`~mawdo.planning.sipp.intervals.forbidden` over ``[a, end of u's interval]`` (the
robot may wait in its interval), and for each safe interval ``J`` of ``v`` the earliest free
departure that arrives no earlier than ``J`` opens gives the arrival in ``J``. Every accepted
departure is re-checked by :func:`~mawdo.planning.sipp.intervals.segment_free` (the wait at
``u``, then the move); one the exact intervals allow but the re-check refuses (rounding at a
touching contact) is pushed on by ``10 EPS`` a few times, then dropped. The heuristic, the
straight-line time to the goal, never exceeds a move's duration plus its wait, so it is
consistent and the first goal state popped has the earliest arrival on this graph.
"""

from __future__ import annotations

import heapq
import math

import numpy as np
from numba import njit

from mawdo.planning.sipp.intervals import EPS, earliest_free, forbidden, segment_free

__all__ = ["search"]

_RETRIES = 3


@njit(cache=True)
def _depart(ux, uy, vx, vy, a, T, F, x, top, J_hi, mv):
    """Earliest checked departure ``>= x`` (``inf`` if none arrives before ``J_hi``)."""
    tau = earliest_free(F, x)
    for _ in range(_RETRIES):
        if tau > top or tau + T >= J_hi:
            return math.inf
        if segment_free(ux, uy, ux, uy, a, tau, mv) and segment_free(
            ux, uy, vx, vy, tau, tau + T, mv
        ):
            return tau
        tau = earliest_free(F, tau + 10.0 * EPS)
    return math.inf


@njit(cache=True)
def _start_state(ptr, lo, hi, start, t0, pos, mv):
    for sid in range(ptr[start], ptr[start + 1]):
        if lo[sid] <= t0 < hi[sid]:
            if segment_free(pos[0], pos[1], pos[0], pos[1], t0, t0, mv):
                return sid
    return -1


@njit(cache=True)
def search(nodes, indptr, indices, weights, speed, start, goal, t0, t_end, ptr, lo, hi, banned, mv):
    """Earliest arrival at ``goal`` from ``start`` at ``t0`` over (vertex, interval) states.

    Parameters
    ----------
    nodes : numpy.ndarray, shape (n, 2)
        Vertices (pixels); ``indptr, indices, weights`` their graph (CSR, edge lengths in px).
    speed : float
        Robot speed (px per time step), > 0.
    start, goal : int
        Vertex indices.
    t0, t_end : float
        Departure time and horizon (time steps).
    ptr, lo, hi : numpy.ndarray
        Safe intervals per vertex (:func:`~mawdo.planning.sipp.intervals.safe_intervals`).
    banned : numpy.ndarray of bool
        Interval states the search may not enter (for alternatives).
    mv : tuple
        :meth:`~mawdo.planning.sipp.intervals.Movers.arrays`.

    Returns
    -------
    goal_state : int
        The goal's interval reached first (-1: none; -2: the start is not safe at ``t0``).
    arrival, parent, depart : numpy.ndarray
        Per interval state: earliest arrival, previous state, departure from its vertex.
    """
    S = len(lo)
    owner = np.empty(S, np.int64)
    for v in range(len(ptr) - 1):
        owner[ptr[v] : ptr[v + 1]] = v
    arrival = np.full(S, np.inf)
    parent = np.full(S, -1, np.int64)
    depart = np.full(S, np.nan)
    closed = np.zeros(S, np.bool_)
    s0 = _start_state(ptr, lo, hi, start, t0, nodes[start], mv)
    if s0 < 0:
        return -2, arrival, parent, depart
    gx, gy = nodes[goal, 0], nodes[goal, 1]
    arrival[s0] = t0
    heap = [(t0 + math.hypot(nodes[start, 0] - gx, nodes[start, 1] - gy) / speed, t0, s0)]
    while heap:
        _, a, sid = heapq.heappop(heap)
        if closed[sid]:
            continue
        closed[sid] = True
        u = owner[sid]
        if u == goal:
            return sid, arrival, parent, depart
        ux, uy = nodes[u, 0], nodes[u, 1]
        for e in range(indptr[u], indptr[u + 1]):
            v = indices[e]
            T = weights[e] / speed
            top = min(hi[sid], t_end - T)
            if top < a or T <= 0.0:
                continue
            vx, vy = nodes[v, 0], nodes[v, 1]
            F = forbidden(ux, uy, (vx - ux) / T, (vy - uy) / T, T, a, top, mv)
            for J in range(ptr[v], ptr[v + 1]):
                if hi[J] <= a + T or closed[J] or banned[J]:
                    continue
                if lo[J] >= top + T:
                    break
                tau = _depart(ux, uy, vx, vy, a, T, F, max(a, lo[J] - T), top, hi[J], mv)
                if tau + T < arrival[J]:
                    arrival[J] = tau + T
                    parent[J] = sid
                    depart[J] = tau
                    h = math.hypot(vx - gx, vy - gy) / speed
                    heapq.heappush(heap, (tau + T + h, tau + T, J))
    return -1, arrival, parent, depart
