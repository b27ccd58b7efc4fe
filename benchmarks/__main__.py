"""Run every benchmark: ``python -m benchmarks [name ...]``."""

from __future__ import annotations

import importlib
import os
import sys

# one core, as the targets are stated per core
for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(var, "1")

SUITES = [
    "bench_optimizers",
    "bench_experiments",
    "bench_planning",
    "bench_planner",
    "bench_scenes",
    "bench_arena",
    "bench_bbob",
    "bench_cec",
    "bench_protocol",
    "bench_sipp",
    "bench_timed",
    "bench_limits",
    "bench_startup",
    "bench_threads",
    "bench_scaling",
    "bench_crowd",
    "bench_gym",
]


def main(argv: list[str]) -> None:
    names = argv or SUITES
    for name in names:
        mod_name = name if name.startswith("bench_") else f"bench_{name}"
        try:
            mod = importlib.import_module(f"benchmarks.{mod_name}")
        except ModuleNotFoundError as exc:
            if exc.name == f"benchmarks.{mod_name}":
                print(f"[{mod_name}] not present, skipped")
                continue
            raise
        print(f"\n=== {mod_name} ===")
        mod.main()


if __name__ == "__main__":
    main(sys.argv[1:])
