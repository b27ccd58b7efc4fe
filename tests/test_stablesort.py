"""mawdo.util.stablesort: the permutation of NumPy's stable argsort (and of Numba's own,
compiled)."""

from __future__ import annotations

import numpy as np
import pytest
from numba import njit

from mawdo.util.stablesort import stable_argsort


@njit
def _numba_stable(keys):
    return np.argsort(keys, kind="mergesort")


@njit
def _numba_default(keys):
    return np.argsort(keys)


def _keys(rng, n, kind):
    if kind == "ties":
        keys = rng.integers(0, 4, n).astype(float)
    else:
        keys = rng.normal(size=n)
    if n:
        keys[rng.integers(0, n, 3)] = np.nan
        keys[rng.integers(0, n, 2)] = -0.0
        keys[rng.integers(0, n, 2)] = np.inf
    return keys


@pytest.mark.parametrize("kind", ["ties", "distinct"])
def test_same_permutation_as_numpy_and_numba_stable_sorts(kind):
    rng = np.random.default_rng(7)
    for n in [0, 1, 2, 15, 16, 17, 31, 32, 33, 100, 257, *rng.integers(0, 400, 40)]:
        keys = _keys(rng, int(n), kind)
        got = stable_argsort(keys)
        assert got.dtype == np.int64
        np.testing.assert_array_equal(got, np.argsort(keys, kind="stable"))
        np.testing.assert_array_equal(got, _numba_stable(keys))


def test_up_to_15_keys_numbas_default_argsort_is_the_same():
    # Numba's quick sort is an insertion sort below 16 keys: the kernels that used it see the
    # same order there (longer inputs differ only among equal keys; see intervals._sweep_order)
    rng = np.random.default_rng(3)
    for _ in range(300):
        keys = _keys(rng, int(rng.integers(0, 16)), "ties")
        np.testing.assert_array_equal(stable_argsort(keys), _numba_default(keys))


def test_ties_keep_index_order_and_nan_goes_last():
    keys = np.array([2.0, np.nan, 1.0, 2.0, -0.0, 0.0, 1.0, np.nan, -np.inf])
    np.testing.assert_array_equal(stable_argsort(keys), [8, 4, 5, 2, 6, 0, 3, 1, 7])
