"""The pass over moving obstacles (spacetime mode) in three steps: where the obstacle's centre
is at each path time (:mod:`mawdo.planning.refine.kernel.centres`), which segments come within
reach of it (a box test, then a lens test: :mod:`mawdo.planning.refine.kernel.near`), and the exact
tests of those, piece by piece of the obstacle's motion (here).

:func:`moving_pass` runs the steps for one obstacle and one block. Most of them are inlined
into it (Numba IR inlining; compiled on their own, called with the pass's long argument lists,
crowd scenes' calls measured up to 20 % slower, for no shorter compile); the few-knot centres
and the box test, called once per obstacle and block with a few arrays, are compiled on their
own (same speed, shorter compile). The pass itself is a row of :mod:`mawdo.jit.warm`'s table
(its arguments are plain tuples), so one process compiles it while another compiles the cost
kernel's other parts. The filters of step 2 only skip segments whose outcome is certain, and
the centres and the exact tests are computed as they always were, so every count is the same.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.refine.kernel.centres import centres
from mawdo.planning.refine.kernel.classify import classify_segments
from mawdo.planning.refine.kernel.constants import MARGIN, PIECES
from mawdo.planning.refine.kernel.near import near_segments, rounding_room
from mawdo.planning.refine.kernel.passes import fill_boxes
from mawdo.planning.refine.kernel.primitives import (
    point_segment_d2,
    polygon_hit,
    segment_hits_polygon,
)


@njit(cache=True, fastmath=False, error_model="numpy")
def moving_pass(i, blk, a2, margin, path, work, cls, obs, extra, motion, pre, grid, hits, ncol):
    """Hits of the block's segments on moving obstacle i (spacetime); adds them to ``ncol``.

    ``blk`` is the block's scalars ``(t0, speed, bn, npts, sane, cmax, tmax)``: planning time
    and robot speed (time steps, px per step), candidates in the block and points per path,
    whether all coordinates are sane, the largest coordinate (px) and the latest path time
    (time steps), as :func:`mawdo.planning.refine.kernel.passes.block_paths` finds them (a plain
    tuple: its type reads back from its ``repr``, so the steps are rows of the jit table).

    The exact test walks the robot's segments and the obstacle's constant-velocity pieces
    together (both are ordered in time): on each common piece the robot's position relative to
    the obstacle moves along a straight segment, tested against the shape at offset zero. Past
    the table's last knot the last piece is extrapolated (callers size tables so that this does
    not happen). Filters in front of it only skip pieces whose outcome is certain.
    """
    emax = centres(i, blk, path, work, obs, motion, grid)
    room = rounding_room(i, blk, pre)
    nf = near_segments(i, blk, room, a2, emax, path, work, obs, pre, hits)
    if nf > 0:
        _exact_moving(i, nf, room, a2, margin, path, work, cls, obs, extra, motion, pre, ncol)


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
