"""Kinematic limits under observed knowledge: each step's run starts from the motion the last
step left (velocity, heading, the followed timed route), the independent kinematic check
judges the whole episode, and the robot still never causes a collision."""

import numpy as np
import pytest

from mawdo.planning.guide.sipp.guide import TimedRoute
from mawdo.planning.judge.kincheck import check_kinematics
from mawdo.planning.run.carried import CarriedMotion
from mawdo.planning.run.config import resolve_config
from mawdo.planning.run.episode import run_episode
from mawdo.planning.run.execute import Run
from mawdo.planning.run.policy import PlannerPolicy
from mawdo.planning.safety.kinematics import Limits
from mawdo.planning.world.scenario import scenario_from_dict
from mawdo.planning.world.stepped import SteppedWorld

LIMITS = {"max_speed": 3.0, "max_accel": 1.0, "max_turn": 0.6}  # robot speed 4 px per step


def _scene(obstacles, start=(20.0, 60.0), goal=(180.0, 60.0)):
    return scenario_from_dict({
        "schema_version": 1, "name": "observed-limits", "width": 200.0, "height": 120.0,
        "start": list(start), "goal": list(goal), "robot": {"radius": 4.0, "speed": 4.0},
        "obstacles": obstacles,
    })  # fmt: skip


CROSSER = {"shape": "circle", "center": [100.0, 110.0], "radius": 8.0,
           "motion": {"velocity": [0.0, -1.5]}}  # fmt: skip
HEAD_ON = {"shape": "circle", "center": [150.0, 60.0], "radius": 8.0,
           "motion": {"velocity": [-2.5, 0.0]}}  # fmt: skip
BLOCK = {"shape": "polygon", "vertices": [[90.0, 40.0], [110.0, 40.0], [110.0, 80.0],
                                          [90.0, 80.0]]}  # fmt: skip


@pytest.mark.parametrize("algorithm", ["guide_only", "mawdo"])
@pytest.mark.parametrize("mover", [CROSSER, HEAD_ON], ids=["crosser", "head-on"])
def test_a_limited_robot_that_only_observes_arrives_within_its_limits(algorithm, mover):
    sc = _scene([mover, BLOCK])
    policy = PlannerPolicy(algorithm, "quick", "observed", time_guide=True, **LIMITS)
    res = run_episode(SteppedWorld(sc), policy, 300, seed=0)
    assert res.success, res.reason
    assert res.robot_caused == 0 and res.collision_free
    # the independent check, on the positions the world recorded
    kin = check_kinematics(res.trajectory, 3.0, 1.0, 0.6)
    assert kin.ok and res.kinematic_violations == 0
    speeds = np.hypot(*np.diff(res.trajectory, axis=0).T)
    assert speeds.max() > 2.0  # it does get up to speed: no crawl at one step's acceleration


def test_the_episode_judge_holds_a_policy_to_its_limits():
    class Jerky:  # full speed at once: breaks max_accel = 1 on its first step
        limits = Limits(None, 1.0, None)

        def reset(self, scenario, seed):
            pass

        def act(self, reading):
            return np.array([4.0, 0.0])

    sc = _scene([])
    res = run_episode(SteppedWorld(sc), Jerky(), 100, seed=0)
    assert not res.success and "kinematic limits" in res.reason
    assert res.kinematic_violations == check_kinematics(res.trajectory, None, 1.0).count >= 1


def test_without_accel_or_turn_limits_nothing_is_carried():
    cfg = resolve_config("quick", {"max_speed": 3.0})
    assert CarriedMotion.of(cfg, 4.0) is None
    assert CarriedMotion.of(resolve_config("quick", {"max_turn": 0.5}), 4.0) is not None
    # a turn rate of pi or more constrains nothing (Limits.of drops it)
    assert CarriedMotion.of(resolve_config("quick", {"max_turn": np.pi}), 4.0) is None


def test_standing_keeps_the_heading_and_counts_the_steps():
    m = CarriedMotion(Limits(None, 1.0, 0.5), velocity=np.array([2.0, 0.0]),
                      heading=np.array([1.0, 0.0]), still=0)  # fmt: skip
    m.route = "a route"
    m.stand()
    m.stand()
    assert np.array_equal(m.velocity, np.zeros(2)) and m.still == 2
    assert np.array_equal(m.heading, [1.0, 0.0]) and m.route is None


def _run_for(sc):
    cfg = resolve_config("quick", {"time_guide": True, **LIMITS})
    return Run(sc, "mawdo", 0, cfg, True)


def test_a_followed_route_is_kept_one_step_earlier_while_it_stays_safe():
    sc = _scene([{"shape": "circle", "center": [100.0, 20.0], "radius": 6.0,
                  "motion": {"velocity": [0.0, 0.0001]}}])  # fmt: skip
    pts = np.array([[20.0, 60.0], [20.0, 60.0], [23.0, 60.0], [180.0, 60.0]])
    route = TimedRoute(pts, np.array([0.0, 1.0, 2.0, 60.0]), (0, 1, 2))
    m = CarriedMotion(Limits(3.0, 1.0, 0.6), route=route)
    run = _run_for(sc)
    m.hand_to(run, np.array([20.0, 60.0]))  # at time 1 of the old route: on it
    assert run.following is not None
    assert np.array_equal(run.following.times, route.times - 1.0)
    assert np.array_equal(run.following.points, route.points)
    run = _run_for(sc)
    m.hand_to(run, np.array([21.0, 60.0]))  # off the route: dropped
    assert run.following is None


def test_a_followed_route_the_new_prediction_blocks_is_dropped():
    pts = np.array([[20.0, 60.0], [180.0, 60.0]])
    route = TimedRoute(pts, np.array([1.0, 54.0]), (0, 1))
    m = CarriedMotion(Limits(3.0, 1.0, 0.6), route=route)
    # a person now predicted to stand on the route ahead
    sc = _scene([{"shape": "circle", "center": [40.0, 60.0], "radius": 6.0,
                  "motion": {"velocity": [0.0, 0.0001]}}])  # fmt: skip
    run = _run_for(sc)
    m.hand_to(run, np.array([20.0, 60.0]))
    assert run.following is None
    # the same route with the person predicted off it is kept
    sc = _scene([{"shape": "circle", "center": [40.0, 100.0], "radius": 6.0,
                  "motion": {"velocity": [0.0, 0.0001]}}])  # fmt: skip
    run = _run_for(sc)
    m.hand_to(run, np.array([20.0, 60.0]))
    assert run.following is not None
