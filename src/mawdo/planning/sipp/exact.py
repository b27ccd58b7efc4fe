"""Exact yes/no tests of the safe-interval guide's re-check: point, segment and polygon.

The guide's own small set, so that it depends on no private part of the cost kernel: the
re-check of a timed move (:func:`mawdo.planning.sipp.intervals.segment_free`) and the interior
test of the departure geometry use these. Touching counts as a hit (distances compared with
``<=``), as in the cost kernel and the checker.
"""

from __future__ import annotations

from numba import njit

__all__ = ["point_in_polygon", "point_segment_d2", "segment_hits_polygon"]


@njit(cache=True)
def point_segment_d2(px, py, ax, ay, bx, by):
    """Squared distance (px^2) from point ``p`` to segment ``ab`` (a point when ``a == b``)."""
    fx, fy = bx - ax, by - ay
    gx, gy = px - ax, py - ay
    dot = gx * fx + gy * fy
    if dot <= 0.0:  # before a (or a zero-length segment)
        return gx * gx + gy * gy
    len2 = fx * fx + fy * fy
    if dot >= len2:  # beyond b
        hx, hy = px - bx, py - by
        return hx * hx + hy * hy
    cross = gx * fy - gy * fx
    return cross * cross / len2


@njit(cache=True)
def _orient(ax, ay, bx, by, cx, cy):
    """Sign of the turn ``a -> b -> c``: 1 left, -1 right, 0 collinear."""
    v = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    return 1 if v > 0.0 else (-1 if v < 0.0 else 0)


@njit(cache=True)
def _cross_or_touch(ax, ay, bx, by, cx, cy, dx, dy):
    """Segments ``ab`` and ``cd`` share a point (proper crossing or contact)."""
    o1 = _orient(ax, ay, bx, by, cx, cy)
    o2 = _orient(ax, ay, bx, by, dx, dy)
    o3 = _orient(cx, cy, dx, dy, ax, ay)
    o4 = _orient(cx, cy, dx, dy, bx, by)
    if o1 * o2 < 0 and o3 * o4 < 0:
        return True
    # contacts: an end on the other segment (collinear overlap included)
    return (
        (o1 == 0 and point_segment_d2(cx, cy, ax, ay, bx, by) == 0.0)
        or (o2 == 0 and point_segment_d2(dx, dy, ax, ay, bx, by) == 0.0)
        or (o3 == 0 and point_segment_d2(ax, ay, cx, cy, dx, dy) == 0.0)
        or (o4 == 0 and point_segment_d2(bx, by, cx, cy, dx, dy) == 0.0)
    )


@njit(cache=True)
def point_in_polygon(px, py, verts, i, nv):
    """``p`` lies inside polygon ``verts[i, :nv]`` by its winding number (nonzero rule; a simple
    polygon, so the same as even-odd). The boundary itself is left to the distance tests."""
    wind = 0
    for k in range(nv):
        kk = k + 1 if k + 1 < nv else 0
        ax, ay = verts[i, k, 0], verts[i, k, 1]
        bx, by = verts[i, kk, 0], verts[i, kk, 1]
        if ay <= py < by and _orient(ax, ay, bx, by, px, py) > 0:
            wind += 1  # an upward edge with p on its left
        elif by <= py < ay and _orient(ax, ay, bx, by, px, py) < 0:
            wind -= 1  # a downward edge with p on its right
    return wind != 0


@njit(cache=True)
def segment_hits_polygon(ax, ay, bx, by, verts, i, nv, r):
    """The segment ``ab`` comes within ``r`` px (``<= r``) of polygon ``verts[i, :nv]``, its
    boundary or its inside."""
    r2 = r * r
    for k in range(nv):
        kk = k + 1 if k + 1 < nv else 0
        cx, cy = verts[i, k, 0], verts[i, k, 1]
        dx, dy = verts[i, kk, 0], verts[i, kk, 1]
        if _cross_or_touch(ax, ay, bx, by, cx, cy, dx, dy):
            return True
        # two disjoint segments are closest at an end of one of them
        if (
            min(
                point_segment_d2(ax, ay, cx, cy, dx, dy),
                point_segment_d2(bx, by, cx, cy, dx, dy),
                point_segment_d2(cx, cy, ax, ay, bx, by),
            )
            <= r2
        ):
            return True  # the edge's end d is the next edge's c
    # no edge within reach: the segment lies wholly inside or wholly outside
    return point_in_polygon(ax, ay, verts, i, nv)
