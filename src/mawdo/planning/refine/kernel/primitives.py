"""Compiled geometry primitives of the cost kernel: |atan2|, distances, orientation, segment
and polygon hit tests (exact; the filters in front of them live in the passes)."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.refine.kernel.constants import (
    MOREBITS,
    P0,
    P1,
    P2,
    P3,
    P4,
    Q0,
    Q1,
    Q2,
    Q3,
    Q4,
    SLACK,
    T3P8,
)


@njit(cache=True, fastmath=False, error_model="numpy")
def abs_atan2(y, x):
    """``|atan2(y, x)|`` in [0, pi], branch-free so that loops over it vectorise.

    Within 2 ulp of the C library's ``atan2`` for finite inputs; NaN for ``(0, 0)`` or an
    infinite input (callers fall back to ``math.atan2`` there).
    """
    ay = abs(y)
    ax = abs(x)
    # t = ay / ax; z is t, (t - 1) / (t + 1) or -1 / t, as one quotient
    big = ay > T3P8 * ax
    mid = ay > 0.66 * ax
    z = (-ax if big else (ay - ax if mid else ay)) / (ay if big else (ay + ax if mid else ax))
    base = 0.5 * math.pi if big else (0.25 * math.pi if mid else 0.0)
    extra = MOREBITS if big else (0.5 * MOREBITS if mid else 0.0)
    zz = z * z
    p = (((P0 * zz + P1) * zz + P2) * zz + P3) * zz + P4
    q = ((((zz + Q0) * zz + Q1) * zz + Q2) * zz + Q3) * zz + Q4
    a = base + (z * (zz * p / q) + z + extra)
    return math.pi - a if x < 0.0 else a


@njit(cache=True, fastmath=False, error_model="numpy")
def point_segment_d2(px, py, ax, ay, bx, by):
    """Squared distance from point p to segment ab (pixels^2).

    Branch-free (min/max clamps) so that loops over many segments stay fast; a zero-length
    segment gives ``u = 0``, the distance to ``a``.
    """
    dx = bx - ax
    dy = by - ay
    wx = px - ax
    wy = py - ay
    u = min(max((wx * dx + wy * dy) / max(dx * dx + dy * dy, 1e-300), 0.0), 1.0)
    wx -= u * dx
    wy -= u * dy
    return wx * wx + wy * wy


@njit(cache=True, fastmath=False, error_model="numpy")
def segment_reaches_origin(ax, ay, bx, by, r2):
    """Segment ab comes within ``sqrt(r2)`` of the origin (pixels), up to rounding: a filter.

    The distance of :func:`point_segment_d2` without its division (which kept loops over it
    several times slower): the nearest point is an end unless the foot of the perpendicular
    falls inside, and then ``d^2 |ab|^2 = cross^2``. Both differ from the true distance by
    rounding only (relative to the coordinates), far below the callers' room; finite
    coordinates only (callers with NaN or huge ones use :func:`point_segment_d2`).
    """
    return segment_reach_levels(ax, ay, bx, by, r2, -1.0)[0]


@njit(cache=True, fastmath=False, error_model="numpy")
def segment_reach_levels(ax, ay, bx, by, r2, s2):
    """:func:`segment_reaches_origin` for two radii at once: ``(within sqrt(r2), within
    sqrt(s2))`` (a negative ``s2``: never)."""
    dx = bx - ax
    dy = by - ay
    dot = -(ax * dx + ay * dy)  # (origin - a) . (b - a)
    ee = dx * dx + dy * dy
    cross = ax * dy - ay * dx
    end2 = ax * ax + ay * ay if dot <= 0.0 else bx * bx + by * by
    foot = (dot > 0.0) & (dot < ee)
    num = cross * cross if foot else end2
    den = ee if foot else 1.0
    return num <= r2 * den, num <= s2 * den


@njit(cache=True, fastmath=False, error_model="numpy")
def orient(ax, ay, bx, by, cx, cy):
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)


@njit(cache=True, fastmath=False, error_model="numpy")
def _on_box(ax, ay, bx, by, px, py):
    # p collinear with ab is on the closed segment iff it is in ab's bounding box
    return min(ax, bx) <= px <= max(ax, bx) and min(ay, by) <= py <= max(ay, by)


@njit(cache=True, fastmath=False, error_model="numpy")
def _segments_touch(ax, ay, bx, by, cx, cy, dx, dy):
    """True iff closed segments ab and cd share a point."""
    o1 = orient(ax, ay, bx, by, cx, cy)
    o2 = orient(ax, ay, bx, by, dx, dy)
    o3 = orient(cx, cy, dx, dy, ax, ay)
    o4 = orient(cx, cy, dx, dy, bx, by)
    if ((o1 > 0.0 and o2 < 0.0) or (o1 < 0.0 and o2 > 0.0)) and (
        (o3 > 0.0 and o4 < 0.0) or (o3 < 0.0 and o4 > 0.0)
    ):
        return True
    if o1 == 0.0 and _on_box(ax, ay, bx, by, cx, cy):
        return True
    if o2 == 0.0 and _on_box(ax, ay, bx, by, dx, dy):
        return True
    if o3 == 0.0 and _on_box(cx, cy, dx, dy, ax, ay):
        return True
    if o4 == 0.0 and _on_box(cx, cy, dx, dy, bx, by):
        return True
    return False


@njit(cache=True, fastmath=False, error_model="numpy")
def point_in_polygon(px, py, verts, i, nv):
    """Even-odd rule for polygon ``verts[i]``; the boundary is decided by the edge tests."""
    inside = False
    j = nv - 1
    for k in range(nv):
        xi = verts[i, k, 0]
        yi = verts[i, k, 1]
        xj = verts[i, j, 0]
        yj = verts[i, j, 1]
        if (yi > py) != (yj > py):
            xint = xi + (xj - xi) * (py - yi) / (yj - yi)
            if px < xint:
                inside = not inside
        j = k
    return inside


@njit(cache=True, fastmath=False, error_model="numpy")
def segment_hits_polygon(ax, ay, bx, by, verts, i, nv, r):
    """Distance from segment ab to polygon ``verts[i]`` (boundary or interior) is ``<= r``."""
    r2 = r * r
    xmin = min(ax, bx) - r
    xmax = max(ax, bx) + r
    ymin = min(ay, by) - r
    ymax = max(ay, by) + r
    for k in range(nv):
        cx = verts[i, k, 0]
        cy = verts[i, k, 1]
        kk = k + 1 if k + 1 < nv else 0
        dx = verts[i, kk, 0]
        dy = verts[i, kk, 1]
        # an edge outside the segment's r-grown box can be neither crossed nor within r
        if max(cx, dx) < xmin or min(cx, dx) > xmax or max(cy, dy) < ymin or min(cy, dy) > ymax:
            continue
        if _segments_touch(ax, ay, bx, by, cx, cy, dx, dy):
            return True
        if r > 0.0:
            if (
                point_segment_d2(ax, ay, cx, cy, dx, dy) <= r2
                or point_segment_d2(bx, by, cx, cy, dx, dy) <= r2
                or point_segment_d2(cx, cy, ax, ay, bx, by) <= r2
            ):
                return True  # the edge's other end is checked as the next edge's first end
    # no edge within reach: the segment is wholly inside or wholly outside
    return point_in_polygon(ax, ay, verts, i, nv)


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def polygon_hit(ax, ay, bx, by, i, thresh, verts, nverts, hull, nhull, extra, margin):
    """Segment ab (in obstacle i's frame) is within ``thresh[i]`` of polygon i.

    Long by design: one exact test, inlined by Numba; its cases share local state.

    Long because it inlines the staged filters of one hit test (Numba hot path).

    ``extra`` comes from :func:`prepare_obstacles`; ``margin`` is the room (pixels) a fast
    decision needs (``inf`` turns them off, leaving the exact test).
    """
    convex = extra[1]
    hlo = extra[2]
    hhi = extra[3]
    einv = extra[4]
    r = thresh[i]
    gap = -np.inf  # largest separation found along an axis (pixels)
    # Separating axes first (exact rejections, cheap): an axis along which the segment lies
    # more than r beyond the polygon proves the distance exceeds r. Convex-hull edge normals
    # (hull[i, k] = (nx, ny, h) with h = n.c + r) ...
    out = False
    for k in range(nhull[i]):
        nx = hull[i, k, 0]
        ny = hull[i, k, 1]
        h = hull[i, k, 2]
        pa = nx * ax + ny * ay
        pb = nx * bx + ny * by
        out = out | ((pa > h) & (pb > h))
        gap = max(gap, max(min(pa, pb) - hhi[i, k], hlo[i, k] - max(pa, pb)))
    if out:
        return False
    # ... and the segment's own normal.
    ex = bx - ax
    ey = by - ay
    length = math.sqrt(ex * ex + ey * ey)
    if length > 0.0:
        nx = -ey / length
        ny = ex / length
        lo = np.inf
        hi = -np.inf
        for k in range(nverts[i]):
            s = nx * (verts[i, k, 0] - ax) + ny * (verts[i, k, 1] - ay)
            lo = min(lo, s)
            hi = max(hi, s)
        if lo > r + SLACK or hi < -r - SLACK:
            return False
        gap = max(gap, max(lo, -hi))
    if convex[i]:
        # A convex polygon and the segment intersect iff they overlap on every one of these
        # axes; if they are disjoint, their distance is attained at a polygon vertex or at a
        # segment end.
        if gap < -margin:
            return True
        if gap > margin:
            nv = nverts[i]
            inv = 1.0 / max(ex * ex + ey * ey, 1e-300)
            best = np.inf
            for k in range(nv):
                vx = verts[i, k, 0]
                vy = verts[i, k, 1]
                kk = k + 1 if k + 1 < nv else 0
                fx = verts[i, kk, 0] - vx
                fy = verts[i, kk, 1] - vy
                # vertex k to the segment
                wx = vx - ax
                wy = vy - ay
                u = min(max((wx * ex + wy * ey) * inv, 0.0), 1.0)
                wx -= u * ex
                wy -= u * ey
                best = min(best, wx * wx + wy * wy)
                # the segment's ends to edge k
                wx = ax - vx
                wy = ay - vy
                u = min(max((wx * fx + wy * fy) * einv[i, k], 0.0), 1.0)
                wx -= u * fx
                wy -= u * fy
                best = min(best, wx * wx + wy * wy)
                wx = bx - vx
                wy = by - vy
                u = min(max((wx * fx + wy * fy) * einv[i, k], 0.0), 1.0)
                wx -= u * fx
                wy -= u * fy
                best = min(best, wx * wx + wy * wy)
            if r > margin and best <= (r - margin) * (r - margin):
                return True
            if best > (r + margin) * (r + margin):
                return False
    return segment_hits_polygon(ax, ay, bx, by, verts, i, nverts[i], r)
