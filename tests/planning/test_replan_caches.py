"""The replan's caches (issue 27's latency work) change no decision.

Each shortcut is compared bit for bit with the plain computation it replaces: the knot index of
every obstacle at a time (one pass over the table instead of one binary search per obstacle,
against a literal port of the loop), the kernel arrays a cost keeps per start time, and whole
planning runs with the caches switched off.
"""

import numpy as np
import pytest

from mawdo.planning import get_scenario
from mawdo.planning.refine.cost import PathCost
from mawdo.planning.run.planner import plan
from mawdo.planning.scenes import generate_scene
from mawdo.planning.world.geometry import MotionTable

FAMILIES = ("dense", "crossing", "corridor", "doorway", "chaser", "crowd", "parked", "slalom")


def searched_start_indices(table: MotionTable, t: float) -> np.ndarray:
    """Literal port of ``MotionTable.start_indices`` before it became one pass (0.9.0)."""
    idx = np.zeros(len(table.nknots), dtype=np.int64)
    for i, nk in enumerate(table.nknots):
        k = int(np.searchsorted(table.times[i, :nk], t, side="right")) - 1
        idx[i] = min(max(k, 0), max(nk - 2, 0))
    return idx


def _scenarios():
    yield get_scenario("paper")
    for family in FAMILIES:
        yield generate_scene(family, 0, seed=0).scenario


def test_start_indices_in_one_pass_equal_one_search_per_obstacle():
    rng = np.random.default_rng(27)
    checked = 0
    for sc in _scenarios():
        for lo, hi in ((0.0, 60.0), (3.7, 400.0), (12.0, 12.0)):
            table = MotionTable.build(sc.obstacles, lo, hi)
            knots = table.times[np.isfinite(table.times)]
            knots = rng.choice(knots, min(len(knots), 150), replace=False)
            # random times, every knot exactly (ties: searchsorted's right side), the ends,
            # before the table, far beyond it and the infinities
            ends = [lo, hi, -1.0, 1e300, np.inf, -np.inf]
            ts = np.concatenate([rng.uniform(lo - 5, hi + 20, 100), knots, ends])
            for t in ts:
                got, ref = table.start_indices(float(t)), searched_start_indices(table, float(t))
                assert got.dtype == ref.dtype and np.array_equal(got, ref), (t, got, ref)
                checked += 1
    assert checked > 1500
    table = MotionTable.build(get_scenario("paper").obstacles, 0.0, 50.0)
    nan = table.start_indices(float("nan"))  # NaN: what the searches gave
    assert np.array_equal(nan, searched_start_indices(table, float("nan")))


def test_a_cost_keeps_the_kernel_arrays_of_each_start_time():
    sc = generate_scene("crowd", 1, seed=0).scenario
    cost = PathCost(sc, mode="spacetime", n_waypoints=8, clearance=2.0)
    X = np.linspace(sc.start, sc.goal, 10)[1:-1].reshape(1, -1)
    times = [0.0, 7.25, 3.0, 7.25, 0.0, 19.5]
    for t0 in times:
        cost(X, start=sc.start, t0=t0)
    assert len(cost._tables) == 1  # (one table covers these calls)
    table, kept = cost._tables[0]
    assert sorted(kept) == [0.0, 3.0, 7.25, 19.5]  # one entry per start time
    for t0, arrays in kept.items():
        fresh = table.kernel_arrays(t0)
        assert all(np.array_equal(a, b) for a, b in zip(arrays, fresh, strict=True))


def _uncached(self, kept, t0):
    return kept[0].kernel_arrays(t0)


def _same_run(a, b) -> None:
    assert np.array_equal(a.route, b.route) and np.array_equal(a.route_times, b.route_times)
    assert np.array_equal(a.trajectory, b.trajectory)
    assert (a.success, a.holds, a.waits, a.evasions, a.fallbacks, a.inevitable) == (
        b.success, b.holds, b.waits, b.evasions, b.fallbacks, b.inevitable,
    )  # fmt: skip
    assert [r.cost for r in a.replans] == [r.cost for r in b.replans]


@pytest.mark.parametrize(
    "scenario, seed",
    [("paper", 1), (("crowd", 0), 0), (("doorway", 0), 0)],
    ids=["paper", "crowd-0", "doorway-0"],
)
def test_runs_with_the_motion_cache_equal_runs_without_it(monkeypatch, scenario, seed):
    sc = get_scenario(scenario) if isinstance(scenario, str) else generate_scene(*scenario, seed=0)
    sc = sc if isinstance(scenario, str) else sc.scenario
    cached = plan(sc, "mawdo", seed=seed, config="quick", time_guide=True)
    monkeypatch.setattr(PathCost, "_motion_arrays", _uncached)
    plain = plan(sc, "mawdo", seed=seed, config="quick", time_guide=True)
    # it replanned and drove many steps, each checked by the guard from its own time
    assert len(plain.replans) >= 2 and len(plain.trajectory) > 20
    _same_run(cached, plain)
