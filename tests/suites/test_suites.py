"""Suite problems give the libraries' own values, bounds and optima; bad input is named."""

import pickle
import sys

import ioh
import numpy as np
import pytest
from opfunu.cec_based import cec2017, cec2022

from mawdo import minimize
from mawdo.registry import UnknownNameError
from mawdo.suites import SUITES, MissingExtraError, evaluation_budget, get_problem
from mawdo.suites.cec import cec_dims, official_id


def points(dim, n, lo, hi, seed):
    return np.random.default_rng(seed).uniform(lo, hi, (n, dim))


@pytest.mark.parametrize("fid", range(1, 25))
@pytest.mark.parametrize(("iid", "dim"), [(1, 2), (3, 5), (7, 20), (2, 40)])
def test_bbob_values_equal_ioh_point_by_point(fid, iid, dim):
    f = get_problem("bbob", fid, instance=iid, dim=dim)
    ref = ioh.get_problem(fid, iid, dim, ioh.ProblemClass.REAL)
    X = points(dim, 9, -5, 5, fid * 100 + dim)
    want = np.array([ref(x) for x in X])  # ioh's own call, one point at a time
    np.testing.assert_array_equal(f.func(X), want)
    np.testing.assert_array_equal(f(X), want)
    assert f.f_star == ref.optimum.y
    np.testing.assert_array_equal(f.x_star, ref.optimum.x)
    np.testing.assert_array_equal(f.lb, np.full(dim, -5.0))
    np.testing.assert_array_equal(f.ub, np.full(dim, 5.0))
    assert f.function_name == ref.meta_data.name
    np.testing.assert_allclose(f(f.x_star), f.f_star, rtol=0, atol=1e-9)


def cec_cases():
    for year, n in ((2017, 29), (2022, 12)):
        for fid in range(1, n + 1):  # opfunu's numbers
            for dim in cec_dims(year, official_id(year, fid)):
                if dim <= 20:
                    yield year, fid, dim


@pytest.mark.parametrize(("year", "fid", "dim"), list(cec_cases()))
def test_cec_opfunu_values_equal_opfunu_under_the_official_number(year, fid, dim):
    f = get_problem(f"cec{year}-opfunu", official_id(year, fid), dim=dim)
    mod = cec2017 if year == 2017 else cec2022
    ref = getattr(mod, f"F{fid}{year}")(ndim=dim)  # a fresh opfunu object, not our cached one
    assert dim in ref.dim_supported
    X = points(dim, 6, -100, 100, year + fid + dim)
    np.testing.assert_array_equal(f(X), [ref.evaluate(x) for x in X])
    assert f.f_star == ref.f_global
    np.testing.assert_array_equal(f.x_star, ref.x_global)
    np.testing.assert_array_equal(np.stack([f.lb, f.ub], axis=1), ref.bounds)
    assert f(f.x_star) == pytest.approx(f.f_star, abs=1e-6)  # the optimum is where opfunu says


@pytest.mark.parametrize(("year", "n"), [(2017, 29), (2022, 12)])
def test_cec_dimensions_are_opfunus(year, n):
    mod = cec2017 if year == 2017 else cec2022
    for fid in range(1, n + 1):
        default = getattr(mod, f"F{fid}{year}")()
        want = cec_dims(year, official_id(year, fid))
        assert tuple(d for d in default.dim_supported if d <= 100) == want


def test_opfunu_suite_numbers_are_official_and_its_missing_f2_is_named():
    assert [official_id(2017, k) for k in (1, 2, 3, 29)] == [1, 3, 4, 30]
    assert get_problem("cec2017-opfunu", 3, dim=10).description.endswith("(opfunu F2)")
    with pytest.raises(ValueError, match="opfunu 1.0.4 does not implement the official CEC 2017"):
        get_problem("cec2017-opfunu", 2, dim=10)
    assert get_problem("cec2022-opfunu", 12, dim=10).function_id == 12


def test_bbob_dimension_range_and_instances():
    assert SUITES["bbob"].dims(1) == tuple(range(2, 41))
    a = get_problem("bbob", 3, instance=1, dim=5)
    b = get_problem("bbob", 3, instance=2, dim=5)
    assert a.f_star != b.f_star  # instances move the optimum


def test_ids_and_names_resolve_to_the_same_function():
    X = points(5, 4, -5, 5, 0)
    ref = get_problem("bbob", 15, dim=5)(X)
    for fid in ("f15", "F15", "15", "rastriginrotated", "RastriginRotated", np.int64(15)):
        np.testing.assert_array_equal(get_problem("BBOB", fid, dim=5)(X), ref)


def test_minimize_takes_a_suite_problem_and_reports_f_star():
    f = get_problem("bbob", 1, instance=2, dim=4)
    res = minimize(f, algorithm="cmaes", runs=2, seed=0, max_evals=400)
    assert res.f_star == f.f_star
    assert np.all(res.nfev == 400)
    np.testing.assert_allclose(f(res.x), res.fun, rtol=0, atol=0)
    assert np.all(res.fun - f.f_star < 1e-3)


def test_problems_pickle_for_worker_processes():
    for f in (get_problem("bbob", 7, 3, 6), get_problem("cec2022", 4, 1, 10)):
        X = points(f.dim, 5, -5, 5, 1)
        g = pickle.loads(pickle.dumps(f))
        np.testing.assert_array_equal(g(X), f(X))


def test_unknown_suite_and_function_suggest_close_names():
    with pytest.raises(UnknownNameError, match="Did you mean 'bbob'"):
        get_problem("bbbo", 1, dim=5)
    with pytest.raises(UnknownNameError, match="Did you mean 'rastrigin'"):
        get_problem("bbob", "rastrign", dim=5)
    with pytest.raises(ValueError, match="bbob defines functions 1-24"):
        get_problem("bbob", 25, dim=5)
    with pytest.raises(ValueError, match="cec2022 defines functions 1-12"):
        get_problem("cec2022", "f13", dim=10)


def test_undefined_dimensions_are_named_with_the_defined_ones():
    with pytest.raises(
        ValueError,
        match=r"cec2017 f5 is not defined in dimension 7; its dim.*"
        r"2, 10, 20, 30, 50, 100",
    ):
        get_problem("cec2017", 5, dim=7)
    with pytest.raises(ValueError, match=r"cec2022 f6 is not defined in dimension 2; .* 10, 20"):
        get_problem("cec2022", 6, dim=2)
    with pytest.raises(ValueError, match=r"bbob f1 is not defined in dimension 41; .* 2-40"):
        get_problem("bbob", 1, dim=41)
    with pytest.raises(ValueError, match="cec2017 defines instances 1-1"):
        get_problem("cec2017", 1, instance=2, dim=10)
    with pytest.raises(ValueError, match="instance=0 must be an integer >= 1"):
        get_problem("bbob", 1, instance=0, dim=5)


@pytest.mark.parametrize("budget", [0, -1, float("nan"), float("inf")])
def test_budget_must_be_positive(budget):
    with pytest.raises(ValueError, match="must be a finite number of evaluations per dimension"):
        evaluation_budget(budget, 5)


def test_budget_is_evaluations_per_dimension():
    assert evaluation_budget(1e4, 20) == 200_000
    assert evaluation_budget(2.5, 3) == 8  # ceil


@pytest.mark.parametrize(("suite", "module"), [("bbob", "ioh"), ("cec2017-opfunu", "opfunu")])
def test_missing_extra_says_which_install_fixes_it(monkeypatch, suite, module):
    from mawdo.suites import cec

    cec._opfunu_function.cache_clear()
    # None in sys.modules makes any import of the package fail, as when it is not installed
    for key in [k for k in sys.modules if k == module or k.startswith(module + ".")]:
        monkeypatch.setitem(sys.modules, key, None)
    monkeypatch.setitem(sys.modules, module, None)
    try:
        with pytest.raises(MissingExtraError, match=r'needs the package .* pip install "mawdo'):
            get_problem(suite, 1, dim=10)
        with pytest.raises(ImportError, match=r'pip install -e "\.\[bbob\]"'):
            get_problem(suite, 1, dim=10)
    finally:
        cec._opfunu_function.cache_clear()


@pytest.mark.parametrize("fid", [1, 8, 15, 21])
@pytest.mark.parametrize("dim", [5, 20])
def test_bbob_batches_leave_ioh_in_the_state_its_own_array_call_leaves(fid, dim):
    # the formula hands ioh nested lists (faster to convert); ioh's count and best-so-far, which
    # an IOH logger would read, must be those of ioh's own ndarray batch call
    f = get_problem("bbob", fid, instance=1, dim=dim)
    ref = ioh.get_problem(fid, 1, dim, ioh.ProblemClass.REAL)
    for seed in range(3):
        X = points(dim, 13, -5, 5, seed)
        np.testing.assert_array_equal(f.func(X), np.asarray(ref(X), dtype=float))
    got, want = f.func.problem.state, ref.state
    assert got.evaluations == want.evaluations == 39
    assert got.current_best.y == want.current_best.y
    np.testing.assert_array_equal(got.current_best.x, want.current_best.x)
