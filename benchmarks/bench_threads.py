"""Replan latency on two threads, on a quiet and on a loaded machine (issue 28, item 10).

Each configuration runs in a child process (the OpenMP runtime reads its wait policy when it
loads), with and without ``HOGS`` busy processes competing for the cores: the realtime MAWDO
planner on the ``paper`` scenario, its replan latencies over ``SEEDS``. ``python -m benchmarks
threads``; no targets (the figures depend on what else runs on the machine, which is the point).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

from mawdo.planning.refine.kernel.threads import WAIT_VARIABLES

HOGS = 2
SEEDS = (0,)

# (label, threads, environment of the child). GOMP_SPINCOUNT=300000 is the GNU OpenMP runtime's
# own default, which mawdo left in place before issue 28 (a set GOMP_SPINCOUNT wins over the
# passive policy mawdo now asks for).
CONFIGS = (
    ("1 thread", 1, {}),
    ("2 threads, mawdo's default (passive)", 2, {}),
    ("2 threads, GOMP_SPINCOUNT=300000 (before)", 2, {"GOMP_SPINCOUNT": "300000"}),
    ("2 threads, workqueue layer", 2, {"NUMBA_THREADING_LAYER": "workqueue"}),
)


def _child(threads: int) -> None:
    """Print the replan latencies (ms) of the realtime planner as JSON."""
    from dataclasses import replace

    import numba
    import numpy as np

    from mawdo.planning.run.planner import PRESETS, plan

    cfg = replace(PRESETS["realtime"], threads=threads)
    plan("paper", "mawdo", seed=99, config=cfg)  # warm-up: compile or load, start the threads
    lat = np.concatenate(
        [plan("paper", "mawdo", seed=s, config=cfg).latencies * 1e3 for s in SEEDS]
    )
    layer = numba.threading_layer() if threads > 1 else "-"
    policy = os.environ.get("OMP_WAIT_POLICY", "-")
    print(json.dumps({"lat": lat.tolist(), "layer": f"{layer}, {policy}"}))


def _measure(threads: int, env: dict) -> tuple[list[float], str]:
    full = {k: v for k, v in os.environ.items() if k not in WAIT_VARIABLES}
    full.update(env, NUMBA_NUM_THREADS=str(max(threads, 2)))
    code = f"from benchmarks.bench_threads import _child; _child({threads})"
    out = subprocess.run(
        [sys.executable, "-c", code], env=full, check=True, capture_output=True, text=True
    ).stdout
    got = json.loads(out.strip().splitlines()[-1])
    return got["lat"], got["layer"]


def _hogs(n: int) -> list[subprocess.Popen]:
    return [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(n)]


def main() -> None:
    import numpy as np

    print(
        f"realtime MAWDO planner on 'paper', seeds {SEEDS}: replan latency p50 / p95 (ms), "
        f"quiet and with {HOGS} busy processes; load average before: {os.getloadavg()[0]:.1f}"
    )
    for label, threads, env in CONFIGS:
        cells = []
        for hogs in (0, HOGS):
            procs = _hogs(hogs)
            try:
                lat, layer = _measure(threads, env)
            finally:
                for p in procs:
                    p.kill()
                    p.wait()
            cells.append(f"{np.median(lat):6.1f} / {np.percentile(lat, 95):6.1f}")
        print(f"  {label:42s} [{layer:16s}] quiet {cells[0]}   loaded {cells[1]}")


if __name__ == "__main__":
    main()
