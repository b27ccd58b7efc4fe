"""scipy's differential evolution as a reference: the real scipy call, point by point.

Many users reach for scipy's DE first, so a comparison should include it as scipy runs it, not
a reimplementation. Each run calls ``differential_evolution`` with scipy's own defaults
(``strategy="best1bin"``, ``popsize=15`` so ``max(5, 15 D)`` members, ``mutation=(0.5, 1)``,
``recombination=0.7``, ``tol=0.01``, ``maxiter=1000``, Latin hypercube init, ``polish=True``,
``updating="immediate"``) in a greenlet of its own. The objective scipy calls hands each point to
the driver and waits for its value, so the driver evaluates, counts and caps every evaluation,
the polishing L-BFGS-B's included, exactly as for the other algorithms.

``updating="immediate"`` (scipy's default) evaluates one trial at a time, each mutation reading
the population the previous trial updated: a driver iteration of ``scipy_de`` is therefore one
evaluation per run (``ask`` returns ``(R, 1, D)``), and ``max_iter`` counts evaluations.

Each run's scipy call lives in a greenlet, not a thread: handing a point over is a switch of
stacks in the driver's own thread (about a microsecond), where a thread hand-over waits for the
operating system to wake the other thread and for the GIL. That halved the CPU time per
evaluation (CEC 2017 F1, D = 10, five runs: about 225 -> 112 us, of which scipy's own loop is
55-80 us; ``benchmarks/log/optimizers.md``). An exception raised in a scipy call, Ctrl-C
included, ends its greenlet and is raised again in the driver.

At the budget the driver stops asking; the point scipy asked for next is never evaluated, and the
greenlet is told to stop (a private exception raised inside the objective unwinds scipy) when the
batch's state is dropped. A call that ends before the budget (converged by ``tol``, or
``maxiter`` generations) is followed by a new call with a fresh seed (``restarts``; the count per
run is ``result.metadata["restarts"]``, the seed of each call ``metadata["de_seeds"]``). Every
seed comes from the run's own stream, so a run is the same alone or in any batch. Warm start:
the ``x0`` points are evaluated first, alone, and scipy's ``x0`` is the best of them (scipy puts
it in the initial population and evaluates it once more).
"""

from __future__ import annotations

import dataclasses
import weakref
from dataclasses import dataclass, field

import greenlet
import numpy as np

from mawdo.optimizers.base import Optimizer, Params, Space, as_x0, option
from mawdo.streams import RunStreams
from mawdo.util.validate import check_real

STRATEGIES = (
    "best1bin", "randtobest1bin", "currenttobest1bin", "best2bin", "rand2bin", "rand1bin",
    "best1exp", "rand1exp", "randtobest1exp", "currenttobest1exp", "best2exp", "rand2exp",
)  # fmt: skip
INITS = ("latinhypercube", "sobol", "halton", "random")


def _mutation(name: str, value) -> None:
    """scipy's rule: a constant in [0, 2), or a dither range ``(min, max)`` of such numbers."""
    if isinstance(value, tuple | list):
        if len(value) != 2:
            raise ValueError(f"{name}={value!r} must be a number in [0, 2) or a pair (min, max)")
        for i, v in enumerate(value):
            check_real(f"{name}[{i}]", v, 0, 2, high_open=True)
    else:
        check_real(name, value, 0, 2, high_open=True)


@dataclass(frozen=True)
class ScipyDEParams(Params):
    """Options of scipy's ``differential_evolution`` (its defaults) and of the restarts.

    Parameters
    ----------
    pop_size : int
        Population size S, >= 5 (scipy's minimum). Used only when ``auto_pop_size`` is false;
        passing ``pop_size`` alone turns ``auto_pop_size`` off, and the initial population
        (drawn by ``scipy.stats.qmc``'s sampler of kind ``init``) is handed to scipy as ``init``.
    auto_pop_size : bool
        Let scipy size the population: ``max(5, popsize * D)`` (Sobol: the next power of two).
    popsize : int
        scipy's population multiplier, >= 1 (15).
    strategy : str
        scipy's mutation strategy, one of :data:`STRATEGIES` ("best1bin").
    maxiter : int
        Generations of one call, >= 1 (1000).
    mutation : float or (float, float)
        Differential weight in [0, 2), or a dither range ``(min, max)`` ((0.5, 1)).
    recombination : float
        Crossover probability in [0, 1] (0.7).
    tol, atol : float
        scipy's convergence test ``std(energies) <= atol + tol |mean(energies)|`` (0.01, 0).
    polish : bool
        Polish the best member with L-BFGS-B at the end of a call (True); its evaluations
        count like any other.
    init : str
        Initial population: "latinhypercube", "sobol", "halton" or "random".
    restarts : bool
        Start a new call (fresh seed) when one ends before the budget; when false, the run
        re-evaluates the call's final ``x`` until the budget ends (counted, nothing learned).
    """

    pop_size: int = option(50, lo=5)
    auto_pop_size: bool = True
    popsize: int = option(15, lo=1)
    strategy: str = option("best1bin", choices=STRATEGIES)
    maxiter: int = option(1000, lo=1)
    mutation: object = option((0.5, 1.0), rule=_mutation)
    recombination: float = option(0.7, lo=0, hi=1)
    tol: float = option(0.01, lo=0)
    atol: float = option(0.0, lo=0)
    polish: bool = True
    init: str = option("latinhypercube", choices=INITS)
    restarts: bool = True

    def __post_init__(self) -> None:
        super().__post_init__()
        S = self.pop_size
        if not self.auto_pop_size and self.init == "sobol" and S & (S - 1):
            raise ValueError(f"pop_size={S} with init='sobol' must be a power of two")


class _Stop(BaseException):
    """Raised inside scipy's objective to unwind a call the driver no longer needs.

    A ``BaseException``: scipy turns an objective's ``TypeError``/``ValueError`` into a
    ``RuntimeError`` and must not catch this one."""


_STOP = object()  # the reply that raises _Stop


class _Run:
    """One run's scipy calls in a greenlet; each objective call switches to the driver."""

    def __init__(self, gen: np.random.Generator, lb, ub, params: ScipyDEParams, start) -> None:
        self.gen, self.lb, self.ub, self.params, self.start = gen, lb, ub, params, start
        self.call, self.seed = 0, 0
        self.glet = greenlet.greenlet(self._main)

    def resume(self, *value):
        """Hand the last point's value (none: start the run) and return the run's next
        message: ``(x, call, seed)``, or the exception its scipy call raised."""
        # the greenlet that resumes (the driver, in whatever greenlet it runs) gets the answer
        self.glet.parent = greenlet.getcurrent()
        return self.glet.switch(*value)

    def stop(self) -> None:
        """Unwind the scipy call (nothing to do once it ended or never started)."""
        if self.glet and not self.glet.dead:
            try:
                self.resume(_STOP)
            except greenlet.error:  # finalised from another thread: greenlet kills it later
                pass

    def objective(self, x: np.ndarray) -> float:
        value = self.glet.parent.switch((np.array(x, dtype=float), self.call, self.seed))
        if value is _STOP:
            raise _Stop
        return value

    def _main(self):
        try:
            while True:
                self.seed = int(self.gen.integers(2**63 - 1))
                res = de_call(self.objective, self.lb, self.ub, self.params, self.seed, self.start)
                self.start = None
                if not self.params.restarts:
                    while True:
                        self.objective(res.x)
                self.call += 1
        except (_Stop, greenlet.GreenletExit):
            return None
        except BaseException as exc:  # handed to the driver, which raises it
            return exc


def de_call(func, lb, ub, params: ScipyDEParams, seed: int, x0=None):
    """One ``scipy.optimize.differential_evolution`` call with these options.

    Parameters
    ----------
    func : callable
        ``func(x) -> float`` for ``x`` of shape ``(D,)``.
    lb, ub : numpy.ndarray
        The box, shape ``(D,)``.
    params : ScipyDEParams
        The options; ``pop_size`` is used only when ``auto_pop_size`` is false.
    seed : int
        ``rng = numpy.random.default_rng(seed)`` drives the call (and the initial population
        drawn here when ``pop_size`` is set).
    x0 : numpy.ndarray, optional
        scipy's ``x0`` (a member of the initial population), inside the box.

    Returns
    -------
    scipy.optimize.OptimizeResult
    """
    from scipy.optimize import differential_evolution

    rng = np.random.default_rng(seed)
    init = params.init
    if not params.auto_pop_size:
        init = lb + (ub - lb) * _initial_unit(init, params.pop_size, lb.size, rng)
    return differential_evolution(
        func, list(zip(lb, ub, strict=True)), strategy=params.strategy, maxiter=params.maxiter,
        popsize=params.popsize, tol=params.tol, mutation=params.mutation,
        recombination=params.recombination, rng=rng, polish=params.polish, init=init,
        atol=params.atol, x0=x0,
    )  # fmt: skip


def _initial_unit(kind: str, n: int, d: int, rng: np.random.Generator) -> np.ndarray:
    """``n`` points in ``[0, 1)^d`` from the sampler scipy uses for ``init=kind``."""
    from scipy.stats import qmc

    if kind == "random":
        return rng.uniform(size=(n, d))
    sampler = {"latinhypercube": qmc.LatinHypercube, "sobol": qmc.Sobol, "halton": qmc.Halton}
    return sampler[kind](d=d, rng=rng).random(n)


def _inside(x: np.ndarray, lb: np.ndarray, ub: np.ndarray) -> np.ndarray:
    """``x`` nudged toward the box centre until scipy's own test (its unit-box image in
    ``[0, 1]``) accepts it: a point on a bound can map to 1 + 1 ulp."""
    mid, width = 0.5 * (lb + ub), np.abs(ub - lb)
    for _ in range(8):
        with np.errstate(invalid="ignore", divide="ignore"):
            u = (x - mid) / width + 0.5
        bad = (u > 1.0) | (u < 0.0)
        if not bad.any():
            break
        x = np.where(bad, np.nextafter(x, mid), x)
    return x


@dataclass
class ScipyDEState:
    runs: list
    space: Space
    streams: RunStreams
    x0: np.ndarray | None = None  # (R, k, D) warm-start points still to evaluate
    seeds: list = field(default_factory=list)  # per run: the seed of each call that asked
    pending: tuple | None = None  # the next points and their calls, collected by tell


def _stop_runs(runs: list) -> None:
    for run in runs:
        if run is not None:
            run.stop()


class ScipyDE(Optimizer):
    """``scipy.optimize.differential_evolution`` per run, driven point by point; see the
    module docstring."""

    name = "scipy_de"
    params_class = ScipyDEParams
    per_run_metadata = ("restarts", "de_seeds")
    sequential = True  # scipy's updating="immediate": one trial at a time

    def __init__(self, params: Params | None = None, name: str | None = None, **options) -> None:
        if params is None and "pop_size" in options and "auto_pop_size" not in options:
            options["auto_pop_size"] = False  # an explicit population size means that size
        super().__init__(params, name, **options)

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> ScipyDEState:
        R, D = streams.runs, space.dim
        if self.params.auto_pop_size:  # scipy's size, reported in the result's params
            S = max(5, self.params.popsize * D)  # (the problem refuses equal bounds)
            S = 1 << (S - 1).bit_length() if self.params.init == "sobol" else S
            self.params = dataclasses.replace(self.params, pop_size=S)
        state = ScipyDEState(runs=[None] * R, space=space, streams=streams)
        state.seeds = [[] for _ in range(R)]
        # the runs' scipy calls wait on the driver; dropping the state unwinds them
        weakref.finalize(state, _stop_runs, state.runs)
        self.metadata["restarts"], self.metadata["de_seeds"] = [0] * R, [[] for _ in range(R)]
        if x0 is not None:
            state.x0 = np.clip(as_x0(x0, R, D, self.params.pop_size), space.lb, space.ub)
            return state
        self._start(state, [None] * R)
        return state

    def _start(self, state: ScipyDEState, starts: list) -> None:
        sp = state.space
        for r, g in enumerate(state.streams.generators):
            state.runs[r] = _Run(g, sp.lb, sp.ub, self.params, starts[r])

    def ask(self, state: ScipyDEState) -> np.ndarray:
        if state.x0 is not None:
            return state.x0
        pending, state.pending = state.pending, None
        X, calls = self._collect(state, None) if pending is None else pending
        # counted here, when the points go to the driver: a call begun after the last tell
        # (its first point collected, never evaluated) is no restart
        new = [(r, c) for r, c in enumerate(calls) if len(state.seeds[r]) == c[0]]
        for r, (_, seed) in new:
            state.seeds[r].append(seed)
        if new:  # new lists: the results already returned keep theirs
            self.metadata["restarts"] = [len(s) - 1 for s in state.seeds]
            self.metadata["de_seeds"] = [list(s) for s in state.seeds]
        return X

    def _collect(self, state: ScipyDEState, F: np.ndarray | None) -> tuple[np.ndarray, list]:
        """Hand each run its value (``F`` of shape ``(R, 1)``; None: start the runs) and take
        its next point (``(R, 1, D)``, in the box) and the ``(call, seed)`` it belongs to."""
        X = np.empty((len(state.runs), 1, state.space.dim))
        calls = []
        for r, run in enumerate(state.runs):
            msg = run.resume() if F is None else run.resume(float(F[r, 0]))
            if isinstance(msg, BaseException):
                raise msg
            X[r, 0], call, seed = msg
            calls.append((call, seed))
        return np.clip(X, state.space.lb, state.space.ub), calls

    def tell(self, state: ScipyDEState, X: np.ndarray, F: np.ndarray) -> ScipyDEState:
        if state.x0 is not None:  # warm start: each run's scipy x0 is its best x0 point
            best = X[np.arange(X.shape[0]), np.argmin(F, axis=1)]
            sp = state.space
            self._start(state, [_inside(b, sp.lb, sp.ub) for b in best])
            state.x0 = None
            return state
        state.pending = self._collect(state, F)
        return state
