"""Crowd navigation: what a step costs, against the targets.

``python -m benchmarks crowd`` (or ``python benchmarks/bench_crowd.py [--episodes N]
[--people 20] [--policies mawdo,guide_only]``).

1. The people's own step (ORCA through pyrvo, social force): median wall time of one
   ``People.step`` with the robot visible, 5 and 20 people. Target <= 1 ms at 20 people.
2. A policy's decision (tracker, predictor and the planner's step together: the wall time of
   ``act``), circle crossing with ``--people`` people who do not see the robot, episodes
   ``0 .. N-1``; p50 and p95 over every decision but each episode's first plan (a planner
   policy that watches first plans at its second decision; a policy that never plans, at
   its first), and the CPU time (``time.process_time``) of the same calls beside it, since
   the wall figure moves with the machine's load (printed above). Target: p95 <= 20 ms
   with 20 people.
   ``--no-guide-gate`` times the planner policies with the guide gate off (the default
   preset has it on); ``--threads N`` gives the planner policies' population cost N threads
   (the preset uses one).
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

TARGET_PEOPLE_MS = 1.0
TARGET_P95_MS = 20.0


def people_step_ms(n: int, model: str, steps: int = 200) -> float:
    """Median wall time (ms) of one people step, ``n`` people, the robot visible at its start."""
    from mawdo.planning.people import circle_crossing

    scene = circle_crossing(n, seed=0, visible=True, model=model)
    people = scene.make_people(np.random.default_rng(0))
    sc = scene.scenario
    times = []
    for _ in range(steps):
        t0 = time.perf_counter()
        people.step(sc.start, np.zeros(2), sc.robot_radius, True)
        times.append(time.perf_counter() - t0)
    return 1e3 * float(np.median(times))


class Timed:
    """A policy whose ``act`` is timed (wall and CPU seconds per call)."""

    def __init__(self, policy) -> None:
        self.policy, self.wall, self.cpu = policy, [], []

    def reset(self, scenario, seed) -> None:
        self.policy.reset(scenario, seed)
        self.first = True

    def act(self, reading):
        # a planner policy has no plan (``last`` None) until its first, which may follow a
        # first decision spent watching: that plan has a first plan's budget, not a replan's
        unplanned = getattr(self.policy, "last", 0) is None
        w, c = time.perf_counter(), time.process_time()
        out = self.policy.act(reading)
        wall, cpu = time.perf_counter() - w, time.process_time() - c
        if not (self.first or unplanned):
            self.wall.append(wall)
            self.cpu.append(cpu)
        self.first = False
        return out


def decisions(
    policy_name: str, people: int, episodes: int, overrides: dict | None = None
) -> tuple[np.ndarray, np.ndarray, int]:
    """Wall and CPU seconds of every decision after the first, and the successes
    (``overrides``: planner settings changed, for the planner policies)."""
    from mawdo.experiments.kinds.crowd.execute import scene_of, world_of
    from mawdo.planning.run.episode import run_episode
    from mawdo.planning.run.policies import make_policy

    wall, cpu, ok = [], [], 0
    for k in range(episodes):
        scene = scene_of(f"circle-{people}-invisible", k)
        options = {"res": scene.res, "dt": scene.dt, "overrides": dict(overrides or {})}
        timed = Timed(make_policy(policy_name, options))
        res = run_episode(world_of(scene, k), timed, scene.time_limit_steps, seed=k)
        wall += timed.wall
        cpu += timed.cpu
        ok += bool(res.success)
    return np.array(wall), np.array(cpu), ok


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=5)
    ap.add_argument("--people", type=int, default=20)
    ap.add_argument("--policies", default="mawdo,guide_only")
    ap.add_argument("--no-guide-gate", action="store_true", help="the guide gate off")
    ap.add_argument("--threads", type=int, default=1, help="the population cost's threads")
    args = ap.parse_args([] if argv is None else argv)  # (python -m benchmarks: defaults)
    if args.threads < 1:
        ap.error(f"--threads {args.threads}: give a thread count >= 1")
    print(f"load average {os.getloadavg()[0]:.2f} (one core per figure)")
    for model in ("orca", "social_force"):
        for n in (5, 20):
            ms = people_step_ms(n, model)
            print(f"people step  {model:>12} {n:>2} people: {ms:7.3f} ms  "
                  f"(target at 20 people <= {TARGET_PEOPLE_MS} ms)")  # fmt: skip
    # one untimed episode first: the kernels compile
    decisions(args.policies.split(",")[0], args.people, 1)
    for name in args.policies.split(","):
        settings = {"guide_gate": False} if args.no_guide_gate else {}
        if args.threads != 1:
            settings["threads"] = args.threads
        wall, cpu, ok = decisions(name, args.people, args.episodes, settings)
        w50, w95 = 1e3 * np.percentile(wall, [50, 95])
        c50, c95 = 1e3 * np.percentile(cpu, [50, 95])
        mark = "ok" if w95 <= TARGET_P95_MS else "MISSED"
        print(
            f"decision {name:>11} ({args.threads} thr), {args.people} people, {args.episodes} ep. "
            f"({ok} succeeded), {len(wall)} decisions: wall p50 {w50:6.1f} ms p95 {w95:6.1f} ms "
            f"(target p95 <= {TARGET_P95_MS:.0f} ms: {mark}); CPU p50 {c50:6.1f} p95 {c95:6.1f} ms"
        )


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
