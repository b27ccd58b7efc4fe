"""Issue 12, defects 3, 9 and 10: inputs that once gave a silently wrong result or NumPy's
anonymous message now give an error naming the argument and the fix, or the right result."""

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import Bounds
from scipy.optimize import minimize as scipy_minimize

from mawdo import ObjectiveError, minimize
from mawdo.budget import Budget
from mawdo.minimize import make_problem
from mawdo.optimizers.registry import OPTIMIZERS, make_optimizer
from mawdo.problem import as_bounds
from mawdo.util.validate import ArgumentTypeError, check_int, check_real, check_seed

NAN, INF = float("nan"), float("inf")
B3 = [(-5, 5)] * 3


def sphere(X):
    return (X**2).sum(axis=1)


def run(fun=sphere, bounds=B3, **kw):
    return minimize(fun, bounds, **{"algorithm": "wdo", "max_iter": 3, "seed": 0, **kw})


# -- defect 3: one reading per bounds form ---------------------------------------------------


def test_lb_ub_arrays_as_a_pair_are_refused_for_d2_where_they_were_misread():
    # was: the box silently became [-5, -4] x [5, 6]
    with pytest.raises(ValueError, match=r"ambiguous.*pass lb=\.\.\., ub=\.\.\..*Bounds"):
        minimize(sphere, bounds=(np.array([-5, -4]), np.array([5, 6])), max_iter=2)
    with pytest.raises(ValueError, match="ambiguous"):
        minimize(sphere, bounds=[np.full(5, -1.0), np.full(5, 1.0)], max_iter=2)


def test_lb_ub_keywords_and_scipy_bounds_give_the_intended_box():
    def neg(X):  # minimum at the upper corner
        return -X.sum(axis=1)

    for kw in (
        {"lb": np.array([-5, -4]), "ub": np.array([5, 6])},
        {"bounds": Bounds([-5, -4], [5, 6])},
    ):
        p = make_problem(neg, **kw)
        np.testing.assert_array_equal(p.lb, [-5, -4])
        np.testing.assert_array_equal(p.ub, [5, 6])
        res = minimize(neg, **kw, algorithm="gwo", runs=3, seed=1, max_iter=60)
        assert np.all(res.x >= [-5, -4]) and np.all(res.x <= [5, 6])
        np.testing.assert_allclose(res.x, np.tile([5.0, 6.0], (3, 1)), atol=1e-3)
    lb, ub = as_bounds(Bounds(-1, 2), dim=3)  # scipy's scalar bounds broadcast with dim
    np.testing.assert_array_equal(lb, [-1, -1, -1])
    np.testing.assert_array_equal(ub, [2, 2, 2])
    lb, ub = as_bounds(lb=0, ub=[1, 2, 3])
    np.testing.assert_array_equal(lb, [0, 0, 0])


def test_pairs_are_read_as_scipy_reads_them():
    # Reference: scipy's L-BFGS-B on a linear objective ends at the corner its reading implies.
    pairs = [(-5, -4), (5, 6)]
    lb, ub = as_bounds(pairs)
    for sign, corner in ((1.0, lb), (-1.0, ub)):
        ref = scipy_minimize(lambda x, s=sign: s * x.sum(), x0=[-4.5, 5.5], bounds=pairs)
        np.testing.assert_allclose(ref.x, corner)


@pytest.mark.parametrize(
    "kw,match",
    [
        ({"bounds": np.array([[-5, -5, -5], [5, 5, 5]])}, r"shape \(2, 3\).*looks like \(lb, ub\)"),
        ({"bounds": None, "lb": [-5, -4]}, "lb= and ub= go together"),
        ({"bounds": B3, "lb": -1, "ub": 1}, "either bounds= or lb=/ub="),
        ({"bounds": None, "lb": [-5, -4], "ub": [5]}, "lb has 2 coordinates but ub has 1"),
        ({"bounds": None, "lb": -1, "ub": 1}, "scalars; give dim=D"),
        ({"bounds": Bounds([-1, -1], [1, 1]), "dim": 3}, "2 coordinates but dim=3"),
        ({"bounds": np.empty((0, 2))}, "no coordinates"),
        ({"bounds": [("-5", "5")] * 3}, "not strings; convert text with float"),
        ({"bounds": [(-5, 5j)] * 3}, "not complex"),
        ({"bounds": (-5, 5), "dim": 0}, r"dim=0 must be an integer >= 1"),
        ({"bounds": (-5, 5), "dim": True}, "dim=True.*bools are not integers"),
        ({"bounds": (-5, 5), "dim": 2.0}, r"write dim=2\)"),
    ],
)
def test_bad_bounds_name_the_fix(kw, match):
    with pytest.raises(ValueError, match=match):
        run(**kw)


def test_dim_zero_is_refused_for_benchmarks_too():
    with pytest.raises(ValueError, match="dim=0 must be an integer >= 1"):
        minimize("sphere", dim=0, max_iter=2)
    p = make_problem("sphere", lb=-1, ub=2, dim=3)  # a benchmark's box overridden by keywords
    np.testing.assert_array_equal(p.ub, [2, 2, 2])


# -- defect 9: silently wrong numerics ---------------------------------------------------------


@pytest.mark.parametrize(
    "fun,vectorized",
    [
        (lambda X: sphere(X) + 1j, True),
        (lambda X: 1j * sphere(X), True),  # was: every value read as 0
        (lambda X: sphere(X).astype(complex), True),  # zero imaginary part: still not real
        (lambda x: complex(x @ x, 1.0), False),
    ],
)
def test_complex_objective_values_are_refused(fun, vectorized):
    with pytest.raises(ObjectiveError, match="returned complex values.*abs\\(z\\)"):
        run(fun, vectorized=vectorized)


@pytest.mark.parametrize(
    "fun,vectorized",
    [
        (lambda X: [repr(v) for v in sphere(X)], True),  # numeric strings were parsed
        (lambda x: str(x @ x), False),
        (lambda X: sphere(X) > 1, True),
    ],
)
def test_non_numeric_objective_values_are_refused(fun, vectorized):
    with pytest.raises(ObjectiveError, match="not numbers"):
        run(fun, vectorized=vectorized)


@pytest.mark.parametrize("algorithm", ["wdo", "mawdo", "gwo", "woa", "mewdo"])
def test_an_objective_that_writes_into_x_cannot_move_the_result(algorithm):
    def clobber(X):
        X *= 3.0  # in place: on the caller's array this pushed best_x out of the box
        return sphere(X)

    def clean(X):
        return sphere(3.0 * X)

    kw = {"algorithm": algorithm, "runs": 3, "seed": 5, "max_iter": 30}
    a = minimize(clobber, B3, **kw)
    b = minimize(clean, B3, **kw)
    assert np.all(np.abs(a.x) <= 5)
    np.testing.assert_array_equal(a.x, b.x)  # the optimizer saw exactly what a pure f shows it
    np.testing.assert_array_equal(a.fun, b.fun)
    np.testing.assert_array_equal(a.fun, clean(a.x))


def test_scalar_objective_that_writes_into_x_cannot_move_the_result():
    def clobber(x):
        x[:] = 100.0
        return 1.0

    res = run(clobber, vectorized=False, runs=2)
    assert np.all(np.abs(res.x) <= 5)


@pytest.mark.parametrize(
    "kw,match",
    [
        ({"alpha": NAN}, r"alpha=nan must be a finite number in \[0, 1\]"),
        ({"RT": NAN}, r"RT=nan must be a finite number in \[0, inf\)"),
        ({"RT": INF}, "RT=inf must be a finite number"),
        ({"alpha": 1.5}, r"alpha=1.5 must be a finite number in \[0, 1\]"),
        ({"g": -0.1}, r"g=-0.1 must be a finite number in \[0, inf\)"),
        ({"vmax": INF}, "vmax=inf"),
        ({"weights": (0.6, NAN, 0.1)}, r"weights\[1\]=nan"),
        ({"alpha": "0.4"}, r"alpha='0.4' must be .*not a str \(write alpha=0.4, not alpha='0.4'\)"),
        ({"alpha": True}, "alpha=True.*bools are not numbers"),
        ({"alpha": 0.4 + 0j}, "complex numbers are not accepted"),
        ({"pop_size": True}, "pop_size=True must be an integer >= 2, not a bool"),
        ({"pop_size": 20.0}, r"write pop_size=20\)"),
        ({"groups": "2"}, "write groups=2, not groups='2'"),
        ({"restart": "no"}, "restart='no' must be True or False"),
        ({"target": NAN}, "target=nan must be a finite number"),
        ({"target": "0"}, "target='0' must be a finite number, not a str"),
        ({"max_time": NAN}, "max_time=nan"),
        ({"max_time": INF}, r"max_time=inf must be a finite number in \(0, inf\)"),
        ({"max_iter": 5.0}, r"max_iter=5.0 must be a positive integer.*write max_iter=5\)"),
        ({"max_evals": True}, "max_evals=True must be a positive integer"),
        ({"x0": [["1", "2", "3"]]}, "x0 must contain real numbers, not strings"),
        ({"callback": 3}, "callback=3 must be a callable"),
        ({"vectorized": "yes"}, "vectorized='yes' must be True or False"),
        ({"progress": 1}, "progress=1 must be True or False"),
    ],
)
def test_bad_numeric_options_name_the_argument(kw, match):
    with pytest.raises(ValueError, match=match):
        run(**{"algorithm": "mawdo", **kw})


def _numeric_fields(name):
    params = make_optimizer(name).params
    for f in dataclasses.fields(params):
        value = getattr(params, f.name)
        if isinstance(value, int | float) and not isinstance(value, bool):
            yield f.name, value


ALL_NUMERIC = [(a, f) for a in OPTIMIZERS for f, _ in _numeric_fields(a)]


@pytest.mark.parametrize("algorithm,field", ALL_NUMERIC)
@pytest.mark.parametrize("bad", [NAN, INF, -INF, "1", True])
def test_every_numeric_option_of_every_algorithm_is_checked(algorithm, field, bad):
    with pytest.raises(ValueError, match=f"^{field}="):
        make_optimizer(algorithm, **{field: bad})


def test_every_numeric_option_declares_its_constraint_on_its_field():
    # a numeric field declared without option() would only get the type-derived check
    undeclared = []
    for name in OPTIMIZERS:
        params = make_optimizer(name).params
        fields = {f.name: f for f in dataclasses.fields(params)}
        undeclared += [
            (name, f) for a, f in ALL_NUMERIC if a == name and "option" not in fields[f].metadata
        ]
    assert undeclared == []
    assert len(ALL_NUMERIC) > 30


def test_an_optimizer_instance_is_checked_too():
    from mawdo.optimizers.wdo import Wind

    with pytest.raises(ValueError, match=r"alpha=nan must be a finite number in \[0, 1\]"):
        Wind(alpha=NAN)  # built directly, bypassing the registry: checked all the same
    with pytest.raises(ValueError, match="RT=nan"):
        run(algorithm=Wind(), RT=NAN)


# -- defect 10: messages that name the argument ------------------------------------------------


@pytest.mark.parametrize(
    "kw,match",
    [
        ({"runs": True}, "runs=True must be an integer >= 1, not a bool; bools are not integers"),
        ({"runs": 2.0}, r"write runs=2\)"),
        ({"first_run": True}, "first_run=True"),
        ({"seed": "abc"}, "seed='abc' is not a valid seed: pass seed=<integer >= 0>"),
        ({"seed": 1.5}, r"seed=1.5 is not a valid seed: pass seed=<integer >= 0> \(e.g. seed=1\)"),
        ({"seed": True}, "seed=True is not a valid seed; bools are not integers here"),
        ({"seed": -1}, "seed=-1 is negative"),
        ({"seed": [1, 2.5]}, r"seed=\[1, 2.5\] is not a valid seed"),
        ({"seed": np.random.default_rng(0)}, "Generator, which cannot be split"),
        ({"shift_seed": 0.5}, "shift_seed=0.5"),
    ],
)
def test_bad_runs_and_seeds_name_the_argument(kw, match):
    with pytest.raises(ValueError, match=match) as info:
        run(**kw)
    assert not isinstance(info.value, OverflowError)


def test_type_errors_are_both_type_and_value_errors():
    with pytest.raises(TypeError):
        run(seed="abc")
    assert issubclass(ArgumentTypeError, ValueError) and issubclass(ArgumentTypeError, TypeError)


def test_valid_seed_forms_still_work_and_agree():
    a = run(seed=3, runs=2)
    b = run(seed=np.int64(3), runs=2)
    c = run(seed=np.random.SeedSequence(3), runs=2)
    np.testing.assert_array_equal(a.fun, b.fun)
    np.testing.assert_array_equal(a.fun, c.fun)
    d = run(seed=[3, 4], runs=2)
    e = run(seed=np.random.SeedSequence([3, 4]), runs=2)
    np.testing.assert_array_equal(d.fun, e.fun)
    assert check_seed(None) is None


# -- the checks themselves ----------------------------------------------------------------------


def test_check_real_and_check_int_edges():
    assert check_real("x", np.float32(0.5), 0, 1) == 0.5
    assert check_real("x", 0, 0, 1) == 0.0
    with pytest.raises(ValueError, match=r"x=0 must be a finite number in \(0, 1\]"):
        check_real("x", 0, 0, 1, low_open=True)
    with pytest.raises(ValueError, match=r"in \[0, 1\)"):
        check_real("x", 1, 0, 1, high_open=True)
    assert check_int("n", np.int32(4), 1, 4) == 4
    with pytest.raises(ValueError, match=r"n=5 must be an integer in \[1, 4\]"):
        check_int("n", 5, 1, 4)
    with pytest.raises(ArgumentTypeError, match="bools are not integers"):
        check_int("n", np.bool_(True), 0)


# -- issue 11: the budget as its own object -----------------------------------------------------


def test_budget_defaults_and_horizon():
    assert Budget().max_iter == 500 and Budget().horizon(50) == 500
    b = Budget(max_evals=1001)
    assert b.max_iter is None and b.horizon(50) == math.ceil(1001 / 50) == 21
    assert Budget(max_iter=7, max_evals=10).horizon(3) == 7


def test_exact_evaluation_budget_and_target_status():
    res = run(algorithm="gwo", max_iter=None, max_evals=97, pop_size=10, runs=2)
    assert np.all(res.nfev == 97) and np.all(res.status == 1) and np.all(res.nit == 10)
    # target: each run freezes when reached; all runs reaching it gives the target message
    res = run(algorithm="gwo", max_iter=200, target=1e3, pop_size=10, runs=2)
    assert np.all(res.status == 2) and np.all(res.nit == 1)
    assert res.message == "target value reached" and np.all(res.fun <= 1e3)
    assert res.history.shape == (2, 1)


def test_an_option_shared_by_name_states_its_own_algorithms_interval():
    # sigma0 means a fraction of the box side for cmaes ((0, 1]) but a step for wind ((0, inf)):
    # each field declares its own range, so the message gives the interval that applies
    with pytest.raises(ValueError, match=r"^sigma0=0 must be a finite number in \(0, 1\]$"):
        make_optimizer("cmaes", sigma0=0)
    with pytest.raises(ValueError, match=r"^sigma0=2 must be a finite number in \(0, 1\]$"):
        make_optimizer("cmaes", sigma0=2)
    assert make_optimizer("wdo", sigma0=2).params.sigma0 == 2
    with pytest.raises(ValueError, match=r"^q_min=0.5 must be a finite number in \[0, 0.333"):
        make_optimizer("mewdo", q_min=0.5)
