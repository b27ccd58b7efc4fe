"""PathCost's per-call shortcuts (issue 27, replan latency): the inputs it no longer converts,
the scenario values it reads once, and the kernel's per-size plans must leave every number as a
fresh cost object computes it from canonical inputs."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.planning import PathCost, get_scenario
from mawdo.planning.refine.kernel import scratch_size
from mawdo.planning.scenes import generate_scene


def _scenario(name):
    return get_scenario("paper") if name == "paper" else generate_scene(name, 0, 0).scenario


def _population(sc, n, seed, spread=1.0):
    rng = np.random.default_rng(seed)
    hi = np.tile([sc.width, sc.height], 20)
    return rng.uniform(0, 1, (n, 40)) * hi * spread


def _same(a, b):
    for u, v in zip(a, b, strict=True):
        np.testing.assert_array_equal(u, v)


@pytest.mark.parametrize("name", ["paper", "crowd"])
def test_one_cost_object_over_many_sizes_and_times_gives_a_fresh_objects_numbers(name):
    # The planner alternates populations and one-candidate checks at ever later t0; the kernel
    # keeps a plan (chunk bounds, scratch size) per size and the cost its motion table. A new
    # PathCost for every call has none of that state: its numbers are the reference.
    sc = _scenario(name)
    kept = PathCost(sc, mode="spacetime", clearance=0.5)
    calls = [(240, 0.0), (1, 0.0), (7, 3.0), (240, 3.0), (1, 40.0), (300, 40.0), (240, 41.5)]
    counts = set()
    for k, (n, t0) in enumerate(calls):
        X = _population(sc, n, k)
        start = np.array([10.0 + k, 12.0])
        ref = PathCost(sc, mode="spacetime", clearance=0.5)
        want = ref.parts(X, start=start, t0=t0)
        _same(kept.parts(X, start=start, t0=t0), want)
        np.testing.assert_array_equal(kept(X, start=start, t0=t0), ref(X, start=start, t0=t0))
        counts.update(want[1].tolist())
    assert len(counts) > 3  # collisions that differ between candidates were counted


def test_the_kernel_plan_follows_a_new_motion_table():
    # A table built for a later, farther call has more knots, so the kernel needs more scratch
    # space: the plan kept for that population size must be redone, not reused.
    sc = _scenario("paper")
    cost = PathCost(sc, mode="spacetime")
    X = _population(sc, 240, 0, spread=0.3)
    cost(X, t0=0.0)
    first = cost._tables[0][0]
    far = _population(sc, 240, 1)
    t0 = first.t_hi + 10.0  # beyond the first table: a new one
    cost(far, t0=t0)
    assert cost._tables[0][0] is not first
    nk = cost._motion_arrays(cost._tables[0], t0)[3]
    assert cost._kernel._buf.shape[1] >= scratch_size(240, 22, nk, True)


def test_tables_asked_in_turn_are_kept_and_their_numbers_are_those_of_a_fresh_cost():
    # a guard asks short stretches and whole routes in turn: each table is built once and
    # kept, and what a call returns is what a cost with no table kept returns
    from mawdo.planning.refine import cost as cost_module

    sc = _scenario("paper")
    cost = PathCost(sc, mode="spacetime")
    short, long_ = _population(sc, 40, 2, spread=0.05), _population(sc, 40, 3)
    # (the first table, built at t = 0, reaches past 5000 steps: the long calls begin later)
    calls = [(long_ if t0 >= 6000 else short, t0) for t0 in (0.0, 6000.0, 0.5, 6000.5, 1.0)]
    fresh = [PathCost(sc, mode="spacetime").parts(X, t0=t0)[1] for X, t0 in calls]
    built, build = [], cost_module.MotionTable.build
    cost_module.MotionTable.build = lambda *a: built.append(a[1:]) or build(*a)
    try:
        got = [cost.parts(X, t0=t0)[1] for X, t0 in calls]
    finally:
        cost_module.MotionTable.build = build
    assert len(built) == 2  # one table for the short calls, one for the long ones
    for a, b in zip(got, fresh, strict=True):
        np.testing.assert_array_equal(a, b)  # the hits (the tables differ only in rounding)
    assert sum(int(b.sum()) for b in fresh) > 0


@pytest.mark.parametrize("mode", ["snapshot", "spacetime"])
def test_inputs_in_any_array_form_give_the_canonical_numbers(mode):
    sc = _scenario("paper")
    cost = PathCost(sc, mode=mode)
    X = _population(sc, 50, 3)
    start = np.array([20.0, 20.0])
    want = cost.parts(X, start=start, t0=5.0, goal=sc.goal)
    forms = [
        X.copy(),
        np.asfortranarray(X),
        X.tolist(),
        np.repeat(X, 2, axis=0)[::2],  # a strided view
    ]
    for form in forms:
        _same(cost.parts(form, start=start, t0=5.0), want)
        _same(cost.parts(form, start=[20, 20], t0=5), want)
        _same(cost.parts(form, start=(20.0, 20.0), t0=5.0, goal=tuple(sc.goal)), want)
    one = cost.parts(X[4], start=start, t0=5.0)  # a single candidate: scalars
    assert [float(v) for v in one] == [float(w[4]) for w in want]
    # a float32 array is converted, not read as float64 bits
    x32 = X.astype(np.float32)
    _same(
        cost.parts(x32, start=start, t0=5.0),
        cost.parts(x32.astype(np.float64), start=start, t0=5.0),
    )


def test_bad_inputs_are_still_refused_by_name():
    sc = _scenario("paper")
    cost = PathCost(sc, mode="spacetime")
    X = _population(sc, 4, 0)
    with pytest.raises(ValueError, match=r"X must have shape \(n, 40\)"):
        cost(X[:, :38])
    with pytest.raises(ValueError, match="goal must be a finite"):
        cost.parts(X, goal=np.array([np.nan, 3.0]))
    with pytest.raises(ValueError, match="start must be a finite"):
        cost(X, start=np.array([1.0, 2.0, 3.0]))
    with pytest.raises(ValueError, match="start or goal is 1000 px, more than one map size"):
        cost(X, start=np.array([1000.0, 2.0]))
    with pytest.raises(ValueError, match="candidate coordinate is -400 px"):
        bad = X.copy()
        bad[1, 5] = -400.0
        cost(bad)


def test_bounds_are_laid_out_once_and_handed_out_as_fresh_copies():
    # the box is built once per cost object; each caller gets its own arrays, so a caller that
    # writes into them (or clips in place) cannot move the box of the next one
    sc = get_scenario("paper")
    cost = PathCost(sc, mode="spacetime", n_waypoints=5)
    lb, ub = cost.bounds
    np.testing.assert_array_equal(lb, np.zeros(10))
    np.testing.assert_array_equal(ub, [sc.width, sc.height] * 5)
    lb[:] = -1.0
    ub[:] = 1e9
    lb2, ub2 = cost.bounds
    np.testing.assert_array_equal(lb2, np.zeros(10))
    np.testing.assert_array_equal(ub2, [sc.width, sc.height] * 5)
    assert not np.shares_memory(lb2, cost.bounds[0])
