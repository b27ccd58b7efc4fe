"""L-SHADE, jSO and NL-SHADE-RSP converge on easy functions (slow: a few runs each at D = 10)."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo import minimize

ALGOS = ["lshade", "jso", "nlshade_rsp"]


def shifted_sphere(X):
    return ((X - 1.234) ** 2).sum(axis=1)


def rastrigin(X):
    Y = X - 0.5
    return (Y * Y - 10 * np.cos(2 * np.pi * Y) + 10).sum(axis=1)


@pytest.mark.slow
@pytest.mark.parametrize("algo", ALGOS)
def test_sphere_to_1e_8(algo):
    res = minimize(shifted_sphere, [(-100, 100)] * 10, algorithm=algo, runs=4, seed=3,
                   max_evals=40_000)  # fmt: skip
    assert np.all(res.fun < 1e-8), res.fun


@pytest.mark.slow
@pytest.mark.parametrize("algo", ALGOS)
def test_rastrigin_solved_within_the_cec_budget(algo):
    res = minimize(rastrigin, [(-5.12, 5.12)] * 10, algorithm=algo, runs=4, seed=4,
                   max_evals=100_000)  # fmt: skip
    assert np.median(res.fun) < 1e-6 and np.all(res.fun < 2.0), res.fun
