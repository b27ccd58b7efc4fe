"""Small drawing helpers shared by the scene families (obstacle dicts in the scenario schema)."""

from __future__ import annotations

import numpy as np

from mawdo.planning.scenes.base import Redraw

__all__ = ["box", "circle", "convex_polygon", "diagonal_endpoints", "place", "polygon"]


def polygon(vertices, motion: dict | None = None) -> dict:
    """A polygon obstacle dict from ``(k, 2)`` vertices (pixels)."""
    ob = {"shape": "polygon", "vertices": np.asarray(vertices, dtype=float).tolist()}
    if motion is not None:
        ob["motion"] = motion
    return ob


def box(x0: float, y0: float, x1: float, y1: float) -> dict:
    """An axis-aligned rectangle ``[x0, x1] x [y0, y1]`` (pixels)."""
    return polygon([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])


def circle(center, radius: float, motion: dict | None = None) -> dict:
    """A disc obstacle dict (pixels)."""
    ob = {"shape": "circle", "center": [float(center[0]), float(center[1])], "radius": radius}
    if motion is not None:
        ob["motion"] = motion
    return ob


def convex_polygon(rng: np.random.Generator, center, radius: float, kmin=4, kmax=8) -> np.ndarray:
    """A random convex polygon: ``k`` sorted angles on a circle of ``radius`` about ``center``.

    Angles are kept at least ``pi / (2 k)`` apart so no vertex is nearly collinear.
    """
    k = int(rng.integers(kmin, kmax + 1))
    base = np.linspace(0.0, 2.0 * np.pi, k, endpoint=False)
    angles = base + rng.uniform(-0.25, 0.25, k) * (2.0 * np.pi / k) + rng.uniform(0, 2 * np.pi)
    return np.asarray(center, float) + radius * np.column_stack([np.cos(angles), np.sin(angles)])


def diagonal_endpoints(rng: np.random.Generator, p: dict, margin: float) -> tuple:
    """Start near a random corner and goal near the opposite one (pixels)."""
    s = p["size"]
    jitter = rng.uniform(0.0, 0.08 * s, 4)
    start = np.array([margin + jitter[0], margin + jitter[1]])
    goal = np.array([s - margin - jitter[2], s - margin - jitter[3]])
    if rng.random() < 0.5:  # mirror: lower-right to upper-left
        start[0], goal[0] = s - start[0], s - goal[0]
    return start, goal


def place(rng: np.random.Generator, draw_one, keep_out, tries: int = 30):
    """Draw an obstacle with ``draw_one(rng) -> (dict, distance_fn)`` until it keeps clear.

    ``keep_out`` is a list of ``(point, distance)``: the obstacle's distance to each point must
    exceed the given distance (pixels). Raises :class:`Redraw` after ``tries`` failures.
    """
    for _ in range(tries):
        ob, dist = draw_one(rng)
        if all(dist(pt) > d for pt, d in keep_out):
            return ob
    raise Redraw("could not place an obstacle clear of start and goal")
