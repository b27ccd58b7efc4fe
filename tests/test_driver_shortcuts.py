"""The driver's per-call shortcuts (issues 10 and 15: a receding-horizon planner calls
``minimize`` ~20 times a second) give exactly what the plain code gave.

Each shortcut is compared with a literal port of the code it replaced, with a fresh build that
takes no shortcut, or with values worked out by hand.
"""

import dataclasses
import math

import numpy as np
import pytest

from mawdo import OPTIMIZERS, make_optimizer
from mawdo.budget import Budget, RunLog
from mawdo.optimizers import registry
from mawdo.optimizers.base import Params
from mawdo.problem import Evaluator, Problem
from mawdo.streams import RunStreams
from mawdo.util.validate import ArgumentTypeError

# -- make_optimizer's cache of validated Params ------------------------------------------------

OPTION_SETS = [{}, {"pop_size": 240}, {"pop_size": 30, "low_dim": 10_000}]


@pytest.mark.parametrize("name", sorted(OPTIMIZERS))
def test_cached_params_equal_a_fresh_build(name):
    for options in OPTION_SETS:
        if (
            options
            and "low_dim" in options
            and "low_dim"
            not in {f.name for f in dataclasses.fields(OPTIMIZERS[name].cls.params_class)}
        ):
            continue
        registry._PARAMS.clear()
        fresh = make_optimizer(name, **options)
        cached = make_optimizer(name, **options)  # from the cache now
        assert registry._params_key(name, options) in registry._PARAMS
        assert cached.params == fresh.params
        assert type(cached) is type(fresh) and cached.name == fresh.name
        assert cached.metadata == fresh.metadata


def test_cache_tells_types_and_signs_apart():
    registry._PARAMS.clear()
    make_optimizer("wdo", alpha=0)
    with pytest.raises(ArgumentTypeError):  # a bool is refused even after 0 was accepted
        make_optimizer("wdo", alpha=False)
    make_optimizer("wdo", c=0.0)
    assert math.copysign(1.0, make_optimizer("wdo", c=-0.0).params.c) == -1.0
    make_optimizer("wdo", weights=(0.6, 0.3, 0.1))
    with pytest.raises(ArgumentTypeError):
        make_optimizer("wdo", weights=(0.6, 0.3, "0.1"))


def test_refused_options_are_refused_every_time():
    registry._PARAMS.clear()
    for _ in range(2):
        with pytest.raises(ValueError, match="pop_size"):
            make_optimizer("wdo", pop_size=1)
        with pytest.raises(ValueError, match="no option"):
            make_optimizer("wdo", pop_sise=20)
    assert not registry._PARAMS


# -- Params.as_dict ----------------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(OPTIMIZERS))
def test_as_dict_equals_dataclasses_asdict(name):
    params = make_optimizer(name).params
    assert params.as_dict() == dataclasses.asdict(params)


@dataclasses.dataclass(frozen=True)
class ListParams(Params):
    steps: list = dataclasses.field(default_factory=lambda: [1.0, 2.0])
    inner: object = ((1, 2), 3)  # no declared kind: nested tuples are not options


def test_as_dict_copies_mutable_and_nested_values():
    params = ListParams()
    out = params.as_dict()
    assert out == dataclasses.asdict(params)
    out["steps"].append(3.0)
    assert params.steps == [1.0, 2.0]  # the result does not alias the frozen params


@pytest.mark.parametrize("name", ["wdo", "mawdo", "gwo"])
def test_as_dict_kept_dict_is_copied_and_invisible(name):
    params = make_optimizer(name, pop_size=30).params
    twin = make_optimizer(name, pop_size=30).params
    first = params.as_dict()
    first["pop_size"] = -1  # a caller may change its dict: the next one is unchanged
    second = params.as_dict()
    assert second == dataclasses.asdict(params) and second is not first
    assert second["pop_size"] == 30
    # the kept dict is not a field: equality, hashing, repr and replace ignore it
    assert params == twin and hash(params) == hash(twin) and repr(params) == repr(twin)
    assert dataclasses.replace(params, pop_size=40).as_dict()["pop_size"] == 40


# -- Evaluator ---------------------------------------------------------------------------------


class Reused:
    """An objective that returns (and later overwrites) one array of its own."""

    def __init__(self, values):
        self.out = np.array(values, dtype=float)

    def __call__(self, X):
        return self.out


def evaluator(fun, runs, noise=False):
    streams = RunStreams([np.random.default_rng(k) for k in range(runs)])
    problem = Problem(fun=fun, lb=np.zeros(2), ub=np.ones(2), noise=noise)
    return Evaluator(problem, streams, "test")


def test_evaluator_maps_non_finite_to_inf_in_its_own_array():
    fun = Reused([1.0, np.nan, -np.inf, 2.0, np.inf, -3.0])
    ev = evaluator(fun, 2)
    F = ev(np.zeros((2, 3, 2)), 1, np.array([True, False]))
    np.testing.assert_array_equal(F, [[1.0, np.inf, np.inf], [2.0, np.inf, -3.0]])
    assert np.isnan(fun.out[1]) and fun.out[2] == -np.inf  # the objective's array untouched
    fun.out[:] = 7.0  # the objective reuses its array: F must not follow
    assert F[0, 0] == 1.0
    np.testing.assert_array_equal(ev.nfev, [3, 0])  # only the active run counts


def test_evaluator_limit_and_noise():
    ev = evaluator(Reused([1.0, 2.0, 3.0, 4.0]), 2, noise=True)
    F = ev(np.zeros((2, 3, 2)), 1, np.array([True, True]), limit=2)
    draws = [np.random.default_rng(k).random(2) for k in range(2)]  # the runs' noise streams
    expect = np.array([[1.0 + draws[0][0], 2.0 + draws[0][1], np.inf],
                       [3.0 + draws[1][0], 4.0 + draws[1][1], np.inf]])  # fmt: skip
    np.testing.assert_array_equal(F, expect)
    np.testing.assert_array_equal(ev.nfev, [2, 2])


def test_evaluator_still_checks_output_that_is_not_float64():
    ev = evaluator(lambda X: np.array([1, 2, 3], dtype=np.int32), 1)
    F = ev(np.zeros((1, 3, 2)), 1, np.array([True]))
    assert F.dtype == np.float64
    np.testing.assert_array_equal(F, [[1.0, 2.0, 3.0]])
    with pytest.raises(Exception, match="complex"):
        evaluator(lambda X: np.ones(3, complex), 1)(np.zeros((1, 3, 2)), 1, np.array([True]))
    with pytest.raises(Exception, match=r"expected \(3,\)"):
        evaluator(lambda X: np.ones(4), 1)(np.zeros((1, 3, 2)), 1, np.array([True]))


# -- RunLog.record -----------------------------------------------------------------------------


def reference_record(log, it, X, F, nfev):
    """Literal port of ``RunLog.record`` before its shortcut (mawdo 0.2.0)."""
    R = F.shape[0]
    j = np.argmin(F, axis=1)
    fj = F[np.arange(R), j]
    better = log.active & (fj < log.best_f)
    log.best_f = np.where(better, fj, log.best_f)
    log.best_x[better] = X[better, j[better]]
    log.nit[log.active] = it
    log.hist.append(log.best_f.copy())
    log.hist_nfev.append(nfev.copy())


def test_record_equals_the_code_it_replaced():
    rng = np.random.default_rng(4)
    R, n, D = 5, 7, 3
    fast = RunLog(Budget(50), R, np.zeros(D))
    ref = RunLog(Budget(50), R, np.zeros(D))
    for it in range(1, 40):
        X = rng.normal(size=(R, n, D))
        F = rng.normal(size=(R, n)) + 0.2 * it  # later iterations improve less and less
        F[rng.random((R, n)) < 0.1] = np.inf
        if it % 9 == 0:
            F[:] = np.inf
        nfev = np.full(R, it * n)
        if it == 20:
            fast.active[1] = ref.active[1] = False
        fast.record(it, X, F, nfev)
        reference_record(ref, it, X, F, nfev)
        np.testing.assert_array_equal(fast.best_f, ref.best_f)
        np.testing.assert_array_equal(fast.best_x, ref.best_x)
        np.testing.assert_array_equal(fast.nit, ref.nit)
    for a, b in zip(fast.history(), ref.history(), strict=True):
        np.testing.assert_array_equal(a, b)
