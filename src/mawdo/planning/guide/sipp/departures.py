"""The forbidden departures of the roadmap's edges, kept and reused across searches and queries.

Proving that a move cannot leave in a window is most of the safe-interval search's work among
many movers: on a 1000 x 1000 px map with 1000 movers one search asks 134 000 departure
windows of as many edges, nearly all of them forbidden throughout (about 22 us each). The same
edge is asked again by the guide's next search of the query (a time-diverse alternative) and,
at the next replan, by the next query from the robot's new position.

The forbidden departures of an edge are a property of the edge and of the movers' motion
only, not of the state that asks. A memo keeps, per roadmap edge, the exact forbidden set
(sorted, disjoint closed intervals, as
:func:`~mawdo.planning.guide.sipp.intervals.forbidden_among` gives them) over one contiguous
span of departures, and answers a window inside the span from it; a window that reaches past
the span computes only the missing part and widens the span. The answer for a window is the
kept set clipped to it, which is what a fresh computation over that window returns, bit for bit:
each mover's forbidden interval is computed from its piece alone (not from the window), and the
union of intervals clipped to a window is the union clipped. So a search with a memo settles
every move at the same departure as without one.

Who may share a memo: searches whose movers' tables are slices of the same motion. The searches
of one query always do. The queries of a run share the roadmap's memo
(:meth:`~mawdo.planning.guide.sipp.roadmap.Roadmap.departures`) when there is no lookahead cut
(a cut piece ends early, so what lies beyond it is untested, and its velocity is re-rounded) and
no random walker taken as a reachable set (it grows from the query's own start time). When a
query keeps one at all is the guide's choice
(:meth:`~mawdo.planning.guide.sipp.guide.SafeIntervalGuide`, ``keep_departures``): filling a
memo costs about a tenth more search, repaid by the queries after it, or among many movers by
the query's own time-diverse alternatives.

The memo is plain arrays (Numba's jit table records only such arguments): an open-addressing
table of edges (``keys``, linear probing, at most half full) with each edge's span and its
intervals' place in a pool of rows. It starts small and doubles as it fills (a search hands the
grown one back); at :data:`MOST_EDGES` and :data:`MOST_ROWS` it stops taking more, answers the
rest afresh, and :func:`roomier` gives the next query an empty one.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from mawdo.planning.guide.sipp.index import candidates
from mawdo.planning.guide.sipp.intervals import forbidden_among

__all__ = ["empty_memo", "new_memo", "roomier", "window_forbidden"]

#: Largest memo: edges (a power of two; 40 bytes each) and pool rows (16 bytes each).
MOST_EDGES, MOST_ROWS = 1 << 21, 1 << 22
#: A new memo's least room: edges (a power of two).
FIRST_EDGES = 1 << 12


def empty_memo(edges: int = 0):
    """A new, empty memo with room for about a thirty-second of ``edges`` (a graph's edge
    count; at least :data:`FIRST_EDGES` // 2) before it first grows, and four interval rows
    per edge of room (a search on the 1000 x 1000 px world asks about a tenth of its
    roadmap's edges, among 200 movers as among 1000; the memo doubles as it needs)."""
    size = max(FIRST_EDGES, 1 << max(0, int(edges // 16) - 1).bit_length())
    return new_memo(min(size, MOST_EDGES), min(2 * size, MOST_ROWS))


@njit(cache=True)
def new_memo(edges, rows):
    """An empty memo for up to ``edges // 2`` edges (``edges`` a power of two) and ``rows``
    forbidden intervals before it grows: ``(keys, span, first, count, pool, meta)``, ``meta``
    = (edges kept, pool rows used, full: no more room at the largest size)."""
    return (
        np.full(edges, -1, np.int64), np.empty((edges, 2)), np.zeros(edges, np.int64),
        np.zeros(edges, np.int64), np.empty((rows, 2)), np.zeros(3, np.int64),
    )  # fmt: skip


def roomier(memo):
    """``memo`` while it had room for all it was given; else a new, empty one as large."""
    return new_memo(len(memo[0]), len(memo[4])) if memo[5][2] else memo


@njit(cache=True)
def _slot(keys, key):
    """Where ``key`` is in the table, or the free slot where it would go."""
    mask = len(keys) - 1
    h = key & mask
    while keys[h] != -1 and keys[h] != key:
        h = (h + 1) & mask
    return h


@njit(cache=True)
def _unlooked():
    """The candidates of a window answered without looking them up: one entry, -1 (a new
    array: a global one would be typed read-only, and every kernel given it compiled twice)."""
    return np.full(1, -1, np.int64)


@njit(cache=True)
def _clip(rows, lo, hi):
    """The kept intervals ``rows`` clipped to ``[lo, hi]``."""
    out = np.empty((len(rows), 2))
    k = 0
    for j in range(len(rows)):
        a, b = max(rows[j, 0], lo), min(rows[j, 1], hi)
        if a > b:
            continue
        out[k, 0], out[k, 1] = a, b
        k += 1
    return out[:k]


@njit(cache=True)
def _joined(left, mid, right):
    """The intervals of ``left``, ``mid`` and ``right`` (each sorted and disjoint, in this
    order along time), touching ones merged (as the union over their whole span has them)."""
    out = np.empty((len(left) + len(mid) + len(right), 2))
    k = 0
    for part in (left, mid, right):
        for j in range(len(part)):
            a, b = part[j, 0], part[j, 1]
            if k > 0 and a <= out[k - 1, 1]:
                out[k - 1, 1] = max(out[k - 1, 1], b)
            else:
                out[k, 0], out[k, 1] = a, b
                k += 1
    return out[:k]


@njit(cache=True)
def _grown(memo, edges, rows):
    """``memo``'s entries in a memo with room for ``edges`` (a power of two) and ``rows``."""
    keys, span, first, count, pool, meta = memo
    out = new_memo(edges, rows)
    nkeys, nspan, nfirst, ncount, npool, nmeta = out
    used = 0
    for h in range(len(keys)):
        if keys[h] == -1:
            continue
        g = _slot(nkeys, keys[h])
        nkeys[g], nspan[g, 0], nspan[g, 1] = keys[h], span[h, 0], span[h, 1]
        nfirst[g], ncount[g] = used, count[h]
        for j in range(count[h]):  # (compacted: rows of spans widened since are dropped)
            npool[used + j, 0], npool[used + j, 1] = pool[first[h] + j, 0], pool[first[h] + j, 1]
        used += count[h]
    nmeta[0], nmeta[1] = meta[0], used
    return out


@njit(cache=True)
def _keep(memo, key, c0, c1, F):
    """``memo`` (grown when it lacks room) with ``F`` kept as the forbidden departures of edge
    ``key`` over ``[c0, c1]`` (a new edge or a wider span of it)."""
    keys, _, _, _, pool, meta = memo
    h = _slot(keys, key)
    new = keys[h] == -1
    edges, rows = len(keys), len(pool)
    if new and 2 * (meta[0] + 1) > edges:
        edges *= 2
    while meta[1] + len(F) > rows:
        rows *= 2
    if edges > len(keys) or rows > len(pool):
        if edges > MOST_EDGES or rows > MOST_ROWS:
            meta[2] = 1  # full: what is kept stays right, the rest is found afresh
            return memo
        memo = _grown(memo, edges, rows)
    keys, span, first, count, pool, meta = memo
    h = _slot(keys, key)
    for j in range(len(F)):  # (a loop: a slice assignment compiles an error message too)
        pool[meta[1] + j, 0], pool[meta[1] + j, 1] = F[j, 0], F[j, 1]
    keys[h], span[h, 0], span[h, 1] = key, c0, c1
    first[h], count[h] = meta[1], len(F)
    meta[1] += len(F)
    meta[0] += new
    return memo


@njit(cache=True)
def window_forbidden(memo, key, ax, ay, ex, ey, dur, lo, hi, mv):
    """The departures in ``[lo, hi]`` (time steps) at which the straight move from
    ``(ax, ay)`` at velocity ``(ex, ey)`` (px per step) for ``dur`` steps meets a mover of
    ``mv``: sorted, disjoint closed intervals, as
    :func:`~mawdo.planning.guide.sipp.intervals.forbidden_among` over its candidates returns
    them; taken from the memo's edge ``key`` (>= 0) where its span covers the window, the
    rest computed and kept.

    Returns ``(F, near, memo)``: ``near`` the window's candidate movers
    (:func:`~mawdo.planning.guide.sipp.index.candidates`) when they were looked up (the whole
    window computed afresh), else one entry, -1; ``memo`` the memo, grown if it had to.
    """
    # the fresh computations below are written out, not one helper taking mv: every call that
    # takes the movers' tables binds each of them again (an atomic count per array), and a
    # helper cost about a tenth more of a search among 200 movers (benchmarks/log/scaling.md)
    keys, span, first, count, pool, _ = memo
    h = _slot(keys, key)
    if keys[h] == key:
        c0, c1 = span[h, 0], span[h, 1]
        rows = pool[first[h] : first[h] + count[h]]
        if c0 <= lo and hi <= c1:
            return _clip(rows, lo, hi), _unlooked(), memo
        if lo <= c1 and c0 <= hi:  # overlapping or touching: widen the span
            left, right = np.empty((0, 2)), np.empty((0, 2))
            if lo < c0:
                near = candidates(ax, ay, ex, ey, dur, lo, c0, mv[15])
                left = forbidden_among(ax, ay, ex, ey, dur, lo, c0, mv, near)
            if c1 < hi:
                near = candidates(ax, ay, ex, ey, dur, c1, hi, mv[15])
                right = forbidden_among(ax, ay, ex, ey, dur, c1, hi, mv, near)
            F = _joined(left, rows, right)
            memo = _keep(memo, key, min(lo, c0), max(hi, c1), F)
            return _clip(F, lo, hi), _unlooked(), memo
    near = candidates(ax, ay, ex, ey, dur, lo, hi, mv[15])
    F = forbidden_among(ax, ay, ex, ey, dur, lo, hi, mv, near)
    return F, near, _keep(memo, key, lo, hi, F)
