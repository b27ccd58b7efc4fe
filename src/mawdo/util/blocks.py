"""Blocks of runs: how :func:`mawdo.minimize` splits a large batch, and how it joins the parts.

A run's result does not depend on the batch it is in (each run has its own streams), so a batch
can go in blocks of runs, one after another, with the same numbers. Blocks whose state fits in a
core's cache keep the time per evaluation flat in the number of runs: one batch of 1000 runs at
D = 30, pop 50 moves 12 MB arrays through memory on every pass of an iteration and cost 6-18 %
more per evaluation than a batch of 30 on the development machine (benchmarks/bench_optimizers.py
prints both: "1000" in blocks, "1000 in one block").
"""

from __future__ import annotations

import dataclasses

import numpy as np

from mawdo.budget import STATUS_MESSAGES, TARGET
from mawdo.result import OptimizeResult

BLOCK_BYTES = 1 << 20
"""Bytes of one ``(runs, N, D)`` float64 state array per block by default (about a core's L2)."""

MIN_BLOCK = 16
"""Fewest runs per default block: below it the per-iteration overhead of a block dominates."""


def block_sizes(runs: int, per_block: int | None, pop_size: int, dim: int) -> list[int]:
    """Sizes of the blocks of a batch of ``runs`` runs, as even as possible.

    Parameters
    ----------
    runs : int
        Runs in the batch, >= 1.
    per_block : int or None
        Most runs per block, >= 1; None sizes blocks so that one ``(runs, pop_size, dim)``
        float64 array takes about :data:`BLOCK_BYTES` (at least :data:`MIN_BLOCK` runs).
    pop_size, dim : int
        Candidates per run and iteration, and dimension (for the default size).

    Returns
    -------
    list of int
        Block sizes, summing to ``runs``, largest first.
    """
    if per_block is None:
        per_block = max(MIN_BLOCK, BLOCK_BYTES // (8 * max(pop_size, 1) * max(dim, 1)))
    n = -(-runs // per_block)
    base, extra = divmod(runs, n)
    return [base + 1] * extra + [base] * (n - extra)


def join_results(parts: list[OptimizeResult], per_run_keys=()) -> OptimizeResult:
    """One result from the results of consecutive blocks of runs, as one batch would give.

    A block that stopped earlier than the longest (every run at its target) repeats its last
    history column, as a stopped run does in a batch. The message is the one a batch would end
    with: the target's when every block stopped at it, else the stop of the longest block that
    did not. ``per_run_keys`` name metadata entries that hold one item per run (joined); other
    entries are taken from the first block. ``time`` is the blocks' total; the runs'
    ``evaluation_trace`` lists are joined in run order.
    """
    T = max(p.history.shape[1] for p in parts)

    def stack(name: str) -> np.ndarray:
        arrays = []
        for p in parts:
            a = getattr(p, name)
            if name.startswith("history") and a.shape[1] < T:
                a = np.pad(a, ((0, 0), (0, T - a.shape[1])), mode="edge")
            arrays.append(a)
        return np.concatenate(arrays, axis=0)

    target = STATUS_MESSAGES[TARGET]
    others = sorted(
        (p for p in parts if p.message != target), key=lambda p: p.history.shape[1], reverse=True
    )
    metadata = dict(parts[0].metadata)
    for key in per_run_keys:
        if key in metadata:
            metadata[key] = [v for p in parts for v in p.metadata[key]]
    fields = ("x", "fun", "nfev", "nit", "history", "history_nfev", "status")
    traced = parts[0].evaluation_trace is not None
    return dataclasses.replace(
        parts[0],
        **{name: stack(name) for name in fields},
        evaluation_trace=[t for p in parts for t in p.evaluation_trace] if traced else None,
        message=others[0].message if others else target,
        time=float(sum(p.time for p in parts)),
        metadata=metadata,
    )
