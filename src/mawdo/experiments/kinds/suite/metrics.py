"""COCO's performance measures as pure array functions: targets, runtimes, aRT, ECDFs, budgets.

A run is summarised by its best-so-far record against evaluations (``evals``: 1-based evaluation
numbers where the best improved; ``best_y``: the best raw value from there on), the format of
the driver's :class:`mawdo.result.EvaluationTrace` and of IOHprofiler's logs. Precision is
``f - f_opt``.

References: Hansen, Auger, Brockhoff, Tusar, "Anytime performance assessment in blackbox
optimization benchmarking", IEEE TEVC 26(6), 2022; Hansen et al., "COCO: performance assessment",
arXiv:1605.03560 (aRT, runtime ECDFs over function-target pairs, the 51 targets 1e2..1e-8).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from mawdo.experiments.stats import Friedman, friedman
from mawdo.suites.bbob import BBOB_GROUPS

__all__ = ["BBOB_GROUPS", "aggregate_runtime", "fixed_budget", "friedman_ranks", "function_group",
           "runtime_ecdf", "runtimes", "standard_targets"]  # fmt: skip


def standard_targets(high: float = 2.0, low: float = -8.0, per_decade: int = 5) -> np.ndarray:
    """COCO's precision targets ``10^high .. 10^low``, ``per_decade`` per decade, decreasing.

    The default is COCO's runtime-ECDF set: 51 targets ``10^{2, 1.8, ..., -8}`` (``1e2 .. 1e-8``).

    Parameters
    ----------
    high, low : float
        Base-10 exponents of the first (easiest) and last (hardest) target, ``high > low``.
    per_decade : int
        Targets per factor of ten, >= 1.

    Returns
    -------
    numpy.ndarray
        Shape ``(round((high - low) * per_decade) + 1,)``, strictly decreasing, > 0.
    """
    if not high > low:
        raise ValueError(f"targets need high > low exponents; got high={high}, low={low}")
    if not isinstance(per_decade, int) or per_decade < 1:
        raise ValueError(f"per_decade={per_decade!r} must be an integer >= 1")
    n = round((high - low) * per_decade) + 1
    return 10.0 ** np.linspace(high, low, n)


def _check_trace(evals, best_y) -> tuple[np.ndarray, np.ndarray]:
    e = np.asarray(evals, dtype=float)
    y = np.asarray(best_y, dtype=float)
    if e.shape != y.shape or e.ndim != 1:
        raise ValueError(f"evals and best_y must be 1-D of one length; got {e.shape}, {y.shape}")
    if e.size > 1 and (np.any(np.diff(e) <= 0) or np.any(np.diff(y) > 0)):
        raise ValueError("a best-so-far record needs increasing evals and non-increasing best_y")
    return e, y


def runtimes(evals, best_y, f_opt: float, targets) -> np.ndarray:
    """Evaluations a run needed to reach each target: the first ``e`` with ``f - f_opt <= t``.

    Parameters
    ----------
    evals, best_y : array_like
        The run's best-so-far record (see the module docstring), shape ``(k,)``.
    f_opt : float
        Optimum value of the problem.
    targets : array_like
        Precision targets, > 0, any order, shape ``(T,)``.

    Returns
    -------
    numpy.ndarray
        Shape ``(T,)``, float: an evaluation number, or ``inf`` for a target never reached.
    """
    e, y = _check_trace(evals, best_y)
    t = np.asarray(targets, dtype=float)
    prec = y - f_opt  # non-increasing
    # first index with prec <= t: count of entries with prec > t (prec is sorted descending)
    idx = np.searchsorted(-prec, -t, side="left")
    padded = np.concatenate([e, [np.inf]])
    return padded[idx]


def aggregate_runtime(rt, total_evals) -> np.ndarray:
    """aRT, COCO's average runtime: evaluations of all runs over the number of successes.

    ``aRT(t) = (sum over successful runs of their runtime + sum over failed runs of their
    evaluations) / (number of runs that reached t)``; ``inf`` when no run reached ``t``.

    Parameters
    ----------
    rt : array_like
        Runtimes ``(runs, T)`` from :func:`runtimes` (``inf`` = not reached), or a stack of such
        sets ``(..., runs, T)`` (bootstrap samples, say).
    total_evals : array_like
        Evaluations each run spent, shape ``(runs,)`` (or ``(..., runs)`` with a stack).

    Returns
    -------
    numpy.ndarray
        Shape ``(T,)`` (or ``(..., T)``), in evaluations.
    """
    rt = np.asarray(rt, dtype=float)
    rt = np.atleast_2d(rt) if rt.ndim < 2 else rt
    tot = np.asarray(total_evals, dtype=float)
    if tot.shape != rt.shape[:-1]:
        n_tot = tot.shape[-1] if tot.ndim else 1
        raise ValueError(f"{rt.shape[-2]} runs of runtimes but {n_tot} total_evals")
    tot = tot[..., None]
    ok = np.isfinite(rt)
    spent = np.where(ok, rt, tot).sum(axis=-2)
    n_ok = ok.sum(axis=-2)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(n_ok > 0, spent / np.maximum(n_ok, 1), np.inf)


def runtime_ecdf(problem_runtimes: Sequence, budgets, dim: int = 1) -> np.ndarray:
    """Runtime ECDF: the fraction of (problem, run, target) triples solved within each budget.

    Each problem (a function, or a function-instance pair) weighs the same, whatever its number
    of runs; within a problem every (run, target) pair weighs the same. COCO's bootstrapped
    restarts are not simulated: a failed run counts as unsolved at every budget
    (docs/deviations.md).

    Parameters
    ----------
    problem_runtimes : sequence of array_like
        One ``(runs_i, T)`` runtime array per problem (same targets ``T`` for all).
    budgets : array_like
        Budgets in evaluations per dimension (the ECDF's x axis), shape ``(B,)``.
    dim : int
        Dimension D; runtimes are divided by it.

    Returns
    -------
    numpy.ndarray
        Shape ``(B,)``, non-decreasing fractions in ``[0, 1]``.
    """
    if len(problem_runtimes) == 0:
        raise ValueError("runtime_ecdf needs at least one problem")
    b = np.asarray(budgets, dtype=float)
    fracs = []
    for rt in problem_runtimes:
        r = np.asarray(rt, dtype=float).ravel() / dim
        r = np.sort(r[np.isfinite(r)])
        total = np.asarray(rt).size
        fracs.append(np.searchsorted(r, b, side="right") / total)
    return np.mean(fracs, axis=0)


def fixed_budget(evals, best_y, budgets) -> np.ndarray:
    """Best-so-far value after each budget (in evaluations); ``inf`` before the first value.

    Parameters
    ----------
    evals, best_y : array_like
        The run's best-so-far record, shape ``(k,)``.
    budgets : array_like
        Evaluation counts, shape ``(B,)``.
    """
    e, y = _check_trace(evals, best_y)
    k = np.searchsorted(e, np.asarray(budgets, dtype=float), side="right")
    return np.concatenate([[np.inf], y])[k]


def function_group(fid: int) -> str:
    """The COCO group of BBOB function ``fid`` (1-24)."""
    for name, ids in BBOB_GROUPS.items():
        if fid in ids:
            return name
    raise ValueError(f"BBOB functions are 1-24; got {fid!r}")


def friedman_ranks(table, algorithms: Sequence[str]) -> Friedman:
    """Friedman mean ranks of a ``(problems, algorithms)`` table, lower is better.

    Use aRT at a target, or a fixed-budget precision, as the table; ties (two ``inf`` aRTs) share
    their average rank. Delegates to :func:`mawdo.experiments.stats.friedman`.
    """
    m = np.asarray(table, dtype=float)
    # rankdata ranks inf equal to inf, which is what two unsolved entries should get
    return friedman(m, algorithms)
