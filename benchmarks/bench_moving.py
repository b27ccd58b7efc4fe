"""The cost kernel's calls of real runs, replayed: CPU per call and a digest of every output.

``python -m benchmarks moving`` (or ``python benchmarks/bench_moving.py [--calls N]
[--repeat R] [--cases crowd,paper] [--store DIR]``): records the first ``N`` calls of
:class:`mawdo.planning.refine.kernel.threads.ThreadedKernel` in a realtime run of ``mawdo`` on crowd
scene 0 (seed 0, no time guide) and on the paper scenario (seed 0, time guide on), then calls
:func:`mawdo.planning.refine.kernel.population.population_cost` on each recorded call ``R`` times
over (one scratch buffer kept, as the planner's kernel does) and prints, per case, the CPU per
call (``time.process_time``: the fastest of the ``R`` sweeps divided by ``N``, and the median
sweep) and a sha256 of the four output arrays of every call. The digest must not move when the
kernel is made faster (issue 27: bit-identical; with the defaults f11e697 prints ``ef71ae5f``
for crowd and ``77263b97`` for paper); the CPU figure is the one the moving obstacles' pass
changes, without the planner's Python around it. For a before/after, record once into
``--store`` and replay it with each copy's ``src`` first on ``PYTHONPATH``, alternated in the
same minutes (the stored calls take about 70 MB a case).
"""

from __future__ import annotations

import argparse
import copy
import hashlib
import pickle
import time
from pathlib import Path

import numpy as np


class _Enough(Exception):
    pass


def record(case: str, calls: int) -> list[tuple]:
    """The arguments of the first ``calls`` kernel calls of one realtime run (deep copies)."""
    from mawdo.planning import get_scenario
    from mawdo.planning.refine.kernel.threads import ThreadedKernel
    from mawdo.planning.run.planner import plan
    from mawdo.planning.scenes import generate_scene

    if case == "paper":
        scenario, guide = get_scenario("paper"), True
    else:
        scenario, guide = generate_scene(case, 0, seed=0).scenario, False
    got: list[tuple] = []
    call = ThreadedKernel.__call__

    def keep(kernel, *args):
        if len(got) < calls:
            got.append(copy.deepcopy(args))
        return call(kernel, *args)

    def stop(*_):
        if len(got) >= calls:
            raise _Enough

    ThreadedKernel.__call__ = keep
    try:
        plan(scenario, "mawdo", seed=0, time_guide=guide, progress=stop)
    except _Enough:
        pass
    finally:
        ThreadedKernel.__call__ = call
    return got


def _recorded(case: str, calls: int, store: str | None) -> list[tuple]:
    if store is None:
        return record(case, calls)
    path = Path(store) / f"{case}-{calls}.pickle"
    if path.exists():
        return pickle.loads(path.read_bytes())
    got = record(case, calls)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(pickle.dumps(got))
    return got


def replay(got: list[tuple], repeat: int) -> tuple[float, float, str]:
    """(fastest, median) CPU seconds per call over ``repeat`` sweeps, and the outputs' digest."""
    from mawdo.planning.refine.kernel.population import population_cost, scratch_size

    need = max(scratch_size(a[0].shape[0], a[0].shape[1] // 2 + 2, a[8][3], a[5]) for a in got)
    buf = np.empty(need + need // 4 + 512)
    sweeps = []
    h = hashlib.sha256()
    for r in range(repeat + 1):  # (the first sweep warms the caches)
        t = time.process_time()
        for a in got:
            population_cost(*a, buf)
        sweeps.append(time.process_time() - t)
        if r == 0:
            for a in got:
                for arr in a[12]:
                    h.update(np.ascontiguousarray(arr).tobytes())
    s = np.array(sweeps[1:]) / len(got)
    return float(s.min()), float(np.median(s)), h.hexdigest()


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--calls", type=int, default=300)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--cases", default="crowd,paper")
    ap.add_argument(
        "--store",
        help="a folder: calls recorded once are kept there as pickles "
        "and replayed from them (to compare copies of the kernel on the same calls)",
    )
    a = ap.parse_args([] if argv is None else argv)
    for case in a.cases.split(","):
        got = _recorded(case, a.calls, a.store)
        best, med, digest = replay(got, a.repeat)
        rows = sum(g[0].shape[0] for g in got) / len(got)
        print(f"{case:6s} {len(got)} calls ({rows:.0f} rows each)  CPU per call: best "
              f"{1e3 * best:.3f} ms, median {1e3 * med:.3f} ms  outputs sha256 {digest[:16]}",
              flush=True)  # fmt: skip


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
