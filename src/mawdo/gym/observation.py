"""The observation vector of the Gymnasium environments, built from a sensor's reading.

The same :class:`Observer` serves the environment and :class:`~mawdo.gym.adapter.CallablePolicy`,
so a learned policy sees the same numbers whether it is trained in the environment or judged by
:func:`~mawdo.planning.run.episode.run_episode`.

Layout (``float32``, ``6 + 6 k + n_rays`` values), in the robot's frame: origin at the robot
centre, axes those of the map (a holonomic robot has no heading). Lengths are in metres and
velocities in metres per second for a metre scenario (pixels and pixels per step for a pixel
one):

=================  =====================================================================
slice              content
=================  =====================================================================
``0:2``            goal offset ``goal - position`` (m)
``2:4``            robot velocity over the last step (m/s; zero at the first step)
``4``              robot radius (m)
``5``              robot preferred (maximum) speed (m/s)
``6 + 6 j + 0:2``  agent ``j``'s position relative to the robot centre (m)
``6 + 6 j + 2:4``  agent ``j``'s velocity as the tracker estimates it (m/s, map axes,
                   not relative to the robot)
``6 + 6 j + 4``    agent ``j``'s radius (m)
``6 + 6 j + 5``    mask: 1 for a tracked agent, 0 for a padding row (all zeros)
``6 + 6 k + i``    range along ray ``i`` at angle ``2 pi i / n_rays`` from the map's x axis,
                   from the robot centre to the first static wall or the map border, capped
                   at ``max_range`` (m; 0 when the centre is inside a wall or off the map)
=================  =====================================================================

Every value is clipped to :meth:`Observer.bounds` (offsets to twice the map's diagonal,
velocities to :data:`SPEED_BOUND` times the robot's speed), which only a track extrapolated far
off the map or a wild velocity estimate reaches.

Agents are the tracker's live tracks (:class:`~mawdo.planning.sense.tracker.Tracker` fed the
reading), nearest first by surface distance ``|offset| - radius`` (ties by track id), the ``k``
nearest kept.
"""

from __future__ import annotations

import numpy as np
import shapely

from mawdo.planning.sense.reading import Reading
from mawdo.util.validate import check_int, check_real

__all__ = [
    "AGENT_FIELDS",
    "ROBOT_FIELDS",
    "SPEED_BOUND",
    "Observer",
    "ray_ranges",
    "static_lines",
    "unit_scales",
]

#: Values of the robot block (goal offset x, y; velocity x, y; radius; preferred speed).
ROBOT_FIELDS = 6
#: Values per agent row (offset x, y; velocity x, y; radius; mask).
AGENT_FIELDS = 6
#: Velocities are clipped to this many times the robot's speed.
SPEED_BOUND = 10.0


def static_lines(walls, width: float, height: float):
    """Boundaries a ray can hit: every wall polygon's outline and the map border (pixels).

    Parameters
    ----------
    walls : sequence of array_like, each shape (m, 2)
        Static wall polygons (pixels), as :meth:`~mawdo.planning.world.stepped.SteppedWorld.walls`
        gives them.
    width, height : float
        Map size (pixels), > 0.

    Returns
    -------
    lines : shapely.MultiLineString
        The closed outlines.
    solid : shapely.Geometry
        The union of the wall polygons (for the inside test); an empty geometry without walls.
    """
    box = np.array([[0.0, 0.0], [width, 0.0], [width, height], [0.0, height], [0.0, 0.0]])
    rings = [box]
    polys = []
    for w in walls:
        v = np.asarray(w, dtype=float).reshape(-1, 2)
        rings.append(np.vstack([v, v[:1]]))
        polys.append(shapely.Polygon(v))
    solid = shapely.union_all(polys) if polys else shapely.GeometryCollection()
    shapely.prepare(solid)
    return shapely.MultiLineString(rings), solid


def ray_ranges(position, n_rays: int, reach: float, lines, solid, width, height) -> np.ndarray:
    """Distance from ``position`` to the first boundary along ``n_rays`` evenly spaced rays.

    Parameters
    ----------
    position : array_like, shape (2,)
        Ray origin (pixels).
    n_rays : int
        Number of rays, >= 0; ray ``i`` points at angle ``2 pi i / n_rays`` from the x axis.
    reach : float
        Ray length (pixels), > 0: the range reported when nothing is hit.
    lines, solid : shapely geometries
        From :func:`static_lines`.
    width, height : float
        Map size (pixels).

    Returns
    -------
    numpy.ndarray, shape (n_rays,)
        Ranges in ``[0, reach]`` (pixels); all 0 when ``position`` is inside a wall or outside
        the map.
    """
    p = np.asarray(position, dtype=float).reshape(2)
    if n_rays == 0:
        return np.zeros(0)
    off_map = not (0.0 <= p[0] <= width and 0.0 <= p[1] <= height)
    if off_map or (not solid.is_empty and shapely.contains_xy(solid, p[0], p[1])):
        return np.zeros(n_rays)
    a = 2.0 * np.pi * np.arange(n_rays) / n_rays
    ends = p + reach * np.column_stack([np.cos(a), np.sin(a)])
    rays = shapely.linestrings(np.stack([np.broadcast_to(p, ends.shape), ends], axis=1))
    hits = shapely.intersection(rays, lines)
    # every hit lies on the ray, so the nearest one to the origin is the first one along it
    d = shapely.distance(shapely.Point(p), hits)
    return np.minimum(np.where(np.isnan(d), reach, d), reach)


def unit_scales(units) -> tuple[float, float]:
    """Metres per pixel and seconds per step of a scenario's units (1 and 1 for pixels)."""
    if units.is_pixels:
        return 1.0, 1.0
    return float(units.resolution), float(units.dt)


class Observer:
    """Turns each step's :class:`~mawdo.planning.sense.reading.Reading` into the observation
    vector (see the module's table) and actions (m/s) into the world's velocities (px/step).

    Parameters
    ----------
    k : int
        Agent rows, >= 0 (the ``k`` nearest tracked agents; fewer are padded).
    n_rays : int
        Range rays against static walls and the map border, >= 0.
    max_range : float
        Ray length (metres, or pixels in a pixel scenario), > 0.
    tracker : Tracker
        Estimates the agents' velocities from the readings; reset at :meth:`reset`.
    """

    def __init__(self, k: int, n_rays: int, max_range: float, tracker) -> None:
        self.k = check_int("k", k, 0)
        self.n_rays = check_int("n_rays", n_rays, 0)
        self.max_range = check_real("max_range", max_range, 0.0, low_open=True)
        self.tracker = tracker
        self.scenario = None

    @property
    def size(self) -> int:
        """Length of the observation vector."""
        return ROBOT_FIELDS + AGENT_FIELDS * self.k + self.n_rays

    def bounds(self, scenario) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper bound of every value in ``scenario`` (``float32``): offsets within
        twice the map's diagonal, velocities within :data:`SPEED_BOUND` times the robot's
        speed, radii within the diagonal; :meth:`observe` clips to them (only a track
        extrapolated far off the map, or a wild velocity estimate, reaches them)."""
        res, dt = unit_scales(scenario.units)
        speed_scale = res / dt
        diag = float(np.hypot(scenario.width, scenario.height)) * res
        v = float(scenario.robot_speed) * speed_scale
        far, fast = 2.0 * diag, SPEED_BOUND * v
        robot = [far, far, fast, fast, diag, v]
        agent = [far, far, fast, fast, diag, 1.0]
        high = np.concatenate([robot, np.tile(agent, self.k), np.full(self.n_rays, self.max_range)])
        low = -high
        low[4:6] = 0.0
        low[ROBOT_FIELDS + 4 : ROBOT_FIELDS + AGENT_FIELDS * self.k : AGENT_FIELDS] = 0.0
        low[ROBOT_FIELDS + 5 : ROBOT_FIELDS + AGENT_FIELDS * self.k : AGENT_FIELDS] = 0.0
        low[ROBOT_FIELDS + AGENT_FIELDS * self.k :] = 0.0
        return low.astype(np.float32), high.astype(np.float32)

    def reset(self, scenario, walls) -> None:
        """Start an episode in ``scenario`` (its units, robot and map) with these static
        ``walls`` (polygons, pixels); forget every track."""
        self.scenario = scenario
        self.res, self.dt = unit_scales(scenario.units)
        self.speed_scale = self.res / self.dt  # (m/s) per (px/step)
        self.low, self.high = self.bounds(scenario)
        self.speed = float(scenario.robot_speed) * self.speed_scale  # m/s
        self.radius = float(scenario.robot_radius) * self.res
        self.size_px = (float(scenario.width), float(scenario.height))
        self.lines, self.solid = static_lines(walls, *self.size_px)
        self.tracker.reset()

    def observe(self, reading: Reading) -> np.ndarray:
        """The observation of one step's reading (updates the tracker: call once per step)."""
        if self.scenario is None:
            raise RuntimeError("Observer.observe before reset(scenario, walls)")
        tracks = self.tracker.update(reading)
        p = reading.position
        out = np.zeros(self.size)
        out[0:2] = (reading.goal - p) * self.res
        out[2:4] = reading.velocity * self.speed_scale
        out[4], out[5] = self.radius, self.speed
        if self.k and len(tracks):
            rel = (tracks.centers - p) * self.res
            radii = tracks.radii * self.res
            order = np.argsort(np.hypot(rel[:, 0], rel[:, 1]) - radii, kind="stable")[: self.k]
            rows = out[ROBOT_FIELDS : ROBOT_FIELDS + AGENT_FIELDS * len(order)]
            rows = rows.reshape(-1, AGENT_FIELDS)
            rows[:, 0:2] = rel[order]
            rows[:, 2:4] = tracks.velocities[order] * self.speed_scale
            rows[:, 4] = radii[order]
            rows[:, 5] = 1.0
        if self.n_rays:
            reach = self.max_range / self.res
            ranges = ray_ranges(p, self.n_rays, reach, self.lines, self.solid, *self.size_px)
            out[ROBOT_FIELDS + AGENT_FIELDS * self.k :] = ranges * self.res
        return np.clip(out.astype(np.float32), self.low, self.high)

    def velocity_px(self, action) -> np.ndarray:
        """The world's velocity (pixels per step) for an action: a velocity (m/s, map axes)
        whose components are clipped to ``[-v, v]`` (``v`` the robot's speed); the world then
        scales a longer one down to the speed."""
        a = np.asarray(action, dtype=float).reshape(-1)
        if a.shape != (2,) or not np.all(np.isfinite(a)):
            raise ValueError(f"an action is a finite velocity (vx, vy) in m/s, got {action!r}")
        return np.clip(a, -self.speed, self.speed) / self.speed_scale

    def action_of(self, velocity_px) -> np.ndarray:
        """The action (m/s) that drives ``velocity_px`` (pixels per step)."""
        return np.asarray(velocity_px, dtype=float).reshape(2) * self.speed_scale
