"""Which movers a timed move can meet: a grid over space, buckets over time.

Every exact test of a timed move (:func:`~mawdo.planning.guide.sipp.intervals.forbidden`,
:func:`~mawdo.planning.guide.sipp.intervals.segment_free`) looped over every moving obstacle; among
hundreds of movers on a large map almost all of them are far away. The index cuts time into
buckets of ``W`` steps and space into square cells of ``C`` px; a mover is listed in every
(bucket, cell) that the bounding box of its inflated shape, swept over the part of a piece
inside the bucket, touches (padded by :data:`PAD` px and steps, so that rounding never drops a
touching contact). A query, the robot's move ``u + s e`` (``0 <= s <= T``) leaving at a time in
``[lo, hi]``, visits per bucket only the cells of the part of the move the robot can drive
within that bucket, and returns the movers listed there, ascending. Every mover a move can touch
is among them (reachable sets, which grow without bound, always are), and every test still runs
on all of a candidate's pieces: the answers equal those over all movers, bit for bit.

Out-of-range cells and buckets are clamped to the border ones on insertion and query alike (a
monotone map keeps overlapping ranges overlapping), and the first and last buckets reach to
minus and plus infinity in time, so no query falls outside the index.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.util.stablesort import stable_argsort

__all__ = ["PAD", "build", "candidates", "everything"]

#: Padding of every box (px) and time window (time steps): rounding never drops a contact.
PAD = 1.0
#: Most (bucket, cell) slots of one index; cells grow beyond this.
MAX_SLOTS = 1 << 21


def _layout(kind, box, pptr, pt0, pt1, po, pv, cell: float, bucket: float):
    """Time origin, bucket width, grid origin, cell size and ``(nb, nx, ny)`` of the pieces."""
    rows = np.repeat(np.arange(len(kind)), np.diff(pptr))
    if len(rows) == 0:
        return np.array([0.0, 1.0, 0.0, 0.0, 1.0]), np.array([1, 1, 1], np.int64)
    end = po + pv * (pt1 - pt0)[:, None]
    lo = np.minimum(po, end) + box[rows, :2]
    hi = np.maximum(po, end) + box[rows, 2:]
    gx0, gy0 = lo.min(axis=0) - PAD
    gx1, gy1 = hi.max(axis=0) + PAD
    t_base, t_top = float(pt0.min()), float(pt1.max())
    nb = max(1, math.ceil((t_top - t_base) / bucket))
    while True:
        nx = max(1, math.ceil((gx1 - gx0) / cell))
        ny = max(1, math.ceil((gy1 - gy0) / cell))
        if nb * nx * ny <= MAX_SLOTS:
            break
        cell *= 1.5
    par = np.array([t_base, float(bucket), float(gx0), float(gy0), float(cell)])
    return par, np.array([nb, nx, ny], np.int64)


@njit(cache=True)
def _slot(x, n):
    """``floor(x)`` clamped to ``0 .. n - 1``; -1 for NaN (a lower end then takes 0, an upper
    one ``n - 1``: the whole range, never too few)."""
    if x != x:
        return -1
    if x <= 0.0:
        return 0
    if x >= n - 1:
        return n - 1
    return int(x)


@njit(cache=True)
def _cells(x0, y0, x1, y1, par, dim):
    """Clamped cell ranges ``cx0, cx1, cy0, cy1`` (inclusive) of a box (pixels)."""
    c, nx, ny = par[4], dim[1], dim[2]
    cx0, cx1 = _slot((x0 - par[2]) / c, nx), _slot((x1 - par[2]) / c, nx)
    cy0, cy1 = _slot((y0 - par[3]) / c, ny), _slot((y1 - par[3]) / c, ny)
    return max(cx0, 0), cx1 if cx1 >= 0 else nx - 1, max(cy0, 0), cy1 if cy1 >= 0 else ny - 1


@njit(cache=True)
def _buckets(t0, t1, par, dim):
    """The buckets ``b0, b1`` (inclusive, clamped; see :func:`_slot`) of times ``t0 .. t1``."""
    b0, b1 = _slot((t0 - par[0]) / par[1], dim[0]), _slot((t1 - par[0]) / par[1], dim[0])
    return max(b0, 0), b1 if b1 >= 0 else dim[0] - 1


@njit(cache=True)
def _fill(kind, box, pptr, pt0, pt1, po, pv, par, dim, counts, cidx, pad):
    """Count (``cidx`` empty) or place the entries of every piece in its (bucket, cell) slots."""
    nx, ny = dim[1], dim[2]
    for m in range(len(kind)):
        if kind[m] != 0:
            continue
        for k in range(pptr[m], pptr[m + 1]):
            ta, tb = pt0[k], pt1[k]
            b0, b1 = _buckets(ta, tb, par, dim)
            for b in range(b0, b1 + 1):
                s0 = max(ta, par[0] + b * par[1]) - ta
                s1 = min(tb, par[0] + (b + 1) * par[1]) - ta
                if s1 < s0:  # (the last bucket of a piece ending on its border)
                    s1 = s0
                xa, xb = po[k, 0] + pv[k, 0] * s0, po[k, 0] + pv[k, 0] * s1
                ya, yb = po[k, 1] + pv[k, 1] * s0, po[k, 1] + pv[k, 1] * s1
                cx0, cx1, cy0, cy1 = _cells(
                    box[m, 0] + min(xa, xb) - pad, box[m, 1] + min(ya, yb) - pad,
                    box[m, 2] + max(xa, xb) + pad, box[m, 3] + max(ya, yb) + pad, par, dim,
                )  # fmt: skip
                for cy in range(cy0, cy1 + 1):
                    for cx in range(cx0, cx1 + 1):
                        slot = (b * ny + cy) * nx + cx
                        if len(cidx):
                            cidx[counts[slot]] = m
                        counts[slot] += 1


def build(kind, box, pptr, pt0, pt1, po, pv, cell: float = 32.0, bucket: float = 16.0) -> tuple:
    """The index of a mover table (:class:`~mawdo.planning.guide.sipp.intervals.Movers`'
    fields): ``(cptr, cidx, always, par, dim)`` as :func:`candidates` takes it.

    ``cell`` (px, > 0) and ``bucket`` (time steps, > 0) set the grid; cells grow when the
    grid would exceed :data:`MAX_SLOTS` slots.
    """
    par, dim = _layout(kind, box, pptr, pt0, pt1, po, pv, float(cell), float(bucket))
    slots = int(np.prod(dim))
    counts = np.zeros(slots + 1, np.int64)
    empty = np.zeros(0, np.int64)
    _fill(kind, box, pptr, pt0, pt1, po, pv, par, dim, counts[1:], empty, PAD)
    cptr = np.cumsum(counts)
    cidx = np.empty(cptr[-1], np.int64)
    _fill(kind, box, pptr, pt0, pt1, po, pv, par, dim, cptr[:-1].copy(), cidx, PAD)
    always = np.flatnonzero(kind != 0).astype(np.int64)
    return cptr, cidx, always, par, np.append(dim, len(kind))


def everything(kind) -> tuple:
    """The index of one slot holding every mover: :func:`candidates` returns all of them
    (the test over all movers, as a reference)."""
    n = len(kind)
    cptr = np.array([0, n], np.int64)
    par = np.array([0.0, 1.0, 0.0, 0.0, 1.0])
    return cptr, np.arange(n, dtype=np.int64), np.zeros(0, np.int64), par, np.array([1, 1, 1, n])


@njit(cache=True)
def candidates(ux, uy, ex, ey, T, lo, hi, ix):
    """Movers (ascending indices) that the move ``u + s e``, ``0 <= s <= T`` (pixels, px per
    step, time steps), leaving at a time in ``[lo, hi]``, can meet: a superset of those it
    meets (see the module docstring)."""
    cptr, cidx, always, par, dim = ix
    nx, ny, n = dim[1], dim[2], dim[3]
    mark = np.zeros(n, np.bool_)
    out = np.empty(max(n, 1), np.int64)
    k = 0
    for m in always:
        mark[m] = True
        out[k] = m
        k += 1
    b0, b1 = _buckets(lo - PAD, hi + T + PAD, par, dim)
    for b in range(b0, b1 + 1):
        # the part of the move driven inside the bucket (the end buckets reach to infinity)
        s0, s1 = 0.0, T
        if b > 0:
            s0 = max(0.0, par[0] + b * par[1] - PAD - hi)
        if b < dim[0] - 1:
            s1 = min(T, par[0] + (b + 1) * par[1] + PAD - lo)
        if s1 < s0:
            continue
        xa, xb, ya, yb = ux + s0 * ex, ux + s1 * ex, uy + s0 * ey, uy + s1 * ey
        cx0, cx1, cy0, cy1 = _cells(
            min(xa, xb) - PAD, min(ya, yb) - PAD, max(xa, xb) + PAD, max(ya, yb) + PAD, par, dim
        )
        for cy in range(cy0, cy1 + 1):
            for cx in range(cx0, cx1 + 1):
                slot = (b * ny + cy) * nx + cx
                for j in range(cptr[slot], cptr[slot + 1]):
                    m = cidx[j]
                    if not mark[m]:
                        mark[m] = True
                        out[k] = m
                        k += 1
    if 8 * k >= n:  # many: read them off the marks, in order
        k = 0
        for m in range(n):
            if mark[m]:
                out[k] = m
                k += 1
        return out[:k]
    if k <= 32:  # few: insertion sort, no allocation
        for i in range(1, k):
            m, j = out[i], i
            while j > 0 and out[j - 1] > m:
                out[j] = out[j - 1]
                j -= 1
            out[j] = m
        return out[:k]
    keys = np.empty(k)
    for j in range(k):
        keys[j] = out[j]
    order = stable_argsort(keys)
    res = np.empty(k, np.int64)
    for j in range(k):
        res[j] = out[order[j]]
    return res
