"""The straight-line baseline: start to goal in one segment, blind to every obstacle."""

from __future__ import annotations

import time

import numpy as np

from mawdo.planning.baselines.result import BaselineResult, make_result
from mawdo.planning.world.scenario import Scenario

__all__ = ["plan_straight"]


def plan_straight(scenario: Scenario) -> BaselineResult:
    """The segment start -> goal followed at the robot's speed, judged by the checker.

    It always "solves"; ``collision_free`` says whether the checker accepts it (a lower bound
    on difficulty: a scene the straight line passes is trivial).
    """
    t0 = time.perf_counter()
    route = np.vstack([scenario.start, scenario.goal])
    return make_result("straight", scenario, route, time.perf_counter() - t0)
