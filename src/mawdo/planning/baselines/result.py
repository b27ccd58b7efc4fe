"""The record every baseline returns, and the independent verdict on its route."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.planning.judge.check import CheckReport, check_static_path, check_trajectory
from mawdo.planning.run.config import PlannerConfig, step_limit
from mawdo.planning.run.result import PlanResult, Replan
from mawdo.planning.world.scenario import Scenario

__all__ = ["BaselineResult", "as_plan_result", "judge", "route_times"]


@dataclass(frozen=True)
class BaselineResult:
    """Outcome of one baseline on one scenario.

    Attributes
    ----------
    planner : str
        Registered baseline name.
    solved : bool
        The planner returned a route (for OMPL: an exact solution within the time budget).
    route : numpy.ndarray or None, shape (k, 2)
        Route vertices from start to goal (pixels), followed at the robot's speed.
    length : float
        Route length (pixels); ``inf`` without a route.
    time : float
        Planning wall time (seconds).
    sees_time : bool
        Whether the planner knows that obstacles move (no baseline here does).
    collision_free : bool
        The independent checker (:func:`mawdo.planning.judge.check.check_trajectory`) approves the
        route followed at the robot's speed from t = 0 against every obstacle, moving ones
        included, and the robot's disc stays in the map.
    static_collision_free : bool
        The checker approves the route against the static obstacles alone.
    min_clearance : float
        Smallest clearance over the timed route and all obstacles (pixels; ``nan`` without route).
    validity_checks : int
        State validity checks the planner made (OMPL; 0 for the straight line).
    reason : str
        ``"ok"`` or why there is no route / why it is rejected.
    hits : int
        The checker's hits on the timed route (0 without a route).
    """

    planner: str
    solved: bool
    route: np.ndarray | None
    length: float
    time: float
    sees_time: bool
    collision_free: bool
    static_collision_free: bool
    min_clearance: float
    validity_checks: int = 0
    reason: str = "ok"
    hits: int = 0

    @property
    def success(self) -> bool:
        """Solved and approved by the independent checker against every obstacle."""
        return self.solved and self.collision_free

    @property
    def check_rate(self) -> float:
        """Validity checks per second of planning time (0 without checks)."""
        return self.validity_checks / self.time if self.time > 0 else 0.0


def route_times(route: np.ndarray, speed: float) -> np.ndarray:
    """Times (time steps) at the route's vertices when it is followed at ``speed`` px/step."""
    seg = np.hypot(*np.diff(route, axis=0).T)
    return np.concatenate([[0.0], np.cumsum(seg) / speed])


def judge(scenario: Scenario, route: np.ndarray) -> tuple[CheckReport, CheckReport]:
    """The checker's verdicts on ``route``: timed against all obstacles, and static only."""
    timed = check_trajectory(route, scenario, times=route_times(route, scenario.robot_speed))
    statics = [scenario.obstacles[i].shape for i in scenario.static_indices]
    static = check_static_path(route, statics, radius=scenario.robot_radius)
    return timed, static


def make_result(
    name: str,
    scenario: Scenario,
    route: np.ndarray | None,
    seconds: float,
    checks: int = 0,
    reason: str = "ok",
) -> BaselineResult:
    """Judge ``route`` (``None``: unsolved) and pack the record."""
    if route is None:
        return BaselineResult(name, False, None, np.inf, seconds, False, False, False, np.nan,
                              checks, reason)  # fmt: skip
    route = np.asarray(route, dtype=float)
    timed, static = judge(scenario, route)
    length = float(np.sum(np.hypot(*np.diff(route, axis=0).T)))
    if reason == "ok" and not timed.ok:
        reason = f"checker rejects the timed route: {timed.describe()}"
    return BaselineResult(
        name, True, route, length, seconds, False, timed.ok, static.ok, timed.min_clearance,
        checks, reason, int(timed.hits),
    )  # fmt: skip


def as_plan_result(
    scenario: Scenario, result: BaselineResult, config: PlannerConfig | None = None
) -> PlanResult:
    """A single-shot baseline's route as a :class:`~mawdo.planning.run.result.PlanResult`: the
    route followed at the robot's speed from t = 0, sampled at every step up to the one that
    reaches the goal, with the checker's verdict of ``result`` (not judged again).

    The step limit is the rule every planner obeys (:func:`~mawdo.planning.run.config.step_limit`,
    ``config.max_steps`` or the automatic value): a route the robot cannot drive within it
    does not reach the goal (``success`` False, the trajectory stops at the limit).
    """
    config = PlannerConfig() if config is None else config
    solved = result.route is not None
    route = result.route if solved else scenario.start[None, :]
    times = route_times(route, scenario.robot_speed) if len(route) > 1 else np.zeros(1)
    limit = _limit(scenario, config.max_steps, float(times[-1]))
    # positions at every step; the last step ends at the goal, as a driven run's does
    end = min(np.ceil(times[-1] - 1e-9), limit)
    steps = np.arange(0.0, end + 1.0)
    traj = np.column_stack([np.interp(steps, times, route[:, i]) for i in (0, 1)])
    success, reason = bool(result.success), result.reason
    if solved and times[-1] > limit:  # the robot never gets to the end of its route
        success, reason = False, "step limit reached before the goal"
    rep = Replan(
        step=0, position=scenario.start.copy(), waypoints=route[1:-1], cost=float("nan"),
        length=float(result.length), collisions=0, latency=float(result.time),
        nfev=int(result.validity_checks), history=np.zeros(0),
    )  # fmt: skip
    return PlanResult(
        scenario=scenario, algorithm=result.planner, seed=0, config=config, trajectory=traj,
        success=success, reason=reason, replans=[rep], route=route, route_times=times,
        collision_free=bool(result.collision_free), min_clearance=float(result.min_clearance),
        hits=int(result.hits), solved=solved, guarded=False,
    )  # fmt: skip


def _limit(scenario: Scenario, max_steps: int | None, duration: float) -> int:
    """The step limit for a route of ``duration`` steps; the static optimum (an oracle call)
    is asked for only when the route outlasts the rule without it."""
    straight, v = scenario.straight_line_length(), scenario.robot_speed
    limit, _ = step_limit(max_steps, straight, 0.0, v)
    if duration > limit and max_steps is None:
        from mawdo.planning.guide.oracle import scenario_optimum

        opt = scenario_optimum(scenario, static_only=True)
        limit, _ = step_limit(None, straight, opt.length if opt.reachable else 0.0, v)
    return limit
