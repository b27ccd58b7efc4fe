"""A dynamic-window / sampling local planner: the classic local planner of robot stacks, as a
baseline policy.

Each step the robot samples velocities (speeds ``0 .. v`` times headings, the whole window of a
holonomic robot that may change velocity at once, as CrowdNav's), rolls each one out for
``horizon`` steps against the tracked agents moving at their estimated velocities (constant
velocity) and the static walls, drops those that come closer than the robot's radius plus
``margin`` (exact closest approach of two linear motions per step), and takes the best of the
rest by the usual weighted score: progress toward the goal, clearance (capped), speed. With no
safe sample it takes the one with the largest clearance. Fox, Burgard & Thrun (1997) is the
origin; this is its holonomic, sampled form.
"""

from __future__ import annotations

import numpy as np
import shapely

from mawdo.planning.sense.reading import Reading

__all__ = ["DynamicWindow", "closest_approach"]


def closest_approach(p0, v, c0, w, steps: int) -> np.ndarray:
    """Smallest distance over ``[0, steps]`` between a point starting at ``p0`` moving at
    ``v`` and points starting at ``c0`` moving at ``w`` (all linear; exact).

    Parameters
    ----------
    p0 : array_like, shape (2,)
    v : array_like, shape (k, 2)
        Candidate velocities (pixels per step).
    c0, w : array_like, shape (n, 2)
        Agents' centres and velocities.
    steps : int
        Horizon (time steps), >= 1.

    Returns
    -------
    numpy.ndarray, shape (k, n)
        Distances (pixels).
    """
    d0 = np.asarray(c0, float)[None, :, :] - np.asarray(p0, float)  # (1, n, 2)
    dv = np.asarray(w, float)[None, :, :] - np.asarray(v, float)[:, None, :]  # (k, n, 2)
    a = np.einsum("kni,kni->kn", dv, dv)
    b = np.einsum("kni,kni->kn", d0 * np.ones_like(dv), dv)
    t = np.where(a > 0, np.clip(-b / np.where(a > 0, a, 1.0), 0.0, steps), 0.0)
    return np.hypot(*np.moveaxis(d0 + t[..., None] * dv, -1, 0))


class DynamicWindow:
    """The sampling local planner (see the module docstring) as a policy.

    Parameters
    ----------
    tracker : object
        ``reset()`` and ``update(reading) -> Tracks``.
    horizon : int
        Roll-out length (time steps), >= 1.
    speeds, headings : int
        Samples of the window: speeds ``v i / speeds`` (i = 1 .. speeds) times ``headings``
        directions, plus standing still.
    margin : float
        Extra clearance (pixels, >= 0) a sample must keep from agents.
    weights : tuple of float
        ``(progress, clearance, speed)`` weights of the score, each term scaled to ``[0, 1]``
        (progress and speed by the robot's speed, clearance by ``clearance_cap``).
    clearance_cap : float
        Clearance (pixels) beyond which more does not score.
    """

    name = "dwa"

    def __init__(
        self, tracker, horizon: int = 8, speeds: int = 4, headings: int = 24,
        margin: float = 1.0, weights=(1.0, 0.2, 0.1), clearance_cap: float = 20.0,
    ):  # fmt: skip
        if int(horizon) < 1 or int(speeds) < 1 or int(headings) < 3 or margin < 0:
            raise ValueError("horizon >= 1, speeds >= 1, headings >= 3 and margin >= 0 needed")
        self.tracker, self.horizon, self.margin = tracker, int(horizon), float(margin)
        self.weights, self.cap = tuple(map(float, weights)), float(clearance_cap)
        a = np.linspace(0.0, 2.0 * np.pi, int(headings), endpoint=False)
        unit = np.column_stack([np.cos(a), np.sin(a)])
        frac = np.arange(1, int(speeds) + 1) / int(speeds)
        self._window = np.vstack([np.zeros((1, 2)), (frac[:, None, None] * unit).reshape(-1, 2)])

    def reset(self, scenario, seed) -> None:
        self.speed, self.radius = scenario.robot_speed, scenario.robot_radius
        self.width, self.height = scenario.width, scenario.height
        walls = [scenario.obstacles[i].shape for i in scenario.static_indices]
        geoms = [shapely.Point(s.center).buffer(s.radius, 32) if s.shape == "circle"
                 else shapely.Polygon(s.vertices) for s in walls]  # fmt: skip
        self.walls = shapely.union_all(geoms) if geoms else None
        self.tracker.reset()

    def _wall_clearance(self, p0, v) -> np.ndarray:
        """Distance (pixels) from each roll-out's segment to the walls and the map's border,
        minus the robot's radius."""
        ends = p0 + self.horizon * v
        lo = np.minimum(np.minimum(ends[:, 0], ends[:, 1]), np.minimum(*p0))
        hi_x = self.width - np.maximum(ends[:, 0], p0[0])
        hi_y = self.height - np.maximum(ends[:, 1], p0[1])
        border = np.minimum(lo, np.minimum(hi_x, hi_y))
        if self.walls is None:
            return border - self.radius
        lines = shapely.linestrings(np.stack([np.broadcast_to(p0, ends.shape), ends + 1e-9], 1))
        return np.minimum(border, shapely.distance(lines, self.walls)) - self.radius

    def act(self, reading: Reading) -> np.ndarray:
        tracks = self.tracker.update(reading)
        p0, goal = reading.position, reading.goal
        v = self._window * self.speed
        to_goal = goal - p0
        dist = float(np.hypot(*to_goal))
        if dist <= self.speed:  # the goal within one step: a sample that lands on it
            v = np.vstack([v, to_goal[None, :]])
        clear = self._wall_clearance(p0, v)
        if len(tracks):
            reach = tracks.radii + self.radius
            gap = closest_approach(p0, v, tracks.centers, tracks.velocities, self.horizon)
            clear = np.minimum(clear, (gap - reach[None, :]).min(axis=1))
        safe = clear >= self.margin
        if not safe.any():
            return v[int(np.argmax(clear))]
        end = p0 + v  # progress of the first step, the one driven
        progress = (dist - np.hypot(*(goal - end).T)) / self.speed  # each term in [0, 1]
        speed = np.hypot(*v.T) / self.speed
        a, b, c = self.weights
        score = a * progress + b * np.minimum(clear, self.cap) / self.cap + c * speed
        return v[int(np.argmax(np.where(safe, score, -np.inf)))]
