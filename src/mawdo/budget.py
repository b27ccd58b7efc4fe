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

from mawdo.result import STATUS_MESSAGES
from mawdo.validate import check_int, check_real

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
            best_x[r, :] = X[r, j, :]
        nit[r] = it


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
    """

    def __init__(self, budget: Budget, runs: int, x_start: np.ndarray) -> None:
        self.budget = budget
        self.best_f = np.full(runs, np.inf)
        self.best_x = np.tile(x_start, (runs, 1))
        self.active = np.ones(runs, dtype=bool)
        self.status = np.zeros(runs, dtype=np.int64)
        self.nit = np.zeros(runs, dtype=np.int64)
        self.hist: list[np.ndarray] = []
        self.hist_nfev: list[np.ndarray] = []
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
