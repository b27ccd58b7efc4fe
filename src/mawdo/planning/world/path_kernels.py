"""Compiled polyline helpers: :func:`densify` for many short polylines at once.

:func:`densify_many` is :func:`mawdo.planning.world.path.densify` row by row, with the same
arithmetic in the same order (the lengths by ``hypot``, each split halving a piece, each cut point
``a + t (b - a)``), so its waypoints are bit for bit the same; it exists because the seeding of a
first plan densifies about a hundred random via paths, which cost a Python heap each.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["densify_many"]


@njit(cache=True)
def _pick(plen, pj, pa, pb, count):
    """Index of the piece a heap of ``(-length, segment, a, b)`` would pop first: the longest,
    then the earliest segment, then the smallest parameters."""
    best = 0
    for q in range(1, count):
        if plen[q] > plen[best]:
            best = q
        elif plen[q] == plen[best]:
            if pj[q] < pj[best] or (
                pj[q] == pj[best] and (pa[q] < pa[best] or (pa[q] == pa[best] and pb[q] < pb[best]))
            ):
                best = q
    return best


@njit(cache=True)
def _cuts(base, need):
    """The ``need`` cuts ``(segment, parameter)`` of :func:`densify`'s longest-piece halving,
    sorted by segment, then parameter."""
    nseg = base.shape[0] - 1
    cap = nseg + need
    plen = np.empty(cap)
    pj = np.empty(cap, np.int64)
    pa = np.empty(cap)
    pb = np.empty(cap)
    for j in range(nseg):
        plen[j] = np.hypot(base[j + 1, 0] - base[j, 0], base[j + 1, 1] - base[j, 1])
        pj[j], pa[j], pb[j] = j, 0.0, 1.0
    count = nseg
    cj = np.empty(need, np.int64)
    cc = np.empty(need)
    for c in range(need):
        q = _pick(plen, pj, pa, pb, count)
        j, a, b, half = pj[q], pa[q], pb[q], 0.5 * plen[q]
        mid = 0.5 * (a + b)
        cj[c], cc[c] = j, mid
        plen[q], pb[q] = half, mid  # the first half replaces the piece
        plen[count], pj[count], pa[count], pb[count] = half, j, mid, b
        count += 1
    for x in range(1, need):  # insertion sort by (segment, parameter): need is small
        y = x
        while y > 0 and (cj[y - 1] > cj[y] or (cj[y - 1] == cj[y] and cc[y - 1] > cc[y])):
            cj[y - 1], cj[y] = cj[y], cj[y - 1]
            cc[y - 1], cc[y] = cc[y], cc[y - 1]
            y -= 1
    return cj, cc


@njit(cache=True)
def densify_many(pts, counts, m):
    """``m`` interior waypoints for each of ``n`` polylines (:func:`densify`'s rule).

    Parameters
    ----------
    pts : numpy.ndarray, shape (n, k_max, 2)
        The polylines' points (pixels); row ``i`` uses its first ``counts[i]``.
    counts : numpy.ndarray of int64, shape (n,)
        Points per polyline, >= 2.
    m : int
        Waypoints per polyline, >= 1.

    Returns
    -------
    numpy.ndarray, shape (n, m, 2)
        Pixels.
    """
    # (rows copied coordinate by coordinate: each row or slice assignment costs Numba about
    # a second of compile, and this kernel is on a cold first plan's path)
    n = pts.shape[0]
    out = np.empty((n, m, 2))
    for i in range(n):
        k = counts[i]
        inner = min(k - 2, m)
        first = 1 + (k - 2 - inner)  # the last ``m`` interior points are kept
        base = np.empty((inner + 2, 2))
        for v in range(inner + 2):
            src = 0 if v == 0 else (k - 1 if v == inner + 1 else first + v - 1)
            base[v, 0] = pts[i, src, 0]
            base[v, 1] = pts[i, src, 1]
        need = m - inner
        if need <= 0:
            for v in range(inner):
                out[i, v, 0] = base[1 + v, 0]
                out[i, v, 1] = base[1 + v, 1]
            continue
        cj, cc = _cuts(base, need)
        w, c = 0, 0
        for seg in range(inner + 1):
            if seg:
                out[i, w, 0] = base[seg, 0]
                out[i, w, 1] = base[seg, 1]
                w += 1
            ax, ay = base[seg, 0], base[seg, 1]
            dx, dy = base[seg + 1, 0] - ax, base[seg + 1, 1] - ay
            while c < need and cj[c] == seg:
                t = cc[c]
                out[i, w, 0] = ax + t * dx
                out[i, w, 1] = ay + t * dy
                w += 1
                c += 1
    return out
