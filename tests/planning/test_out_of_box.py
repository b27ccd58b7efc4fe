"""Candidates outside the cost's box: the planner costs them as their projection onto the box.

EA4eig's jSO step leaves its eigen-crossover trials outside the box, as its authors' code does
(docs/deviations.md#d-ea4eig); on a planning map such a trial more than one map size outside
made the spacetime cost refuse the batch and the plan fail."""

import numpy as np
import pytest

from mawdo.minimize import minimize
from mawdo.optimizers.random_search import RandomSearch
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.execute import Run, in_box

from . import maps


class Outside(RandomSearch):
    """Random search whose every trial after the first batch lies far left of the box: at
    least twice its width out, so far past what the spacetime cost accepts."""

    def ask(self, state):
        X = super().ask(state)
        if state.t == 0:
            return X
        width = state.space.ub - state.space.lb
        return X - 3.0 * width


def test_in_box_projects_and_copies_only_when_needed():
    lb, ub = np.zeros(4), np.full(4, 10.0)
    X = np.array([[1.0, 2.0, 3.0, 4.0]])
    assert in_box(X, lb, ub) is X  # inside: the same array, no copy
    Y = np.array([[-5.0, 2.0, 12.0, np.nan]])
    np.testing.assert_array_equal(in_box(Y, lb, ub), [[0.0, 2.0, 10.0, np.nan]])
    np.testing.assert_array_equal(Y, [[-5.0, 2.0, 12.0, np.nan]])  # the optimizer's untouched


def test_the_optimizer_outside_the_box_is_costed_at_the_projection():
    sc = maps._scenario("empty", [], (20.0, 183.0), (346.0, 183.0))
    start = np.array([20.0, 183.0])
    cfg = dict(pop_size=40, replan_iters=3, n_waypoints=4, auto_waypoints=False, guide_routes=0)
    run = Run(sc, "random", 0, PlannerConfig(**cfg), dynamic=True)
    lb, ub = run.cost.bounds
    far = np.full((1, lb.size), lb - 3.0 * (ub - lb))
    # the cost itself refuses such a candidate; the run's search does not
    with pytest.raises(ValueError, match="more than one map size outside"):
        run.cost(far, start=start, t0=0.0)
    run.optimizers = {p: Outside(pop_size=p) for p in run.optimizers}
    cands, _ = run.optimise(start, 0, None)
    assert np.all(cands >= lb) and np.all(cands <= ub)
    rep = run.replans[-1]
    # the reported best is the point costed: its cost from start at t = 0 is the one found
    x = rep.waypoints.reshape(1, -1)
    assert np.all(x >= lb) and np.all(x <= ub)
    np.testing.assert_allclose(run.cost(x, start=start, t0=0.0)[0], rep.cost, rtol=1e-12)


def test_ea4eig_leaves_the_box_as_coded():
    # why the projection exists: with the optimum outside the box, EA4eig evaluates outside it
    # (its jSO step's eigen crossover repairs nothing), unlike every other registered optimizer
    seen = []

    def f(X):
        seen.append(np.max(np.abs(X)))
        return ((np.asarray(X) - 3.0) ** 2).sum(axis=-1)

    minimize(f, lb=-np.ones(8), ub=np.ones(8), algorithm="ea4eig", seed=0, max_iter=60, runs=2)
    assert max(seen) > 1.0
