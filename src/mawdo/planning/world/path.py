"""Polyline helpers for the planner and the metrics: arc length, advancing, re-spreading, turning.

Pure NumPy on ``(k, 2)`` point arrays (pixels); independent of the Numba cost kernel so the
metrics of an executed path are not computed by the code that produced it.
"""

from __future__ import annotations

import functools

import numpy as np


def segment_lengths(points: np.ndarray) -> np.ndarray:
    """Lengths of the ``k - 1`` segments of a polyline ``(k, 2)`` (pixels)."""
    p = np.asarray(points)
    d = p[1:] - p[:-1]  # np.diff's own arithmetic, without its wrapper
    return np.hypot(d[:, 0], d[:, 1])


def polyline_length(points: np.ndarray) -> float:
    """Total length (pixels)."""
    return float(segment_lengths(points).sum())


def turning_angles(points: np.ndarray, eps: float = 1e-9) -> np.ndarray:
    """Turning angle at each interior vertex, ``|theta_i - pi|`` of Eq. 28 (radians, [0, pi]).

    Zero-length segments (shorter than ``eps`` pixels) are dropped first: a robot standing still
    does not turn.
    """
    seg = np.diff(points, axis=0)
    seg = seg[np.hypot(*seg.T) > eps]
    if len(seg) < 2:
        return np.zeros(0)
    a, b = seg[:-1], seg[1:]
    cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    dot = (a * b).sum(axis=1)
    return np.abs(np.arctan2(cross, dot))


def advance(points: np.ndarray, distance: float):
    """Move ``distance`` pixels along a polyline from its first point.

    Returns
    -------
    position : numpy.ndarray, shape (2,)
        Where the robot ends (the last point if the polyline is shorter than ``distance``).
    remainder : numpy.ndarray, shape (j, 2)
        The rest of the polyline, starting at ``position``.
    passed : numpy.ndarray, shape (q, 2)
        Vertices passed on the way (strictly after the start, before ``position``).
    fractions : numpy.ndarray, shape (q,)
        Where each passed vertex lies, as a fraction of ``distance`` (for time stamps).
    """
    if distance <= 0:  # standing still passes no vertex (and has no fraction to speak of)
        return points[0].copy(), points.copy(), np.zeros((0, 2)), np.zeros(0)
    # (called several times per replan on short polylines: numpy's methods, not its
    # function wrappers; the same sums and products)
    seg = segment_lengths(points)
    cum = np.zeros(len(points))
    seg.cumsum(out=cum[1:])
    if distance >= cum[-1]:
        inner = slice(1, len(points) - 1)
        frac = cum[inner] / distance if distance > 0 else np.zeros(len(points) - 2)
        return points[-1].copy(), points[-1:].copy(), points[inner].copy(), frac
    j = int(cum.searchsorted(distance, side="right")) - 1  # segment j holds the point
    frac = (distance - cum[j]) / seg[j] if seg[j] > 0 else 0.0
    pos = points[j] + frac * (points[j + 1] - points[j])
    inner = slice(1, j + 1)
    rest = np.concatenate((pos[None], points[j + 1 :]))
    return pos, rest, points[inner].copy(), cum[inner] / distance


def respread(points: np.ndarray, m: int) -> np.ndarray:
    """``m`` interior waypoints at equal arc length along a polyline (its ends excluded).

    Returns an array ``(m, 2)``; a degenerate polyline gives ``m`` copies of its point.
    """
    seg = segment_lengths(points)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    if cum[-1] <= 0:
        return np.repeat(points[:1], m, axis=0)
    s = cum[-1] * np.arange(1, m + 1) / (m + 1)
    return np.column_stack([np.interp(s, cum, points[:, k]) for k in range(2)])


def densify(points: np.ndarray, m: int) -> np.ndarray:
    """``m`` interior waypoints for a polyline, keeping its geometry exactly.

    The polyline's own interior vertices are kept (at most ``m`` of them: the last ones); the
    count is made up by splitting the longest segment at its midpoint, repeatedly. Unlike
    :func:`respread`, this never cuts a corner of the route, so a collision-free route stays
    collision-free when the planner re-seeds the optimizer with it.

    Returns an array ``(m, 2)`` (pixels).
    """
    import heapq

    pts = np.asarray(points, dtype=float)
    inner = pts[1:-1][-m:] if m > 0 else pts[:0]
    base = np.concatenate((pts[:1], inner, pts[-1:]))
    need = m - len(inner)
    if need <= 0:
        return base[1:-1].copy()
    # split the longest piece at its midpoint, repeatedly (ties: the earliest piece on the
    # route); a heap of pieces (segment j, parameters a..b) instead of re-measuring the list.
    # The few points are worked on as Python floats: numpy's per-call cost dominated here
    # (the lengths, halvings, comparisons and interpolations are the same doubles)
    d = base[1:] - base[:-1]
    heap = [(-s, j, 0.0, 1.0) for j, s in enumerate(np.hypot(d[:, 0], d[:, 1]).tolist())]
    heapq.heapify(heap)
    cuts: list[tuple[int, float]] = []
    for _ in range(need):
        neg, j, a, b = heapq.heappop(heap)
        c = 0.5 * (a + b)
        cuts.append((j, c))
        heapq.heappush(heap, (0.5 * neg, j, a, c))
        heapq.heappush(heap, (0.5 * neg, j, c, b))
    cuts.sort()
    # in route order: original vertex k (k >= 1) after every cut on the segments before it,
    # then the cuts on segment k by parameter, each base[k] + t (base[k + 1] - base[k])
    B = base.tolist()
    out = []
    c = 0
    for k in range(len(B) - 1):
        if k:
            out.append(B[k])
        (ax, ay), (bx, by) = B[k], B[k + 1]
        dx, dy = bx - ax, by - ay
        while c < need and cuts[c][0] == k:
            t = cuts[c][1]
            out.append((ax + t * dx, ay + t * dy))
            c += 1
    return np.array(out, dtype=np.float64)


@functools.lru_cache(maxsize=8)
def unit_headings(n: int) -> np.ndarray:
    """``n`` (>= 1) unit vectors at equal angles, counter-clockwise from +x: the fan of
    directions the guard, the inevitable-collision rule and the kinematic fallback try;
    shape (n, 2), read-only (shared between calls)."""
    ang = np.linspace(0.0, 2.0 * np.pi, int(n), endpoint=False)
    dirs = np.column_stack([np.cos(ang), np.sin(ang)])
    dirs.setflags(write=False)
    return dirs
