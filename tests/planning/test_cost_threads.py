"""The population cost on several threads (``PathCost(threads=...)``, issue 15).

The reference is the one-thread call: chunks of rows must give the very same cost, length,
count and turning for every candidate, bit for bit, on scenes of several families, both modes,
with NaN and far-off candidates in the population, whatever the number of chunks.
"""

from __future__ import annotations

import json
import subprocess
import sys
import threading

import numpy as np
import pytest

from mawdo.planning import PathCost, get_scenario
from mawdo.planning.judge.metrics import run_metrics_kept
from mawdo.planning.refine.kernel import threads as kthreads
from mawdo.planning.refine.kernel.constants import INDEX_MOVERS, INDEX_STANDING
from mawdo.planning.refine.kernel.threads import (
    MIN_ROWS,
    PARALLEL_SECONDS,
    ThreadedKernel,
    chunk_bounds,
    index_choice,
)
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.planner import plan
from mawdo.planning.scenes import generate_scene
from mawdo.util.validate import ArgumentTypeError


def _scenario(name):
    return get_scenario("paper") if name == "paper" else generate_scene(name, 0, 3).scenario


def _population(sc, n, seed, far=1.9):
    rng = np.random.default_rng(seed)
    hi = np.tile([sc.width, sc.height], 20)
    X = rng.uniform(0, 1, (n, 40)) * hi
    if n > 40:  # a few rows the kernel handles apart: NaN, outside the map, repeated points
        X[3, 7] = np.nan
        X[11] = X[11] * far
        X[17, 2:6] = X[17, 0:4]
    return X


@pytest.fixture
def always_split(monkeypatch):
    """Split every call that has rows enough, however short (else small test populations
    would run on one thread only)."""
    monkeypatch.setattr(kthreads, "PARALLEL_SECONDS", 0.0)


def _same(a, b):
    for u, v in zip(a, b, strict=True):
        np.testing.assert_array_equal(u, v)


@pytest.mark.parametrize("name", ["paper", "crossing", "dense", "movingai", "maze"])
@pytest.mark.parametrize("mode", ["snapshot", "spacetime"])
def test_threads_give_the_one_thread_numbers_bit_for_bit(name, mode, always_split):
    sc = _scenario(name)
    one = PathCost(sc, mode=mode)
    many = {t: PathCost(sc, mode=mode, threads=t) for t in (2, 3, 7)}
    # (beyond 1e7 px the kernel skips its fast accepts; spacetime mode refuses such paths)
    far = 1e8 if mode == "snapshot" else 1.9
    for n, seed in ((1, 0), (MIN_ROWS * 2 - 1, 1), (MIN_ROWS * 2, 2), (300, 3), (1021, 4)):
        X = _population(sc, n, seed, far)
        for t0 in (0.0, 23.5):
            ref = one.parts(X, t0=t0)
            ref_cost = one(X, t0=t0)
            assert np.unique(ref[1]).size > 1 or n < 40  # counts that differ between rows
            for cost in many.values():  # (the first call of a size is timed on one thread)
                for _ in range(2):
                    _same(cost.parts(X, t0=t0), ref)
                    np.testing.assert_array_equal(cost(X, t0=t0), ref_cost)


def test_chunk_bounds_are_even_cover_every_row_and_respect_the_minimum():
    for n in (0, 1, 15, 16, 31, 32, 33, 240, 1360, 1361):
        for threads in (1, 2, 3, 8, 100):
            b = chunk_bounds(n, threads)
            sizes = np.diff(b)
            assert b[0] == 0 and b[-1] == n
            assert 1 <= sizes.size <= threads
            assert sizes.max() - sizes.min() <= 1
            if sizes.size > 1:
                assert sizes.min() >= MIN_ROWS
            else:  # one chunk only where two would fall below the minimum
                assert threads == 1 or n < 2 * MIN_ROWS


class _Clock:
    """A stand-in for the thread's CPU clock: each call advances it by ``step`` seconds."""

    def __init__(self, step):
        self.step, self.now, self.calls = step, 0.0, 0

    def __call__(self):
        self.calls += 1
        self.now += self.step
        return self.now


def _kernel_args(sc, n, t0=4.0):
    cost = PathCost(sc, mode="spacetime")
    X = _population(sc, n, 5)
    args, ref = [], cost.parts(X, t0=t0)

    def grab(kernel, *a):
        args.append(a)

    original = ThreadedKernel.__call__
    ThreadedKernel.__call__ = grab
    try:
        cost.parts(X, t0=t0)
    finally:
        ThreadedKernel.__call__ = original
    return args[0], ref


@pytest.mark.parametrize(
    "seconds, split", [(PARALLEL_SECONDS * 0.9, False), (PARALLEL_SECONDS, True)]
)
def test_a_call_is_split_only_when_one_thread_took_long_enough(monkeypatch, seconds, split):
    args, ref = _kernel_args(get_scenario("paper"), 240)
    chunked = []
    run = kthreads._chunked
    monkeypatch.setattr(kthreads, "_chunked", lambda *a: chunked.append(1) or run(*a))
    clock = _Clock(seconds)  # (two readings per timed call, ``seconds`` apart)
    kernel = ThreadedKernel(2, clock=clock)
    for call in range(4):
        out = tuple(np.zeros_like(o) for o in args[-1])
        kernel(*args[:-1], out)
        _same((out[1], out[2], out[3]), ref)
        # the first call is timed on one thread; later calls split or not by what it took
        assert len(chunked) == (call if split else 0)
    assert clock.calls == 2  # timed once per size and motion table
    # a new motion table (another planning time) is timed again
    args2, _ = _kernel_args(get_scenario("paper"), 240, t0=9.0)
    out = tuple(np.zeros_like(o) for o in args2[-1])
    kernel(*args2[:-1], out)
    assert clock.calls == 4


def test_one_thread_never_times_or_splits(monkeypatch):
    args, ref = _kernel_args(get_scenario("paper"), 240)
    monkeypatch.setattr(kthreads, "_chunked", lambda *a: pytest.fail("split on one thread"))
    clock = _Clock(1.0)
    kernel = ThreadedKernel(1, clock=clock)
    for _ in range(3):
        out = tuple(np.zeros_like(o) for o in args[-1])
        kernel(*args[:-1], out)
        _same((out[1], out[2], out[3]), ref)
    assert clock.calls == 0


def _knots(moving, standing):
    return np.array([3] * moving + [1] * standing, dtype=np.int64)


def test_each_world_gets_only_the_indexes_it_may_use():
    # (the counts on either side of each threshold; standing ones in snapshot mode include
    # every obstacle, since none moves there)
    below = _knots(INDEX_MOVERS - 1, INDEX_STANDING - 1)
    assert index_choice(below, True) == (None, None)
    assert index_choice(_knots(INDEX_MOVERS, 3), True) == (INDEX_MOVERS, None)
    assert index_choice(_knots(INDEX_MOVERS, 3), False) == (INDEX_MOVERS, True)
    assert index_choice(_knots(10, INDEX_STANDING), True) == (INDEX_MOVERS, True)
    assert index_choice(_knots(INDEX_MOVERS, INDEX_STANDING), True) == (INDEX_MOVERS, True)
    assert index_choice(_knots(0, INDEX_STANDING - 1), False) == (None, None)


def test_concurrent_callers_each_get_their_own_numbers(always_split):
    sc = get_scenario("paper")
    X = [_population(sc, 400, s) for s in range(4)]
    ref = [PathCost(sc, mode="spacetime").parts(x, t0=5.0) for x in X]
    got = [None] * 4

    def work(k):
        cost = PathCost(sc, mode="spacetime", threads=2)
        for _ in range(5):
            got[k] = cost.parts(X[k], t0=5.0)

    workers = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    for g, r in zip(got, ref, strict=True):
        _same(g, r)


@pytest.mark.parametrize("bad", [0, -2])
def test_a_thread_count_below_one_is_refused_with_its_name(bad):
    sc = get_scenario("paper")
    with pytest.raises(ValueError, match=r"threads=.* must be an integer >= 1"):
        PathCost(sc, threads=bad)
    with pytest.raises(ValueError, match=r"PlannerConfig.threads"):
        PlannerConfig(threads=bad)


@pytest.mark.parametrize("bad", [True, 2.0, "2"])
def test_a_thread_count_that_is_not_an_integer_is_refused(bad):
    with pytest.raises(ArgumentTypeError, match="threads"):
        PathCost(get_scenario("paper"), threads=bad)


def test_the_planner_drives_the_same_route_on_two_threads(always_split):
    runs = [plan("paper", "mawdo", seed=4, config="fast", threads=t) for t in (1, 2)]
    np.testing.assert_array_equal(runs[0].route, runs[1].route)
    assert [r.cost for r in runs[0].replans] == [r.cost for r in runs[1].replans]
    assert len(runs[0].replans) > 5


def test_plan_run_on_two_threads_reports_them_and_drives_the_one_thread_route(tmp_path):
    cmd = [sys.executable, "-m", "mawdo.cli", "plan", "paper", "--preset", "fast", "--seed", "4"]
    cmd += ["--threads", "2", "--no-figures", "--no-progress", "--out", str(tmp_path)]
    res = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    got = json.loads((tmp_path / "metrics.json").read_text())
    assert got["threads"] == 2
    ref, error = run_metrics_kept(plan("paper", "mawdo", seed=4, config="fast"))
    assert error is None
    timing = {"first_plan_s"} | {k for k in ref if k.startswith("latency")}
    assert {k: v for k, v in ref.items() if k not in timing} == {
        k: got[k] for k in ref if k not in timing
    }
    assert ref["success"] and ref["length_px"] > 0
