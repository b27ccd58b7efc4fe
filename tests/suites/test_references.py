"""The reference algorithms' own promises: CMA-ES's default lambda and restarts; random search."""

import math

import numpy as np
from cmaes import CMA

from mawdo import minimize
from mawdo.suites import get_problem


def test_cmaes_default_lambda_is_hansens_and_an_explicit_one_wins():
    f = get_problem("bbob", 2, instance=1, dim=20)
    res = minimize(f, algorithm="cmaes", runs=2, seed=0, max_iter=3)
    lam = 4 + math.floor(3 * math.log(20))
    assert CMA(mean=np.zeros(20), sigma=1.0).population_size == lam == 12  # the library agrees
    assert res.params["pop_size"] == lam and np.all(res.nfev == 3 * lam)
    res = minimize(f, algorithm="cmaes", runs=2, seed=0, max_iter=3, pop_size=7)
    assert res.params["pop_size"] == 7 and np.all(res.nfev == 21)


def test_cmaes_restarts_when_it_stalls_and_not_when_told_not_to():
    f = get_problem("bbob", 3, instance=1, dim=2)  # Rastrigin: CMA-ES converges to local minima
    kw = {"runs": 3, "seed": 1, "max_evals": 3000, "algorithm": "cmaes"}
    on = minimize(f, **kw)
    off = minimize(f, restarts=False, **kw)
    assert min(on.metadata["restarts"]) >= 1
    assert off.metadata["restarts"] == [0, 0, 0]
    assert np.all(on.nfev == 3000) and np.all(off.nfev == 3000)


def test_random_search_is_uniform_in_the_box():
    seen = []

    def f(X):
        seen.append(X.copy())
        return X.sum(axis=1)

    bounds = [(-5.0, 5.0), (0.0, 1.0)]
    res = minimize(f, bounds, algorithm="random", runs=2, seed=3, max_evals=20_000)
    X = np.concatenate(seen)
    assert X.shape == (40_000, 2)
    # uniform: the mean and variance of U[a, b] within 5 standard errors
    for k, (a, b) in enumerate(bounds):
        sd = (b - a) / math.sqrt(12)
        assert abs(X[:, k].mean() - (a + b) / 2) < 5 * sd / math.sqrt(X.shape[0])
        assert abs(X[:, k].std() - sd) < 0.02 * sd
    per_run = np.concatenate([b.reshape(2, -1, 2) for b in seen], axis=1)  # batches: run-major
    np.testing.assert_array_equal(res.fun, per_run.sum(axis=2).min(axis=1))
