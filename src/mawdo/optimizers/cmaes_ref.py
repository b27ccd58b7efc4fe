"""CMA-ES reference: the ``cmaes`` library (CyberAgentAILab), one instance per run, with restarts.

Hansen's CMA-ES is the reference any BBOB comparison is read against; we drive the maintained
``cmaes.CMA`` rather than our own. Every run owns one ``CMA`` (seeded from the run's stream), so a
run is the same alone or in any batch; ``ask`` stacks the runs' samples into ``(R, lambda, D)``.

The search happens in the unit box ``u = (x - lb) / (ub - lb) in [0, 1]^D`` (``cmaes``'s
``bounds`` resamples infeasible points), so one step size fits boxes of unequal sides. Defaults:
``lambda = 4 + floor(3 ln D)``; mean uniform in the middle 80% of the box (COCO's example draws
``x0`` in ``[-4, 4]^D`` on BBOB); ``sigma0 = 0.2`` of the box side (2 on BBOB's ``[-5, 5]``).
When ``CMA.should_stop()`` fires, the run restarts from a new uniform mean with the same
``lambda`` (no IPOP doubling: the runs of a batch share one candidate count per iteration, so one
run cannot double its population alone; docs/bbob.md). ``result.metadata["restarts"]`` counts
each run's restarts. Warm start: the ``x0`` points are
evaluated first, alone, and the CMA-ES starts from the best of them.

A generation is sampled by :func:`ask_generation`, which reproduces ``lambda`` calls of
``CMA.ask()`` draw for draw in a few array operations (``ask()`` costs ~5 us of Python per
sample); it reads the library's private state, so ``pyproject.toml`` pins the ``cmaes`` versions
it was checked against and ``tests/optimizers/test_cmaes_batch_ask.py`` guards the equality.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from mawdo.optimizers.base import Optimizer, Params, Space, as_x0, finite_last, option
from mawdo.streams import RunStreams


@dataclass(frozen=True)
class CMAESParams(Params):
    """CMA-ES coefficients.

    Parameters
    ----------
    pop_size : int
        Offspring per generation ``lambda``, >= 2. Used only when ``auto_pop_size`` is false;
        passing ``pop_size`` alone turns ``auto_pop_size`` off.
    auto_pop_size : bool
        Use ``lambda = 4 + floor(3 ln D)`` (Hansen's default). True by default.
    sigma0 : float
        Initial step size as a fraction of the box side, in (0, 1].
    restarts : bool
        Restart a run (same ``lambda``, new uniform mean) when ``CMA.should_stop()`` fires.
    """

    auto_pop_size: bool = True
    sigma0: float = option(0.2, lo=0, hi=1, lo_open=True)
    restarts: bool = True


def ask_generation(cma, n: int) -> np.ndarray:
    """``n`` samples of a ``cmaes.CMA``, bit-identical to ``n`` calls of ``cma.ask()``.

    ``ask()`` draws ``z ~ N(0, I)`` from the CMA's ``RandomState``, maps it to
    ``x = m + sigma B diag(D) z`` and, with bounds, redraws an infeasible ``x`` up to
    ``n_max_resampling`` times before clipping one more draw. Here the draws come in blocks
    (:func:`_accept_draws` walks them in ``ask()``'s order); a block may draw past what the
    ``ask()`` calls would have drawn, so the generator is then rewound and advanced by exactly
    the draws used. ``randn`` yields one sequence whatever the block shapes (its cached second
    Gaussian lives in the state), so the samples and the final state are ``ask()``'s. The
    matrix-vector products are one stacked ``matmul``, which calls the same BLAS ``gemv`` as
    ``ask()``'s ``dot`` (a ``gemm`` would round differently).

    Parameters
    ----------
    cma : cmaes.CMA
        The optimizer (``cmaes`` 0.13.1, as pinned; its private sampling state is read and
        advanced).
    n : int
        Samples to draw, >= 0.

    Returns
    -------
    numpy.ndarray
        Shape ``(n, dim)``, in the CMA's coordinates, in the order ``ask()`` returns them.
    """
    dim = cma._n_dim
    if n == 0:
        return np.empty((0, dim))  # ask() never called: the eigendecomposition must not run
    B, D = cma._eigen_decomposition()
    BD = B.dot(np.diag(D))  # as in CMA._sample_solution, so the same matrix
    rng, bounds, max_tries = cma._rng, cma._bounds, cma._n_max_resampling

    def draw(rows: int) -> np.ndarray:
        Z = rng.randn(rows, dim)
        return cma._mean + cma._sigma * np.matmul(BD, Z[:, :, None])[:, :, 0]

    if bounds is None:
        return draw(n)
    saved = rng.get_state()
    X = draw(n)
    feasible = np.all((X >= bounds[:, 0]) & (X <= bounds[:, 1]), axis=1)
    if max_tries > 0 and feasible.all():
        return X  # the common case: every first draw is inside the box
    out, used, drawn = _accept_draws(cma, X, feasible, n, draw)
    if used < drawn:  # the blocks drew past ask(): rewind, redraw what was used
        rng.set_state(saved)
        rng.randn(used * dim)
    # (used == drawn, e.g. every sample spent all its tries on a slope against the bound: the
    # state is already ask()'s, and redrawing would double the cost of the generation)
    return out


def _accept_draws(cma, X: np.ndarray, feasible: np.ndarray, n: int, draw) -> tuple:
    """The ``n`` samples ``ask()`` makes from the draws ``X`` (more drawn as needed).

    Sample ``k`` takes the first feasible draw among the next ``n_max_resampling`` draws, or
    else clips the draw after them. Returns the samples, how many draws they used and how many
    were drawn.
    """
    bounds, max_tries = cma._bounds, cma._n_max_resampling
    out = np.empty((n, X.shape[1]))
    worst = n * (max_tries + 1)  # every sample spends all its tries and one clipped draw
    p = 0  # next unused draw
    for k in range(n):
        while True:
            hit = np.flatnonzero(feasible[p : p + max_tries])
            if hit.size or X.shape[0] > p + max_tries:
                break
            # neither a feasible draw nor the clipped one is drawn yet: draw more (doubling)
            more = min(worst - X.shape[0], max(p + max_tries + 1 - X.shape[0], X.shape[0]))
            Y = draw(more)
            X = np.concatenate([X, Y])
            ok = np.all((Y >= bounds[:, 0]) & (Y <= bounds[:, 1]), axis=1)
            feasible = np.concatenate([feasible, ok])
        if hit.size:
            out[k], p = X[p + hit[0]], p + hit[0] + 1
        else:  # ask(): the draw after the last resampling is clipped
            out[k], p = cma._repair_infeasible_params(X[p + max_tries]), p + max_tries + 1
    return out, p, X.shape[0]


def default_pop_size(dim: int) -> int:
    """Hansen's default offspring number ``4 + floor(3 ln D)``."""
    return 4 + math.floor(3 * math.log(dim))


@dataclass
class CMAESState:
    cmas: list
    U: np.ndarray | None  # (R, lambda, D) unit-box samples of the last ask; None after x0
    space: Space
    streams: RunStreams
    x0: np.ndarray | None = None  # (R, k, D) warm-start points still to evaluate
    restarts: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))


class CMAES(Optimizer):
    """CMA-ES (``cmaes.CMA``) per run with restarts; see the module docstring."""

    name = "cmaes"
    params_class = CMAESParams
    per_run_metadata = ("restarts",)

    def __init__(self, params: Params | None = None, name: str | None = None, **options) -> None:
        if params is None and "pop_size" in options and "auto_pop_size" not in options:
            options["auto_pop_size"] = False  # an explicit lambda means that lambda
        super().__init__(params, name, **options)

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> CMAESState:
        D, R = space.dim, streams.runs
        if self.params.auto_pop_size:
            self.params = dataclasses.replace(self.params, pop_size=default_pop_size(D))
        state = CMAESState(cmas=[None] * R, U=None, space=space, streams=streams)
        state.restarts = np.zeros(R, np.int64)
        self.metadata["restarts"] = [0] * R
        if x0 is not None:
            x0 = as_x0(x0, R, D, self.params.pop_size)
            state.x0 = np.clip(x0, space.lb, space.ub)
            return state
        for r in range(R):
            state.cmas[r] = self._new_cma(streams.generators[r], D)
        return state

    def _new_cma(self, rng: np.random.Generator, D: int, mean: np.ndarray | None = None):
        from cmaes import CMA

        if mean is None:
            mean = rng.uniform(0.1, 0.9, D)
        bounds = np.tile([0.0, 1.0], (D, 1))
        return CMA(
            mean=np.clip(mean, 0.0, 1.0),
            sigma=self.params.sigma0,
            bounds=bounds,
            seed=int(rng.integers(2**31 - 1)),
            population_size=self.params.pop_size,
        )

    def ask(self, state: CMAESState) -> np.ndarray:
        sp = state.space
        if state.x0 is not None:
            return state.x0
        lam = self.params.pop_size
        state.U = np.stack([ask_generation(c, lam) for c in state.cmas])
        return np.clip(sp.lb + state.U * (sp.ub - sp.lb), sp.lb, sp.ub)

    def tell(self, state: CMAESState, X: np.ndarray, F: np.ndarray) -> CMAESState:
        sp = state.space
        if state.x0 is not None:  # warm start: the CMA-ES starts at each run's best x0 point
            best = X[np.arange(X.shape[0]), np.argmin(F, axis=1)]
            for r, g in enumerate(state.streams.generators):
                state.cmas[r] = self._new_cma(g, sp.dim, sp.to_unit(best[r]) * 0.5 + 0.5)
            state.x0 = None
            return state
        F = finite_last(F)  # cmaes ranks by value: invalid ones just worse than the worst valid
        for r, cma in enumerate(state.cmas):
            cma.tell(list(zip(state.U[r], F[r].tolist(), strict=True)))
            if self.params.restarts and cma.should_stop():
                state.cmas[r] = self._new_cma(state.streams.generators[r], sp.dim)
                state.restarts[r] += 1
                self.metadata["restarts"] = state.restarts.tolist()  # per run, in the result
        return state
