"""Polish (PlannerConfig.polish_rounds): the midpoint moves, the descent, and its place in a run."""

import numpy as np
import pytest

from mawdo.planning.refine.cost import assemble_paths
from mawdo.planning.refine.polish import midpoint_moves, polish
from mawdo.planning.run.config import PRESETS, PlannerConfig
from mawdo.planning.run.execute import Run
from mawdo.planning.world.path import polyline_length

from . import maps


def test_midpoint_moves_by_hand():
    # start (0, 0), waypoints (1, 2) and (3, 2), goal (4, 0)
    x = np.array([1.0, 2.0, 3.0, 2.0])
    V = midpoint_moves(x, [0.0, 0.0], [4.0, 0.0], (0.5, 1.0))
    # waypoint 0's neighbours are the start and (3, 2): midpoint (1.5, 1); waypoint 1's are
    # (1, 2) and the goal: midpoint (2.5, 1)
    expected = np.array(
        [
            [1.25, 1.5, 3.0, 2.0],  # half way
            [1.0, 2.0, 2.75, 1.5],
            [1.5, 1.0, 3.0, 2.0],  # onto the midpoint
            [1.0, 2.0, 2.5, 1.0],
        ]
    )
    np.testing.assert_allclose(V, expected, rtol=0, atol=1e-15)
    np.testing.assert_array_equal(x, [1.0, 2.0, 3.0, 2.0])  # the plan is not written


@pytest.mark.parametrize("m", [1, 2, 7, 20])
def test_midpoint_moves_equal_a_row_by_row_construction(m):
    # the variants are built by one flat scatter into copies of the plan; written the plain
    # way, row a m + i is the plan with waypoint i moved, w_i + f_a (midpoint - w_i)
    rng = np.random.default_rng(m)
    x, start, goal = rng.uniform(0, 366, 2 * m), rng.uniform(0, 366, 2), rng.uniform(0, 366, 2)
    fractions = (0.25, 0.5, 1.0)
    V = midpoint_moves(x, start, goal, fractions)
    chain = [start] + [x[2 * i : 2 * i + 2] for i in range(m)] + [goal]
    rows = []
    for f in fractions:
        for i in range(m):
            row = x.copy()
            w = chain[i + 1]
            mid = 0.5 * (chain[i] + chain[i + 2])
            row[2 * i : 2 * i + 2] = w + f * (mid - w)
            rows.append(row)
    np.testing.assert_array_equal(V, np.array(rows))  # the same doubles, not only close ones
    assert V.flags.writeable and not np.shares_memory(V, x)


def _length_cost(start, goal):
    """Route length, row by row: a cost whose optimum (the straight line) is known."""

    def cost(X):
        return np.array([polyline_length(p) for p in assemble_paths(np.atleast_2d(X), start, goal)])

    return cost


def test_polish_shortens_a_zigzag_and_never_raises_the_cost():
    start, goal = np.array([0.0, 0.0]), np.array([10.0, 0.0])
    m = 9
    xs = np.linspace(1.0, 9.0, m)
    ys = np.where(np.arange(m) % 2 == 0, 2.0, -2.0)  # a zig-zag across the straight line
    x = np.column_stack([xs, ys]).reshape(-1)
    cost = _length_cost(start, goal)
    f0 = float(cost(x)[0])
    steps = (0.5, 1.0)
    x1, f1, n1 = polish(cost, x, f0, start, goal, 1, steps)
    assert f1 < f0 and n1 == len(steps) * m
    assert f1 == pytest.approx(float(cost(x1)[0]), rel=1e-15)  # the cost it reports is x1's
    x8, f8, n8 = polish(cost, x, f0, start, goal, 8, steps)
    assert f8 < f1 and n8 == 8 * len(steps) * m  # every round found a cheaper variant
    # the straight line has nothing left to gain: one round, then stop, plan unchanged
    line = np.column_stack([xs, np.zeros(m)]).reshape(-1)
    fl = float(cost(line)[0])
    xl, fl2, nl = polish(cost, line, fl, start, goal, 8, steps)
    assert nl == len(steps) * m and fl2 == fl
    np.testing.assert_array_equal(xl, line)


def test_polish_rejects_variants_that_cost_more():
    start, goal = np.array([0.0, 0.0]), np.array([10.0, 0.0])
    x = np.array([5.0, 3.0])  # one waypoint; its midpoint move is (5, 0)
    # a cost that prefers the detour: the straightening move is refused, nothing changes
    detour_cost = lambda X: -np.abs(np.atleast_2d(X)[:, 1])  # noqa: E731
    x_out, f_out, n = polish(detour_cost, x, -3.0, start, goal, 4, (1.0,))
    np.testing.assert_array_equal(x_out, x)
    assert f_out == -3.0 and n == 1


def _run(sc, **cfg):
    return Run(sc, "mawdo", 0, PlannerConfig(**cfg), dynamic=True)


def test_a_replan_with_polish_costs_no_more_and_counts_its_evaluations():
    sc = maps._scenario("empty", [], (20.0, 183.0), (346.0, 183.0))
    start = np.array([20.0, 183.0])
    detour = np.array([start, [120.0, 60.0], [250.0, 300.0], [346.0, 183.0]])
    # no guide routes: the seeds are the detour and its perturbed copies
    base = dict(pop_size=40, replan_iters=3, n_waypoints=10, auto_waypoints=False, guide_routes=0)
    plain = _run(sc, polish_rounds=0, **base)
    plain.optimise(start, 3, detour)
    polished = _run(sc, polish_rounds=4, **base)
    polished.optimise(start, 3, detour)
    a, b = plain.replans[-1], polished.replans[-1]
    # the same search (same seeds), then the polish: never costlier, its evaluations counted
    np.testing.assert_array_equal(a.history, b.history)
    assert b.cost < a.cost  # three iterations leave slack on a detour
    assert b.length < a.length
    extra = b.nfev - a.nfev
    per_round = 2 * 10  # two step lengths x ten waypoints
    assert 0 < extra <= 4 * per_round and extra % per_round == 0


def test_presets_and_validation():
    assert PRESETS["paper"].polish_rounds == 0 and PRESETS["study"].polish_rounds == 0
    assert PRESETS["realtime"].polish_rounds > 0
    assert PlannerConfig(polish_steps=[0.25, 1]).polish_steps == (0.25, 1.0)
    for bad in (-1, 1.5, "3"):
        with pytest.raises(ValueError, match="polish_rounds"):
            PlannerConfig(polish_rounds=bad)
    for bad in ((), (0.0,), (0.5, 1.5), ((0.5,),), (float("nan"),)):
        with pytest.raises(ValueError, match="polish_steps"):
            PlannerConfig(polish_steps=bad)
