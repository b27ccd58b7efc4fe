"""Compiled A* over (vertex, safe interval) states on arrival time, with or without limits.

A state is one safe interval of one graph vertex (its row in the lazy table of
:mod:`~mawdo.planning.guide.sipp.lazy`: a vertex's intervals are made when the search first
expands a state next to it, and states that tie are ordered as the table of every vertex would
number them); its value is the earliest arrival in it. An edge ``u -> v`` is driven as its
*moves*, a table of straight uniform pieces, and how the robot drives is data,
``kin = (v, accel_on, turn, whole)`` (``whole`` None: straight moves, one piece each, and the
search compiled without the several-piece code, which a type decides; see
:func:`~mawdo.planning.guide.sipp.moves.pieces_forbidden_for`):

* without limits (:func:`search`, moves :func:`straight_moves`): one piece at full speed ``v``,
  duration ``T = L / v``, departures at any time, instant starts, stops and turns;
* under acceleration or turn-rate limits (:func:`search_limited`, moves
  :func:`profiled_moves`): the edge's rest-to-rest profile
  (:mod:`mawdo.planning.guide.sipp.profile`), ``T`` its whole steps, departures at whole steps
  (the run's clock; the start time is one), and the robot stands at ``u`` at least
  :func:`~mawdo.planning.guide.sipp.profile.rest_steps` steps after arriving there (its heading
  in is the edge it arrived by, or the start's; without limits that rest is zero).

Expanding a state reached at ``a`` tries every edge ``u -> v``: the departures that collide are
the union over its pieces of the departures at which each piece, shifted by its start, meets a
mover (:func:`~mawdo.planning.guide.sipp.intervals.forbidden`, exact), within ``[ready, end of
u's interval]`` (the robot may wait in its interval), and for each safe interval ``J`` of ``v``
the earliest free departure that arrives no earlier than ``J`` opens gives the arrival in ``J``
(the forbidden sets are computed over windows that grow from there until a free departure is
found). Every accepted departure is re-checked by
:func:`~mawdo.planning.guide.sipp.intervals.segment_free` (the wait at ``u``, then each piece); one
the exact intervals allow but the re-check refuses (rounding at a touching contact) is pushed on
(by ``10 EPS``, or to the next whole step) a few times, then dropped. The positions driven are
the pieces', straight and uniform in between, so the check covers exactly what is driven.

The heuristic, the static shortest time to the goal at speed ``v``, never exceeds a move's
duration plus its wait plus the heuristic where it arrives (``T >= L / v``). Without limits it is
consistent and the first goal state popped has the earliest arrival on this graph. With limits
the rest at a vertex depends on the edge the robot came by, which a state does not hold: the
route found is safe and its timing exact, but a later arrival in the same interval from another
heading, which could turn faster, is not kept, so the earliest arrival is over the routes this
search keeps. Either way, once a goal arrival is known, a target interval whose earliest
possible arrival plus heuristic exceeds it cannot be popped before that goal state, so its exact
departure is never searched.

Lazy relaxation: expanding a state does not search the exact departures of its moves at once.
Each move to a target interval ``J`` goes on a second heap with its lower bound, the departure
``x`` it cannot precede: key ``x + T + h``, arrival ``x + T``, then ``J``. Its exact departure is
searched when that entry is the least of both heaps (a lazy entry first on a tie with a state's
entry); by then ``J`` may be closed, or reached earlier, and the search is skipped (on the
1000 x 1000 px map with 200 movers about half of them). The states close in the same order with
the same arrival, parent and departure as when every move was settled at its expansion: a state
comes off the heap at its arrival's key, and every move that could reach it as early has a lower
bound at most that key, so it has been settled before; the state keeps the earliest arrival and,
among equal ones, the move the eager order settles first (its source expanded first, then the
lower edge), as the eager search's strict ``<`` kept the first. Moves to the goal are settled
first (the order of settling changes none of this): their arrival bounds the others early.
A move from a state reached after the movers' last piece ends (a guide's lookahead cuts them
there) leaves at its first departure ``x``, which is what the exact search would return: no
forbidden set can start after that time.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.guide.heap import heap_new, heap_pop, heap_push, heap_put, heap_room
from mawdo.planning.guide.sipp.departures import new_memo, window_forbidden
from mawdo.planning.guide.sipp.index import candidates
from mawdo.planning.guide.sipp.intervals import (
    EPS,
    earliest_free,
    forbidden_among,
    segment_free,
    segment_free_among,
)
from mawdo.planning.guide.sipp.lazy import JB, order_key, state_of, touch, vertex_bits
from mawdo.planning.guide.sipp.moves import (
    pieces_forbidden,
    pieces_forbidden_for,
    pieces_free,
    pieces_free_for,
    profiled_moves,
    straight_moves,
    straight_rows,
)
from mawdo.planning.guide.sipp.profile import rest_steps

__all__ = [
    "pieces_forbidden",
    "pieces_free",
    "profiled_moves",
    "search",
    "search_limited",
    "start_state",
    "straight_moves",
    "straight_rows",
    "timed_search",
]

_RETRIES = 3
#: First window of departures examined per edge and target interval (time steps).
_WINDOW = 8.0


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


@njit(cache=True, inline="always")
def _depart(moves, e, ux, uy, a, T, x, top, J_hi, whole, mv, memo, key):
    """Earliest checked departure ``>= x`` and ``<= top`` (a whole step if ``whole``) whose
    arrival precedes ``J_hi`` (``inf`` if none), and the memo (grown if it had to). The
    forbidden departures are computed over windows growing from ``x`` (the answer is usually
    at or just after it), each exact over its span; a one-piece move of a roadmap edge
    (``key >= 0``) takes them from ``memo`` (:mod:`~mawdo.planning.guide.sipp.departures`: the
    same sets, kept)."""
    eptr, _, piece = moves
    i, j = eptr[e], eptr[e + 1]
    # one piece from the departure (every edge without limits): the movers near the window
    # serve its departure sets and the re-check of the move alike, as one query
    one, near = j - i == 1 and piece[i, 0] == 0.0, np.empty(0, np.int64)
    ax, ay, ex, ey, dur, bx, by = piece[i, 1:8] if one else np.zeros(7)
    lo, span, tries = x, _WINDOW, 0
    while lo <= top and lo + T < J_hi:
        hi = min(top, lo + span)
        if one and key >= 0:
            F, near, memo = window_forbidden(memo, key, ax, ay, ex, ey, dur, lo, hi, mv)
        elif one:
            near = candidates(ax, ay, ex, ey, dur, lo, hi, mv[15])
            F = forbidden_among(ax, ay, ex, ey, dur, lo, hi, mv, near)
        else:
            F = pieces_forbidden_for(whole, piece, i, j, lo, hi, mv)
        tau = _integer_free(F, lo) if whole else earliest_free(F, lo)
        if tau > hi:  # forbidden up to the window's end: look further
            if hi == top:
                return math.inf, memo
            lo, span = hi, 2.0 * span
            continue
        if tau + T >= J_hi:
            return math.inf, memo
        if one and len(near) == 1 and near[0] < 0:  # the window's own (as computed afresh)
            near = candidates(ax, ay, ex, ey, dur, lo, hi, mv[15])
        if segment_free(ux, uy, ux, uy, a, tau, mv) and (
            segment_free_among(ax, ay, bx, by, tau, tau + dur, mv, near)
            if one
            else pieces_free_for(whole, piece, i, j, tau, mv)
        ):
            return tau, memo
        tries += 1  # refused at a touching contact (rounding): push on a little
        if tries == _RETRIES:
            return math.inf, memo
        lo = tau + (1.0 if whole else 10.0 * EPS)
    return math.inf, memo


@njit(cache=True)
def start_state(a, b, lo, hi, t0, pos, mv):
    """Among the safe intervals ``a .. b - 1`` of the start's vertex, the one holding ``t0``
    in which standing at ``pos`` (pixels) at ``t0`` is safe, or -1."""
    for sid in range(a, b):
        if lo[sid] <= t0 < hi[sid]:
            if segment_free(pos[0], pos[1], pos[0], pos[1], t0, t0, mv):
                return sid
    return -1


@njit(cache=True)
def _states(S):
    """The search's arrays per interval state (arrival, parent, departure, heading in,
    closed, rank among the expanded, edge its arrival came by) before it starts."""
    return _regrown(
        (np.empty(0), np.empty(0, np.int64), np.empty(0), np.empty((0, 2)),
         np.empty(0, np.bool_), np.empty(0, np.int64), np.empty(0, np.int64)), S,
    )  # fmt: skip


@njit(cache=True)
def _regrown(st, S):
    """The state arrays ``st`` (:func:`_states`) with room for ``S`` states, the old ones
    copied and the new ones as before a search. (Loops, not slices or ``np.full``: they cost
    Numba about a second more to compile.)"""
    arrival, parent, depart, heading = (
        np.empty(S),
        np.empty(S, np.int64),
        np.empty(S),
        np.empty((S, 2)),
    )
    closed, rank, via = np.empty(S, np.bool_), np.empty(S, np.int64), np.empty(S, np.int64)
    n = len(st[0])
    for s in range(S):
        old = s < n
        arrival[s] = st[0][s] if old else np.inf
        parent[s] = st[1][s] if old else -1
        depart[s] = st[2][s] if old else np.nan
        heading[s, 0] = st[3][s, 0] if old else 0.0
        heading[s, 1] = st[3][s, 1] if old else 0.0
        closed[s] = st[4][s] if old else False
        rank[s] = st[5][s] if old else -1
        via[s] = st[6][s] if old else -1
    return arrival, parent, depart, heading, closed, rank, via


@njit(cache=True)
def timed_search(graph, moves, kin, start, goal, t_start, h0, t_end, table, banned, mv, memo, kept):
    """Earliest arrival at ``goal`` from ``start`` at ``t_start`` over (vertex, interval) states.

    Parameters
    ----------
    graph : tuple
        ``(nodes, indptr, indices, weights, to_goal)``: vertices (pixels, shape ``(n, 2)``),
        their graph (CSR, edge lengths in px) and the static distance to the goal over it
        (px; ``inf``: cut off), the heuristic.
    moves : tuple
        The edges' pieces (:func:`straight_moves` or :func:`profiled_moves`).
    kin : tuple
        ``(v, accel_on, turn, whole)``: speed (px per step, > 0), whether acceleration is
        limited, turn rate (radians per step, ``inf`` for none), whether departures are whole
        steps (module docstring); ``whole`` None for straight moves (:func:`straight_moves`:
        any departure, and no several-piece code compiled).
    start, goal : int
        Vertex indices.
    t_start : float
        Departure time (time steps; a whole step if ``whole``).
    h0 : numpy.ndarray, shape (2,)
        Unit heading the robot has at the start (zeros: none).
    t_end : float
        Horizon (time steps).
    table : tuple
        Safe intervals per vertex, made as the search touches the vertices
        (:func:`~mawdo.planning.guide.sipp.lazy.new_table`; a table a search of the same
        query returned may be given again: its states keep their numbers).
    banned : numpy.ndarray of bool
        Interval states the search may not enter (for alternatives; states past its end are
        not barred).
    mv : tuple
        :meth:`~mawdo.planning.guide.sipp.intervals.Movers.arrays`.
    memo : tuple
        Forbidden departures kept per edge
        (:func:`~mawdo.planning.guide.sipp.departures.new_memo`; filled as the search goes).
        Give one only to searches whose ``mv`` are slices of the same motion (see
        :mod:`~mawdo.planning.guide.sipp.departures`).
    kept : int
        The edges ``e < kept`` (one-piece moves only) use and fill ``memo``; 0: none.

    Returns
    -------
    goal_state : int
        The goal's interval reached first (-1: none; -2: the start is not safe at ``t_start``).
    arrival, parent, depart : numpy.ndarray
        Per interval state (the table's rows, at least ``table``'s ``used``): earliest
        arrival, previous state, departure from its vertex.
    memo : tuple
        ``memo`` with what this search found (a new, larger one when it had to grow).
    table : tuple
        ``table`` with the intervals of every vertex the search touched.
    """
    nodes, indptr, indices, weights, to_goal = graph
    table = touch(table, start, nodes, mv)
    first, count, lo, hi, owner, used = table[2:]
    st = _states(len(lo))
    arrival, parent, depart, heading, closed, rank, via = st
    s0 = start_state(first[start], first[start] + count[start], lo, hi, t_start, nodes[start],
                     mv)  # fmt: skip
    if s0 < 0:
        return -2, arrival, parent, depart, memo, table
    arrival[s0] = t_start
    heading[s0, 0], heading[s0, 1] = h0[0], h0[1]
    keys, ids, nh = heap_new()
    keys, ids, nh = heap_push(keys, ids, nh, t_start + to_goal[start] / kin[0], t_start,
                              order_key(first, owner, s0))  # fmt: skip
    # the earliest goal arrival found so far: no state whose arrival plus heuristic exceeds it
    # can precede the goal off the heap, so its exact departure is never needed
    bound = math.inf
    edge, whole = moves[1], kin[3]
    # moves waiting for their exact departure (module docstring: lazy relaxation): a heap of
    # lower bounds, each entry's source state and edge; its target interval's order key is its
    # id's top, above `shift` bits
    lkeys, lids, ln = heap_new()
    lsrc, ledge, made = np.empty(16, np.int64), np.empty(16, np.int64), 0
    shift = 63 - JB - vertex_bits(len(nodes))
    low = (1 << shift) - 1
    expanded = 0
    # no mover is tested after t_free (its pieces end there; reachable sets never end): a
    # move from a vertex reached after it is free at its first departure, as _depart finds
    t_free = _movers_end(mv)
    # The loops are written out here, every table bound once above: Numba counts each binding
    # of an array (an atomic increment and decrement), and an inlined relaxation per edge
    # bound about twenty tables, 60 % of the search's CPU on the 1000 x 1000 px, 200-mover map.
    while nh > 0 or ln > 0:
        if ln > 0 and (nh == 0 or _lazy_first(lkeys, lids, keys, ids, shift)):
            _, _, lid, ln = heap_pop(lkeys, lids, ln)
            J, sid, e = state_of(first, lid >> shift), lsrc[lid & low], ledge[lid & low]
            if closed[J]:
                continue
            u, v, a, T = owner[sid], indices[e], arrival[sid], edge[e, 0]
            ready = a + rest_steps(heading[sid, 0], heading[sid, 1], edge[e, 1], edge[e, 2],
                                   kin[1], kin[2])  # fmt: skip
            top, hv = min(hi[sid], t_end - T), to_goal[v] / kin[0]
            x = max(ready, lo[J] - T)
            if whole:
                x = float(math.ceil(x))
            # (as when it was made; the arrival and the bound may have fallen since)
            if x + T + hv > bound or not _may_win(x + T, J, sid, e, arrival, parent, rank, via):
                continue
            if a >= t_free and x <= top and x + T < hi[J]:  # no mover left: x is free
                tau = x
            else:
                tau, memo = _depart(moves, e, nodes[u, 0], nodes[u, 1], a, T, x, top, hi[J],
                                    whole, mv, memo, e if e < kept else -1)  # fmt: skip
            if not _may_win(tau + T, J, sid, e, arrival, parent, rank, via):
                continue
            if tau + T < arrival[J]:
                keys, ids, nh = heap_push(keys, ids, nh, tau + T + hv, tau + T,
                                          order_key(first, owner, J))  # fmt: skip
            arrival[J], parent[J], depart[J], via[J] = tau + T, sid, tau, e
            if weights[e] > 0.0:  # a move: its heading; else the one it had
                heading[J, 0], heading[J, 1] = edge[e, 1], edge[e, 2]
            else:
                heading[J, 0], heading[J, 1] = heading[sid, 0], heading[sid, 1]
            if v == goal:
                bound = min(bound, tau + T)
            continue
        _, a, skey, nh = heap_pop(keys, ids, nh)
        sid = state_of(first, skey)
        if closed[sid]:
            continue
        closed[sid], rank[sid], expanded = True, expanded, expanded + 1
        u = owner[sid]
        if u == goal:
            return sid, arrival, parent, depart, memo, table
        # the safe intervals of the vertices this state can move to, made where not yet
        need = 0
        for e in range(indptr[u], indptr[u + 1]):
            v = indices[e]
            if first[v] < 0 and to_goal[v] < math.inf:
                table = touch(table, v, nodes, mv)
                lo, hi, owner, used = table[4], table[5], table[6], table[7]
            need += count[v]
        if used > len(arrival):
            st = _regrown((arrival, parent, depart, heading, closed, rank, via), len(lo))
            arrival, parent, depart, heading, closed, rank, via = st
        lkeys, lids = heap_room(lkeys, lids, ln, need)
        if made + need > len(lsrc):
            if made + need > low:
                raise ValueError("the safe-interval search made more moves than it can order")
            lsrc, ledge = _grown(lsrc, made + need), _grown(ledge, made + need)
        for e in range(indptr[u], indptr[u + 1]):
            v = indices[e]
            if not to_goal[v] < math.inf:
                continue
            T = edge[e, 0]
            # standing at u first: turning in place, or the stop between two profiles
            ready = a + rest_steps(heading[sid, 0], heading[sid, 1], edge[e, 1], edge[e, 2],
                                   kin[1], kin[2])  # fmt: skip
            top = min(hi[sid], t_end - T)
            if top < ready:
                continue
            hv = to_goal[v] / kin[0]
            # the arrivals in the safe intervals of v by this move
            for J in range(first[v], first[v] + count[v]):
                if hi[J] <= ready + T or closed[J] or (J < len(banned) and banned[J]):
                    continue
                if lo[J] >= top + T:
                    break
                x = max(ready, lo[J] - T)
                if whole:
                    x = float(math.ceil(x))
                # the departure is >= x, so an arrival no earlier than the best known one is
                # certain: the exact (and costly) departure could not change anything
                if x + T >= arrival[J] or x + T + hv > bound:
                    continue
                lsrc[made], ledge[made] = sid, e
                # a move to the goal is settled first (as the eager search did): its arrival
                # bounds every other (the order of settling changes no result)
                key = -math.inf if v == goal else x + T + hv
                lid = (order_key(first, owner, J) << shift) | made
                ln = heap_put(lkeys, lids, ln, key, x + T, lid)
                made += 1
    return -1, arrival, parent, depart, memo, table


@njit(cache=True)
def _movers_end(mv):
    """The time (time steps) after which no mover of ``mv`` is tested: the end of its last
    piece; ``inf`` with a reachable set (it grows without end)."""
    kind, pt1 = mv[0], mv[12]
    for m in range(len(kind)):
        if kind[m] == 1:
            return math.inf
    end = -math.inf
    for k in range(len(pt1)):
        end = max(end, pt1[k])
    return end


@njit(cache=True, inline="always")
def _lazy_first(lkeys, lids, keys, ids, shift):
    """The least lazy entry comes before the least state entry: ``(key, arrival, interval)``
    not greater (a lazy entry first on a tie: its move may arrive there as early; intervals in
    the order of their order keys, the top of a lazy entry's id above ``shift`` bits)."""
    if lkeys[0, 0] != keys[0, 0]:
        return lkeys[0, 0] < keys[0, 0]
    if lkeys[0, 1] != keys[0, 1]:
        return lkeys[0, 1] < keys[0, 1]
    return (lids[0] >> shift) <= ids[0]


@njit(cache=True, inline="always")
def _may_win(t, J, sid, e, arrival, parent, rank, via):
    """An arrival ``t`` in interval ``J`` by edge ``e`` from state ``sid`` replaces the one
    known: earlier, or as early by a move the eager search relaxes first (its source expanded
    earlier, or the same source and a lower edge), which it keeps."""
    if t != arrival[J]:
        return t < arrival[J]
    p = parent[J]
    return p < 0 or rank[sid] < rank[p] or (sid == p and e < via[J])


@njit(cache=True)
def _grown(a, n):
    """``a`` copied into an array of at least ``n`` (and twice its) entries."""
    out = np.empty(max(n, 2 * len(a)), a.dtype)
    for i in range(len(a)):
        out[i] = a[i]
    return out


@njit(cache=True)
def search(
    nodes, indptr, indices, weights, to_goal, speed, start, goal, t0, t_end, table, banned, mv
):
    """:func:`timed_search` without limits: straight moves at ``speed`` (px per step, > 0),
    departures at any time from ``t0``, instant starts, stops and turns, no memo; the other
    arguments and the results (but the memo) as there."""
    moves = straight_moves(nodes, indptr, indices, weights, speed)
    res = timed_search(
        (nodes, indptr, indices, weights, to_goal), moves, (speed, False, math.inf, None),
        start, goal, t0, np.zeros(2), t_end, table, banned, mv, new_memo(2, 2), 0,
    )  # fmt: skip
    return res[0], res[1], res[2], res[3], res[5]


@njit(cache=True)
def search_limited(graph, profile, lim, start, goal, t_start, h0, t_end, table, banned, mv):
    """:func:`timed_search` under acceleration or turn-rate limits: each edge its rest-to-rest
    profile (:func:`~mawdo.planning.guide.sipp.profile.profile_table` of the graph's
    weights), departures at whole steps from the whole step ``t_start``, rests at the vertices.

    ``lim`` is ``(v, accel_on, turn)``: speed (px per step, > 0), whether acceleration is
    limited, turn rate (radians per step, ``inf`` for none); the other arguments and the
    results (but the memo: its moves are not straight) as in :func:`timed_search`.
    """
    nodes, indptr, indices, weights, _ = graph
    moves = profiled_moves(nodes, indptr, indices, weights, profile)
    res = timed_search(
        graph, moves, (lim[0], lim[1], lim[2], True), start, goal, t_start, h0, t_end, table,
        banned, mv, new_memo(2, 2), 0,
    )  # fmt: skip
    return res[0], res[1], res[2], res[3], res[5]
