"""Opt-in kinematic limits (issue 27, item 3): the projection that makes the motion, the
refinement's turn penalty, the independent checker, and runs of the real planner.

Every expected value is worked out by hand in the test's comment."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mawdo.planning.judge.kincheck import check_kinematics
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.planner import plan
from mawdo.planning.safety.kinematics import Limits, project, turn_penalty
from tests.planning.maps import around_a_block


def test_speed_limit_scales_the_velocity_down():
    # |(6, 8)| = 10 -> 5: (3, 4)
    np.testing.assert_allclose(project([6.0, 8.0], [0.0, 0.0], Limits(speed=5.0)), [3, 4])
    np.testing.assert_allclose(project([1.0, 1.0], [0.0, 0.0], Limits(speed=5.0)), [1, 1])


def test_accel_limit_moves_at_most_that_far_from_the_last_velocity():
    # (4, 0) -> wanted (4, 4): the change (0, 4) cut to length 2 -> (4, 2); from rest the
    # first step is at most 2 long: (3, 4) -> (1.2, 1.6)
    np.testing.assert_allclose(project([4.0, 4.0], [4.0, 0.0], Limits(accel=2.0)), [4, 2])
    np.testing.assert_allclose(project([3.0, 4.0], [0.0, 0.0], Limits(accel=2.0)), [1.2, 1.6])


def test_turn_limit_turns_at_most_that_far_from_the_last_heading():
    # (4, 0) -> wanted (0, 4), 90 degrees left: pi / 4 at speed 4 -> (2 sqrt 2, 2 sqrt 2);
    # to the right likewise; from rest any heading
    s = 2.0 * math.sqrt(2.0)
    lim = Limits(turn=math.pi / 4)
    np.testing.assert_allclose(project([0.0, 4.0], [4.0, 0.0], lim), [s, s])
    np.testing.assert_allclose(project([0.0, -4.0], [4.0, 0.0], lim), [s, -s])
    np.testing.assert_allclose(project([0.0, 4.0], [0.0, 0.0], lim), [0, 4])


def test_all_three_limits_hold_together():
    # (4, 0) -> wanted (-4, 0): speed 3 -> (-3, 0); accel 2 -> (2, 0); turn: same heading
    np.testing.assert_allclose(
        project([-4.0, 0.0], [4.0, 0.0], Limits(speed=3.0, accel=2.0, turn=0.1)), [2, 0]
    )


def test_turn_penalty_is_the_weighted_excess_turn_of_each_corner():
    # start (0, 0) -> (10, 0) -> goal (10, 10): one corner of pi / 2; limit 0.5 -> excess
    # pi / 2 - 0.5; a straight candidate has none
    X = np.array([[10.0, 0.0], [5.0, 5.0]])
    pen = turn_penalty(X, np.zeros(2), np.array([10.0, 10.0]), 0.5, 100.0)
    np.testing.assert_allclose(pen, [100.0 * (math.pi / 2 - 0.5), 0.0])


def test_checker_reports_each_limit_by_hand():
    # moves (3, 4), (3, 4), (0, 5): speeds 5, 5, 5; accelerations (from rest) 5, 0,
    # |(-3, 1)| = sqrt 10; turns -, 0, acos(20 / 25) = 0.6435
    p = np.array([[0.0, 0.0], [3.0, 4.0], [6.0, 8.0], [6.0, 13.0]])
    rep = check_kinematics(p, max_speed=4.9, max_accel=3.0, max_turn=0.6)
    assert rep.speed == (0, 1, 2) and rep.accel == (0, 2) and rep.turn == (2,)
    assert rep.count == 3 and not rep.ok
    np.testing.assert_allclose(
        [rep.worst["speed"], rep.worst["accel"], rep.worst["turn"]],
        [5.0, 5.0, math.acos(0.8)],  # the worst acceleration is the start's
    )
    assert check_kinematics(p, max_speed=5.0, max_accel=5.0, max_turn=0.65).ok
    assert check_kinematics(p).ok  # no limits


@pytest.mark.parametrize(
    "name, value",
    [("max_speed", 0.0), ("max_speed", -1.0), ("max_accel", float("nan")),
     ("max_accel", True), ("max_turn", 4.0), ("max_turn", "0.5")],
)  # fmt: skip
def test_config_refuses_bad_limits(name, value):
    with pytest.raises(ValueError, match=f"PlannerConfig.{name}="):
        PlannerConfig(**{name: value})


def test_a_run_with_limits_keeps_them_and_reaches_the_goal():
    """Limits speed 3, accel 0.5, turn 0.2 on a robot of speed 4: the run without limits
    breaks them (4 px per step from rest at once), the limited run keeps them all (the
    checker) and still reaches the goal; its first step from rest is at most 0.5 px."""
    sc = around_a_block()
    lim = {"max_speed": 3.0, "max_accel": 0.5, "max_turn": 0.2}
    free = plan(sc, "mawdo", seed=0, config="quick")
    assert not check_kinematics(free.trajectory, 3.0, 0.5, 0.2).ok
    res = plan(sc, "mawdo", seed=0, config="quick", **lim)
    assert res.success, res.reason
    rep = check_kinematics(res.trajectory, 3.0, 0.5, 0.2)
    assert rep.ok, rep.describe()
    assert res.kinematic_violations == 0
    assert np.hypot(*(res.trajectory[1] - res.trajectory[0])) <= 0.5 + 1e-9
    np.testing.assert_allclose(res.route, res.trajectory)  # straight between steps
