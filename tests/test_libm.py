"""The C library's elementwise functions (mawdo.util.libm): the same bits as Python's ``math``
(the C library's scalar routines) on every element, whatever the shape; and mawdo's own
optimizers and benchmark functions do not depend on NumPy's CPU-chosen loops for them."""

from __future__ import annotations

import ast
import inspect
import math
from pathlib import Path

import numpy as np
import pytest

import mawdo
from mawdo import FUNCTIONS, OPTIMIZERS, minimize
from mawdo.util import libm

SRC = Path(mawdo.__file__).parent
UNARY = {
    "tan": (math.tan, (-1.6, 1.6)),
    "arctan": (math.atan, (-300.0, 300.0)),
    "exp": (math.exp, (-700.0, 700.0)),
    "expm1": (math.expm1, (-3.0, 3.0)),
    "log": (math.log, (1e-300, 1e6)),
    "sin": (math.sin, (-1e4, 1e4)),
    "cos": (math.cos, (-1e4, 1e4)),
}
NUMPY_NAMES = ("tan", "arctan", "exp", "expm1", "log", "sin", "cos", "power")


@pytest.mark.parametrize("name", list(UNARY))
def test_each_element_is_the_c_librarys_scalar_value(name):
    scalar, (lo, hi) = UNARY[name]
    x = np.random.default_rng(3).uniform(lo, hi, 20_000)
    got = getattr(libm, name)(x)
    assert got.dtype == np.float64 and got.shape == x.shape
    assert [float(v) for v in got] == [scalar(v) for v in x.tolist()]


def test_edges_follow_ieee_as_numpy_does():
    assert libm.log(np.array([0.0, -1.0, np.inf])).tolist()[0] == -math.inf
    assert math.isnan(libm.log(-1.0)) and libm.exp(1000.0) == math.inf
    assert libm.exp(-1000.0) == 0.0 and math.isnan(libm.tan(np.inf))
    assert math.isnan(libm.power(-2.0, 0.5)) and libm.power(0.0, -1.0) == math.inf


def test_shapes_scalars_and_strided_inputs_are_kept():
    X = np.arange(24.0).reshape(4, 6)[:, ::2] / 10  # not contiguous
    assert libm.sin(X).shape == (4, 3)
    assert libm.sin(X).tolist() == [[math.sin(v) for v in row] for row in X.tolist()]
    assert np.ndim(libm.cos(0.5)) == 0 and float(libm.cos(0.5)) == math.cos(0.5)
    assert libm.exp(np.float64(2.0)) == math.exp(2.0)
    assert libm.exp(np.empty((0, 3))).shape == (0, 3)


def test_power_broadcasts_like_numpy_and_is_the_c_librarys_pow():
    rng = np.random.default_rng(5)
    a, b = rng.random((3, 1, 4)), rng.uniform(-3, 30, (5, 1))
    got = libm.power(a, b)
    assert got.shape == np.broadcast_shapes(a.shape, b.shape)
    pairs = zip(*(v.ravel().tolist() for v in np.broadcast_arrays(a, b)), strict=True)
    ref = [math.pow(x, y) for x, y in pairs]
    assert got.ravel().tolist() == ref
    assert libm.power(0.3, 25) == math.pow(0.3, 25)


def _library_backed(cls) -> bool:
    """Whether an optimizer's module computes with another library (cmaes, SciPy), whose
    NumPy calls mawdo does not choose."""
    tree = ast.parse(inspect.getsource(inspect.getmodule(cls)))
    roots = {
        (n.module or "").split(".")[0] if isinstance(n, ast.ImportFrom) else a.name.split(".")[0]
        for n in ast.walk(tree)
        if isinstance(n, ast.Import | ast.ImportFrom)
        for a in n.names
    }
    return bool(roots & {"cmaes", "scipy"})


OWN = [name for name, spec in OPTIMIZERS.items() if not _library_backed(spec.cls)]


@pytest.fixture
def off_by_one_ulp(monkeypatch):
    """Call it to replace NumPy's functions by ones one ulp above: what another processor's
    SIMD loop may return. Code that uses them then gives other numbers; code that does not,
    the same."""

    def perturb():
        for name in NUMPY_NAMES:
            f = getattr(np, name)
            monkeypatch.setattr(np, name, lambda *a, _f=f, **k: np.nextafter(_f(*a, **k), np.inf))

    return perturb


def _run(algo):
    # a multimodal function: a changed last bit moves the run's trajectory
    res = minimize("rastrigin", dim=6, algorithm=algo, runs=2, seed=11, max_evals=3000)
    return res.fun.tolist(), res.x.tolist()


def test_the_library_backed_references_are_told_apart():
    assert {"cmaes", "scipy_de"} <= set(OPTIMIZERS) - set(OWN)
    assert {"lshade", "jso", "nlshade_rsp", "woa", "wdo_plus", "mawdo"} <= set(OWN)


@pytest.mark.parametrize("algo", OWN)
def test_an_optimizer_gives_the_same_run_whatever_numpys_math_returns(algo, off_by_one_ulp):
    before = _run(algo)
    off_by_one_ulp()
    assert _run(algo) == before


@pytest.mark.parametrize("name", list(FUNCTIONS))
def test_a_benchmark_function_gives_the_same_values_whatever_numpys_math_returns(
    name, off_by_one_ulp
):
    f = FUNCTIONS[name]
    f = f if f.dim else f.with_dim(5)
    X = np.random.default_rng(2).uniform(f.lb, f.ub, (50, f.dim))
    before = f.func(X)  # the formula (a noisy function adds its noise outside it)
    off_by_one_ulp()
    assert np.array_equal(f.func(X), before, equal_nan=True)


def test_the_perturbation_reaches_code_that_calls_numpy(off_by_one_ulp):
    # the two tests above would pass if the patch did nothing: it does not
    x = np.linspace(0.1, 1.0, 7)
    before = np.tan(x)
    off_by_one_ulp()
    assert not np.array_equal(np.tan(x), before)
