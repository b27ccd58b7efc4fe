"""Compiled departure-time geometry of the safe-interval guide: which departures collide.

A straight move from ``u`` with velocity ``e`` (pixels per time step) for ``T`` time steps,
departing at ``tau``, is at ``u + s e`` at time ``t = tau + s`` (``0 <= s <= T``). On one
constant-velocity piece of an obstacle's motion (times ``[ta, tb]``, offset ``o + w (t - ta)``)
the robot's position in the obstacle's frame is the affine map
``q(s, t) = d0 + s e - t w`` with ``d0 = u - o + w ta``. So the pairs ``(s, t)`` at which the
robot is within the hit distance of the shape are the preimage of the inflated shape, cut to
the rectangle ``[0, T] x [ta, tb]``; the departures that collide are that set's image under
``tau = t - s``. The inflated shape is a union of convex parts (a disc for a circle; for a
polygon, per edge a rectangle of half-width ``thr`` and per vertex a disc of radius ``thr``,
plus the polygon itself), so each part gives one closed interval of departures:

* disc: the preimage is an ellipse (a strip when ``e`` and ``w`` are parallel); the extremes of
  ``t - s`` over ellipse and rectangle are among the rectangle's corners inside it, the
  crossings of the rectangle's edges with the ellipse (a quadratic each) and the ellipse's own
  extremes (where its tangent is parallel to ``t - s = const``) when they lie in the rectangle;
* half-planes (edge rectangles): the rectangle is clipped by each transformed half-plane
  (Sutherland-Hodgman) and ``t - s`` is read at the clipped polygon's vertices;
* the polygon's interior: a departure not within ``thr`` of any edge moves the robot along a
  relative segment that never meets the boundary, so it is wholly inside or outside; one
  point-in-polygon test per gap between the other intervals decides the whole gap.

All of it is exact in real arithmetic (no time sampling); a waiting robot is the case ``e = 0``
and a point in time the case ``T = 0``. Random walkers seen as reachable sets (a shape growing
at ``vmax`` from where it was at ``t_base``) forbid every departure from a time on:
:func:`cone_start` gives it in closed form.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.refine.kernel.primitives import point_in_polygon

__all__ = ["clip_range", "cone_start", "disc_missed", "disc_range"]

_INF = math.inf


@njit(cache=True, inline="always")
def _update(lo, hi, f):
    return min(lo, f), max(hi, f)


@njit(cache=True)
def disc_range(dx, dy, ex, ey, wx, wy, T, ta, tb, rho):
    """Departures ``t - s`` at which ``|d + s e - t w| <= rho`` for ``(s, t)`` in
    ``[0, T] x [ta, tb]``: ``(lo, hi)`` (time steps), ``(inf, -inf)`` when none."""
    lo, hi = _INF, -_INF
    r2 = rho * rho
    cs = (0.0, T, T, 0.0)
    ct = (ta, ta, tb, tb)
    for k in range(4):
        s0, t0 = cs[k], ct[k]
        s1, t1 = cs[(k + 1) % 4], ct[(k + 1) % 4]
        qx = dx + s0 * ex - t0 * wx
        qy = dy + s0 * ey - t0 * wy
        c = qx * qx + qy * qy - r2
        if c <= 0.0:
            lo, hi = _update(lo, hi, t0 - s0)
        ux = (s1 - s0) * ex - (t1 - t0) * wx
        uy = (s1 - s0) * ey - (t1 - t0) * wy
        a = ux * ux + uy * uy
        if a > 0.0:
            b = 2.0 * (qx * ux + qy * uy)
            disc = b * b - 4.0 * a * c
            if disc >= 0.0:
                sq = math.sqrt(disc)
                for lam in ((-b - sq) / (2.0 * a), (-b + sq) / (2.0 * a)):
                    if 0.0 <= lam <= 1.0:
                        lo, hi = _update(lo, hi, (t0 + lam * (t1 - t0)) - (s0 + lam * (s1 - s0)))
    # the ellipse's own extremes of t - s (M = [e, -w] must be invertible)
    det = wx * ey - ex * wy
    scale = (abs(ex) + abs(ey)) * (abs(wx) + abs(wy))
    if abs(det) > 1e-12 * scale and rho > 0.0:
        hx = (wy - ey) / det
        hy = (ex - wx) / det
        hn = math.hypot(hx, hy)
        tol = 1e-12 * (1.0 + abs(T) + abs(tb))
        for sign in (-1.0, 1.0):
            yx = sign * rho * hx / hn - dx
            yy = sign * rho * hy / hn - dy
            s = (-wy * yx + wx * yy) / det
            t = (-ey * yx + ex * yy) / det
            if -tol <= s <= T + tol and ta - tol <= t <= tb + tol:
                lo, hi = _update(lo, hi, t - s)
    return lo, hi


@njit(cache=True, inline="always")
def disc_missed(dx, dy, ex, ey, wx, wy, T, lo, hi, rho):
    """True when no departure ``tau`` in ``[lo, hi]`` (finite) brings the move within ``rho``
    of the disc's centre: ``|d + s (e - w) - tau w| > rho`` for every ``s`` in ``[0, T]`` (the
    robot's position relative to the centre, ``q = d + s e - t w`` at ``t = tau + s``, as in
    :func:`disc_range`; the piece's own time span is not looked at, so a move this calls
    missed meets the disc at no time at all). False when it cannot tell.

    In the frame moving with the disc the robot runs along the direction ``m = e - w``, one
    line per departure, these lines shifted by ``-tau w``: the test is that every such line
    passes farther than ``rho`` from the centre (the cross-track offsets over ``[lo, hi]``), or
    that along the track the part driven (``0 <= s <= T``) stays beyond ``rho`` on one side.
    Squares and no root: the comparisons are of sums of products, so the rounding is orders of
    magnitude below any margin a caller adds to ``rho``."""
    mx, my = ex - wx, ey - wy
    mm = mx * mx + my * my
    if not (mm > 1e-12 and lo > -math.inf and hi < math.inf):
        return False
    r2 = rho * rho * mm
    # cross-track: |q x m| / |m| over tau in [lo, hi] (linear in tau, s drops out)
    c0 = (dx - lo * wx) * my - (dy - lo * wy) * mx
    c1 = (dx - hi * wx) * my - (dy - hi * wy) * mx
    if c0 * c1 > 0.0 and min(c0 * c0, c1 * c1) > r2:
        return True
    # along the track: q . m over s in [0, T], tau in [lo, hi] (bilinear: its corners bound it)
    a0 = dx * mx + dy * my
    wm = wx * mx + wy * my
    a_lo = a0 + min(0.0, T * mm) - max(lo * wm, hi * wm)
    a_hi = a0 + max(0.0, T * mm) - min(lo * wm, hi * wm)
    return (a_lo > 0.0 and a_lo * a_lo > r2) or (a_hi < 0.0 and a_hi * a_hi > r2)


@njit(cache=True)
def clip_range(d0x, d0y, ex, ey, wx, wy, T, ta, tb, planes):
    """Departures ``t - s`` at which ``q = d0 + s e - t w`` satisfies every half-plane
    ``nx qx + ny qy <= h`` (rows of ``planes``) for ``(s, t)`` in ``[0, T] x [ta, tb]``.

    Returns ``(lo, hi)`` (time steps), ``(inf, -inf)`` when the clipped region is empty.
    """
    cap = 4 + 2 * planes.shape[0]
    xs = np.empty(cap)
    ys = np.empty(cap)
    nx_ = np.empty(cap)
    ny_ = np.empty(cap)
    # element by element: a slice assignment makes every process compile Numba's shape-error
    # message (string formatting, about 4 s of CPU for all the kernels' slice assignments)
    xs[0], xs[1], xs[2], xs[3] = 0.0, T, T, 0.0
    ys[0], ys[1], ys[2], ys[3] = ta, ta, tb, tb
    n = 4
    for k in range(planes.shape[0]):
        nx, ny, h = planes[k, 0], planes[k, 1], planes[k, 2]
        a = nx * ex + ny * ey  # a s + b t <= c in (s, t)
        b = -(nx * wx + ny * wy)
        c = h - (nx * d0x + ny * d0y)
        m = 0
        for i in range(n):
            j = (i + 1) % n
            fi = a * xs[i] + b * ys[i] - c
            fj = a * xs[j] + b * ys[j] - c
            if fi <= 0.0:
                nx_[m] = xs[i]
                ny_[m] = ys[i]
                m += 1
            if (fi < 0.0 < fj) or (fj < 0.0 < fi):
                lam = fi / (fi - fj)
                nx_[m] = xs[i] + lam * (xs[j] - xs[i])
                ny_[m] = ys[i] + lam * (ys[j] - ys[i])
                m += 1
        n = m
        if n == 0:
            return _INF, -_INF
        for i in range(n):
            xs[i] = nx_[i]
            ys[i] = ny_[i]
    lo, hi = _INF, -_INF
    for i in range(n):
        lo, hi = _update(lo, hi, ys[i] - xs[i])
    return lo, hi


@njit(cache=True)
def _point_min(px, py, ex, ey, T, vmax):
    """Min over ``s`` in ``[0, T]`` of ``|p + s e| / vmax - s`` (convex in ``s``)."""
    best = min(math.hypot(px, py) / vmax, math.hypot(px + T * ex, py + T * ey) / vmax - T)
    sp = math.hypot(ex, ey)
    if sp > vmax and T > 0.0:
        # stationary where the component along e is kappa / sqrt(1 - kappa^2) |perpendicular|
        kappa = vmax / sp
        along = (px * ex + py * ey) / sp
        perp = abs(px * ey - py * ex) / sp
        s = (kappa * perp / math.sqrt(1.0 - kappa * kappa) - along) / sp
        if 0.0 < s < T:
            best = min(best, math.hypot(px + s * ex, py + s * ey) / vmax - s)
    return best


@njit(cache=True)
def _edge_min(px, py, ex, ey, T, vmax, ax, ay, bx, by):
    """Min over ``s`` of ``dist(p + s e, edge ab) / vmax - s``: ends and the edge's interior."""
    best = min(
        _point_min(px - ax, py - ay, ex, ey, T, vmax), _point_min(px - bx, py - by, ex, ey, T, vmax)
    )
    fx, fy = bx - ax, by - ay
    length = math.hypot(fx, fy)
    if length == 0.0:
        return best
    ux, uy = fx / length, fy / length
    # projection onto the edge: lam(s) = l0 + l1 s must lie in [0, length]
    l0 = (px - ax) * ux + (py - ay) * uy
    l1 = ex * ux + ey * uy
    s_lo, s_hi = 0.0, T
    if l1 != 0.0:
        s_a, s_b = -l0 / l1, (length - l0) / l1
        s_lo, s_hi = max(s_lo, min(s_a, s_b)), min(s_hi, max(s_a, s_b))
    elif not 0.0 <= l0 <= length:
        return best
    if s_lo > s_hi:
        return best
    # distance to the line: |h0 + h1 s|, linear pieces; the min of |.|/vmax - s is at an end or
    # where it crosses zero
    h0 = (px - ax) * -uy + (py - ay) * ux
    h1 = ex * -uy + ey * ux
    for s in (s_lo, s_hi, -h0 / h1 if h1 != 0.0 else s_lo):
        if s_lo <= s <= s_hi:
            best = min(best, abs(h0 + h1 * s) / vmax - s)
    return best


@njit(cache=True)
def cone_start(ux, uy, ex, ey, T, circle, cx, cy, thr, verts, i, nv, ox, oy, vmax, t_base):
    """First departure (time steps) at which the move meets a reachable set.

    The set is the shape translated by ``(ox, oy)``, grown by ``thr`` and by ``vmax (t -
    t_base)`` after ``t_base``: the move departing at ``tau`` meets it iff ``tau >= t_base +
    min_s (dist(u + s e, shape) - thr) / vmax - s``. Exact per part (the circle, or each polygon
    edge and the polygon's inside at the move's end). ``verts[i, :nv]`` is the polygon.
    """
    px, py = ux - ox, uy - oy
    if circle:
        best = _point_min(px - cx, py - cy, ex, ey, T, vmax)
        return t_base + best - thr / vmax
    best = _INF
    for k in range(nv):
        kk = k + 1 if k + 1 < nv else 0
        best = min(
            best,
            _edge_min(
                px,
                py,
                ex,
                ey,
                T,
                vmax,
                verts[i, k, 0],
                verts[i, k, 1],
                verts[i, kk, 0],
                verts[i, kk, 1],
            ),
        )
    if point_in_polygon(px + T * ex, py + T * ey, verts, i, nv):
        best = min(best, -T)
    return t_base + best - thr / vmax
