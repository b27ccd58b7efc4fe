"""What one step of the environment did: collision, blame, separation, and the reward.

The collision verdict is the independent checker's
(:func:`~mawdo.planning.judge.check.check_trajectory`) on the step just driven, against the
world's realised scenario, and the blame is :func:`~mawdo.planning.judge.fault.blame`'s: the
same verdicts :func:`~mawdo.planning.run.episode.run_episode` reaches over a whole episode.
Building the realised scenario grows with the episode's length, so each step first computes
the people's clearances in closed form (:func:`disc_clearance`, exact for discs that move
linearly during the step, as the realised tracks do) and calls the checker on the realised
scenario only when one of them comes within :data:`SUSPECT_PX` of contact; static walls, the
scripted movers and the map's border are checked by the checker on the world's own scenario
every step.

The reward is CrowdNav's (vita-epfl/CrowdNav, ``crowd_sim/envs/crowd_sim.py``, ``step``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.planning.judge.check import DEFAULT_TOL, check_trajectory
from mawdo.planning.judge.fault import blame

__all__ = ["SUSPECT_PX", "Outcome", "Rewards", "crowdnav_reward", "disc_clearance", "judge_step"]

#: A person whose closed-form clearance during the step is below this (pixels) sends the step
#: to the checker on the realised scenario; far above any rounding difference between the two.
SUSPECT_PX = 1e-6


def disc_clearance(robot0, robot1, people0, people1, radius: float, radii) -> np.ndarray:
    """Smallest surface-to-surface distance between the robot and each person during a step.

    Both move in straight lines at constant speed from their ``0`` to their ``1`` positions, so
    the robot's position relative to a person moves along the segment ``a -> b``
    (``a = robot0 - people0``, ``b = robot1 - people1``) and the smallest centre distance is the
    distance from the origin to that segment.

    Parameters
    ----------
    robot0, robot1 : array_like, shape (2,)
        Robot centre at the start and end of the step (pixels).
    people0, people1 : array_like, shape (n, 2)
        People's centres at the start and end of the step (pixels).
    radius : float
        Robot radius (pixels).
    radii : array_like, shape (n,)
        People's radii (pixels).

    Returns
    -------
    numpy.ndarray, shape (n,)
        Clearance (pixels; negative: the discs overlap at some moment of the step).
    """
    a = np.asarray(robot0, float).reshape(1, 2) - np.asarray(people0, float).reshape(-1, 2)
    b = np.asarray(robot1, float).reshape(1, 2) - np.asarray(people1, float).reshape(-1, 2)
    d = b - a
    dd = np.einsum("ij,ij->i", d, d)
    u = np.clip(-np.einsum("ij,ij->i", a, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    closest = a + u[:, None] * d
    return np.hypot(closest[:, 0], closest[:, 1]) - radius - np.asarray(radii, float)


@dataclass(frozen=True)
class Outcome:
    """One step's verdict.

    Attributes
    ----------
    collision : bool
        The robot's disc met an agent, a wall or the map's border during the step.
    robot_caused : bool
        At least one of those collisions was the robot's doing (leaving the map always is).
    separation : float
        Smallest surface-to-surface distance to any moving agent during the step (pixels;
        ``inf`` without agents).
    """

    collision: bool
    robot_caused: bool
    separation: float


def judge_step(world, people0) -> Outcome:
    """The verdict on the step ``world`` has just taken.

    Parameters
    ----------
    world : SteppedWorld
        After its step (the robot drove a velocity: one straight segment).
    people0 : numpy.ndarray, shape (n, 2)
        The people's centres before the step (pixels).
    """
    route = np.array(world.route[-2:])
    times = np.array(world.stamps[-2:])
    sc = world.scenario
    sep = np.inf
    suspect = False
    if world.people is not None and len(people0):
        c = disc_clearance(route[0], route[1], people0, world.people.positions(),
                           sc.robot_radius, world.people.radii)  # fmt: skip
        sep = float(c.min())
        suspect = sep < SUSPECT_PX
    own = check_trajectory(route, sc, times=times)
    moving = sc.moving_indices
    if moving:
        sep = min(sep, float(own.clearance[:, moving].min()))
    if not suspect and own.ok:
        return Outcome(False, False, sep)
    realised = world.realised()
    rep = check_trajectory(route, realised, times=times, tol=DEFAULT_TOL)
    if rep.ok:
        return Outcome(False, False, sep)
    mine, _ = blame(route, times, realised, rep.collisions)
    return Outcome(True, bool(mine) or bool(rep.border), sep)


@dataclass(frozen=True)
class Rewards:
    """The reward's weights (CrowdNav's ``env.config``: ``success_reward = 1``,
    ``collision_penalty = -0.25``, ``discomfort_dist = 0.2``, ``discomfort_penalty_factor =
    0.5``).

    Attributes
    ----------
    success_reward : float
        Reward of the step that reaches the goal.
    collision_penalty : float
        Reward of the step that collides (negative to penalise).
    discomfort_dist : float
        Separation (metres) below which a step is penalised, >= 0.
    discomfort_penalty_factor : float
        Penalty per metre inside ``discomfort_dist`` and per second of the step, >= 0.
    """

    success_reward: float = 1.0
    collision_penalty: float = -0.25
    discomfort_dist: float = 0.2
    discomfort_penalty_factor: float = 0.5


def crowdnav_reward(collision: bool, success: bool, separation: float, dt: float,
                    w: Rewards) -> float:  # fmt: skip
    """CrowdNav's step reward.

    ``collision_penalty`` on a collision, else ``success_reward`` at the goal, else
    ``(d - discomfort_dist) * discomfort_penalty_factor * dt`` when the separation ``d``
    (metres) is below ``discomfort_dist`` (``dt`` the step in seconds), else 0.
    """
    if collision:
        return float(w.collision_penalty)
    if success:
        return float(w.success_reward)
    if separation < w.discomfort_dist:
        return float((separation - w.discomfort_dist) * w.discomfort_penalty_factor * dt)
    return 0.0
