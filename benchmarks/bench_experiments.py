"""Time the full ``paper-table3`` sweep (2880 runs) into a temporary store.

Usage: ``python benchmarks/bench_experiments.py [--workers 2] [--preset paper-table3]``.
Importing this module runs nothing. Prints wall time, runs per second and where time went
(sum of task wall times per algorithm), then writes the report to check that it is quick too.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from collections import defaultdict
from pathlib import Path


def main(argv: list[str] | None = None) -> dict:
    from mawdo.experiments import Store, preset_plan, run_plan, write_report

    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--preset", default="paper-table3")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--report", action=argparse.BooleanOptionalAction, default=True)
    args = ap.parse_args(argv)

    plan = preset_plan(args.preset)
    with tempfile.TemporaryDirectory() as tmp:
        db = Path(tmp) / "bench.db"
        t0 = time.perf_counter()
        summary = run_plan(plan, db, workers=args.workers, progress=False)
        wall = time.perf_counter() - t0
        with Store.read(db) as store:
            per_algo: dict[str, float] = defaultdict(float)
            for t in store.task_log():
                per_algo[t["algorithm"]] += t["wall_time"]
        size = db.stat().st_size
        t1 = time.perf_counter()
        if args.report:
            write_report(db, Path(tmp) / "report")
        report_wall = time.perf_counter() - t1

    print(f"{plan.describe()}")
    print(f"cpus: {os.cpu_count()}, workers: {args.workers}")
    print(
        f"sweep: {summary.done} runs in {wall:.1f} s = {summary.done / wall:.1f} runs/s "
        f"({summary.failed} failed); store {size / 2**20:.1f} MiB"
    )
    for a, s in sorted(per_algo.items(), key=lambda kv: -kv[1]):
        print(f"  {a:8s} {s:7.1f} s of worker time")
    if args.report:
        print(f"report (tables + figures): {report_wall:.1f} s")
    return {
        "wall": wall,
        "runs": summary.done,
        "runs_per_s": summary.done / wall,
        "report_wall": report_wall,
    }


if __name__ == "__main__":
    main()
