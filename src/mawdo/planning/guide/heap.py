"""A binary min-heap of ``(key, tie, id)`` entries for the graph searches, in three arrays.

It replaces :mod:`heapq` on a list of tuples in the compiled searches: Numba compiles
``heapq``'s functions and the list's for every tuple type in every process (about 0.8 s of CPU
each for the oracle's Dijkstra and the safe-interval search). The searches pop the same
entries in the same order as with ``heapq``: no two entries they push compare equal (a node or
state is pushed again only with a strictly smaller key, and keys are never NaN), so the pop
order is the entries' sorted order, whichever heap holds them.

The heap is ``(keys, ids, n)``: ``keys`` float64 ``(cap, 2)``, ``ids`` int64 ``(cap,)``, ``n``
entries; :func:`heap_push` returns it, grown when full. A search that pushes many entries in a
loop makes room once (:func:`heap_room`) and adds them with :func:`heap_put`, which never
rebinds the arrays (Numba counts every binding of an array, an atomic operation each).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def heap_new():  # pragma: no cover - compiled
    """An empty heap ``(keys, ids, n)`` with room for 16 entries."""
    return np.empty((16, 2)), np.empty(16, np.int64), np.int64(0)


@njit(cache=True)
def _less(a0, a1, ai, b0, b1, bi):  # pragma: no cover - compiled
    """``(a0, a1, ai) < (b0, b1, bi)`` as Python compares tuples."""
    if a0 != b0:
        return a0 < b0
    if a1 != b1:
        return a1 < b1
    return ai < bi


@njit(cache=True)
def heap_room(keys, ids, n, extra):  # pragma: no cover - compiled
    """The heap's arrays with room for ``extra`` more entries: as they are, or grown (at
    least doubled) with the ``n`` entries copied."""
    if n + extra <= ids.shape[0]:
        return keys, ids
    cap = max(2 * ids.shape[0], n + extra)
    grown_k, grown_i = np.empty((cap, 2)), np.empty(cap, np.int64)
    for r in range(n):
        grown_k[r, 0], grown_k[r, 1], grown_i[r] = keys[r, 0], keys[r, 1], ids[r]
    return grown_k, grown_i


@njit(cache=True)
def heap_put(keys, ids, n, k0, k1, i):  # pragma: no cover - compiled
    """Add ``(k0, k1, i)`` to a heap with room for it (:func:`heap_room`); returns ``n + 1``."""
    j = n
    while j > 0:  # up from the new leaf while the parent is larger
        p = (j - 1) >> 1
        if not _less(k0, k1, i, keys[p, 0], keys[p, 1], ids[p]):
            break
        keys[j, 0], keys[j, 1], ids[j] = keys[p, 0], keys[p, 1], ids[p]
        j = p
    keys[j, 0], keys[j, 1], ids[j] = k0, k1, i
    return n + 1


@njit(cache=True)
def heap_push(keys, ids, n, k0, k1, i):  # pragma: no cover - compiled
    """Add ``(k0, k1, i)``; returns the heap ``(keys, ids, n + 1)``."""
    keys, ids = heap_room(keys, ids, n, 1)
    return keys, ids, heap_put(keys, ids, n, k0, k1, i)


@njit(cache=True)
def heap_pop(keys, ids, n):  # pragma: no cover - compiled
    """Remove the least entry (``n >= 1``); returns ``(k0, k1, i, n - 1)``."""
    top0, top1, top_i = keys[0, 0], keys[0, 1], ids[0]
    n -= 1
    k0, k1, i = keys[n, 0], keys[n, 1], ids[n]  # the last leaf, sifted down from the root
    j = 0
    while True:
        c = 2 * j + 1
        if c >= n:
            break
        if c + 1 < n and _less(
            keys[c + 1, 0], keys[c + 1, 1], ids[c + 1], keys[c, 0], keys[c, 1], ids[c]
        ):
            c += 1
        if not _less(keys[c, 0], keys[c, 1], ids[c], k0, k1, i):
            break
        keys[j, 0], keys[j, 1], ids[j] = keys[c, 0], keys[c, 1], ids[c]
        j = c
    if n > 0:
        keys[j, 0], keys[j, 1], ids[j] = k0, k1, i
    return top0, top1, top_i, n
