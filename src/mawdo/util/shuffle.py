"""Uniform permutations in O(d) from raw 64-bit words: Fisher-Yates with batched swaps.

A core module (no optimizer imports) so that :class:`mawdo.streams.RunStreams` can draw
permutations and the optimizers' kernels (:mod:`mawdo.optimizers.kernels`) can inline the same
shuffle (docs/deviations.md#d-kernel-draws).
"""

from __future__ import annotations

import numpy as np
from numba import njit

_LOW32 = np.uint64(0xFFFFFFFF)
_SHIFT32 = np.uint64(32)


SHUFFLE_BATCH = 1 << 32  # product of the ranges drawn from one 64-bit word: bias <= 2**-32


def words_per_permutation(d: int) -> int:
    """Raw 64-bit words one permutation of ``range(d)`` consumes in :func:`shuffle_from_words`."""
    words, prod = (1 if d > 1 else 0), 1
    for k in range(d - 1, 0, -1):
        if prod * (k + 1) > SHUFFLE_BATCH:
            words, prod = words + 1, 1
        prod *= k + 1
    return words


@njit(cache=True, nogil=True, inline="always")
def bounded_draw(x, n):  # pragma: no cover - compiled
    """``j`` uniform in ``[0, n)`` from the 64-bit word ``x``, and the rest of the word:
    ``j = floor(x n / 2**64)``, ``x <- x n mod 2**64`` (batched multiply-shift)."""
    un = np.uint64(n)
    hi = ((x >> _SHIFT32) * un + (((x & _LOW32) * un) >> _SHIFT32)) >> _SHIFT32
    return np.intp(hi), x * un


@njit(cache=True, nogil=True, inline="always")
def shuffle_values_from_words(words, base, vals):  # pragma: no cover - compiled
    """Permute ``vals`` ``(d,)`` in place with the swaps of :func:`shuffle_from_words`, so that
    entry ``k`` ends up holding ``vals[perm[k]]`` (the kernels shuffle values this way, with no
    permutation array)."""
    d = vals.shape[0]
    if d < 2:
        return
    w = base
    x = words[w]
    prod = 1
    for k in range(d - 1, 0, -1):
        n = k + 1
        if prod * n > SHUFFLE_BATCH:
            w += 1
            x = words[w]
            prod = 1
        prod *= n
        j, x = bounded_draw(x, n)
        tmp = vals[k]
        vals[k] = vals[j]
        vals[j] = tmp


@njit(cache=True, nogil=True, inline="always")
def shuffle_from_words(words, base, out):  # pragma: no cover - compiled
    """Fill ``out`` ``(d,)`` with a permutation of ``range(d)`` drawn from ``words[base:]``.

    Fisher-Yates: swap ``k = d-1 .. 1`` exchanges ``out[k]`` and ``out[j]``, ``j`` uniform in
    ``[0, k]``. Several ``j`` come from one 64-bit word ``x`` by batched multiply-shift
    (Brackett-Rozinsky & Lemire 2024, without the rejection step, :func:`bounded_draw`) while
    the product of the ranges stays <= 2**32; each permutation's probability is ``1/d!`` within
    a relative ``2**-32``.
    """
    for k in range(out.shape[0]):
        out[k] = k
    shuffle_values_from_words(words, base, out)


@njit(cache=True, nogil=True)
def fisher_yates_batch(words, out):  # pragma: no cover - compiled
    """Permutations of ``range(d)`` for ``out`` ``(R, n, d)`` from ``words (R, n * W)``,
    ``W = words_per_permutation(d)`` consecutive words per row."""
    R, n, d = out.shape
    W = words.shape[1] // n if n else 0
    row = np.empty(d, out.dtype)
    for r in range(R):
        for i in range(n):
            shuffle_from_words(words[r], i * W, row)
            out[r, i, :] = row
