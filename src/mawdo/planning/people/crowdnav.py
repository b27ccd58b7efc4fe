"""CrowdNav's benchmark scenes, circle crossing and square crossing, in pixels and time steps.

The people are placed exactly as CrowdNav does (``crowd_sim/envs/crowd_sim.py`` of
vita-epfl/CrowdNav, ``env.config``): radius 0.3 m, preferred speed 1 m/s, start and goal drawn by
rejection so that each person keeps ``r + r' + 0.2 m`` (the discomfort distance) from the robot's
and the earlier people's start and goal; circle crossing starts on the 4 m circle plus a uniform
noise of width ``v_pref * 1 s`` per axis and walks to the antipodal point; square crossing
starts on one side of the 10 m square and walks to a random point on the other. The robot
(radius 0.3 m, 1 m/s) goes from (0, -4) to (0, 4) m within 25 s.

A person who reaches its goal picks a new one as CrowdNav++ does (``end_goal_changing``,
Shuijing725/CrowdNav_Prediction_AttnGraph): a fresh point drawn like a start (circle), or on the
other side of the square (square crossing, our analogue); ``goal_changing=False`` keeps the
original CrowdNav behaviour (people stop at their goals). Departures from CrowdNav:
docs/deviations.md#d-crowdnav-scenes.

Pixels: the map is a ``2 half_size`` square box (14 m x 14 m by default, 280 x 280 px at
0.05 m/px) with CrowdNav's origin at its centre, so every start, goal and new goal lies at least
2 m inside it (circle: within 4 + 0.5 sqrt(2) m of the centre; square: within 5 m per axis).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from mawdo.planning.people.base import KeepGoal, People
from mawdo.planning.people.orca import OrcaParams, OrcaPeople
from mawdo.planning.people.social_force import SocialForceParams, SocialForcePeople
from mawdo.planning.world.scenario import Scenario, scenario_from_dict
from mawdo.planning.world.units import Units

__all__ = [
    "CircleGoals",
    "CrowdScene",
    "SquareGoals",
    "circle_crossing",
    "square_crossing",
]

#: CrowdNav's configuration (metres, seconds): env.config of vita-epfl/CrowdNav.
HUMAN_RADIUS = 0.3
HUMAN_SPEED = 1.0
ROBOT_RADIUS = 0.3
ROBOT_SPEED = 1.0
CIRCLE_RADIUS = 4.0
SQUARE_WIDTH = 10.0
DISCOMFORT_DIST = 0.2
TIME_LIMIT = 25.0
#: Rejection draws for one new goal before the person keeps its goal for this step (CrowdNav
#: draws forever).
MAX_TRIES = 10_000

MODELS = ("orca", "social_force")


def _clear(p, r, agents_xy, agents_r, gap) -> bool:
    if not len(agents_xy):
        return True
    d = np.hypot(agents_xy[:, 0] - p[0], agents_xy[:, 1] - p[1])
    return bool(np.all(d >= r + agents_r + gap))


def circle_people(n: int, random: Callable[[], float]) -> tuple[np.ndarray, np.ndarray]:
    """CrowdNav's ``generate_circle_crossing_human`` for ``n`` people (metres).

    ``random()`` gives uniform draws in [0, 1) in CrowdNav's order. Returns starts and goals,
    each ``(n, 2)``.
    """
    starts = [np.array([0.0, -CIRCLE_RADIUS])]  # the robot comes first
    goals = [np.array([0.0, CIRCLE_RADIUS])]
    radii = [ROBOT_RADIUS]
    for _ in range(n):
        while True:
            angle = random() * np.pi * 2
            px_noise = (random() - 0.5) * HUMAN_SPEED
            py_noise = (random() - 0.5) * HUMAN_SPEED
            p = np.array(
                [CIRCLE_RADIUS * np.cos(angle) + px_noise, CIRCLE_RADIUS * np.sin(angle) + py_noise]
            )
            r = np.array(radii)
            if _clear(p, HUMAN_RADIUS, np.array(starts), r, DISCOMFORT_DIST) and _clear(
                p, HUMAN_RADIUS, np.array(goals), r, DISCOMFORT_DIST
            ):
                break
        starts.append(p)
        goals.append(-p)
        radii.append(HUMAN_RADIUS)
    return np.array(starts[1:]).reshape(n, 2), np.array(goals[1:]).reshape(n, 2)


def square_people(n: int, random: Callable[[], float]) -> tuple[np.ndarray, np.ndarray]:
    """CrowdNav's ``generate_square_crossing_human`` for ``n`` people (metres); see
    :func:`circle_people`."""
    starts = [np.array([0.0, -CIRCLE_RADIUS])]
    goals = [np.array([0.0, CIRCLE_RADIUS])]
    radii = [ROBOT_RADIUS]
    for _ in range(n):
        sign = -1 if random() > 0.5 else 1
        r = np.array(radii)
        while True:
            p = np.array([random() * SQUARE_WIDTH * 0.5 * sign, (random() - 0.5) * SQUARE_WIDTH])
            if _clear(p, HUMAN_RADIUS, np.array(starts), r, DISCOMFORT_DIST):
                break
        while True:
            g = np.array([random() * SQUARE_WIDTH * 0.5 * -sign, (random() - 0.5) * SQUARE_WIDTH])
            if _clear(g, HUMAN_RADIUS, np.array(goals), r, DISCOMFORT_DIST):
                break
        starts.append(p)
        goals.append(g)
        radii.append(HUMAN_RADIUS)
    return np.array(starts[1:]).reshape(n, 2), np.array(goals[1:]).reshape(n, 2)


def _others(i: int, people: People, robot_position, robot_radius, robot_goal):
    keep = np.arange(len(people)) != i
    xy = np.vstack([robot_position, people.positions()[keep]])
    goals = np.vstack([robot_goal, people.goals[keep]])
    radii = np.append(robot_radius, people.radii[keep])
    return xy, goals, radii


def _first_clear(draw, people, i, agents_xy, agents_r, gap, batch: int = 64):
    """The first of the candidate goals ``draw(k) -> (k, 2)`` (tries in order, drawn ``batch``
    at a time) that keeps ``r_i + r + gap`` from every agent point and whose disc is free; None
    after ``MAX_TRIES``. Drawing in batches consumes whole batches of random numbers, so the goals
    that follow differ from one-at-a-time draws, but the same seed gives the same goals."""
    r = people.radii[i]
    for _ in range(MAX_TRIES // batch):
        cand = draw(batch)
        d = np.hypot(*(cand[:, None, :] - agents_xy[None, :, :]).transpose(2, 0, 1))
        ok = np.all(d >= r + agents_r + gap, axis=1)
        for k in np.flatnonzero(ok):
            if people.free(cand[k], [r])[0]:
                return cand[k]
    return None


@dataclass(frozen=True, eq=False)
class CircleGoals:
    """CrowdNav++'s ``update_human_goal`` (pixels): with probability ``change_chance`` a person
    who arrived draws a point on the circle plus noise, kept only at ``r + r' + discomfort``
    from every other agent's position and goal (the robot's included) and inside the free map.

    Parameters
    ----------
    centre : numpy.ndarray, shape (2,)
        Circle centre (pixels).
    radius : float
        Circle radius (pixels).
    noise_time : float
        Noise width per axis is ``preferred_speed * noise_time`` (time steps; CrowdNav: 1 s).
    unit_noise : float
        Noise width for a person of preferred speed 0 (pixels; CrowdNav: 1 m).
    discomfort : float
        Extra gap (pixels).
    robot_goal : numpy.ndarray, shape (2,)
        Pixels.
    change_chance : float
        In [0, 1]; CrowdNav++ uses 1.
    """

    centre: np.ndarray
    radius: float
    noise_time: float
    unit_noise: float
    discomfort: float
    robot_goal: np.ndarray
    change_chance: float = 1.0

    def new_goal(self, i, people, robot_position, robot_radius, rng):
        if not rng.random() <= self.change_chance:
            return None
        xy, goals, radii = _others(i, people, robot_position, robot_radius, self.robot_goal)
        v = people.preferred_speed[i] * self.noise_time
        width = self.unit_noise if v == 0 else v

        def draw(k):
            u = rng.random((k, 3))  # (angle, x noise, y noise) per try, CrowdNav's order
            angle = u[:, 0] * np.pi * 2
            ring = self.radius * np.column_stack([np.cos(angle), np.sin(angle)])
            return self.centre + ring + (u[:, 1:] - 0.5) * width

        return _first_clear(
            draw, people, i, np.vstack([xy, goals]), np.tile(radii, 2), self.discomfort
        )


@dataclass(frozen=True, eq=False)
class SquareGoals:
    """New goal on the other side of the square (pixels), drawn as CrowdNav draws a square
    crossing goal: ``x`` uniform over the half the person is not in, ``y`` uniform over the
    width, kept only at ``r + r' + discomfort`` from every other agent's goal (the robot's
    included) and inside the free map.

    Parameters
    ----------
    centre : numpy.ndarray, shape (2,)
        Square centre (pixels).
    width : float
        Square side (pixels).
    discomfort : float
        Extra gap (pixels).
    robot_goal : numpy.ndarray, shape (2,)
        Pixels.
    """

    centre: np.ndarray
    width: float
    discomfort: float
    robot_goal: np.ndarray

    def new_goal(self, i, people, robot_position, robot_radius, rng):
        _, goals, radii = _others(i, people, robot_position, robot_radius, self.robot_goal)
        side = 1.0 if people.positions()[i, 0] >= self.centre[0] else -1.0

        def draw(k):
            u = rng.random((k, 2))  # (x, y) per try, CrowdNav's order
            return self.centre + np.column_stack(
                [u[:, 0] * self.width * 0.5 * -side, (u[:, 1] - 0.5) * self.width]
            )

        return _first_clear(draw, people, i, goals, radii, self.discomfort)


def _frozen(a) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class CrowdScene:
    """One CrowdNav episode in pixels and time steps.

    Attributes
    ----------
    scenario : Scenario
        The static world: the box map (no obstacles), the robot's start, goal, radius and speed
        in pixels, and the seed.
    rule : str
        ``"circle_crossing"`` or ``"square_crossing"``.
    model : str
        ``"orca"`` or ``"social_force"``: how the people walk.
    positions, goals : numpy.ndarray, shape (n, 2)
        People's starts and first goals (pixels).
    radii, preferred_speed : numpy.ndarray, shape (n,)
        Pixels and pixels per time step.
    res : float
        Metres per pixel.
    dt : float
        Seconds per time step.
    time_limit_steps : int
        CrowdNav's 25 s in time steps.
    origin : numpy.ndarray, shape (2,)
        Pixel position of CrowdNav's origin (the box centre).
    visible : bool
        Whether the people see the robot.
    goal_changing : bool
        Whether a person who arrives picks a new goal.
    """

    scenario: Scenario
    rule: str
    model: str
    positions: np.ndarray
    goals: np.ndarray
    radii: np.ndarray
    preferred_speed: np.ndarray
    res: float
    dt: float
    time_limit_steps: int
    origin: np.ndarray
    visible: bool
    goal_changing: bool

    @property
    def seed(self) -> int:
        return self.scenario.seed

    def to_metres(self, px_points) -> np.ndarray:
        """Pixel points (..., 2) to CrowdNav's metre frame."""
        return (np.asarray(px_points, dtype=float) - self.origin) * self.res

    def to_pixels(self, m_points) -> np.ndarray:
        """CrowdNav metre points (..., 2) to pixels."""
        return self.origin + np.asarray(m_points, dtype=float) / self.res

    def goal_policy(self):
        """What an arriving person does (see :class:`CircleGoals`, :class:`SquareGoals`)."""
        if not self.goal_changing:
            return KeepGoal()
        gap = DISCOMFORT_DIST / self.res
        if self.rule == "circle_crossing":
            return CircleGoals(
                self.origin,
                CIRCLE_RADIUS / self.res,
                1.0 / self.dt,
                1.0 / self.res,
                gap,
                self.scenario.goal,
            )
        return SquareGoals(self.origin, SQUARE_WIDTH / self.res, gap, self.scenario.goal)

    def make_people(self, rng: np.random.Generator | None = None) -> People:
        """Build the scene's people at their starts.

        Parameters
        ----------
        rng : numpy.random.Generator, optional
            Draws new goals; default: a stream derived from the scene's seed (spawn key 1).
        """
        if rng is None:
            rng = np.random.default_rng(np.random.SeedSequence(self.seed, spawn_key=(1,)))
        kw = dict(
            bounds=(self.scenario.width, self.scenario.height),
            goal_policy=self.goal_policy(),
            rng=rng,
            arrival_time=1.0 / self.dt,  # CrowdNav slows down within v_pref * 1 s
        )
        if self.model == "orca":
            params = OrcaParams.from_metres(self.res, self.dt)
            return OrcaPeople(
                self.positions, self.goals, self.radii, self.preferred_speed, params=params, **kw
            )
        params = SocialForceParams.from_metres(self.res, self.dt)
        return SocialForcePeople(
            self.positions, self.goals, self.radii, self.preferred_speed, params=params, **kw
        )


def _scene(rule, n_people, seed, visible, res, dt, model, goal_changing, half_size):
    if not (isinstance(n_people, int | np.integer) and not isinstance(n_people, bool)):
        raise ValueError(f"n_people={n_people!r} must be an int >= 0")
    if n_people < 0:
        raise ValueError(f"n_people={n_people!r} must be >= 0")
    if not (isinstance(seed, int | np.integer) and 0 <= seed < 2**63):
        raise ValueError(f"seed={seed!r} must be an int in [0, 2**63)")
    if model not in MODELS:
        raise ValueError(f"model={model!r} must be one of {', '.join(MODELS)}")
    for name, v in (("res", res), ("dt", dt), ("half_size", half_size)):
        if not (np.isfinite(v) and v > 0):
            raise ValueError(f"{name}={v!r} must be > 0")
    reach = SQUARE_WIDTH / 2 if rule == "square_crossing" else CIRCLE_RADIUS + 0.5 * HUMAN_SPEED
    if half_size < reach + HUMAN_RADIUS:
        raise ValueError(
            f"half_size={half_size!r} m leaves people's starts and goals outside the map; "
            f"use half_size >= {reach + HUMAN_RADIUS:g} m"
        )
    rng = np.random.default_rng(np.random.SeedSequence(int(seed), spawn_key=(0,)))
    place = circle_people if rule == "circle_crossing" else square_people
    starts, goals = place(int(n_people), rng.random)
    side = 2 * half_size / res
    origin = np.array([side / 2, side / 2])
    spec = {
        "schema_version": 1,
        "name": f"crowdnav-{rule.replace('_', '-')}-{n_people}",
        "description": f"CrowdNav {rule} with {n_people} {model} people (CrowdNav origin at "
        f"the box centre, {res:g} m/px, {dt:g} s/step)",
        "seed": int(seed),
        "width": side,
        "height": side,
        "start": (origin + np.array([0.0, -CIRCLE_RADIUS]) / res).tolist(),
        "goal": (origin + np.array([0.0, CIRCLE_RADIUS]) / res).tolist(),
        "robot": {"radius": ROBOT_RADIUS / res, "speed": ROBOT_SPEED * dt / res},
    }
    # a pixel scenario that reads and draws in metres and seconds (CrowdNav's units)
    scenario = replace(scenario_from_dict(spec), derived_units=Units("m", float(dt), float(res)))
    return CrowdScene(
        scenario=scenario,
        rule=rule,
        model=model,
        positions=_frozen(origin + starts / res),
        goals=_frozen(origin + goals / res),
        radii=_frozen(np.full(n_people, HUMAN_RADIUS / res)),
        preferred_speed=_frozen(np.full(n_people, HUMAN_SPEED * dt / res)),
        res=float(res),
        dt=float(dt),
        time_limit_steps=int(round(TIME_LIMIT / dt)),
        origin=_frozen(origin),
        visible=bool(visible),
        goal_changing=bool(goal_changing),
    )


def circle_crossing(
    n_people: int,
    seed: int,
    visible: bool = False,
    res: float = 0.05,
    dt: float = 0.25,
    model: str = "orca",
    *,
    goal_changing: bool = True,
    half_size: float = 7.0,
) -> CrowdScene:
    """CrowdNav's circle crossing scene.

    Parameters
    ----------
    n_people : int
        Number of people, >= 0.
    seed : int
        Seeds the placement (spawn key 0) and, by default, the new goals (spawn key 1).
    visible : bool
        Whether people see the robot (CrowdNav's robot is invisible by default).
    res : float
        Metres per pixel, > 0.
    dt : float
        Seconds per time step, > 0 (CrowdNav: 0.25).
    model : str
        ``"orca"`` or ``"social_force"``.
    goal_changing : bool
        Whether a person who arrives picks a new goal (CrowdNav++), else it stays.
    half_size : float
        Half the side of the square map (metres).

    Returns
    -------
    CrowdScene
    """
    return _scene(
        "circle_crossing", n_people, seed, visible, res, dt, model, goal_changing, half_size
    )


def square_crossing(
    n_people: int,
    seed: int,
    visible: bool = False,
    res: float = 0.05,
    dt: float = 0.25,
    model: str = "orca",
    *,
    goal_changing: bool = True,
    half_size: float = 7.0,
) -> CrowdScene:
    """CrowdNav's square crossing scene; parameters as :func:`circle_crossing`."""
    return _scene(
        "square_crossing", n_people, seed, visible, res, dt, model, goal_changing, half_size
    )
