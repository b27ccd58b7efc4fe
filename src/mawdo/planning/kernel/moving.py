"""The pass over moving obstacles (spacetime mode) in three steps: where the obstacle's centre
is at each path time, which segments come within reach of it (a lens test), and the exact tests
of those, piece by piece of the obstacle's motion.

One compiled function per step; :func:`moving_pass` runs them for one obstacle and one block.
The steps are inlined into it (Numba IR inlining; compiled on their own, called with the pass's
long argument lists, crowd scenes' calls measured up to 20 % slower, for no shorter compile).
The pass itself is a row of :mod:`mawdo.jitwarm`'s table (its arguments are plain tuples), so
one process compiles it while another compiles the cost kernel's other parts. The lens test of
step 2 measures without a division (a filter with room to spare; see :func:`_near_segments`);
the centres and the exact tests are computed as they always were, so every count is the same.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.kernel.classify import classify_segments
from mawdo.planning.kernel.constants import COUNT, GRID_CELLS, MARGIN, PIECES
from mawdo.planning.kernel.passes import fill_boxes
from mawdo.planning.kernel.primitives import (
    point_segment_d2,
    polygon_hit,
    segment_hits_polygon,
    segment_reach_levels,
)


@njit(cache=True, fastmath=False, error_model="numpy")
def moving_pass(i, blk, a2, margin, path, work, cls, obs, extra, motion, pre, grid, hits, ncol):
    """Hits of the block's segments on moving obstacle i (spacetime); adds them to ``ncol``.

    ``blk`` is the block's scalars ``(t0, speed, bn, npts, sane, cmax, tmax)``: planning time
    and robot speed (time steps, px per step), candidates in the block and points per path,
    whether all coordinates are sane, the largest coordinate (px) and the latest path time
    (time steps), as :func:`mawdo.planning.kernel.passes.block_paths` finds them (a plain
    tuple: its type reads back from its ``repr``, so the steps are rows of the jit table).

    The exact test walks the robot's segments and the obstacle's constant-velocity pieces
    together (both are ordered in time): on each common piece the robot's position relative to
    the obstacle moves along a straight segment, tested against the shape at offset zero. Past
    the table's last knot the last piece is extrapolated (callers size tables so that this does
    not happen). Filters in front of it only skip pieces whose outcome is certain.
    """
    emax = _centres(i, blk, path, work, obs, motion, grid)
    room = _room(i, blk, pre)
    nf = _near_segments(i, blk, room, a2, emax, path, work, obs, pre, hits)
    if nf > 0:
        _exact_moving(i, nf, room, a2, margin, path, work, cls, obs, extra, motion, pre, ncol)


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _centres(i, blk, path, work, obs, motion, grid):
    """Step 1: obstacle i's centre at each path time into ``work`` (cxp, cyp, cep, kpt);
    returns the largest ``cep`` it can have written (pixels).

    Long by design: one fused Numba step; splitting it adds calls in the hot loop.

    Long because its three ways (count knots, interpolate in the grid, walk) share one set of
    outputs and are each a tight loop; splitting them would only pass the same arrays around.
    """
    t0, _, bn, npts, _, _, tmax = blk
    tt = path[2]
    kpt, cxp, cyp, cep = work[4], work[5], work[6], work[7]
    bound = obs[4]
    kt, ko, kv, nk, k_start = motion
    gdt, ggap, grow, gfill, gwalk, gx, gy, ge, gk = grid
    gr = grow[i]  # this obstacle's row in the grid
    last = nk[i] - 2  # index of the last piece
    ks = k_start[i]
    bcx = bound[i, 4]
    bcy = bound[i, 5]
    npt = bn * npts
    # the obstacle's centre at each path time: (cxp, cyp), within cep of the true one
    kw = ks  # the last knot at or before the block's latest time
    while kw < last and kt[i, kw + 1] <= tmax:
        kw += 1
    gi = 1.0 / gdt[i]
    gneed = int((tmax - t0) * gi) + 2 if tmax - t0 < (GRID_CELLS - 2) * gdt[i] else -1
    on_grid = gneed > 0 and kw - ks > COUNT
    if kw - ks <= COUNT:
        # few knots: each path time takes the last of pieces ks..kw that has begun by then (the
        # piece ks if none), as placing the centre on each piece in turn did; chosen among four
        # pieces at a time (branch-free), then placed once
        _few_knots(i, ks, kw, bcx, bcy, npt, tt, kt, ko, kv, kpt, cxp, cyp, cep)
    elif on_grid:
        # many knots: interpolate in the grid (extended as far as this block needs)
        g = gfill[i]
        k = gwalk[i]
        while g < gneed:
            t = t0 + g * gdt[i]
            while k < last and kt[i, k + 1] <= t:
                k += 1
            gk[gr, g] = k
            gx[gr, g] = bcx + ko[i, k, 0] + kv[i, k, 0] * (t - kt[i, k])
            gy[gr, g] = bcy + ko[i, k, 1] + kv[i, k, 1] * (t - kt[i, k])
            if g > 0:
                ge[gr, g - 1] = ggap[i] if k != gk[gr, g - 1] else 0.0
            g += 1
        gfill[i] = g
        gwalk[i] = k
        # (this obstacle's rows, indexed unsigned: no wraparound code in the loop)
        gxr, gyr, ger, gkr = gx[gr], gy[gr], ge[gr], gk[gr]
        for p in range(npt):
            u = (tt[p] - t0) * gi
            gf = math.floor(u) if u > 0.0 else 0.0
            g = np.uint32(gf)
            fr = u - gf
            x0 = gxr[g]
            y0 = gyr[g]
            cxp[p] = x0 + fr * (gxr[g + np.uint32(1)] - x0)
            cyp[p] = y0 + fr * (gyr[g + np.uint32(1)] - y0)
            cep[p] = ger[g]
            kpt[p] = gkr[g]  # the piece at the cell's start: at most one before (a hint)
        return ggap[i]  # (each cell's is ggap or 0)
    else:
        # (times beyond the grid) walk
        for b in range(bn):
            k = ks
            for p in range(b * npts, b * npts + npts):
                t = tt[p]
                while k < last and kt[i, k + 1] <= t:
                    k += 1
                kpt[p] = k
                cxp[p] = bcx + ko[i, k, 0] + kv[i, k, 0] * (t - kt[i, k])
                cyp[p] = bcy + ko[i, k, 1] + kv[i, k, 1] * (t - kt[i, k])
                cep[p] = 0.0
    return 0.0


@njit(cache=True, fastmath=False, error_model="numpy")
def _few_knots(i, ks, kw, bcx, bcy, npt, tt, kt, ko, kv, kpt, cxp, cyp, cep):
    """Step 1 for pieces ks..kw: four at a time, the first four placing every point.

    Compiled on its own (not inlined): called once per obstacle and block, it spares the
    pass's compile the inlining of its loops.
    """
    for w in range(ks, kw + 1, 4):
        # pieces w..w + 3 (past kw: a start time NaN, never begun, and piece kw's motion)
        wb, wc, wd = min(w + 1, kw), min(w + 2, kw), min(w + 3, kw)
        ta, tb, tc, td = kt[i, w], kt[i, wb], kt[i, wc], kt[i, wd]
        tb = tb if w + 1 <= kw else np.nan
        tc = tc if w + 2 <= kw else np.nan
        td = td if w + 3 <= kw else np.nan
        oxa, oxb, oxc, oxd = (
            bcx + ko[i, w, 0],
            bcx + ko[i, wb, 0],
            bcx + ko[i, wc, 0],
            bcx + ko[i, wd, 0],
        )
        oya, oyb, oyc, oyd = (
            bcy + ko[i, w, 1],
            bcy + ko[i, wb, 1],
            bcy + ko[i, wc, 1],
            bcy + ko[i, wd, 1],
        )
        vxa, vxb, vxc, vxd = kv[i, w, 0], kv[i, wb, 0], kv[i, wc, 0], kv[i, wd, 0]
        vya, vyb, vyc, vyd = kv[i, w, 1], kv[i, wb, 1], kv[i, wc, 1], kv[i, wd, 1]
        later = ((tb, oxb, oyb, vxb, vyb), (tc, oxc, oyc, vxc, vyc), (td, oxd, oyd, vxd, vyd))
        for p in range(npt):
            t = tt[p]
            tw, ox, oy, vx, vy = ta, oxa, oya, vxa, vya
            for tn, oxn, oyn, vxn, vyn in later:
                on = tn <= t
                tw = tn if on else tw
                ox = oxn if on else ox
                oy = oyn if on else oy
                vx = vxn if on else vx
                vy = vyn if on else vy
            x = ox + vx * (t - tw)
            y = oy + vy * (t - tw)
            if w == ks:
                cxp[p] = x
                cyp[p] = y
                cep[p] = 0.0
                kpt[p] = ks  # (a hint; the exact tests walk on from it)
            else:
                on = (ta <= t) | (tb <= t) | (tc <= t) | (td <= t)
                cxp[p] = x if on else cxp[p]
                cyp[p] = y if on else cyp[p]


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _room(i, blk, pre):
    """Room for rounding (pixels) of obstacle i's tests in this block."""
    vmax, omax = pre[0], pre[1]
    _, speed, _, _, sane, cmax, tmax = blk
    vm = vmax[i]
    # relative to the coordinates and times involved
    room = (
        MARGIN * (1.0 + 4.0 * cmax + 4.0 * omax[i]) + 1e-9 * tmax * (2.0 * speed + vm)
        if sane
        else np.inf
    )
    return room


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _lens_dev(p, vm, tt, cxp, cyp, cep):
    """How far (pixels) obstacle i's true centre may be from the moving point of the lens test
    while the robot is on segment p (see :func:`_near_segments`)."""
    dcx = cxp[p + 1] - cxp[p]
    dcy = cyp[p + 1] - cyp[p]
    ha = 0.5 * vm * (tt[p + 1] - tt[p])
    ea = cep[p]
    eb = cep[p + 1]
    e = 0.5 * (ea + eb)  # the true half distance is at least d - e
    dev = math.sqrt(max(ha * ha - 0.25 * (dcx * dcx + dcy * dcy) + 2.0 * e * (ha + e), 0.0))
    return dev + max(ea, eb)


@njit(cache=True, fastmath=False, error_model="numpy")
def _box_kept(npt, k0, k1, px, py, tt, cxp, cyp, real, near, flagged):
    """The box test of :func:`_near_segments` (radius ``(k0 + k1 |tb - ta|) / 2``) on every
    segment; lists those it keeps in ``flagged`` and returns how many (compiled on its own,
    as :func:`_few_knots`)."""
    for p in range(npt - 1):
        ax = px[p] - cxp[p]
        ay = py[p] - cyp[p]
        bx = px[p + 1] - cxp[p + 1]
        by = py[p + 1] - cyp[p + 1]
        r = k0 + k1 * abs(tt[p + 1] - tt[p])
        # (kept unless shown far: NaN keeps it)
        far = (abs(ax + bx) - abs(bx - ax) > r) | (abs(ay + by) - abs(by - ay) > r)
        near[p] = real[p] & ~far
    # the kept segments listed (branch-free within each word of eight flags that has one),
    # then tested in order; the list is compacted in place into the flagged ones
    nk = 0
    nw = (npt - 1) >> 3
    words = near[: nw * 8].view(np.uint64)
    for w in range(nw):
        if words[w] != 0:
            for p in range(8 * w, 8 * w + 8):
                flagged[nk] = p
                nk += near[p]
    for p in range(8 * nw, npt - 1):
        flagged[nk] = p
        nk += near[p]
    return nk


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _near_segments(i, blk, room, a2, emax, path, work, obs, pre, hits):
    """Step 2: flag the segments that come within reach of obstacle i; returns how many.

    While the robot is on a segment, the centre moves at most vmax from where it was at
    ta and where it will be at tb, so it stays within sqrt(a^2 - d^2) (a = vmax (tb - ta) / 2,
    d half the distance between the two) of the point that moves uniformly between them; the
    robot, relative to that point, moves along a segment (the lens test). Sane blocks measure
    the distance without a division (:func:`segment_reach_levels`, with room to spare), others
    as before (NaN and infinities compare as they always did).

    In sane blocks a segment whose relative segment comes within the accept radius
    (``sqrt(a2)``) less that deviation and the room is a sure hit: at that moment the true
    centre is within the accept disc of the robot, so the exact tests would find the hit on
    the piece holding that moment. It is added to ``hits`` and not flagged (the exact tests
    gave the same count for it, a little later).

    A cheap box test of every segment (branch-free, no root) runs first, and the lens test
    only for the few it keeps (about 3 % on crowd scenes): the relative segment ab comes
    within R of the moving point only if ``|a + b| - |b - a| <= 2 R`` along x and along y, and
    R here bounds both radii of the lens test (``dev <= |ha| + 3 max(ea, eb)``, and ``emax``
    bounds ``ea`` and ``eb``) with twice the room for rounding (in other blocks the room is
    infinite: all are kept). The segments it keeps go through the very same lens test, in the
    same order, so the hits and the flagged list are bit for bit those of testing every segment.
    """
    px, py, tt = path[0], path[1], path[2]
    flagged = work[1]
    cxp, cyp, cep = work[5], work[6], work[7]
    rho = obs[4][i, 6]
    _, _, bn, npts, sane, _, _ = blk
    npt = bn * npts
    vm = pre[0][i]
    acc = math.sqrt(a2) if a2 > 0.0 else -np.inf  # (a2 < 0: no accept disc)
    # 2 R, as k0 + k1 |tb - ta|
    k0 = 2.0 * (max(rho, acc) + 3.0 * emax) * (1.0 + 2.0 * MARGIN) + 4.0 * room
    k1 = vm * (1.0 + 2.0 * MARGIN)
    nk = _box_kept(npt, k0, k1, px, py, tt, cxp, cyp, work[2], work[0], flagged)
    nf = 0
    for k in range(nk):
        p = flagged[k]
        dev = _lens_dev(p, vm, tt, cxp, cyp, cep)
        reach = (rho + dev) * (1.0 + MARGIN) + room
        ax = px[p] - cxp[p]
        ay = py[p] - cyp[p]
        bx = px[p + 1] - cxp[p + 1]
        by = py[p + 1] - cyp[p + 1]
        if sane:
            inner = (acc - dev) * (1.0 - MARGIN) - room
            r2 = inner * inner if inner > 0.0 else -1.0
            close, sure = segment_reach_levels(ax, ay, bx, by, reach * reach, r2)
        else:
            close = point_segment_d2(0.0, 0.0, ax, ay, bx, by) <= reach * reach
            sure = False
        hits[p] += 1 if sure else 0
        flagged[nf] = p
        nf += 1 if close and not sure else 0
    return nf


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _exact_moving(i, nf, room, a2, margin, path, work, cls, obs, extra, motion, pre, ncol):
    """Step 3: exact tests of the ``nf`` flagged segments on obstacle i, piece by piece.

    Long by design: one fused Numba step; splitting it adds calls in the hot loop.

    Long because it is one loop that fills a bounded list of relative segments, tests the list
    in one pass and resumes where it stopped; its phases share the loop's state.
    """
    px, py, tt, rvx, rvy = path[0], path[1], path[2], path[6], path[7]
    flagged, cand, kpt = work[1], work[3], work[4]
    qax, qay, qbx, qby, qd2 = work[8], work[9], work[10], work[11], work[12]
    qseg, done = work[13], work[14]
    is_circle, thresh, verts, nverts, bound, hull, nhull = obs
    kt, ko, kv, nk, k_start = motion
    boxes, bbase, lg, boxed = pre[2], pre[3], pre[4], pre[5]
    last = nk[i] - 2  # index of the last piece
    ks = k_start[i]
    bcx = bound[i, 4]
    bcy = bound[i, 5]
    rho = bound[i, 6]
    rho2 = rho * rho
    convex = extra[1][i] and not is_circle[i]  # (polygon tests all at once)
    # 3. Exact tests, piece by piece, for the segments that come within reach: their relative
    # segments on each piece (exactly as the walk computes them) go to a list, then their
    # distances to the bounding-circle centre are found in one pass, then the exact tests run
    # for those within it, each segment counted once.
    cap = qax.shape[0]
    for f in range(nf):
        done[flagged[f]] = False  # (set once a piece hits; counted at the end)
    f = 0
    while True:
        ne = 0
        while f < nf:
            p = flagged[f]
            ax = px[p]
            ay = py[p]
            ta = tt[p]
            tb = tt[p + 1]
            # the pieces the segment needs, from the one ta falls in (last knot <= ta) to the
            # one tb falls in (last knot < tb), as the walk finds them
            k = kpt[p]
            while k > ks and kt[i, k] > ta:
                k -= 1
            while k < last and kt[i, k + 1] <= ta:
                k += 1
            kb = max(k, kpt[p + 1])
            while kb > k and not kt[i, kb] < tb:
                kb -= 1
            while kb < last and kt[i, kb + 1] < tb:
                kb += 1
            if kb - k > PIECES:
                # many pieces: first the box of the offsets over them
                if not boxed[i]:
                    fill_boxes(i, ko, nk, boxes, bbase, lg)
                    boxed[i] = True
                k0 = kt[i, k]
                sa = max(ta, k0)
                oxa = ko[i, k, 0] + kv[i, k, 0] * (sa - k0)
                oya = ko[i, k, 1] + kv[i, k, 1] * (sa - k0)
                oxb = ko[i, kb, 0] + kv[i, kb, 0] * (tb - kt[i, kb])
                oyb = ko[i, kb, 1] + kv[i, kb, 1] * (tb - kt[i, kb])
                lv = lg[kb - k]
                r0 = bbase[i] + lv * nk[i] + k + 1
                r1 = bbase[i] + lv * nk[i] + kb - (1 << lv) + 1
                xlo = min(min(oxa, oxb), min(boxes[r0, 0], boxes[r1, 0]))
                ylo = min(min(oya, oyb), min(boxes[r0, 1], boxes[r1, 1]))
                xhi = max(max(oxa, oxb), max(boxes[r0, 2], boxes[r1, 2]))
                yhi = max(max(oya, oyb), max(boxes[r0, 3], boxes[r1, 3]))
                # the robot's segment must come within rho of the centre's box: separating
                # axes x, y and the segment's normal, and the box's circumcircle
                bx = px[p + 1]
                by = py[p + 1]
                hx = 0.5 * (xhi - xlo)
                hy = 0.5 * (yhi - ylo)
                mx = bcx + 0.5 * (xlo + xhi)
                my = bcy + 0.5 * (ylo + yhi)
                r_ = rho * (1.0 + MARGIN) + room
                ex = bx - ax
                ey = by - ay
                reach = (rho + math.sqrt(hx * hx + hy * hy)) * (1.0 + MARGIN) + room
                if (
                    max(ax, bx) < mx - hx - r_
                    or min(ax, bx) > mx + hx + r_
                    or max(ay, by) < my - hy - r_
                    or min(ay, by) > my + hy + r_
                    or abs(ex * (my - ay) - ey * (mx - ax))
                    > r_ * math.sqrt(ex * ex + ey * ey) + hx * abs(ey) + hy * abs(ex)
                    or point_segment_d2(mx, my, ax, ay, bx, by) > reach * reach
                ):
                    f += 1
                    continue
            if ne + kb - k < cap:
                for kk in range(k, kb + 1):
                    k0 = kt[i, kk]
                    k1 = kt[i, kk + 1] if kk < last else np.inf
                    sa = max(ta, k0)
                    sb = min(tb, k1)
                    vx = kv[i, kk, 0]
                    vy = kv[i, kk, 1]
                    qax[ne] = ax + rvx[p] * (sa - ta) - (ko[i, kk, 0] + vx * (sa - k0))
                    qay[ne] = ay + rvy[p] * (sa - ta) - (ko[i, kk, 1] + vy * (sa - k0))
                    qbx[ne] = ax + rvx[p] * (sb - ta) - (ko[i, kk, 0] + vx * (sb - k0))
                    qby[ne] = ay + rvy[p] * (sb - ta) - (ko[i, kk, 1] + vy * (sb - k0))
                    qseg[ne] = p
                    ne += 1
                f += 1
                continue
            if ne > 0:
                break  # test the list first, then come back to this segment
            # more pieces than the list holds: test them on the spot
            for kk in range(k, kb + 1):
                k0 = kt[i, kk]
                k1 = kt[i, kk + 1] if kk < last else np.inf
                sa = max(ta, k0)
                sb = min(tb, k1)
                vx = kv[i, kk, 0]
                vy = kv[i, kk, 1]
                pax = ax + rvx[p] * (sa - ta) - (ko[i, kk, 0] + vx * (sa - k0))
                pay = ay + rvy[p] * (sa - ta) - (ko[i, kk, 1] + vy * (sa - k0))
                pbx = ax + rvx[p] * (sb - ta) - (ko[i, kk, 0] + vx * (sb - k0))
                pby = ay + rvy[p] * (sb - ta) - (ko[i, kk, 1] + vy * (sb - k0))
                d = point_segment_d2(bcx, bcy, pax, pay, pbx, pby)
                if d <= rho2 and (
                    d <= a2
                    or (
                        not is_circle[i]
                        and polygon_hit(
                            pax, pay, pbx, pby, i, thresh, verts, nverts, hull, nhull, extra,
                            margin,
                        )
                    )
                ):  # fmt: skip
                    done[p] = True
                    break
            f += 1
        for e in range(ne):
            qd2[e] = point_segment_d2(bcx, bcy, qax[e], qay[e], qbx[e], qby[e])
        if convex:
            # the polygon tests of the entries within the bounding circle, all at once
            sax, say, sbx, sby = cls[0]
            verdict = cls[1]
            sidx = cls[3]
            vmap = cls[4]
            # (an int64 from the start: a literal 0 made Numba compile classify_segments a
            # second time, for the type Literal[int](0), before the loop widened it)
            nt = np.int64(0)
            for e in range(ne):
                d = qd2[e]
                sax[nt] = qax[e]
                say[nt] = qay[e]
                sbx[nt] = qbx[e]
                sby[nt] = qby[e]
                sidx[nt] = e
                vmap[e] = 2  # (not tested)
                nt += 1 if (d <= rho2) & (d > a2) else 0
            classify_segments(i, nt, cls[0], verdict, cls[2], obs, extra, margin)
            for t in range(nt):
                vmap[sidx[t]] = verdict[t]
        # the entries within the bounding circle, listed without a branch (most are not)
        inside = cls[3]
        nin = 0
        for e in range(ne):
            inside[nin] = e
            nin += 1 if qd2[e] <= rho2 else 0
        # (branch-free where it can be: whether an entry hits is as good as random)
        for q in range(nin):
            e = inside[q]
            p = qseg[e]
            hit = qd2[e] <= a2
            if convex:
                v = vmap[e]  # (2 for those within a2: not classified)
                hit = hit | (v == 1)
                if v < 0 and not done[p]:
                    hit = segment_hits_polygon(
                        qax[e], qay[e], qbx[e], qby[e], verts, i, nverts[i], thresh[i]
                    )
            elif not hit and not is_circle[i] and not done[p]:
                hit = polygon_hit(
                    qax[e], qay[e], qbx[e], qby[e], i, thresh, verts, nverts, hull, nhull,
                    extra, margin,
                )  # fmt: skip
            done[p] = done[p] | hit
        if f >= nf:
            break
    for f in range(nf):
        p = flagged[f]
        ncol[cand[p]] += 1 if done[p] else 0
