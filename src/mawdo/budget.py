"""Budgets and termination: when each run of a batch stops, and why.

One :class:`Budget` holds the limits (iterations, evaluations, target value, wall-clock time);
one :class:`RunLog` per batch keeps each run's best-so-far, history and stopping status. The
driver (:func:`mawdo.minimize`) only asks, evaluates, tells and records, so every optimizer is
counted and stopped the same way.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numba import njit

from mawdo.result import STATUS_MESSAGES, EvaluationTrace
from mawdo.util.validate import check_int, check_real

DEFAULT_MAX_ITER = 500

# Status codes, the keys of STATUS_MESSAGES.
MAX_ITER, MAX_EVALS, TARGET, TIME, CALLBACK = 0, 1, 2, 3, 4


@dataclass(frozen=True)
class Budget:
    """The limits of a batch of runs (validated; at least one of iterations or evaluations).

    Parameters
    ----------
    max_iter : int, optional
        Iterations per run, >= 1 (the initial population is iteration 1). Default 500 when
        neither ``max_iter`` nor ``max_evals`` is given.
    max_evals : int, optional
        Exact evaluations per run, >= 1; the last iteration is truncated to hit it.
    target : float, optional
        A run stops once its best value is <= ``target`` (finite).
    max_time : float, optional
        Wall-clock seconds for the whole batch, finite and > 0.
    """

    max_iter: int | None = None
    max_evals: int | None = None
    target: float | None = None
    max_time: float | None = None

    def __post_init__(self) -> None:
        for name in ("max_iter", "max_evals"):
            val = getattr(self, name)
            if val is not None:
                check_int(name, val, 1, what="a positive integer")
        if self.target is not None:
            check_real("target", self.target)
        if self.max_time is not None:
            check_real("max_time", self.max_time, 0, None, low_open=True)
        if self.max_iter is None and self.max_evals is None:
            object.__setattr__(self, "max_iter", DEFAULT_MAX_ITER)

    def horizon(self, pop_size: int) -> int:
        """Iterations T that schedules (MAWDO's mixing, GWO's ``a``) are planned over: under an
        evaluation budget, the number of plain iterations that budget buys."""
        if self.max_iter is not None:
            return self.max_iter
        return math.ceil(self.max_evals / pop_size)


@njit(cache=True, nogil=True)
def take_best(X, F, active, best_f, best_x, nit, it):  # pragma: no cover - compiled
    """Each active run's best of ``F`` (its first least value) replaces ``best_f``/``best_x`` when
    strictly better; ``nit`` of active runs becomes ``it``.

    ``F (R, n)`` comes from the evaluator (no NaN); ``X`` is ``(R, n, D)``. One pass instead
    of NumPy's argmin, gathers and masked writes (about 5 us an iteration).
    """
    R, n = F.shape
    if n == 0:
        return
    for r in range(R):
        if not active[r]:
            continue
        j = 0
        fj = F[r, 0]
        for k in range(1, n):
            if F[r, k] < fj:
                fj = F[r, k]
                j = k
        if fj < best_f[r]:
            best_f[r] = fj
            for d in range(X.shape[2]):  # (no slice assignment: compiles faster)
                best_x[r, d] = X[r, j, d]
        nit[r] = it


@njit(cache=True, nogil=True)
def scan_improvements(F, active, best_f, nfev, r_out, e_out, y_out):  # pragma: no cover
    """Each active run's improvements of its best-so-far within one iteration, in evaluation
    order (read before :func:`take_best` moves ``best_f``).

    Parameters (``R`` runs, ``n`` candidates each)
    ----------
    F : float64 (R, n)
        The evaluator's values (non-finite and unevaluated candidates are +inf: never better).
    active : bool (R,)
        Runs still counting; the others record nothing (the target freeze).
    best_f : float64 (R,)
        Best-so-far before the iteration (+inf before any finite value); not written.
    nfev : int64 (R,)
        Evaluations of each run before the iteration.
    r_out, e_out, y_out : (R n,)
        Filled with ``k`` improvements, run by run: run, 1-based evaluation number, value.

    Returns
    -------
    int
        ``k``. A strict ``<`` makes a tie belong to its first evaluation (COCO's first least
        value), so the last improvement of a run is the candidate :func:`take_best` keeps.
    """
    R, n = F.shape
    k = 0
    for r in range(R):
        if not active[r]:
            continue
        b = best_f[r]
        for j in range(n):
            if F[r, j] < b:
                b = F[r, j]
                r_out[k], e_out[k], y_out[k] = r, nfev[r] + j + 1, b
                k += 1
    return k


class EvaluationLog:
    """Per-run improvements of the best-so-far against evaluations, gathered iteration by
    iteration (the opt-in ``trace_evaluations`` of :func:`mawdo.minimize`)."""

    def __init__(self, runs: int) -> None:
        self.runs = runs
        self.nfev = np.zeros(runs, dtype=np.int64)  # evaluations before the next iteration
        self.chunks: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []

    def record(self, F: np.ndarray, active: np.ndarray, best_f: np.ndarray, nfev) -> None:
        """Scan one iteration's ``F (R, n)`` against ``best_f`` before it; ``nfev`` after it."""
        size = F.size
        r, e, y = np.empty(size, np.int64), np.empty(size, np.int64), np.empty(size)
        k = scan_improvements(F, active, best_f, self.nfev, r, e, y)
        if k:
            self.chunks.append((r[:k].copy(), e[:k].copy(), y[:k].copy()))
        self.nfev[:] = nfev

    def traces(self) -> list[EvaluationTrace]:
        """One :class:`~mawdo.result.EvaluationTrace` per run, in run order."""
        if self.chunks:
            r, e, y = (np.concatenate(c) for c in zip(*self.chunks, strict=True))
        else:
            r, e, y = np.empty(0, np.int64), np.empty(0, np.int64), np.empty(0)
        order = np.argsort(r, kind="stable")  # within a run the chunks are in time order
        r, e, y = r[order], e[order], y[order]
        self.chunks = [(r, e, y)] if r.size else []  # one chunk: a callback's snapshots stay cheap
        cuts = np.searchsorted(r, np.arange(self.runs + 1))
        return [
            EvaluationTrace(e[cuts[i] : cuts[i + 1]].copy(), y[cuts[i] : cuts[i + 1]].copy())
            for i in range(self.runs)
        ]


class RunLog:
    """Per-run best-so-far, history and status of a batch under one :class:`Budget`.

    Parameters
    ----------
    budget : Budget
        The limits.
    runs : int
        Number of runs R.
    x_start : numpy.ndarray
        Point reported as ``x`` by a run that has evaluated nothing yet, shape ``(D,)``.
    trace : bool
        Also keep each run's best-so-far against evaluations (:class:`EvaluationLog`).
    """

    def __init__(self, budget: Budget, runs: int, x_start: np.ndarray, trace: bool = False):
        self.budget = budget
        self.best_f = np.full(runs, np.inf)
        self.best_x = np.tile(x_start, (runs, 1))
        self.active = np.ones(runs, dtype=bool)
        self.status = np.zeros(runs, dtype=np.int64)
        self.nit = np.zeros(runs, dtype=np.int64)
        self.hist: list[np.ndarray] = []
        self.hist_nfev: list[np.ndarray] = []
        self.evaluations = EvaluationLog(runs) if trace else None
        self.message = STATUS_MESSAGES[MAX_ITER]
        self.t0 = time.perf_counter()

    def elapsed(self) -> float:
        return time.perf_counter() - self.t0

    def eval_limit(self, nfev: np.ndarray) -> int | None:
        """Candidates each run may still evaluate this iteration (None: no evaluation budget)."""
        if self.budget.max_evals is None:
            return None
        return int(self.budget.max_evals - nfev[self.active].max(initial=0))

    def record(self, it: int, X: np.ndarray, F: np.ndarray, nfev: np.ndarray) -> None:
        """Take iteration ``it``'s candidates ``X (R, n, D)`` and values ``F (R, n)``.

        The driver keeps its own best-so-far from evaluated points only; stopped runs freeze.
        """
        if self.evaluations is not None:
            self.evaluations.record(F, self.active, self.best_f, nfev)
        take_best(X, F, self.active, self.best_f, self.best_x, self.nit, it)
        self.hist.append(self.best_f.copy())
        self.hist_nfev.append(nfev.copy())

    def finished(self, it: int, n: int, limit: int | None) -> bool:
        """Apply the budget after iteration ``it`` (``n`` candidates per run, evaluation
        ``limit`` as given to the evaluator); True when the whole batch stops."""
        b = self.budget
        if b.target is not None:
            hit = self.active & (self.best_f <= b.target)
            self.status[hit], self.active[hit] = TARGET, False
        if b.max_evals is not None and limit is not None and limit <= n:
            self.stop(MAX_EVALS)
        if b.max_iter is not None and it >= b.max_iter:
            self.stop(MAX_ITER)
        if not self.active.any():
            if b.target is not None and (self.status == TARGET).all():
                self.message = STATUS_MESSAGES[TARGET]
            return True
        if b.max_time is not None and self.elapsed() >= b.max_time:
            self.stop(TIME)
            return True
        return False

    def stop(self, code: int) -> None:
        """Stop every run still going, with status ``code``; the batch message follows it."""
        self.status[self.active], self.active[:] = code, False
        self.message = STATUS_MESSAGES[code]

    def history(self) -> tuple[np.ndarray, np.ndarray]:
        """``(history, history_nfev)``, each ``(R, T)``."""
        R = self.best_f.size
        if not self.hist:
            return np.empty((R, 0)), np.empty((R, 0))
        return np.stack(self.hist, axis=1), np.stack(self.hist_nfev, axis=1)
