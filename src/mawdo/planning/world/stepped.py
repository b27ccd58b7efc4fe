"""A world that advances one time step at a time from the robot's action.

The world holds a scenario's obstacles (static ones and scripted movers, whose closed-form
motions are unchanged) and, optionally, **people who react** (:mod:`mawdo.planning.people`): each
step the robot moves as its policy asked, the scripted movers follow their motions, and the people
take one step of their own model, seeing the robot or not (``visible``). Every realised position is
recorded: :meth:`SteppedWorld.realised` returns a scenario in which each person is a circle obstacle
moving along its recorded track (:class:`~mawdo.planning.world.motion.Track`, linear between
steps), so the independent checker judges what really happened, through the same interface it uses
for scripted motions.

Units are internal: pixels and time steps.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.planning.world.motion import Track
from mawdo.planning.world.scenario import CircleObstacle, Obstacle, Scenario
from mawdo.planning.world.scenario_schema import StaticMotion
from mawdo.planning.world.uncertainty import Uncertainty

#: The motion field of a mover's shape spec (its motion is the obstacle's ``Track``), shared:
#: specs are frozen, and ``model_construct`` would deep-copy the default for every mover.
_SPEC_MOTION = StaticMotion()

__all__ = ["Move", "SteppedWorld", "bounding_disc", "people_future", "static_part", "with_movers"]


@dataclass(frozen=True, eq=False)
class Move:
    """A robot's motion over one time step through corner points.

    Parameters
    ----------
    points : array_like, shape (k, 2)
        Positions passed during the step (pixels), the last one where the step ends.
    fracs : array_like, shape (k,)
        When each point is reached, as a fraction of the step, increasing, in ``(0, 1]``, the
        last one 1. Between points the robot moves in a straight line at constant speed.
    """

    points: np.ndarray
    fracs: np.ndarray

    def __post_init__(self) -> None:
        p = np.asarray(self.points, dtype=float).reshape(-1, 2)
        f = np.asarray(self.fracs, dtype=float).reshape(-1)
        if len(p) == 0 or f.shape != (len(p),) or f[-1] != 1.0 or np.any(np.diff(f) <= 0):
            raise ValueError("a move needs k >= 1 points and increasing fractions ending at 1")
        if f[0] <= 0 or not np.all(np.isfinite(p)):
            raise ValueError("move fractions must be in (0, 1] and points finite")
        object.__setattr__(self, "points", p)
        object.__setattr__(self, "fracs", f)

    @classmethod
    def straight(cls, position, velocity) -> Move:
        """The move at constant ``velocity`` (pixels per step) from ``position``."""
        end = np.asarray(position, dtype=float) + np.asarray(velocity, dtype=float)
        return cls(end[None, :], np.ones(1))

    def length(self, position) -> float:
        """Path length of the move from ``position`` (pixels)."""
        pts = np.vstack([np.asarray(position, dtype=float), self.points])
        return float(np.hypot(*np.diff(pts, axis=0).T).sum())


def with_movers(scenario: Scenario, radii, tracks, ids=None, start=None, spreads=None) -> Scenario:
    """``scenario`` plus circle obstacles moving along ``tracks``; the start may be replaced.

    The result is built without the whole-scenario checks (a person may stand on the robot's
    start): it is a model of what happens or is predicted, not a file to validate.

    Parameters
    ----------
    scenario : Scenario
        The map (its obstacles are kept, in order, before the new ones).
    radii : array_like, shape (n,)
        Radius of each mover (pixels), > 0.
    tracks : sequence of tuple (times, centres)
        Each mover's knot times (time steps, increasing) and centres there (pixels, ``(k, 2)``).
    ids : sequence of str, optional
        Names of the new obstacles (default ``mover-<i>``).
    start : array_like, shape (2,), optional
        A new robot start (pixels).
    spreads : sequence of tuple, optional
        Per mover ``(own_radius, position_sd, velocity_sd, accel_sd)`` of a predicted motion
        (:attr:`~mawdo.planning.sense.predict.Predicted.spread`): the result's
        ``uncertainty``, look-ahead from time 0. None (default): the motions are known.
    """
    radii = np.asarray(radii, dtype=float).reshape(-1)
    obstacles = list(scenario.obstacles)
    specs = list(scenario.spec.obstacles)
    for j, ((times, centres), r) in enumerate(zip(tracks, radii, strict=True)):
        centres = np.asarray(centres, dtype=float).reshape(-1, 2)
        name = ids[j] if ids is not None else f"mover-{j}"
        shape = CircleObstacle.model_construct(
            shape="circle", id=name, center=(float(centres[0, 0]), float(centres[0, 1])),
            radius=float(r), motion=_SPEC_MOTION,
        )  # fmt: skip
        motion = Track(np.asarray(times, dtype=float), centres - centres[0])
        obstacles.append(Obstacle(len(obstacles), name, shape, motion))
        specs.append(shape)
    update = {"obstacles": specs}
    if start is not None:
        update["start"] = (float(start[0]), float(start[1]))
    units = scenario.units
    first = len(scenario.obstacles)
    spread = None
    if spreads is not None and len(radii):
        cols = np.asarray(spreads, dtype=float).reshape(len(radii), 4).T
        spread = Uncertainty(np.arange(first, first + len(radii)), *cols)
    return Scenario(scenario.spec.model_copy(update=update), tuple(obstacles),
                    derived_units=None if units.is_pixels else units,
                    uncertainty=spread)  # fmt: skip


def bounding_disc(obstacle: Obstacle, t: float) -> tuple[np.ndarray, float]:
    """Centre (pixels) and radius (pixels) of a disc covering ``obstacle`` at time ``t``."""
    off = obstacle.offset(float(t))
    shape = obstacle.shape
    if isinstance(shape, CircleObstacle):
        return np.asarray(shape.center, dtype=float) + off, float(shape.radius)
    v = np.asarray(shape.vertices, dtype=float)
    c = 0.5 * (v.min(axis=0) + v.max(axis=0))
    return c + off, float(np.hypot(*(v - c).T).max())


class SteppedWorld:
    """The world of one episode: robot, scripted obstacles and reactive people.

    Parameters
    ----------
    scenario : Scenario
        Map, robot, start, goal, and the scripted obstacles (static and moving).
    people : People, optional
        Reactive agents (:mod:`mawdo.planning.people`), already placed at their starts.
    visible : bool
        Whether the people see (and avoid) the robot.
    goal_tolerance : float
        The goal counts as reached within this distance of the robot centre (pixels, >= 0).
    """

    def __init__(self, scenario, people=None, visible: bool = False, goal_tolerance=1e-9):
        if goal_tolerance < 0:
            raise ValueError(f"goal_tolerance must be >= 0 px, got {goal_tolerance!r}")
        self.scenario, self.people, self.visible = scenario, people, bool(visible)
        self.goal_tolerance = float(goal_tolerance)
        self.step_index = 0
        self.position = scenario.start.copy()
        self.velocity = np.zeros(2)
        # the robot's realised route: every corner passed, time-stamped (steps)
        self.route, self.stamps = [self.position.copy()], [0.0]
        self.trajectory = [self.position.copy()]
        n = 0 if people is None else len(people.radii)
        self._people_track = [[] for _ in range(n)]
        self._record_people()

    @classmethod
    def of(cls, scenario, seed=0, goal_tolerance: float = 1e-9) -> SteppedWorld:
        """The world of a scenario: its scripted obstacles and, from its ``[crowd]`` table,
        its people at their starts (drawing from the episode's world stream of ``seed``:
        :func:`~mawdo.streams.episode_seed_sequences`)."""
        from mawdo.planning.people.from_scenario import people_of
        from mawdo.streams import episode_seed_sequences

        rng = np.random.default_rng(episode_seed_sequences(seed)["world"])
        crowd = scenario.spec.crowd
        people = people_of(scenario, rng)
        return cls(scenario, people, bool(crowd and crowd.visible), goal_tolerance)

    def _record_people(self) -> None:
        if self.people is None:
            return
        for j, p in enumerate(self.people.positions()):
            self._people_track[j].append(np.array(p, dtype=float))

    @property
    def n_people(self) -> int:
        return len(self._people_track)

    def agents(self) -> tuple[np.ndarray, np.ndarray]:
        """Centres (pixels, ``(n, 2)``) and radii (pixels) of every moving agent now: the
        scripted movers (a polygon as its bounding disc) then the people."""
        t = float(self.step_index)
        discs = [bounding_disc(self.scenario.obstacles[i], t) for i in self.scenario.moving_indices]
        centres = [c for c, _ in discs]
        radii = [r for _, r in discs]
        if self.people is not None:
            centres.extend(np.asarray(self.people.positions(), dtype=float))
            radii.extend(np.asarray(self.people.radii, dtype=float))
        return np.asarray(centres, dtype=float).reshape(-1, 2), np.asarray(radii, dtype=float)

    def walls(self) -> list[np.ndarray]:
        """The static obstacles as polygon vertex arrays (circles as 32-gons), pixels."""
        out = []
        for i in self.scenario.static_indices:
            shape = self.scenario.obstacles[i].shape
            if isinstance(shape, CircleObstacle):
                a = np.linspace(0.0, 2.0 * np.pi, 32, endpoint=False)
                ring = np.column_stack([np.cos(a), np.sin(a)]) * shape.radius
                out.append(np.asarray(shape.center) + ring)
            else:
                out.append(np.asarray(shape.vertices, dtype=float))
        return out

    def at_goal(self) -> bool:
        return bool(np.hypot(*(self.scenario.goal - self.position)) <= self.goal_tolerance)

    def step(self, action) -> None:
        """Advance one time step: the robot drives ``action`` (a velocity, pixels per step, or
        a :class:`Move`), longer than the robot's speed allows is scaled down to it."""
        move = action if isinstance(action, Move) else Move.straight(self.position, action)
        speed = self.scenario.robot_speed
        length = move.length(self.position)
        if length > speed * (1.0 + 1e-9):  # a policy cannot drive faster than the robot
            pts = np.vstack([self.position, move.points])
            move = Move((pts[1:] - self.position) * (speed / length) + self.position, move.fracs)
        if self.people is not None:  # everyone acts on the same moment's state (as CrowdNav)
            r = self.scenario.robot_radius
            self.people.step(self.position, self.velocity, r, self.visible)
        start = self.position
        for p, f in zip(move.points, move.fracs, strict=True):
            self.route.append(p.copy())
            self.stamps.append(self.step_index + float(f))
        self.position = move.points[-1].copy()
        self.velocity = self.position - start
        self.trajectory.append(self.position.copy())
        self.step_index += 1
        self._record_people()

    def realised(self) -> Scenario:
        """The scenario as it happened: the scripted obstacles unchanged, then one circle per
        person moving along its recorded centres (linear between steps)."""
        if not self._people_track:
            return self.scenario
        times = np.arange(self.step_index + 1, dtype=float)
        tracks = [(times, np.array(tr)) for tr in self._people_track]
        ids = [f"person-{j}" for j in range(self.n_people)]
        return with_movers(self.scenario, self.people.radii, tracks, ids)


def static_part(scenario: Scenario) -> Scenario:
    """The scenario without its moving obstacles: the map a robot knows beforehand."""
    keep = scenario.static_indices
    if len(keep) == len(scenario.obstacles):
        return scenario
    obstacles = tuple(
        Obstacle(j, scenario.obstacles[i].id, scenario.obstacles[i].shape,
                 scenario.obstacles[i].motion)
        for j, i in enumerate(keep)
    )  # fmt: skip
    specs = [scenario.spec.obstacles[i] for i in keep]
    units = None if scenario.units.is_pixels else scenario.units
    spec = scenario.spec.model_copy(update={"obstacles": specs})
    return Scenario(spec, obstacles, derived_units=units)


def people_future(scenario: Scenario, people, steps: int) -> Scenario:
    """``scenario`` plus every person's next ``steps`` steps as they walk without the robot
    (it is invisible to them): their exact future when they do not see it, an estimate when
    they do. ``people`` is stepped (pass a fresh copy)."""
    far = np.array([-1e9, -1e9])
    track = [np.array(people.positions(), dtype=float)]
    for _ in range(int(steps)):
        people.step(far, np.zeros(2), scenario.robot_radius, False)
        track.append(np.array(people.positions(), dtype=float))
    track = np.stack(track, axis=1)  # (people, steps + 1, 2)
    times = np.arange(int(steps) + 1, dtype=float)
    ids = [f"person-{j}" for j in range(len(track))]
    return with_movers(scenario, people.radii, [(times, t) for t in track], ids)
