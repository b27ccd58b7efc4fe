"""The official CEC 2017 protocol at D = 10 on this machine: its projected length with 2 workers.

The protocol (``mawdo study run cec2017-official --set dims=10``) is 10 algorithms x 30
functions x 51 runs of ``10000 D`` evaluations, each run stopping early at an error of 1e-8.
Its cost is almost all the algorithms' own: the batched CEC functions take 0.2-3 us a point.
This benchmark computes, for every algorithm of the committed study, one task of that plan (the
plan's batch of runs 0-4, full budget, through the runner's ``execute_task`` as a worker computes
it) on one function of each CEC 2017 group, and measures its CPU time. The projection weights
each group's sample by the group's size (3 unimodal, 7 simple multimodal, 10 hybrid, 10
composition functions):

    hours = sum over algorithms and groups of size x CPU s a run x 51 / 3600 / workers

with 2 workers. Target at D = 10: <= 6 h (``--dim 30`` projects the protocol's other
dimension, which has no target: three times the evaluations). The study's report states what
the real run took, from its stored wall times.

Usage: ``python -m benchmarks protocol`` or ``python -m benchmarks.bench_protocol
[--functions 1,5,15,25] [--algorithms a,b] [--dim 30]``; at D = 10 about 10 minutes of one
core.
"""

from __future__ import annotations

import argparse
import time

TARGET_H = 6.0
WORKERS = 2
RUNS = 51
# CEC 2017's groups (official numbering) and the function sampled from each
GROUPS = {"unimodal": (1, 3), "simple multimodal": (4, 10), "hybrid": (11, 20),
          "composition": (21, 30)}  # fmt: skip
SAMPLE = (1, 5, 15, 25)
ALGORITHMS = ("wdo_plus", "mawdo", "wdo", "gwo", "cmaes", "scipy_de", "lshade", "jso",
              "nlshade_rsp", "random")  # fmt: skip


def _group(fid: int) -> str:
    return next(g for g, (lo, hi) in GROUPS.items() if lo <= fid <= hi)


def task_cpu(plan, algorithm: str, fid: int, dim: int = 10) -> float:
    """CPU seconds a run of the plan's first task of ``algorithm`` on function ``fid`` at
    ``dim``, computed as a study's worker computes it (:func:`~mawdo.experiments.runner
    .execute_task`: BLAS on one thread)."""
    from mawdo.experiments.protocol import Task
    from mawdo.experiments.runner import execute_task

    problem = f"f{fid:02d}_i01_d{dim:02d}"
    n = min(plan.batch_size, plan.runs)
    spec = plan.task_spec(Task(algorithm, problem, 0, n))
    t = time.process_time()
    rows = execute_task(spec)["rows"]
    cpu = time.process_time() - t
    errors = [r.error_text for r in rows if r.error_text]
    if errors:
        raise RuntimeError(f"{algorithm} on F{fid}: {errors[0]}")
    return cpu / n


def main(argv: list[str] | None = None) -> dict:
    from mawdo.experiments.protocol import find_preset

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--functions", default=",".join(map(str, SAMPLE)))
    ap.add_argument("--algorithms", default=",".join(ALGORITHMS))
    ap.add_argument("--dim", type=int, default=10, choices=(10, 30))
    args = ap.parse_args(argv or [])
    fids = [int(f) for f in args.functions.split(",")]
    algos = args.algorithms.split(",")
    plan = find_preset("cec2017-official").with_fields(dims=[args.dim], algorithms=algos)
    sampled = {g: [f for f in fids if _group(f) == g] for g in GROUPS}
    missing = [g for g, f in sampled.items() if not f]
    if missing:
        raise SystemExit(f"--functions must sample every group; none from {', '.join(missing)}")
    print(f"CEC 2017, D = {args.dim}, 10000 D evaluations; CPU s a run ({plan.batch_size} runs "
          "a task)")  # fmt: skip
    print(f"{'algorithm':12s} " + " ".join(f"{'F' + str(f):>7s}" for f in fids) + f" {'h':>7s}")
    total = 0.0
    per_algo = {}
    for algo in algos:
        cpu = {f: task_cpu(plan, algo, f, args.dim) for f in fids}
        hours = 0.0
        for g, (lo, hi) in GROUPS.items():
            mean = sum(cpu[f] for f in sampled[g]) / len(sampled[g])
            hours += (hi - lo + 1) * mean * RUNS / 3600 / WORKERS
        per_algo[algo] = hours
        total += hours
        print(f"{algo:12s} " + " ".join(f"{cpu[f]:7.2f}" for f in fids) + f" {hours:7.2f}",
              flush=True)  # fmt: skip
    target = ""
    if args.dim == 10:
        target = f" (target <= {TARGET_H:.0f} h) {'ok' if total <= TARGET_H else 'MISSED'}"
    print(f"projected: {total:.2f} h with {WORKERS} workers{target}")
    return {"hours": total, "per_algorithm": per_algo}


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
