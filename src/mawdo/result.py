"""``OptimizeResult``: what a batch of runs returns, with per-run arrays (and, on request, each
run's best-so-far against evaluations, :class:`EvaluationTrace`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

# One table of termination reasons (as scipy.optimize keeps one table of status messages).
STATUS_MESSAGES = {
    0: "maximum number of iterations reached",
    1: "maximum number of evaluations reached",
    2: "target value reached",
    3: "time limit reached",
    4: "stopped by callback",
}


@dataclass(frozen=True)
class EvaluationTrace:
    """One run's best-so-far against evaluations (``minimize(..., trace_evaluations=True)``).

    The record IOHprofiler's ``Analyzer`` logs and COCO reads runtimes from: the evaluation
    numbers at which the best-so-far value improved, and the value from there on. Within one
    iteration an improvement belongs to the first evaluation that reached its least value
    (COCO's "first least value"); NaN and +-inf never improve; a run that reached ``target``
    records nothing more.

    Attributes
    ----------
    evals : numpy.ndarray of int64
        1-based evaluation numbers of the run at which its best-so-far improved, shape ``(k,)``,
        strictly increasing, each ``<= nfev`` of the run.
    best_y : numpy.ndarray of float
        Best-so-far value (raw ``f``, not ``f - f_star``) from each of those evaluations on,
        shape ``(k,)``, strictly decreasing.
    """

    evals: np.ndarray
    best_y: np.ndarray

    def best_at(self, evaluations) -> np.ndarray:
        """Best-so-far after ``evaluations`` evaluations (int or array of ints >= 0; +inf
        before the first finite value)."""
        k = np.searchsorted(self.evals, np.asarray(evaluations), side="right")
        return np.concatenate([[np.inf], self.best_y])[k]


@dataclass
class OptimizeResult:
    """The outcome of ``R`` independent runs of one algorithm on one problem.

    Attributes
    ----------
    x : numpy.ndarray
        Best point found by each run, shape ``(R, D)``, in the problem's coordinates.
    fun : numpy.ndarray
        Best objective value of each run, shape ``(R,)``.
    nfev : numpy.ndarray
        Objective evaluations spent by each run, shape ``(R,)`` (OBL's extra evaluations included).
    nit : numpy.ndarray
        Iterations of each run, shape ``(R,)``; the initial population is iteration 1.
    history : numpy.ndarray
        Best-so-far value after each iteration, shape ``(R, T)``; a run that stopped early
        repeats its final value.
    history_nfev : numpy.ndarray
        Evaluations spent after each iteration, shape ``(R, T)`` (for equal-budget plots).
    status : numpy.ndarray
        Termination code per run, shape ``(R,)``; see ``STATUS_MESSAGES``.
    message : str
        Why the batch stopped.
    algorithm : str
        Registered name of the algorithm.
    params : dict
        The algorithm's full parameter set (defaults included).
    problem : str
        Name of the objective.
    seed : object
        The master seed the runs were derived from.
    time : float
        Wall-clock seconds for the whole batch.
    f_star : float or None
        Known optimum of the problem, when there is one.
    metadata : dict
        Algorithm metadata (reference, ``reconstructed`` flag).
    evaluation_trace : list of EvaluationTrace or None
        Per run (``R`` items), its best-so-far against evaluations; None unless
        ``minimize(..., trace_evaluations=True)``.
    """

    x: np.ndarray
    fun: np.ndarray
    nfev: np.ndarray
    nit: np.ndarray
    history: np.ndarray
    history_nfev: np.ndarray
    status: np.ndarray
    message: str
    algorithm: str
    params: dict = field(default_factory=dict)
    problem: str = "objective"
    seed: object = None
    time: float = 0.0
    f_star: float | None = None
    metadata: dict = field(default_factory=dict)
    evaluation_trace: list[EvaluationTrace] | None = None

    @property
    def runs(self) -> int:
        return int(self.fun.shape[0])

    @property
    def success(self) -> np.ndarray:
        """Per run: found at least one finite objective value."""
        return np.isfinite(self.fun)

    @property
    def best_run(self) -> int:
        """Index of the run with the lowest final value."""
        return int(np.argmin(self.fun))

    @property
    def error(self) -> np.ndarray | None:
        """``fun - f_star`` per run, when the optimum is known."""
        return None if self.f_star is None else self.fun - self.f_star

    def summary(self) -> dict:
        """Best / mean / std (ddof=1) / median of the final values, and mean nfev."""
        f = self.fun
        return {
            "best": float(np.min(f)),
            "mean": float(np.mean(f)),
            "std": float(np.std(f, ddof=1)) if f.size > 1 else 0.0,
            "median": float(np.median(f)),
            "worst": float(np.max(f)),
            "nfev": float(np.mean(self.nfev)),
            "time": self.time,
        }

    def __repr__(self) -> str:
        s = self.summary()
        return (
            f"OptimizeResult({self.algorithm} on {self.problem}: runs={self.runs}, "
            f"best={s['best']:.6g}, mean={s['mean']:.6g}, std={s['std']:.3g}, "
            f"nfev={s['nfev']:.0f}, time={self.time:.3f}s, message={self.message!r})"
        )
