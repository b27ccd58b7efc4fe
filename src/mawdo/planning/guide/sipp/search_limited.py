"""Compiled A* over (vertex, safe interval) states with rest-to-rest edge profiles.

The search of :mod:`mawdo.planning.guide.sipp.search` under acceleration or turn-rate limits
(:mod:`mawdo.planning.guide.sipp.profile`): an edge ``u -> v`` takes the whole steps ``T`` of its
profile, departures and arrivals are whole steps (the run's clock; the start time is one), and
the robot stands at ``u`` at least :func:`~mawdo.planning.guide.sipp.profile.rest_steps` steps after
arriving there (its heading in is the edge it arrived by, or the start's heading). The
departures at which the profile collides are the union over its uniform pieces of the
departures at which each piece, shifted by its start, collides
(:func:`~mawdo.planning.guide.sipp.intervals.forbidden`, exact); every accepted departure is
re-checked piece by piece with :func:`~mawdo.planning.guide.sipp.intervals.segment_free` (and the
wait at ``u`` before it). The positions the run drives at whole steps are the profile's, and
between them it moves straight and uniformly, so the check covers exactly what is driven.

The heuristic, the static distance to the goal over ``v``, never exceeds an edge's steps plus
the heuristic where it arrives (``T >= L / v``), so every arrival is monotone along a route.
The rest at a vertex depends on the edge the robot came by, which a (vertex, interval) state
does not hold: the route found is safe and its timing exact, but a later arrival in the same
interval from another heading, which could turn faster, is not kept, so the earliest arrival
is over the routes this search keeps, not proven over all of them.
"""

from __future__ import annotations

import heapq
import math

import numpy as np
from numba import njit

from mawdo.planning.guide.sipp.intervals import forbidden, segment_free
from mawdo.planning.guide.sipp.profile import rest_steps
from mawdo.planning.guide.sipp.search import start_state

__all__ = ["profile_forbidden", "profile_free", "search_limited"]

_RETRIES = 3
_WINDOW = 8.0


@njit(cache=True)
def profile_forbidden(ux, uy, dx, dy, k0, c0, dur, w, lo, hi, mv):
    """Departures in ``[lo, hi]`` (time steps) at which the profile from ``u`` along the unit
    heading ``d`` (pieces ``k0, c0, dur, w``) meets a mover: sorted, disjoint closed
    intervals ``(k, 2)``."""
    parts = np.empty((0, 2))
    for j in range(len(k0)):
        F = forbidden(
            ux + c0[j] * dx, uy + c0[j] * dy, w[j] * dx, w[j] * dy, dur[j],
            lo + k0[j], hi + k0[j], mv,
        )  # fmt: skip
        parts = np.concatenate((parts, F - k0[j]))
    parts = parts[np.argsort(parts[:, 0])]
    out = np.empty_like(parts)
    k = 0
    for j in range(len(parts)):
        if k > 0 and parts[j, 0] <= out[k - 1, 1]:
            out[k - 1, 1] = max(out[k - 1, 1], parts[j, 1])
        else:
            out[k] = parts[j]
            k += 1
    return out[:k]


@njit(cache=True)
def profile_free(ux, uy, dx, dy, k0, c0, dur, w, tau, mv):
    """True iff the profile departing at ``tau`` keeps clear of every mover (each piece by
    :func:`~mawdo.planning.guide.sipp.intervals.segment_free`)."""
    for j in range(len(k0)):
        ax, ay = ux + c0[j] * dx, uy + c0[j] * dy
        c1 = c0[j] + w[j] * dur[j]
        t1 = tau + k0[j]
        if not segment_free(ax, ay, ux + c1 * dx, uy + c1 * dy, t1, t1 + dur[j], mv):
            return False
    return True


@njit(cache=True)
def _integer_free(F, x):
    """The first whole step ``>= x`` outside the closed intervals ``F`` (sorted, disjoint)."""
    tau = float(math.ceil(x))
    for j in range(len(F)):
        if F[j, 1] < tau:
            continue
        if F[j, 0] > tau:
            break
        tau = math.floor(F[j, 1]) + 1.0
    return tau


@njit(cache=True)
def _depart(ux, uy, d, pc, a, T, x, top, J_hi, mv):
    """Earliest checked whole-step departure ``>= x`` and ``<= top`` whose arrival precedes
    ``J_hi`` (``inf`` if none); forbidden sets over growing windows, as in the plain search."""
    dx, dy = d
    k0, c0, dur, w = pc
    lo, span, tries = float(math.ceil(x)), _WINDOW, 0
    while lo <= top and lo + T < J_hi:
        hi = min(top, lo + span)
        tau = _integer_free(profile_forbidden(ux, uy, dx, dy, k0, c0, dur, w, lo, hi, mv), lo)
        if tau > hi:
            if hi == top:
                return math.inf
            lo, span = hi, 2.0 * span
            continue
        if tau + T >= J_hi:
            return math.inf
        if segment_free(ux, uy, ux, uy, a, tau, mv) and profile_free(
            ux, uy, dx, dy, k0, c0, dur, w, tau, mv
        ):
            return tau
        tries += 1  # refused at a touching contact (rounding): the next step
        if tries == _RETRIES:
            return math.inf
        lo = tau + 1.0
    return math.inf


@njit(cache=True)
def search_limited(graph, table, lim, start, goal, t_start, h0, t_end, ptr, lo, hi, banned, mv):
    """Earliest arrival at ``goal`` from ``start`` at the whole step ``t_start``.

    Parameters
    ----------
    graph : tuple
        ``(nodes, indptr, indices, weights, to_goal)`` as in
        :func:`~mawdo.planning.guide.sipp.search.search`.
    table : tuple
        :func:`~mawdo.planning.guide.sipp.profile.profile_table` of ``weights``.
    lim : tuple
        ``(v, accel_on, turn)``: speed (px per step, > 0), whether acceleration is limited,
        turn rate (radians per step, ``inf`` for none).
    h0 : numpy.ndarray, shape (2,)
        Unit heading the robot has at the start (zeros: none).
    t_end, ptr, lo, hi, banned, mv
        As in :func:`~mawdo.planning.guide.sipp.search.search`.

    Returns
    -------
    goal_state, arrival, parent, depart
        As :func:`~mawdo.planning.guide.sipp.search.search` (``-2``: the start is not safe).
    """
    nodes, indptr, indices, weights, to_goal = graph
    v = lim[0]
    S = len(lo)
    owner = np.empty(S, np.int64)
    for q in range(len(ptr) - 1):
        owner[ptr[q] : ptr[q + 1]] = q
    arrival = np.full(S, np.inf)
    parent = np.full(S, -1, np.int64)
    depart = np.full(S, np.nan)
    heading = np.zeros((S, 2))
    closed = np.zeros(S, np.bool_)
    s0 = start_state(ptr, lo, hi, start, t_start, nodes[start], mv)
    if s0 < 0:
        return -2, arrival, parent, depart
    arrival[s0] = t_start
    heading[s0, 0], heading[s0, 1] = h0[0], h0[1]
    heap = [(t_start + to_goal[start] / v, t_start, s0)]
    state = (arrival, parent, depart, heading, closed, banned)
    while heap:
        _, a, sid = heapq.heappop(heap)
        if closed[sid]:
            continue
        closed[sid] = True
        u = owner[sid]
        if u == goal:
            return sid, arrival, parent, depart
        for e in range(indptr[u], indptr[u + 1]):
            vv = indices[e]
            if not to_goal[vv] < math.inf:
                continue
            _edge(nodes, u, vv, e, weights[e], sid, a, table, lim, t_end, ptr, lo, hi, state,
                  heap, to_goal[vv] / v, mv)  # fmt: skip
    return -1, arrival, parent, depart


@njit(cache=True)
def _edge(nodes, u, vv, e, L, sid, a, table, lim, t_end, ptr, lo, hi, state, heap, hv, mv):
    """Arrivals in the safe intervals of ``vv`` by edge ``e`` from ``u`` (state ``sid``,
    reached at ``a``)."""
    arrival, parent, depart, heading, closed, banned = state
    tptr, k0, c0, dur, w, steps = table
    T = steps[e]
    dx, dy = 0.0, 0.0
    if L > 0.0:
        dx, dy = (nodes[vv, 0] - nodes[u, 0]) / L, (nodes[vv, 1] - nodes[u, 1]) / L
    ready = a + rest_steps(heading[sid, 0], heading[sid, 1], dx, dy, lim[1], lim[2])
    top = min(hi[sid], t_end - T)
    if top < ready:
        return
    i, j = tptr[e], tptr[e + 1]
    pc = (k0[i:j], c0[i:j], dur[i:j], w[i:j])
    ux, uy = nodes[u, 0], nodes[u, 1]
    for J in range(ptr[vv], ptr[vv + 1]):
        if hi[J] <= ready + T or closed[J] or banned[J]:
            continue
        if lo[J] >= top + T:
            break
        x = float(math.ceil(max(ready, lo[J] - T)))
        if x + T >= arrival[J]:  # no earlier arrival possible: skip the exact search
            continue
        tau = _depart(ux, uy, (dx, dy), pc, a, T, x, top, hi[J], mv)
        if tau + T < arrival[J]:
            arrival[J], parent[J], depart[J] = tau + T, sid, tau
            if L > 0.0:
                heading[J, 0], heading[J, 1] = dx, dy
            else:
                heading[J, 0], heading[J, 1] = heading[sid, 0], heading[sid, 1]
            heapq.heappush(heap, (tau + T + hv, tau + T, J))
