"""The driver loop: init -> (ask, evaluate, tell)* -> OptimizeResult.

Budgets (``max_iter``, ``max_evals``, ``target``, ``max_time``; :mod:`mawdo.budget`) and the
callback are applied here, not in the algorithms, so every optimizer is stopped and counted the
same way. Arguments are checked before anything runs (:mod:`mawdo.util.validate`).
"""

from __future__ import annotations

import sys
from collections.abc import Callable

import numpy as np

from mawdo.budget import CALLBACK, DEFAULT_MAX_ITER, Budget, RunLog
from mawdo.optimizers.base import Optimizer, Space
from mawdo.optimizers.registry import make_optimizer
from mawdo.problem import Evaluator, Problem, as_bounds, box_scale, check_x0
from mawdo.result import OptimizeResult
from mawdo.streams import RunStreams, run_seed_sequences
from mawdo.util.blocks import block_sizes, join_results
from mawdo.util.validate import ArgumentTypeError, check_bool, check_int, check_seed

__all__ = ["DEFAULT_MAX_ITER", "NoFiniteValueWarning", "make_problem", "minimize"]


def make_problem(
    fun,
    bounds=None,
    *,
    lb=None,
    ub=None,
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
        An objective with the attribute ``pure = True`` declares that it never writes into its
        argument: the driver then hands it the candidates without copying them.
    bounds : sequence of (low, high) pairs, (low, high) scalars, or scipy.optimize.Bounds
        Box bounds (see :func:`~mawdo.problem.as_bounds`): ``[(-5, 5)] * 10``, ``(-5, 5)`` with
        ``dim=10``, or ``Bounds(lb, ub)``. Required for a plain callable (or ``lb``/``ub``);
        overrides a benchmark's bounds when given.
    lb, ub : float or array_like, optional
        Lower and upper bounds, shape ``(D,)`` or scalars (with ``dim``), instead of ``bounds``.
    dim : int, optional
        Dimension D >= 1 for scalable benchmarks, or with scalar bounds.
    vectorized : bool
        Whether a plain callable takes ``(n, D)`` batches.
    shifted : bool
        Move a benchmark's optimum to a seeded point in the middle 80% of the box
        (docs/functions.md#f-shift).
    shift_seed : int
        Seed of that shift.
    preset : {"paper", "standard"}
        Benchmark bounds preset (docs/functions.md#f-preset table).
    """
    from mawdo.functions import BenchmarkFunction, get_function

    if dim is not None:
        check_int("dim", dim, 1)
    check_bool("vectorized", vectorized)
    check_bool("shifted", shifted)
    check_int("shift_seed", shift_seed, 0)
    box = bounds is not None or lb is not None or ub is not None
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
        if box:
            fun = fun.with_bounds(*as_bounds(bounds, fun.dim, lb=lb, ub=ub))
        return Problem(
            fun=fun.func,
            lb=np.asarray(fun.lb, float),
            ub=np.asarray(fun.ub, float),
            vectorized=True,
            noise=fun.noise,
            name=fun.name,
            f_star=fun.f_star,
            x_star=fun.x_star,
            pure=True,  # tests/functions: no benchmark function writes into its argument
        )
    if not callable(fun):
        raise TypeError(
            f"fun must be a function name, a BenchmarkFunction or a callable; "
            f"got {type(fun).__name__}"
        )
    lo, hi = as_bounds(bounds, dim, lb=lb, ub=ub)
    name = getattr(fun, "__name__", "objective")
    pure = getattr(fun, "pure", False) is True  # it says it never writes into its argument
    return Problem(fun=fun, lb=lo, ub=hi, vectorized=vectorized, name=name, pure=pure)


def minimize(
    fun,
    bounds=None,
    *,
    lb=None,
    ub=None,
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
    runs_per_block: int | None = None,
    trace_evaluations: bool = False,
    **options,
) -> OptimizeResult:
    """Minimise ``fun`` over a box with ``runs`` independent runs of one algorithm.

    Long by design: the numpydoc parameter list is most of it; the body reads top-down.

    Parameters
    ----------
    fun : str, BenchmarkFunction or callable
        See :func:`make_problem`. A callable takes ``X`` of shape ``(n, D)`` (a copy it may
        modify) and returns ``(n,)`` real values (or, with ``vectorized=False``, takes ``(D,)``
        and returns a float). NaN and inf count as worst; complex or string values are errors.
    bounds, lb, ub, dim, vectorized, shifted, shift_seed, preset
        The problem: see :func:`make_problem` (``bounds=[(lo, hi)] * D``, or ``lb=``/``ub=``).
    algorithm : str or Optimizer
        A registered name (``mawdo list``) or an optimizer instance.
    runs : int
        Independent runs, executed as one vectorised batch (a large one in blocks of runs, see
        ``runs_per_block``); >= 1.
    seed : int >= 0, sequence of int, SeedSequence or None
        Master seed; run ``r`` uses the ``r``-th spawned child, so its result is the same alone
        or in any batch.
    first_run : int
        Index of the first run of this batch under ``seed`` (to recompute runs ``k..k+R-1``).
    max_iter, max_evals, target, max_time
        The budget, see :class:`~mawdo.budget.Budget`: iterations (the initial population is
        iteration 1; default 500 when neither is set), exact evaluations per run (the last
        iteration is truncated), a target value freezing each run that reaches it, and
        wall-clock seconds for the batch.
    callback : callable, optional
        ``callback(result_so_far) -> bool``, called after every iteration with an
        :class:`OptimizeResult` snapshot; returning True stops all runs.
    x0 : array_like, optional
        Warm start: ``(k, D)`` points (shared by all runs) or ``(runs, k, D)``,
        ``k <= pop_size``, each inside the bounds (a point outside is an error, never clipped
        silently), placed in the initial population; the rest is drawn at random.
    progress : bool
        Show a progress bar (rich).
    runs_per_block : int, optional
        Most runs evaluated together, >= 1: a larger batch goes in blocks of runs, one after
        another, with the same results (:mod:`mawdo.util.blocks`). Default: blocks whose state fits
        in a core's cache (about 1 MiB per state array), which keeps the time per evaluation
        flat in ``runs``; one block with ``callback`` or ``max_time``, which see the whole
        batch. Pass ``runs`` for an objective that must see every run in each call.
    **options
        Algorithm coefficients, e.g. ``pop_size=50``, ``groups=8``; each checked against the
        constraint its algorithm declares on the field (:func:`mawdo.optimizers.base.option`).

    Returns
    -------
    OptimizeResult
        Per-run arrays ``x (R, D)``, ``fun (R,)``, ``nfev (R,)``, ``history (R, T)``, and
        ``evaluation_trace`` (with ``trace_evaluations``).
    """
    _check_driver_arguments(runs, seed, first_run, callback, progress)
    check_bool("trace_evaluations", trace_evaluations)
    budget = Budget(max_iter, max_evals, target, max_time)
    whole = callback is not None or max_time is not None
    _check_blocks(runs_per_block, runs, whole)
    problem = make_problem(
        fun, bounds, lb=lb, ub=ub, dim=dim, vectorized=vectorized, shifted=shifted,
        shift_seed=shift_seed, preset=preset,
    )  # fmt: skip
    x0 = check_x0(x0, runs, problem.lb, problem.ub)  # the batch's runs, before any block
    opt = make_optimizer(algorithm, **options)
    if whole:
        sizes = [runs]
    else:
        sizes = block_sizes(runs, runs_per_block, opt.params.pop_size, problem.dim)
    bar = _progress(progress, opt.name, problem.name, budget.max_iter, budget.max_evals, sizes)
    parts, done = [], 0
    try:
        for size in sizes:
            part_x0 = x0[done : done + size] if x0 is not None and np.ndim(x0) == 3 else x0
            run = _Batch(problem, opt, budget, seed, (first_run + done, size), part_x0,
                         trace_evaluations)  # fmt: skip
            parts.append(run.drive(callback, bar))
            done += size
    finally:
        if bar is not None:
            bar.close()
    res = parts[0] if len(parts) == 1 else join_results(parts, opt.per_run_metadata)
    warn_no_finite_value(res, problem)
    return res


class NoFiniteValueWarning(RuntimeWarning):
    """Runs that evaluated points but never saw a finite objective value: their ``x`` is the
    box centre, which they never evaluated, and their ``fun`` is inf."""


def warn_no_finite_value(res: OptimizeResult, problem: Problem) -> None:
    """Warn (:class:`NoFiniteValueWarning`) when runs evaluated points and found no finite
    value: ``x`` = the box centre with ``fun`` = inf would else read as a result (the box
    (-1e308, 1e308) gave ``x = 0``, ``fun = inf`` for sum(x**2), whose value at 0 is 0)."""
    lost = ~np.isfinite(res.fun) & (np.asarray(res.nfev) > 0)
    if not lost.any():
        return
    import warnings

    reach = float(np.max(np.maximum(np.abs(problem.lb), np.abs(problem.ub))))
    hint = (
        f"; the box reaches {reach:.3g}: an objective such as sum(x**2) overflows almost "
        "everywhere in it, give bounds that fit the problem"
        if reach > 1e150
        else "; check the objective (NaN and inf count as the worst value)"
    )
    warnings.warn(
        f"{int(lost.sum())} of {lost.size} runs found no finite objective value in "
        f"{int(np.max(res.nfev[lost]))} evaluations (every value was inf or NaN): their x is "
        f"the box centre, never evaluated, and their fun is inf{hint}",
        NoFiniteValueWarning,
        stacklevel=3,
    )


class _Batch:
    """One batch of runs through the driver loop: init -> (ask, evaluate, tell)*."""

    def __init__(self, problem: Problem, opt: Optimizer, budget: Budget, seed,
                 block: tuple[int, int], x0, trace: bool = False) -> None:  # fmt: skip
        first_run, runs = block  # the block's first run index under seed, and its runs
        self.problem, self.opt, self.seed = problem, opt, seed
        algo_streams, noise_streams = _streams(seed, runs, first_run)
        self.evaluator = Evaluator(problem, noise_streams, opt.name)
        # a box wider than floats can span is searched divided by a power of two (exact)
        self.scale = box_scale(problem.lb, problem.ub)
        s = self.scale
        space = Space(problem.lb / s, problem.ub / s)
        x0 = None if x0 is None else x0 / s
        self.state = opt.init(space, algo_streams, opt.horizon(budget, problem.dim), x0)
        x_start = self._to_box(space.from_unit(np.zeros(problem.dim)))
        self.log = RunLog(budget, runs, x_start, trace)

    def _to_box(self, X: np.ndarray) -> np.ndarray:
        """The optimizer's candidates in the problem's box (themselves unless it is scaled)."""
        if self.scale == 1.0:
            return X
        # clipped before it is scaled back: a candidate outside the scaled box (an optimizer
        # may evaluate one) would overflow; the power of two makes the order exact
        s = self.scale
        return np.clip(X, self.problem.lb / s, self.problem.ub / s) * s

    def snapshot(self, message: str) -> OptimizeResult:
        return _result(self.opt, self.problem, self.seed, self.log, self.evaluator.nfev, message)

    def drive(self, callback, bar) -> OptimizeResult:
        opt, log, evaluator = self.opt, self.log, self.evaluator
        it = 0
        while True:
            it += 1
            X = opt.ask(self.state)
            limit = log.eval_limit(evaluator.nfev)
            Xb = self._to_box(X)
            F = evaluator(Xb, it, log.active, limit)
            self.state = opt.tell(self.state, X, F)
            log.record(it, Xb, F, evaluator.nfev)
            if bar is not None:
                bar.advance(it, evaluator.nfev.max(), log.best_f.min())
            if log.finished(it, X.shape[1], limit):
                break
            if callback is not None and callback(self.snapshot("in progress")):
                log.stop(CALLBACK)
                break
        if bar is not None:
            bar.next_block()
        return self.snapshot(log.message)


def _check_blocks(runs_per_block, runs: int, whole: bool) -> None:
    if runs_per_block is None:
        return
    check_int("runs_per_block", runs_per_block, 1)
    if whole and runs_per_block < runs:
        raise ValueError(
            f"runs_per_block={runs_per_block} < runs={runs} cannot be combined with callback or "
            "max_time, which see the whole batch: leave runs_per_block=None"
        )


def _check_driver_arguments(runs, seed, first_run, callback, progress) -> None:
    check_int("runs", runs, 1)
    check_int("first_run", first_run, 0)
    check_seed(seed)
    check_bool("progress", progress)
    if callback is not None and not callable(callback):
        raise ArgumentTypeError(f"callback={callback!r} must be a callable or None")


def _streams(seed, runs: int, first_run: int) -> tuple[RunStreams, RunStreams]:
    """Each run's algorithm and noise streams: two children of the run's seed sequence."""
    children = [s.spawn(2) for s in run_seed_sequences(seed, runs, first_run)]
    algo = RunStreams.from_seed_sequences([c[0] for c in children])
    noise = RunStreams.from_seed_sequences([c[1] for c in children])
    return algo, noise


def _result(opt, problem, seed, log: RunLog, nfev, message: str) -> OptimizeResult:
    history, history_nfev = log.history()
    return OptimizeResult(
        x=log.best_x.copy(),
        fun=log.best_f.copy(),
        nfev=nfev.copy(),
        nit=log.nit.copy(),
        history=history,
        history_nfev=history_nfev,
        status=log.status.copy(),
        message=message,
        algorithm=opt.name,
        params=opt.params.as_dict(),
        problem=problem.name,
        seed=seed,
        time=log.elapsed(),
        f_star=problem.f_star,
        metadata=dict(opt.metadata),
        evaluation_trace=None if log.evaluations is None else log.evaluations.traces(),
    )


class _Bar:
    """A thin rich progress bar over iterations (or evaluations under an evaluation budget)."""

    def __init__(self, label: str, total: int, by_evals: bool, blocks: int = 1) -> None:
        from rich.console import Console
        from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

        self.by_evals = by_evals
        self.per_block, self.offset, self.best = total, 0, np.inf
        self.progress = Progress(
            TextColumn("[bold]{task.description}"),
            BarColumn(),
            TextColumn("{task.completed}/{task.total}"),
            TextColumn("best {task.fields[best]}"),
            TimeRemainingColumn(),
            # stderr, and only on a terminal: a bar that is not drawn must not leave blank
            # lines on stdout, where the results go
            console=Console(stderr=True),
            transient=True,
            disable=not sys.stderr.isatty(),
        )
        self.task = self.progress.add_task(label, total=total * blocks, best="-")
        self.progress.start()

    def advance(self, it: int, nfev: int, best: float) -> None:
        self.best = min(self.best, best)
        done = self.offset + (nfev if self.by_evals else it)
        self.progress.update(self.task, completed=done, best=f"{self.best:.4g}")

    def next_block(self) -> None:
        """Move on to the next block of runs (each block counts ``total`` once)."""
        self.offset += self.per_block

    def close(self) -> None:
        self.progress.stop()


def _progress(show: bool, algo: str, prob: str, max_iter, max_evals, sizes: list[int]):
    if not show:
        return None
    by_evals = max_iter is None
    label = f"{algo} on {prob}" + (f" ({len(sizes)} blocks of runs)" if len(sizes) > 1 else "")
    return _Bar(label, max_evals if by_evals else max_iter, by_evals, len(sizes))
