"""BBOB pipeline throughput at D = 20: our run (driver + recorder + ioh) beside the bare ioh call.

The pipeline is :func:`mawdo.suites.run_problem` with uniform random search (whose own work is
one uniform draw per point), so the gap to the bare ``ioh`` loop is the cost of the driver,
the evaluation recorder and the batching. The bare loop calls ``problem(X)`` on batches of the
same shape as many times. Target (issue 13): pipeline overhead <= 2x the bare call. CMA-ES and
MAWDO are timed too, for information (their own algorithm cost is not pipeline overhead).
"""

from __future__ import annotations

import time

import numpy as np

DIM, RUNS, POP, BUDGET = 20, 10, 50, 1000  # 1000 x D = 20 000 evaluations per run
FUNCTIONS = (1, 8, 15, 21)
TARGET_OVERHEAD = 2.0


def bare_ioh(fid: int, repeats: int = 3) -> float:
    """Best wall time of ``RUNS * BUDGET * DIM`` evaluations through ``ioh``'s batch call."""
    import ioh

    p = ioh.get_problem(fid, 1, DIM, ioh.ProblemClass.REAL)
    rng = np.random.default_rng(0)
    batches = RUNS * BUDGET * DIM // (RUNS * POP)
    X = rng.uniform(-5, 5, (RUNS * POP, DIM))
    best = np.inf
    for _ in range(repeats):
        t = time.perf_counter()
        for _ in range(batches):
            np.asarray(p(X), dtype=float)
        best = min(best, time.perf_counter() - t)
    return best


def pipeline(fid: int, algo: str, repeats: int = 3, runs: int = RUNS) -> tuple[float, int]:
    """Best wall time and evaluations of ``run_problem`` on BBOB ``fid`` at ``DIM``."""
    from mawdo.suites import get_problem, run_problem

    f = get_problem("bbob", fid, instance=1, dim=DIM)
    opts = {"pop_size": POP} if algo == "random" else {}
    best, nfev = np.inf, 0
    for _ in range(repeats):
        t = time.perf_counter()
        res, _ = run_problem(f, algo, runs=runs, budget=BUDGET, seed=0, final_target=None, **opts)
        best = min(best, time.perf_counter() - t)
        nfev = int(res.nfev.sum())
    return best, nfev


def study_projection(workers: int = 2) -> list[dict]:
    """Projected wall time of the ``bbob-quick`` and ``bbob-full`` presets on ``workers``.

    Each algorithm's evaluations per second are measured on f15 (multimodal, so no run stops
    early) at D = 5 and D = 20, 2 runs of 1e3 x D evaluations through the study's own task
    (:func:`execute_suite_task`); a preset's time is the sum over (algorithm, D) of its
    evaluations over that rate, divided by ``workers``. An upper bound: runs that reach 1e-8
    stop early.
    """
    from mawdo.experiments.bbob import execute_suite_task, preset_plan
    from mawdo.experiments.bbob.plan import problem_key
    from mawdo.experiments.protocol import Task
    from mawdo.suites import evaluation_budget

    full, quick = preset_plan("bbob-full"), preset_plan("bbob-quick")
    probe = quick.with_overrides(budget=1e3, runs=2, functions=[15], instances=[1])
    rate = {}
    for algo in full.algorithms:
        for dim in full.dims:
            spec = probe.task_spec(Task(algo, problem_key(15, 1, dim), 0, 2))
            t = time.perf_counter()
            rows = execute_suite_task(spec)
            rate[algo, dim] = sum(r.nfev for r in rows) / (time.perf_counter() - t)
    out = []
    for plan, target in ((quick, 10.0), (full, 30.0)):
        per = len(plan.functions) * len(plan.instances) * plan.runs
        sec = sum(
            per * evaluation_budget(plan.budget, d) / rate[a, d]
            for a in plan.algorithms
            for d in plan.dims
        )
        minutes = sec / workers / 60
        flag = "ok" if minutes <= target else "MISSED"
        print(
            f"  {plan.name:10s} projected {minutes:7.1f} min on {workers} workers "
            f"(target <= {target:.0f} min) {flag}"
        )
        out.append({"preset": plan.name, "minutes": minutes})
    slow = ", ".join(f"{a} D={d}: {r:.2e}" for (a, d), r in sorted(rate.items()))
    print(f"  evaluations/s per (algorithm, D): {slow}")
    return out


def main() -> list[dict]:
    pipeline(1, "random", repeats=1)  # imports, ioh problem construction
    print(
        f"BBOB D={DIM}, {RUNS} runs x {BUDGET}*D evaluations (random search, pop {POP}); best of 3"
    )
    print(f"{'function':9s} {'bare ioh evals/s':>17s} {'pipeline evals/s':>17s} {'overhead':>9s}")
    rows = []
    for fid in FUNCTIONS:
        bare = bare_ioh(fid)
        wall, nfev = pipeline(fid, "random")
        ratio = wall / bare
        flag = "ok" if ratio <= TARGET_OVERHEAD else "MISSED"
        print(
            f"f{fid:<8d} {nfev / bare:17.3e} {nfev / wall:17.3e} {ratio:8.2f}x "
            f"(target <= {TARGET_OVERHEAD:.0f}x) {flag}"
        )
        rows.append({"function": fid, "bare": nfev / bare, "pipeline": nfev / wall})
    print("algorithms on f15, 2 runs, same budget (their own cost included), one repeat:")
    for algo in ("cmaes", "mawdo"):
        wall, nfev = pipeline(15, algo, repeats=1, runs=2)
        print(f"  {algo:8s} {nfev / wall:12.3e} evals/s ({wall:.2f} s)")
        rows.append({"function": 15, "algorithm": algo, "pipeline": nfev / wall})
    print("suite-study presets (mawdo bench run --preset ...), projected from measured rates:")
    rows += study_projection()
    return rows


if __name__ == "__main__":
    main()
