"""Opt-in kinematic limits in the time guide (issue 27, item 3): a speed limit below the
robot's speed is the speed of every timing of the run (:func:`~mawdo.planning.safety.kinematics.
at_speed`): the safe-interval guide, the guard, the rule and the refinement's cost. Expected
values are worked out by hand in the comments."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.execute import Run
from mawdo.planning.run.planner import plan
from mawdo.planning.safety.kinematics import SLACK, at_speed
from mawdo.planning.scenes import generate_scene
from mawdo.planning.world.scenario import scenario_from_dict


def _lane():
    """A free 240 x 60 map, start (20, 30) -> goal (220, 30): 200 px straight; one mover
    far off the lane (a disc of radius 5 at (120, 55) pacing 10 px along x)."""
    return scenario_from_dict({
        "schema_version": 1, "width": 240.0, "height": 60.0, "start": [20.0, 30.0],
        "goal": [220.0, 30.0], "robot": {"radius": 4.0, "speed": 4.0},
        "obstacles": [{"shape": "circle", "center": [120.0, 55.0], "radius": 5.0,
                       "motion": {"model": "patrol", "speed": 1.0,
                                  "waypoints": [[10.0, 0.0]]}}],
    })  # fmt: skip


def test_at_speed_lowers_only_a_slower_limit():
    sc = _lane()
    assert at_speed(sc, None) is sc and at_speed(sc, 9.0) is sc
    # a limit at the robot's speed: the projection would clamp each step by SLACK, so it is
    # the planned speed too
    assert at_speed(sc, 4.0).robot_speed == 4.0 * (1.0 - SLACK)
    slow = at_speed(sc, 2.0)
    assert slow.robot_speed == 2.0 * (1.0 - SLACK) and slow.robot_radius == sc.robot_radius
    assert slow.obstacles is sc.obstacles and sc.robot_speed == 4.0


def test_half_the_speed_doubles_the_timed_route():
    """200 px at 4 px per step: arrival at t = 50; at max_speed 2: t = 100 (over 1 - SLACK,
    the projection's margin). The guard and the rule time at 2 px per step too."""
    sc = _lane()
    times, routes = {}, {}
    for limit in (None, 2.0):
        cfg = PlannerConfig(time_guide=True, max_speed=limit)
        run = Run(sc, "mawdo", 0, cfg, dynamic=True)
        (route, *_) = run.timer.routes(sc.start, 0.0)
        times[limit], routes[limit] = route.times, route
        speed = 4.0 if limit is None else 2.0 * (1.0 - SLACK)
        assert run.guard.cost.scenario.robot_speed == speed and run.ics.v == speed
    np.testing.assert_allclose(times[None][[0, -1]], [0.0, 50.0], rtol=1e-12)
    np.testing.assert_allclose(times[2.0][[0, -1]], [0.0, 100.0 / (1.0 - SLACK)], rtol=1e-12)
    # every edge (the slow route may pass collinear waiting spots, no waits) at 2 px per step
    seg = np.hypot(*np.diff(routes[2.0].points, axis=0).T)
    np.testing.assert_allclose(np.diff(times[2.0]), seg / (2.0 * (1.0 - SLACK)), rtol=1e-12)
    np.testing.assert_allclose(routes[2.0].points[:, 1], 30.0)


def test_a_limited_run_takes_twice_the_steps_and_keeps_the_scenario():
    """The lane at 4 px per step: 50 steps; at max_speed 2: 200 / (2 (1 - 1e-9)) is a hair
    over 100, so 101 steps, each at most 2 px. The result reports the scenario as given."""
    sc = _lane()
    free = plan(sc, "mawdo", seed=0, config="quick", time_guide=True)
    res = plan(sc, "mawdo", seed=0, config="quick", time_guide=True, max_speed=2.0)
    assert free.success and res.success, (free.reason, res.reason)
    assert (free.steps, res.steps) == (50, 101)
    assert res.scenario is sc and res.kinematic_violations == 0
    assert np.max(np.hypot(*np.diff(res.trajectory, axis=0).T)) <= 2.0


@pytest.mark.slow
@pytest.mark.parametrize("family", ["corridor", "doorway", "parked"])
def test_runs_with_limits_keep_them_and_never_collide_actively(family):
    """Timed-family scenes with the time guide on and speed, acceleration and turn limits
    (0.75 of the robot's speed, a quarter of it per step, 0.6 rad per step): no kinematic
    violation (the independent checker) and no active collision. ``chaser`` (a mover faster
    than the robot) with the same limits: ``tests/planning/test_ics_limits.py``."""
    for index in (0, 1):
        sc = generate_scene(family, index, seed=0).scenario
        v = sc.robot_speed
        lim = {"max_speed": 0.75 * v, "max_accel": 0.25 * v, "max_turn": 0.6}
        res = plan(sc, "mawdo", seed=0, config="realtime", time_guide=True, **lim)
        assert res.kinematic_violations == 0, (family, index)
        rep = check_trajectory(res.route, sc, times=res.route_times)
        assert not rep.active, (family, index, rep.describe())
