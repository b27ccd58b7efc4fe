"""Kinematic limits at their edges: a turn made while standing counts, limits that cannot reach
the goal are refused with the range that can, limits that constrain nothing take the unlimited
path, and the checker's verdict agrees with a second, plain-loop recomputation on random runs.

Every expected value is worked out by hand in the test's comment."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mawdo.planning.judge.kincheck import check_kinematics
from mawdo.planning.run.planner import plan
from mawdo.planning.safety.kinematics import Limits, limits_refusal, project, turned
from tests.planning.maps import around_a_block


def plain_turn_rates(positions) -> list[float]:
    """A second reading of the turn rule, one step at a time: the robot keeps the heading of
    its last move while it stands; a move's rate is its angle to that heading over the steps
    since that move (0 for the first move and for standing steps)."""
    rates, heading, since = [], None, 0
    for a, b in zip(positions[:-1], positions[1:], strict=True):
        dx, dy = b[0] - a[0], b[1] - a[1]
        since += 1
        if math.hypot(dx, dy) <= 1e-9:
            rates.append(0.0)
            continue
        if heading is None:
            rates.append(0.0)
        else:
            dot = (heading[0] * dx + heading[1] * dy) / (math.hypot(*heading) * math.hypot(dx, dy))
            rates.append(math.acos(max(-1.0, min(1.0, dot))) / since)
        heading, since = (dx, dy), 0
    return rates


def test_a_turn_made_standing_counts_against_the_steps_it_took():
    # east 3 px, stand one step, north 3 px: a quarter turn over 2 steps, pi / 4 per step.
    # Limit 0.6 (< 0.785): step 2 is over; limit 0.8: fine. Moving straight on after a stand
    # is no turn; a U-turn after two standing steps is pi / 3 per step.
    p = np.array([[0, 0], [3, 0], [3, 0], [3, 3]], dtype=float)
    rep = check_kinematics(p, max_turn=0.6)
    assert rep.turn == (2,) and rep.worst["turn"] == pytest.approx(math.pi / 4)
    assert check_kinematics(p, max_turn=0.8).ok
    back = np.array([[0, 0], [3, 0], [3, 0], [3, 0], [0, 0]], dtype=float)
    assert check_kinematics(back, max_turn=math.pi / 3 + 1e-6).ok
    assert check_kinematics(back, max_turn=math.pi / 3 - 1e-3).turn == (3,)


def test_at_rest_the_robot_turns_in_place_before_it_moves():
    # heading east, at rest, wanted north (a quarter turn) at max_turn 0.6 per step: standing
    # 0, 1 steps allows 0.6, 1.2 < pi / 2: it stands; after 2 standing steps 1.8 >= pi / 2
    lim = Limits(turn=0.6)
    east, want, rest = np.array([1.0, 0.0]), np.array([0.0, 4.0]), np.zeros(2)
    assert not project(want, rest, lim, east, 0).any()
    assert not project(want, rest, lim, east, 1).any()
    np.testing.assert_allclose(project(want, rest, lim, east, 2), want)
    np.testing.assert_allclose(project(want, rest, lim, None, 0), want)  # never moved: free
    h, still = turned(np.zeros(2), east, 1)
    assert still == 2 and h is east
    h, still = turned(want, east, 2)
    np.testing.assert_allclose(h, [0.0, 1.0]) and still == 0


def test_limits_that_constrain_nothing_are_dropped():
    # robot speed 4: a cap of 4 or more, an acceleration of 2 * 4 = 8 or more and a turn of pi
    # constrain nothing; a cap of 3 makes the acceleration bound 2 * 3 = 6
    class C:
        def __init__(self, s=None, a=None, t=None):
            self.max_speed, self.max_accel, self.max_turn = s, a, t

    assert Limits.of(C(4.0, 8.0, math.pi), 4.0) is None
    assert Limits.of(C(None, 1e300, None), 4.0) is None
    assert Limits.of(C(3.0, 6.0, 1.0), 4.0) == Limits(3.0, None, 1.0)
    assert Limits.of(C(3.0, 5.9, None), 4.0) == Limits(3.0, 5.9, None)
    assert Limits.of(C(None, 7.9, None), 4.0) == Limits(None, 7.9, None)


@pytest.mark.parametrize(
    "limits, field, bound",
    [
        # 226.3 px start-goal, 300 steps: 0.754 px per step at least
        (Limits(speed=0.5), "max_speed", 226.27 / 300),
        # a (n + 1)^2 / 4 >= 226.27 with n = 300: a >= 4 * 226.27 / 301^2 = 0.00999
        (Limits(accel=1e-4), "max_accel", 4 * 226.27 / 301**2),
        # a half turn in 300 steps: pi / 300 = 0.0105
        (Limits(turn=1e-6), "max_turn", math.pi / 300),
    ],
)
def test_limits_that_cannot_reach_the_goal_name_the_range_that_can(limits, field, bound):
    why = limits_refusal(limits, 226.27, 300)
    assert why.startswith(f"{field}=") and f">= {bound:.3g}" in why
    assert "max_steps" in why
    assert limits_refusal(Limits(speed=0.76, accel=0.0101, turn=0.0105), 226.27, 300) is None


@pytest.mark.parametrize("setting", [{"max_accel": 1e-6}, {"max_accel": 1e-4}, {"max_turn": 1e-6}])
def test_a_run_with_unreachable_limits_is_refused_before_it_starts(setting):
    name = next(iter(setting))
    with pytest.raises(ValueError, match=rf"{name}=.* use {name} >= "):
        plan(around_a_block(), "mawdo", seed=0, config="quick", **setting)


@pytest.mark.parametrize("setting", [{"max_accel": 1e300}, {"max_turn": math.pi}])
def test_a_limit_that_constrains_nothing_gives_the_unlimited_run(setting):
    sc = around_a_block()
    free = plan(sc, "mawdo", seed=0, config="quick")
    same = plan(sc, "mawdo", seed=0, config="quick", **setting)
    assert same.success and np.array_equal(same.trajectory, free.trajectory)


def _random_limits(rng) -> dict:
    out = {}
    for name in ("max_speed", "max_accel", "max_turn"):
        if rng.random() < 0.6:
            out[name] = float(10.0 ** rng.uniform(-6, 6))
    if "max_turn" in out:
        out["max_turn"] = min(out["max_turn"], math.pi)
    return out


def _agrees(rng) -> str:
    """One random limited run: refused with the range, or checked twice alike."""
    setting = _random_limits(rng)
    try:
        res = plan(around_a_block(), "mawdo", seed=int(rng.integers(1000)), config="quick",
                   max_steps=400, **setting)  # fmt: skip
    except ValueError as e:
        assert " >= " in str(e), str(e)
        return "refused"
    speed = setting.get("max_speed")
    accel, turn = setting.get("max_accel"), setting.get("max_turn")
    rep = check_kinematics(res.trajectory, speed, accel, turn)
    assert rep.count == res.kinematic_violations
    t = res.trajectory
    u = np.diff(t, axis=0)
    sp = np.hypot(*u.T)
    ac = np.hypot(*np.diff(np.vstack([np.zeros((1, 2)), u]), axis=0).T)
    tr = np.array(plain_turn_rates(t.tolist()))
    bad = set()
    for vals, lim in ((sp, speed), (ac, accel), (tr, turn)):
        if lim is not None:
            bad |= set(np.nonzero(vals > lim * (1 + 1e-7))[0].tolist())
    assert len(bad) == rep.count, (setting, rep.describe())
    assert rep.ok, (setting, rep.describe())  # the planner keeps its limits
    return "ok" if res.success else "failed"


def test_the_checker_agrees_with_a_plain_recomputation_on_random_limited_runs():
    rng = np.random.default_rng(20261129)
    seen = [_agrees(rng) for _ in range(8)]
    assert "refused" in seen and "ok" in seen


@pytest.mark.slow
def test_the_checker_agrees_on_200_random_limited_runs():
    rng = np.random.default_rng(47)
    seen = [_agrees(rng) for _ in range(200)]
    assert seen.count("ok") >= 20
