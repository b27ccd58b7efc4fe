"""The step's verdict and CrowdNav's reward."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.gym.reward import Rewards, crowdnav_reward, disc_clearance, judge_step  # noqa: E402


def _brute(robot0, robot1, p0, p1, r, radii, n=200_001):
    """Clearance by dense sampling of the step (a second implementation)."""
    u = np.linspace(0.0, 1.0, n)[:, None]
    robot = robot0 + u * (robot1 - robot0)
    out = []
    for a, b, rr in zip(p0, p1, radii, strict=True):
        person = a + u * (b - a)
        out.append(np.hypot(*(robot - person).T).min() - r - rr)
    return np.array(out)


def test_disc_clearance_against_sampling():
    rng = np.random.default_rng(0)
    for _ in range(20):
        r0, r1 = rng.uniform(0, 20, 2), rng.uniform(0, 20, 2)
        p0, p1 = rng.uniform(0, 20, (4, 2)), rng.uniform(0, 20, (4, 2))
        radii = rng.uniform(0.5, 3.0, 4)
        got = disc_clearance(r0, r1, p0, p1, 1.5, radii)
        np.testing.assert_allclose(got, _brute(r0, r1, p0, p1, 1.5, radii), atol=1e-6)
    # no relative motion: the plain distance
    assert disc_clearance([0, 0], [1, 0], [[5, 0]], [[6, 0]], 1.0, [1.0])[0] == pytest.approx(3.0)


def test_disc_clearance_matches_the_checker():
    from mawdo.planning.judge.check import check_trajectory
    from mawdo.planning.world.scenario import scenario_from_dict
    from mawdo.planning.world.stepped import with_movers

    spec = {"schema_version": 1, "name": "box", "seed": 0, "width": 100.0, "height": 100.0,
            "start": [10.0, 10.0], "goal": [90.0, 90.0], "robot": {"radius": 2.0, "speed": 4.0},
            "obstacles": []}  # fmt: skip
    base = scenario_from_dict(spec)
    rng = np.random.default_rng(1)
    for _ in range(10):
        p0, p1 = rng.uniform(20, 80, (3, 2)), rng.uniform(20, 80, (3, 2))
        radii = rng.uniform(1.0, 4.0, 3)
        sc = with_movers(base, radii, [(np.array([0.0, 1.0]), np.stack([a, b]))
                                       for a, b in zip(p0, p1, strict=True)])  # fmt: skip
        route = rng.uniform(20, 80, (2, 2))
        rep = check_trajectory(route, sc, times=np.array([0.0, 1.0]))
        got = disc_clearance(route[0], route[1], p0, p1, 2.0, radii)
        np.testing.assert_allclose(got, rep.clearance[0], atol=1e-9)


def test_crowdnav_reward_by_hand():
    w = Rewards()
    assert crowdnav_reward(True, False, -0.1, 0.25, w) == -0.25
    assert crowdnav_reward(False, True, 0.05, 0.25, w) == 1.0
    # 0.1 m inside the 0.2 m discomfort distance for 0.25 s at 0.5 per m per s
    assert crowdnav_reward(False, False, 0.1, 0.25, w) == pytest.approx(-0.0125)
    assert crowdnav_reward(False, False, 0.2, 0.25, w) == 0.0
    assert crowdnav_reward(False, False, np.inf, 0.25, w) == 0.0
    w2 = Rewards(success_reward=10.0, collision_penalty=-1.0, discomfort_dist=0.5,
                 discomfort_penalty_factor=2.0)  # fmt: skip
    assert crowdnav_reward(False, False, 0.1, 0.5, w2) == pytest.approx(-0.4)
    assert crowdnav_reward(True, True, 0.0, 0.5, w2) == -1.0  # a collision outweighs arrival


def _world(person_start, person_goal, speed_px=4.0):
    """A 200 px box (0.05 m/px, 0.25 s) with the robot at (100, 100) and one ORCA person."""
    from dataclasses import replace

    from mawdo.planning.people.orca import OrcaParams, OrcaPeople
    from mawdo.planning.world.scenario import scenario_from_dict
    from mawdo.planning.world.stepped import SteppedWorld
    from mawdo.planning.world.units import Units

    spec = {"schema_version": 1, "name": "box", "seed": 0, "width": 200.0, "height": 200.0,
            "start": [100.0, 100.0], "goal": [100.0, 190.0],
            "robot": {"radius": 6.0, "speed": 5.0}, "obstacles": []}  # fmt: skip
    sc = replace(scenario_from_dict(spec), derived_units=Units("m", 0.25, 0.05))
    people = OrcaPeople([person_start], [person_goal], [6.0], [speed_px], bounds=(200.0, 200.0),
                        params=OrcaParams.from_metres(0.05, 0.25))  # fmt: skip
    return SteppedWorld(sc, people, visible=False, goal_tolerance=6.0)


def _run(world, velocity, steps):
    for _ in range(steps):
        p0 = world.people.positions()
        world.step(np.asarray(velocity, float))
        out = judge_step(world, p0)
        if out.collision:
            return out, world.step_index
    return out, world.step_index


def test_a_person_walking_into_a_robot_at_rest_is_not_robot_caused():
    world = _world([161.0, 100.0], [20.0, 100.0])
    out, step = _run(world, [0.0, 0.0], 30)
    # gap 61 - 12 = 49 px closed at 4 px/step: contact during step 13
    assert out.collision and not out.robot_caused and step == 13


def test_driving_into_a_person_is_robot_caused_and_separation_is_reported():
    world = _world([160.0, 100.0], [160.0, 100.0])  # stands at its goal
    p0 = world.people.positions()
    world.step(np.array([5.0, 0.0]))
    out = judge_step(world, p0)
    assert not out.collision and out.separation == pytest.approx(60.0 - 5.0 - 12.0)
    out, step = _run(world, [5.0, 0.0], 30)
    # 43 px left at 5 px/step: contact during step 1 + 9 = 10
    assert out.collision and out.robot_caused and step == 10
