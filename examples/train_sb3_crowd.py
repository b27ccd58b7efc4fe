"""Train a small PPO policy on ``mawdo/Crowd-v0`` with stable-baselines3, then judge it as a
mawdo policy beside a random policy and ``straight``, on the crowd study's own episodes.

Needs the ``rl`` extra (``pip install "mawdo[rl]"``; a CPU build of PyTorch is enough)::

    python examples/train_sb3_crowd.py                      # 20 000 steps, 50 episodes
    python examples/train_sb3_crowd.py --steps 2000 --episodes 10 --out out/sb3-small

1. Train: PPO with a small multilayer perceptron on ``--envs`` copies of the environment
   (stable-baselines3's ``make_vec_env``; copy ``i`` starts at episode seed ``seed + i``).
2. Save the model (``<out>/ppo_crowd.zip``; ``PPO.load`` reads it back).
3. Judge: the trained network (deterministic actions) and a uniform random velocity are
   registered as mawdo policies (``register_policy``) and run with ``straight`` through the
   crowd study's plan and runner, in this process: the same ``--episodes`` episodes for every
   policy (people drawn from the study's episode seeds, none of them a training episode),
   judged by the independent checker. The table is the study's aggregate of the stored rows.

A few thousand steps teach little; the table shows how little, against the two baselines.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.env_util import make_vec_env

import mawdo.gym  # noqa: F401 - registers mawdo/Crowd-v0
from mawdo.experiments.progress import Heartbeat

SETTING = "circle-5-invisible"
#: The names the judged policies get in the policy registry while they are judged.
PPO_NAME, RANDOM_NAME = "ppo", "random"


def say(message: str) -> None:
    print(message, flush=True)


# ---------------------------------------------------------------------- training
class TrainingLog(BaseCallback):
    """Counts steps and how the training episodes ended (the environment's ``info``: goal,
    collision, or the step limit), and prints a line every second from a heartbeat thread, so
    neither the rollouts nor the network updates between them go silent."""

    def __init__(self, total: int, log=say, last: int = 20) -> None:
        super().__init__()
        self.total, self.log, self.last = total, log, last
        self.ends: list[str] = []
        self.returns: list[float] = []
        self.heartbeat: Heartbeat | None = None

    def _on_training_start(self) -> None:
        self.heartbeat = Heartbeat(self._line, every=1.0)

    def _on_step(self) -> bool:
        for done, info in zip(self.locals["dones"], self.locals["infos"], strict=True):
            if done:
                ended = "collision" if info["collision"] else "timeout"
                self.ends.append("success" if info["success"] else ended)
                self.returns.append(float(info["episode"]["r"]))  # the Monitor wrapper's
        return True

    def _on_training_end(self) -> None:
        if self.heartbeat is not None:
            self.heartbeat.stop()
        self._line(None)

    def _line(self, seconds: float | None) -> None:
        ends = self.ends[-self.last :]
        text = f"train: {self.num_timesteps}/{self.total} steps, {len(self.ends)} episodes"
        if ends:
            rates = ", ".join(f"{k} {ends.count(k) / len(ends):.2f}"
                              for k in ("success", "collision", "timeout"))  # fmt: skip
            mean = float(np.mean(self.returns[-self.last :]))
            text += f"; last {len(ends)}: {rates}, return {mean:+.3f}"
        self.log(text + ("" if seconds is None else f" ({seconds:.0f} s)"))


def train(setting: str = SETTING, steps: int = 20_000, seed: int = 0, n_envs: int = 4,
          log=say) -> PPO:  # fmt: skip
    """PPO (``MlpPolicy``, two hidden layers of 64, CPU) trained for ``steps`` environment
    steps in all (rounded up to whole rollouts of at most 2048 steps)."""
    if steps < 2 * n_envs:
        raise ValueError(f"steps={steps} must be at least 2 per environment ({2 * n_envs})")
    what = f"train: building {n_envs} environments of {setting} (the first may compile kernels)"
    log(what)
    beat = Heartbeat(lambda s: log(f"{what}, {s:.0f} s"), every=1.0)
    try:
        kwargs = {"setting": setting}
        env = make_vec_env("mawdo/Crowd-v0", n_envs=n_envs, seed=seed, env_kwargs=kwargs)
        n_steps = max(2, min(2048, steps) // n_envs)  # per environment and rollout
        model = PPO("MlpPolicy", env, n_steps=n_steps, batch_size=min(64, n_steps * n_envs),
                    policy_kwargs={"net_arch": [64, 64]}, seed=seed, device="cpu",
                    verbose=0)  # fmt: skip
    finally:
        beat.stop()
    model.learn(total_timesteps=steps, callback=TrainingLog(steps, log))
    env.close()
    return model


def network_policy(model: PPO):
    """The trained network as ``observation -> action`` (its deterministic action, m/s)."""

    def act(observation):
        action, _ = model.predict(observation, deterministic=True)
        return action

    return act


class UniformRandom:
    """A velocity drawn uniformly from the action box ``[-v, v]^2`` (``v`` the robot's speed,
    ``observation[5]``), from a generator reseeded with each episode's policy seed."""

    def __init__(self) -> None:
        self.rng = np.random.default_rng(0)

    def reset(self, seed) -> None:
        self.rng = np.random.default_rng(seed)

    def __call__(self, observation) -> np.ndarray:
        v = float(observation[5])
        return self.rng.uniform(-v, v, size=2)


# ---------------------------------------------------------------------- judging
@dataclass
class Judgement:
    """The study's verdicts: ``rows`` one dict per (policy, episode) with the checker's
    verdicts (``success``, ``robot_caused``, ``collision``, ``timeout``: 0 or 1; ``time_s``
    for successes; ``discomfort``, ``min_separation_m``, ``reason``); ``summary`` the study's
    aggregate per policy (:func:`~mawdo.experiments.kinds.crowd.report.crowd_summary`)."""

    plan: Any
    rows: list[dict[str, Any]]
    summary: dict[str, dict[str, float]]


_ROW_FIELDS = ("run", "reason", "success", "robot_caused", "collision", "timeout", "time_s",
               "discomfort", "min_separation_m", "steps", "error_text")  # fmt: skip


def judge(model: PPO, setting: str = SETTING, episodes: int = 50, seed: int = 0,
          store: Path | str = "crowd-sb3.db", progress: bool = True) -> Judgement:  # fmt: skip
    """Run the crowd study (``setting`` x ``episodes`` x {``ppo``, ``random``, ``straight``})
    in this process and read its verdicts; ``store`` is the study's results file (replaced).

    The two policies are in the registry only while they are judged, so a second call (or a
    second model) registers them afresh.
    """
    from mawdo.experiments import Store, run_plan
    from mawdo.experiments.kinds.crowd import CrowdPlan, crowd_summary
    from mawdo.gym import register_policy
    from mawdo.planning.run.policies import POLICIES

    rand = UniformRandom()
    entries = [
        (PPO_NAME, network_policy(model), "PPO network (stable-baselines3)", None),
        (RANDOM_NAME, rand, "uniform random velocity", rand.reset),
    ]
    store = Path(store)
    store.unlink(missing_ok=True)  # a stored run of another model under the same name
    registered = []
    try:
        for name, fn, text, on_reset in entries:
            register_policy(name, fn, text, on_reset=on_reset)
            registered.append(name)
        plan = CrowdPlan(name="sb3", settings=[setting], n=episodes, seed=seed,
                         policies=[PPO_NAME, RANDOM_NAME, "straight"], batch_size=10)  # fmt: skip
        run_plan(plan, store, workers=1, progress=progress)  # workers see this registry
        with Store.read(store) as s:
            rows = [{"policy": a, **{k: getattr(r, k) for k in _ROW_FIELDS}}
                    for a, _, r in s.rows()]  # fmt: skip
            summary = {p: m for (_, p), m in crowd_summary(s).items()}
    finally:
        for name in registered:
            POLICIES.unregister(name)
    return Judgement(plan, rows, summary)


def table(judgement: Judgement) -> str:
    """The study's aggregate as a small Markdown table (rates are shares of the episodes)."""
    from mawdo.experiments.tables import Table, to_markdown

    keys = {"episodes": "episodes", "success": "success", "robot_caused": "robot-caused",
            "collision": "collision", "timeout": "timeout", "time_s": "time to goal (s)",
            "discomfort": "discomfort", "min_separation_m": "min sep. (m)"}  # fmt: skip
    rows = [[p, *(m[k] for k in keys)] for p, m in judgement.summary.items()]
    fmts = {c: ".2f" for c in list(keys.values())[1:]}
    return to_markdown(Table(
        name="sb3", title=judgement.plan.describe(), columns=["policy", *keys.values()],
        rows=rows, formats=fmts,
        notes=["time to goal over successes; discomfort: share of steps closer than 0.2 m to "
               "a person; min sep.: median over episodes of the smallest clearance"],
    ))  # fmt: skip


# ---------------------------------------------------------------------- command line
def parse(argv=None) -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)  # fmt: skip
    p.add_argument("--setting", default=SETTING, help="crowd setting (default %(default)s)")
    p.add_argument("--steps", type=int, default=20_000, help="training steps (%(default)s)")
    p.add_argument("--envs", type=int, default=4, help="environments per rollout (%(default)s)")
    p.add_argument("--episodes", type=int, default=50, help="judged episodes (%(default)s)")
    p.add_argument("--seed", type=int, default=0, help="training and study seed (%(default)s)")
    p.add_argument("--threads", type=int, default=1, help="PyTorch threads (%(default)s)")
    p.add_argument("--out", type=Path, default=Path("out/sb3-crowd"), help="output folder")
    args = p.parse_args(argv)
    for name in ("steps", "envs", "episodes", "threads"):
        if getattr(args, name) < 1:
            p.error(f"--{name} must be >= 1, got {getattr(args, name)}")
    if args.seed < 0:
        p.error(f"--seed must be >= 0, got {args.seed}")
    return args


def main(argv=None) -> int:
    import stable_baselines3
    import torch

    args = parse(argv)
    torch.set_num_threads(args.threads)
    say(f"torch {torch.__version__}, stable-baselines3 {stable_baselines3.__version__}")
    args.out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    model = train(args.setting, args.steps, args.seed, args.envs)
    t_train = time.perf_counter() - t0
    path = args.out / "ppo_crowd.zip"
    model.save(path)
    say(f"saved {path} after {t_train:.0f} s of training")
    judgement = judge(model, args.setting, args.episodes, args.seed, args.out / "crowd.db")
    text = table(judgement)
    (args.out / "table.md").write_text(text)
    print(text)
    say(f"wall time {time.perf_counter() - t0:.0f} s (training {t_train:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
