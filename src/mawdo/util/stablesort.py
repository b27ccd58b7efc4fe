"""A stable argsort of float keys for the compiled kernels, cheap to compile.

Numba compiles its own ``np.argsort`` anew in every process that compiles a kernel calling it
(its generic sort machinery: about 2 s of CPU for the merge sort, 1.7 s for the quick sort), and
a cold ``mawdo plan`` compiles the kernels in two processes. This one compiles in about a tenth
of that.

Order: NumPy's for floats (ascending, NaN after every number), equal keys in index order. A
stable sort's permutation is unique, so it is ``np.argsort(keys, kind="stable")``'s (NumPy's
and Numba's) bit for bit; for ``len(keys) <= 15`` it is also Numba's default
``np.argsort(keys)`` (an insertion sort up to 15 keys, so stable).
"""

from __future__ import annotations

import numpy as np
from numba import njit

_RUN = 16  # keys per insertion-sorted run before the merges


@njit(cache=True, nogil=True)
def _before(a, b):  # pragma: no cover - compiled
    """Whether key ``a`` sorts strictly before ``b`` (NaN after every number)."""
    return a < b or (b != b and a == a)


@njit(cache=True, nogil=True)
def stable_argsort(keys):  # pragma: no cover - compiled
    """Indices that sort ``keys`` (float64[:], contiguous) ascending, NaN last, ties by index.

    Returns
    -------
    int64[:], shape (len(keys),)
        The permutation ``np.argsort(keys, kind="stable")`` returns.
    """
    n = keys.shape[0]
    order = np.empty(n, np.int64)
    for i in range(n):
        order[i] = i
    for lo in range(0, n, _RUN):  # insertion sort of each run
        for i in range(lo + 1, min(lo + _RUN, n)):
            k = order[i]
            j = i
            while j > lo and _before(keys[k], keys[order[j - 1]]):
                order[j] = order[j - 1]
                j -= 1
            order[j] = k
    if n <= _RUN:
        return order
    work = np.empty(n, np.int64)
    width = _RUN
    while width < n:  # bottom-up merges; the left run wins ties (stable)
        for lo in range(0, n, 2 * width):
            mid, hi = min(lo + width, n), min(lo + 2 * width, n)
            i, j = lo, mid
            for k in range(lo, hi):
                if j < hi and (i == mid or _before(keys[order[j]], keys[order[i]])):
                    work[k] = order[j]
                    j += 1
                else:
                    work[k] = order[i]
                    i += 1
        order, work = work, order
        width *= 2
    return order
