"""Adapters: the same episode in the environment and through ``run_episode``."""

from __future__ import annotations

import gymnasium
import numpy as np
import pytest

import mawdo.gym  # noqa: E402,F401
from mawdo.experiments.kinds.crowd.execute import scene_of, world_of  # noqa: E402
from mawdo.gym import CallablePolicy, policy_action, register_policy  # noqa: E402
from mawdo.gym.options import COMMON, sensor_of  # noqa: E402
from mawdo.planning.judge.check import check_trajectory  # noqa: E402
from mawdo.planning.judge.fault import blame  # noqa: E402
from mawdo.planning.run.episode import run_episode  # noqa: E402
from mawdo.planning.run.policies import POLICIES, make_policy  # noqa: E402
from mawdo.planning.sense.tracker import Tracker  # noqa: E402

SETTING = "circle-5-invisible"


class RandomPolicy:
    """Uniform velocities (m/s) from a generator reseeded every episode; remembers what it saw."""

    def __init__(self, speed: float) -> None:
        self.speed, self.seen = speed, []

    def reseed(self, seed) -> None:
        self.rng = np.random.default_rng(seed)

    def __call__(self, obs):
        self.seen.append(np.array(obs))
        return self.rng.uniform(-self.speed, self.speed, 2)


def _drive(env, act, seed):
    """Run ``act`` in ``env`` from ``reset(seed)``; the last info and the robot's positions."""
    obs, _ = env.reset(seed=seed)
    while True:
        obs, _, term, trunc, info = env.step(act(obs))
        if term or trunc:
            return info, np.array(env.unwrapped.world.trajectory)


def _first_collision(res):
    """The first colliding step of a finished episode (None without) and whether the robot
    caused a collision in it (the checker and the blame on the realised scenario)."""
    rep = check_trajectory(res.route, res.scenario, times=res.route_times)
    steps = sorted({s for s, _ in rep.collisions} | set(rep.border))
    if not steps:
        return None, False
    s = steps[0]
    hits = [c for c in rep.collisions if c[0] == s]
    mine, _ = blame(res.route, res.route_times, res.scenario, hits)
    return s, bool(mine) or s in rep.border


def _compare(info, traj, res):
    """The environment's episode is ``run_episode``'s up to its end."""
    np.testing.assert_allclose(traj, res.trajectory[: len(traj)], rtol=0, atol=1e-9)
    assert info["success"] == res.success
    first, caused = _first_collision(res)
    if info["collision"]:
        assert first == len(traj) - 2  # the env stopped in the step that collided
        assert info["robot_caused"] == caused
    else:
        assert first is None or first >= len(traj) - 1
        assert len(traj) == len(res.trajectory)  # goal or time limit: the whole episode


@pytest.mark.parametrize("seed, noise, strays", [(0, 0.0, False), (1, 0.0, False),
                                                 (2, 0.1, False), (2, 0.1, True)])  # fmt: skip
def test_random_callable_policy_same_episode_in_env_and_run_episode(seed, noise, strays):
    scene = scene_of(SETTING, seed)
    opts = {**COMMON, "sensor_noise": noise, "miss_rate": 0.1 if noise else 0.0}
    env = gymnasium.make("mawdo/Crowd-v0", setting=SETTING, sensor_noise=noise,
                         miss_rate=opts["miss_rate"], strays=strays)  # fmt: skip
    assert env.unwrapped.observer.tracker.strays is strays
    in_env = RandomPolicy(1.0)
    in_env.reseed(seed)  # the env path: the caller seeds its own policy
    info, traj = _drive(env, in_env, seed)

    judged = RandomPolicy(1.0)
    policy = CallablePolicy(judged, tracker=Tracker(noise=noise / scene.res, strays=strays),
                            on_reset=lambda s: judged.reseed(seed))  # fmt: skip
    res = run_episode(world_of(scene, seed), policy, scene.time_limit_steps, seed=seed,
                      sensor=sensor_of(opts, scene.res))  # fmt: skip
    _compare(info, traj, res)
    # the policy saw the same observations both ways
    n = len(in_env.seen)
    assert n >= 2
    np.testing.assert_array_equal(np.array(in_env.seen), np.array(judged.seen[:n]))


@pytest.mark.parametrize("seed", [0, 3])
def test_orca_robot_same_episode_in_env_and_run_episode(seed):
    scene = scene_of(SETTING, seed)
    opts = {"res": scene.res, "dt": scene.dt}
    env = gymnasium.make("mawdo/Crowd-v0", setting=SETTING)
    info, traj = _drive(env, policy_action(make_policy("orca_robot", opts), env), seed)
    res = run_episode(world_of(scene, seed), make_policy("orca_robot", opts),
                      scene.time_limit_steps, seed=seed)  # fmt: skip
    _compare(info, traj, res)
    assert info["success"]  # ORCA crosses these scenes (a run to the goal, compared whole)


def test_policy_action_resets_the_policy_every_episode():
    env = gymnasium.make("mawdo/Crowd-v0", setting="circle-2-invisible", max_steps=3)
    calls = []

    class Spy:
        def reset(self, scenario, seed):
            calls.append(seed)

        def act(self, reading):
            return np.zeros(2)

    act = policy_action(Spy(), env)
    for seed in (4, 5):
        _drive(env, act, seed)
    from mawdo.streams import episode_seed_sequences

    want = [episode_seed_sequences(s)["policy"].spawn_key for s in (4, 5)]
    assert [c.spawn_key for c in calls] == want
    fresh = gymnasium.make("mawdo/Crowd-v0", setting="circle-2-invisible")
    with pytest.raises(RuntimeError, match="reset the environment"):
        policy_action(Spy(), fresh)(None)


def test_register_policy_puts_a_callable_in_the_registry():
    name = "gym_test_still"
    try:
        spec = register_policy(name, lambda obs: np.zeros(2), "stands still", k=2, n_rays=4)
        assert POLICIES[name] is spec and spec.knowledge == "observed"
        policy = make_policy(name, {"noise": 2.0})
        assert isinstance(policy, CallablePolicy) and policy.observer.tracker.noise == 2.0
        scene = scene_of("circle-2-invisible", 0)
        res = run_episode(world_of(scene, 0), policy, 5, seed=0)
        np.testing.assert_array_equal(res.trajectory, np.repeat(res.trajectory[:1], 6, axis=0))
        with pytest.raises(ValueError, match="already registered"):
            register_policy(name, lambda obs: np.zeros(2))
    finally:
        POLICIES.unregister(name)
    with pytest.raises(ValueError, match="callable"):
        CallablePolicy(3)
    with pytest.raises(ValueError, match="n_rays"):
        register_policy("gym_test_bad", lambda obs: np.zeros(2), n_rays=-1)
    assert "gym_test_bad" not in POLICIES


def _towards_goal(obs):
    goal = obs[0:2]
    return goal / max(float(np.hypot(*goal)), 1e-9) * obs[5]


@pytest.mark.parametrize("seed", [0, 1])
def test_scenario_env_with_walls_and_a_noisy_occluded_sensor_is_run_episodes(seed):
    # hall: two wall blocks (rays hit them, they hide people) and two ORCA people
    from mawdo.planning.people.from_scenario import people_of
    from mawdo.planning.world.scenario import load_scenario
    from mawdo.planning.world.stepped import SteppedWorld
    from mawdo.streams import episode_seed_sequences

    from .test_env import HALL

    sc = load_scenario(HALL)
    res = sc.units.resolution
    kw = {"sensor_noise": 0.05, "sensor_range": 6.0, "max_range": 3.0}
    env = gymnasium.make("mawdo/Scenario-v0", scenario=sc, **kw)
    in_env = RandomPolicy(1.0)
    in_env.reseed(seed)
    info, traj = _drive(env, in_env, seed)

    judged = RandomPolicy(1.0)
    policy = CallablePolicy(judged, max_range=3.0, tracker=Tracker(noise=0.05 / res),
                            on_reset=lambda s: judged.reseed(seed))  # fmt: skip
    rng = np.random.default_rng(episode_seed_sequences(seed)["world"])
    world = SteppedWorld(sc, people_of(sc, rng), goal_tolerance=sc.robot_radius)
    res_ = run_episode(world, policy, env.unwrapped.max_steps, seed=seed,
                       sensor=sensor_of({**COMMON, **kw}, res))  # fmt: skip
    _compare(info, traj, res_)
    seen = np.array(in_env.seen)
    np.testing.assert_array_equal(seen, np.array(judged.seen[: len(seen)]))
    rays = seen[:, 6 + 60 :]
    assert (rays < 3.0 - 1e-6).any()  # some ray met a wall or the border


def test_scripted_movers_and_walls_judged_as_run_episode_does():
    # the built-in pixel scenario: static and scripted moving obstacles, no people; heading
    # blindly for the goal collides, and the verdict and blame match the checker's
    from mawdo.planning.world.scenario import get_scenario
    from mawdo.planning.world.stepped import SteppedWorld

    sc = get_scenario("paper")
    assert sc.moving_indices and sc.static_indices
    env = gymnasium.make("mawdo/Scenario-v0", scenario=sc, max_range=100.0)
    info, traj = _drive(env, _towards_goal, 0)
    res = run_episode(SteppedWorld(sc, goal_tolerance=sc.robot_radius),
                      CallablePolicy(_towards_goal, max_range=100.0), env.unwrapped.max_steps,
                      seed=0)  # fmt: skip
    assert info["collision"]
    _compare(info, traj, res)


def test_policy_action_drives_a_move_as_one_straight_step():
    from mawdo.planning.world.stepped import Move

    class Corner:
        def reset(self, scenario, seed):
            pass

        def act(self, reading):  # 2 px right, then 2 px up: ends at (+2, +2) px
            p = reading.position
            return Move(np.array([p + [2.0, 0.0], p + [2.0, 2.0]]), np.array([0.5, 1.0]))

    env = gymnasium.make("mawdo/Crowd-v0", setting="circle-0-invisible")
    obs, _ = env.reset(seed=0)
    start = env.unwrapped.world.position.copy()
    env.step(policy_action(Corner(), env)(obs))
    np.testing.assert_allclose(env.unwrapped.world.position - start, [2.0, 2.0], atol=1e-12)
    assert len(env.unwrapped.world.route) == 2  # one straight segment, no corner


def test_a_registered_callable_runs_in_the_crowd_study_as_in_the_env():
    from mawdo.experiments.kinds.crowd.execute import execute_crowd_task

    name = "gym_test_towards_goal"
    register_policy(name, _towards_goal, "heads for the goal")
    try:
        spec = {"algorithm": name, "preset": None, "overrides": {},
                "predictor": "constant_velocity",
                "sensor": {"noise": 0.05, "range": None, "miss_rate": 0.0},
                "problem": SETTING, "seeds": [0, 4], "first_run": 0}  # fmt: skip
        rows = execute_crowd_task(spec)
    finally:
        POLICIES.unregister(name)
    for seed, row in zip(spec["seeds"], rows, strict=True):
        assert row.status == "ok", row.error_text
        env = gymnasium.make("mawdo/Crowd-v0", setting=SETTING, sensor_noise=0.05)
        info, traj = _drive(env, _towards_goal, seed)
        assert row.success == int(info["success"])
        if info["collision"]:  # the study's row counts the whole episode, the env its first hit
            assert row.collision == 1
            assert row.robot_caused >= int(info["robot_caused"])
        else:
            assert row.steps == len(traj) - 1
