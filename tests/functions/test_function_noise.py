"""F6 noise: one U[0,1) draw per evaluated point, from an explicit generator
(docs/functions.md#f-noise)."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.functions import FUNCTIONS, get_function


def _X(n: int = 8) -> np.ndarray:
    return np.random.default_rng(0).uniform(-1.28, 1.28, (n, 30))


def test_quartic_requires_a_generator():
    f = FUNCTIONS["quartic"]
    assert f.noise
    with pytest.raises(ValueError, match=r"rng=np\.random\.default_rng\(seed\)"):
        f(_X())
    with pytest.raises(ValueError, match="RandomState"):
        f(_X(), rng=np.random.RandomState(0))  # legacy generators are refused
    with pytest.raises(ValueError, match="int"):
        f(_X(), rng=0)  # a bare seed is not a generator


def test_noise_is_the_generators_draws_added_once_per_point():
    f = FUNCTIONS["quartic"]
    X = _X(8)
    rng = np.random.default_rng(42)
    values = f(X, rng=rng)
    draws = np.random.default_rng(42).random(8)
    np.testing.assert_array_equal(values, f.func(X) + draws)
    noise = values - f.func(X)
    assert np.all(noise >= 0.0) and np.all(noise < 1.0)
    # exactly n draws were consumed: the generators are in step afterwards
    ref = np.random.default_rng(42)
    ref.random(8)
    assert rng.random() == ref.random()


def test_same_seed_same_values_different_seed_differs():
    f = FUNCTIONS["F6"]
    X = _X()
    a = f(X, rng=np.random.default_rng(7))
    b = f(X, rng=np.random.default_rng(7))
    c = f(X, rng=np.random.default_rng(8))
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)


def test_single_point_draws_once():
    f = FUNCTIONS["quartic"]
    rng = np.random.default_rng(3)
    value = f(np.zeros(30), rng=rng)
    ref = np.random.default_rng(3)
    assert value == ref.random()  # f*(= 0) + one draw
    assert rng.random() == ref.random()


def test_noiseless_functions_ignore_rng_and_draw_nothing():
    rng = np.random.default_rng(11)
    f = FUNCTIONS["quartic_noiseless"]
    X = _X()
    np.testing.assert_array_equal(f(X, rng=rng), FUNCTIONS["quartic"].func(X))
    np.testing.assert_array_equal(f(X), f.func(X))
    assert rng.random() == np.random.default_rng(11).random()  # stream untouched


def test_noise_survives_variants():
    for f in (get_function("quartic", dim=4), get_function("quartic", preset="standard")):
        assert f.noise
        with pytest.raises(ValueError, match="default_rng"):
            f(np.zeros(f.dim))
