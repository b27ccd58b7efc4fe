"""Blocks of runs (mawdo.util.blocks): a batch split into blocks gives the numbers of one batch."""

import dataclasses

import numpy as np
import pytest

from mawdo import minimize
from mawdo.util.blocks import BLOCK_BYTES, MIN_BLOCK, block_sizes, join_results


def test_block_sizes_are_even_and_cover_the_batch():
    # 1000 runs of a (50, 30) state: 1 MiB / (8 * 50 * 30 B) = 87 runs per block at most,
    # so 12 blocks: 1000 = 4 * 84 + 8 * 83
    assert BLOCK_BYTES == 1 << 20
    assert block_sizes(1000, None, 50, 30) == [84] * 4 + [83] * 8
    assert block_sizes(10, 4, 50, 30) == [4, 3, 3]
    assert block_sizes(3, 4, 50, 30) == [3]
    # a huge state still keeps MIN_BLOCK runs per block
    assert MIN_BLOCK == 16
    assert block_sizes(40, None, 1000, 1000) == [14, 13, 13]
    for runs in (1, 17, 100, 301):
        sizes = block_sizes(runs, None, 20, 2000)
        assert sum(sizes) == runs and max(sizes) - min(sizes) <= 1


def _fields(res):
    d = dataclasses.asdict(res)
    d.pop("time")
    return d


def _assert_same(a, b):
    fa, fb = _fields(a), _fields(b)
    assert fa.keys() == fb.keys()
    for k, v in fa.items():
        if isinstance(v, np.ndarray):
            np.testing.assert_array_equal(v, fb[k], err_msg=k)
        else:
            assert v == fb[k], k


BUDGETS = [
    {"max_iter": 15},
    {"max_evals": 333},
    # sphere in 2-D reaches 1e-2 within a few iterations in some runs only: blocks stop at
    # different iterations and one batch's frozen runs repeat their last value
    {"max_iter": 40, "target": 1e-2},
    {"max_iter": 400, "target": 1e-1},  # every run reaches it: the target's message
]


@pytest.mark.parametrize("algo", ["wdo", "mawdo", "gwo", "woa", "random", "cmaes"])
@pytest.mark.parametrize("budget", BUDGETS, ids=lambda b: "-".join(b))
def test_blocks_give_the_numbers_of_one_batch(algo, budget):
    kw = dict(algorithm=algo, runs=7, seed=3, dim=2, pop_size=10, **budget)
    whole = minimize("sphere", runs_per_block=7, **kw)
    blocks = minimize("sphere", runs_per_block=3, **kw)
    _assert_same(whole, blocks)


def test_blocks_split_history_lengths_like_one_batch():
    # the case that needs padding: one block stops early on its target
    kw = dict(algorithm="gwo", runs=6, seed=0, dim=2, pop_size=8, max_iter=60, target=1e-6)
    parts = [minimize("sphere", runs=2, first_run=f, **{k: v for k, v in kw.items() if k != "runs"})
             for f in (0, 2, 4)]  # fmt: skip
    lengths = {p.history.shape[1] for p in parts}
    assert len(lengths) > 1, "the seeds no longer make blocks stop at different iterations"
    whole = minimize("sphere", runs_per_block=6, **kw)
    _assert_same(whole, join_results(parts))


def test_per_run_x0_goes_with_its_runs():
    rng = np.random.default_rng(1)
    x0 = rng.uniform(-5, 5, (5, 2, 3))
    kw = dict(algorithm="mawdo", runs=5, seed=2, dim=3, pop_size=10, max_iter=5, x0=x0)
    _assert_same(minimize("sphere", **kw), minimize("sphere", runs_per_block=2, **kw))


def test_default_blocks_match_one_batch_at_scale():
    # pop 50 x D 30: the default block holds 87 runs, so 100 runs go in two blocks
    kw = dict(algorithm="mawdo", runs=100, seed=5, dim=30, pop_size=50, max_iter=3)
    assert len(block_sizes(100, None, 50, 30)) == 2
    _assert_same(minimize("sphere", **kw), minimize("sphere", runs_per_block=100, **kw))


def test_cmaes_restarts_are_joined_per_run():
    kw = dict(algorithm="cmaes", runs=5, seed=1, dim=2, max_evals=600)
    a = minimize("rastrigin", runs_per_block=5, **kw)
    b = minimize("rastrigin", runs_per_block=2, **kw)
    assert len(b.metadata["restarts"]) == 5
    assert a.metadata["restarts"] == b.metadata["restarts"]
    assert max(a.metadata["restarts"]) > 0, "no restart: the test no longer joins anything"


@pytest.mark.parametrize(
    "kw,match",
    [
        ({"runs_per_block": 0}, "runs_per_block=0 must be an integer >= 1"),
        ({"runs_per_block": 2, "max_time": 5.0}, "cannot be combined with callback or max_time"),
        ({"runs_per_block": 2, "callback": lambda r: False}, "leave runs_per_block=None"),
    ],
)
def test_bad_runs_per_block(kw, match):
    with pytest.raises(ValueError, match=match):
        minimize("sphere", algorithm="wdo", runs=4, dim=2, max_iter=2, **kw)


def test_wrong_per_run_x0_names_the_batch():
    x0 = np.zeros((3, 1, 2))
    with pytest.raises(ValueError, match=r"\(4, k, 2\)"):
        minimize("sphere", algorithm="wdo", runs=4, dim=2, max_iter=2, x0=x0, runs_per_block=2)
