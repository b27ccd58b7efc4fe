"""mawdo.planning.guide.heap pops what heapq pops, for any sequence of pushes and pops."""

from __future__ import annotations

import heapq

import numpy as np

from mawdo.planning.guide.heap import heap_new, heap_pop, heap_push


def test_pops_the_same_entries_in_the_same_order_as_heapq():
    rng = np.random.default_rng(1)
    for _ in range(200):
        keys, ids, n = heap_new()
        ref: list = []
        for _ in range(int(rng.integers(1, 300))):  # past the initial 16 entries: it grows
            if ref and rng.random() < 0.4:
                assert heap_pop(keys, ids, n)[:3] == heapq.heappop(ref)
                n -= 1
            else:  # few distinct values: many equal first and second keys
                e = (float(rng.integers(0, 5)), float(rng.integers(0, 3)), int(rng.integers(0, 50)))
                heapq.heappush(ref, e)
                keys, ids, n = heap_push(keys, ids, n, *e)
            assert n == len(ref)
        while ref:
            k0, k1, i, n = heap_pop(keys, ids, n)
            assert (k0, k1, i) == heapq.heappop(ref)
        assert n == 0


def test_infinite_keys_and_negative_ids_order_as_tuples_do():
    entries = [(np.inf, 0.0, 3), (1.0, np.inf, 2), (1.0, 0.5, -7), (-np.inf, 9.0, 0)]
    entries.append((1.0, 0.5, -8))
    keys, ids, n = heap_new()
    for e in entries:
        keys, ids, n = heap_push(keys, ids, n, *e)
    out = []
    while n:
        *e, n = heap_pop(keys, ids, n)
        out.append(tuple(e))
    assert out == sorted(entries)
