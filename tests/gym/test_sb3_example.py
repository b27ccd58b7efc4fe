"""The stable-baselines3 example (``examples/train_sb3_crowd.py``) with a tiny budget: the
trained network is registered and judged by the crowd study, the same seed gives the same
numbers, the saved model reloads to the same actions.

Needs the ``rl`` extra (stable-baselines3, PyTorch): marked ``rl``, deselected by ``make
test``, run by ``make test-rl``. stable-baselines3 is imported inside the fixtures so that the
default tier, without it, still collects this module before deselecting it.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

pytestmark = pytest.mark.rl

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "train_sb3_crowd.py"
STEPS, EPISODES, SEED = 256, 3, 3


@pytest.fixture(scope="module")
def example():
    import torch

    torch.set_num_threads(1)  # as the example's main does: one summation order for all runs
    spec = importlib.util.spec_from_file_location("train_sb3_crowd", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclass looks its module up there
    spec.loader.exec_module(module)
    yield module
    del sys.modules[spec.name]


@pytest.fixture(scope="module")
def trained(example):
    log: list[str] = []
    model = example.train(steps=STEPS, seed=SEED, n_envs=2, log=log.append)
    return model, log


@pytest.fixture(scope="module")
def judged(example, trained, tmp_path_factory):
    store = tmp_path_factory.mktemp("sb3") / "crowd.db"
    return example.judge(trained[0], episodes=EPISODES, seed=SEED, store=store, progress=False)


def _parameters(model) -> dict[str, np.ndarray]:
    return {k: v.detach().cpu().numpy().copy() for k, v in model.policy.state_dict().items()}


def test_training_runs_its_budget_and_reports_it(trained):
    model, log = trained
    assert model.num_timesteps >= STEPS
    assert log[-1].startswith(f"train: {model.num_timesteps}/{STEPS} steps")


def test_every_policy_is_judged_on_every_episode_by_the_checker(example, judged):
    from mawdo.planning.run.policies import POLICIES

    policies = (example.PPO_NAME, example.RANDOM_NAME, "straight")
    assert judged.plan.policies == policies
    for p in policies:
        rows = [r for r in judged.rows if r["policy"] == p]
        assert sorted(r["run"] for r in rows) == list(range(EPISODES))
        assert all(r["error_text"] is None for r in rows)
        for r in rows:
            reached = r["reason"].startswith("goal reached")
            # an episode ends at the goal or at the step limit; success is reaching it cleanly
            assert r["timeout"] == int(not reached)
            assert r["success"] == int(reached and not r["collision"])
            assert r["robot_caused"] <= r["collision"]
            assert (r["time_s"] is not None) == bool(r["success"])
        goal_with_collision = sum(r["reason"].startswith("goal reached but") for r in rows)
        ends = sum(r["success"] for r in rows) + sum(r["timeout"] for r in rows)
        assert ends + goal_with_collision == EPISODES
        m = judged.summary[p]
        assert m["episodes"] == EPISODES
        for key in ("success", "robot_caused", "collision", "timeout"):
            assert m[key] == pytest.approx(np.mean([r[key] for r in rows]))
    # registered only while judged: a second model can take the names
    names = set(POLICIES)
    assert example.PPO_NAME not in names and example.RANDOM_NAME not in names


def test_the_ppo_rows_are_the_networks_episodes(example, trained, judged):
    """Episode 0 rerun without the registry, the plan or the store: the network wrapped by
    CallablePolicy in run_episode, as the gymnasium page shows."""
    from mawdo.experiments.kinds.crowd.execute import episode_row, scene_of, world_of
    from mawdo.gym import CallablePolicy
    from mawdo.planning.run.episode import run_episode

    setting = judged.plan.settings[0]
    seed = judged.plan.episode_seed(setting, 0)
    scene = scene_of(setting, seed)
    policy = CallablePolicy(example.network_policy(trained[0]))
    res = run_episode(world_of(scene, seed), policy, scene.time_limit_steps, seed=seed)
    again = episode_row(res, scene)
    row = next(r for r in judged.rows if r["policy"] == example.PPO_NAME and r["run"] == 0)
    for key in ("reason", "success", "robot_caused", "steps", "min_separation_m", "discomfort"):
        assert row[key] == again[key], key


def test_same_seed_same_numbers(example, trained, judged, tmp_path):
    model = example.train(steps=STEPS, seed=SEED, n_envs=2, log=lambda _: None)
    first, second = _parameters(trained[0]), _parameters(model)
    assert first.keys() == second.keys()
    assert all(np.array_equal(first[k], second[k]) for k in first)
    again = example.judge(model, episodes=EPISODES, seed=SEED, store=tmp_path / "again.db",
                          progress=False)  # fmt: skip
    assert again.rows == judged.rows
    # and the seed matters: another one trains another network
    other = _parameters(example.train(steps=STEPS, seed=SEED + 1, n_envs=2, log=lambda _: None))
    assert not all(np.array_equal(first[k], other[k]) for k in first)


def test_saved_model_reloads_to_the_same_actions(trained, tmp_path):
    import gymnasium
    from stable_baselines3 import PPO

    import mawdo.gym  # noqa: F401 - registers the environment

    model = trained[0]
    path = tmp_path / "ppo.zip"
    model.save(path)
    loaded = PPO.load(path, device="cpu")
    env = gymnasium.make("mawdo/Crowd-v0", setting="circle-5-invisible")
    env.action_space.seed(0)
    obs = []
    for seed in range(3):
        o, _ = env.reset(seed=seed)
        for _ in range(5):  # a few steps in, people and velocities in the observation
            obs.append(o)
            o, *_ = env.step(env.action_space.sample())
    batch = np.array(obs)
    a, _ = model.predict(batch, deterministic=True)
    b, _ = loaded.predict(batch, deterministic=True)
    assert a.shape == (len(obs), 2)
    assert np.array_equal(a, b)
    assert not np.allclose(a, a[0])  # the actions depend on the observation


def test_main_writes_the_model_and_the_table(example, tmp_path, capsys):
    assert example.main(["--steps", "64", "--envs", "2", "--episodes", "2",
                         "--out", str(tmp_path)]) == 0  # fmt: skip
    out = capsys.readouterr().out
    assert (tmp_path / "ppo_crowd.zip").is_file()
    table = (tmp_path / "table.md").read_text()
    for name in (example.PPO_NAME, example.RANDOM_NAME, "straight"):
        assert f"| {name} | 2 |" in table
    assert table in out


def test_bad_budget_is_a_clear_error(example):
    with pytest.raises(SystemExit) as exc:
        example.parse(["--steps", "0"])
    assert exc.value.code == 2
    with pytest.raises(ValueError, match="at least 2 per environment"):
        example.train(steps=3, n_envs=2)
