"""COCO measures against hand calculations."""

import numpy as np
import pytest

from mawdo.experiments.kinds.suite.metrics import (
    BBOB_GROUPS,
    aggregate_runtime,
    fixed_budget,
    friedman_ranks,
    function_group,
    runtime_ecdf,
    runtimes,
    standard_targets,
)


def test_standard_targets_are_cocos_51():
    t = standard_targets()
    assert t.shape == (51,)
    assert t[0] == 100.0 and t[-1] == pytest.approx(1e-8, rel=1e-12)
    np.testing.assert_allclose(t[:6], [100, 10**1.8, 10**1.6, 10**1.4, 10**1.2, 10])
    np.testing.assert_allclose(np.log10(t[:-1] / t[1:]), 0.2)
    np.testing.assert_allclose(standard_targets(1, -1, 1), [10, 1, 0.1])
    with pytest.raises(ValueError, match="high > low"):
        standard_targets(-8, 2)


def test_runtimes_by_hand():
    # f_opt = 10; precisions 90, 5, 0.5, 1e-9 reached at evaluations 1, 4, 9, 30
    evals = [1, 4, 9, 30]
    best = [100.0, 15.0, 10.5, 10.0 + 1e-9]
    rt = runtimes(evals, best, 10.0, [100, 90, 50, 5, 1, 0.5, 1e-8, 1e-10])
    np.testing.assert_array_equal(rt, [1, 1, 4, 4, 9, 9, 30, np.inf])


def test_runtimes_of_an_empty_record_are_inf():
    assert np.all(np.isinf(runtimes([], [], 0.0, [1.0, 0.1])))


def test_aggregate_runtime_by_hand():
    # three runs of 100 evaluations; target A solved by runs 0, 1 at 10, 30; target B by run 0
    rt = np.array([[10, 50], [30, np.inf], [np.inf, np.inf]])
    art = aggregate_runtime(rt, [100, 100, 100])
    np.testing.assert_allclose(art, [(10 + 30 + 100) / 2, (50 + 100 + 100) / 1])
    art0 = aggregate_runtime(np.full((2, 1), np.inf), [5, 7])
    assert art0[0] == np.inf
    with pytest.raises(ValueError, match="2 runs of runtimes but 3"):
        aggregate_runtime(rt[:2], [1, 2, 3])


def test_runtime_ecdf_by_hand():
    # D = 2. Problem 1: 1 run x 2 targets, runtimes 4 and 20 evals (2 and 10 per dim).
    # Problem 2: 2 runs x 2 targets, runtimes {2, inf} and {6, 8} (1, inf, 3, 4 per dim).
    p1 = np.array([[4, 20]])
    p2 = np.array([[2, np.inf], [6, 8]])
    budgets = [0.5, 1, 2, 3, 4, 10, 1e9]
    got = runtime_ecdf([p1, p2], budgets, dim=2)
    f1 = np.array([0, 0, 1, 1, 1, 2, 2]) / 2
    f2 = np.array([0, 1, 1, 2, 3, 3, 3]) / 4
    np.testing.assert_allclose(got, (f1 + f2) / 2)  # each problem weighs one half


def test_fixed_budget_by_hand():
    got = fixed_budget([3, 10, 50], [8.0, 2.0, 1.0], [1, 3, 9, 10, 49, 50, 1000])
    np.testing.assert_array_equal(got, [np.inf, 8, 8, 2, 2, 1, 1])


def test_bad_records_are_refused():
    with pytest.raises(ValueError, match="increasing evals and non-increasing best_y"):
        runtimes([1, 5, 3], [3.0, 2.0, 1.0], 0.0, [1.0])
    with pytest.raises(ValueError, match="one length"):
        fixed_budget([1, 2], [1.0], [3])


def test_groups_partition_the_24_functions():
    ids = sorted(i for g in BBOB_GROUPS.values() for i in g)
    assert ids == list(range(1, 25))
    assert function_group(1) == "separable" and function_group(24).startswith("multimodal, weak")
    with pytest.raises(ValueError, match="1-24"):
        function_group(25)


def test_friedman_ranks_by_hand():
    # three problems, three algorithms; ranks (1,2,3), (2,1,3), (1.5,1.5,3) -> means
    table = [[1.0, 2.0, 3.0], [5.0, 4.0, 9.0], [7.0, 7.0, np.inf]]
    fr = friedman_ranks(table, ["a", "b", "c"])
    np.testing.assert_allclose(fr.mean_ranks, [(1 + 2 + 1.5) / 3, (2 + 1 + 1.5) / 3, 3.0])
    assert fr.n_functions == 3
