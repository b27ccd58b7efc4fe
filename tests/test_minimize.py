"""The driver: budgets, callbacks, problem set-up, and clear errors for bad input."""

import numpy as np
import pytest

from mawdo import ObjectiveError, minimize
from mawdo.problem import as_bounds


def sphere(X):
    return (X**2).sum(axis=1)


B3 = [(-5, 5)] * 3


@pytest.mark.parametrize(
    "bounds,match",
    [
        ([(1, 1), (0, 2)], "coordinate 0 has low=1.0 >= high=1.0"),
        ([(0, 2), (3, -3)], "coordinate 1 has low=3.0 >= high=-3.0"),
        ([(0, np.inf)], "finite"),
        ([(np.nan, 1)], "finite"),
        ([(0, 1, 2)], "pairs"),
        (None, "bounds are required"),
    ],
)
def test_bad_bounds(bounds, match):
    with pytest.raises(ValueError, match=match):
        minimize(sphere, bounds, algorithm="wdo", max_iter=2)


def test_bounds_forms_agree_and_mismatched_lengths_are_named():
    a = as_bounds([(-1, 1), (0, 2), (3, 4)])
    b = as_bounds(lb=np.array([-1, 0, 3]), ub=np.array([1, 2, 4]))
    # a (2, 2) array is read as two (low, high) pairs, as scipy.optimize does
    np.testing.assert_array_equal(as_bounds([(-1, 1), (0, 2)])[1], [1, 2])
    np.testing.assert_array_equal(a[0], b[0])
    np.testing.assert_array_equal(a[1], b[1])
    lb, ub = as_bounds((-2, 2), dim=4)
    assert lb.shape == (4,) and ub[3] == 2
    with pytest.raises(ValueError, match="3 coordinates but dim=2"):
        as_bounds([(0, 1)] * 3, dim=2)
    with pytest.raises(ValueError, match="give dim"):
        as_bounds((0, 1))
    # the former (lb_array, ub_array) form is refused for every D, not only where it is ambiguous
    with pytest.raises(ValueError, match="ambiguous.*lb=..., ub=..."):
        as_bounds((np.array([-1, 0, 3]), np.array([1, 2, 4])))


@pytest.mark.parametrize(
    "kw,match",
    [
        ({"pop_size": 1}, "pop_size=1 must be an integer >= 2"),
        ({"runs": 0}, "runs=0 must be an integer >= 1"),
        ({"max_iter": 0}, "max_iter=0 must be a positive integer"),
        ({"max_evals": -5}, "max_evals=-5"),
        ({"max_time": 0}, "max_time"),
        ({"first_run": -1}, "first_run"),
    ],
)
def test_bad_budget_arguments(kw, match):
    with pytest.raises(ValueError, match=match):
        minimize(sphere, B3, algorithm="gwo", **{"max_iter": 3, **kw})


def test_unknown_algorithm_suggests_close_names():
    with pytest.raises(KeyError, match="unknown algorithm 'mawod'. Did you mean 'mawdo'"):
        minimize(sphere, B3, algorithm="mawod")


def test_unknown_function_suggests_close_names():
    with pytest.raises(KeyError, match="rastrigin"):
        minimize("rastrign", algorithm="wdo")


def test_objective_that_raises_names_algorithm_run_and_iteration():
    def f(X):
        if np.any(X[:, 0] > 4.0):
            raise ZeroDivisionError("boom")
        return sphere(X)

    with pytest.raises(
        ObjectiveError,
        match=r"ZeroDivisionError: boom \(algorithm 'woa', run \d+, "
        r"iteration \d+\)",
    ):
        minimize(f, B3, algorithm="woa", runs=4, seed=0, max_iter=50)


@pytest.mark.parametrize(
    "out,match",
    [
        (lambda X: sphere(X)[:, None], r"returned shape \(\d+, 1\) for \d+ points"),
        (lambda X: X, r"returned shape \(\d+, 3\)"),
        (lambda X: 1.0, r"returned shape \(\)"),
        (lambda X: ["a"] * len(X), "not numbers"),
    ],
)
def test_objective_with_wrong_output_shape(out, match):
    with pytest.raises(ObjectiveError, match=match):
        minimize(out, B3, algorithm="wdo", max_iter=2)


def test_scalar_objective_returning_arrays_is_an_error():
    with pytest.raises(ObjectiveError, match="one float per point"):
        minimize(lambda x: x, B3, algorithm="wdo", vectorized=False, max_iter=2)


def test_callback_can_stop_and_sees_progress():
    seen = []

    def cb(res):
        seen.append(res.nit.max())
        return res.nit.max() >= 7

    res = minimize(sphere, B3, algorithm="mawdo", runs=2, max_iter=100, callback=cb)
    assert seen == list(range(1, 8))
    assert np.all(res.nit == 7) and np.all(res.status == 4)
    assert res.message == "stopped by callback"


def test_max_time_stops():
    import time

    def slow(X):
        time.sleep(0.01)
        return sphere(X)

    res = minimize(slow, B3, algorithm="gwo", max_iter=10_000, max_time=0.2)
    assert res.nit[0] < 100 and res.status[0] == 3


def test_benchmark_by_name_and_shifted():
    r = minimize("F12", algorithm="mawdo", runs=3, seed=1, max_iter=100)
    assert r.x.shape == (3, 2) and r.f_star == pytest.approx(-1.0316284534898774)
    assert np.all(r.fun >= r.f_star - 1e-12)
    s = minimize("sphere", algorithm="gwo", runs=2, seed=1, max_iter=50, shifted=True, dim=5)
    assert s.x.shape == (2, 5) and s.problem.endswith("@shifted")
    with pytest.raises(ValueError, match="shifted=True applies to benchmark"):
        minimize(sphere, B3, algorithm="gwo", shifted=True)


def test_quartic_noise_is_reproducible_and_per_run():
    a = minimize("quartic", algorithm="wdo", runs=3, seed=4, max_iter=20, dim=5)
    b = minimize("quartic", algorithm="wdo", runs=3, seed=4, max_iter=20, dim=5)
    np.testing.assert_array_equal(a.fun, b.fun)
    alone = minimize("quartic", algorithm="wdo", runs=1, seed=4, first_run=2, max_iter=20, dim=5)
    assert alone.fun[0] == a.fun[2]


def test_compiled_driver_steps_equal_their_numpy_forms():
    # the evaluator's value store and the run log's best-so-far, against the NumPy code they
    # replaced, on values with NaN, +-inf, ties, inactive runs and a truncated batch
    from mawdo.budget import take_best
    from mawdo.problem import store_values

    rng = np.random.default_rng(3)
    R, n, m, D = 5, 7, 4, 3
    for _ in range(50):
        vals = np.round(rng.normal(size=(R, m)), 1)
        vals[rng.random((R, m)) < 0.15] = rng.choice([np.nan, np.inf, -np.inf])
        active = rng.random(R) < 0.7
        nfev = rng.integers(0, 100, R)
        F = np.full((R, n), -7.0)
        want_nfev = nfev.copy()
        store_values(vals, F, nfev, active)
        ref = np.empty((R, n))
        ref[:, :m] = np.where(np.isfinite(vals), vals, np.inf)
        ref[:, m:] = np.inf
        want_nfev[active] += m
        np.testing.assert_array_equal(F, ref)
        np.testing.assert_array_equal(nfev, want_nfev)

        X = rng.normal(size=(R, n, D))
        best_f = np.where(rng.random(R) < 0.3, np.inf, rng.normal(size=R))
        best_x, nit = rng.normal(size=(R, D)), rng.integers(0, 9, R)
        want = best_f.copy(), best_x.copy(), nit.copy()
        j = F.argmin(axis=1)
        fj = F[np.arange(R), j]
        better = active & (fj < want[0])
        want[0][better] = fj[better]
        want[1][better] = X[better, j[better]]
        want[2][active] = 11
        take_best(X, F, active, best_f, best_x, nit, 11)
        for got, w in zip((best_f, best_x, nit), want, strict=True):
            np.testing.assert_array_equal(got, w)


class _Spy:
    """An objective that keeps every batch it is given; ``pure`` as declared."""

    def __init__(self, pure):
        self.pure, self.seen = pure, []

    def __call__(self, X):
        self.seen.append(X)
        return sphere(X)


def test_an_objective_that_declares_itself_pure_gets_the_candidates_without_a_copy():
    from mawdo.minimize import make_problem

    assert make_problem(_Spy(True), B3).pure
    assert not make_problem(sphere, B3).pure  # no declaration: a copy, as before
    assert not make_problem(_Spy("yes"), B3).pure  # only True itself declares it
    kw = {"algorithm": "mawdo", "seed": 1, "max_iter": 5}
    pure, copied = _Spy(True), _Spy(False)
    a, b = minimize(pure, B3, **kw), minimize(copied, B3, **kw)
    # the pure one saw views of the driver's candidates, the other fresh copies of them
    assert all(X.base is not None for X in pure.seen)
    assert all(X.base is None for X in copied.seen)
    np.testing.assert_array_equal(a.x, b.x)  # and the search is the same
    np.testing.assert_array_equal(a.fun, b.fun)
    np.testing.assert_array_equal(a.nfev, b.nfev)
