"""The driver loop: init -> (ask, evaluate, tell)* -> OptimizeResult.

Budgets (``max_iter``, ``max_evals``, ``target``, ``max_time``) and the callback live here, not
in the algorithms, so every optimizer is stopped and counted the same way.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

from mawdo.optimizers.base import Optimizer, Space
from mawdo.optimizers.registry import make_optimizer
from mawdo.problem import Evaluator, Problem, as_bounds
from mawdo.result import STATUS_MESSAGES, OptimizeResult
from mawdo.streams import RunStreams, run_seed_sequences

DEFAULT_MAX_ITER = 500


def make_problem(
    fun,
    bounds=None,
    *,
    dim: int | None = None,
    vectorized: bool = True,
    shifted: bool = False,
    shift_seed: int = 0,
    preset: str = "paper",
) -> Problem:
    """Turn a function name, a :class:`~mawdo.functions.BenchmarkFunction` or a callable into a
    :class:`Problem`.

    Parameters
    ----------
    fun : str, BenchmarkFunction or callable
        A registered benchmark name (``"sphere"``, ``"F7"``), a benchmark object, or an objective.
    bounds : optional
        Box bounds; required for a plain callable, overrides a benchmark's bounds when given.
    dim : int, optional
        Dimension for scalable benchmarks, or with ``bounds=(lo, hi)``.
    vectorized : bool
        Whether a plain callable takes ``(n, D)`` batches.
    shifted : bool
        Move a benchmark's optimum to a seeded point in the middle 80% of the box (SPEC 2).
    shift_seed : int
        Seed of that shift.
    preset : {"paper", "standard"}
        Benchmark bounds preset (SPEC 2 table).
    """
    from mawdo.functions import BenchmarkFunction, get_function

    if isinstance(fun, str):
        fun = get_function(fun, dim=dim, preset=preset, shifted=shifted, shift_seed=shift_seed)
    elif isinstance(fun, BenchmarkFunction):
        if dim is not None and dim != fun.dim:
            fun = fun.with_dim(dim)
        if shifted:
            from mawdo.functions import shifted as make_shifted

            fun = make_shifted(fun, shift_seed)
    elif shifted:
        raise ValueError("shifted=True applies to benchmark functions, not to a plain callable")
    if isinstance(fun, BenchmarkFunction):
        if bounds is not None:
            fun = fun.with_bounds(*as_bounds(bounds, fun.dim))
        return Problem(
            fun=fun.func,
            lb=np.asarray(fun.lb, float),
            ub=np.asarray(fun.ub, float),
            vectorized=True,
            noise=fun.noise,
            name=fun.name,
            f_star=fun.f_star,
            x_star=fun.x_star,
        )
    if not callable(fun):
        raise TypeError(
            f"fun must be a function name, a BenchmarkFunction or a callable; "
            f"got {type(fun).__name__}"
        )
    lb, ub = as_bounds(bounds, dim)
    name = getattr(fun, "__name__", "objective")
    return Problem(fun=fun, lb=lb, ub=ub, vectorized=vectorized, name=name)


def minimize(
    fun,
    bounds=None,
    *,
    algorithm: str | Optimizer = "mawdo",
    runs: int = 1,
    seed=None,
    first_run: int = 0,
    max_iter: int | None = None,
    max_evals: int | None = None,
    target: float | None = None,
    max_time: float | None = None,
    callback: Callable | None = None,
    x0=None,
    dim: int | None = None,
    vectorized: bool = True,
    shifted: bool = False,
    shift_seed: int = 0,
    preset: str = "paper",
    progress: bool = False,
    **options,
) -> OptimizeResult:
    """Minimise ``fun`` over a box with ``runs`` independent runs of one algorithm.

    Parameters
    ----------
    fun : str, BenchmarkFunction or callable
        See :func:`make_problem`. A callable takes ``X`` of shape ``(n, D)`` and returns ``(n,)``
        (or, with ``vectorized=False``, takes ``(D,)`` and returns a float).
    bounds : sequence of (low, high), optional
        Required for a callable.
    algorithm : str or Optimizer
        A registered name (``mawdo list``) or an optimizer instance.
    runs : int
        Independent runs, executed as one vectorised batch; >= 1.
    seed : int, SeedSequence or None
        Master seed; run ``r`` uses the ``r``-th spawned child, so its result is the same alone
        or in any batch.
    first_run : int
        Index of the first run of this batch under ``seed`` (to recompute runs ``k..k+R-1``).
    max_iter : int, optional
        Iterations (the initial population is iteration 1). Default 500 when no budget is set.
    max_evals : int, optional
        Exact evaluation budget per run; the last iteration is truncated to hit it exactly.
    target : float, optional
        A run stops once its best value is <= ``target`` (its result freezes; others go on).
    max_time : float, optional
        Wall-clock seconds for the whole batch.
    callback : callable, optional
        ``callback(result_so_far) -> bool``, called after every iteration with an
        :class:`OptimizeResult` snapshot; returning True stops all runs.
    x0 : array_like, optional
        Warm start: ``(k, D)`` points (shared by all runs) or ``(R, k, D)``, ``k <= pop_size``,
        placed in the initial population; the rest is drawn at random.
    progress : bool
        Show a progress bar (rich).
    **options
        Algorithm coefficients, e.g. ``pop_size=50``, ``groups=8``.

    Returns
    -------
    OptimizeResult
        Per-run arrays ``x (R, D)``, ``fun (R,)``, ``nfev (R,)``, ``history (R, T)``.
    """
    if not isinstance(runs, int | np.integer) or runs < 1:
        raise ValueError(f"runs={runs!r} must be an integer >= 1")
    for name, val in (("max_iter", max_iter), ("max_evals", max_evals)):
        if val is not None and (not isinstance(val, int | np.integer) or val < 1):
            raise ValueError(f"{name}={val!r} must be a positive integer")
    if max_time is not None and not max_time > 0:
        raise ValueError(f"max_time={max_time!r} must be > 0 seconds")
    problem = make_problem(
        fun,
        bounds,
        dim=dim,
        vectorized=vectorized,
        shifted=shifted,
        shift_seed=shift_seed,
        preset=preset,
    )
    opt = make_optimizer(algorithm, **options)
    pop = opt.params.pop_size
    if max_iter is None and max_evals is None:
        max_iter = DEFAULT_MAX_ITER
    # Schedules (MAWDO's mixing, GWO's a) need T up front; under an evaluation budget it is the
    # number of plain iterations that budget buys.
    T = max_iter if max_iter is not None else math.ceil(max_evals / pop)

    if not isinstance(first_run, int | np.integer) or first_run < 0:
        raise ValueError(f"first_run={first_run!r} must be an integer >= 0")
    seqs = run_seed_sequences(seed, runs, first_run)
    children = [s.spawn(2) for s in seqs]
    algo_streams = RunStreams.from_seed_sequences([c[0] for c in children])
    noise_streams = RunStreams.from_seed_sequences([c[1] for c in children])
    evaluator = Evaluator(problem, noise_streams, opt.name)
    space = Space(problem.lb, problem.ub)
    state = opt.init(space, algo_streams, T, x0)

    R, D = runs, problem.dim
    best_f = np.full(R, np.inf)
    best_x = np.tile(space.from_unit(np.zeros(D)), (R, 1))
    active = np.ones(R, dtype=bool)
    status = np.zeros(R, dtype=np.int64)
    nit = np.zeros(R, dtype=np.int64)
    hist, hist_nfev = [], []
    message = STATUS_MESSAGES[0]
    t0 = time.perf_counter()
    bar = _progress(progress, opt.name, problem.name, max_iter, max_evals)
    it = 0

    def snapshot(msg: str) -> OptimizeResult:
        return _result(
            opt,
            problem,
            seed,
            best_x,
            best_f,
            evaluator.nfev,
            nit,
            hist,
            hist_nfev,
            status,
            msg,
            time.perf_counter() - t0,
        )

    try:
        while True:
            it += 1
            X = opt.ask(state)
            limit = None
            if max_evals is not None:
                limit = int(max_evals - evaluator.nfev[active].max(initial=0))
            F = evaluator(X, it, active, limit)
            state = opt.tell(state, X, F)
            # The driver keeps its own best-so-far from evaluated points only.
            j = np.argmin(F, axis=1)
            fj = F[np.arange(R), j]
            better = active & (fj < best_f)
            best_f = np.where(better, fj, best_f)
            best_x[better] = X[better, j[better]]
            nit[active] = it
            hist.append(best_f.copy())
            hist_nfev.append(evaluator.nfev.copy())
            if bar is not None:
                bar.advance(it, evaluator.nfev.max(), best_f.min())
            # Termination, per run first, then for the batch.
            if target is not None:
                hit = active & (best_f <= target)
                status[hit], active[hit] = 2, False
            if max_evals is not None and limit is not None and limit <= X.shape[1]:
                status[active], active[:] = 1, False
                message = STATUS_MESSAGES[1]
            if max_iter is not None and it >= max_iter:
                status[active], active[:] = 0, False
                message = STATUS_MESSAGES[0]
            if not active.any():
                if target is not None and (status == 2).all():
                    message = STATUS_MESSAGES[2]
                break
            if max_time is not None and time.perf_counter() - t0 >= max_time:
                status[active], active[:] = 3, False
                message = STATUS_MESSAGES[3]
                break
            if callback is not None:
                snap = snapshot("in progress")
                if callback(snap):
                    status[active], active[:] = 4, False
                    message = STATUS_MESSAGES[4]
                    break
    finally:
        if bar is not None:
            bar.close()
    return snapshot(message)


def _result(
    opt, problem, seed, best_x, best_f, nfev, nit, hist, hist_nfev, status, message, elapsed
) -> OptimizeResult:
    return OptimizeResult(
        x=best_x.copy(),
        fun=best_f.copy(),
        nfev=nfev.copy(),
        nit=nit.copy(),
        history=np.stack(hist, axis=1) if hist else np.empty((best_f.size, 0)),
        history_nfev=np.stack(hist_nfev, axis=1) if hist_nfev else np.empty((best_f.size, 0)),
        status=status.copy(),
        message=message,
        algorithm=opt.name,
        params=opt.params.as_dict(),
        problem=problem.name,
        seed=seed,
        time=elapsed,
        f_star=problem.f_star,
        metadata=dict(opt.metadata),
    )


class _Bar:
    """A thin rich progress bar over iterations (or evaluations under an evaluation budget)."""

    def __init__(self, label: str, total: int, by_evals: bool) -> None:
        from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

        self.by_evals = by_evals
        self.progress = Progress(
            TextColumn("[bold]{task.description}"),
            BarColumn(),
            TextColumn("{task.completed}/{task.total}"),
            TextColumn("best {task.fields[best]}"),
            TimeRemainingColumn(),
            transient=True,
        )
        self.task = self.progress.add_task(label, total=total, best="-")
        self.progress.start()

    def advance(self, it: int, nfev: int, best: float) -> None:
        self.progress.update(self.task, completed=nfev if self.by_evals else it, best=f"{best:.4g}")

    def close(self) -> None:
        self.progress.stop()


def _progress(show: bool, algo: str, prob: str, max_iter, max_evals):
    if not show:
        return None
    by_evals = max_iter is None
    return _Bar(f"{algo} on {prob}", max_evals if by_evals else max_iter, by_evals)
