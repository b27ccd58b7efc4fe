"""A space-time index of a block's segments, so that the pass over a moving obstacle
(:func:`mawdo.planning.refine.kernel.moving.moving_pass`) runs on the segments that can come
near it, not on all of them.

Per block (:func:`block_index`): time in slices of ``w`` time steps from ``t0``, space in square
cells of ``G`` pixels over the box of the block's points; each real segment is listed in every
(slice, cell) that the box of the part of it travelled in the slice meets, with that box. Per
moving obstacle (:func:`obstacle_segments`): the box of its centre's positions over each slice
(its pieces clipped to the slice, the formula the exact tests use), grown by the bounding radius
and room for rounding; the segments listed in the cells that box meets, whose own box meets it,
are the ones kept. A segment left out is, at every moment it is travelled, farther than the
bounding radius (plus the room) from the obstacle's centre: the exact tests would count no hit
for it, and no filter of the pass would call it a sure hit (each sure hit is one the exact tests
find).

The kept segments are laid out as pairs of points (:func:`compact_pairs`: point ``2q`` and
``2q + 1`` are segment ``q``'s ends, the "segment" between pairs is not a real one) and the pass
runs on them with the block's own scalars (latest time, largest coordinate), so each kept
segment gets the very numbers it gets in the pass over the whole block: centres, filters and
exact tests are per segment (the centre walk per pair, from the obstacle's first piece). The one
departure: an obstacle with a short table (``constants.WALK_KNOTS`` knots at most) has its
centres placed by the walk (exact) where the whole-block pass would interpolate them in its
grid; only the filters see the difference (they keep room for the grid's error, none is needed
for the walk's), the exact tests decide the same.

Measured on the planner's calls (``benchmarks/log/scaling.md``): with 200 movers on 1000 x 1000
px the index costs about what it saves (the populations' blocks spread over the map, and the
brute-force pass is a vectorised 2 ns per path point and obstacle); with 1000 it saves 12 % of
the replayed calls' kernel CPU, 20 % in a planning run; with 20 (crowds) it costs 30 %. Hence
``constants.INDEX_MOVERS``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.refine.kernel.constants import INDEX_SLICES, MARGIN
from mawdo.planning.refine.kernel.moving import moving_pass
from mawdo.planning.refine.kernel.near import rounding_room
from mawdo.util.cells import cell_of as grid_cell


@njit(cache=True, fastmath=False, error_model="numpy")
def _slice_span(t0, w, s, ns):
    """Times (time steps) of slice s: the first and last reach out to every time in them."""
    ts = t0 + s * w if s > 0 else -np.inf
    te = t0 + (s + 1) * w if s + 1 < ns else np.inf
    return ts, te


@njit(cache=True, fastmath=False, error_model="numpy")
def _part_box(px, py, tt, p, t0, w, s, ns):
    """Box ``(x0, y0, x1, y1)`` (pixels) of the part of segment p travelled in slice s (the
    whole segment's if it takes no time)."""
    ax = px[p]
    ay = py[p]
    bx = px[p + 1]
    by = py[p + 1]
    ta = tt[p]
    tb = tt[p + 1]
    if tb > ta:
        ts, te = _slice_span(t0, w, s, ns)
        ua = min(max((max(ts, ta) - ta) / (tb - ta), 0.0), 1.0)
        ub = min(max((min(te, tb) - ta) / (tb - ta), 0.0), 1.0)
        xa = ax + (bx - ax) * ua
        ya = ay + (by - ay) * ua
        xb = ax + (bx - ax) * ub
        yb = ay + (by - ay) * ub
        return min(xa, xb), min(ya, yb), max(xa, xb), max(ya, yb)
    return min(ax, bx), min(ay, by), max(ax, bx), max(ay, by)


@njit(cache=True, fastmath=False, error_model="numpy")
def _doubled_rows(items, ibox, ni):
    """``items`` and ``ibox`` with room for twice their ``ni`` rows, those copied (loops: a
    slice assignment costs Numba about a second to compile)."""
    grown = np.empty((2 * ni, 6), dtype=np.int64)
    gbox = np.empty((2 * ni, 4))
    for r in range(ni):
        for c in range(6):
            grown[r, c] = items[r, c]
        for c in range(4):
            gbox[r, c] = ibox[r, c]
    return grown, gbox


@njit(cache=True, fastmath=False, error_model="numpy")
def block_index(bn, npts, t0, speed, tmax, cell, span, path, real, head, ents, ebox, items, ibox):
    """Space-time buckets of the block's real segments (the block must be sane).

    Cells of ``cell`` pixels (more where the buckets would not fit in ``head``), slices of the
    time the robot takes to cross ``span`` cells (longer where there would be more than
    :data:`INDEX_SLICES`). Returns ``(geo, ents, ebox)``: ``geo = (gx, gy, ginv, nx, ny, winv,
    ns)`` (grid origin in pixels, inverse cell size, cells per axis, inverse slice length in
    time steps, slices), each bucket's segments and the box of the part of the segment
    travelled in the bucket's slice (``ents``, ``ebox`` or larger ones when they are too
    short); ``head`` gets the start of each bucket's entries (bucket ``(s * ny + cy) * nx +
    cx``). ``items`` and ``ibox`` are work space (larger ones are returned where they were
    too short).
    """
    px, py, tt = path[0], path[1], path[2]
    npt = bn * npts
    xlo = np.inf
    ylo = np.inf
    xhi = -np.inf
    yhi = -np.inf
    for p in range(npt):
        xlo = min(xlo, px[p])
        ylo = min(ylo, py[p])
        xhi = max(xhi, px[p])
        yhi = max(yhi, py[p])
    ncap = head.shape[0] - 1
    g = cell
    w = span * cell / speed
    ext = max(xhi - xlo, yhi - ylo)
    while True:
        nx = int((xhi - xlo) / g) + 1
        ny = int((yhi - ylo) / g) + 1
        ns = int((tmax - t0) / w) + 1
        if ns > INDEX_SLICES:
            w = (tmax - t0) / (INDEX_SLICES - 2)
            continue
        if nx * ny * ns <= ncap:
            break
        g = max(2.0 * g, ext / 64.0)
    ginv = 1.0 / g
    winv = 1.0 / w
    nb = nx * ny * ns
    for c in range(nb + 1):
        head[c] = 0
    # a counting sort by bucket: the items (segment, slice) with the buckets and box of the
    # part of the segment travelled in the slice, counted per bucket, then placed
    ni = 0
    for p in range(npt - 1):
        if not real[p]:
            continue
        for s in range(grid_cell(tt[p], t0, winv, ns), grid_cell(tt[p + 1], t0, winv, ns) + 1):
            x0, y0, x1, y1 = _part_box(px, py, tt, p, t0, w, s, ns)
            cx0 = grid_cell(x0, xlo, ginv, nx)
            cx1 = grid_cell(x1, xlo, ginv, nx)
            cy0 = grid_cell(y0, ylo, ginv, ny)
            cy1 = grid_cell(y1, ylo, ginv, ny)
            if ni == items.shape[0]:  # (more than room for: a larger list)
                items, ibox = _doubled_rows(items, ibox, ni)
            items[ni, 0] = p
            items[ni, 1] = s
            items[ni, 2] = cx0
            items[ni, 3] = cx1
            items[ni, 4] = cy0
            items[ni, 5] = cy1
            ibox[ni, 0] = x0
            ibox[ni, 1] = y0
            ibox[ni, 2] = x1
            ibox[ni, 3] = y1
            ni += 1
            for cy in range(cy0, cy1 + 1):
                c = (s * ny + cy) * nx
                for cx in range(cx0, cx1 + 1):
                    head[c + cx + 1] += 1
    for c in range(1, nb + 1):
        head[c] += head[c - 1]  # (now the start of each bucket)
    if head[nb] > ents.shape[0]:
        ents = np.empty(head[nb] + head[nb] // 4, dtype=np.int64)
        ebox = np.empty((ents.shape[0], 4))
    for k in range(ni):
        p = items[k, 0]
        s = items[k, 1]
        for cy in range(items[k, 4], items[k, 5] + 1):
            c = (s * ny + cy) * nx
            for cx in range(items[k, 2], items[k, 3] + 1):
                e = head[c + cx]
                ents[e] = p
                ebox[e, 0] = ibox[k, 0]
                ebox[e, 1] = ibox[k, 1]
                ebox[e, 2] = ibox[k, 2]
                ebox[e, 3] = ibox[k, 3]
                head[c + cx] = e + 1
    # (placing moved each start to the next bucket's: shift back)
    for c in range(nb, 0, -1):
        head[c] = head[c - 1]
    head[0] = 0
    return (xlo, ylo, ginv, nx, ny, winv, ns), ents, ebox, items, ibox


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _slice_boxes(i, t0, tmax, winv, ns, obs, motion, sbox):
    """Box of obstacle i's centre over each time slice, into ``sbox[:ns]`` (pixels)."""
    bound = obs[4]
    kt, ko, kv, nk, k_start = motion
    last = nk[i] - 2
    bcx = bound[i, 4]
    bcy = bound[i, 5]
    w = 1.0 / winv
    for s in range(ns):
        sbox[s, 0] = np.inf
        sbox[s, 1] = np.inf
        sbox[s, 2] = -np.inf
        sbox[s, 3] = -np.inf
    for k in range(k_start[i], last + 1):
        a = max(kt[i, k], t0)
        b = min(kt[i, k + 1], tmax) if k < last else tmax
        if not a <= b:
            if kt[i, k] > tmax:
                break
            continue
        for s in range(grid_cell(a, t0, winv, ns), grid_cell(b, t0, winv, ns) + 1):
            ts, te = _slice_span(t0, w, s, ns)
            sa = min(max(a, ts), b)
            sb = max(min(b, te), sa)
            for t in (sa, sb):
                x = bcx + ko[i, k, 0] + kv[i, k, 0] * (t - kt[i, k])
                y = bcy + ko[i, k, 1] + kv[i, k, 1] * (t - kt[i, k])
                sbox[s, 0] = min(sbox[s, 0], x)
                sbox[s, 1] = min(sbox[s, 1], y)
                sbox[s, 2] = max(sbox[s, 2], x)
                sbox[s, 3] = max(sbox[s, 3], y)
    for s in range(ns):
        # a slice no piece covered (times out of order, NaN): anywhere
        if not (sbox[s, 0] <= sbox[s, 2] and sbox[s, 1] <= sbox[s, 3]):
            sbox[s, 0] = -np.inf
            sbox[s, 1] = -np.inf
            sbox[s, 2] = np.inf
            sbox[s, 3] = np.inf


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def mover_reach(i, blk, a2, obs, pre):
    """How near (pixels) a segment must come to obstacle i's centre to be kept."""
    rho = obs[4][i, 6]
    acc = math.sqrt(a2) if a2 > 0.0 else 0.0
    return max(rho, acc) * (1.0 + MARGIN) + 4.0 * rounding_room(i, blk, pre) + MARGIN


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def window_misses(i, t0, tmax, reach, geo, obs, motion, sbox):
    """Obstacle i's centre stays, from ``t0`` to ``tmax``, farther than ``reach`` (pixels,
    with room for rounding) from the block index's grid, which holds every entry's box: no
    segment can be kept (:func:`obstacle_segments` would keep none). The caller tests it
    before :func:`indexed_moving_pass`: among thousands of movers most are far from a block's
    segments, and the call with its many arrays costs more than this test of a few pieces.
    ``sbox`` is work space (its first row)."""
    gx, gy, ginv, nx, ny, _, _ = geo
    _slice_boxes(i, t0, tmax, 1.0, 1, obs, motion, sbox)  # one slice: the whole window
    xlo, ylo, xhi, yhi = sbox[0, 0], sbox[0, 1], sbox[0, 2], sbox[0, 3]
    # a piece's points in between lie on its chord, up to rounding: room of MARGIN, relative
    room = reach + MARGIN * (1.0 + max(abs(xlo), abs(xhi), abs(ylo), abs(yhi), reach))
    g = 1.0 / ginv
    return (  # (a window no piece covered is anywhere: inf room, never missed)
        xhi + room < gx or yhi + room < gy or xlo - room > gx + nx * g or ylo - room > gy + ny * g
    )


@njit(cache=True, fastmath=False, error_model="numpy")
def obstacle_segments(i, reach, blk, geo, head, ents, ebox, path, obs, motion, sbox, mark, kept):
    """Segments of the block that may come within ``reach`` (pixels) of obstacle i's centre:
    into ``kept``, each once; returns how many."""
    t0, _, _, _, _, _, tmax = blk
    gx, gy, ginv, nx, ny, winv, ns = geo
    _slice_boxes(i, t0, tmax, winv, ns, obs, motion, sbox)
    nk = 0
    for s in range(ns):
        xlo = sbox[s, 0] - reach
        ylo = sbox[s, 1] - reach
        xhi = sbox[s, 2] + reach
        yhi = sbox[s, 3] + reach
        if xhi < gx or yhi < gy:
            continue
        x0 = grid_cell(xlo, gx, ginv, nx)
        x1 = grid_cell(xhi, gx, ginv, nx)
        y0 = grid_cell(ylo, gy, ginv, ny)
        y1 = grid_cell(yhi, gy, ginv, ny)
        for cy in range(y0, y1 + 1):
            for cx in range(x0, x1 + 1):
                c = (s * ny + cy) * nx + cx
                for e in range(head[c], head[c + 1]):
                    p = ents[e]
                    if mark[p]:
                        continue
                    if ebox[e, 2] < xlo or ebox[e, 0] > xhi or ebox[e, 3] < ylo or ebox[e, 1] > yhi:
                        continue
                    mark[p] = True
                    kept[nk] = p
                    nk += 1
    for q in range(nk):
        mark[kept[q]] = False
    return nk


@njit(cache=True, fastmath=False, error_model="numpy")
def compact_pairs(nq, kept, path, cand, cpath, creal, ccand, chits):
    """Lay the kept segments out as pairs of points (see the module docstring)."""
    px, py, tt, rvx, rvy = path[0], path[1], path[2], path[6], path[7]
    cpx, cpy, ctt, crvx, crvy = cpath[0], cpath[1], cpath[2], cpath[6], cpath[7]
    for q in range(nq):
        p = kept[q]
        a = 2 * q
        cpx[a] = px[p]
        cpy[a] = py[p]
        ctt[a] = tt[p]
        crvx[a] = rvx[p]
        crvy[a] = rvy[p]
        cpx[a + 1] = px[p + 1]
        cpy[a + 1] = py[p + 1]
        ctt[a + 1] = tt[p + 1]
        crvx[a + 1] = 0.0
        crvy[a + 1] = 0.0
        creal[a] = True
        creal[a + 1] = False
        ccand[a] = cand[p]
        ccand[a + 1] = cand[p]
        chits[a] = 0
        chits[a + 1] = 0


@njit(cache=True, fastmath=False, error_model="numpy")
def indexed_moving_pass(
    i, blk, a2, margin, path, work, cls, obs, extra, motion, pre, grid, ncol, index, compact
):
    """:func:`moving_pass` of obstacle i on the block's segments that can come near it (a sane
    block): the same counts, added to ``ncol``."""
    geo, head, ents, ebox, sbox, mark, kept = index
    cpath, cwork, chits = compact
    reach = mover_reach(i, blk, a2, obs, pre)
    nq = obstacle_segments(
        i, reach, blk, geo, head, ents, ebox, path, obs, motion, sbox, mark, kept
    )
    if nq == 0:
        return
    ccand = cwork[3]
    compact_pairs(nq, kept, path, work[3], cpath, cwork[2], ccand, chits)
    t0, speed, _, _, sane, cmax, tmax = blk
    cblk = (t0, speed, nq, np.int64(2), sane, cmax, tmax)
    moving_pass(i, cblk, a2, margin, cpath, cwork, cls, obs, extra, motion, pre, grid, chits, ncol)
    for q in range(nq):
        ncol[ccand[2 * q]] += chits[2 * q]
