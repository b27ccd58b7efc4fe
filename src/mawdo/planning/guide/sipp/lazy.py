"""Safe intervals made lazily: for the vertices a search touches, when it first touches them.

A table ``(ta, tb, first, count, lo, hi, owner, used)`` holds the open safe intervals over
``[ta, tb]`` (time steps) of the vertices made so far: vertex ``v``'s are rows ``first[v] ..
first[v] + count[v] - 1`` of ``lo, hi`` (``first[v] = -1``: not made yet), ``owner[s]`` is the
vertex of row ``s`` and ``used`` the rows in use. A row is an interval *state* of the search
(:mod:`~mawdo.planning.guide.sipp.search`); rows are numbered in the order the vertices are
made, and grow (doubled) as they fill. Each vertex's intervals are those
:func:`~mawdo.planning.guide.sipp.intervals.safe_intervals` gives it (the same function,
:func:`~mawdo.planning.guide.sipp.intervals.vertex_intervals`), so a search over the lazy table
sees exactly the intervals of the eager one.

Where the search must order two states that tie on key and arrival, it orders them as the eager
table numbers them, vertex first, then interval: by :func:`order_key`, ``v`` shifted above
:data:`JB` bits and the interval's rank within its vertex below them, which
:func:`state_of` turns back into a row. Thus the search pops the same states in the same order
as over the eager table, and returns the same routes and times, bit for bit.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from mawdo.planning.guide.sipp.intervals import vertex_intervals

__all__ = ["JB", "new_table", "order_key", "state_of", "touch", "vertex_bits"]

#: Bits of an interval's rank within its vertex in an order key (at most 2^20 - 1 intervals).
JB = 20


@njit(cache=True)
def new_table(n, ta, tb):
    """An empty table for ``n`` vertices over ``[ta, tb]`` (time steps)."""
    return (
        ta, tb, np.full(n, -1, np.int64), np.zeros(n, np.int64), np.empty(16), np.empty(16),
        np.empty(16, np.int64), np.int64(0),
    )  # fmt: skip


@njit(cache=True)
def touch(table, v, nodes, mv):
    """The table with vertex ``v``'s safe intervals made (as it is if they were).

    Raises ``ValueError`` where a vertex would have more intervals than an order key holds.
    """
    ta, tb, first, count, lo, hi, owner, used = table
    if first[v] >= 0:
        return table
    lo, hi, k = vertex_intervals(nodes[v, 0], nodes[v, 1], ta, tb, mv, lo, hi, used)
    if k - used >= 1 << JB:
        raise ValueError("a vertex has more safe intervals than the search can order")
    # (loops, not slices: a slice assignment costs Numba about a second more to compile)
    if len(owner) < len(lo):
        grown = np.empty(len(lo), np.int64)
        for s in range(used):
            grown[s] = owner[s]
        owner = grown
    for s in range(used, k):
        owner[s] = v
    first[v], count[v] = used, k - used
    return ta, tb, first, count, lo, hi, owner, k


@njit(cache=True, inline="always")
def order_key(first, owner, s):
    """State ``s``'s place in the eager table's order: its vertex, then its rank there."""
    v = owner[s]
    return (v << JB) | (s - first[v])


@njit(cache=True, inline="always")
def state_of(first, key):
    """The state (row) of order key ``key``."""
    return first[key >> JB] + (key & ((1 << JB) - 1))


@njit(cache=True)
def vertex_bits(n):
    """Bits of a vertex number below ``n``."""
    b = 1
    while (1 << b) < n:
        b += 1
    return b
