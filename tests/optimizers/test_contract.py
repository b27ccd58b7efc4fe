"""The contract every registered optimizer honours (DESIGN tier 1).

Parametrised over the registry, so a new entry is tested without touching this file.
"""

import numpy as np
import pytest

from mawdo import OPTIMIZERS, minimize
from mawdo.minimize import NoFiniteValueWarning

ALGOS = list(OPTIMIZERS)
LB = np.array([-5.0, -1.0, 0.0, 10.0])
UB = np.array([5.0, 3.0, 1.0, 20.0])
BOUNDS = list(zip(LB, UB, strict=True))
CENTRE = (LB + UB) / 2 + np.array([1.3, 0.4, 0.2, 2.0])  # optimum off the box centre


def shifted_sphere(X):
    return ((X - CENTRE) ** 2).sum(axis=1)


def run(algo, **kw):
    kw = {"runs": 3, "seed": 7, "max_iter": 30, "pop_size": 12, **kw}
    return minimize(kw.pop("fun", shifted_sphere), kw.pop("bounds", BOUNDS), algorithm=algo, **kw)


@pytest.mark.parametrize("algo", ALGOS)
def test_every_evaluated_point_is_inside_the_box(algo):
    seen = []

    def f(X):
        seen.append(X.copy())
        return shifted_sphere(X)

    run(algo, fun=f, max_iter=40)
    X = np.concatenate(seen)
    assert X.shape[1] == 4
    assert np.all(X >= LB) and np.all(X <= UB)


@pytest.mark.parametrize("algo", ALGOS)
def test_shapes_and_iteration_budget(algo):
    res = run(algo, max_iter=25)
    assert res.x.shape == (3, 4) and res.fun.shape == (3,)
    assert res.history.shape == (3, 25)
    assert np.all(res.nit == 25)
    assert np.all(np.diff(res.history, axis=1) <= 0), "best-so-far must never increase"
    np.testing.assert_allclose(res.fun, res.history[:, -1])
    np.testing.assert_allclose(shifted_sphere(res.x), res.fun, rtol=1e-12, atol=1e-300)
    # a population per iteration; one point for a sequential algorithm (scipy_de), at least
    # the final size 4 for one whose population shrinks (L-SHADE)
    cls = OPTIMIZERS[algo].cls
    assert np.all(res.nfev >= (1 if cls.sequential else 4 if cls.shrinking else 12) * 25)


@pytest.mark.parametrize("algo", ALGOS)
@pytest.mark.parametrize("budget", [12, 100, 257])
def test_evaluation_budget_is_exact(algo, budget):
    calls = []

    def f(X):
        calls.append(X.shape[0])
        return shifted_sphere(X)

    res = run(algo, fun=f, max_iter=None, max_evals=budget)
    assert np.all(res.nfev == budget)
    assert sum(calls) <= 3 * (budget + 12 * 2)  # evaluated no more than the last batch over
    assert np.all(res.history_nfev[:, -1] == budget)
    assert np.all(res.status == 1)


@pytest.mark.parametrize("algo", ALGOS)
def test_same_seed_same_result_and_different_seeds_differ(algo):
    a, b, c = run(algo), run(algo), run(algo, seed=8)
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.history, b.history)
    assert not np.array_equal(a.history, c.history)
    assert not np.array_equal(a.x[0], a.x[1]), "runs of one batch must differ"


@pytest.mark.parametrize("algo", ALGOS)
def test_run_is_identical_alone_or_in_a_batch(algo):
    batch = run(algo, runs=5, seed=11)
    for k in (0, 3):
        alone = run(algo, runs=1, seed=11, first_run=k)
        np.testing.assert_array_equal(alone.x[0], batch.x[k])
        np.testing.assert_array_equal(alone.history[0], batch.history[k])
    # and a batch cut elsewhere
    tail = run(algo, runs=2, seed=11, first_run=3)
    np.testing.assert_array_equal(tail.history, batch.history[3:5])


@pytest.mark.parametrize("algo", ALGOS)
def test_nan_and_inf_rank_as_worst(algo):
    def f(X):
        v = shifted_sphere(X)
        v[X[:, 0] < 0] = np.nan  # half the box is undefined
        v[X[:, 1] > 2.5] = np.inf
        v[X[:, 1] < -0.5] = -np.inf  # -inf is not a "great" value, it is invalid
        return v

    res = run(algo, fun=f, max_iter=40)
    assert np.all(np.isfinite(res.fun))
    assert np.all(res.x[:, 0] >= 0) and np.all(res.x[:, 1] <= 2.5) and np.all(res.x[:, 1] >= -0.5)


@pytest.mark.parametrize("algo", ALGOS)
def test_all_nan_objective_does_not_crash(algo):
    # and says that x is the unevaluated box centre, not a result
    with pytest.warns(NoFiniteValueWarning, match="3 of 3 runs found no finite objective"):
        res = run(algo, fun=lambda X: np.full(X.shape[0], np.nan), max_iter=5)
    assert np.all(np.isinf(res.fun))


@pytest.mark.parametrize("algo", ALGOS)
def test_scalar_objective_matches_vectorised(algo):
    vec = run(algo, max_iter=15)
    sca = run(algo, max_iter=15, fun=lambda x: float(((x - CENTRE) ** 2).sum()), vectorized=False)
    np.testing.assert_allclose(sca.history, vec.history, rtol=1e-12)


@pytest.mark.parametrize("algo", ALGOS)
def test_makes_progress_on_a_smooth_bowl(algo):
    res = run(algo, max_iter=60, pop_size=20)
    start = res.history[:, 0]
    assert np.all(res.fun < start), "no improvement over the initial population"


@pytest.mark.parametrize("algo", ALGOS)
def test_target_stops_each_run_and_freezes_it(algo):
    res = run(algo, max_iter=200, target=2.0)
    hit = res.status == 2
    assert np.all(res.fun[hit] <= 2.0)
    # a frozen run's budget stops when it hits the target
    assert np.all(res.nfev[hit] < res.nfev.max() + 1)
    for r in np.flatnonzero(hit):
        k = np.argmax(res.history[r] <= 2.0)
        assert np.all(res.history[r, k:] == res.history[r, k])


@pytest.mark.parametrize("algo", ALGOS)
def test_warm_start_points_are_evaluated_first(algo):
    seen = []

    def f(X):
        seen.append(X.copy())
        return shifted_sphere(X)

    x0 = np.stack([CENTRE, LB, UB])  # the optimum and two corners
    res = run(algo, fun=f, x0=x0, max_iter=3)
    first = seen[0].reshape(3, -1, 4)
    for r in range(3):
        np.testing.assert_allclose(first[r, :3], np.stack([CENTRE, LB, UB]), atol=1e-12)
    assert np.all(res.fun < 1e-20)  # the optimum was handed in (up to [-1,1] round-off), kept
    with pytest.raises(ValueError, match="x0 must have shape"):
        run(algo, x0=np.zeros((2, 3)))
    with pytest.raises(ValueError, match=r"x0\[2, 0\] = 12.0 lies outside the box"):
        run(algo, x0=np.stack([CENTRE, LB, UB + 7.0]))  # never clipped without a word
    with pytest.raises(ValueError, match="x0 has 13 points but pop_size is 12"):
        run(algo, x0=np.tile(CENTRE, (13, 1)))
