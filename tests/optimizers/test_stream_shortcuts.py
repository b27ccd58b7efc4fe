"""RunStreams.uniform scales its draw in place (issue 15); it must give the numbers of the
formula it replaced, ``low + (high - low) * U``, bit for bit."""

import numpy as np
import pytest

from mawdo.streams import RunStreams


def streams(seed, runs=3):
    return RunStreams.from_seed_sequences(np.random.SeedSequence(seed).spawn(runs))


CASES = [
    (-0.3, 0.3, (5, 4)),
    (np.linspace(-100.0, -1.0, 4), np.linspace(1.0, 600.0, 4), (6, 4)),
    (np.array([0.15, 0.15, 0.9, 0.1]), np.array([0.45, 0.45, 1.5, 0.5]), (8, 4)),
    (-np.ones(7), np.ones(7), (50, 7)),
    (-5, 5, (3, 2)),  # integers
    (np.float32(-1.5), np.float32(2.25), (4,)),
    (np.zeros((1, 3, 1)), np.ones((1, 3, 1)), (3,)),  # bounds broadcast past the draw
]


@pytest.mark.parametrize(("low", "high", "shape"), CASES)
def test_uniform_equals_the_formula_it_replaced(low, high, shape):
    got = streams(7).uniform(low, high, shape)
    want = low + (np.asarray(high) - low) * streams(7).random(shape)
    assert got.dtype == want.dtype and got.shape == want.shape
    np.testing.assert_array_equal(got, want)
    assert np.unique(got).size == got.size  # distinct draws, not a constant


@pytest.mark.parametrize(
    "shapes", [((4, 5), (5, 3)), ((4, 5), (5, 1)), ((2,), (), (3, 2, 2)), ((7, 6),)]
)
def test_random_parts_equal_successive_random_calls(shapes):
    mine = streams(11)
    got = mine.random_parts(*shapes)
    ref = streams(11)
    want = [ref.random(s) for s in shapes]
    assert len(got) == len(want)
    for g, w in zip(got, want, strict=True):
        assert g.shape == w.shape
        np.testing.assert_array_equal(g, w)
    # each generator is left where the separate calls leave it
    np.testing.assert_array_equal(mine.random(2), ref.random(2))
    assert np.unique(np.concatenate([g.ravel() for g in got])).size == sum(g.size for g in got)
