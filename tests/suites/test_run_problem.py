"""COCO's protocol on suite problems: the driver's evaluation trace equals a point-by-point log
of the library's values; budgets are exact; the final target stops a run."""

import numpy as np
import pytest

from mawdo import minimize
from mawdo.suites import get_problem, run_problem


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
    res = minimize(log, lb=f.lb, ub=f.ub, algorithm=algo, runs=3, seed=5, max_evals=3 * 157,
                   runs_per_block=3, trace_evaluations=True)  # fmt: skip
    traced = run_problem(f, algo, runs=3, budget=157, seed=5, final_target=None)
    assert np.all(res.nfev == 471) and np.all(traced.nfev == 471)
    for r, tr in enumerate(traced.evaluation_trace):
        assert len(log.values[r]) == 471  # the driver evaluated exactly the budget
        want = improvements(log.values[r])
        np.testing.assert_array_equal(tr.evals, [e for e, _ in want])
        np.testing.assert_array_equal(tr.best_y, [v for _, v in want])
        assert tr.best_y[-1] == traced.fun[r] == res.fun[r]


def test_run_problem_stops_at_the_final_target():
    f = get_problem("bbob", 1, instance=1, dim=4)
    res = run_problem(f, "cmaes", runs=4, budget=500, seed=2)
    prec = res.fun - f.f_star
    assert np.all(prec <= 1e-8) and np.all(res.status == 2)
    for r, tr in enumerate(res.evaluation_trace):
        assert res.nfev[r] < 2000
        # the run stopped at the end of the iteration that reached the target
        hit = tr.evals[np.argmax(tr.best_y - f.f_star <= 1e-8)]
        assert res.nfev[r] - hit < 8  # lambda = 4 + floor(3 ln 4) = 8


def test_run_problem_uses_budget_times_dimension():
    f = get_problem("bbob", 15, instance=2, dim=5)
    res = run_problem(f, "mawdo", runs=2, budget=61, seed=0, final_target=None)
    assert res.nfev.tolist() == [305, 305]
    assert all(t.evals[-1] <= 305 for t in res.evaluation_trace)


def test_a_run_is_recorded_the_same_alone_or_in_a_batch():
    f = get_problem("bbob", 20, instance=1, dim=5)
    batch = run_problem(f, "cmaes", runs=4, budget=100, seed=9).evaluation_trace
    (alone,) = run_problem(f, "cmaes", runs=1, budget=100, seed=9, first_run=2).evaluation_trace
    np.testing.assert_array_equal(alone.evals, batch[2].evals)
    np.testing.assert_array_equal(alone.best_y, batch[2].best_y)
