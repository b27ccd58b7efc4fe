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
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["ZERO_LENGTH", "population_cost"]

#: Segments shorter than this (pixels) have no direction and contribute no turning.
ZERO_LENGTH = 1e-9
# Separating-axis rejections only fire with this much room to spare (pixels), so that rounding
# can never reject a true hit; anything closer goes to the exact test.
_SLACK = 1e-9


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


@njit(cache=True, fastmath=False, error_model="numpy")
def _polygon_hit(ax, ay, bx, by, i, thresh, verts, nverts, hull, nhull):
    """Segment ab (in obstacle i's frame) is within ``thresh[i]`` of polygon i."""
    r = thresh[i]
    # Separating axes first (exact rejections, cheap): an axis along which the segment lies
    # more than r beyond the polygon proves the distance exceeds r. Convex-hull edge normals
    # (hull[i, k] = (nx, ny, h) with h = n.c + r) ...
    for k in range(nhull[i]):
        nx = hull[i, k, 0]
        ny = hull[i, k, 1]
        h = hull[i, k, 2]
        if nx * ax + ny * ay > h and nx * bx + ny * by > h:
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
    return _segment_hits_polygon(ax, ay, bx, by, verts, i, nverts[i], r)


@njit(cache=True, fastmath=False, error_model="numpy")
def population_cost(X, start, goal, t0, speed, spacetime, obs, snap_off, motion, weights, out):
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
    """
    is_circle, thresh, verts, nverts, bound, hull, nhull = obs
    kt, ko, kv, nk, k_start = motion
    alpha, beta, lam, k_coll = weights
    out_cost, out_len, out_ncol, out_turn = out
    n = X.shape[0]
    m = X.shape[1] // 2
    npts = m + 2
    nseg = npts - 1
    n_obs = nk.shape[0]
    px = np.empty(npts)
    py = np.empty(npts)
    cum = np.empty(npts)
    d2 = np.empty(nseg)
    tt = np.empty(npts)  # time the robot reaches each path point (time steps)
    rvx = np.empty(nseg)  # robot velocity on each segment (pixels per time step)
    rvy = np.empty(nseg)
    inv_speed = 1.0 / speed
    for c in range(n):
        px[0] = start[0]
        py[0] = start[1]
        for j in range(m):
            px[j + 1] = X[c, 2 * j]
            py[j + 1] = X[c, 2 * j + 1]
        px[npts - 1] = goal[0]
        py[npts - 1] = goal[1]

        # C1: polyline length (Eq. 19); C3: total turning (Eq. 21), zero-length segments skipped
        cum[0] = 0.0
        tt[0] = t0
        turn = 0.0
        have_prev = False
        pdx = 0.0
        pdy = 0.0
        for j in range(nseg):
            dx = px[j + 1] - px[j]
            dy = py[j + 1] - py[j]
            seg = math.sqrt(dx * dx + dy * dy)
            cum[j + 1] = cum[j] + seg
            tt[j + 1] = t0 + cum[j + 1] * inv_speed
            rvx[j] = dx * speed / seg if seg > 0.0 else 0.0
            rvy[j] = dy * speed / seg if seg > 0.0 else 0.0
            if seg <= ZERO_LENGTH:
                continue
            if have_prev:
                # |theta_i - pi| equals the angle between consecutive directions
                turn += abs(math.atan2(pdx * dy - pdy * dx, pdx * dx + pdy * dy))
            pdx = dx
            pdy = dy
            have_prev = True

        # n_collision (Eq. 20): (segment, obstacle) pairs that hit
        ncol = 0
        for i in range(n_obs):
            rho2 = bound[i, 6] * bound[i, 6]
            if not spacetime or nk[i] == 1:
                ox = ko[i, 0, 0] if spacetime else snap_off[i, 0]
                oy = ko[i, 0, 1] if spacetime else snap_off[i, 1]
                cx = bound[i, 4] + ox
                cy = bound[i, 5] + oy
                # bounding-circle distances in one branch-free pass, exact tests for the few
                # segments that come close (for a circle obstacle that test is already exact)
                for j in range(nseg):
                    d2[j] = _point_segment_d2(cx, cy, px[j], py[j], px[j + 1], py[j + 1])
                for j in range(nseg):
                    if d2[j] <= rho2:
                        if is_circle[i] or _polygon_hit(
                            px[j] - ox, py[j] - oy, px[j + 1] - ox, py[j + 1] - oy, i, thresh,
                            verts, nverts, hull, nhull,
                        ):  # fmt: skip
                            ncol += 1
                continue
            # Moving obstacle: walk the robot's segments and the obstacle's constant-velocity
            # pieces together (both are ordered in time). On each common piece the robot's
            # position relative to the obstacle moves along a straight segment, tested against
            # the shape at offset zero. Past the table's last knot the last piece is
            # extrapolated (callers size tables so that this does not happen).
            k = k_start[i]
            last = nk[i] - 2  # index of the last piece
            for j in range(nseg):
                ax = px[j]
                ay = py[j]
                ta = tt[j]
                tb = tt[j + 1]
                while k < last and kt[i, k + 1] <= ta:
                    k += 1
                kk = k
                while True:
                    k0 = kt[i, kk]
                    k1 = kt[i, kk + 1] if kk < last else np.inf
                    sa = max(ta, k0)
                    sb = min(tb, k1)
                    qax = ax + rvx[j] * (sa - ta) - (ko[i, kk, 0] + kv[i, kk, 0] * (sa - k0))
                    qay = ay + rvy[j] * (sa - ta) - (ko[i, kk, 1] + kv[i, kk, 1] * (sa - k0))
                    qbx = ax + rvx[j] * (sb - ta) - (ko[i, kk, 0] + kv[i, kk, 0] * (sb - k0))
                    qby = ay + rvy[j] * (sb - ta) - (ko[i, kk, 1] + kv[i, kk, 1] * (sb - k0))
                    if _point_segment_d2(bound[i, 4], bound[i, 5], qax, qay, qbx, qby) <= rho2:
                        if is_circle[i] or _polygon_hit(
                            qax, qay, qbx, qby, i, thresh, verts, nverts, hull, nhull
                        ):
                            ncol += 1
                            break
                    if kk >= last or not k1 < tb:  # (a NaN time must end the walk too)
                        break
                    kk += 1
        out_len[c] = cum[npts - 1]
        out_turn[c] = turn
        out_ncol[c] = ncol
        nc = float(ncol)
        out_cost[c] = alpha * cum[npts - 1] + beta * k_coll * nc * nc * nc * nc + lam * turn
