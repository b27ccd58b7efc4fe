"""The crowd-navigation benchmark's classic robot baselines: the robot driven by ORCA (CrowdNav's
``ORCA`` policy) and by the social force model.

Both are :class:`~mawdo.planning.sense.reading.Policy` objects. The work is in ``decide``,
which takes the robot's state and the others as :class:`~mawdo.planning.sense.reading.Tracks`;
``act`` gets the tracks from a tracker (an object with ``reset()`` and
``update(reading) -> Tracks``) given to the constructor.

Units: pixels, time steps, pixels per time step.
"""

from __future__ import annotations

import numpy as np

from mawdo.planning.people.base import preferred_velocities
from mawdo.planning.people.orca import OrcaParams, OrcaSim, cap_speed
from mawdo.planning.people.social_force import SocialForceParams, integrate
from mawdo.planning.people.walls import Walls
from mawdo.planning.sense.reading import Reading, Tracks
from mawdo.planning.world.geometry import circumscribed_polygon

__all__ = ["OrcaRobot", "SocialForceRobot", "static_polygons"]


def static_polygons(scenario) -> list[np.ndarray]:
    """The scenario's static obstacles as polygons ``(k, 2)`` (pixels); a circle becomes its
    circumscribed 32-gon (which contains it)."""
    out = []
    for o in scenario.obstacles:
        if not o.is_static:
            continue
        if o.is_circle:
            poly = circumscribed_polygon(o.shape.center, o.shape.radius)
            out.append(np.asarray(poly.exterior.coords, dtype=float)[:-1])
        else:
            out.append(np.asarray(o.shape.vertices, dtype=float))
    return out


class _TrackedRobot:
    """Shared part: the scenario's robot, its static walls and the tracker."""

    def __init__(self, arrival_time: float, tracker=None) -> None:
        if not (np.isfinite(arrival_time) and arrival_time > 0):
            raise ValueError(f"arrival_time={arrival_time!r} must be > 0 time steps")
        self.arrival_time = float(arrival_time)
        self.tracker = tracker
        self.scenario = None

    def reset(self, scenario, seed) -> None:
        """Start an episode: take the robot's radius and speed and the static obstacles from
        ``scenario``; reset the tracker (``seed`` is unused: the policy is deterministic)."""
        self.scenario = scenario
        self.radius = float(scenario.robot_radius)
        self.speed = float(scenario.robot_speed)
        self.polygons = static_polygons(scenario)
        self._setup()
        if self.tracker is not None:
            self.tracker.reset()

    def _setup(self) -> None:
        """Build what ``decide`` needs from the static obstacles."""

    def act(self, reading: Reading) -> np.ndarray:
        """The velocity to drive for one step (pixels per step, norm <= the robot's speed)."""
        if self.tracker is None:
            raise RuntimeError(
                f"{type(self).__name__}.act needs a tracker (an object with reset() and "
                "update(reading) -> Tracks); pass tracker=... to the constructor, or call "
                "decide(position, velocity, goal, tracks) with tracks of your own"
            )
        if self.scenario is None:
            raise RuntimeError(f"{type(self).__name__}.act before reset(scenario, seed)")
        tracks = self.tracker.update(reading)
        return self.decide(reading.position, reading.velocity, reading.goal, tracks)

    def _state(self, position, velocity, goal):
        if self.scenario is None:
            raise RuntimeError(f"{type(self).__name__}.decide before reset(scenario, seed)")
        p = np.asarray(position, dtype=float).reshape(1, 2)
        v = np.asarray(velocity, dtype=float).reshape(1, 2)
        g = np.asarray(goal, dtype=float).reshape(1, 2)
        pref = preferred_velocities(p, g, [self.speed], self.arrival_time)
        return p, v, pref


class OrcaRobot(_TrackedRobot):
    """The robot driven by ORCA toward its goal (CrowdNav's ``ORCA`` robot policy).

    One ORCA step with the robot as agent 0 (maximum speed its speed, preferred velocity toward
    the goal) and every track as an agent with its estimated position and velocity and a zero
    preferred velocity (their goals are unknown); the static obstacles are RVO2 obstacles.

    Parameters
    ----------
    params : OrcaParams
        Pixels and time steps (CrowdNav: ``OrcaParams.from_metres(res, dt)``; its test script
        sets ``safety_space = 0``, so only the 0.01 m pad).
    arrival_time : float
        Time steps over which the robot slows into its goal (CrowdNav: 1 s), > 0.
    tracker : object, optional
        ``reset()`` and ``update(reading) -> Tracks``; needed by :meth:`act`.
    """

    def __init__(self, params: OrcaParams, arrival_time: float, tracker=None) -> None:
        super().__init__(arrival_time, tracker)
        if not isinstance(params, OrcaParams):
            raise ValueError("params must be an OrcaParams (e.g. OrcaParams.from_metres(res, dt))")
        self.params = params

    @classmethod
    def from_metres(cls, res: float, dt: float, tracker=None, **params) -> OrcaRobot:
        """CrowdNav's ORCA robot at ``res`` (m/px) and ``dt`` (s): ``OrcaParams.from_metres``
        (``params`` override its metre values) and a 1 s slow-down into the goal."""
        return cls(OrcaParams.from_metres(res, dt, **params), 1.0 / dt, tracker)

    def _setup(self) -> None:
        self._orca = OrcaSim(self.params, self.polygons)

    def decide(self, position, velocity, goal, tracks: Tracks) -> np.ndarray:
        """The robot's velocity for the next step (pixels per step, norm <= its speed).

        Parameters
        ----------
        position, velocity, goal : array_like, shape (2,)
            The robot's centre, velocity over the last step and goal.
        tracks : Tracks
            The others' estimated centres, velocities and radii.
        """
        p, v, pref = self._state(position, velocity, goal)
        pos = np.vstack([p, tracks.centers])
        vel = np.vstack([v, tracks.velocities])
        radii = np.append(self.radius, tracks.radii)
        speeds = np.append(self.speed, np.hypot(*tracks.velocities.T))
        prefs = np.vstack([pref, np.zeros((len(tracks), 2))])
        out = self._orca.solve(pos, vel, radii, speeds, prefs)[:1]
        return cap_speed(out, [self.speed])[0]


class SocialForceRobot(_TrackedRobot):
    """The robot driven by the social force model (the forces of
    :mod:`~mawdo.planning.people.social_force`: toward its goal, away from the tracked agents
    and the static walls).

    Over one step the robot integrates its own force with ``params.substeps`` sub-steps while
    the tracks move on at their estimated velocities; the returned velocity is the step's mean
    (its displacement), at most the robot's speed.

    Parameters
    ----------
    params : SocialForceParams
        Pixels and time steps (e.g. ``SocialForceParams.from_metres(res, dt)``);
        ``max_speed_factor`` is not used (the robot's speed caps it).
    arrival_time : float
        Time steps over which the robot slows into its goal, > 0.
    tracker : object, optional
        ``reset()`` and ``update(reading) -> Tracks``; needed by :meth:`act`.
    """

    def __init__(self, params: SocialForceParams, arrival_time: float, tracker=None) -> None:
        super().__init__(arrival_time, tracker)
        if not isinstance(params, SocialForceParams):
            raise ValueError(
                "params must be a SocialForceParams (e.g. SocialForceParams.from_metres(res, dt))"
            )
        self.params = params

    @classmethod
    def from_metres(cls, res: float, dt: float, tracker=None, **params) -> SocialForceRobot:
        """The social force robot at ``res`` (m/px) and ``dt`` (s):
        ``SocialForceParams.from_metres`` (``params`` override its metre values) and a 1 s
        slow-down into the goal."""
        return cls(SocialForceParams.from_metres(res, dt, **params), 1.0 / dt, tracker)

    def _setup(self) -> None:
        s = self.scenario
        self._walls = Walls.build(self.polygons, (s.width, s.height))

    def decide(self, position, velocity, goal, tracks: Tracks) -> np.ndarray:
        """The robot's velocity for the next step (pixels per step, norm <= its speed); see
        :meth:`OrcaRobot.decide` for the arguments."""
        p, v, _ = self._state(position, velocity, goal)
        g = np.asarray(goal, dtype=float).reshape(1, 2)
        radius = np.array([self.radius])

        def desired_at(x):
            return preferred_velocities(x, g, [self.speed], self.arrival_time)

        def others_at(s, x):
            return tracks.centers + s * tracks.velocities, tracks.radii, None

        # the guard needs a clear start; a robot already touching a wall moves unguarded
        clear = bool(self._walls.free(p, radius)[0])
        end = integrate(
            self.params,
            self._walls,
            p,
            v,
            radius,
            np.array([self.speed]),
            desired_at,
            others_at,
            guard=clear,
        )
        return cap_speed(end - p, [self.speed])[0]
