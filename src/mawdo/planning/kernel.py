"""Numba kernel: the path cost (paper Eqs. 17-21) of a whole population in one call.

The public wrapper is :class:`mawdo.planning.cost.PathCost`; this module holds the compiled
geometry primitives and the population loop. All coordinates are pixels, times are time steps.

Hit test
--------
A segment hits an obstacle inflated by the robot radius iff its distance to the raw shape is
``<= thresh`` (exact inflation; touching counts as a hit):

* circle: distance from the centre to the segment ``<= R + r``;
* polygon (convex or not): the segment crosses or touches an edge, passes within ``r`` of an
  edge, or lies wholly inside (point-in-polygon of one endpoint; if no edge is within reach both
  endpoints are on the same side).

Moving obstacles (``spacetime`` mode) are tested in the obstacle's frame: over a time piece where
both the robot and the obstacle move with constant velocity, the robot's position relative to
the obstacle moves along a straight segment, which is tested against the shape at offset zero.

Speed
-----
The exact tests above decide every hit. Everything in front of them only skips work whose
outcome is certain, with room to spare for rounding (:data:`_MARGIN`), so the counts are those of
the exact tests alone (which get the very numbers they would get without the filters):

* Candidates go in blocks of :data:`_BLOCK`, their paths laid end to end, so that the passes
  over segments are long, branch-free loops that vectorise.
* Standing obstacles: one pass of distances to the bounding-circle centre. Within the *accept
  disc* (for a circle, the circle itself: the exact test; for a polygon, the largest disc about
  that centre inside it, grown by ``r``) a segment hits; beyond the bounding circle it misses;
  in between, the polygon test runs.
* Polygon test: separating axes (convex-hull edge normals and the segment's normal) reject. For
  a convex polygon they also accept (overlap on every axis means intersection) and otherwise
  prove the two disjoint, when the distance is attained at a polygon vertex or a segment end
  (vertex-segment and end-edge distances). Only what lies within :data:`_MARGIN` of a decision
  boundary goes to the general test (edges, distances, point-in-polygon). For a convex polygon
  the tests of all a pass's segments run at once (:func:`_classify`, vectorised).
* Moving obstacles (``spacetime``): the obstacle's centre at each path time (few knots in the
  block's time span: each piece in turn, branch-free; many: interpolated in a grid of
  positions, filled as far as needed), then a *lens* test per segment: while the robot is on a
  segment the centre moves at most ``vmax`` from where it was at ``ta`` and will be at ``tb``,
  so it stays within ``sqrt(a^2 - d^2)`` (``a = vmax (tb - ta) / 2``, ``d`` half their
  distance) of the point that moves uniformly between the two; relative to that point the robot
  moves along a segment. Exact for a segment within one piece, up to the rounding room. The
  segments that pass it are walked piece by piece, as above; those spanning more than
  :data:`_PIECES` pieces are first tested against the box of the obstacle's positions over them
  (sparse tables of knot boxes), and the pieces' relative segments are measured in one pass.
* Turning: ``|atan2|`` by a branch-free Cephes ``atan`` (within 2 ulp of the C library), one
  vectorised pass per block.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["ZERO_LENGTH", "population_cost", "scratch_size"]

#: Segments shorter than this (pixels) have no direction and contribute no turning.
ZERO_LENGTH = 1e-9
# Separating-axis rejections only fire with this much room to spare (pixels), so that rounding
# can never reject a true hit; anything closer goes to the exact test.
_SLACK = 1e-9
# Fast decisions keep this much room (pixels, and relative): rounding is below 1e-9 px for
# coordinates up to 1e7 px, so a fast decision is always the exact one.
_MARGIN = 1e-6
# Candidates with a coordinate beyond this (pixels), or NaN, skip the fast accepts.
_SANE = 1e7
# A segment spanning more of an obstacle's pieces than this is first tested against a box.
_PIECES = 3
# Candidates per block (the loops over a block's segments vectorise).
_BLOCK = 128
# A block's path times find their pieces by counting knots when it spans at most this many.
_COUNT = 10
# Cells of the moving obstacles' position grids.
_GRID_CELLS = 2048

# |atan2| (Cephes atan.c, double precision: peak relative error 1.9e-16)
_P0 = -8.750608600031904122785e-1
_P1 = -1.615753718733365076637e1
_P2 = -7.500855792314704667340e1
_P3 = -1.228866684490136173410e2
_P4 = -6.485021904942025371773e1
_Q0 = 2.485846490142306297962e1
_Q1 = 1.650270098316988542046e2
_Q2 = 4.328810604912902668951e2
_Q3 = 4.853903996359136964868e2
_Q4 = 1.945506571482613964425e2
_MOREBITS = 6.123233995736765886130e-17
_T3P8 = 2.41421356237309504880  # tan(3 pi / 8)


@njit(cache=True, fastmath=False, error_model="numpy")
def _abs_atan2(y, x):
    """``|atan2(y, x)|`` in [0, pi], branch-free so that loops over it vectorise.

    Within 2 ulp of the C library's ``atan2`` for finite inputs; NaN for ``(0, 0)`` or an
    infinite input (callers fall back to ``math.atan2`` there).
    """
    ay = abs(y)
    ax = abs(x)
    # t = ay / ax; z is t, (t - 1) / (t + 1) or -1 / t, as one quotient
    big = ay > _T3P8 * ax
    mid = ay > 0.66 * ax
    z = (-ax if big else (ay - ax if mid else ay)) / (ay if big else (ay + ax if mid else ax))
    base = 0.5 * math.pi if big else (0.25 * math.pi if mid else 0.0)
    extra = _MOREBITS if big else (0.5 * _MOREBITS if mid else 0.0)
    zz = z * z
    p = (((_P0 * zz + _P1) * zz + _P2) * zz + _P3) * zz + _P4
    q = ((((zz + _Q0) * zz + _Q1) * zz + _Q2) * zz + _Q3) * zz + _Q4
    a = base + (z * (zz * p / q) + z + extra)
    return math.pi - a if x < 0.0 else a


@njit(cache=True, fastmath=False, error_model="numpy")
def _point_segment_d2(px, py, ax, ay, bx, by):
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
def _orient(ax, ay, bx, by, cx, cy):
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)


@njit(cache=True, fastmath=False, error_model="numpy")
def _on_box(ax, ay, bx, by, px, py):
    # p collinear with ab is on the closed segment iff it is in ab's bounding box
    return min(ax, bx) <= px <= max(ax, bx) and min(ay, by) <= py <= max(ay, by)


@njit(cache=True, fastmath=False, error_model="numpy")
def _segments_touch(ax, ay, bx, by, cx, cy, dx, dy):
    """True iff closed segments ab and cd share a point."""
    o1 = _orient(ax, ay, bx, by, cx, cy)
    o2 = _orient(ax, ay, bx, by, dx, dy)
    o3 = _orient(cx, cy, dx, dy, ax, ay)
    o4 = _orient(cx, cy, dx, dy, bx, by)
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
def _point_in_polygon(px, py, verts, i, nv):
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
def _segment_hits_polygon(ax, ay, bx, by, verts, i, nv, r):
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
                _point_segment_d2(ax, ay, cx, cy, dx, dy) <= r2
                or _point_segment_d2(bx, by, cx, cy, dx, dy) <= r2
                or _point_segment_d2(cx, cy, ax, ay, bx, by) <= r2
            ):
                return True  # the edge's other end is checked as the next edge's first end
    # no edge within reach: the segment is wholly inside or wholly outside
    return _point_in_polygon(ax, ay, verts, i, nv)


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _polygon_hit(ax, ay, bx, by, i, thresh, verts, nverts, hull, nhull, extra, margin):
    """Segment ab (in obstacle i's frame) is within ``thresh[i]`` of polygon i.

    ``extra`` comes from :func:`_prepare`; ``margin`` is the room (pixels) a fast decision needs
    (``inf`` turns them off, leaving the exact test).
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
        if lo > r + _SLACK or hi < -r - _SLACK:
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
    return _segment_hits_polygon(ax, ay, bx, by, verts, i, nverts[i], r)


@njit(cache=True, fastmath=False, error_model="numpy")
def _classify(i, n, seg, out, scratch, obs, extra, margin):
    """:func:`_polygon_hit` for ``n`` segments at once, convex polygon i, loops over segments
    innermost (they vectorise).

    ``seg = (ax, ay, bx, by)`` arrays (obstacle i's frame); writes ``out[e]``: 1 hit, 0 miss, -1
    undecided (the general test, :func:`_segment_hits_polygon`, decides). The same arithmetic
    as :func:`_polygon_hit`, so the same decisions.
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
        miss = sep[e] | (has & ((lo[e] > r + _SLACK) | (hi[e] < -r - _SLACK)))
        far = 0 if best[e] > hi_rej else -1
        apart = 1 if best[e] <= lo_acc else far
        out[e] = 0 if miss else (1 if g < -margin else (apart if g > margin else -1))


@njit(cache=True, fastmath=False, error_model="numpy")
def _prepare(is_circle, thresh, verts, nverts, bound, hull, nhull):
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
        if _point_in_polygon(cx, cy, verts, i, nv):
            d2 = np.inf
            for k in range(nv):
                kk = k + 1 if k + 1 < nv else 0
                d2 = min(
                    d2,
                    _point_segment_d2(
                        cx, cy, verts[i, k, 0], verts[i, k, 1], verts[i, kk, 0], verts[i, kk, 1]
                    ),
                )
            acc = (math.sqrt(d2) + thresh[i]) * (1.0 - _MARGIN) - _MARGIN
            if acc > 0.0:
                acc2[i] = acc * acc
        pos = False
        neg = False
        for k in range(nv):
            k0 = k - 1 if k > 0 else nv - 1
            k1 = k + 1 if k + 1 < nv else 0
            o = _orient(
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


@njit(cache=True, fastmath=False, error_model="numpy")
def _box_tables(nk):
    """Layout of sparse tables of the knot offsets' boxes, for box-of-a-knot-range queries.

    Returns ``(base, lg, filled)``: level ``L`` of obstacle ``i`` holds, for each knot ``p``,
    the box ``(xmin, ymin, xmax, ymax)`` of knots ``p .. p + 2^L - 1`` at row
    ``base[i] + L * nk[i] + p`` of a table of ``base[-1]`` rows, once :func:`_fill_boxes` has
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
def _fill_boxes(i, ko, nk, table, base, lg):
    """Fill obstacle i's sparse table (see :func:`_box_tables`)."""
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
def _stride(n):
    """Elements (8 bytes each) between the starts of scratch arrays of n elements: n rounded up
    to whole 4 KiB pages, plus 576 bytes (so that 64 of them start at 64 different offsets)."""
    return (n + 511) // 512 * 512 + 72


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _block_paths(X, c0, bn, start, goal, t0, speed, path, out_len, out_turn):
    """Lay the paths of candidates ``c0 .. c0 + bn - 1`` end to end, with their lengths (C1),
    times, velocities and turning (C3).

    Returns ``(sane, cmax, tmax)``: no coordinate is NaN or beyond ``_SANE``, the largest
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
        bad += 0 if (ax <= _SANE) & (ay <= _SANE) else 1  # (NaN too)
        cmax = ax if ax > cmax else cmax
        cmax = ay if ay > cmax else cmax
    sane = bad == 0
    # C1: polyline length (Eq. 19); C3: total turning (Eq. 21), zero-length segments skipped
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
        ang[v] = _abs_atan2(
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
def _static_pass(i, ox, oy, bn, npts, path, work, cls, obs, extra, a2, margin, hits, ncol):
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
    nnear = 0
    for p in range(bn * npts - 1):
        d = _point_segment_d2(cx, cy, px[p], py[p], px[p + 1], py[p + 1])
        hit = d <= a2
        close = d <= rho2 and not hit and real[p]
        hits[p] += 1 if hit else 0
        nnear += 1 if close else 0
        near[p] = close
    if nnear == 0:
        return
    nf = 0
    for p in range(bn * npts - 1):
        flagged[nf] = p
        nf += 1 if near[p] else 0
    if not extra[1][i]:  # not convex: one by one
        for f in range(nf):
            p = flagged[f]
            if _polygon_hit(
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
    _classify(i, nf, cls[0], verdict, cls[2], obs, extra, margin)
    for f in range(nf):
        v = verdict[f]
        if v == 1 or (
            v < 0
            and _segment_hits_polygon(
                sax[f], say[f], sbx[f], sby[f], verts, i, nverts[i], thresh[i]
            )
        ):
            ncol[cand[flagged[f]]] += 1


@njit(cache=True, fastmath=False, error_model="numpy")
def _moving_pass(i, t0, speed, bn, npts, sane, cmax, tmax, path, work, cls, obs, extra, a2,
                 margin, motion, pre, grid, ncol):  # fmt: skip
    """Hits of the block's segments on moving obstacle i (spacetime).

    The exact test walks the robot's segments and the obstacle's constant-velocity pieces
    together (both are ordered in time): on each common piece the robot's position relative to
    the obstacle moves along a straight segment, tested against the shape at offset zero. Past
    the table's last knot the last piece is extrapolated (callers size tables so that this does
    not happen). Filters in front of it only skip pieces whose outcome is certain.
    """
    px, py, tt, _, _, _, rvx, rvy = path[:8]
    near, flagged, real, cand, kpt, cxp, cyp, cep, qax, qay, qbx, qby, qd2, qseg, done = work
    is_circle, thresh, verts, nverts, bound, hull, nhull = obs
    kt, ko, kv, nk, k_start = motion
    vmax, omax, boxes, bbase, lg, boxed = pre
    gdt, ggap, grow, gfill, gwalk, gx, gy, ge, gk = grid
    gr = grow[i]  # this obstacle's row in the grid
    last = nk[i] - 2  # index of the last piece
    ks = k_start[i]
    bcx = bound[i, 4]
    bcy = bound[i, 5]
    rho = bound[i, 6]
    rho2 = rho * rho
    npt = bn * npts
    convex = extra[1][i] and not is_circle[i]  # (polygon tests all at once)
    # 1. the obstacle's centre at each path time: (cxp, cyp), within cep of the true one
    kw = ks  # the last knot at or before the block's latest time
    while kw < last and kt[i, kw + 1] <= tmax:
        kw += 1
    gi = 1.0 / gdt[i]
    gneed = int((tmax - t0) * gi) + 2 if tmax - t0 < (_GRID_CELLS - 2) * gdt[i] else -1
    on_grid = gneed > 0 and kw - ks > _COUNT
    if kw - ks <= _COUNT:
        # few knots: place the centre on each piece in turn where the piece has begun
        # (branch-free)
        tw = kt[i, ks]
        ox = bcx + ko[i, ks, 0]
        oy = bcy + ko[i, ks, 1]
        vx = kv[i, ks, 0]
        vy = kv[i, ks, 1]
        for p in range(npt):
            kpt[p] = ks  # (a hint; the exact tests walk on from it)
            cxp[p] = ox + vx * (tt[p] - tw)
            cyp[p] = oy + vy * (tt[p] - tw)
            cep[p] = 0.0
        for w in range(ks + 1, kw + 1):
            tw = kt[i, w]
            ox = bcx + ko[i, w, 0]
            oy = bcy + ko[i, w, 1]
            vx = kv[i, w, 0]
            vy = kv[i, w, 1]
            for p in range(npt):
                t = tt[p]
                on = tw <= t
                cxp[p] = ox + vx * (t - tw) if on else cxp[p]
                cyp[p] = oy + vy * (t - tw) if on else cyp[p]
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
        for p in range(npt):
            u = (tt[p] - t0) * gi
            g = int(u) if u > 0.0 else 0
            fr = u - g
            cxp[p] = gx[gr, g] + fr * (gx[gr, g + 1] - gx[gr, g])
            cyp[p] = gy[gr, g] + fr * (gy[gr, g + 1] - gy[gr, g])
            cep[p] = ge[gr, g]
            kpt[p] = gk[gr, g]  # the piece at the cell's start: at most one before (a hint)
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
    # 2. While the robot is on a segment, the centre moves at most vmax from where it was at
    # ta and where it will be at tb, so it stays within sqrt(a^2 - d^2) (a = vmax (tb - ta) / 2,
    # d half the distance between the two) of the point that moves uniformly between them; the
    # robot, relative to that point, moves along a segment. Branch-free.
    vm = vmax[i]
    # room for rounding (pixels): relative to the coordinates and times involved
    room = (
        _MARGIN * (1.0 + 4.0 * cmax + 4.0 * omax[i]) + 1e-9 * tmax * (2.0 * speed + vm)
        if sane
        else np.inf
    )
    nnear = 0
    for p in range(npt - 1):
        dcx = cxp[p + 1] - cxp[p]
        dcy = cyp[p + 1] - cyp[p]
        ha = 0.5 * vm * (tt[p + 1] - tt[p])
        ea = cep[p]
        eb = cep[p + 1]
        e = 0.5 * (ea + eb)  # the true half distance is at least d - e
        dev = math.sqrt(
            max(ha * ha - 0.25 * (dcx * dcx + dcy * dcy) + 2.0 * e * (ha + e), 0.0)
        ) + max(ea, eb)
        reach = (rho + dev) * (1.0 + _MARGIN) + room
        d = _point_segment_d2(
            0.0, 0.0, px[p] - cxp[p], py[p] - cyp[p], px[p + 1] - cxp[p + 1],
            py[p + 1] - cyp[p + 1],
        )  # fmt: skip
        close = d <= reach * reach and real[p]
        nnear += 1 if close else 0
        near[p] = close
    if nnear == 0:
        return
    nf = 0
    for p in range(npt - 1):
        flagged[nf] = p
        nf += 1 if near[p] else 0
    # 3. Exact tests, piece by piece, for the segments that come within reach: their relative
    # segments on each piece (exactly as the walk computes them) go to a list, then their
    # distances to the bounding-circle centre are found in one pass, then the exact tests run
    # for those within it, each segment counted once.
    cap = qax.shape[0]
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
            if kb - k > _PIECES:
                # many pieces: first the box of the offsets over them
                if not boxed[i]:
                    _fill_boxes(i, ko, nk, boxes, bbase, lg)
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
                r_ = rho * (1.0 + _MARGIN) + room
                ex = bx - ax
                ey = by - ay
                reach = (rho + math.sqrt(hx * hx + hy * hy)) * (1.0 + _MARGIN) + room
                if (
                    max(ax, bx) < mx - hx - r_
                    or min(ax, bx) > mx + hx + r_
                    or max(ay, by) < my - hy - r_
                    or min(ay, by) > my + hy + r_
                    or abs(ex * (my - ay) - ey * (mx - ax))
                    > r_ * math.sqrt(ex * ex + ey * ey) + hx * abs(ey) + hy * abs(ex)
                    or _point_segment_d2(mx, my, ax, ay, bx, by) > reach * reach
                ):
                    f += 1
                    continue
            if ne + kb - k < cap:
                done[p] = False
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
                d = _point_segment_d2(bcx, bcy, pax, pay, pbx, pby)
                if d <= rho2 and (
                    d <= a2
                    or (
                        not is_circle[i]
                        and _polygon_hit(
                            pax, pay, pbx, pby, i, thresh, verts, nverts, hull, nhull, extra,
                            margin,
                        )
                    )
                ):  # fmt: skip
                    ncol[cand[p]] += 1
                    break
            f += 1
        for e in range(ne):
            qd2[e] = _point_segment_d2(bcx, bcy, qax[e], qay[e], qbx[e], qby[e])
        if convex:
            # the polygon tests of the entries within the bounding circle, all at once
            sax, say, sbx, sby = cls[0]
            verdict = cls[1]
            sidx = cls[3]
            vmap = cls[4]
            nt = 0
            for e in range(ne):
                d = qd2[e]
                sax[nt] = qax[e]
                say[nt] = qay[e]
                sbx[nt] = qbx[e]
                sby[nt] = qby[e]
                sidx[nt] = e
                vmap[e] = 2  # (not tested)
                nt += 1 if (d <= rho2) & (d > a2) else 0
            _classify(i, nt, cls[0], verdict, cls[2], obs, extra, margin)
            for t in range(nt):
                vmap[sidx[t]] = verdict[t]
        for e in range(ne):
            d = qd2[e]
            if d <= rho2:
                p = qseg[e]
                if done[p]:
                    continue
                if convex and d > a2:
                    v = vmap[e]
                    hit = v == 1 or (
                        v < 0
                        and _segment_hits_polygon(
                            qax[e], qay[e], qbx[e], qby[e], verts, i, nverts[i], thresh[i]
                        )
                    )
                else:
                    hit = d <= a2 or (
                        not is_circle[i]
                        and _polygon_hit(
                            qax[e], qay[e], qbx[e], qby[e], i, thresh, verts, nverts, hull,
                            nhull, extra, margin,
                        )
                    )  # fmt: skip
                if hit:
                    ncol[cand[p]] += 1
                    done[p] = True
        if f >= nf:
            return


@njit(cache=True, fastmath=False, error_model="numpy")
def _layout(n, npts, nk, spacetime):
    """Scratch layout for a call: ``(nb, size, cap, fs, fc, gs, nmov, rows, total)``."""
    nb = max(min(_BLOCK, n), 1)  # candidates per block
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
    fs = _stride(size)
    fc = _stride(cap)
    gs = _stride(nmov * _GRID_CELLS)
    return nb, size, cap, fs, fc, gs, nmov, rows, 18 * fs + 20 * fc + 4 * gs + 4 * rows


@njit(cache=True, fastmath=False, error_model="numpy")
def scratch_size(n, npts, nk, spacetime):
    """Floats of scratch space :func:`population_cost` needs for ``n`` candidates of ``npts``
    path points (pass it a buffer at least this long to spare it allocating one)."""
    return _layout(n, npts, nk, spacetime)[8]


@njit(cache=True, fastmath=False, error_model="numpy")
def population_cost(
    X, start, goal, t0, speed, spacetime, obs, snap_off, motion, weights, out, scratch
):
    """Cost of every candidate path; writes the arrays of ``out`` in place.

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
        :class:`mawdo.planning.geometry.FlatObstacles`.
    snap_off : float64[:, :], shape (n_obs, 2)
        Obstacle offsets at ``t0`` (pixels), used in snapshot mode.
    motion : tuple
        ``(times, offsets, velocity, nknots, k_start)``: the knot table of
        :class:`mawdo.planning.geometry.MotionTable` (starting at or before ``t0``) and per
        obstacle the piece that contains ``t0``. Used in spacetime mode.
    weights : tuple of float
        ``(alpha, beta, lam, k)`` of Eqs. 17 and 20.
    out : tuple of arrays, each shape (n,)
        ``(cost, length, n_collisions, turning)``: C (Eq. 17), C1 in pixels (Eq. 19), the
        number of hitting (segment, obstacle) pairs (int64, Eq. 20), C3 in radians (Eq. 21).
    scratch : float64[:]
        Work space, kept by the caller from call to call: :func:`scratch_size` floats or more
        (a shorter one makes the kernel allocate its own).
    """
    is_circle, thresh, verts, nverts, bound, hull, nhull = obs
    kt, ko, kv, nk, k_start = motion
    alpha, beta, lam, k_coll = weights
    out_cost, out_len, out_ncol, out_turn = out
    n = X.shape[0]
    npts = X.shape[1] // 2 + 2
    nseg = npts - 1
    n_obs = nk.shape[0]
    extra = _prepare(is_circle, thresh, verts, nverts, bound, hull, nhull)
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
            for k in range(nk[i] - 1):
                vmax[i] = max(vmax[i], math.sqrt(kv[i, k, 0] ** 2 + kv[i, k, 1] ** 2))
            vmax[i] = vmax[i] * (1.0 + _MARGIN) + _MARGIN
            extent = 0.0
            for k in range(nk[i]):
                extent = max(extent, max(abs(ko[i, k, 0]), abs(ko[i, k, 1])))
            omax[i] += extent
    bbase, lg, boxed = _box_tables(nk if spacetime else nk[:0])
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
            gdt[i] = max(2.0 / vmax[i], span / (_GRID_CELLS - 2))
            ggap[i] = 0.5 * vmax[i] * gdt[i]
            grow[i] = nmov
            nmov += 1
    # Candidates are processed in blocks of _BLOCK, their paths laid end to end (point p of the
    # block is point p % npts of candidate p // npts; "segment" p joins points p and p + 1 and
    # is a real segment unless p % npts == nseg), so that the loops over segments are long
    # enough to vectorise.
    nb, size, cap, fs, fc, gs, nmov, nrow, total = _layout(n, npts, nk, spacetime)
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
    ng = nmov * _GRID_CELLS
    grid = (
        gdt,
        ggap,
        grow,
        np.zeros(n_obs, dtype=np.int64),  # cells filled
        k_start.copy(),  # piece at the last filled cell
        buf[o : o + ng].reshape((nmov, _GRID_CELLS)),
        buf[o + gs : o + gs + ng].reshape((nmov, _GRID_CELLS)),
        buf[o + 2 * gs : o + 2 * gs + ng].reshape((nmov, _GRID_CELLS)),
        buf[o + 3 * gs : o + 3 * gs + ng].view(np.int64).reshape((nmov, _GRID_CELLS)),
    )
    o += 4 * gs
    nbox = 4 * nrow
    pre = (vmax, omax, buf[o : o + nbox].reshape((nrow, 4)), bbase, lg, boxed)
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
    cls = (  # for _classify: segments, verdicts, scratch; entries and their verdicts
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
    ncol = np.empty(nb, dtype=np.int64)  # and by the exact tests, per candidate
    for c0 in range(0, n, nb):
        bn = min(nb, n - c0)
        sane, cmax, tmax = _block_paths(X, c0, bn, start, goal, t0, speed, path, out_len, out_turn)
        margin = _MARGIN if sane else np.inf
        hits[:] = 0
        ncol[:] = 0
        # n_collision (Eq. 20): (segment, obstacle) pairs that hit
        for i in range(n_obs):
            a2 = acc2[i] if sane or is_circle[i] else -1.0
            if moving[i]:
                _moving_pass(
                    i, t0, speed, bn, npts, sane, cmax, tmax, path, work, cls, obs, extra, a2,
                    margin, motion, pre, grid, ncol,
                )  # fmt: skip
            else:
                ox = ko[i, 0, 0] if spacetime else snap_off[i, 0]
                oy = ko[i, 0, 1] if spacetime else snap_off[i, 1]
                _static_pass(
                    i, ox, oy, bn, npts, path, work, cls, obs, extra, a2, margin, hits, ncol
                )
        for b in range(bn):
            nc = ncol[b]
            for p in range(b * npts, b * npts + nseg):
                nc += hits[p]
            c = c0 + b
            out_ncol[c] = nc
            x = float(nc)
            out_cost[c] = alpha * out_len[c] + beta * k_coll * x * x * x * x + lam * out_turn[c]
