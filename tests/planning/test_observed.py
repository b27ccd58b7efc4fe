"""Observed knowledge on scripted scenes that fool a constant-velocity predictor: a person who
stops in front of the robot, one who turns, a head-on walker, one hidden behind a wall. The
robot may wait or evade; it must never cause a collision, and a success must be real."""

import numpy as np
import pytest

from mawdo.planning.run.episode import run_episode
from mawdo.planning.run.policy import PlannerPolicy
from mawdo.planning.sense.sensor import Sensor
from mawdo.planning.world.scenario import scenario_from_dict
from mawdo.planning.world.stepped import SteppedWorld


def _scene(obstacles, start=(20.0, 60.0), goal=(180.0, 60.0)):
    return scenario_from_dict({
        "schema_version": 1, "name": "observed-test", "width": 200.0, "height": 120.0,
        "start": list(start), "goal": list(goal), "robot": {"radius": 4.0, "speed": 4.0},
        "obstacles": obstacles,
    })  # fmt: skip


def _run(sc, algorithm="guide_only", sensor=None, steps=200, seed=0):
    policy = PlannerPolicy(algorithm, "quick", "observed", time_guide=True)
    return run_episode(SteppedWorld(sc), policy, steps, seed=seed, sensor=sensor)


def _assert_safe(res):
    assert res.robot_caused == 0, res.reason
    if res.success:  # a success is checker-approved against the realised motion
        assert res.collision_free and res.other_collisions == 0


HEAD_ON = {"shape": "circle", "center": [150.0, 60.0], "radius": 8.0,
           "motion": {"velocity": [-2.5, 0.0]}}  # fmt: skip
# walks toward the robot's line, then stops on it for 40 steps, then walks on
STOPPER = {"shape": "circle", "center": [100.0, 100.0], "radius": 8.0, "motion": {
    "model": "patrol", "waypoints": [[0.0, -40.0], [0.0, -80.0]], "speed": 2.0,
    "waits": [0.0, 40.0, 0.0], "cycle": "back_and_forth"}}  # fmt: skip
# walks along the robot's line toward it, then turns across it
TURNER = {"shape": "circle", "center": [150.0, 60.0], "radius": 8.0,
          "motion": {"model": "patrol", "waypoints": [[-30.0, 0.0], [-30.0, 40.0]],
                     "speed": 2.5, "cycle": "back_and_forth"}}  # fmt: skip


@pytest.mark.parametrize("mover", [HEAD_ON, STOPPER, TURNER], ids=["head-on", "stops", "turns"])
def test_observed_robot_never_causes_a_collision(mover):
    res = _run(_scene([mover]))
    _assert_safe(res)
    assert res.success, res.reason  # room enough to evade in all three


@pytest.mark.slow
@pytest.mark.parametrize("mover", [HEAD_ON, STOPPER, TURNER], ids=["head-on", "stops", "turns"])
def test_observed_mawdo_never_causes_a_collision(mover):
    res = _run(_scene([mover]), algorithm="mawdo")
    _assert_safe(res)
    assert res.success, res.reason


def test_a_walker_hidden_behind_a_wall_appears_and_is_avoided():
    # a wall between the robot's start and a walker crossing its line further on; the sensor
    # sees 60 px: the walker is detected only late, from behind the wall's end
    wall = {"shape": "polygon", "vertices": [[60, 66], [110, 66], [110, 110], [60, 110]]}
    walker = {"shape": "circle", "center": [120.0, 110.0], "radius": 6.0,
              "motion": {"velocity": [0.0, -2.0]}}  # fmt: skip
    sensor = Sensor(range=60.0)
    res = _run(_scene([wall, walker], start=(20.0, 50.0), goal=(180.0, 50.0)), sensor=sensor)
    _assert_safe(res)
    assert res.success, res.reason


def test_noisy_sensor_keeps_the_robot_blameless():
    sc = _scene([HEAD_ON, TURNER])
    for seed in range(3):
        res = _run(sc, sensor=Sensor(noise=1.0), seed=seed)
        _assert_safe(res)


def test_observed_planner_ignores_the_scenarios_future():
    # two scenes whose movers are identical until step 10 and then differ: the first ten
    # decisions of an observing planner are the same (it cannot know what comes later)
    a = {
        "shape": "circle",
        "center": [120.0, 60.0],
        "radius": 8.0,
        "motion": {"model": "patrol", "waypoints": [[-20.0, 0.0], [-20.0, 40.0]], "speed": 2.0},
    }
    b = {
        "shape": "circle",
        "center": [120.0, 60.0],
        "radius": 8.0,
        "motion": {"model": "patrol", "waypoints": [[-20.0, 0.0], [-20.0, -40.0]], "speed": 2.0},
    }
    ra, rb = _run(_scene([a]), steps=10), _run(_scene([b]), steps=10)
    assert np.array_equal(ra.trajectory, rb.trajectory)


def test_the_robot_looks_once_before_it_plans_around_people():
    sc = _scene([HEAD_ON])
    policy = PlannerPolicy("guide_only", "quick", "observed", time_guide=True)
    res = run_episode(SteppedWorld(sc), policy, 3, seed=0)
    assert np.array_equal(res.trajectory[1], res.trajectory[0])  # step 0: it watches
    assert not np.array_equal(res.trajectory[2], res.trajectory[1])  # then it moves
    eager = PlannerPolicy("guide_only", "quick", "observed", look_first=0, time_guide=True)
    res = run_episode(SteppedWorld(sc), eager, 2, seed=0)
    assert not np.array_equal(res.trajectory[1], res.trajectory[0])


def _reading(step, centers, radii):
    from mawdo.planning.sense.reading import Reading

    c = np.asarray(centers, float).reshape(-1, 2)
    return Reading(step, np.array([20.0, 60.0]), np.zeros(2), np.array([180.0, 60.0]), c,
                   np.asarray(radii, float))  # fmt: skip


def test_the_robot_watches_only_while_nobody_can_reach_it_before_the_watch_ends():
    policy = PlannerPolicy("guide_only", "quick", "observed", look_first=2, time_guide=True)
    policy.reset(_scene([HEAD_ON]), 0)
    # reach per watch step: k_sd (2) x the tracker's speed prior (4 px per step) = 8 px; gaps
    # are centre distance - agent radius (8) - robot radius (4)
    assert policy.tracker.birth_speed_sd == 4.0
    assert policy.may_watch(_reading(0, [[20.0 + 12.0 + 16.5, 60.0]], [8.0]))  # gap 16.5 > 16
    assert not policy.may_watch(_reading(0, [[20.0 + 12.0 + 15.5, 60.0]], [8.0]))  # 15.5
    assert policy.may_watch(_reading(1, [[20.0, 60.0 + 12.0 + 8.5]], [8.0]))  # one step left
    assert not policy.may_watch(_reading(1, [[20.0, 60.0 + 12.0 + 7.5]], [8.0]))
    assert not policy.may_watch(_reading(2, [[150.0, 60.0]], [8.0]))  # the watch is over
    assert not policy.may_watch(_reading(0, np.zeros((0, 2)), []))  # nobody to watch
    # one agent in reach is enough to plan at once, and k_sd is the predictor's own
    two = [[150.0, 60.0], [20.0 + 12.0 + 10.0, 60.0]]
    assert not policy.may_watch(_reading(0, two, [8.0, 8.0]))  # 10 < 16
    loose = PlannerPolicy("guide_only", "quick", "observed", look_first=1, time_guide=True,
                          predictor_options={"k_sd": 1.0})  # fmt: skip
    loose.reset(_scene([HEAD_ON]), 0)
    assert loose.may_watch(_reading(0, two, [8.0, 8.0]))  # 10 > 1 x 4 x 1


def test_a_pursuer_close_behind_at_the_start_gets_no_free_step():
    # a disc 1.3x the robot's speed, 6 px behind the robot's disc, on its line: watching one
    # step would let it close in (the fast chasers of the timed families)
    chaser = {"shape": "circle", "center": [40.0 - 4.0 - 6.0 - 6.0, 60.0], "radius": 6.0,
              "motion": {"velocity": [5.2, 0.0]}}  # fmt: skip
    sc = _scene([chaser], start=(40.0, 60.0), goal=(190.0, 60.0))
    policy = PlannerPolicy("guide_only", "quick", "observed", time_guide=True)
    res = run_episode(SteppedWorld(sc), policy, 200, seed=0)
    assert not np.array_equal(res.trajectory[1], res.trajectory[0])  # it moves at once
    _assert_safe(res)
    assert res.success, res.reason


class _Budgets:
    """A planner policy that records the evaluations of each plan it makes (None: no plan)."""

    def __init__(self, policy) -> None:
        self.policy, self.nfev = policy, []

    def reset(self, scenario, seed) -> None:
        self.policy.reset(scenario, seed)

    def act(self, reading):
        before = self.policy.last
        out = self.policy.act(reading)
        last = self.policy.last
        self.nfev.append(None if last is before else last.nfev)
        return out

    def __getattr__(self, name):
        return getattr(self.policy, name)


@pytest.mark.parametrize("movers", [[], [HEAD_ON]], ids=["plans-at-once", "watches-first"])
def test_only_the_first_plan_spends_a_first_plans_budget(movers):
    # with nobody in view the robot plans at step 0, with a walker far away it watches first:
    # either way every later decision is a replan (quick: 5 iterations against 60)
    rec = _Budgets(PlannerPolicy("mawdo", "quick", "observed"))
    run_episode(SteppedWorld(_scene(movers)), rec, 4, seed=0)
    plans = [n for n in rec.nfev if n is not None]
    assert len(plans) == (4 if not movers else 3), rec.nfev
    assert all(5 * n < plans[0] for n in plans[1:]), rec.nfev
