"""The numbers of a suite-study report, as arrays: aRT, fixed-budget precision, Friedman ranks,
runtime ECDFs. Pure functions of :class:`~mawdo.experiments.kinds.suite.data.StudyRuns`; the
tables and figures only format them (tests compare these with values recomputed from the raw store).
"""

from __future__ import annotations

import math

import numpy as np

from mawdo.experiments.kinds.suite.data import StudyRuns, precision_at, runtime_table
from mawdo.experiments.kinds.suite.metrics import (
    aggregate_runtime,
    friedman_ranks,
    runtime_ecdf,
    standard_targets,
)
from mawdo.experiments.stats import Friedman
from mawdo.suites import SUITES

ART_TARGETS = (1e1, 1e-1, 1e-3, 1e-5, 1e-8)
"""Precision targets of the aRT tables."""

RANK_FLOOR = 1e-8
"""Precisions below COCO's final target count as equal when ranking (runs stop there)."""


def art(study: StudyRuns, dim: int, targets=ART_TARGETS) -> dict[int, np.ndarray]:
    """aRT in evaluations per function: ``{fid: (algorithms, T)}`` (``inf``: never reached).

    All instances and runs of a function are pooled, as COCO does.
    """
    out = {}
    for fid in study.functions:
        rows = []
        for algo in study.algorithms:
            runs = study.select(algo, fid, dim)
            if not runs:
                rows.append(np.full(len(targets), np.nan))
                continue
            rt, spent = runtime_table(runs, targets)
            rows.append(aggregate_runtime(rt, spent))
        out[fid] = np.array(rows)
    return out


def success_counts(study: StudyRuns, dim: int, target: float = 1e-8) -> dict[int, np.ndarray]:
    """Runs that reached ``target`` and runs in all: ``{fid: (algorithms, 2)}``."""
    out = {}
    for fid in study.functions:
        rows = []
        for algo in study.algorithms:
            runs = study.select(algo, fid, dim)
            rt, _ = runtime_table(runs, [target])
            rows.append((int(np.isfinite(rt).sum()), len(runs)))
        out[fid] = np.array(rows)
    return out


def budget_grid(study: StudyRuns, dim: int) -> np.ndarray:
    """Fixed budgets in evaluations: ``D * 10^k`` below the budget, then the budget itself."""
    top = math.ceil(study.budget * dim - 1e-9)
    decades = [dim * 10**k for k in range(1, 12) if dim * 10**k < top]
    return np.array([*decades, top], dtype=float)


def median_precision(study: StudyRuns, dim: int, budgets) -> dict[int, np.ndarray]:
    """Median precision ``f - f_opt`` over instances and runs after each budget:
    ``{fid: (algorithms, B)}``."""
    out = {}
    for fid in study.functions:
        rows = []
        for algo in study.algorithms:
            runs = study.select(algo, fid, dim)
            p = precision_at(runs, budgets)
            rows.append(np.median(p, axis=0) if len(runs) else np.full(len(budgets), np.nan))
        out[fid] = np.array(rows)
    return out


def friedman_final(study: StudyRuns, dims, functions=None) -> Friedman:
    """Friedman ranks over ``(function, instance, dimension)`` blocks of the median final
    precision (floored at :data:`RANK_FLOOR`, so runs that all solved the problem tie), over
    ``functions`` (default: all of the study's)."""
    blocks = []
    for dim in dims:
        for fid in study.functions if functions is None else functions:
            for iid in sorted({r.instance for r in study.select(dim=dim, function_id=fid)}):
                row = []
                for algo in study.algorithms:
                    runs = [r for r in study.select(algo, fid, dim) if r.instance == iid]
                    fin = [max(float(r.precision[-1]), RANK_FLOOR) for r in runs if r.evals.size]
                    row.append(np.median(fin) if fin else np.nan)
                blocks.append(row)
    return friedman_ranks(np.array(blocks).reshape(-1, len(study.algorithms)), study.algorithms)


def groups(study: StudyRuns) -> dict[str, tuple[int, ...]]:
    """Function groups of the study: every function, then the suite's own groups
    (:attr:`mawdo.suites.SuiteSpec.groups`: COCO's five for BBOB), each cut to the functions
    in the plan. A store in opfunu's numbering (``study.numbering``) has no groups: its ids
    are not those the groups name."""
    out = {"all functions": study.functions}
    suite_groups = {} if study.numbering else SUITES[study.suite].groups
    for name, ids in suite_groups.items():
        kept = tuple(f for f in ids if f in study.functions)
        if kept:
            out[name] = kept
    return out


def ecdf_curves(study: StudyRuns, dim: int, functions, x) -> dict[str, np.ndarray]:
    """Runtime ECDF over COCO's 51 targets ``1e2 .. 1e-8`` for each algorithm, on budgets
    ``x`` in evaluations per dimension; each function weighs the same."""
    targets = standard_targets()
    out = {}
    for algo in study.algorithms:
        per_fn = [runtime_table(study.select(algo, f, dim), targets)[0] for f in functions]
        per_fn = [rt for rt in per_fn if rt.size]
        out[algo] = runtime_ecdf(per_fn, x, dim) if per_fn else np.full(len(x), np.nan)
    return out
