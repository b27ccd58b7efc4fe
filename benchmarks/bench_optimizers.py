"""Optimizer throughput: 30 runs of F1 (D=30, pop 50, 500 iterations) as one batch.

Prints wall time, evaluations per second, and the time of a bare NumPy loop that only
evaluates batches of the same shape, so each algorithm's own overhead is visible.
Targets (issue 2/3): WDO, GWO, WOA under 1 s; MAWDO under 2 s, on one core.
"""

from __future__ import annotations

import time

import numpy as np

TARGETS = {"wdo": 1.0, "gwo": 1.0, "woa": 1.0, "mawdo": 2.0}


def bare_loop(runs=30, pop=50, dim=30, iters=500, seed=0) -> float:
    """Evaluate ``iters`` random batches ``(runs*pop, dim)`` of the sphere: the floor."""
    rng = np.random.default_rng(seed)
    X = rng.uniform(-100, 100, (runs * pop, dim))
    t = time.perf_counter()
    for _ in range(iters):
        (X * X).sum(axis=1)
    return time.perf_counter() - t


def time_algorithm(algo: str, repeats: int = 3, **kw) -> tuple[float, int]:
    from mawdo import minimize

    best, nfev = np.inf, 0
    for _ in range(repeats):
        res = minimize("sphere", algorithm=algo, runs=30, seed=0, max_iter=500, pop_size=50, **kw)
        best = min(best, res.time)
        nfev = int(res.nfev.sum())
    return best, nfev


def main() -> list[dict]:
    from mawdo import minimize

    minimize("sphere", algorithm="mawdo", runs=2, max_iter=5)  # imports, caches
    floor = min(bare_loop() for _ in range(3))
    rows = []
    print("F1 sphere, D=30, pop 50, 500 iterations, 30 runs in one batch (best of 3)")
    print(
        f"{'algorithm':10s} {'wall (s)':>9s} {'evals/s':>12s} {'overhead (s)':>13s} "
        f"{'target (s)':>10s}"
    )
    for algo in ("wdo", "gwo", "woa", "awdo", "mewdo", "mawdo"):
        wall, nfev = time_algorithm(algo)
        target = TARGETS.get(algo)
        flag = "" if target is None else ("  ok" if wall < target else "  MISSED")
        print(
            f"{algo:10s} {wall:9.3f} {nfev / wall:12.3e} {wall - floor:13.3f} "
            f"{'' if target is None else f'{target:.1f}':>10s}{flag}"
        )
        rows.append({"algorithm": algo, "wall": wall, "evals_per_s": nfev / wall})
    print(f"{'bare loop':10s} {floor:9.3f} {30 * 50 * 500 / floor:12.3e}  (evaluation only)")
    return rows


if __name__ == "__main__":
    main()
