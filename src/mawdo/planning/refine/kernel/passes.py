"""Block layout of the candidates' paths, box tables of obstacle motion, and the pass over
standing obstacles."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.refine.kernel.classify import classify_segments
from mawdo.planning.refine.kernel.constants import SANE, ZERO_LENGTH
from mawdo.planning.refine.kernel.primitives import (
    abs_atan2,
    point_segment_d2,
    polygon_hit,
    segment_hits_polygon,
)


@njit(cache=True, fastmath=False, error_model="numpy")
def box_tables(nk):
    """Layout of sparse tables of the knot offsets' boxes, for box-of-a-knot-range queries.

    Returns ``(base, lg, filled)``: level ``L`` of obstacle ``i`` holds, for each knot ``p``,
    the box ``(xmin, ymin, xmax, ymax)`` of knots ``p .. p + 2^L - 1`` at row
    ``base[i] + L * nk[i] + p`` of a table of ``base[-1]`` rows, once :func:`fill_boxes` has
    filled it (``filled[i]``); ``lg[n] = floor(log2(n))``.
    """
    n = nk.shape[0]
    kmax = 1
    for i in range(n):
        kmax = max(kmax, nk[i])
    lg = np.zeros(kmax + 1, dtype=np.int64)
    for q in range(2, kmax + 1):
        lg[q] = lg[q // 2] + 1
    base = np.zeros(n + 1, dtype=np.int64)
    for i in range(n):
        base[i + 1] = base[i] + nk[i] * (lg[max(nk[i], 1)] + 1)
    return base, lg, np.zeros(n, dtype=np.bool_)


@njit(cache=True, fastmath=False, error_model="numpy")
def fill_boxes(i, ko, nk, table, base, lg):
    """Fill obstacle i's sparse table (see :func:`box_tables`)."""
    b = base[i]
    for p in range(nk[i]):
        table[b + p, 0] = ko[i, p, 0]
        table[b + p, 1] = ko[i, p, 1]
        table[b + p, 2] = ko[i, p, 0]
        table[b + p, 3] = ko[i, p, 1]
    for L in range(1, lg[max(nk[i], 1)] + 1):
        half = 1 << (L - 1)
        prev = b + (L - 1) * nk[i]
        cur = b + L * nk[i]
        for p in range(nk[i] - (1 << L) + 1):
            table[cur + p, 0] = min(table[prev + p, 0], table[prev + p + half, 0])
            table[cur + p, 1] = min(table[prev + p, 1], table[prev + p + half, 1])
            table[cur + p, 2] = max(table[prev + p, 2], table[prev + p + half, 2])
            table[cur + p, 3] = max(table[prev + p, 3], table[prev + p + half, 3])


@njit(cache=True, fastmath=False, error_model="numpy")
def stride(n):
    """Elements (8 bytes each) between the starts of scratch arrays of n elements: n rounded up
    to whole 4 KiB pages, plus 576 bytes (so that 64 of them start at 64 different offsets)."""
    return (n + 511) // 512 * 512 + 72


# Not inlined: compiled on its own its loops run more than twice as fast as inlined into the
# population loop (0.67 -> 0.28 ms a call of 1360 candidates without obstacles), and one call
# per block costs nothing.
@njit(cache=True, fastmath=False, error_model="numpy")
def block_paths(X, c0, bn, start, goal, t0, speed, path, out_len, out_turn):
    """Lay the paths of candidates ``c0 .. c0 + bn - 1`` end to end, with their lengths (C1),
    times, velocities and turning (C3).

    Returns ``(sane, cmax, tmax)``: no coordinate is NaN or beyond ``SANE``, the largest
    coordinate magnitude, the latest path time (NaN times left out).
    """
    px, py, tt, seg, sdx, sdy, rvx, rvy, ux, uy, ang, ufirst = path
    m = X.shape[1] // 2
    npts = m + 2
    nseg = npts - 1
    last_p = bn * npts - 1
    for b in range(bn):
        c = c0 + b
        p0 = b * npts
        px[p0] = start[0]
        py[p0] = start[1]
        for j in range(m):
            px[p0 + j + 1] = X[c, 2 * j]
            py[p0 + j + 1] = X[c, 2 * j + 1]
        px[p0 + npts - 1] = goal[0]
        py[p0 + npts - 1] = goal[1]
    bad = 0
    cmax = 0.0
    for p in range(bn * npts):
        ax = abs(px[p])
        ay = abs(py[p])
        bad += 0 if (ax <= SANE) & (ay <= SANE) else 1  # (NaN too)
        cmax = ax if ax > cmax else cmax
        cmax = ay if ay > cmax else cmax
    sane = bad == 0
    # C1: polyline length (Eq. 26); C3: total turning (Eq. 28), zero-length segments skipped
    for p in range(last_p):
        dx = px[p + 1] - px[p]
        dy = py[p + 1] - py[p]
        s = math.sqrt(dx * dx + dy * dy)
        seg[p] = s
        sdx[p] = dx
        sdy[p] = dy
        rvx[p] = dx * speed / s if s > 0.0 else 0.0
        rvy[p] = dy * speed / s if s > 0.0 else 0.0
    inv_speed = 1.0 / speed
    nz = 0
    for b in range(bn):
        p0 = b * npts
        ufirst[b] = nz
        cum = 0.0
        tt[p0] = t0
        for j in range(nseg):
            cum += seg[p0 + j]
            tt[p0 + j + 1] = t0 + cum * inv_speed
            ux[nz] = sdx[p0 + j]
            uy[nz] = sdy[p0 + j]
            nz += 0 if seg[p0 + j] <= ZERO_LENGTH else 1
        out_len[c0 + b] = cum
    ufirst[bn] = nz
    # |theta_i - pi| equals the angle between consecutive directions
    for v in range(nz - 1):
        ang[v] = abs_atan2(
            ux[v] * uy[v + 1] - uy[v] * ux[v + 1], ux[v] * ux[v + 1] + uy[v] * uy[v + 1]
        )
    for b in range(bn):
        turn = 0.0
        for v in range(ufirst[b], ufirst[b + 1] - 1):
            a = ang[v]
            if a != a:  # an infinite coordinate (or NaN): the library decides
                a = abs(
                    math.atan2(
                        ux[v] * uy[v + 1] - uy[v] * ux[v + 1],
                        ux[v] * ux[v + 1] + uy[v] * uy[v + 1],
                    )
                )
            turn += a
        out_turn[c0 + b] = turn
    tmax = 0.0
    for p in range(bn * npts):
        t = tt[p]
        if t > tmax:
            tmax = t
    return sane, cmax, tmax


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _exact_distances(cx, cy, p0, p1, px, py, real, a2, rho2, near, hits):
    """Segments ``p0 .. p1 - 1`` against the accept disc ``a2`` and the bounding circle
    ``rho2`` about ``(cx, cy)``, by the exact distance (for a circle obstacle, the exact test):
    adds the hits to ``hits``, flags the others within the circle in ``near``; returns how many
    it flagged."""
    nnear = 0
    for p in range(p0, p1):
        d = point_segment_d2(cx, cy, px[p], py[p], px[p + 1], py[p + 1])
        hit = d <= a2
        close = d <= rho2 and not hit and real[p]
        hits[p] += 1 if hit else 0
        nnear += 1 if close else 0
        near[p] = close
    return nnear


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def scaled_d2(ax, ay, bx, by):
    """Squared distance from the origin to segment ab (pixels), times ``den``, without a
    division: ``(num, den)`` = ``(cross^2, |ab|^2)`` where the foot of the perpendicular falls
    inside the segment, else (the nearer end's squared distance, 1)."""
    dx = bx - ax
    dy = by - ay
    dot = -(ax * dx + ay * dy)
    ee = dx * dx + dy * dy
    cross = ax * dy - ay * dx
    foot = (dot > 0.0) & (dot < ee)
    num = cross * cross if foot else (ax * ax + ay * ay if dot <= 0.0 else bx * bx + by * by)
    return num, ee if foot else 1.0


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _sure_distances(cx, cy, npt, px, py, real, a2, rho, margin, near, hits):
    """:func:`_exact_distances` for a block of sane coordinates, without its division.

    The division kept this loop several times slower. Without it the distance differs from
    the exact one by rounding only (about 1e-8 px at 1e7 px, the sane limit), so a segment more
    than ``margin`` (pixels) from both radii gets the verdict the exact distance gives; the
    rare ones within ``margin`` of either are measured again exactly (then the flags of all
    near segments are redone, which gives the same flags for the others).
    """
    acc = math.sqrt(a2) if a2 > 0.0 else -np.inf  # (a2 < 0: no accept disc)
    in2 = (acc - margin) * (acc - margin) if acc > margin else -1.0  # surely a hit within
    out2 = (acc + margin) * (acc + margin) if acc > 0.0 else -1.0  # surely none beyond
    lo2 = (rho - margin) * (rho - margin) if rho > margin else -1.0  # surely close within
    hi2 = (rho + margin) * (rho + margin)  # surely not close beyond
    nnear = 0
    namb = 0
    for p in range(npt - 1):
        num, den = scaled_d2(px[p] - cx, py[p] - cy, px[p + 1] - cx, py[p + 1] - cy)
        hit = num <= in2 * den
        close = (num > out2 * den) & (num <= lo2 * den) & real[p]
        # within margin of the accept radius or of the bounding radius: undecided
        amb = (num > in2 * den) & ((num <= out2 * den) | (num > lo2 * den) & (num <= hi2 * den))
        hits[p] += 1 if hit else 0
        nnear += 1 if close | amb else 0
        namb += 1 if amb else 0
        near[p] = close | amb
    if namb == 0:
        return nnear
    # within rounding of a radius: redo the near ones exactly (hits are not flagged near)
    nnear = 0
    for p in range(npt - 1):
        if near[p]:
            nnear += _exact_distances(cx, cy, p, p + 1, px, py, real, a2, rho * rho, near, hits)
    return nnear


# Not inlined either: on its own it compiles to tighter loops than inside the population loop.
@njit(cache=True, fastmath=False, error_model="numpy")
def static_pass(i, ox, oy, bn, npts, path, work, cls, obs, extra, a2, margin, hits, ncol):
    """Hits of the block's segments on obstacle i standing at offset ``(ox, oy)``.

    Bounding-circle distances in one branch-free pass: inside the accept disc is a hit (for a
    circle obstacle that is the exact test), the few segments between it and the bounding
    circle get the exact test.
    """
    px = path[0]
    py = path[1]
    near, flagged, real, cand = work[0], work[1], work[2], work[3]
    is_circle, thresh, verts, nverts, bound, hull, nhull = obs
    cx = bound[i, 4] + ox
    cy = bound[i, 5] + oy
    rho2 = bound[i, 6] * bound[i, 6]
    npt = bn * npts
    if margin < np.inf:
        nnear = _sure_distances(cx, cy, npt, px, py, real, a2, bound[i, 6], margin, near, hits)
    else:  # (NaN or huge coordinates: every distance measured as the exact test needs it)
        nnear = _exact_distances(cx, cy, 0, npt - 1, px, py, real, a2, rho2, near, hits)
    if nnear == 0:
        return
    nf = np.int64(0)  # (not a literal 0: see moving._exact_moving's nt)
    for p in range(bn * npts - 1):
        flagged[nf] = p
        nf += 1 if near[p] else 0
    near_verdicts(i, ox, oy, nf, flagged, px, py, cand, cls, obs, extra, margin, ncol)


# Not inlined: the standing obstacles' grid (kernel.static_index) calls it too, and one
# compiled copy of the polygon tests spares a second.
@njit(cache=True, fastmath=False, error_model="numpy")
def near_verdicts(i, ox, oy, nf, flagged, px, py, cand, cls, obs, extra, margin, ncol):
    """The exact verdicts of the segments ``flagged[:nf]`` (each joins points ``p`` and ``p +
    1`` of ``px, py``) that come within standing obstacle i's bounding circle, the obstacle at
    offset ``(ox, oy)`` (pixels): one added to ``ncol[cand[p]]`` per hit."""
    is_circle, thresh, verts, nverts, bound, hull, nhull = obs
    if not extra[1][i]:  # not convex: one by one
        for f in range(nf):
            p = flagged[f]
            if polygon_hit(
                px[p] - ox, py[p] - oy, px[p + 1] - ox, py[p + 1] - oy, i, thresh, verts,
                nverts, hull, nhull, extra, margin,
            ):  # fmt: skip
                ncol[cand[p]] += 1
        return
    sax, say, sbx, sby = cls[0]
    verdict = cls[1]
    for f in range(nf):
        p = flagged[f]
        sax[f] = px[p] - ox
        say[f] = py[p] - oy
        sbx[f] = px[p + 1] - ox
        sby[f] = py[p + 1] - oy
    classify_segments(i, nf, cls[0], verdict, cls[2], obs, extra, margin)
    for f in range(nf):
        v = verdict[f]
        if v == 1 or (
            v < 0
            and segment_hits_polygon(sax[f], say[f], sbx[f], sby[f], verts, i, nverts[i], thresh[i])
        ):
            ncol[cand[flagged[f]]] += 1
