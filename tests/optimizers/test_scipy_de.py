"""Issue 29: scipy's differential evolution registered as ``scipy_de``.

The reference is scipy itself: a direct ``scipy.optimize.differential_evolution`` call with the
seed the run used must ask for the same points and return the same best ``x`` and ``f``.
"""

import gc
import threading

import numpy as np
import pytest
from scipy.optimize import differential_evolution
from scipy.optimize._differentialevolution import DifferentialEvolutionSolver

from mawdo import ObjectiveError, minimize
from mawdo.optimizers.base import Space
from mawdo.optimizers.scipy_de import STRATEGIES, ScipyDE
from mawdo.streams import RunStreams
from tests.cli_run import mawdo

BOUNDS = [(-5.0, 5.0), (-2.0, 3.0), (0.0, 4.0)]
C = np.array([1.3, -0.7, 2.2])


def bowl(x):
    return float(((x - C) ** 2).sum() + 0.5 * x[0] * x[1])


def de_run(runs=2, seed=4, **kw):
    kw = {"algorithm": "scipy_de", "runs": runs, "seed": seed, "vectorized": False, **kw}
    return minimize(kw.pop("fun", bowl), BOUNDS, **kw)


def direct(seed, points=None, **kw):
    def f(x):
        if points is not None:
            points.append(np.array(x))
        return bowl(x)

    return differential_evolution(f, BOUNDS, rng=np.random.default_rng(seed), **kw)


@pytest.mark.parametrize("run", [0, 3])
def test_asks_the_points_of_a_direct_scipy_call_and_returns_its_result(run):
    seed = de_run(runs=1, first_run=run, max_evals=1).metadata["de_seeds"][0][0]
    calls = []
    ref = direct(seed, calls, maxiter=30)
    assert len(calls) == ref.nfev  # scipy's count includes the polish
    seen = []

    def f(x):
        seen.append(np.array(x))
        return bowl(x)

    res = de_run(fun=f, runs=1, first_run=run, max_evals=ref.nfev, maxiter=30)
    assert res.nfev[0] == ref.nfev and res.metadata["restarts"] == [0]
    np.testing.assert_array_equal(np.array(seen), np.array(calls))  # the same points, in order
    # scipy returns its polished x; the driver keeps the least value it evaluated (the rule of
    # every algorithm), which a finite-difference probe of the polish can undercut in the last
    # digits (run 3: -0.6306666666636376 against scipy's -0.630666666663628)
    values = [bowl(x) for x in calls]
    assert ref.fun in values and res.fun[0] == min(values) <= ref.fun
    np.testing.assert_array_equal(res.x[0], calls[int(np.argmin(values))])
    assert abs(res.fun[0] - ref.fun) <= 1e-12 * abs(ref.fun)
    if run == 0:  # here scipy's answer is the least value evaluated: the very same x and f
        assert res.fun[0] == ref.fun
        np.testing.assert_array_equal(res.x[0], ref.x)


def test_scipy_defaults_are_its_own():
    res = de_run(max_evals=3)
    assert res.params["pop_size"] == 15 * 3  # popsize 15 times D
    ref = DifferentialEvolutionSolver(bowl, BOUNDS)
    assert ref.num_population_members == res.params["pop_size"]
    assert (ref.strategy, ref.cross_over_probability, ref.tol, ref.maxiter, ref.polish) == (
        res.params["strategy"], res.params["recombination"], res.params["tol"],
        res.params["maxiter"], res.params["polish"],
    )  # fmt: skip
    assert tuple(ref.dither) == res.params["mutation"] and ref.atol == res.params["atol"]
    assert set(STRATEGIES) == set(ref._binomial) | set(ref._exponential)
    # Sobol rounds the population up to a power of two
    res = de_run(max_evals=3, init="sobol")
    size = DifferentialEvolutionSolver(bowl, BOUNDS, init="sobol").num_population_members
    assert res.params["pop_size"] == size == 64


@pytest.mark.parametrize("budget", [7, 130, 200])
def test_the_budget_is_exact_and_nothing_past_it_is_evaluated(budget):
    # maxiter=2 ends a call after 3 x 45 points and its polish: 200 cuts into the next call
    rows = []

    def f(X):
        rows.append(X.shape[0])
        return ((X - C) ** 2).sum(axis=1)

    res = de_run(fun=f, runs=3, max_evals=budget, maxiter=2, vectorized=True)
    assert np.all(res.nfev == budget) and np.all(res.history_nfev[:, -1] == budget)
    assert sum(rows) == 3 * budget  # one point per run and iteration, none past the cap
    restarted = budget > 3 * 45
    assert all((n > 0) == restarted for n in res.metadata["restarts"])


def test_polish_evaluations_count_and_a_cut_polish_keeps_the_best_evaluated():
    seeds = de_run(max_evals=1, runs=1).metadata["de_seeds"][0]
    ref = direct(seeds[0], maxiter=10)
    unpolished = direct(seeds[0], maxiter=10, polish=False)
    assert ref.nfev > unpolished.nfev  # L-BFGS-B spent evaluations
    values = []

    def f(x):
        values.append(bowl(x))
        return values[-1]

    cut = unpolished.nfev + 3  # three polish evaluations, then the cap
    res = de_run(fun=f, runs=1, max_evals=cut, maxiter=10)
    assert len(values) == cut and res.nfev[0] == cut
    assert res.fun[0] == min(values) <= unpolished.fun


def test_a_run_is_the_same_alone_in_a_batch_or_in_blocks():
    kw = {"max_evals": 400, "maxiter": 3, "seed": 9}  # restarts and polish inside the budget
    batch = de_run(runs=4, **kw)
    assert min(batch.metadata["restarts"]) >= 1
    blocks = de_run(runs=4, runs_per_block=1, **kw)
    np.testing.assert_array_equal(blocks.history, batch.history)
    assert blocks.metadata["de_seeds"] == batch.metadata["de_seeds"]
    for k in (0, 3):
        alone = de_run(runs=1, first_run=k, **kw)
        np.testing.assert_array_equal(alone.history[0], batch.history[k])
        assert alone.metadata["de_seeds"][0] == batch.metadata["de_seeds"][k]
    assert len({s[0] for s in batch.metadata["de_seeds"]}) == 4


def test_without_restarts_a_finished_run_repeats_its_result():
    res = de_run(runs=1, max_evals=400, maxiter=3, restarts=False)
    assert res.metadata["restarts"] == [0] and len(res.metadata["de_seeds"][0]) == 1
    assert res.nfev[0] == 400
    k = np.argmax(res.history[0] == res.fun[0])
    assert k < 399 and np.all(res.history[0, k:] == res.fun[0])


def _live_scipy_calls() -> list:
    gc.collect()
    runs = [o for o in gc.get_objects() if type(o).__qualname__ == "_Run"]
    return [r for r in runs if r.glet]  # started and not ended


def test_scipy_calls_end_with_the_batch_even_after_an_objective_error():
    threads = threading.active_count()
    res = de_run(runs=3, max_evals=50)
    assert res.nfev.tolist() == [50, 50, 50] and _live_scipy_calls() == []

    def broken(x):
        raise RuntimeError("boom")

    with pytest.raises(ObjectiveError, match="boom"):
        de_run(runs=3, max_evals=50, fun=broken)
    assert _live_scipy_calls() == []
    assert threading.active_count() == threads  # the calls run in the driver's own thread


def test_a_dropped_state_unwinds_its_scipy_calls_at_once():
    opt = ScipyDE()
    space = Space(np.array([b[0] for b in BOUNDS]), np.array([b[1] for b in BOUNDS]))
    streams = RunStreams.from_seed_sequences(np.random.SeedSequence(1).spawn(2))
    state = opt.init(space, streams, max_iter=10)
    X = opt.ask(state)
    opt.tell(state, X, ((X - C) ** 2).sum(axis=2))
    runs = list(state.runs)
    assert all(r.glet for r in runs)  # suspended inside scipy, waiting for a value
    del state
    assert not any(r.glet for r in runs) and all(r.glet.dead for r in runs)


@pytest.mark.parametrize(
    "kw,match",
    [
        (
            {"strategy": "best3bin"},
            r"^strategy='best3bin' is not valid; choose one of \('best1bin'",
        ),
        ({"mutation": (0.5, 2)}, r"^mutation\[1\]=2 must be a finite number in \[0, 2\)$"),
        ({"mutation": 2.5}, r"^mutation=2.5 must be a finite number in \[0, 2\)$"),
        ({"mutation": (0.1, 0.2, 0.3)}, r"must be a number in \[0, 2\) or a pair"),
        ({"recombination": 1.5}, r"^recombination=1.5 must be a finite number in \[0, 1\]$"),
        ({"pop_size": 4}, "^pop_size=4 must be an integer >= 5$"),
        ({"pop_size": 12, "init": "sobol"}, "pop_size=12 with init='sobol' must be a power of two"),
        ({"polish": "yes"}, "^polish='yes' must be True or False"),
    ],
)
def test_bad_options_name_the_option(kw, match):
    with pytest.raises(ValueError, match=match):
        de_run(max_evals=5, **kw)


def test_scipy_de_is_listed_by_the_command_line():
    res = mawdo("list", "algorithms")
    assert res.returncode == 0, res.stderr
    line = next(s for s in res.stdout.splitlines() if "scipy_de" in s)
    assert "differential evolution" in line
