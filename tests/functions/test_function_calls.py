"""Calling conventions: batches, single points, shape errors, purity, variants, pickling."""

from __future__ import annotations

import dataclasses
import pickle

import numpy as np
import pytest

from mawdo.functions import FUNCTIONS, BenchmarkFunction, get_function, shifted

ALL = list(FUNCTIONS)


def _points(f: BenchmarkFunction, n: int, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).uniform(f.lb, f.ub, (n, f.dim))


@pytest.mark.parametrize("name", ALL)
def test_batch_equals_row_by_row(name):
    f = FUNCTIONS[name]
    X = _points(f, 9)
    batch = f.func(X)
    assert batch.shape == (9,) and batch.dtype == np.float64
    rows = np.array([f.func(X[i : i + 1])[0] for i in range(9)])
    singles = np.array([f.func(x[None, :])[0] for x in X])
    np.testing.assert_array_equal(batch, rows)
    np.testing.assert_array_equal(batch, singles)


@pytest.mark.parametrize("name", ALL)
def test_public_call_is_layout_and_batch_independent(name):
    """Large batches, Fortran order and strided views give the row-by-row values bit for bit."""
    f = FUNCTIONS[name]
    rng = np.random.default_rng(0) if f.noise else None
    g = f if not f.noise else FUNCTIONS["quartic_noiseless"]
    X = _points(f, 3000, seed=2)
    batch = g(X, rng=rng)
    rows = np.array([g(X[i]) for i in range(0, 3000, 101)])
    np.testing.assert_array_equal(batch[::101], rows)
    np.testing.assert_array_equal(g(np.asfortranarray(X)), batch)
    np.testing.assert_array_equal(g(X[::101]), rows)
    wide = np.concatenate([X, X], axis=1)[:, : f.dim]  # non-contiguous rows
    np.testing.assert_array_equal(g(wide), batch)


@pytest.mark.parametrize("name", ALL)
def test_public_call_shapes(name):
    f = FUNCTIONS[name]
    X = _points(f, 5, seed=1)
    rng = np.random.default_rng(0) if f.noise else None
    out = f(X, rng=rng)
    assert isinstance(out, np.ndarray) and out.shape == (5,)
    one = f(X[2], rng=np.random.default_rng(0) if f.noise else None)
    assert np.ndim(one) == 0 and isinstance(one, float)
    assert f(X.tolist(), rng=rng).shape == (5,)  # plain nested lists are accepted
    assert f(np.empty((0, f.dim)), rng=rng).shape == (0,)
    if not f.noise:
        assert one == out[2]


@pytest.mark.parametrize("name", ALL)
def test_wrong_last_axis_names_shapes(name):
    f = FUNCTIONS[name]
    rng = np.random.default_rng(0)
    bad = np.zeros((3, f.dim + 1))
    with pytest.raises(ValueError, match=rf"\(n, {f.dim}\).*\(3, {f.dim + 1}\)"):
        f(bad, rng=rng)
    with pytest.raises(ValueError, match=rf"got an array of shape \({f.dim + 1},\)"):
        f(np.zeros(f.dim + 1), rng=rng)
    with pytest.raises(ValueError, match=r"shape \(2, 2, "):
        f(np.zeros((2, 2, f.dim)), rng=rng)
    with pytest.raises(ValueError, match=r"shape \(\)"):
        f(1.0, rng=rng)


@pytest.mark.parametrize("name", ALL)
def test_formula_is_pure(name):
    f = FUNCTIONS[name]
    X = _points(f, 4, seed=3)
    before = X.copy()
    first = f.func(X)
    np.testing.assert_array_equal(X, before)  # input untouched
    np.testing.assert_array_equal(f.func(X), first)  # deterministic


@pytest.mark.parametrize("name", ALL)
def test_every_variant_minimize_builds_is_pure(name):
    # minimize() hands these functions the optimizer's own candidates (Problem.pure, no copy):
    # shifted variants, other dimensions and the standard bounds must not write either
    f = FUNCTIONS[name]
    dims = [f.dim] + ([2, 7] if f.scalable and f.min_dim <= 2 else [])
    for dim in dims:
        for kw in ({}, {"shifted": True, "shift_seed": 3}, {"preset": "standard"}):
            g = get_function(name, dim=dim, **kw)
            X = _points(g, 5, seed=dim)
            before = X.copy()
            g.func(X)
            np.testing.assert_array_equal(X, before)


def test_a_pure_problem_is_evaluated_without_a_copy_and_gives_the_same_values():
    from mawdo.problem import Evaluator, Problem
    from mawdo.streams import RunStreams

    seen = []

    def spy(X):
        seen.append(X)
        return (X**2).sum(axis=1)

    X = np.random.default_rng(0).uniform(-1, 1, (2, 4, 3))
    out = {}
    for pure in (False, True):
        seen.clear()
        prob = Problem(fun=spy, lb=-np.ones(3), ub=np.ones(3), pure=pure)
        ev = Evaluator(
            prob, RunStreams.from_seed_sequences(np.random.SeedSequence(0).spawn(2)), "t"
        )
        out[pure] = ev(X, 1, np.ones(2, bool))
        assert np.shares_memory(seen[0], X) == pure  # a user's objective gets a copy
    np.testing.assert_array_equal(out[True], out[False])


def test_records_are_immutable():
    f = FUNCTIONS["sphere"]
    with pytest.raises(dataclasses.FrozenInstanceError):
        f.dim = 3  # type: ignore[misc]
    for arr in (f.lb, f.ub, f.x_star):
        with pytest.raises(ValueError, match="read-only"):
            arr[0] = 1.0
    lb, ub = f.bounds
    assert lb is f.lb and ub is f.ub


def test_constructor_copies_and_validates():
    lb = np.array([-1.0, -1.0])
    f = BenchmarkFunction("t", None, 2, lb, 1.0, 0.0, np.zeros(2), FUNCTIONS["sphere"].func)
    lb[0] = -5.0
    assert f.lb[0] == -1.0  # no aliasing of the caller's array
    kwargs = dict(name="t", paper_id=None, dim=2, lb=-1, ub=1, f_star=0.0, x_star=np.zeros(2),
                  func=FUNCTIONS["sphere"].func)  # fmt: skip
    with pytest.raises(ValueError, match="lb < ub"):
        BenchmarkFunction(**{**kwargs, "lb": 1})
    with pytest.raises(ValueError, match="outside the box"):
        BenchmarkFunction(**{**kwargs, "x_star": np.full(2, 3.0)})
    with pytest.raises(ValueError, match=r"shape \(2,\)"):
        BenchmarkFunction(**{**kwargs, "lb": [-1, -1, -1]})
    with pytest.raises(ValueError, match="paper_id"):
        BenchmarkFunction(**{**kwargs, "paper_id": "F17"})
    with pytest.raises(ValueError, match="dim must be >= 1"):
        BenchmarkFunction(**{**kwargs, "dim": 0})
    with pytest.raises(ValueError, match="optimum rule"):
        BenchmarkFunction(**{**kwargs, "scalable": True})
    with pytest.raises(ValueError, match="finite"):
        BenchmarkFunction(**{**kwargs, "f_star": np.nan})


@pytest.mark.parametrize("name", ALL)
def test_records_pickle(name):
    f = FUNCTIONS[name]
    g = pickle.loads(pickle.dumps(shifted(f, 4)))
    X = _points(f, 3, seed=5)
    assert g.name == f"{name}@shifted"
    np.testing.assert_array_equal(g.func(X), shifted(f, 4).func(X))
    h = pickle.loads(pickle.dumps(f))
    np.testing.assert_array_equal(h.func(X), f.func(X))


def test_with_dim():
    f = FUNCTIONS["rastrigin"].with_dim(7)
    assert f.dim == 7 and f.lb.shape == f.ub.shape == f.x_star.shape == (7,)
    assert f.name == "rastrigin" and f.paper_id == "F7"
    assert f(np.zeros(7)) == 0.0
    assert FUNCTIONS["rastrigin"].with_dim(30) is FUNCTIONS["rastrigin"]
    with pytest.raises(ValueError, match="fixed dimension 4"):
        FUNCTIONS["shekel_5"].with_dim(5)
    with pytest.raises(ValueError, match="dim >= 2"):
        FUNCTIONS["rosenbrock"].with_dim(1)
    with pytest.raises(TypeError, match="int"):
        FUNCTIONS["sphere"].with_dim(2.0)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="same bounds"):
        FUNCTIONS["sphere"].with_dim(2).with_bounds([-1, -2], [1, 2]).with_dim(3)


def test_with_bounds():
    f = FUNCTIONS["sphere"].with_bounds(-2, [3.0] * 30)
    assert np.all(f.lb == -2) and np.all(f.ub == 3) and f.f_star == 0.0
    assert np.all(FUNCTIONS["sphere"].lb == -100)  # original untouched
    with pytest.raises(ValueError, match="lb < ub"):
        FUNCTIONS["sphere"].with_bounds(1, -1)
    with pytest.raises(ValueError, match="outside the box"):
        FUNCTIONS["rosenbrock"].with_bounds(2, 3)  # optimum (1, ..., 1) left out
    with pytest.raises(ValueError, match="outside the box"):
        FUNCTIONS["goldstein_price"].with_bounds(0, 2)
    lit = FUNCTIONS["f8_paper_literal"].with_bounds(0, 100)
    assert lit.f_star == -36.25 and lit(lit.x_star) == lit.f_star  # staircase re-placed


def test_get_function_dim_errors():
    assert get_function("sphere", dim=3).dim == 3
    assert get_function("F12", dim=2) is FUNCTIONS["six_hump_camel"]
    with pytest.raises(ValueError, match="six_hump_camel has a fixed dimension 2"):
        get_function("F12", dim=3)
    with pytest.raises(ValueError, match="dim >= 1"):
        get_function("sphere", dim=0)
    with pytest.raises(ValueError, match="schaffer_f7 needs dim >= 2"):
        get_function("schaffer_f7", dim=1)
    with pytest.raises(ValueError, match="f8_paper_literal needs dim >= 2"):
        get_function("f8_paper_literal", dim=1)
    with pytest.raises(TypeError, match="dim must be an int"):
        get_function("sphere", dim=2.5)  # type: ignore[arg-type]


def test_repr_is_short_and_informative():
    text = repr(FUNCTIONS["F6"])
    assert "quartic (F6)" in text and "D=30" in text and "noise" in text and len(text) < 120
