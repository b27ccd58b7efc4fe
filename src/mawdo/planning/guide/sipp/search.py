"""Compiled A* over (vertex, safe interval) states on arrival time.

A state is one safe interval of one graph vertex (its global index in the interval arrays);
its value is the earliest arrival in it. Expanding a state reached at ``a`` tries every graph
edge ``u -> v`` (driven straight at full speed, duration ``T``): the departures that collide
are :func:`~mawdo.planning.guide.sipp.intervals.forbidden` within ``[a, end of u's interval]`` (the
robot may wait in its interval), and for each safe interval ``J`` of ``v`` the earliest free
departure that arrives no earlier than ``J`` opens gives the arrival in ``J`` (the forbidden
sets are computed over windows that grow from there until a free departure is found). Every accepted
departure is re-checked by :func:`~mawdo.planning.guide.sipp.intervals.segment_free` (the wait at
``u``, then the move); one the exact intervals allow but the re-check refuses (rounding at a
touching contact) is pushed on by ``10 EPS`` a few times, then dropped. The heuristic, the
static shortest time to the goal over the same graph, never exceeds a move's duration plus
its wait plus the heuristic where it arrives, so it is consistent and the first goal state
popped has the earliest arrival on this graph.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.guide.heap import heap_new, heap_pop, heap_push
from mawdo.planning.guide.sipp.index import candidates
from mawdo.planning.guide.sipp.intervals import (
    EPS,
    earliest_free,
    forbidden_among,
    segment_free,
    segment_free_among,
)

__all__ = ["search", "start_state"]

_RETRIES = 3
#: First window of departures examined per edge and target interval (time steps).
_WINDOW = 8.0


@njit(cache=True, inline="always")
def _depart(ux, uy, vx, vy, a, T, x, top, J_hi, mv):
    """Earliest checked departure ``>= x`` and ``<= top`` whose arrival precedes ``J_hi``
    (``inf`` if none). The forbidden departures are computed over windows growing from ``x``
    (the answer is usually at or just after it), each exact over its span."""
    # a zero-length edge (the start on a vertex) is a move of no duration
    ex, ey = ((vx - ux) / T, (vy - uy) / T) if T > 0.0 else (0.0, 0.0)
    lo, span, tries = x, _WINDOW, 0
    while lo <= top and lo + T < J_hi:
        hi = min(top, lo + span)
        # the movers near the move, for the departure sets and the re-check of the move alike
        near = candidates(ux, uy, ex, ey, T, lo, hi, mv[15])
        tau = earliest_free(forbidden_among(ux, uy, ex, ey, T, lo, hi, mv, near), lo)
        if tau > hi:  # forbidden up to the window's end: look further
            lo, span = hi, 2.0 * span
            if hi == top:
                return math.inf
            continue
        if tau + T >= J_hi:
            return math.inf
        if segment_free(ux, uy, ux, uy, a, tau, mv) and segment_free_among(
            ux, uy, vx, vy, tau, tau + T, mv, near
        ):
            return tau
        tries += 1  # refused at a touching contact (rounding): push on a little
        if tries == _RETRIES:
            return math.inf
        lo = tau + 10.0 * EPS
    return math.inf


@njit(cache=True)
def start_state(ptr, lo, hi, start, t0, pos, mv):
    """The safe interval of vertex ``start`` holding ``t0`` in which standing at ``pos``
    (pixels) at ``t0`` is safe, or -1."""
    for sid in range(ptr[start], ptr[start + 1]):
        if lo[sid] <= t0 < hi[sid]:
            if segment_free(pos[0], pos[1], pos[0], pos[1], t0, t0, mv):
                return sid
    return -1


@njit(cache=True)
def search(
    nodes, indptr, indices, weights, to_goal, speed, start, goal, t0, t_end, ptr, lo, hi, banned, mv
):
    """Earliest arrival at ``goal`` from ``start`` at ``t0`` over (vertex, interval) states.

    Parameters
    ----------
    nodes : numpy.ndarray, shape (n, 2)
        Vertices (pixels); ``indptr, indices, weights`` their graph (CSR, edge lengths in px).
    to_goal : numpy.ndarray, shape (n,)
        Static distance to the goal over the graph (px; ``inf``: cut off): the heuristic.
    speed : float
        Robot speed (px per time step), > 0.
    start, goal : int
        Vertex indices.
    t0, t_end : float
        Departure time and horizon (time steps).
    ptr, lo, hi : numpy.ndarray
        Safe intervals per vertex (:func:`~mawdo.planning.guide.sipp.intervals.safe_intervals`).
    banned : numpy.ndarray of bool
        Interval states the search may not enter (for alternatives).
    mv : tuple
        :meth:`~mawdo.planning.guide.sipp.intervals.Movers.arrays`.

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
    s0 = start_state(ptr, lo, hi, start, t0, nodes[start], mv)
    if s0 < 0:
        return -2, arrival, parent, depart
    arrival[s0] = t0
    keys, ids, nh = heap_new()
    keys, ids, nh = heap_push(keys, ids, nh, t0 + to_goal[start] / speed, t0, s0)
    # the earliest goal arrival found so far: no state whose arrival plus heuristic exceeds it
    # can precede the goal off the heap, so its exact departure is never needed
    bound = np.full(1, np.inf)
    state = (arrival, parent, depart, closed, banned, bound)
    while nh > 0:
        _, a, sid, nh = heap_pop(keys, ids, nh)
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
            if top < a or not to_goal[v] < math.inf:
                continue
            hv = to_goal[v] / speed
            keys, ids, nh = _relax(
                ux, uy, nodes[v], ptr[v], ptr[v + 1], sid, a, T, top, hv, v == goal, lo, hi,
                state, keys, ids, nh, mv,
            )  # fmt: skip
    return -1, arrival, parent, depart


@njit(cache=True, inline="always")
def _relax(ux, uy, pv, j0, j1, sid, a, T, top, hv, is_goal, lo, hi, state, keys, ids, nh, mv):
    """Arrivals in the safe intervals ``j0:j1`` of vertex ``pv`` (the goal if ``is_goal``) by
    the move from ``u``, pushed on the heap ``(keys, ids, nh)``
    (:mod:`mawdo.planning.guide.heap`), which it returns."""
    arrival, parent, depart, closed, banned, bound = state
    for J in range(j0, j1):
        if hi[J] <= a + T or closed[J] or banned[J]:
            continue
        if lo[J] >= top + T:
            break
        x = max(a, lo[J] - T)
        # the departure is >= x, so an arrival no earlier than the best known one is certain:
        # skip the exact (and costly) departure search, which could not change anything
        if x + T >= arrival[J] or x + T + hv > bound[0]:
            continue
        tau = _depart(ux, uy, pv[0], pv[1], a, T, x, top, hi[J], mv)
        if tau + T < arrival[J]:
            arrival[J] = tau + T
            parent[J] = sid
            depart[J] = tau
            keys, ids, nh = heap_push(keys, ids, nh, tau + T + hv, tau + T, J)
            if is_goal:
                bound[0] = min(bound[0], tau + T)
    return keys, ids, nh
