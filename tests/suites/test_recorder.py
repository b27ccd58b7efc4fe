"""The recorder's best-so-far against evaluations equals a point-by-point log; counts are exact."""

import numpy as np
import pytest

from mawdo import minimize
from mawdo.suites import EvaluationRecorder, get_problem, run_problem
from mawdo.suites.base import replace_formula


class PointLog:
    """A second, naive record: every value of every run, in the order evaluated."""

    def __init__(self, func, runs):
        self.func, self.runs = func, runs
        self.values = [[] for _ in range(runs)]

    def __call__(self, X):
        y = self.func(X)
        for r, block in enumerate(np.split(y, self.runs)):
            self.values[r].extend(block.tolist())
        return y


def improvements(values):
    """(evaluation, best) at each strict improvement, by a plain loop."""
    best, out = np.inf, []
    for i, v in enumerate(values, start=1):
        if v < best:
            best = v
            out.append((i, v))
    return out


@pytest.mark.parametrize("algo", ["cmaes", "random", "mawdo", "gwo"])
def test_traces_equal_a_point_by_point_log_and_budget_is_exact(algo):
    f = get_problem("bbob", 10, instance=1, dim=3)
    log = PointLog(f.func, 3)
    rec = EvaluationRecorder(log, 3)
    res = minimize(replace_formula(f, rec), algorithm=algo, runs=3, seed=5, max_evals=3 * 157)
    assert np.all(res.nfev == 471) and np.all(rec.nfev == 471)
    for r, tr in enumerate(rec.traces()):
        assert len(log.values[r]) == 471  # the driver evaluated exactly the budget
        want = improvements(log.values[r])
        np.testing.assert_array_equal(tr.evals, [e for e, _ in want])
        np.testing.assert_array_equal(tr.best_y, [v for _, v in want])
        assert tr.total_evals == 471
        assert tr.best_y[-1] == res.fun[r]
        np.testing.assert_array_equal(tr.best_x, res.x[r])


def test_run_problem_stops_at_the_final_target_and_counts_like_the_driver():
    f = get_problem("bbob", 1, instance=1, dim=4)
    res, traces = run_problem(f, "cmaes", runs=4, budget=500, seed=2)
    prec = res.fun - f.f_star
    assert np.all(prec <= 1e-8) and np.all(res.status == 2)
    for r, tr in enumerate(traces):
        assert tr.total_evals == res.nfev[r] < 2000
        # the run stopped at the end of the iteration that reached the target
        hit = tr.evals[np.argmax(tr.best_y - f.f_star <= 1e-8)]
        assert tr.total_evals - hit < 8  # lambda = 4 + floor(3 ln 4) = 8


def test_run_problem_uses_budget_times_dimension():
    f = get_problem("bbob", 15, instance=2, dim=5)
    res, traces = run_problem(f, "mawdo", runs=2, budget=61, seed=0, final_target=None)
    assert np.all(res.nfev == 305)
    assert [t.total_evals for t in traces] == [305, 305]


def test_a_run_is_recorded_the_same_alone_or_in_a_batch():
    f = get_problem("bbob", 20, instance=1, dim=5)
    _, batch = run_problem(f, "cmaes", runs=4, budget=100, seed=9)
    _, alone = run_problem(f, "cmaes", runs=1, budget=100, seed=9, first_run=2)
    np.testing.assert_array_equal(alone[0].evals, batch[2].evals)
    np.testing.assert_array_equal(alone[0].best_y, batch[2].best_y)


def test_best_at_reads_the_step_function():
    f = get_problem("bbob", 1, instance=1, dim=2)
    rec = EvaluationRecorder(f.func, 1)
    X = np.array([[1.0, 1.0], [4.0, 4.0], [0.5, 0.5], [3.0, 3.0]])
    y = f.func(X)
    rec(X[:2])
    rec(X[2:])
    tr = rec.traces()[0]
    expect = np.minimum.accumulate(y)
    np.testing.assert_array_equal(tr.best_at([1, 2, 3, 4]), expect)
    assert tr.best_at(0) == np.inf


def test_nan_values_are_worst_and_a_bad_batch_is_named():
    rec = EvaluationRecorder(lambda X: np.array([np.nan, 3.0, 1.0, np.nan]), 2)
    rec(np.zeros((4, 2)))
    a, b = rec.traces()
    assert a.evals.tolist() == [2] and a.best_y.tolist() == [3.0]
    assert b.evals.tolist() == [1] and b.best_y.tolist() == [1.0]
    with pytest.raises(ValueError, match="got 3 rows; a batch must hold runs x m rows"):
        rec(np.zeros((3, 2)))


class ArrayRecorder(EvaluationRecorder):
    """The recorder's batch update as it was written in NumPy before the compiled scan
    (a port kept as the reference): running minima, then the strict drops."""

    def _record(self, X, vals):
        R = self.runs
        m = vals.size // R
        V = np.where(np.isfinite(vals), vals, np.inf).reshape(R, m)
        counted = np.ones(R, bool) if self.target is None else ~(self.best <= self.target)
        cm = np.minimum.accumulate(np.concatenate([self.best[:, None], V], axis=1), axis=1)
        improved = (cm[:, 1:] < cm[:, :-1]) & counted[:, None]
        r, j = np.nonzero(improved)
        if r.size:
            self._chunks.append((r, self.nfev[r] + j + 1, V[r, j]))
            if self.best_x is None:
                self.best_x = np.full((R, X.shape[1]), np.nan)
            last = np.argmin(V, axis=1)
            upd = improved.any(axis=1)
            self.best_x[upd] = X.reshape(R, m, -1)[upd, last[upd]]
        self.best = np.where(counted, cm[:, -1], self.best)
        self.nfev += np.where(counted, m, 0)


@pytest.mark.parametrize("target", [None, 0.1])
def test_compiled_scan_equals_the_array_reference(target):
    rng = np.random.default_rng(7)
    R, D = 4, 3
    batches = []
    for it in range(30):
        m = int(rng.integers(1, 6))
        X = rng.normal(size=(R * m, D))
        # coarse values (ties), decreasing over time (targets reached), and non-finite ones
        y = np.round(rng.uniform(0, 6.0 / (1 + it), R * m), 1)
        y[rng.random(R * m) < 0.1] = rng.choice([np.nan, np.inf, -np.inf])
        batches.append((X, y))
    recs = []
    for cls in (EvaluationRecorder, ArrayRecorder):
        values = iter([y for _, y in batches])
        rec = cls(lambda X, values=values: next(values), R, target)
        for X, _ in batches:
            rec(X)
        recs.append(rec)
    new, ref = recs
    np.testing.assert_array_equal(new.best, ref.best)
    np.testing.assert_array_equal(new.nfev, ref.nfev)
    np.testing.assert_array_equal(new.best_x, ref.best_x)
    assert np.isfinite(new.best).all() and (np.isfinite(new.best_x).all())
    for a, b in zip(new.traces(), ref.traces(), strict=True):
        np.testing.assert_array_equal(a.evals, b.evals)
        np.testing.assert_array_equal(a.best_y, b.best_y)
        assert a.total_evals == b.total_evals
    if target is not None:  # some runs stopped recording: the target case is exercised
        assert (ref.best <= target).any() and (ref.nfev < ref.nfev.max()).any()
