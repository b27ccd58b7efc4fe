"""The population loop: scratch layout and :func:`population_cost`, the kernel's entry point."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.refine.kernel.classify import prepare_obstacles
from mawdo.planning.refine.kernel.constants import (
    BLOCK,
    GRID_CELLS,
    INDEX_CELL,
    INDEX_CELLS,
    INDEX_MOVERS,
    INDEX_SLICES,
    INDEX_SPAN,
    MARGIN,
    WALK_KNOTS,
)
from mawdo.planning.refine.kernel.horizon import horizon_path
from mawdo.planning.refine.kernel.index import (
    block_index,
    indexed_moving_pass,
    mover_reach,
    window_misses,
)
from mawdo.planning.refine.kernel.moving import moving_pass
from mawdo.planning.refine.kernel.passes import block_paths, box_tables, static_pass, stride
from mawdo.planning.refine.kernel.static_index import (
    indexed_standing_pass,
    no_standing_table,
    standing_table,
)


@njit(cache=True, fastmath=False, error_model="numpy")
def _layout(n, npts, nk, spacetime, min_movers):
    """Scratch layout for a call: ``(nb, size, cap, fs, fc, gs, nmov, rows, total)`` (the
    index's work space counted where it is used: ``min_movers`` moving obstacles or more)."""
    nb = max(min(BLOCK, n), 1)  # candidates per block
    size = nb * npts  # points per block
    cap = size * 2  # relative segments on pieces, per batch
    nmov = 0
    rows = 0  # of the box tables
    if spacetime:
        for i in range(nk.shape[0]):
            if nk[i] > 1:
                nmov += 1
            q = 0  # floor(log2(nk[i]))
            while (2 << q) <= nk[i]:
                q += 1
            rows += nk[i] * (q + 1)
    fs = stride(size)
    fc = stride(cap)
    gs = stride(nmov * GRID_CELLS)
    total = 18 * fs + 20 * fc + 4 * gs + 4 * rows
    if nmov > 0 and nmov >= min_movers:  # the index of the moving pass
        total += _index_floats(size, INDEX_CELLS)
    return nb, size, cap, fs, fc, gs, nmov, rows, total


@njit(cache=True, fastmath=False, error_model="numpy")
def _index_floats(size, cells):
    """Floats of :func:`_index_scratch`'s work space."""
    return (
        12 * stride(2 * size) + stride(size) + stride(cells + 1) + 5 * stride(8 * size)
        + stride(12 * size) + stride(8 * size)
    )  # fmt: skip


@njit(cache=True, fastmath=False, error_model="numpy")
def scratch_size(n, npts, nk, spacetime):
    """Floats of scratch space :func:`population_cost` needs for ``n`` candidates of ``npts``
    path points (pass it a buffer at least this long to spare it allocating one;
    :func:`fused_population_cost` with ``min_movers`` below the number of moving obstacles and
    under ``INDEX_MOVERS`` needs more, and allocates it)."""
    return _layout(n, npts, nk, spacetime, INDEX_MOVERS)[8]


@njit(cache=True, fastmath=False, error_model="numpy", nogil=True)
def population_cost(
    X, start, goal, t0, speed, spacetime, obs, snap_off, motion, horizon, weights, box, out,
    scratch,
):  # fmt: skip
    """Cost of every candidate path; writes the arrays of ``out`` in place.

    Long by design: one fused Numba pass; splitting it adds calls and array round trips.
    Runs without the GIL: :class:`mawdo.planning.refine.kernel.threads.ThreadedKernel` calls it on
    chunks of rows at once.

    Long because it lays out one scratch buffer for every pass (a single allocation the caller
    keeps) and then runs the block loop over it; the passes themselves are separate functions.

    Parameters
    ----------
    X : float64[:, :], shape (n, 2 m)
        Candidates: ``m`` waypoints ``(x1, y1, ..., xm, ym)`` (pixels).
    start, goal : float64[:], shape (2,)
        Path ends (pixels); the path is ``start, w1..wm, goal``.
    t0 : float
        Planning time (time steps): obstacles frozen at ``t0`` (snapshot) or robot leaving
        ``start`` at ``t0`` (spacetime).
    speed : float
        Robot speed (pixels per time step), > 0.
    spacetime : bool
        Test each segment against the obstacles' motion while the robot traverses it.
    obs : tuple
        ``(is_circle, thresh, verts, nverts, bound, hull, nhull)``, see
        :class:`mawdo.planning.world.geometry.FlatObstacles`.
    snap_off : float64[:, :], shape (n_obs, 2)
        Obstacle offsets at ``t0`` (pixels), used in snapshot mode.
    motion : tuple
        ``(times, offsets, velocity, nknots, k_start)``: the knot table of
        :class:`mawdo.planning.world.geometry.MotionTable` (starting at or before ``t0``) and per
        obstacle the piece that contains ``t0``. Used in spacetime mode.
    horizon : float
        Lookahead (time steps, > 0; ``inf``: none): in spacetime mode, moving obstacles are
        tested only against the segments the robot begins before ``t0 + horizon``
        (:mod:`mawdo.planning.refine.kernel.horizon`); standing ones and the border against all.
    weights : tuple of float
        ``(alpha, beta, lam, k)`` of Eqs. 24 and 27.
    box : tuple of float
        ``(xlo, ylo, xhi, yhi)`` (pixels): where the robot's centre may go, the map shrunk by
        the hit distance. A segment with an end strictly outside it hits the map's border
        (a segment lies in a convex box iff both its ends do); that pair counts in ``n`` like a
        (segment, obstacle) pair.
    out : tuple of arrays, each shape (n,)
        ``(cost, length, n_collisions, turning)``: C (Eq. 24), C1 in pixels (Eq. 26), the
        number of hitting (segment, obstacle) pairs, the border included (int64, Eq. 27), C3
        in radians (Eq. 28).
    scratch : float64[:]
        Work space, kept by the caller from call to call: :func:`scratch_size` floats or more
        (a shorter one makes the kernel allocate its own).

    With :data:`~mawdo.planning.refine.kernel.constants.INDEX_MOVERS` moving obstacles or more,
    each is tested only against the segments of a block that come near it in space and time
    (:mod:`mawdo.planning.refine.kernel.index`; with fewer, building the index costs more than
    it saves); the counts are those of testing all of them (:func:`fused_population_cost` with
    neither index), bit for bit.
    """
    fused_population_cost(
        X, start, goal, t0, speed, spacetime, obs, snap_off, motion, horizon, weights, box, out,
        scratch,
        INDEX_MOVERS,
        None,
    )  # fmt: skip


@njit(cache=True, fastmath=False, error_model="numpy")
def _index_scratch(buf, o, size, cells):
    """The index's work space from ``buf[o:]`` (:func:`_index_floats` floats): the pairs' path
    and work arrays, the list of kept segments, bucket heads and entries."""
    cs = stride(2 * size)
    cf = buf[o : o + 8 * cs]
    ci = buf[o + 8 * cs : o + 12 * cs].view(np.int64)
    o += 12 * cs
    kept = buf[o : o + size].view(np.int64)
    o += stride(size)
    head = buf[o : o + cells + 1].view(np.int64)
    o += stride(cells + 1)
    ents = buf[o : o + 8 * size].view(np.int64)
    o += stride(8 * size)
    ebox = buf[o : o + 32 * size].reshape((8 * size, 4))
    o += 4 * stride(8 * size)
    items = buf[o : o + 12 * size].view(np.int64).reshape((2 * size, 6))
    o += stride(12 * size)
    ibox = buf[o : o + 8 * size].reshape((2 * size, 4))
    n2 = 2 * size
    pairs = (cf[0:n2], cf[cs : cs + n2], cf[2 * cs : 2 * cs + n2], cf[3 * cs : 3 * cs + n2],
             cf[4 * cs : 4 * cs + n2], cf[5 * cs : 5 * cs + n2], cf[6 * cs : 6 * cs + n2],
             cf[7 * cs : 7 * cs + n2], ci[0:n2], ci[cs : cs + n2], ci[2 * cs : 2 * cs + n2],
             ci[3 * cs : 3 * cs + n2])  # fmt: skip
    return pairs, kept, head, ents, ebox, items, ibox


@njit(cache=True, fastmath=False, error_model="numpy", nogil=True)
def fused_population_cost(
    X, start, goal, t0, speed, spacetime, obs, snap_off, motion, horizon, weights, box, out,
    scratch, min_movers, by_cells,
):  # fmt: skip
    """:func:`population_cost` with its indexes chosen by the caller: the space-time index
    where there are ``min_movers`` moving obstacles or more (else, or where ``min_movers`` is
    None, the moving pass runs on all of a block's segments), and the standing obstacles
    measured through the grid of a block's segments unless ``by_cells`` is None
    (:mod:`~mawdo.planning.refine.kernel.static_index`). The numbers are the same, bit for bit,
    whatever the choice.

    None is a compile-time choice: Numba prunes the branches an argument tested against None
    guards before typing (the argument never assigned), so a call with None never compiles
    that index. :class:`~mawdo.planning.refine.kernel.threads.ThreadedKernel` calls this
    function itself, not one of the thin entry points around it: each call level costs the
    compile another pass of LLVM over everything below it (about 2 s).

    Long by design: one fused Numba pass; splitting it adds calls and array round trips.
    """
    is_circle, thresh, verts, nverts, bound, hull, nhull = obs
    kt, ko, kv, nk, k_start = motion
    alpha, beta, lam, k_coll = weights
    xlo, ylo, xhi, yhi = box
    out_cost, out_len, out_ncol, out_turn = out
    n = X.shape[0]
    npts = X.shape[1] // 2 + 2
    nseg = npts - 1
    n_obs = nk.shape[0]
    extra = prepare_obstacles(is_circle, thresh, verts, nverts, bound, hull, nhull)
    acc2 = extra[0]
    moving = np.zeros(n_obs, dtype=np.bool_)
    for i in range(n_obs):
        moving[i] = spacetime and nk[i] > 1
    # per obstacle a bound of its speed (pixels per time step) and of its centre's coordinates
    # (pixels, for rounding room)
    vmax = np.zeros(n_obs)
    omax = np.zeros(n_obs)
    for i in range(n_obs):
        omax[i] = max(abs(bound[i, 4]), abs(bound[i, 5]))
        if moving[i]:
            # the largest square first, one root after (the root is correctly rounded and
            # monotone: the root of the largest square is the largest root, bit for bit)
            v2 = 0.0
            for k in range(nk[i] - 1):
                v2 = max(v2, kv[i, k, 0] ** 2 + kv[i, k, 1] ** 2)
            vmax[i] = math.sqrt(v2) * (1.0 + MARGIN) + MARGIN
            extent = 0.0
            for k in range(nk[i]):
                extent = max(extent, max(abs(ko[i, k, 0]), abs(ko[i, k, 1])))
            omax[i] += extent
    bbase, lg, boxed = box_tables(nk if spacetime else nk[:0])
    # Per moving obstacle a grid of its centre's positions over time, filled as far as the
    # blocks need: cells of gdt time steps from t0, the piece at each cell's start, and per cell
    # how far the centre can stray from the chord between its ends (0 without a knot inside,
    # else vmax gdt / 2: 1 px, more where the table is too long for 1 px cells).
    gdt = np.ones(n_obs)
    ggap = np.zeros(n_obs)
    grow = np.zeros(n_obs, dtype=np.int64)  # row of each moving obstacle's grid
    nmov = 0
    for i in range(n_obs):
        if moving[i]:
            span = max(kt[i, nk[i] - 1] - t0, 0.0) + 1.0
            gdt[i] = max(2.0 / vmax[i], span / (GRID_CELLS - 2))
            ggap[i] = 0.5 * vmax[i] * gdt[i]
            grow[i] = nmov
            nmov += 1
    # Candidates are processed in blocks of BLOCK, their paths laid end to end (point p of the
    # block is point p % npts of candidate p // npts; "segment" p joins points p and p + 1 and
    # is a real segment unless p % npts == nseg), so that the loops over segments are long
    # enough to vectorise.
    fewest = 1 << 62  # (no index: the entry point passed None)
    if min_movers is not None:
        fewest = min_movers
    nb, size, cap, fs, fc, gs, nmov, nrow, total = _layout(n, npts, nk, spacetime, fewest)
    # All scratch space is one buffer the caller keeps (allocating it on every call would cost
    # page faults). The arrays of the loops start at different multiples of 64 bytes into a
    # 4 KiB page, so that their streams never share cache sets (nor trip the store-to-load
    # checks that compare addresses modulo 4 KiB).
    buf = scratch if scratch.shape[0] >= total else np.empty(total)
    fbuf = buf[0 : 14 * fs]  # floats of the block's points
    ibuf = buf[14 * fs : 18 * fs].view(np.int64)
    o = 18 * fs
    cbuf = buf[o : o + 16 * fc]  # floats of the relative segments on pieces
    jbuf = buf[o + 16 * fc : o + 20 * fc].view(np.int64)
    o += 20 * fc
    ng = nmov * GRID_CELLS
    grid = (
        gdt,
        ggap,
        grow,
        np.zeros(n_obs, dtype=np.int64),  # cells filled
        k_start.copy(),  # piece at the last filled cell
        buf[o : o + ng].reshape((nmov, GRID_CELLS)),
        buf[o + gs : o + gs + ng].reshape((nmov, GRID_CELLS)),
        buf[o + 2 * gs : o + 2 * gs + ng].reshape((nmov, GRID_CELLS)),
        buf[o + 3 * gs : o + 3 * gs + ng].view(np.int64).reshape((nmov, GRID_CELLS)),
    )
    o += 4 * gs
    # The indexed pass places the centres of the few segments near an obstacle by the walk
    # (exact) where its table is short, sparing the grid's filling (cell size 0: no grid)
    cgdt = np.zeros(n_obs)
    for i in range(n_obs):
        cgdt[i] = gdt[i] if nk[i] > WALK_KNOTS else 0.0
    cgrid = (cgdt, ggap, grow, grid[3], grid[4], grid[5], grid[6], grid[7], grid[8])
    nbox = 4 * nrow
    pre = (vmax, omax, buf[o : o + nbox].reshape((nrow, 4)), bbase, lg, boxed)
    o += nbox
    path = (
        fbuf[0:size],  # px
        fbuf[fs : fs + size],  # py
        fbuf[2 * fs : 2 * fs + size],  # tt: time the robot reaches each path point (time steps)
        fbuf[3 * fs : 3 * fs + size],  # segment lengths
        fbuf[4 * fs : 4 * fs + size],  # dx
        fbuf[5 * fs : 5 * fs + size],  # dy
        fbuf[6 * fs : 6 * fs + size],  # rvx: robot velocity on each segment (px per time step)
        fbuf[7 * fs : 7 * fs + size],  # rvy
        fbuf[8 * fs : 8 * fs + size],  # ux, uy: directions of the non-zero segments
        fbuf[9 * fs : 9 * fs + size],
        fbuf[10 * fs : 10 * fs + size],  # angles between them
        np.empty(nb + 1, dtype=np.int64),  # first direction of each candidate
    )
    real = np.empty(size, dtype=np.bool_)  # "segment" p is a real segment of its candidate
    cand = ibuf[0:size]  # candidate (in the block) of point p
    for p in range(size):
        real[p] = p % npts != nseg
        cand[p] = p // npts
    work = (
        np.empty(size, dtype=np.bool_),  # near: comes within reach
        ibuf[fs : fs + size],  # flagged: those, listed
        real,
        cand,
        ibuf[2 * fs : 2 * fs + size],  # kpt: piece of each path time (a hint)
        fbuf[11 * fs : 11 * fs + size],  # cxp, cyp: obstacle centre at each path time
        fbuf[12 * fs : 12 * fs + size],
        fbuf[13 * fs : 13 * fs + size],  # cep: how far the true centre may be from it
        cbuf[0:cap],  # qax, qay, qbx, qby: relative segments on pieces
        cbuf[fc : fc + cap],
        cbuf[2 * fc : 2 * fc + cap],
        cbuf[3 * fc : 3 * fc + cap],
        cbuf[4 * fc : 4 * fc + cap],  # qd2: their squared distances to the bounding-circle centre
        jbuf[0:cap],  # qseg: their segments
        np.zeros(size, dtype=np.bool_),  # done: segment already counted
    )
    cls = (  # for classify_segments: segments, verdicts, scratch; entries and their verdicts
        (
            cbuf[5 * fc : 5 * fc + cap],
            cbuf[6 * fc : 6 * fc + cap],
            cbuf[7 * fc : 7 * fc + cap],
            cbuf[8 * fc : 8 * fc + cap],
        ),
        jbuf[fc : fc + cap],
        (
            cbuf[9 * fc : 9 * fc + cap],
            cbuf[10 * fc : 10 * fc + cap],
            cbuf[11 * fc : 11 * fc + cap],
            cbuf[12 * fc : 12 * fc + cap],
            cbuf[13 * fc : 13 * fc + cap],
            cbuf[14 * fc : 14 * fc + cap],
            cbuf[15 * fc : 15 * fc + cap],
            np.empty(cap, dtype=np.bool_),
        ),
        jbuf[2 * fc : 2 * fc + cap],
        jbuf[3 * fc : 3 * fc + cap],
    )
    hits = ibuf[3 * fs : 3 * fs + size]  # hits found by the branch-free passes, per segment
    # the index of the moving pass: kept segments as pairs of points (path and work arrays
    # of their own; the rest shared), bucket heads and entries, per-slice boxes
    # (without the index, a few pages of their own: one set of types either way)
    indexed = nmov > 0 and nmov >= fewest
    if min_movers is not None:  # (pruned before typing where None)
        isize = size if indexed else 0
        icells = INDEX_CELLS if indexed else 0
        ibase = buf if indexed else np.empty(_index_floats(0, 0))
        pairs, kept, head, ents, ebox, items, ibox = _index_scratch(
            ibase, o if indexed else 0, isize, icells
        )
        cpx, cpy, ctt, crvx, crvy, ccxp, ccyp, ccep, cflag, ccand, ckpt, chits = pairs
        cpath = (cpx, cpy, ctt, path[3], path[4], path[5], crvx, crvy, path[8], path[9],
                 path[10], path[11])  # fmt: skip
        cwork = (np.empty(2 * isize, dtype=np.bool_), cflag, np.empty(2 * isize, dtype=np.bool_),
                 ccand, ckpt, ccxp, ccyp, ccep, work[8], work[9], work[10], work[11], work[12],
                 work[13], np.zeros(2 * isize, dtype=np.bool_))  # fmt: skip
        compact = (cpath, cwork, chits)
        sbox = np.empty((INDEX_SLICES, 4))
        mark = np.zeros(isize, dtype=np.bool_)
        one = np.int64(1)
        geo = (0.0, 0.0, 1.0, one, one, 1.0, one)
        index = (geo, head, ents, ebox, sbox, mark, kept)
    # the horizon's layout (kernel.horizon): its own points, flags and hits, the rest shared
    t_cut = t0 + horizon
    hsize = size if spacetime and nmov > 0 and t_cut < np.inf else 0
    hpath = (np.empty(hsize), np.empty(hsize), np.empty(hsize), path[3], path[4], path[5],
             np.empty(hsize), np.empty(hsize), path[8], path[9], path[10], path[11])  # fmt: skip
    hreal = np.empty(hsize, dtype=np.bool_)
    hcand = np.empty(hsize, dtype=np.int64)
    hhits = np.zeros(hsize, dtype=np.int64)
    hwork = (work[0], work[1], hreal, hcand, work[4], work[5], work[6], work[7], work[8],
             work[9], work[10], work[11], work[12], work[13], work[14])  # fmt: skip
    hnpt = np.int64(0)
    ncol = np.empty(nb, dtype=np.int64)  # and by the exact tests, per candidate
    # the standing obstacles' table, for the entry points with their grid (else empty)
    ox = np.empty(n_obs)
    oy = np.empty(n_obs)
    for i in range(n_obs):
        ox[i] = ko[i, 0, 0] if spacetime else snap_off[i, 0]
        oy[i] = ko[i, 0, 1] if spacetime else snap_off[i, 1]
    if by_cells is None:
        table = no_standing_table(moving, ox, oy, obs, acc2, MARGIN)
    else:
        table = standing_table(moving, ox, oy, obs, acc2, MARGIN)
    sgrid = (np.zeros(1, np.int64), np.empty(0, np.int64), np.empty((0, 4)), np.empty(0, np.int64))
    for c0 in range(0, n, nb):
        bn = min(nb, n - c0)
        sane, cmax, tmax = block_paths(X, c0, bn, start, goal, t0, speed, path, out_len, out_turn)
        margin = MARGIN if sane else np.inf
        for p in range(size):  # (loops: a slice assignment costs Numba a compile)
            hits[p] = 0
        for b in range(nb):
            ncol[b] = 0
        # what the moving pass sees: the whole block, or its part before the horizon
        cut = hsize > 0 and t_cut < tmax
        if cut:
            hnpt, htmax = horizon_path(bn, npts, t_cut, path, hpath, hreal, hcand, hhits)
            blk = (t0, speed, np.int64(1), hnpt, sane, cmax, htmax)
            mpath, mwork, mhits = hpath, hwork, hhits
        else:
            blk = (t0, speed, bn, npts, sane, cmax, tmax)
            mpath, mwork, mhits = path, work, hits
        use_index = indexed and sane
        if min_movers is not None:  # (pruned before typing where None)
            if use_index:
                geo, ents, ebox, items, ibox = block_index(
                    blk[2], blk[3], t0, speed, blk[6], INDEX_CELL, INDEX_SPAN, mpath, mwork[2],
                    head, ents, ebox, items, ibox,
                )  # fmt: skip
                index = (geo, head, ents, ebox, sbox, mark, kept)
        by_grid = False
        if by_cells is not None:  # (pruned before typing where None)
            by_grid = sane and len(table[0]) > 0
            if by_grid:
                sgrid = indexed_standing_pass(
                    bn * npts, path, work, cls, obs, extra, margin, hits, ncol, table, sgrid
                )
        # n_collision (Eq. 27): (segment, obstacle) pairs that hit
        for i in range(n_obs):
            a2 = acc2[i] if sane or is_circle[i] else -1.0
            if moving[i]:
                if min_movers is not None:  # (pruned before typing where None)
                    if use_index:
                        reach = mover_reach(i, blk, a2, obs, pre)
                        if not window_misses(i, t0, blk[6], reach, index[0], obs, motion, sbox):
                            indexed_moving_pass(
                                i, blk, a2, margin, mpath, mwork, cls, obs, extra, motion, pre,
                                cgrid, ncol, index, compact,
                            )  # fmt: skip
                if not use_index:
                    moving_pass(
                        i, blk, a2, margin, mpath, mwork, cls, obs, extra, motion, pre, grid,
                        mhits, ncol,
                    )  # fmt: skip
            elif not by_grid:
                static_pass(
                    i, ox[i], oy[i], bn, npts, path, work, cls, obs, extra, a2, margin, hits,
                    ncol,
                )  # fmt: skip
        if cut:  # (the horizon's sure hits, per candidate)
            for p in range(hnpt):
                ncol[hcand[p]] += hhits[p]
        px, py = path[0], path[1]
        for b in range(bn):
            nc = ncol[b]
            # the border: a NaN end is never outside (its cost is NaN through the length)
            q = b * npts
            out_prev = px[q] < xlo or px[q] > xhi or py[q] < ylo or py[q] > yhi
            for p in range(q, q + nseg):
                out_next = px[p + 1] < xlo or px[p + 1] > xhi or py[p + 1] < ylo or py[p + 1] > yhi
                nc += hits[p] + (1 if out_prev or out_next else 0)
                out_prev = out_next
            c = c0 + b
            out_ncol[c] = nc
            x = float(nc)
            out_cost[c] = alpha * out_len[c] + beta * k_coll * x * x * x * x + lam * out_turn[c]
