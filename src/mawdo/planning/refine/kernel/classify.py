"""Vectorised polygon verdicts (separating axes) and the per-call obstacle tables."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.refine.kernel.constants import MARGIN, SLACK
from mawdo.planning.refine.kernel.primitives import orient, point_in_polygon, point_segment_d2


@njit(cache=True, fastmath=False, error_model="numpy")
def classify_segments(i, n, seg, out, scratch, obs, extra, margin):
    """:func:`polygon_hit` for ``n`` segments at once, convex polygon i, loops over segments
    innermost (they vectorise).

    Long by design: one fused Numba pass; splitting it adds calls in the hot loop.

    Long because it is one vectorised pass per axis over all segments (Numba hot loop).

    ``seg = (ax, ay, bx, by)`` arrays (obstacle i's frame); writes ``out[e]``: 1 hit, 0 miss, -1
    undecided (the general test, :func:`segment_hits_polygon`, decides). The same arithmetic
    as :func:`polygon_hit`, so the same decisions.
    """
    sax, say, sbx, sby = seg
    gap, lo, hi, snx, sny, slen, best, sep = scratch
    _, thresh, verts, nverts, _, hull, nhull = obs
    hlo = extra[2]
    hhi = extra[3]
    einv = extra[4]
    r = thresh[i]
    for e in range(n):
        gap[e] = -np.inf
        sep[e] = False
    # separating axes: convex-hull edge normals ...
    for k in range(nhull[i]):
        nx = hull[i, k, 0]
        ny = hull[i, k, 1]
        h = hull[i, k, 2]
        hl = hlo[i, k]
        hh = hhi[i, k]
        for e in range(n):
            pa = nx * sax[e] + ny * say[e]
            pb = nx * sbx[e] + ny * sby[e]
            sep[e] = sep[e] | ((pa > h) & (pb > h))
            gap[e] = max(gap[e], max(min(pa, pb) - hh, hl - max(pa, pb)))
    # ... and the segment's own normal
    for e in range(n):
        ex = sbx[e] - sax[e]
        ey = sby[e] - say[e]
        length = math.sqrt(ex * ex + ey * ey)
        slen[e] = length
        snx[e] = -ey / length
        sny[e] = ex / length
        lo[e] = np.inf
        hi[e] = -np.inf
    for k in range(nverts[i]):
        vx = verts[i, k, 0]
        vy = verts[i, k, 1]
        for e in range(n):
            s = snx[e] * (vx - sax[e]) + sny[e] * (vy - say[e])
            lo[e] = min(lo[e], s)
            hi[e] = max(hi[e], s)
    # disjoint ones: the distance, at a polygon vertex or at a segment end
    for e in range(n):
        best[e] = np.inf
    nv = nverts[i]
    for k in range(nv):
        vx = verts[i, k, 0]
        vy = verts[i, k, 1]
        kk = k + 1 if k + 1 < nv else 0
        fx = verts[i, kk, 0] - vx
        fy = verts[i, kk, 1] - vy
        ek = einv[i, k]
        for e in range(n):
            ax = sax[e]
            ay = say[e]
            bx = sbx[e]
            by = sby[e]
            ex = bx - ax
            ey = by - ay
            inv = 1.0 / max(ex * ex + ey * ey, 1e-300)
            b = best[e]
            wx = vx - ax
            wy = vy - ay
            u = min(max((wx * ex + wy * ey) * inv, 0.0), 1.0)
            wx -= u * ex
            wy -= u * ey
            b = min(b, wx * wx + wy * wy)
            wx = ax - vx
            wy = ay - vy
            u = min(max((wx * fx + wy * fy) * ek, 0.0), 1.0)
            wx -= u * fx
            wy -= u * fy
            b = min(b, wx * wx + wy * wy)
            wx = bx - vx
            wy = by - vy
            u = min(max((wx * fx + wy * fy) * ek, 0.0), 1.0)
            wx -= u * fx
            wy -= u * fy
            best[e] = min(b, wx * wx + wy * wy)
    lo_acc = (r - margin) * (r - margin) if r > margin else -1.0
    hi_rej = (r + margin) * (r + margin)
    for e in range(n):
        has = slen[e] > 0.0
        g = max(gap[e], max(lo[e], -hi[e])) if has else gap[e]
        miss = sep[e] | (has & ((lo[e] > r + SLACK) | (hi[e] < -r - SLACK)))
        far = 0 if best[e] > hi_rej else -1
        apart = 1 if best[e] <= lo_acc else far
        out[e] = 0 if miss else (1 if g < -margin else (apart if g > margin else -1))


@njit(cache=True, fastmath=False, error_model="numpy")
def prepare_obstacles(is_circle, thresh, verts, nverts, bound, hull, nhull):
    """Per-obstacle data for the fast paths: ``(acc2, convex, hlo, hhi, einv)``.

    acc2 : squared radius about the bounding-circle centre within which any segment is a hit:
        ``rho^2`` for a circle (the exact test), for a polygon the largest disc about the centre
        inside it, grown by ``r`` and shrunk by the margin (``-1`` when the centre is outside).
    convex : the polygon is convex (then separating axes decide intersection, and a vertex or
        a segment end the distance).
    hlo, hhi : the polygon's extent along each hull edge normal (pixels).
    einv : ``1 / |edge|^2`` per polygon edge (0 for a zero-length edge).
    """
    n = thresh.shape[0]
    acc2 = np.empty(n)
    convex = np.zeros(n, dtype=np.bool_)
    hlo = np.zeros((n, max(hull.shape[1], 1)))
    hhi = np.zeros((n, max(hull.shape[1], 1)))
    einv = np.zeros((n, max(verts.shape[1], 1)))
    for i in range(n):
        if is_circle[i]:
            acc2[i] = bound[i, 6] * bound[i, 6]
            continue
        nv = nverts[i]
        cx = bound[i, 4]
        cy = bound[i, 5]
        acc2[i] = -1.0
        if point_in_polygon(cx, cy, verts, i, nv):
            d2 = np.inf
            for k in range(nv):
                kk = k + 1 if k + 1 < nv else 0
                d2 = min(
                    d2,
                    point_segment_d2(
                        cx, cy, verts[i, k, 0], verts[i, k, 1], verts[i, kk, 0], verts[i, kk, 1]
                    ),
                )
            acc = (math.sqrt(d2) + thresh[i]) * (1.0 - MARGIN) - MARGIN
            if acc > 0.0:
                acc2[i] = acc * acc
        pos = False
        neg = False
        for k in range(nv):
            k0 = k - 1 if k > 0 else nv - 1
            k1 = k + 1 if k + 1 < nv else 0
            o = orient(
                verts[i, k0, 0], verts[i, k0, 1], verts[i, k, 0], verts[i, k, 1],
                verts[i, k1, 0], verts[i, k1, 1],
            )  # fmt: skip
            pos = pos or o > 0.0
            neg = neg or o < 0.0
            fx = verts[i, k1, 0] - verts[i, k, 0]
            fy = verts[i, k1, 1] - verts[i, k, 1]
            e2 = fx * fx + fy * fy
            einv[i, k] = 1.0 / e2 if e2 > 0.0 else 0.0
        convex[i] = not (pos and neg) and nhull[i] > 0
        for k in range(nhull[i]):
            lo = np.inf
            hi = -np.inf
            for v in range(nv):
                s = hull[i, k, 0] * verts[i, v, 0] + hull[i, k, 1] * verts[i, v, 1]
                lo = min(lo, s)
                hi = max(hi, s)
            hlo[i, k] = lo
            hhi[i, k] = hi
    return acc2, convex, hlo, hhi, einv
