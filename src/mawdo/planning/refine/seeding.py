"""Seed candidates of a (re)plan: perturbed copies of a route, and via-point paths.

The run loop (:mod:`mawdo.planning.run.execute`) draws them from its own replan streams."""

from __future__ import annotations

import numpy as np

from mawdo.planning.guide.homotopy import Guide
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.world.path import densify

__all__ = ["RunGuide", "via_paths", "warm_seeds"]


class RunGuide(Guide):
    """The run loop's :class:`~mawdo.planning.guide.homotopy.Guide`: it keeps its last query. A
    step's hold test (the shortest route from the robot) and its seeds (the routes from the robot)
    ask from the same position; on paper about two queries in five repeat the one before.
    The arrays returned are the query's own (its callers only read them)."""

    _last: tuple = (None, None)
    _routes: tuple = (None, None)
    _rows: tuple = (None, None)

    def query(self, pos):
        key = np.asarray(pos, dtype=float).tobytes()
        if self._last[0] != key:
            self._last = (key, super().query(pos))
        return self._last[1]

    def routes(self, pos) -> list[np.ndarray]:
        # the guide gate and the search's seeds ask from the same position in one replan
        key = np.asarray(pos, dtype=float).tobytes()
        if self._routes[0] != key:
            self._routes = (key, super().routes(pos))
        return self._routes[1]

    def seed_rows(self, pos, m: int) -> list[np.ndarray]:
        """The routes from ``pos`` as ``m`` waypoints each (:func:`densify`), flat ``(2 m,)``
        rows, made once per position and read only by the callers."""
        key = (np.asarray(pos, dtype=float).tobytes(), m)
        if self._rows[0] != key:
            self._rows = (key, [densify(r, m).reshape(-1) for r in self.routes(pos)])
        return self._rows[1]


def warm_seeds(route, m: int, config: PlannerConfig, rng, lb, ub) -> np.ndarray:
    """A route's ``m`` waypoints (geometry kept) plus ``config.warm_copies`` copies perturbed
    by N(0, ``config.warm_sigma``) px, clipped to ``[lb, ub]``; shape ``(1 + copies, 2 m)``."""
    base = densify(route, m).reshape(-1)
    noise = rng.normal(0.0, config.warm_sigma, (config.warm_copies, base.size))
    return np.clip(np.vstack([base, base + noise]), lb, ub)


def via_paths(start, goal, m: int, n: int, rng, lb, ub, width: float, height: float):
    """``n`` path-like candidates: start -> one or two random via points -> goal, densified
    to ``m`` waypoints and clipped to ``[lb, ub]`` (pixels); shape ``(n, 2 m)``.

    Uniform random waypoints make zig-zags that cross every obstacle; routes through random via
    points are short, diverse, and often collision-free, the usual way to seed a waypoint planner.
    """
    from mawdo.planning.world.path_kernels import densify_many

    pts = np.empty((n, 4, 2))
    counts = np.empty(n, np.int64)
    scale = np.array([width, height], dtype=float)
    for i in range(n):  # the draws in the order they always had: one or two via points each
        k = 1 + int(rng.random() < 0.5)
        pts[i, 0], pts[i, 1 : k + 1], pts[i, k + 1] = start, rng.random((k, 2)) * scale, goal
        counts[i] = k + 2
    if n == 0:
        return np.empty((0, 2 * m))
    return np.clip(densify_many(pts, counts, m).reshape(n, -1), lb, ub)
