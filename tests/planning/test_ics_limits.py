"""The inevitable-collision rule within kinematic limits (issue 27, item 3): the continuations
:mod:`mawdo.planning.safety.ics` simulates within them. A robot at speed cannot stop at once:
with an acceleration limit ``a`` its speed falls by ``a`` per step, so from 4 px per step with
``a = 1`` it drives 3 + 2 + 1 = 6 px before it rests. Expected values are worked out by hand
in the comments."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.execute import Run
from mawdo.planning.run.planner import plan
from mawdo.planning.safety.ics import SafeContinuation
from mawdo.planning.safety.kinematics import Limits
from mawdo.planning.scenes import generate_scene
from mawdo.planning.world.scenario import scenario_from_dict

R, V, C = 4.0, 4.0, 0.5  # robot radius, speed (px, px per step), the planner's margin (px)


def _wall(x0: float):
    """A static 10 px bar over the whole height (100 px) of a 400 px map, left edge ``x0``:
    no move along y passes it, only the robot's x motion matters."""
    bar = [[x0, 0.0], [x0 + 10, 0.0], [x0 + 10, 100.0], [x0, 100.0]]
    return scenario_from_dict({
        "schema_version": 1, "width": 400.0, "height": 100.0,
        "start": [100.0, 50.0], "goal": [300.0, 50.0], "robot": {"radius": R, "speed": V},
        "obstacles": [{"shape": "polygon", "id": "bar", "vertices": bar}],
    })  # fmt: skip


# the rule keeps r + C / 2 = 4.25 px from a static obstacle; the bar's edge 7.25 px ahead of
# the robot's centre leaves 3 px to stop in
GAP = R + C / 2 + 3.0


def _rule(accel, turn=None):
    ics = SafeContinuation(_wall(100.0 + GAP), C, horizon=30)
    ics.limits = Limits(speed=None, accel=accel, turn=turn)
    return ics


def test_an_instant_stop_exists_but_braking_does_not():
    """At (100, 50) moving at (4, 0) px per step toward the bar: standing at once is safe
    (the rule without limits, or asked without a velocity), but braking by 1 per step drives
    6 px (> 3) into the bar, and every escape heading keeps an x speed falling by at most 1
    per step (>= 6 px further right): no continuation within the limits."""
    p, u = np.array([100.0, 50.0]), np.array([V, 0.0])
    assert SafeContinuation(_wall(100.0 + GAP), C, horizon=30).find(p, 0.0, 0.0).kind == "wait"
    ics = _rule(accel=1.0)
    assert ics.find(p, 0.0, 0.0).kind == "wait"  # no velocity: the old rule
    assert ics.find(p, 0.0, 0.0, vel=u) is None
    # at rest the robot may stand where it is
    assert ics.find(p, 0.0, 0.0, vel=np.zeros(2)).kind == "wait"


@pytest.mark.parametrize("accel, travel", [(2.0, 2.0), (4.0, 0.0)])
def test_braking_within_the_gap_is_a_continuation(accel, travel):
    """``a = 2``: 4 -> 2 -> 0 px per step, 2 px of travel (< 3); ``a = 4``: rest after one
    step (up to the projection's 1e-9 slack). The continuation brakes along x, then stands
    until the horizon's end (t = 30)."""
    p, u = np.array([100.0, 50.0]), np.array([V, 0.0])
    c = _rule(accel).find(p, 0.0, 0.0, vel=u)
    assert c is not None and c.kind == "wait"
    np.testing.assert_allclose(c.points[-1], [100.0 + travel, 50.0], atol=1e-6)
    np.testing.assert_allclose(c.points[:, 1], 50.0)
    assert c.times[-1] == 30.0 and np.all(np.diff(c.times[:-1]) == 1.0)
    # each step within the limit: speed changes by at most a
    steps = np.diff(c.points[:-1], axis=0)
    dv = np.hypot(*np.diff(np.vstack([u, steps]), axis=0).T)
    assert np.all(dv <= accel + 1e-12)


def test_a_turn_limit_alone_keeps_the_instant_stop():
    """A turn-rate limit without an acceleration limit: the robot may still stop at once
    (the projection's acceleration step is free), so the old 'wait' stays a continuation."""
    p, u = np.array([100.0, 50.0]), np.array([V, 0.0])
    c = _rule(accel=None, turn=0.3).find(p, 0.0, 0.0, vel=u)
    assert c is not None and c.kind == "wait"
    np.testing.assert_allclose(c.points[-1], p)


@pytest.mark.parametrize("index", [0, 1])
def test_a_limited_robot_is_never_hit_moving_on_the_chaser(index):
    """chaser scenes (a mover faster than the robot, from behind) with speed 0.75 v,
    acceleration 0.25 v per step and turn 0.6 rad per step: the independent checker finds
    no active collision (before the limits were in the rule: 7 and 2) and no violation. The
    limited robot cannot always escape: where no continuation within the limits exists, or
    every move hits, it comes to rest, so a hit that follows is passive (7 and 6 of them).
    About 5 s each on a warm cache."""
    sc = generate_scene("chaser", index, seed=0).scenario
    v = sc.robot_speed
    lim = {"max_speed": 0.75 * v, "max_accel": 0.25 * v, "max_turn": 0.6}
    res = plan(sc, "mawdo", seed=0, config="realtime", **lim)
    assert res.kinematic_violations == 0
    rep = check_trajectory(res.route, sc, times=res.route_times)
    assert not rep.active, rep.describe()


def test_the_plan_is_followed_within_the_limits_and_stops_at_its_end():
    """The plan's rest (100, 50) -> (160, 50), 60 px, the robot at (4, 0) px per step with
    ``a = 1``: the 'goal' continuation follows it step by step within the limits (speed
    changes by at most 1 per step) and ends at rest on the plan's last point, before the
    bar (left edge at 200)."""
    ics = SafeContinuation(_wall(200.0), C, horizon=30)
    ics.limits = Limits(speed=None, accel=1.0, turn=0.6)
    p, u = np.array([100.0, 50.0]), np.array([V, 0.0])
    c = ics.find(p, 0.0, 0.0, route=np.array([p, [160.0, 50.0]]), vel=u)
    assert c.kind == "goal"
    np.testing.assert_allclose(c.points[-1], [160.0, 50.0], atol=1e-9)
    steps = np.diff(c.points, axis=0)
    assert np.all(np.hypot(*steps.T) <= V + 1e-9)
    dv = np.hypot(*np.diff(np.vstack([u, steps, [0.0, 0.0]]), axis=0).T)
    assert np.all(dv <= 1.0 + 1e-9), dv


def test_only_acceleration_or_turn_limits_switch_the_rule_to_limited_continuations():
    """A run without limits, or with a speed limit alone, keeps the rule's instant stops
    (``ics.limits`` None: its decisions are those of a run without this module); an
    acceleration or a turn-rate limit sets them."""
    sc = _wall(330.0)
    for extra, on in [({}, False), ({"max_speed": 2.0}, False), ({"max_accel": 1.0}, True),
                      ({"max_turn": 0.5}, True)]:  # fmt: skip
        run = Run(sc, "mawdo", 0, PlannerConfig(**extra), dynamic=True)
        assert (run.ics.limits is not None) == on, extra
