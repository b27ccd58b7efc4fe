"""Plain shapely/numpy reference for the path cost, independent of the Numba kernel.

Used only by the tests: lengths by numpy, turning by arccos (the kernel uses atan2), hits by
shapely distances between LineStrings and the raw shapes. In spacetime mode the relative motion
in each obstacle's frame is built as a polyline through the obstacle's knots (one straight piece
per constant-velocity piece), with offsets interpolated by ``numpy.interp``.
"""

from __future__ import annotations

import numpy as np
import shapely

from mawdo.planning.world.scenario import CircleObstacle

# Pairs whose distance is this close to the hit threshold are tangency cases (pixels): the
# kernel and shapely may round them differently, so comparisons exclude them.
AMBIGUOUS = 1e-6


def paths_from(X, start, goal) -> np.ndarray:
    n = X.shape[0]
    pts = X.reshape(n, -1, 2)
    s = np.broadcast_to(np.asarray(start, float), (n, 1, 2))
    g = np.broadcast_to(np.asarray(goal, float), (n, 1, 2))
    return np.concatenate([s, pts, g], axis=1)


def length_and_turning(paths: np.ndarray):
    d = np.diff(paths, axis=1)
    seg = np.hypot(d[..., 0], d[..., 1])
    length = seg.sum(axis=1)
    turning = np.zeros(len(paths))
    for c in range(len(paths)):
        dirs = d[c][seg[c] > 1e-9]
        if len(dirs) < 2:
            continue
        u = dirs / np.hypot(dirs[:, 0], dirs[:, 1])[:, None]
        cos = np.clip(np.sum(u[:-1] * u[1:], axis=1), -1.0, 1.0)
        turning[c] = np.sum(np.arccos(cos))
    return length, turning


def _distance(shape, lines):
    """Distance to the raw shape; negative when clearly inside (so tangency stands out)."""
    if isinstance(shape, CircleObstacle):
        return shapely.distance(lines, shapely.Point(shape.center)) - shape.radius
    poly = shapely.Polygon(shape.vertices)
    d = shapely.distance(lines, poly)
    # distance is 0 both for a crossing and for a mere touch: a line that also meets the
    # polygon shrunk by 10 AMBIGUOUS is a clear hit
    deep = (d == 0) & shapely.intersects(lines, poly.buffer(-10 * AMBIGUOUS))
    return np.where(deep, -1.0, d)


def hit_margins(scenario, paths: np.ndarray, mode: str, t0: float = 0.0) -> np.ndarray:
    """Distance minus robot radius per (candidate, segment, obstacle): <= 0 is a hit."""
    n, npts, _ = paths.shape
    nseg = npts - 1
    r = scenario.robot_radius
    a = paths[:, :-1].reshape(-1, 2)
    b = paths[:, 1:].reshape(-1, 2)
    out = np.empty((n * nseg, len(scenario.obstacles)))
    if mode == "snapshot":
        off = scenario.offsets(t0)
        for o in scenario.obstacles:
            lines = shapely.linestrings(np.stack([a - off[o.index], b - off[o.index]], axis=1))
            out[:, o.index] = _distance(o.shape, lines) - r
        return out.reshape(n, nseg, -1)
    seg = np.hypot(*(b - a).T).reshape(n, nseg)
    cum = np.concatenate([np.zeros((n, 1)), np.cumsum(seg, axis=1)], axis=1)
    ta = (t0 + cum[:, :-1] / scenario.robot_speed).ravel()
    tb = (t0 + cum[:, 1:] / scenario.robot_speed).ravel()
    for o in scenario.obstacles:
        kt, ko = o.knots(t0, float(tb.max()) + 1.0)
        # times of each relative polyline: ta, the knots strictly inside (ta, tb), tb
        lo = np.searchsorted(kt, ta, side="right")
        hi = np.searchsorted(kt, tb, side="left")
        inner = np.maximum(hi - lo, 0)
        counts = inner + 2
        seg_id = np.repeat(np.arange(len(ta)), counts)
        pos = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        times = np.where(pos == 0, ta[seg_id], 0.0)
        is_end = pos == counts[seg_id] - 1
        times = np.where(is_end, tb[seg_id], times)
        mid = (~is_end) & (pos > 0)
        times[mid] = kt[lo[seg_id[mid]] + pos[mid] - 1]
        ox = np.interp(times, kt, ko[:, 0])
        oy = np.interp(times, kt, ko[:, 1])
        dur = tb[seg_id] - ta[seg_id]
        f = np.where(dur > 0, (times - ta[seg_id]) / np.where(dur > 0, dur, 1.0), 0.0)
        rx = a[seg_id, 0] + f * (b[seg_id, 0] - a[seg_id, 0]) - ox
        ry = a[seg_id, 1] + f * (b[seg_id, 1] - a[seg_id, 1]) - oy
        lines = shapely.linestrings(np.column_stack([rx, ry]), indices=seg_id)
        out[:, o.index] = _distance(o.shape, lines) - r
    return out.reshape(n, nseg, -1)


def border_hits(scenario, paths: np.ndarray, clearance: float = 0.0) -> np.ndarray:
    """Segments per candidate that leave the map shrunk by ``r + clearance`` (shapely: the
    segment is not covered by that box; touching its edge is inside). Exact on both sides:
    the kernel compares the very coordinates with the very box, so no tangency is ambiguous."""
    reach = scenario.robot_radius + clearance
    box = shapely.box(reach, reach, scenario.width - reach, scenario.height - reach)
    n, npts, _ = paths.shape
    lines = shapely.linestrings(np.stack([paths[:, :-1], paths[:, 1:]], axis=2).reshape(-1, 2, 2))
    return (~shapely.covers(box, lines)).reshape(n, npts - 1).sum(axis=1)


def reference_parts(scenario, X, start, mode: str, t0: float = 0.0):
    """(length, n_collisions, turning, ambiguous) per candidate; the collisions count the
    (segment, obstacle) pairs and the segments that leave the map (:func:`border_hits`)."""
    paths = paths_from(np.asarray(X, float), start, scenario.goal)
    length, turning = length_and_turning(paths)
    margin = hit_margins(scenario, paths, mode, t0)
    ncol = np.sum(margin <= 0.0, axis=(1, 2)) + border_hits(scenario, paths)
    ambiguous = np.any(np.abs(margin) < AMBIGUOUS, axis=(1, 2))
    return length, ncol, turning, ambiguous
