"""BBOB pipeline throughput at D = 20: our run (driver, its evaluation trace, ioh) beside the
bare ioh call.

The pipeline is :func:`mawdo.suites.run_problem` with uniform random search, whose own work is
one uniform draw per point. The bare loop calls ``problem(X)`` on batches of the same shape as
many times (handing ioh the float64 batch, as our formula does). Two ratios are printed: the raw
one (pipeline time over the bare loop's) and the overhead, which leaves out the random search's
own draws (timed alone, :func:`bare_draws`: about 0.1 us per D = 20 point, more than half the
raw gap on the cheapest functions), so that it is the cost of the driver, its evaluation
trace and the batching. Target (issue 13): overhead <= 2x the bare call. CMA-ES and MAWDO are
timed too, for information (their own algorithm cost is not pipeline overhead).

Then the suite-study presets are projected from every algorithm's measured rate
(:func:`study_projection`; ``python -m benchmarks.bench_bbob projection`` runs it alone).
"""

from __future__ import annotations

import sys
import time

import numpy as np

from mawdo.experiments.kinds.suite import preset_plan
from mawdo.suites import evaluation_budget

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


def bare_draws(repeats: int = 3) -> float:
    """Best wall time of the random search's own draws for the pipeline's evaluations: the
    same :meth:`~mawdo.streams.RunStreams.uniform` call on the same shapes, as many times."""
    from mawdo.streams import RunStreams

    streams = RunStreams.from_seed_sequences(np.random.SeedSequence(0).spawn(RUNS))
    lb, ub = np.full(DIM, -5.0), np.full(DIM, 5.0)
    batches = RUNS * BUDGET * DIM // (RUNS * POP)
    best = np.inf
    for _ in range(repeats):
        t = time.perf_counter()
        for _ in range(batches):
            streams.uniform(lb, ub, (POP, DIM))
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
        res = run_problem(f, algo, runs=runs, budget=BUDGET, seed=0, final_target=None, **opts)
        best = min(best, time.perf_counter() - t)
        nfev = int(res.nfev.sum())
    return best, nfev


# The projection's sample: cheap to costly ioh calls, one that stops early (f1) and multimodal
# ones that do not, so early stopping and per-call cost enter the measured rates.
SAMPLE_FUNCTIONS = (1, 8, 15, 21)  # Sphere, Rosenbrock, Rastrigin rotated, Gallagher 101
# f5, the linear slope, is measured apart and counted once: its optimum lies on the bound, so
# CMA-ES's samples leave the box and the library resamples each up to 100 times (several times
# its cost elsewhere); averaged into the sample it would weigh 1/5 instead of 1/24
SLOPE = 5
PROBE_BUDGET, PROBE_RUNS = 1000, 2


def _run_task(plan, algo: str, fid: int, dim: int) -> tuple[list[int], float, float]:
    """Each run's evaluations, CPU and wall seconds of one study task (``plan.runs`` runs)."""
    from mawdo.experiments.kinds.suite import execute_suite_task
    from mawdo.experiments.kinds.suite.plan import problem_key
    from mawdo.experiments.protocol import Task

    spec = plan.task_spec(Task(algo, problem_key(fid, 1, dim), 0, plan.runs))
    c, w = time.process_time(), time.perf_counter()
    rows = execute_suite_task(spec)
    cpu, wall = time.process_time() - c, time.perf_counter() - w
    if any(r.error_text for r in rows):
        raise RuntimeError(f"{algo} failed on f{fid} D={dim}: {rows[0].error_text}")
    return [r.nfev for r in rows], cpu, wall


def measure_rates(plan, functions=SAMPLE_FUNCTIONS) -> dict:
    """Evaluations per CPU second of each (algorithm, D) of ``plan`` over ``functions``.

    Each algorithm first runs a tiny task, so Numba's compilation or cache loading (paid once
    per worker process) is not timed. The probe runs the study's own task with its final target
    (runs that reach 1e-8 stop, as in the study), at ``PROBE_BUDGET x D`` evaluations.
    ``stopped`` holds the evaluations of the probe's runs that stopped early, ``runs`` their
    number in all.
    """
    probe = plan.with_overrides(budget=PROBE_BUDGET, runs=PROBE_RUNS, instances=[1])
    tiny = plan.with_overrides(budget=50, runs=1, instances=[1])  # a few iterations: every kernel
    rate = {}
    for algo in plan.algorithms:
        for dim in plan.dims:
            _run_task(tiny, algo, 15, dim)  # warm: JIT or kernel cache, imports
            nfev, cpu, wall = [], 0.0, 0.0
            for fid in functions:
                e, c, w = _run_task(probe, algo, fid, dim)
                nfev, cpu, wall = nfev + e, cpu + c, wall + w
            cap = evaluation_budget(PROBE_BUDGET, dim)
            rate[algo, dim] = {
                "rate": sum(nfev) / cpu,
                "wall_rate": sum(nfev) / wall,
                "used": sum(nfev) / (len(nfev) * cap),
                "stopped": [e for e in nfev if e < cap],
                "runs": len(nfev),
            }
    return rate


def budget_share(r: dict, max_evals: int) -> float:
    """Expected share of ``max_evals`` a run spends, from the probe's early stops.

    A probe run that stopped spends the same at any larger budget; the others are counted at
    ``max_evals``, though some would stop between the probe's budget and ``max_evals``.
    """
    n_stopped = len(r["stopped"])
    return (sum(r["stopped"]) + (r["runs"] - n_stopped) * max_evals) / (r["runs"] * max_evals)


def study_projection(workers: int = 2) -> list[dict]:
    """Projected CPU time of the ``bbob-quick`` and ``bbob-full`` presets on ``workers``.

    Rates from :func:`measure_rates` (warmed, on ``SAMPLE_FUNCTIONS``, early stopping on; f5
    apart, see ``SLOPE``); a preset's time is the sum over (algorithm, D) of its evaluations
    over those rates, divided by ``workers``. ``upper`` counts every run at its full budget;
    ``estimate`` scales each (algorithm, D) by :func:`budget_share` of the sample (a few of 24
    functions, so a rough guide; it still counts runs that stop after the probe's budget in
    full). Runs that stop are
    deterministic continuations for CMA-ES and random search; for algorithms whose schedule
    depends on the budget (GWO, WOA), the probe's early stops are only indicative.
    """
    full, quick = preset_plan("bbob-full"), preset_plan("bbob-quick")
    rate = measure_rates(full)
    apart = measure_rates(full, functions=(SLOPE,))
    sample = ", ".join(f"f{f}" for f in SAMPLE_FUNCTIONS)
    print(
        f"  rates on {sample} (f{SLOPE} apart), instance 1, {PROBE_RUNS} runs x {PROBE_BUDGET} x D,"
        " final target 1e-8 (warmed):"
    )
    print(
        f"  {'algorithm':11s} {'D':>3s} {'evals/CPU s':>12s} {'evals/wall s':>13s} {'used':>6s} "
        f"{f'f{SLOPE} evals/CPU s':>16s}"
    )
    for (a, d), r in sorted(rate.items()):
        print(
            f"  {a:11s} {d:3d} {r['rate']:12.3e} {r['wall_rate']:13.3e} {r['used']:6.1%} "
            f"{apart[a, d]['rate']:16.3e}"
        )
    out = []
    for plan, target in ((quick, 10.0), (full, 30.0)):
        upper = est = 0.0
        for a in plan.algorithms:
            for d in plan.dims:
                cap = evaluation_budget(plan.budget, d)
                for fids, r in _strata(plan.functions, rate[a, d], apart[a, d]):
                    runs = fids * len(plan.instances) * plan.runs
                    sec = runs * cap / r["rate"] / workers / 60
                    upper, est = upper + sec, est + sec * budget_share(r, cap)
        flag = "ok" if est <= target else "MISSED"
        print(
            f"  {plan.name:10s} projected {est:7.1f} min (upper bound {upper:7.1f}) on "
            f"{workers} workers (target <= {target:.0f} min) {flag}"
        )
        out.append({"preset": plan.name, "minutes": est, "upper_minutes": upper})
    return out


def _strata(functions, rate: dict, slope: dict) -> list[tuple[int, dict]]:
    """(number of functions, their rates): f5 at its own rate, the others at the sample's."""
    n = len(functions)
    return [(n - 1, rate), (1, slope)] if SLOPE in functions else [(n, rate)]


def main(argv: list[str] | None = None) -> list[dict]:
    """The pipeline overhead table, then the projection; ``projection`` alone runs the latter."""
    if argv and argv[0] == "projection":
        return study_projection()
    pipeline(1, "random", repeats=1)  # imports, ioh problem construction
    print(
        f"BBOB D={DIM}, {RUNS} runs x {BUDGET}*D evaluations (random search, pop {POP}); best of 3"
    )
    draws = bare_draws()
    print(
        f"{'function':9s} {'bare ioh evals/s':>17s} {'pipeline evals/s':>17s} {'raw':>6s} "
        f"{'overhead (random search draws left out)':>40s}"
    )
    rows = []
    for fid in FUNCTIONS:
        bare = bare_ioh(fid)
        wall, nfev = pipeline(fid, "random")
        raw, ratio = wall / bare, (wall - draws) / bare
        flag = "ok" if ratio <= TARGET_OVERHEAD else "MISSED"
        print(
            f"f{fid:<8d} {nfev / bare:17.3e} {nfev / wall:17.3e} {raw:5.2f}x {ratio:8.2f}x "
            f"(target <= {TARGET_OVERHEAD:.0f}x) {flag}"
        )
        rows.append({"function": fid, "bare": nfev / bare, "pipeline": nfev / wall})
    print(f"  (the random search's own draws: {draws / (RUNS * BUDGET * DIM) * 1e6:.3f} us/eval)")
    print("algorithms on f15, 2 runs, same budget (their own cost included), one repeat:")
    for algo in ("cmaes", "mawdo"):
        wall, nfev = pipeline(15, algo, repeats=1, runs=2)
        print(f"  {algo:8s} {nfev / wall:12.3e} evals/s ({wall:.2f} s)")
        rows.append({"function": 15, "algorithm": algo, "pipeline": nfev / wall})
    print("suite-study presets (mawdo bench run --preset ...), projected from measured rates:")
    rows += study_projection()
    return rows


if __name__ == "__main__":
    main(sys.argv[1:])
