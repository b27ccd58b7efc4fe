"""The record every baseline returns, and the independent verdict on its route."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.planning.check import CheckReport, check_static_path, check_trajectory
from mawdo.planning.scenario import Scenario

__all__ = ["BaselineResult", "judge", "route_times"]


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
        The independent checker (:func:`mawdo.planning.check.check_trajectory`) approves the
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
        checks, reason,
    )  # fmt: skip
