"""CEC 2017 / CEC 2022: the batched suites (``cec2017``, ``cec2022``) against opfunu's one point
per call (``cec2017-opfunu``, ``cec2022-opfunu``), measured in the same run.

Each function is evaluated on a batch of ``BATCH`` = 100 uniform points (an optimizer's
population): the batched suite in one call, opfunu through its ``evaluate(x)`` per row (what
``cec*-opfunu`` does). The two take turns for ``ROUNDS`` rounds, so that a slow spell of the
machine does not fall on one side only; in a round the batched call runs three times in a row
(the first of them finds its data and code evicted from the caches by opfunu's batch: about
twice the time of the others at D = 10), opfunu once (its first points warm its own). Each
keeps its best time. CEC 2017 at D = 10 and 30, CEC 2022 at D = 10 and 20 (it has no D = 30),
on every function both define (CEC 2017: all but F2, which opfunu lacks). Printed: microseconds
per point by function kind, and the speedup of the whole suite (opfunu's total time over the
batched total). Target: >= 100x.
"""

from __future__ import annotations

import time

import numpy as np

from mawdo.suites import SUITES, get_problem

BATCH, ROUNDS, WARM = 100, 5, 3
TARGET = 100.0
DIMS = {2017: (10, 30), 2022: (10, 20)}


def _seconds(fn) -> float:
    t = time.perf_counter()
    fn()
    return time.perf_counter() - t


def time_function(year: int, fid: int, dim: int) -> tuple[float, float]:
    """Best seconds of one batch of ``BATCH`` points: batched call, opfunu's per-point calls."""
    ours = get_problem(f"cec{year}", fid, dim=dim)
    ref = get_problem(f"cec{year}-opfunu", fid, dim=dim)
    X = np.random.default_rng(fid * 100 + dim).uniform(-100, 100, (BATCH, dim))
    ours.func(X), ref.func(X)  # data read, opfunu object built
    a = b = np.inf
    for _ in range(ROUNDS):
        a = min(a, *(_seconds(lambda: ours.func(X)) for _ in range(WARM)))
        b = min(b, _seconds(lambda: ref.func(X)))
    return a, b


def _kind(f) -> str:
    return f.description.split("(", 1)[1].split(";", 1)[0]  # "basic", "hybrid", "composition"


def main() -> list[dict]:
    print(f"batch of {BATCH} uniform points per call, best of {ROUNDS} rounds; us per point")
    print(
        f"{'suite':8s} {'D':>3s} {'kind':12s} {'n':>3s} {'batched':>9s} {'opfunu':>9s} "
        f"{'speedup':>9s}"
    )
    rows = []
    for year, dims in DIMS.items():
        for dim in dims:
            spec = SUITES[f"cec{year}-opfunu"]
            fids = []
            for fid in SUITES[f"cec{year}"].functions:
                try:
                    if dim in spec.dims(fid):
                        fids.append(fid)
                except ValueError:  # CEC 2017 F2: not in opfunu
                    continue
            by_kind: dict[str, list[tuple[float, float]]] = {}
            for fid in fids:
                kind = _kind(get_problem(f"cec{year}", fid, dim=dim))
                by_kind.setdefault(kind, []).append(time_function(year, fid, dim))
            total_ours = sum(a for v in by_kind.values() for a, _ in v)
            total_ref = sum(b for v in by_kind.values() for _, b in v)
            for kind, times in by_kind.items():
                a = sum(t for t, _ in times) / len(times) / BATCH * 1e6
                b = sum(t for _, t in times) / len(times) / BATCH * 1e6
                print(f"cec{year:<4d} {dim:3d} {kind:12s} {len(times):3d} {a:9.2f} {b:9.1f} "
                      f"{b / a:8.0f}x")  # fmt: skip
            speedup = total_ref / total_ours
            flag = "ok" if speedup >= TARGET else "MISSED"
            print(
                f"cec{year:<4d} {dim:3d} {'all':12s} {len(fids):3d} "
                f"{total_ours / len(fids) / BATCH * 1e6:9.2f} "
                f"{total_ref / len(fids) / BATCH * 1e6:9.1f} {speedup:8.0f}x "
                f"(target >= {TARGET:.0f}x) {flag}"
            )
            rows.append({"suite": f"cec{year}", "dim": dim, "speedup": speedup})
    return rows


if __name__ == "__main__":
    main()
