"""The driver's best-so-far against evaluations (``minimize(..., trace_evaluations=True)``):
a hand-counted run, and a naive replay of every value the objective returned."""

import numpy as np
import pytest

from mawdo import minimize
from mawdo.result import EvaluationTrace


class Script:
    """A vectorised objective that returns scripted values, call by call, whatever ``X``;
    it keeps every batch it was given (rows run-major, as the evaluator sends them)."""

    def __init__(self, calls):
        self.calls, self.seen = list(calls), []

    def __call__(self, X):
        self.seen.append(X.copy())
        return np.asarray(self.calls[len(self.seen) - 1], dtype=float)


def test_a_hand_counted_run():
    # 2 runs x pop 4, max_evals 10: two full iterations, then 2 evaluations each (the cut).
    # Values run-major per call: run 0's, then run 1's.
    nan, inf = np.nan, np.inf
    f = Script(
        [
            [5, nan, 3, 3] + [inf, -inf, 7, 2],  # NaN, +-inf never improve; the tie at 3 does not
            [4, 1, 1, 0.5] + [2, 3, 1.8, nan],  # run 0 reaches the target 0.8 at evaluation 8
            [0.1, 0.2] + [0.9, 0.9],  # run 0 frozen; run 1's tie goes to its first evaluation
        ]
    )
    res = minimize(f, [(-1, 1)] * 2, algorithm="random", runs=2, seed=3, pop_size=4,
                   max_evals=10, target=0.8, trace_evaluations=True)  # fmt: skip
    a, b = res.evaluation_trace
    assert a.evals.tolist() == [1, 3, 6, 8] and a.best_y.tolist() == [5, 3, 1, 0.5]
    assert b.evals.tolist() == [3, 4, 7, 9] and b.best_y.tolist() == [7, 2, 1.8, 0.9]
    assert a.evals.dtype == np.int64
    assert res.nfev.tolist() == [8, 10] and res.fun.tolist() == [0.5, 0.9]
    assert res.status.tolist() == [2, 1]  # target, evaluations
    assert [X.shape[0] for X in f.seen] == [8, 8, 4]  # the last call holds the cut batch
    np.testing.assert_array_equal(res.x[0], f.seen[1][3])  # run 0's 0.5
    np.testing.assert_array_equal(res.x[1], f.seen[2][2])  # run 1's first 0.9
    assert a.best_at([0, 1, 2, 5, 8, 100]).tolist() == [inf, 5, 5, 3, 0.5, 0.5]


def test_no_trace_unless_asked_and_a_bool_only():
    res = minimize("sphere", dim=2, algorithm="random", runs=2, seed=0, max_iter=3)
    assert res.evaluation_trace is None
    with pytest.raises(TypeError, match="trace_evaluations"):
        minimize("sphere", dim=2, runs=1, max_iter=2, trace_evaluations="yes")


def naive_traces(calls, runs, target):
    """Replay every batch the objective saw, run by run, value by value, as COCO counts."""
    count, best = [0] * runs, [np.inf] * runs
    out = [([], []) for _ in range(runs)]
    for vals in calls:
        m = len(vals) // runs
        frozen = [target is not None and best[r] <= target for r in range(runs)]
        for r in range(runs):
            if frozen[r]:
                continue
            for v in vals[r * m : (r + 1) * m]:
                count[r] += 1
                if np.isfinite(v) and v < best[r]:
                    best[r] = v
                    out[r][0].append(count[r])
                    out[r][1].append(v)
    return out, count, best


class RandomValues:
    """Coarse random values (ties), falling over time (targets reached), some non-finite."""

    def __init__(self, seed):
        self.rng, self.calls, self.t = np.random.default_rng(seed), [], 0

    def __call__(self, X):
        self.t += 1
        y = np.round(self.rng.uniform(0, 8.0 / self.t, X.shape[0]), 1)
        bad = self.rng.random(X.shape[0]) < 0.1
        y[bad] = self.rng.choice([np.nan, np.inf, -np.inf], bad.sum())
        self.calls.append(y.tolist())
        return y


@pytest.mark.parametrize(
    ("algorithm", "seed", "target"),
    [
        ("random", 1, None),
        ("random", 2, 0.15),
        ("mawdo", 3, 0.2),
        ("gwo", 4, 0.1),
        ("cmaes", 5, 0.2),
    ],
)
def test_equals_a_naive_replay_of_every_value(algorithm, seed, target):
    runs = 5
    f = RandomValues(seed)
    res = minimize(f, [(-2, 2)] * 3, algorithm=algorithm, runs=runs, seed=seed, max_evals=301,
                   target=target, trace_evaluations=True, runs_per_block=runs)  # fmt: skip
    want, count, best = naive_traces(f.calls, runs, target)
    assert res.nfev.tolist() == count
    np.testing.assert_array_equal(res.fun, best)
    for tr, (evals, values) in zip(res.evaluation_trace, want, strict=True):
        assert isinstance(tr, EvaluationTrace)
        assert tr.evals.tolist() == evals and tr.best_y.tolist() == values
    if target is not None:  # the freeze is exercised: some run stopped before the budget
        assert (res.status == 2).any() and (res.nfev < 301).any()


def test_blocks_of_runs_give_the_batch_trace():
    kw = dict(dim=4, algorithm="mawdo", runs=5, seed=11, max_evals=400, target=1e-2)
    one = minimize("rastrigin", trace_evaluations=True, **kw)
    blocks = minimize("rastrigin", trace_evaluations=True, runs_per_block=2, **kw)
    alone = minimize("rastrigin", trace_evaluations=True, **{**kw, "runs": 1}, first_run=3)
    assert len(blocks.evaluation_trace) == 5
    for a, b in zip(one.evaluation_trace, blocks.evaluation_trace, strict=True):
        np.testing.assert_array_equal(a.evals, b.evals)
        np.testing.assert_array_equal(a.best_y, b.best_y)
    np.testing.assert_array_equal(alone.evaluation_trace[0].evals, one.evaluation_trace[3].evals)
    for r, tr in enumerate(one.evaluation_trace):  # the trace ends where the driver's best is
        assert tr.best_y[-1] == one.fun[r] and tr.evals[-1] <= one.nfev[r]
        assert np.all(np.diff(tr.evals) > 0) and np.all(np.diff(tr.best_y) < 0)


def test_a_callbacks_snapshots_leave_the_trace_as_it_is():
    seen = []

    def watch(snapshot):
        seen.append(snapshot.evaluation_trace)
        return False

    kw = dict(dim=3, algorithm="gwo", runs=3, seed=4, max_evals=600, trace_evaluations=True)
    watched, plain = minimize("ackley", callback=watch, **kw), minimize("ackley", **kw)
    for a, b in zip(watched.evaluation_trace, plain.evaluation_trace, strict=True):
        np.testing.assert_array_equal(a.evals, b.evals)
        np.testing.assert_array_equal(a.best_y, b.best_y)
    assert len(seen) > 5
    for snapshot in seen:  # each holds the improvements so far: a prefix of the final trace
        for part, final in zip(snapshot, plain.evaluation_trace, strict=True):
            np.testing.assert_array_equal(part.evals, final.evals[: part.evals.size])
            np.testing.assert_array_equal(part.best_y, final.best_y[: part.best_y.size])
    assert sum(t.evals.size for t in seen[0]) < sum(t.evals.size for t in seen[-1])
