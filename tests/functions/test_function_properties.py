"""Property tests: every value in the box is finite and at least f_star (the true minimum)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from mawdo.functions import ALTERNATES, FUNCTIONS, PAPER_SUITE, shifted

SLACK = 1e-9
# kowalik has poles inside its box (denominator b_i^2 + b_i x3 + x4 = 0): inf/nan allowed there.
FINITE = [*PAPER_SUITE, *(n for n in ALTERNATES if n != "kowalik")]


def _box_points(f, data, max_rows: int = 6) -> np.ndarray:
    n = data.draw(st.integers(1, max_rows), label="n")
    lo, hi = float(f.lb[0]), float(f.ub[0])
    assert np.all(f.lb == lo) and np.all(f.ub == hi)  # the registered boxes are uniform
    elements = st.floats(lo, hi, allow_nan=False, allow_infinity=False)
    return data.draw(arrays(np.float64, (n, f.dim), elements=elements), label="X")


@pytest.mark.parametrize("name", FINITE)
@settings(max_examples=60, deadline=None)
@given(data=st.data())
def test_values_finite_and_above_minimum(name, data):
    f = FUNCTIONS[name]
    X = _box_points(f, data)
    values = f.func(X)  # noiseless formula (F6's noise only adds to it)
    assert values.shape == (X.shape[0],)
    assert np.all(np.isfinite(values))
    assert np.all(values >= f.f_star - SLACK), (values.min(), f.f_star)


@pytest.mark.parametrize("name", PAPER_SUITE)
@settings(max_examples=30, deadline=None)
@given(data=st.data(), seed=st.integers(0, 2**32 - 1))
def test_shifted_values_above_minimum(name, seed, data):
    g = shifted(FUNCTIONS[name], seed)
    X = _box_points(g, data)
    values = g.func(X)
    assert np.all(np.isfinite(values)) and np.all(values >= g.f_star - SLACK)


@settings(max_examples=60, deadline=None)
@given(data=st.data())
def test_kowalik_never_below_its_minimum(data):
    f = FUNCTIONS["kowalik"]
    values = f.func(_box_points(f, data))
    finite = values[~np.isnan(values)]
    assert np.all(finite >= f.f_star - SLACK)


@settings(max_examples=40, deadline=None)
@given(data=st.data())
def test_noisy_quartic_within_noise_band(data):
    f = FUNCTIONS["quartic"]
    X = _box_points(f, data)
    seed = data.draw(st.integers(0, 2**32 - 1), label="seed")
    noise = f(X, rng=np.random.default_rng(seed)) - f.func(X)
    assert np.all(noise >= 0.0) and np.all(noise < 1.0 + 1e-12)
