"""The world runner: a stepped world driven by any policy (our planner, every baseline).

Each step the sensor reads the world, the policy decides, the world steps (the one run loop,
:func:`~mawdo.planning.run.loop.run_loop`, that the planner's own run uses too); at the end the
independent checker judges the robot's realised route against the realised trajectories of every
agent (:meth:`~mawdo.planning.world.stepped.SteppedWorld.realised`) and
:func:`~mawdo.planning.judge.fault.blame` splits its collisions into robot-caused and other ones.
"""

from __future__ import annotations

import time
import warnings

import numpy as np

from mawdo.planning.run.loop import GOAL_REACHED, run_loop
from mawdo.planning.run.result import PlanResult, Replan
from mawdo.planning.sense.reading import Reading
from mawdo.streams import episode_seed_sequences

__all__ = ["EpisodeRun", "perfect_reading", "read_world", "run_episode"]

LIMIT_REASON = "step limit reached before the goal"


def perfect_reading(world) -> Reading:
    """What an ideal sensor reports: every moving agent, exactly (pixels)."""
    centres, radii = world.agents()
    return Reading(
        world.step_index, world.position, world.velocity, world.scenario.goal, centres, radii
    )


def read_world(world, sensor, rng) -> Reading:
    """The reading of ``world`` at its current step: every agent exactly without a sensor (no
    draw), else ``sensor``'s reading drawn from ``rng``."""
    if sensor is None:
        return perfect_reading(world)
    centres, radii = world.agents()
    args = (world.position, world.velocity, world.scenario.goal, centres, radii, world.walls(), rng)
    return sensor.read(world.step_index, *args)


def _record(step: int, position, latency: float, policy) -> Replan:
    """A decision's record: the policy's wall time, and its plan's waypoints when it shows
    them (a ``waypoints`` attribute, pixels; for the figures' current plan)."""
    way = getattr(policy, "waypoints", None)
    way = np.zeros((0, 2)) if way is None else np.asarray(way, dtype=float).reshape(-1, 2)
    return Replan(step, np.array(position), way, np.nan, np.nan, 0, latency, 0, np.zeros(0))


def _warn_if_tracker_trusts_more(policy, sensor) -> None:
    """Warn when ``policy``'s tracker assumes less position noise than ``sensor`` adds: it
    would take noisy readings at their word (jittering velocities, margins too thin)."""
    noise = getattr(getattr(policy, "tracker", None), "noise", None)
    if sensor is None or noise is None or not noise < sensor.noise:
        return
    warnings.warn(
        f"the policy's tracker assumes position noise {noise:g} px but the sensor adds "
        f"{sensor.noise:g} px: pass tracker=Tracker.for_sensor(sensor) to the policy "
        "(mawdo.planning.Tracker)",
        UserWarning,
        stacklevel=3,
    )


def run_episode(
    world, policy, max_steps: int, seed=0, sensor=None, name: str = "policy", config=None,
    progress=None, known=None,
) -> PlanResult:  # fmt: skip
    """Drive ``policy`` in ``world`` until the goal, the step limit, or a policy's stop.

    Parameters
    ----------
    world : SteppedWorld
        A fresh world (step 0).
    policy : Policy
        ``reset(scenario, seed)`` then ``act(reading)`` each step
        (:class:`~mawdo.planning.sense.reading.Policy`).
    max_steps : int
        Step limit (time steps), >= 1; reaching it is a timeout.
    seed : int
        The episode's seed (the sensor's and the policy's streams derive from it:
        :func:`~mawdo.streams.episode_seed_sequences`).
    sensor : Sensor, optional
        ``None``: a perfect sensor (every agent, exact positions).
    name : str
        What the result's ``algorithm`` field calls the policy.
    config : PlannerConfig, optional
        Stored in the result (the policy's settings, when it has them).
    progress : callable, optional
        ``progress(step, max_steps, decisions)`` before each step.
    known : Scenario, optional
        What the policy is told at reset (default: the world's scenario, whose moving
        obstacles an ``observed`` policy ignores).

    Returns
    -------
    PlanResult
        ``scenario`` is the realised one; ``robot_caused`` and ``other_collisions`` are set.

    Notes
    -----
    Leaving the map counts as robot-caused: only the robot's motion can do it.
    """
    if int(max_steps) < 1:
        raise ValueError(f"max_steps must be >= 1, got {max_steps!r}")
    streams = episode_seed_sequences(seed)
    rng = np.random.default_rng(streams["sensor"])
    policy.reset(world.scenario if known is None else known, streams["policy"])
    _warn_if_tracker_trusts_more(policy, sensor)
    decisions: list[Replan] = []

    def decide(step: int):
        reading = read_world(world, sensor, rng)
        t0 = time.perf_counter()
        action = policy.act(reading)
        decisions.append(_record(step, world.position, time.perf_counter() - t0, policy))
        return action

    def world_step(action) -> None:  # a stepped world never ends an episode by itself
        world.step(action)

    # the world runner never reported the limit step to ``progress`` (the planner's loop does)
    reason = run_loop(max_steps, world.at_goal, decide, world_step, LIMIT_REASON, progress,
                      decisions.__len__, progress_at_limit=False)  # fmt: skip
    return _judged(world, policy, reason, decisions, name, seed, config)


def _judged(world, policy, reason: str, decisions, name: str, seed, config) -> PlanResult:
    """The episode's result: the checker's verdict on the realised route, its collisions split
    by :func:`~mawdo.planning.judge.fault.blame`, and the kinematic check of the driven
    trajectory against the policy's ``limits`` when it has them."""
    from mawdo.planning.judge.check import check_trajectory
    from mawdo.planning.judge.fault import blame

    realised = world.realised()
    route, stamps = np.array(world.route), np.array(world.stamps)
    rep = check_trajectory(route, realised, times=stamps)
    mine, theirs = blame(route, stamps, realised, rep.collisions)
    kin = _kinematics(world, policy)
    reached = reason == GOAL_REACHED
    if reached and not rep.ok:
        reason = f"goal reached but the route collides ({rep.hits} checker hits: {rep.describe()})"
    elif reached and kin is not None and not kin.ok:
        reason = f"goal reached but the motion breaks the kinematic limits ({kin.describe()})"
        reached = False
    # the first decision is the plan, the rest replans (PlanResult.latencies skips the first)
    return PlanResult(
        scenario=realised, algorithm=name, seed=seed, config=config,
        trajectory=np.array(world.trajectory), success=reached and rep.ok, reason=reason,
        replans=decisions, route=route, route_times=stamps, collision_free=bool(rep.ok),
        min_clearance=float(rep.min_clearance), hits=int(rep.hits),
        robot_caused=len(mine) + len(rep.border), other_collisions=len(theirs), check=rep,
        kinematic_violations=0 if kin is None else kin.count,
    )  # fmt: skip


def _kinematics(world, policy):
    """The independent kinematic check of the driven trajectory against the policy's
    ``limits`` (:class:`~mawdo.planning.safety.kinematics.Limits`), or None when it has none."""
    limits = getattr(policy, "limits", None)
    if limits is None:
        return None
    from mawdo.planning.judge.kincheck import check_kinematics

    traj = np.array(world.trajectory)
    return check_kinematics(traj, limits.speed, limits.accel, limits.turn)


class EpisodeRun:
    """A stepped episode set up to run, with the interface of a planner's
    :class:`~mawdo.planning.run.execute.Run` that the command line uses (``step_limit``,
    ``estimate_seconds``, ``execute(progress)``).

    Parameters
    ----------
    scenario : Scenario
        The world: map, scripted obstacles and, from its ``[crowd]`` table, people.
    policy : Policy
        What drives the robot.
    seed : int
        The episode's seed (the people's, the sensor's and the policy's streams).
    max_steps : int
        Step limit, >= 1.
    sensor : Sensor, optional
        ``None``: every agent, exactly.
    name : str
        The result's ``algorithm``.
    config : PlannerConfig, optional
        Stored in the result.
    """

    def __init__(self, scenario, policy, seed, max_steps: int, sensor=None, name="policy",
                 config=None):  # fmt: skip
        from mawdo.planning.world.stepped import SteppedWorld

        self.scenario, self.policy, self.seed, self.max_steps = scenario, policy, seed, max_steps
        self.sensor, self.name, self.config = sensor, name, config
        self.known = None  # what the policy is told at reset (None: the scenario)
        self.world = SteppedWorld.of(scenario, seed)

    def step_limit(self) -> tuple[int, int]:
        """The step limit, twice (it is given, not derived)."""
        return self.max_steps, self.max_steps

    def estimate_seconds(self, steps: int) -> float:
        """Unknown before the run: 0 (no warning is printed)."""
        return 0.0

    def execute(self, progress=None) -> PlanResult:
        """Run the episode (:func:`run_episode`)."""
        return run_episode(self.world, self.policy, self.max_steps, self.seed, self.sensor,
                           self.name, self.config, progress, self.known)  # fmt: skip
