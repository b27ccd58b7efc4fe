"""CrowdNav scenes: placement against a line-by-line port of CrowdNav's generators, geometry
against hand values, pixels and metres, reproducibility."""

import numpy as np
import pytest
from numpy.linalg import norm

from mawdo.planning.people import (
    CircleGoals,
    KeepGoal,
    OrcaPeople,
    SocialForcePeople,
    SquareGoals,
    circle_crossing,
    square_crossing,
)
from mawdo.planning.people.crowdnav import circle_people, square_people


class Agent:
    def __init__(self, px, py, gx, gy, radius=0.3, v_pref=1.0):
        self.px, self.py, self.gx, self.gy, self.radius, self.v_pref = (
            px,
            py,
            gx,
            gy,
            radius,
            v_pref,
        )


def crowdnav_generate(rule, human_num, seed):
    """vita-epfl/CrowdNav crowd_sim.py: reset() places the robot, then
    generate_circle_crossing_human / generate_square_crossing_human (env.config values), with
    CrowdNav's global ``np.random.seed(seed)`` as a RandomState of that seed (the same stream)."""
    rs = np.random.RandomState(seed)
    circle_radius, square_width, discomfort_dist = 4, 10, 0.2
    robot = Agent(0, -circle_radius, 0, circle_radius)
    humans = []
    for _ in range(human_num):
        human = Agent(None, None, None, None)
        if rule == "circle_crossing":
            while True:
                angle = rs.random_sample() * np.pi * 2
                px_noise = (rs.random_sample() - 0.5) * human.v_pref
                py_noise = (rs.random_sample() - 0.5) * human.v_pref
                px = circle_radius * np.cos(angle) + px_noise
                py = circle_radius * np.sin(angle) + py_noise
                collide = False
                for agent in [robot] + humans:
                    min_dist = human.radius + agent.radius + discomfort_dist
                    if (
                        norm((px - agent.px, py - agent.py)) < min_dist
                        or norm((px - agent.gx, py - agent.gy)) < min_dist
                    ):
                        collide = True
                        break
                if not collide:
                    break
            human.px, human.py, human.gx, human.gy = px, py, -px, -py
        else:
            sign = -1 if rs.random_sample() > 0.5 else 1
            while True:
                px = rs.random_sample() * square_width * 0.5 * sign
                py = (rs.random_sample() - 0.5) * square_width
                collide = False
                for agent in [robot] + humans:
                    if (
                        norm((px - agent.px, py - agent.py))
                        < human.radius + agent.radius + discomfort_dist
                    ):
                        collide = True
                        break
                if not collide:
                    break
            while True:
                gx = rs.random_sample() * square_width * 0.5 * -sign
                gy = (rs.random_sample() - 0.5) * square_width
                collide = False
                for agent in [robot] + humans:
                    if (
                        norm((gx - agent.gx, gy - agent.gy))
                        < human.radius + agent.radius + discomfort_dist
                    ):
                        collide = True
                        break
                if not collide:
                    break
            human.px, human.py, human.gx, human.gy = px, py, gx, gy
        humans.append(human)
    return np.array([[h.px, h.py] for h in humans]), np.array([[h.gx, h.gy] for h in humans])


@pytest.mark.parametrize(
    "rule, place", [("circle_crossing", circle_people), ("square_crossing", square_people)]
)
@pytest.mark.parametrize("seed", [1000, 1001, 1234])
def test_placement_is_crowdnavs(rule, place, seed):
    want = crowdnav_generate(rule, 10, seed)
    got = place(10, np.random.RandomState(seed).random_sample)
    np.testing.assert_array_equal(got[0], want[0])
    np.testing.assert_array_equal(got[1], want[1])


def test_circle_geometry():
    scene = circle_crossing(10, seed=3)
    starts, goals = scene.to_metres(scene.positions), scene.to_metres(scene.goals)
    r = norm(starts, axis=1)
    assert np.all(np.abs(r - 4.0) <= 0.5 * np.sqrt(2))  # on the 4 m circle up to +-0.5 m per axis
    assert r.std() > 0.05  # the noise is there
    np.testing.assert_allclose(goals, -starts, atol=1e-12)  # antipodal
    robot = np.array([[0.0, -4.0], [0.0, 4.0]])
    for i in range(10):
        earlier = np.vstack([robot, starts[:i], goals[:i]])
        assert np.all(norm(earlier - starts[i], axis=1) >= 0.8 - 1e-12)  # 0.3 + 0.3 + 0.2


def test_square_geometry():
    scene = square_crossing(10, seed=3)
    starts, goals = scene.to_metres(scene.positions), scene.to_metres(scene.goals)
    assert np.all(np.abs(starts) <= 5.0) and np.all(np.abs(goals) <= 5.0)
    assert np.all(np.sign(starts[:, 0]) == -np.sign(goals[:, 0]))  # crossing to the other side


@pytest.mark.parametrize("res, dt", [(0.05, 0.25), (0.1, 0.5)])
def test_pixels_and_robot(res, dt):
    scene = circle_crossing(4, seed=0, res=res, dt=dt)
    sc = scene.scenario
    side = 14.0 / res
    assert (sc.width, sc.height) == (pytest.approx(side), pytest.approx(side))
    np.testing.assert_allclose(scene.origin, [side / 2, side / 2])
    np.testing.assert_allclose(sc.start, [side / 2, side / 2 - 4.0 / res])
    np.testing.assert_allclose(sc.goal, [side / 2, side / 2 + 4.0 / res])
    assert sc.robot_radius == pytest.approx(0.3 / res)
    assert sc.robot_speed == pytest.approx(dt / res)  # 1 m/s
    assert scene.time_limit_steps == round(25 / dt)
    assert sc.obstacles == () and sc.seed == 0
    np.testing.assert_allclose(scene.radii, 0.3 / res)
    np.testing.assert_allclose(scene.preferred_speed, dt / res)
    np.testing.assert_allclose(scene.to_metres(sc.start), [0.0, -4.0], atol=1e-12)
    pts = np.array([[1.5, -2.0], [0.0, 0.0]])
    np.testing.assert_allclose(scene.to_metres(scene.to_pixels(pts)), pts, atol=1e-12)


def test_reproducible_from_the_seed():
    a, b, c = square_crossing(6, seed=9), square_crossing(6, seed=9), square_crossing(6, seed=10)
    np.testing.assert_array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.goals, b.goals)
    assert not np.array_equal(a.positions, c.positions)


@pytest.mark.parametrize("fn", [circle_crossing, square_crossing])
@pytest.mark.parametrize("model, cls", [("orca", OrcaPeople), ("social_force", SocialForcePeople)])
def test_people_walk_a_whole_episode_inside_the_box(fn, model, cls):
    scene = fn(10, seed=4, visible=True, model=model)
    crowd = scene.make_people()
    assert isinstance(crowd, cls) and isinstance(
        crowd.goal_policy, CircleGoals if fn is circle_crossing else SquareGoals
    )
    np.testing.assert_array_equal(crowd.positions(), scene.positions)
    sc = scene.scenario
    changes = 0
    runs = []
    for _ in range(2):
        crowd = scene.make_people()
        traj = []
        for t in range(scene.time_limit_steps):
            before = crowd.goals.copy()
            crowd.step(sc.start + [0.0, t * 1.0], [0.0, 1.0], sc.robot_radius, True)
            changes += int(np.any(crowd.goals != before, axis=1).sum())
            x = crowd.positions()
            traj.append(x)
            # 2 m of margin: nobody comes near the border
            assert np.all(np.abs(scene.to_metres(x)) <= 6.0)
            assert np.all(np.abs(scene.to_metres(crowd.goals)) <= 5.0 + 0.5)
        runs.append(np.array(traj))
    np.testing.assert_array_equal(runs[0], runs[1])  # same seed, same trajectories
    assert changes > 0


def test_goal_changing_off_keeps_goals():
    scene = circle_crossing(3, seed=1, goal_changing=False)
    assert isinstance(scene.make_people().goal_policy, KeepGoal)


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(n_people=-1), "n_people=-1 must be >= 0"),
        (dict(n_people=2.0), "n_people=2.0 must be an int"),
        (dict(model="helbing"), "model='helbing' must be one of orca, social_force"),
        (dict(res=0.0), "res=0.0 must be > 0"),
        (dict(half_size=4.0), r"use half_size >= 5\.3 m"),
        (dict(seed=-3), "seed=-3 must be an int"),
    ],
)
def test_bad_scene_input(kw, match):
    args = dict(n_people=3, seed=0) | kw
    with pytest.raises(ValueError, match=match):
        square_crossing(**args)
