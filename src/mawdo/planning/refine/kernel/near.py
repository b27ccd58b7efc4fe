"""Step 2 of the pass over moving obstacles (:mod:`mawdo.planning.refine.kernel.moving`): which of a
block's segments come within reach of an obstacle. A cheap box test of every segment first
(no square root, no division; it keeps every segment the lens test could find near), then the
lens test of those it keeps; sure hits are counted here, the rest are flagged for the exact
tests of step 3. Every filter has room for rounding, so the counts are those of the exact tests.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.refine.kernel.constants import MARGIN
from mawdo.planning.refine.kernel.primitives import point_segment_d2, segment_reach_levels


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def rounding_room(i, blk, pre):
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
def lens_dev(p, vm, tt, cxp, cyp, cep):
    """How far (pixels) obstacle i's true centre may be from the moving point of the lens test
    while the robot is on segment p (see :func:`near_segments`)."""
    dcx = cxp[p + 1] - cxp[p]
    dcy = cyp[p + 1] - cyp[p]
    ha = 0.5 * vm * (tt[p + 1] - tt[p])
    ea = cep[p]
    eb = cep[p + 1]
    e = 0.5 * (ea + eb)  # the true half distance is at least d - e
    dev = math.sqrt(max(ha * ha - 0.25 * (dcx * dcx + dcy * dcy) + 2.0 * e * (ha + e), 0.0))
    return dev + max(ea, eb)


@njit(cache=True, fastmath=False, error_model="numpy")
def box_kept(npt, k0, k1, px, py, tt, cxp, cyp, real, near, flagged):
    """The box test of :func:`near_segments` (radius ``(k0 + k1 |tb - ta|) / 2``) on every
    segment; lists those it keeps in ``flagged`` and returns how many (compiled on its own,
    as :func:`~mawdo.planning.refine.kernel.centres.few_knots`)."""
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
def near_segments(i, blk, room, a2, emax, path, work, obs, pre, hits):
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
    nk = box_kept(npt, k0, k1, px, py, tt, cxp, cyp, work[2], work[0], flagged)
    nf = 0
    for k in range(nk):
        p = flagged[k]
        dev = lens_dev(p, vm, tt, cxp, cyp, cep)
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
