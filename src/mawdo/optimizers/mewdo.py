"""MEWDO, RECONSTRUCTED: a multi-strategy ensemble WDO with success-adaptive strategy shares.

The MEWDO paper (Zhang, Yang & Chen, Math. Comput. Simul. 231, 2025) was not available to us.
This is our reconstruction from its one-line description in the MAWDO paper ("multi-strategy
enhanced WDO"), as our reading asks
(docs/deviations.md#d-mewdo): an ensemble of WDO-family update strategies whose share of the
population adapts to each strategy's recent success rate. Every output that names it says
"reconstructed"; see docs/deviations.md.

Strategies (all in WDO's normalised space, velocity clamp ``vmax``, clipping):
  0. classic WDO (fixed alpha, g, RT, c; ``|1 - 1/i|`` pressure weight);
  1. AWDO (coefficients ~ U[0, 1] per parcel, pressure and Coriolis divided by the rank);
  2. personal-best WDO: the pressure term pulls toward a random better parcel's ``pbest``
     (a current-to-pbest move that keeps diversity), gravity toward the population centroid.

Each iteration every parcel draws its strategy from probabilities ``q``; a parcel succeeds when
its new pressure is below its previous one. ``q`` follows an exponential moving average of each
strategy's success rate (learning rate ``lr``), floored at ``q_min`` and renormalised.
No greedy selection: every parcel moves, as in WDO.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from numba import njit

from mawdo.optimizers.base import Optimizer, Params, Space, as_x0, initial_population, option
from mawdo.optimizers.kernels import mewdo_step, update_personal_best, words_per_permutation
from mawdo.streams import RunStreams

N_STRATEGIES = 3
_NO_PERM = np.zeros((1, 1, 1), np.int16)
_NO_WORDS = np.zeros((1, 1), np.uint64)
_words = functools.cache(words_per_permutation)  # a Python loop over D, asked every iteration


@dataclass(frozen=True)
class MEWDOParams(Params):
    """MEWDO (reconstructed) coefficients.

    Parameters
    ----------
    alpha, g, RT, c : float
        Coefficients of the classic strategy (WDO defaults).
    vmax : float
        Velocity clamp, normalised units (0.3).
    lr : float
        Learning rate of the success-rate average, in (0, 1].
    q_min : float
        Floor of each strategy's share, in [0, 1/3].
    """

    alpha: float = option(0.4, lo=0, hi=1)
    g: float = option(0.2, lo=0)
    RT: float = option(3.0, lo=0)
    c: float = option(0.4, lo=0)
    vmax: float = option(0.3, lo=0, lo_open=True)
    lr: float = option(0.1, lo=0, hi=1, lo_open=True)
    q_min: float = option(0.1, lo=0, hi=1.0 / N_STRATEGIES)


def update_shares(succ_rate, q, lr, q_min):
    """Move strategy shares toward the normalised success rates, floored at ``q_min``.

    ``succ_rate`` and ``q`` have shape ``(R, K)``; strategies that were not used keep their share.
    """
    tot = succ_rate.sum(axis=1, keepdims=True)
    target = np.where(tot > 0, succ_rate / np.where(tot > 0, tot, 1.0), q)
    q = (1.0 - lr) * q + lr * target
    q = np.maximum(q, q_min)
    return q / q.sum(axis=1, keepdims=True)


@njit(cache=True, nogil=True)
def choose_strategies(f, pbest_f, q, draws, rank, tb, strat, guide):  # pragma: no cover - compiled
    """Each parcel's rank, strategy and guide, written to ``rank``, ``tb``, ``strat``, ``guide``.

    Parameters (``R`` runs, ``N`` parcels, ``K`` strategies)
    ----------
    f, pbest_f : (R, N)
        Last pressures and personal-best pressures (no NaN).
    q : (R, K)
        Strategy shares; parcel ``i`` takes the first strategy whose cumulative share is
        ``>= draws[r, i, 0]`` (the inverse CDF; the last one if rounding leaves none).
    draws : (R, N, 6)
        The parcels' uniforms; ``draws[..., 5]`` picks the guide of strategy 2.
    rank : (R, N) float
        1-based rank of ``f`` (1 = best, ties by index, as a stable sort).
    tb : (R,) int
        Index of the least ``pbest_f`` (the first one).
    strat, guide : (R, N) int
        Strategy of each parcel, and the parcel of rank ``floor(draws[..., 5] (rank - 1)) + 1``
        (a better one, or itself when it is the best).
    """
    R, N = f.shape
    K = q.shape[1]
    order = np.empty(N, np.intp)
    cdf = np.empty(K)
    for r in range(R):
        for k in range(N):  # insertion sort: stable, no allocation, fast for N ~ 50
            j = k
            v = f[r, k]
            while j > 0 and f[r, order[j - 1]] > v:
                order[j] = order[j - 1]
                j -= 1
            order[j] = k
        for k in range(N):
            rank[r, order[k]] = k + 1.0
        best = 0
        for i in range(1, N):
            if pbest_f[r, i] < pbest_f[r, best]:
                best = i
        tb[r] = best
        acc = 0.0
        for k in range(K):  # numpy.cumsum's order
            acc += q[r, k]
            cdf[k] = acc
        for i in range(N):
            n = 0
            for k in range(K):
                n += draws[r, i, 0] > cdf[k]
            strat[r, i] = min(n, K - 1)
            guide[r, i] = order[int(np.floor(draws[r, i, 5] * (rank[r, i] - 1.0)))]


@njit(cache=True, nogil=True)
def strategy_success(strategy, F, f, n_used, n_succ):  # pragma: no cover - compiled
    """Per run and strategy ``k``: parcels that used it (``n_used``) and those whose new pressure
    ``F`` beat their last one ``f`` (``n_succ``), both ``(R, K)``, overwritten."""
    R, N = F.shape
    n_used[:] = 0
    n_succ[:] = 0
    for r in range(R):
        for i in range(N):
            k = strategy[r, i]
            if 0 <= k < n_used.shape[1]:
                n_used[r, k] += 1
                n_succ[r, k] += F[r, i] < f[r, i]


@njit(cache=True, nogil=True)
def centroid(p, out):  # pragma: no cover - compiled
    """Mean over the parcels of ``p (R, N, D)`` into ``out (R, D)``: ``p.mean(axis=1)`` to the
    bit (NumPy sums a middle axis parcel by parcel, then divides by N), without its overhead
    (about a tenth of an iteration at R = 30, N = 50, D = 30)."""
    R, N, D = p.shape
    out[:] = 0.0
    for r in range(R):
        for i in range(N):
            for d in range(D):
                out[r, d] += p[r, i, d]
    for r in range(R):
        for d in range(D):
            out[r, d] /= N


@dataclass
class MEWDOState:
    p: np.ndarray
    u: np.ndarray
    f: np.ndarray
    pbest: np.ndarray
    pbest_f: np.ndarray
    q: np.ndarray  # (R, K) strategy shares
    strategy: np.ndarray  # (R, N) strategy used by the last move
    t: int
    T: int
    space: Space
    streams: RunStreams


class MEWDO(Optimizer):
    """MEWDO (reconstructed); see the module docstring."""

    name = "mewdo"
    params_class = MEWDOParams

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> MEWDOState:
        P = self.params
        N, D, R = P.pop_size, space.dim, streams.runs
        p0 = None if x0 is None else space.to_unit(as_x0(x0, streams.runs, D, N))
        p = initial_population(streams, N, -np.ones(D), np.ones(D), p0)
        return MEWDOState(
            p=p,
            u=streams.uniform(-P.vmax, P.vmax, (N, D)),
            f=np.full((R, N), np.inf),
            pbest=p.copy(),
            pbest_f=np.full((R, N), np.inf),
            q=np.full((R, N_STRATEGIES), 1.0 / N_STRATEGIES),
            strategy=np.full((R, N), -1),
            t=0,
            T=max_iter,
            space=space,
            streams=streams,
        )

    def ask(self, state: MEWDOState) -> np.ndarray:
        s, P = state, self.params
        if s.t == 0:
            return s.space.from_unit(s.p)
        R, N, D = s.p.shape
        if hasattr(s.streams, "raw_words"):
            # the words shuffle_rows would turn into permutations; the kernel applies each
            # permutation to the velocities directly (no (R, N, D) index array, no gather)
            words = s.streams.raw_words(np.empty((R, N * _words(D)), np.uint64))
            perm = _NO_PERM
        else:  # stand-in streams hand out the permutations
            perm = s.streams.shuffle_rows(np.empty((R, N, D), np.int16 if D < 2**15 else np.int32))
            words = _NO_WORDS
        draws = s.streams.random((N, 6))
        r, tb = np.empty((R, N)), np.empty(R, np.intp)
        strat, guide = np.empty((R, N), np.int64), np.empty((R, N), np.int64)
        choose_strategies(s.f, s.pbest_f, s.q, draws, r, tb, strat, guide)
        centre = np.empty((R, D))
        centroid(s.p, centre)
        X = np.empty_like(s.p)
        coef = np.array([P.alpha, P.g, P.RT, P.c])
        width = np.asarray(s.space.ub - s.space.lb, float)
        mewdo_step(s.p, s.u, s.pbest, r, tb, guide, centre, strat, draws, perm, words,
                   words is not _NO_WORDS, coef, float(P.vmax), np.asarray(s.space.lb, float),
                   width, X)  # fmt: skip
        s.strategy = strat
        return X

    def tell(self, state: MEWDOState, X: np.ndarray, F: np.ndarray) -> MEWDOState:
        s, P = state, self.params
        R = F.shape[0]
        if s.t > 0:
            n_used = np.empty((R, N_STRATEGIES), np.int64)
            n_succ = np.empty((R, N_STRATEGIES), np.int64)
            strategy_success(s.strategy, F, s.f, n_used, n_succ)
            rate = np.where(n_used > 0, n_succ / np.maximum(n_used, 1), 0.0)
            s.q = np.where(
                n_used.sum(axis=1, keepdims=True) > 0, update_shares(rate, s.q, P.lr, P.q_min), s.q
            )
        s.f = F.copy()
        update_personal_best(s.p, F, s.pbest, s.pbest_f)
        s.t += 1
        return s
