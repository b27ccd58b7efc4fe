"""The Gymnasium environments: API conformance, seeding, vectorisation, bad input."""

from __future__ import annotations

import warnings
from pathlib import Path

import gymnasium
import numpy as np
import pytest

import mawdo.gym  # noqa: E402,F401  (registers the environments)
from mawdo.gym.options import COMMON  # noqa: E402

HALL = Path(__file__).parents[1] / "data" / "crowd" / "hall.toml"


def _episode(env, seed: int, actions: int = 1000):
    """Observations, rewards, flags and infos of one episode driven by seeded random actions."""
    rng = np.random.default_rng(99)
    obs, info = env.reset(seed=seed)
    out = [(obs, info)]
    speed = env.action_space.high[0]
    for _ in range(actions):
        a = rng.uniform(-speed, speed, 2)
        obs, r, term, trunc, info = env.step(a)
        out.append((obs, r, term, trunc, info))
        if term or trunc:
            break
    return out, np.array(env.unwrapped.world.trajectory)


def _same(a, b) -> bool:
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, tuple | list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    return bool(np.array_equal(a, b))


@pytest.mark.parametrize(
    "make",
    [
        lambda: gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible"),
        lambda: gymnasium.make("mawdo/Crowd-v0", setting="square-3-visible", sensor_noise=0.05,
                               sensor_range=3.0, miss_rate=0.1, k=2, n_rays=5),
        lambda: gymnasium.make("mawdo/Scenario-v0", scenario=str(HALL)),
    ],
)  # fmt: skip
def test_env_checker_is_clean(make):
    from gymnasium.utils.env_checker import check_env

    env = make()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any checker warning fails the test
        check_env(env.unwrapped)


def test_spaces():
    env = gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible", k=3, n_rays=8)
    assert env.observation_space.shape == (6 + 6 * 3 + 8,)
    assert env.observation_space.dtype == np.float32
    # CrowdNav's robot: 1 m/s, radius 0.3 m
    assert env.action_space.shape == (2,)
    np.testing.assert_allclose(env.action_space.high, [1.0, 1.0])
    obs, _ = env.reset(seed=0)
    # start (0, -4) m, goal (0, 4) m in CrowdNav's frame: offset (0, 8) m, at rest
    np.testing.assert_allclose(obs[:6], [0.0, 8.0, 0.0, 0.0, 0.3, 1.0], atol=1e-6)
    assert env.observation_space.contains(obs)


def test_same_seed_same_episode_and_different_seed_differs():
    make = lambda: gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible",  # noqa: E731
                                  sensor_noise=0.05, miss_rate=0.2)  # fmt: skip
    a, traj_a = _episode(make(), seed=7)
    b, traj_b = _episode(make(), seed=7)
    assert len(a) > 2
    assert _same(a, b)
    np.testing.assert_array_equal(traj_a, traj_b)
    c, _ = _episode(make(), seed=8)
    assert not _same(a[0][0], c[0][0])  # other people, other noise


def test_unseeded_resets_follow_the_last_seed():
    e1 = gymnasium.make("mawdo/Crowd-v0", setting="circle-2-invisible")
    e2 = gymnasium.make("mawdo/Crowd-v0", setting="circle-2-invisible")
    e1.reset(seed=3)
    e2.reset(seed=3)
    seeds1 = [e1.reset()[1]["episode_seed"] for _ in range(3)]
    seeds2 = [e2.reset()[1]["episode_seed"] for _ in range(3)]
    assert seeds1 == seeds2 and len(set(seeds1)) == 3


def test_time_limit_truncates():
    env = gymnasium.make("mawdo/Crowd-v0", setting="circle-0-invisible", max_steps=4)
    env.reset(seed=0)
    flags = [env.step(np.zeros(2))[2:4] for _ in range(4)]
    assert flags == [(False, False)] * 3 + [(False, True)]
    with pytest.raises(RuntimeError, match="reset"):
        env.unwrapped.step(np.zeros(2))


def test_goal_ends_with_success_reward():
    # no people: straight up at 1 m/s, 8 m in 0.25 s steps reaches the goal within its
    # tolerance (the robot radius, 0.3 m) after ceil((8 - 0.3) / 0.25) = 31 steps
    env = gymnasium.make("mawdo/Crowd-v0", setting="circle-0-invisible")
    env.reset(seed=0)
    for step in range(1, 40):  # noqa: B007 - the step it ended in
        obs, r, term, trunc, info = env.step(np.array([0.0, 1.0]))
        if term:
            break
    assert step == 31 and info["success"] and not info["collision"] and r == 1.0
    assert info["time_s"] == pytest.approx(31 * 0.25)


def test_leaving_the_map_is_a_robot_caused_collision():
    env = gymnasium.make("mawdo/Crowd-v0", setting="circle-0-invisible")
    env.reset(seed=0)
    # start (7, 3) m from the box's corner: downwards the disc leaves the map after
    # (3 - 0.3) / 0.25 = 10.8 steps, i.e. during step 11
    for step in range(1, 20):  # noqa: B007 - the step it ended in
        _, r, term, _, info = env.step(np.array([0.0, -1.0]))
        if term:
            break
    assert step == 11 and info["collision"] and info["robot_caused"] and not info["success"]
    assert r == -0.25


def test_scenario_env_takes_a_scenario_object_and_has_its_people():
    from mawdo.planning.world.scenario import load_scenario

    sc = load_scenario(HALL)
    env = gymnasium.make("mawdo/Scenario-v0", scenario=sc, k=4)
    obs, _ = env.reset(seed=0)
    rows = obs[6 : 6 + 24].reshape(4, 6)
    assert rows[:, 5].tolist() == [1.0, 1.0, 0.0, 0.0]  # two people, two padding rows
    np.testing.assert_array_equal(rows[2:], 0.0)
    # hall: start (1, 4) m, goal (11, 4) m
    np.testing.assert_allclose(obs[:2], [10.0, 0.0], atol=1e-5)


def test_make_vec_sync():
    envs = gymnasium.make_vec("mawdo/Crowd-v0", num_envs=2, vectorization_mode="sync",
                              setting="circle-5-invisible")  # fmt: skip
    obs, info = envs.reset(seed=0)
    assert obs.shape == (2, envs.single_observation_space.shape[0])
    assert info["episode_seed"].tolist() == [0, 1]
    assert not np.array_equal(obs[0], obs[1])
    for _ in range(3):
        obs, rew, term, trunc, info = envs.step(np.zeros((2, 2)))
    assert obs.shape[0] == rew.shape[0] == 2 and "robot_caused" in info
    # each sub-environment is the single environment on its seed
    single = gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible")
    ref, _ = single.reset(seed=1)
    for _ in range(3):
        ref = single.step(np.zeros(2))[0]
    np.testing.assert_array_equal(obs[1], ref)
    envs.close()


def test_unknown_option_names_it_and_the_known_ones():
    with pytest.raises(ValueError, match=r"unknown option 'n_ray'.*known options: .*n_rays"):
        gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible", n_ray=4)
    with pytest.raises(ValueError, match="goal_tolerance"):
        gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible", goal_tolerance=0.1)
    assert set(COMMON) >= {"k", "n_rays", "max_range", "sensor_noise"}


def test_unknown_setting_names_it_and_the_form():
    with pytest.raises(ValueError, match=r"'circle-5-blind'.*circle or square.*visible"):
        gymnasium.make("mawdo/Crowd-v0", setting="circle-5-blind")


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"k": -1}, "k"),
        ({"max_range": 0.0}, "max_range"),
        ({"miss_rate": 1.0}, "miss_rate"),
        ({"max_steps": 0}, "max_steps"),
        ({"strays": "yes"}, "strays"),
    ],
)
def test_bad_option_values(kwargs, match):
    with pytest.raises(ValueError, match=match):
        gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible", **kwargs)


def test_an_unknown_render_mode_is_refused():
    with pytest.raises(ValueError, match="render_mode='human'.*'rgb_array'"):
        mawdo.gym.CrowdEnv("circle-5-invisible", render_mode="human")


def test_rgb_array_frames_show_the_robot_where_it_is_and_follow_the_episode():
    env = gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible", render_mode="rgb_array")
    env.reset(seed=3)
    base = env.unwrapped
    first = env.render()
    sc = base.world.scenario
    assert first.dtype == np.uint8 and first.ndim == 3 and first.shape[2] == 3
    assert max(first.shape[:2]) == mawdo.gym.render.FRAME_PX
    assert first.shape[1] / first.shape[0] == pytest.approx(sc.width / sc.height, rel=0.02)

    def robot_pixel(image):  # the robot's centre in image rows and columns (y grows upward)
        s = image.shape[1] / sc.width
        x, y = base.world.position
        return image[int(image.shape[0] - y * s), int(x * s)]

    # deepskyblue, the robot's colour in every mawdo figure
    assert tuple(robot_pixel(first)) == (0, 191, 255)
    for _ in range(8):
        env.step(np.array([0.0, 1.0]))
    later = env.render()
    assert tuple(robot_pixel(later)) == (0, 191, 255)
    assert not np.array_equal(first, later)  # the robot and the people moved
    # no render mode: nothing drawn
    plain = gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible")
    plain.reset(seed=3)
    assert plain.render() is None


def test_scenario_env_bad_input():
    with pytest.raises(ValueError, match="needs scenario"):
        gymnasium.make("mawdo/Scenario-v0")
    with pytest.raises(ValueError, match="a Scenario, a file path"):
        gymnasium.make("mawdo/Scenario-v0", scenario=3)
    with pytest.raises(ValueError, match="unknown option 'sensor'"):
        gymnasium.make("mawdo/Scenario-v0", scenario=str(HALL), sensor=None)
    with pytest.raises(ValueError, match="goal_tolerance"):
        gymnasium.make("mawdo/Scenario-v0", scenario=str(HALL), goal_tolerance=-0.1)


def test_step_before_reset_and_bad_action():
    env = gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible").unwrapped
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(2))
    env.reset(seed=0)
    with pytest.raises(ValueError, match="finite velocity"):
        env.step(np.array([np.nan, 0.0]))
    with pytest.raises(ValueError, match="finite velocity"):
        env.step(np.zeros(3))
