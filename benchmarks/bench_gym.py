"""Gymnasium environment: what one ``env.step`` costs, against the target.

``python -m benchmarks gym`` (or ``python benchmarks/bench_gym.py [--steps N]``).

``mawdo/Crowd-v0``, circle crossing with 5 and 20 people who do not see the robot (ORCA people,
perfect sensor, the default observation: 10 agent rows, 16 rays): median wall time of one
``step`` (the people's step, the step's verdict, the sensor's reading, the tracker and the
observation) over ``N`` steps of a robot that heads for its goal, episodes restarting when they
end (resets not timed), and the CPU time (``time.process_time``) beside it, since the wall figure
moves with the machine's load. Target: <= 1 ms per step with 20 people (the median).

The step that collides is printed apart: it also builds the realised scenario and runs the
checker and the blame on it (once per episode; a blind robot among 20 people collides every ten
steps or so, far more often than a policy worth training).
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

TARGET_STEP_MS = 1.0


def step_ms(people: int, steps: int) -> dict[str, float]:
    """Median and p95 wall time and mean CPU time (ms) of one step with ``people`` people, and
    the median wall time of the steps that collide."""
    import gymnasium

    import mawdo.gym  # noqa: F401  (registers the environments)

    env = gymnasium.make("mawdo/Crowd-v0", setting=f"circle-{people}-invisible").unwrapped
    seed = 0
    obs, _ = env.reset(seed=seed)
    wall, cpu, hit = [], [], []
    for _ in range(steps):
        goal = obs[0:2]
        action = goal / max(float(np.hypot(*goal)), 1e-9) * obs[5]
        w, c = time.perf_counter(), time.process_time()
        obs, _, term, trunc, info = env.step(action)
        wall.append(time.perf_counter() - w)
        cpu.append(time.process_time() - c)
        hit.append(info["collision"])
        if term or trunc:
            seed += 1
            obs, _ = env.reset(seed=seed)
    wall_ms, hit = 1e3 * np.asarray(wall), np.asarray(hit)
    return {
        "p50": float(np.median(wall_ms)), "p95": float(np.percentile(wall_ms, 95)),
        "cpu": 1e3 * float(np.mean(cpu)), "collisions": int(hit.sum()),
        "p50_other": float(np.median(wall_ms[~hit])),
        "p50_collision": float(np.median(wall_ms[hit])) if hit.any() else float("nan"),
    }  # fmt: skip


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=1000, help="timed steps per crowd size")
    args = ap.parse_args(argv if argv is not None else [])
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    step_ms(5, 20)  # imports and first calls, not timed
    for people in (5, 20):
        m = step_ms(people, args.steps)
        verdict = "meets" if m["p50"] <= TARGET_STEP_MS else "MISSES"
        print(
            f"mawdo/Crowd-v0 step, {people:2d} people: p50 {m['p50']:.3f} ms, "
            f"p95 {m['p95']:.3f} ms, CPU {m['cpu']:.3f} ms/step ({verdict} the "
            f"{TARGET_STEP_MS:g} ms target); without a collision p50 {m['p50_other']:.3f} ms, "
            f"the {m['collisions']} colliding steps p50 {m['p50_collision']:.3f} ms"
        )


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
