"""Static walls as line segments: distances, nearest points and the move guard that keeps discs
out of walls and inside the map.

Units: pixels. A wall is a simple polygon given by its vertices, shape ``(k, 2)``, ``k >= 3``,
in either orientation. Why people need a guard: docs/deviations.md#d-people-guard.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import shapely

__all__ = ["Walls", "point_segment_distance", "segment_segment_distance"]

# Bisection rounds of the guard when neither the move nor the slide along the wall is clear:
# the kept fraction of the move is within 2**-20 of the largest clear one.
_BISECTIONS = 20


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


def point_segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray):
    """Distances and nearest points from points to segments, every pair.

    Parameters
    ----------
    p : numpy.ndarray, shape (n, 2)
        Points (pixels).
    a, b : numpy.ndarray, shape (m, 2)
        Segment ends (pixels); a degenerate segment (``a == b``) is its point.

    Returns
    -------
    dist : numpy.ndarray, shape (n, m)
        Euclidean distances (pixels).
    nearest : numpy.ndarray, shape (n, m, 2)
        Nearest point of each segment to each point (pixels).
    """
    d = b - a  # (m, 2)
    dd = np.einsum("mk,mk->m", d, d)
    rel = p[:, None, :] - a[None, :, :]  # (n, m, 2)
    t = np.einsum("nmk,mk->nm", rel, d) / np.where(dd > 0, dd, 1.0)
    t = np.clip(t, 0.0, 1.0)
    nearest = a[None, :, :] + t[..., None] * d[None, :, :]
    diff = p[:, None, :] - nearest
    return np.hypot(diff[..., 0], diff[..., 1]), nearest


def segment_segment_distance(p0: np.ndarray, p1: np.ndarray, a: np.ndarray, b: np.ndarray):
    """Smallest distance between each segment ``p0[i] p1[i]`` and each segment ``a[j] b[j]``.

    Parameters
    ----------
    p0, p1 : numpy.ndarray, shape (n, 2)
        First segments (pixels), e.g. moves.
    a, b : numpy.ndarray, shape (m, 2)
        Second segments (pixels), e.g. wall edges.

    Returns
    -------
    numpy.ndarray, shape (n, m)
        Distances (pixels), 0 where the segments cross or touch.
    """
    d_p0, _ = point_segment_distance(p0, a, b)
    d_p1, _ = point_segment_distance(p1, a, b)
    dist = np.minimum(d_p0, d_p1)
    # the wall ends against the moves
    for end in (a, b):
        rel = end[None, :, :] - p0[:, None, :]
        mv = (p1 - p0)[:, None, :]
        mm = np.einsum("nmk,nmk->nm", mv, mv)
        t = np.clip(np.einsum("nmk,nmk->nm", rel, mv) / np.where(mm > 0, mm, 1.0), 0.0, 1.0)
        gap = rel - t[..., None] * mv
        dist = np.minimum(dist, np.hypot(gap[..., 0], gap[..., 1]))
    # proper crossings: the ends of each segment lie on opposite sides of the other
    mx, my = (p1 - p0)[:, 0:1], (p1 - p0)[:, 1:2]
    wx, wy = (b - a)[None, :, 0], (b - a)[None, :, 1]
    s1 = _cross(mx, my, a[None, :, 0] - p0[:, 0:1], a[None, :, 1] - p0[:, 1:2])
    s2 = _cross(mx, my, b[None, :, 0] - p0[:, 0:1], b[None, :, 1] - p0[:, 1:2])
    s3 = _cross(wx, wy, p0[:, 0:1] - a[None, :, 0], p0[:, 1:2] - a[None, :, 1])
    s4 = _cross(wx, wy, p1[:, 0:1] - a[None, :, 0], p1[:, 1:2] - a[None, :, 1])
    crossing = (s1 * s2 < 0) & (s3 * s4 < 0)
    return np.where(crossing, 0.0, dist)


def _polygon(vertices, name: str) -> np.ndarray:
    v = np.asarray(vertices, dtype=float)
    if v.ndim != 2 or v.shape[1] != 2 or len(v) < 3 or not np.all(np.isfinite(v)):
        raise ValueError(
            f"{name} must be a (k, 2) array of k >= 3 finite vertices (pixels), got shape "
            f"{v.shape}; give each wall as its polygon's corner points"
        )
    poly = shapely.Polygon(v)
    if not poly.is_valid or poly.area <= 0:
        raise ValueError(
            f"{name} is not a simple polygon of positive area "
            f"({shapely.is_valid_reason(poly)}); list its corners in order around it"
        )
    return v


@dataclass(frozen=True, eq=False)
class Walls:
    """Static wall polygons and the map box, as segments.

    Parameters
    ----------
    polygons : tuple of numpy.ndarray
        Wall polygons, each ``(k, 2)`` (pixels), as given.
    width, height : float
        Map box ``[0, width] x [0, height]`` (pixels); its border keeps discs inside (the guard)
        but exerts no force and is not an ORCA obstacle.
    """

    polygons: tuple[np.ndarray, ...]
    width: float
    height: float

    @classmethod
    def build(cls, polygons, bounds) -> Walls:
        """Validate ``polygons`` (sequence of ``(k, 2)`` vertex arrays) and ``bounds``
        (``(width, height)`` pixels, both > 0) and build the walls."""
        try:
            width, height = (float(x) for x in bounds)
        except (TypeError, ValueError):
            raise ValueError(f"bounds must be (width, height) in pixels, got {bounds!r}") from None
        if not (np.isfinite(width) and np.isfinite(height) and width > 0 and height > 0):
            raise ValueError(f"bounds={bounds!r}: width and height must be finite and > 0 pixels")
        polys = tuple(_polygon(p, f"obstacles[{i}]") for i, p in enumerate(polygons))
        return cls(polys, width, height)

    @cached_property
    def segments(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Wall edges ``(a, b, polygon_index)``: ends ``(m, 2)`` and owner ``(m,)``."""
        if not self.polygons:
            return np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0, dtype=np.int64)
        a = np.vstack(self.polygons)
        b = np.vstack([np.roll(p, -1, axis=0) for p in self.polygons])
        owner = np.repeat(np.arange(len(self.polygons)), [len(p) for p in self.polygons])
        return a, b, owner

    @cached_property
    def _guard_segments(self) -> tuple[np.ndarray, np.ndarray]:
        w, h = self.width, self.height
        box = np.array([[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]])
        a, b, _ = self.segments
        return np.vstack([a, box]), np.vstack([b, np.roll(box, -1, axis=0)])

    def clearance(self, points) -> np.ndarray:
        """Distance from each point to the nearest wall or map border (pixels); negative inside
        a wall or outside the map (minus the depth there)."""
        p = np.asarray(points, dtype=float).reshape(-1, 2)
        a, b = self._guard_segments
        dist = point_segment_distance(p, a, b)[0].min(axis=1)
        inside_map = (p[:, 0] >= 0) & (p[:, 0] <= self.width)
        inside_map &= (p[:, 1] >= 0) & (p[:, 1] <= self.height)
        inside_wall = np.zeros(len(p), dtype=bool)
        for poly in self.polygons:
            inside_wall |= shapely.contains_xy(shapely.Polygon(poly), p[:, 0], p[:, 1])
        return np.where(inside_map & ~inside_wall, dist, -dist)

    def free(self, points, radii) -> np.ndarray:
        """Whether discs (centres ``(n, 2)``, radii ``(n,)`` pixels) lie in the map, clear of
        every wall (touching allowed)."""
        return self.clearance(points) >= np.asarray(radii, dtype=float)

    def guard(self, p0: np.ndarray, move: np.ndarray, radii: np.ndarray) -> np.ndarray:
        """Where discs end up when they try to move by ``move``: the move if the swept disc
        stays clear of the walls and the map border, else the move without its part into the
        nearest wall (sliding along it) if that is clear, else the longest clear fraction of
        the move (found by bisection). Discs that start clear stay clear.

        Parameters
        ----------
        p0 : numpy.ndarray, shape (n, 2)
            Centres now (pixels), clear of the walls.
        move : numpy.ndarray, shape (n, 2)
            Wanted displacements (pixels).
        radii : numpy.ndarray, shape (n,)
            Disc radii (pixels).

        Returns
        -------
        numpy.ndarray, shape (n, 2)
            New centres (pixels).
        """
        out = p0 + move
        bad = ~self._clear_moves(p0, out, radii)
        if not bad.any():
            return out
        a, b = self._guard_segments
        idx = np.flatnonzero(bad)
        q0, mv, r = p0[idx], move[idx], radii[idx]
        dist, nearest = point_segment_distance(q0, a, b)
        k = dist.argmin(axis=1)
        normal = q0 - nearest[np.arange(len(idx)), k]
        normal /= np.maximum(np.hypot(normal[:, 0], normal[:, 1]), 1e-300)[:, None]
        into = np.minimum(np.einsum("nk,nk->n", mv, normal), 0.0)
        slide = mv - into[:, None] * normal
        ok = self._swept_clear(q0, q0 + slide, r, a, b)
        res = np.where(ok[:, None], q0 + slide, q0)
        lo, hi = np.zeros(len(idx)), np.ones(len(idx))
        todo = ~ok
        if todo.any():
            for _ in range(_BISECTIONS):
                mid = 0.5 * (lo + hi)
                clear = self._swept_clear(q0, q0 + mid[:, None] * mv, r, a, b)
                lo = np.where(clear, mid, lo)
                hi = np.where(clear, hi, mid)
            res = np.where(todo[:, None], q0 + lo[:, None] * mv, res)
        out[idx] = res
        return out

    def _clear_moves(self, p0, p1, radii) -> np.ndarray:
        # The map box is convex: a disc swept along a segment stays inside it when the disc at
        # the segment's end does (the start is inside), so only the walls need the sweep test.
        ok = (p1[:, 0] >= radii) & (p1[:, 0] <= self.width - radii)
        ok &= (p1[:, 1] >= radii) & (p1[:, 1] <= self.height - radii)
        if self.polygons:
            a, b, _ = self.segments
            ok &= self._swept_clear(p0, p1, radii, a, b)
        return ok

    @staticmethod
    def _swept_clear(p0, p1, radii, a, b) -> np.ndarray:
        return segment_segment_distance(p0, p1, a, b).min(axis=1) >= radii
