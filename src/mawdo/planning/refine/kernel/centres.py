"""Step 1 of the pass over moving obstacles (:mod:`mawdo.planning.refine.kernel.moving`): where an
obstacle's centre is at each path time of a block, exactly on its constant-velocity pieces (few
knots), interpolated in its grid (many knots, within the grid's gap), or by a walk (times beyond
the grid). Hints of the piece at each time go to the exact tests of step 3.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.refine.kernel.constants import COUNT, GRID_CELLS


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def centres(i, blk, path, work, obs, motion, grid):
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
        few_knots(i, ks, kw, bcx, bcy, npt, tt, kt, ko, kv, kpt, cxp, cyp, cep)
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
        # (times beyond the grid) walk, from piece ks again wherever time goes back (a
        # horizon's layout is one path of many candidates' starts: kernel.horizon)
        for b in range(bn):
            k = ks
            prev = -np.inf
            for p in range(b * npts, b * npts + npts):
                t = tt[p]
                if t < prev:
                    k = ks
                if t == t:  # (a NaN time leaves the last one)
                    prev = t
                while k < last and kt[i, k + 1] <= t:
                    k += 1
                kpt[p] = k
                cxp[p] = bcx + ko[i, k, 0] + kv[i, k, 0] * (t - kt[i, k])
                cyp[p] = bcy + ko[i, k, 1] + kv[i, k, 1] * (t - kt[i, k])
                cep[p] = 0.0
    return 0.0


@njit(cache=True, fastmath=False, error_model="numpy")
def few_knots(i, ks, kw, bcx, bcy, npt, tt, kt, ko, kv, kpt, cxp, cyp, cep):
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
