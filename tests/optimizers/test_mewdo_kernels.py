"""MEWDO's bookkeeping kernels against the NumPy expressions they replaced (same numbers)."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.optimizers.base import ranks
from mawdo.optimizers.mewdo import N_STRATEGIES, choose_strategies, strategy_success


def numpy_choices(f, pbest_f, q, draws):
    """Ranks, best parcel, strategies and guides as MEWDO computed them with NumPy arrays."""
    r = ranks(f).astype(float)
    tb = np.argmin(pbest_f, axis=1)
    cdf = np.cumsum(q, axis=1)[:, None, :]
    strat = np.minimum((draws[..., 0:1] > cdf).sum(axis=2), N_STRATEGIES - 1)
    better = np.floor(draws[..., 5] * (r - 1)).astype(np.int64)
    order = np.argsort(f, axis=1, kind="stable")
    return r, tb, strat, np.take_along_axis(order, better, axis=1)


@pytest.mark.parametrize("seed", range(8))
def test_choose_strategies_equals_the_numpy_expressions(seed):
    rng = np.random.default_rng(seed)
    R, N = 4, 23
    f = rng.integers(0, 5, (R, N)).astype(float)  # many ties: the rank must be the stable one
    f[0, :3] = np.inf  # unevaluated parcels tie at +inf
    pbest_f = rng.integers(0, 4, (R, N)).astype(float)
    q = rng.dirichlet(np.ones(N_STRATEGIES), R)
    draws = rng.random((R, N, 6))
    draws[1, :, 0] = 1.0 - 1e-16  # beyond a cumulative share that rounds below 1
    got = np.empty((R, N)), np.empty(R, np.intp), np.empty((R, N), np.int64)
    guide = np.empty((R, N), np.int64)
    choose_strategies(f, pbest_f, q, draws, *got, guide)
    for g, w in zip((*got, guide), numpy_choices(f, pbest_f, q, draws), strict=True):
        np.testing.assert_array_equal(g, w)
    assert len(np.unique(got[2])) == N_STRATEGIES  # every strategy is exercised


def test_strategy_success_counts_like_numpy():
    rng = np.random.default_rng(3)
    R, N = 5, 17
    strategy = rng.integers(0, N_STRATEGIES, (R, N))
    strategy[0] = -1  # before the first move no parcel has a strategy
    F, f = rng.integers(0, 3, (R, N)).astype(float), rng.integers(0, 3, (R, N)).astype(float)
    used = np.stack([strategy == k for k in range(N_STRATEGIES)], axis=-1)
    n_used, n_succ = np.empty((R, N_STRATEGIES), np.int64), np.empty((R, N_STRATEGIES), np.int64)
    strategy_success(strategy, F, f, n_used, n_succ)
    np.testing.assert_array_equal(n_used, used.sum(axis=1))
    np.testing.assert_array_equal(n_succ, (used & (F < f)[..., None]).sum(axis=1))
    assert n_succ.sum() > 0 and n_used[0].sum() == 0
