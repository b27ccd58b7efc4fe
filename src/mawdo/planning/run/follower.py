"""The oracle follower: the baseline a robotics engineer would pick.

Every step it follows the exact shortest path (:mod:`mawdo.planning.guide.oracle`) on the obstacles
frozen where they are at that instant, ignoring their motion. Deterministic (no seed). When the
frozen map leaves no path (a moving obstacle covers the robot's inflated position or blocks
every route) the robot waits for a step.
"""

from __future__ import annotations

import time

import numpy as np

from mawdo.planning.guide.oracle import scenario_optimum
from mawdo.planning.run.config import PlannerConfig, resolve_scenario, step_limit, step_limit_note
from mawdo.planning.run.loop import GOAL_TOL, run_loop
from mawdo.planning.run.result import Drive, PlanResult, Replan
from mawdo.planning.world.path import advance

__all__ = ["ORACLE_FOLLOWER", "follow_oracle"]

ORACLE_FOLLOWER = "oracle_follower"


def follow_oracle(scenario, max_steps: int | None = None, reach: float | None = None) -> PlanResult:
    """Follow the exact shortest path on the obstacles frozen at each step.

    Parameters
    ----------
    scenario : Scenario or str
        A scenario or the name of a built-in one.
    max_steps : int, optional
        Step limit; default the automatic rule every planner uses
        (:func:`~mawdo.planning.run.config.step_limit`).
    reach : float, optional
        Length of a route around the static obstacles (px) for that rule; default the exact
        static optimum.

    Returns
    -------
    PlanResult
        One :class:`~mawdo.planning.run.result.Replan` per step (no optimizer: ``nfev`` 0), judged
        by the independent checker like every run.
    """
    sc = resolve_scenario(scenario)
    v = sc.robot_speed
    if reach is None:
        opt = scenario_optimum(sc, static_only=True)
        reach = opt.length if opt.reachable else 0.0
    limit, rule = step_limit(max_steps, sc.straight_line_length(), reach, v)
    run = _Following(sc)
    limit_reason = step_limit_note(max_steps, limit, rule)
    reason = run_loop(limit, run.at_goal, run.decide, run.step, limit_reason)
    return run.drive.result(
        reason, scenario=sc, algorithm=ORACLE_FOLLOWER, seed=0, config=PlannerConfig(),
        replans=run.replans,
    )  # fmt: skip


class _Following:
    """The follower as a decision and the world's step, for
    :func:`~mawdo.planning.run.loop.run_loop`: its world is the scenario (it knows the
    obstacles' motion, and uses only where they are now)."""

    def __init__(self, sc) -> None:
        self.sc, self.pos = sc, sc.start.copy()
        self.drive, self.replans = Drive(self.pos), []

    def at_goal(self) -> bool:
        return bool(np.hypot(*(self.sc.goal - self.pos)) <= GOAL_TOL)

    def decide(self, step: int):
        """The move of ``step``: ``(step, position, passed, frac)`` (Drive.move's arguments)."""
        pos, rep, passed, frac = _step(self.sc, self.pos, step)
        self.replans.append(Replan(step=step, position=self.pos.copy(), **rep))
        return step, pos, passed, frac

    def step(self, move) -> None:
        self.drive.move(*move)
        self.pos = move[1]


def _step(sc, pos, step: int):
    """One step along the frozen map's optimum (a wait where there is none): the new
    position, the replan's record and the route vertices passed."""
    t0 = time.perf_counter()
    opt = scenario_optimum(sc, t=float(step), static_only=False, start=pos)
    latency = time.perf_counter() - t0
    passed, frac = (), ()
    if opt.reachable:
        pos, _, passed, frac = advance(opt.path, sc.robot_speed)
        waypoints = opt.path[1:-1]
    else:
        waypoints = np.zeros((0, 2))
    rep = dict(
        waypoints=waypoints, cost=float("nan"), length=float(opt.length), collisions=0,
        latency=latency, nfev=0, history=np.zeros(0),
    )  # fmt: skip
    return pos, rep, passed, frac
