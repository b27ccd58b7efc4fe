"""The kernels shuffle the velocities themselves instead of building a permutation and gathering
through it (issue 15); each shortcut is compared with the code path it replaced."""

import numpy as np
import pytest

from mawdo.optimizers.kernels import (
    mewdo_step,
    shuffle_from_words,
    shuffle_values_from_words,
    words_per_permutation,
)
from mawdo.optimizers.wind_kernel import shuffle_values
from mawdo.util.shuffle import fisher_yates_batch

from .test_kernels import python_xoshiro

M64 = (1 << 64) - 1
DIMS = [1, 2, 3, 7, 13, 30, 40, 101]


def xoshiro_words(state, n):
    """``n`` outputs of xoshiro256** from ``state`` (the Python-integer port), and the state."""
    out, s = python_xoshiro(state, n)
    return np.array(out, np.uint64), s


@pytest.mark.parametrize("d", DIMS)
def test_shuffle_values_equals_the_permutation_then_the_gather(d):
    rng = np.random.default_rng(d)
    W = words_per_permutation(d)
    for _ in range(20):
        state = rng.integers(1, 2**63, 4, dtype=np.int64).astype(np.uint64)
        vals = rng.normal(size=d)
        words, after = xoshiro_words(state, W)
        perm = np.empty(d, np.intp)
        shuffle_from_words(words, 0, perm)
        got = vals.copy()
        s = shuffle_values(got, *(np.uint64(v) for v in state))
        np.testing.assert_array_equal(got, vals[perm])
        assert [int(v) for v in s] == [int(v) for v in after]  # exactly W words consumed
        got = vals.copy()
        padded = np.concatenate([rng.integers(0, 2**63, 3).astype(np.uint64), words])
        shuffle_values_from_words(padded, 3, got)
        np.testing.assert_array_equal(got, vals[perm])
    if d > 3:  # the draws do reach every position
        assert sorted(perm.tolist()) == list(range(d)) and perm.tolist() != list(range(d))


@pytest.mark.parametrize("D", [1, 6, 30])
def test_mewdo_step_from_words_moves_as_from_the_permutation_array(D):
    rng = np.random.default_rng(40 + D)
    R, N = 3, 11
    p, u = rng.uniform(-1, 1, (R, N, D)), rng.uniform(-0.5, 0.5, (R, N, D))
    pbest = rng.uniform(-1, 1, (R, N, D))
    rank = np.tile(np.arange(1.0, N + 1), (R, 1))
    tb, guide = rng.integers(0, N, R), rng.integers(0, N, (R, N))
    strat, draws = rng.integers(0, 3, (R, N)), rng.random((R, N, 6))
    words = rng.integers(0, 2**63, (R, N * words_per_permutation(D))).astype(np.uint64)
    words[:, ::2] |= np.uint64(1 << 63)  # high bits set too
    perm = np.empty((R, N, D), np.int16)
    fisher_yates_batch(words, perm)  # what MEWDO.ask built before (RunStreams.shuffle_rows)
    coef, lb, width = np.array([0.4, 0.2, 3.0, 0.4]), np.full(D, -3.0), np.full(D, 4.0)
    out = []
    for use_words in (False, True):
        P, U, X = p.copy(), u.copy(), np.empty((R, N, D))
        mewdo_step(P, U, pbest, rank, tb, guide, p.mean(axis=1), strat, draws, perm, words,
                   use_words, coef, 0.3, lb, width, X)  # fmt: skip
        out.append((P, U, X))
    for a, b in zip(*out, strict=True):
        np.testing.assert_array_equal(a, b)
    assert not np.array_equal(out[0][1], u)
