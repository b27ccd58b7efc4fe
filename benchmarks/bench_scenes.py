"""Scene suite speed: generation + exact L* per scene and family; OMPL baselines' check rate.

Target (issue 14): scene generation + L* in at most 50 ms per scene (default parameters, one
core). The OMPL figures are measurements, not targets: validity checks per second through our
shapely geometry, and success / gap L/L* at a fixed time budget.
"""

from __future__ import annotations

import time

import numpy as np

TARGET_MS = 50.0


def generation(n: int = 8, seed: int = 0) -> None:
    from mawdo.planning.guide.oracle import scenario_optimum
    from mawdo.planning.scenes import FAMILIES, TIMED_FAMILIES, generate_scene

    print(f"scene generation + L*, default parameters, {n} scenes per family (seed {seed})")
    print(
        f"  (timed families {', '.join(TIMED_FAMILIES)} also compute T*: python -m benchmarks sipp)"
    )
    for fam in (f for f in FAMILIES if f not in TIMED_FAMILIES):
        generate_scene(fam, 0, seed=seed + 1)  # warm caches (map files, imports)
        times, oracle, attempts, obstacles = [], [], [], []
        for i in range(n):
            t = time.perf_counter()
            sc = generate_scene(fam, i, seed=seed)
            times.append(time.perf_counter() - t)
            t = time.perf_counter()
            scenario_optimum(sc.scenario)  # the oracle alone, again, for the split
            oracle.append(time.perf_counter() - t)
            attempts.append(sc.attempts)
            obstacles.append(len(sc.scenario.obstacles))
        med, worst = np.median(times) * 1e3, np.max(times) * 1e3
        flag = "ok" if med <= TARGET_MS else "MISSED"
        print(
            f"  {fam:9s} median {med:7.1f} ms  max {worst:7.1f} ms  target {TARGET_MS:g} ms "
            f"{flag:6s} (oracle alone {np.median(oracle) * 1e3:6.1f} ms, draws/scene "
            f"{np.mean(attempts):.2f}, obstacles {np.mean(obstacles):.0f})"
        )


def ompl_rate(budget: float = 0.5, seed: int = 0) -> None:
    from mawdo.planning.baselines import ompl_available, run_baseline
    from mawdo.planning.scenes import generate_scene

    if not ompl_available():
        print("OMPL baselines: ompl not installed (pip install 'mawdo[ompl]'), skipped")
        return
    fams = ("open", "forest", "maze", "narrow")
    print(f"OMPL baselines, {budget:g} s budget, resolution 0.5 px, one scene of {', '.join(fams)}")
    scenes = [generate_scene(f, 0, seed=seed) for f in fams]
    for name in ("rrtstar", "bitstar", "prmstar"):
        rates, gaps, ok = [], [], 0
        for sc in scenes:
            res = run_baseline(name, sc.scenario, time_limit=budget)
            rates.append(res.check_rate)
            ok += res.static_collision_free
            if res.solved:
                gaps.append(res.length / sc.l_star)
        gap = f"{np.median(gaps):.3f}" if gaps else "-"
        print(
            f"  {name:8s} validity checks {np.median(rates) / 1e3:6.1f} k/s (median)  "
            f"static route accepted {ok}/{len(scenes)}  gap L/L* median {gap}"
        )


def main() -> None:
    generation()
    ompl_rate()


if __name__ == "__main__":
    main()
