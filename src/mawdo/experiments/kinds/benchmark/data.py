"""Benchmark values read back from a results store (final values, convergence curves), and
:class:`SweepData`, what every table of a report is computed from."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mawdo.experiments import stats
from mawdo.experiments.kinds.benchmark.plan import ExperimentPlan
from mawdo.experiments.store import Store

#: The algorithm a report's Wilcoxon tests are against when the store has it.
REFERENCE = "mawdo"


def finals(store: Store) -> dict[tuple[str, str], dict[str, Any]]:
    """Final values per ``(algorithm, function)``: arrays ``run, fun, error, nfev, wall`` of the
    successful runs (run order) and ``failed``, the number of failed runs."""
    acc: dict[tuple[str, str], list] = {}
    for a, f, r in store.rows(skip=("curve", "curve_nfev", "params")):
        acc.setdefault((a, f), []).append(r)
    out: dict[tuple[str, str], dict[str, Any]] = {}
    for key, items in acc.items():
        ok = [r for r in items if not r.failed]
        out[key] = {
            "run": np.array([r.run for r in ok], dtype=np.int64),
            "fun": np.array([r.fun for r in ok], dtype=float),
            "error": np.array([r.error for r in ok], dtype=float),
            "nfev": np.array([r.nfev for r in ok], dtype=float),
            "wall": np.array([r.wall_time for r in ok], dtype=float),
            "failed": len(items) - len(ok),
        }
    return out


def curves(store: Store, algorithm: str, function: str) -> tuple[np.ndarray, np.ndarray, float]:
    """Best-so-far curves of the successful runs of one (algorithm, function).

    Returns
    -------
    curve : numpy.ndarray
        ``(R, T)`` best-so-far values; shorter curves are padded with their last value.
    curve_nfev : numpy.ndarray
        ``(R, T)`` evaluations spent, padded the same way.
    f_star : float
        The function's optimum (NaN if unknown).
    """
    recs = [r for _, _, r in store.rows(algorithm, function) if not r.failed]
    if not recs:
        return np.empty((0, 0)), np.empty((0, 0)), float("nan")
    T = max(r.curve.size for r in recs)
    c = np.stack([np.pad(r.curve, (0, T - r.curve.size), mode="edge") for r in recs])
    n = np.stack([np.pad(r.curve_nfev, (0, T - r.curve_nfev.size), mode="edge") for r in recs])
    fs = recs[0].f_star
    return c, n, float("nan") if fs is None else float(fs)


@dataclass
class SweepData:
    """What a report needs, read from a store.

    Attributes
    ----------
    plan : ExperimentPlan
        The stored plan.
    algorithms, functions : tuple of str
        Plan order, restricted to those with at least one stored run.
    finals : dict
        ``(algorithm, function) -> {"run", "fun", "error", "nfev", "wall", "failed"}``.
    reference : str
        The algorithm the Wilcoxon tests are against (MAWDO, else the plan's last algorithm).
    stored, total : int
        Stored runs and runs in the plan.
    """

    plan: ExperimentPlan
    algorithms: tuple[str, ...]
    functions: tuple[str, ...]
    finals: dict
    reference: str
    stored: int
    total: int
    plan_hash: str
    library_version: str

    def values(self, kind: str) -> dict[tuple[str, str], np.ndarray]:
        return {k: v[kind] for k, v in self.finals.items()}


def load(store: Store, reference: str | None = None) -> SweepData:
    """Read a store into :class:`SweepData`."""
    plan = store.plan
    if plan.kind != ExperimentPlan.study_kind:
        raise ValueError(
            f"{store.path} holds a {plan.kind!r} study, not a benchmark sweep; "
            f"write its report with its own command (mawdo plan report for planning studies)"
        )
    got = finals(store)
    have = {k for k, v in got.items() if v["fun"].size}
    algos = tuple(a for a in plan.algorithms if any((a, f) in have for f in plan.functions))
    fns = tuple(f for f in plan.functions if any((a, f) in have for a in plan.algorithms))
    if reference is None:
        reference = REFERENCE if REFERENCE in algos else (algos[-1] if algos else REFERENCE)
    elif reference.lower() not in algos:
        raise ValueError(
            f"reference {reference!r} is not an algorithm of this store ({', '.join(algos)})"
        )
    reference = reference.lower()
    return SweepData(
        plan,
        algos,
        fns,
        got,
        reference,
        store.count(),
        plan.total_runs,
        store.meta["plan_hash"],
        store.meta["library_version"],
    )


def summaries(data: SweepData, kind: str) -> dict[tuple[str, str], stats.Summary]:
    """Best, mean, std ... of ``kind`` (``"fun"`` or ``"error"``) per (algorithm, function)."""
    return {k: stats.summarize(v) for k, v in data.values(kind).items()}


def comparisons(data: SweepData) -> list[stats.Comparison]:
    """The Wilcoxon comparisons of the reference against every other algorithm, per function."""
    rivals = [a for a in data.algorithms if a != data.reference]
    # Ranks of raw f and of f - f* agree; raw f is stored exactly, so the tests use it.
    return stats.compare(data.values("fun"), data.reference, rivals, data.functions)
