"""Planning arena speed: a sample of the default suite on 2 workers, extrapolated to the suite.

Target (issue 14): the default suite (``arena-default``: >= 6 families x 50 scenes, MAWDO, WOA,
GWO and the baselines) in at most 15 min on 2 workers. The sample runs ``n`` scenes per family
of the same plan; the suite's time is extrapolated linearly in scenes (tasks are independent and
the pool stays full), and the per-planner seconds per run say where the time goes.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

TARGET_MIN = 15.0


def arena_sample(n: int = 2, workers: int = 2) -> None:
    from mawdo.experiments import Store, run_plan
    from mawdo.experiments.kinds.arena import arena_preset

    suite = arena_preset("arena-default")
    plan = suite.with_overrides(n=n, batch_size=1, name="arena-sample")
    with tempfile.TemporaryDirectory() as tmp:
        db = Path(tmp) / "sample.db"
        t = time.perf_counter()
        run_plan(plan, db, workers=workers, progress=False)
        wall = time.perf_counter() - t
        with Store.read(db) as store:
            per = {p: [r.wall_time for _, _, r in store.rows(p, skip=("trace", "scene_toml"))]
                   for p in plan.planners}  # fmt: skip
    est = wall * suite.n / n / 60
    flag = "ok" if est <= TARGET_MIN else "MISSED"
    print(f"arena sample: {plan.describe()}")
    print(f"  wall {wall:7.1f} s on {workers} workers for {plan.total_runs} runs")
    print(
        f"  default suite ({suite.total_runs} runs) extrapolated: {est:6.1f} min  "
        f"target {TARGET_MIN:g} min {flag}"
    )
    for p, w in per.items():
        w = np.asarray(w, dtype=float)
        share = w.sum() * suite.n / n / workers / 60
        print(f"  {p:16s} {np.mean(w):7.2f} s/run   suite share {share:6.1f} min on {workers}")


def main() -> None:
    arena_sample()


if __name__ == "__main__":
    main()
