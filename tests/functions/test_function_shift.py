"""The shift wrapper (docs/functions.md#f-shift, origin bias): optimum moved into the middle 80%
of the box."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.functions import FUNCTIONS, get_function, shifted

ALL = list(FUNCTIONS)


@pytest.mark.parametrize("name", ALL)
@pytest.mark.parametrize("seed", [0, 1, 12345])
def test_shifted_optimum(name, seed):
    f = FUNCTIONS[name]
    g = shifted(f, seed)
    assert g.name == f"{name}@shifted" and g.paper_id == f.paper_id
    assert g.f_star == f.f_star and g.dim == f.dim and g.noise == f.noise
    np.testing.assert_array_equal(g.lb, f.lb)
    np.testing.assert_array_equal(g.ub, f.ub)
    assert g.func(g.x_star[None, :])[0] == f.f_star  # exact: g(s) = f(x_star)
    width = f.ub - f.lb
    assert np.all(g.x_star >= f.lb + 0.1 * width) and np.all(g.x_star <= f.ub - 0.1 * width)


@pytest.mark.parametrize("name", ALL)
def test_shifted_is_a_translation(name):
    f, g = FUNCTIONS[name], shifted(FUNCTIONS[name], 3)
    X = np.random.default_rng(0).uniform(f.lb, f.ub, (6, f.dim))
    np.testing.assert_array_equal(g.func(X), f.func((X - g.x_star) + f.x_star))


def test_shift_deterministic_and_seed_dependent():
    f = FUNCTIONS["rastrigin"]
    a, b, c = shifted(f, 5), shifted(f, 5), shifted(f, 6)
    np.testing.assert_array_equal(a.x_star, b.x_star)
    assert not np.array_equal(a.x_star, c.x_star)
    assert not np.array_equal(a.x_star, f.x_star)
    expected = -100 + 20 + 160 * np.random.default_rng(5).random(30)  # lb + 0.1w + 0.8w u
    np.testing.assert_allclose(a.x_star, expected, rtol=0, atol=1e-12)
    seeds = {tuple(shifted(f, s).x_star) for s in range(20)}
    assert len(seeds) == 20


def test_shift_spreads_over_the_middle_box():
    """Over many seeds the optimum is not biased toward the centre (fills the middle 80%)."""
    f = FUNCTIONS["sphere"]
    S = np.array([shifted(f, s).x_star for s in range(200)])
    assert S.min() < -70 and S.max() > 70  # middle 80% of [-100, 100] is [-80, 80]
    assert abs(S.mean()) < 5


def test_shift_seed_validation():
    f = FUNCTIONS["sphere"]
    assert shifted(f, np.int64(3)).x_star.tolist() == shifted(f, 3).x_star.tolist()
    with pytest.raises(TypeError, match="int"):
        shifted(f, 1.5)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="int"):
        shifted(f, True)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=">= 0"):
        shifted(f, -1)
    with pytest.raises(TypeError, match="BenchmarkFunction"):
        shifted("sphere", 0)  # type: ignore[arg-type]


def test_get_function_shifted_after_dim_and_preset():
    g = get_function("F7", dim=5, preset="standard", shifted=True, shift_seed=9)
    assert g.dim == 5 and np.all(g.ub == 5.12)
    assert np.all(np.abs(g.x_star) <= 0.8 * 5.12)
    assert g(g.x_star) == 0.0
    assert not g.scalable
    with pytest.raises(ValueError, match="fixed dimension"):
        g.with_dim(6)
    unshifted = get_function("F7", shifted=False, shift_seed=9)
    assert unshifted is FUNCTIONS["rastrigin"]


def test_shifted_noisy_quartic_keeps_noise():
    g = get_function("quartic", shifted=True, shift_seed=2)
    assert g.noise
    value = g(g.x_star, rng=np.random.default_rng(1))
    assert value == np.random.default_rng(1).random(1)[0]  # f* = 0 plus the single draw
