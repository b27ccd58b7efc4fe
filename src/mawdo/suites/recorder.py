"""Best-so-far against *evaluations* (not iterations), per run, for the benchmarking protocol.

:class:`EvaluationRecorder` wraps a problem's formula. :func:`mawdo.minimize` calls the formula
once per iteration on all ``R x m`` candidates, run-major (run 0's ``m`` rows, then run 1's ...),
so the recorder sees every evaluation of every run in order and keeps, per run, the evaluation
numbers at which the best-so-far improved (what IOHprofiler's ``Analyzer`` logs). Runtime to any
target, fixed-budget values and IOH logs are read from these traces.

Counting mirrors the driver's :class:`~mawdo.problem.Evaluator`: under ``max_evals`` only the
evaluated prefix of the last batch reaches the formula; a run that reached ``target`` stops
counting (the driver still evaluates it, its optimizer state goes on, but nothing is recorded).
:func:`run_problem` checks the recorder's counts against the driver's ``nfev`` and raises if they
ever differ.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from mawdo.suites.base import SuiteFunction, evaluation_budget, replace_formula


@njit(cache=True, nogil=True)
def scan_improvements(V, best, counted, nfev, r_out, e_out, y_out, last):  # pragma: no cover
    """One batch's improvements of each run's best-so-far; updates ``best`` and ``nfev``.

    Parameters (``R`` runs, ``m`` values each)
    ----------
    V : float64 (R, m)
        The runs' values in evaluation order; NaN and +-inf never improve (the driver ranks
        them worst).
    best : float64 (R,)
        Best-so-far before the batch (+inf before any finite value); updated.
    counted : bool (R,)
        Runs still recording; the others keep ``best`` and ``nfev``.
    nfev : int64 (R,)
        Evaluations recorded before the batch; ``m`` is added to counted runs.
    r_out, e_out, y_out : (R m,)
        Filled with ``k`` improvements, run by run: run, 1-based evaluation number, value.
    last : int64 (R,)
        Per run the batch index of its last improvement (its first least value), -1 if none.

    Returns
    -------
    int
        ``k``, the number of improvements.
    """
    R, m = V.shape
    k = 0
    for r in range(R):
        last[r] = -1
        if not counted[r]:
            continue
        b = best[r]
        for j in range(m):
            v = V[r, j]
            if -np.inf < v < b:
                b = v
                r_out[k] = r
                e_out[k] = nfev[r] + j + 1
                y_out[k] = v
                last[r] = j
                k += 1
        best[r] = b
        nfev[r] += m
    return k


@dataclass(frozen=True)
class RunTrace:
    """One run's best-so-far record.

    Attributes
    ----------
    evals : numpy.ndarray of int64
        1-based evaluation numbers at which the best-so-far improved, shape ``(k,)``, increasing.
    best_y : numpy.ndarray of float
        Best-so-far raw value (``f``, not ``f - f_star``) from each of those evaluations on,
        shape ``(k,)``, strictly decreasing.
    total_evals : int
        Evaluations the run spent.
    best_x : numpy.ndarray
        The best point, shape ``(D,)`` (NaN when no finite value was seen).
    """

    evals: np.ndarray
    best_y: np.ndarray
    total_evals: int
    best_x: np.ndarray

    def best_at(self, evaluations) -> np.ndarray:
        """Best-so-far after ``evaluations`` evaluations (+inf before the first finite value)."""
        b = np.asarray(evaluations)
        k = np.searchsorted(self.evals, b, side="right")
        padded = np.concatenate([[np.inf], self.best_y])
        return padded[k]


class EvaluationRecorder:
    """A formula wrapper that records per-run best-so-far against evaluations.

    Parameters
    ----------
    func : callable
        The batched formula ``(n, D) -> (n,)``.
    runs : int
        Runs ``R`` of the batch; every call must carry ``R x m`` rows, run-major.
    target : float, optional
        Absolute value at which the driver stops a run (``minimize(target=...)``); a run whose
        best-so-far is ``<= target`` records nothing more.
    """

    def __init__(self, func, runs: int, target: float | None = None) -> None:
        if not isinstance(runs, int | np.integer) or runs < 1:
            raise ValueError(f"runs={runs!r} must be an integer >= 1")
        self.func, self.runs, self.target = func, int(runs), target
        self.nfev = np.zeros(self.runs, dtype=np.int64)
        self.best = np.full(self.runs, np.inf)
        self.best_x: np.ndarray | None = None
        self._chunks: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
        self._failed = False

    def __call__(self, X: np.ndarray) -> np.ndarray:
        n = X.shape[0]
        if n % self.runs:
            if self._failed:  # the driver re-evaluates run by run to name a failing run
                return self.func(X)
            raise ValueError(
                f"EvaluationRecorder for {self.runs} runs got {n} rows; a batch must hold "
                f"runs x m rows (pass the same runs= to minimize)"
            )
        try:
            out = self.func(X)
        except Exception:
            self._failed = True
            raise
        self._record(X, np.asarray(out, dtype=float).reshape(-1))
        return out

    def _record(self, X: np.ndarray, vals: np.ndarray) -> None:
        R = self.runs
        m = vals.size // R
        if m == 0 or vals.size != X.shape[0]:
            return  # a wrong shape: the driver raises ObjectiveError about it
        V = np.ascontiguousarray(vals, dtype=np.float64).reshape(R, m)
        counted = np.ones(R, bool) if self.target is None else ~(self.best <= self.target)
        r, e, y = np.empty(R * m, np.int64), np.empty(R * m, np.int64), np.empty(R * m)
        last = np.empty(R, np.int64)
        k = scan_improvements(V, self.best, counted, self.nfev, r, e, y, last)
        if k:
            self._chunks.append((r[:k].copy(), e[:k].copy(), y[:k].copy()))
            if self.best_x is None:
                self.best_x = np.full((R, X.shape[1]), np.nan)
            upd = last >= 0
            self.best_x[upd] = X.reshape(R, m, -1)[upd, last[upd]]

    def traces(self) -> list[RunTrace]:
        """The runs' records, in run order."""
        if self._chunks:
            r, e, y = (np.concatenate(c) for c in zip(*self._chunks, strict=True))
        else:
            r = e = np.empty(0, np.int64)
            y = np.empty(0)
        order = np.lexsort((e, r))
        r, e, y = r[order], e[order], y[order]
        cuts = np.searchsorted(r, np.arange(self.runs + 1))
        out = []
        for k in range(self.runs):
            s = slice(cuts[k], cuts[k + 1])
            bx = self.best_x[k].copy() if self.best_x is not None else np.array([np.nan])
            out.append(RunTrace(e[s].astype(np.int64), y[s].copy(), int(self.nfev[k]), bx))
        return out


def run_problem(
    problem: SuiteFunction,
    algorithm="mawdo",
    *,
    runs: int,
    budget: float,
    seed=0,
    first_run: int = 0,
    final_target: float | None = 1e-8,
    **options,
):
    """Run ``algorithm`` on a suite problem under COCO's protocol and record every evaluation.

    Parameters
    ----------
    problem : SuiteFunction
        From :func:`mawdo.suites.get_problem`.
    algorithm : str or Optimizer
        Any registered optimizer (``cmaes``, ``random``, ``mawdo``, ...).
    runs : int
        Independent runs, one vectorised batch.
    budget : float
        Evaluations per dimension, > 0; each run gets exactly ``ceil(budget * D)`` evaluations
        (OBL's extra evaluations count), fewer if it reaches the final target.
    seed, first_run
        As in :func:`mawdo.minimize`; run ``k`` is the same alone or in any batch.
    final_target : float or None
        Precision ``f - f_star`` at which a run stops (COCO's last target, 1e-8); None runs
        the whole budget.
    **options
        The algorithm's coefficients.

    Returns
    -------
    result : OptimizeResult
        The driver's result.
    traces : list of RunTrace
        Per-run best-so-far against evaluations.
    """
    from mawdo.minimize import minimize

    max_evals = evaluation_budget(budget, problem.dim)
    target = None if final_target is None else problem.f_star + final_target
    rec = EvaluationRecorder(problem.func, runs, target)
    res = minimize(
        replace_formula(problem, rec),
        algorithm=algorithm,
        runs=runs,
        seed=seed,
        first_run=first_run,
        max_evals=max_evals,
        target=target,
        runs_per_block=runs,  # the recorder reads every call as R x m rows, run-major
        **options,
    )
    traces = rec.traces()
    if not np.array_equal(rec.nfev, res.nfev) or not np.array_equal(rec.best, res.fun):
        raise RuntimeError(  # an invariant of the recorder, not a user error
            f"evaluation record out of step with the driver: recorded {rec.nfev.tolist()} "
            f"evaluations and best {rec.best.tolist()}, driver {res.nfev.tolist()} and "
            f"{res.fun.tolist()}"
        )
    return res, traces
