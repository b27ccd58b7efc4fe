"""The cost's lookahead (``PathCost(horizon=H)``): moving obstacles count only on the path the
robot travels before ``t0 + H``, standing ones and the border on every segment.

The reference is built from the cost without a horizon, on other paths: the standing
obstacles and the border on the whole path, and the movers on the path cut where the robot is
at ``t0 + H`` (that point repeated as the goal, and the hits of the repeat, a point at one
moment, taken off again)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mawdo.planning import PathCost
from tests.planning.test_kernel_index import SIZE, _population, _world

CLEARANCE = 0.5


def _times(P, t0, speed):
    """Path times as the kernel computes them (the same operations, in the same order)."""
    tt, cum, inv = [t0], 0.0, 1.0 / speed
    for a, b in zip(P[:-1], P[1:], strict=True):
        dx, dy = float(b[0] - a[0]), float(b[1] - a[1])
        cum += math.sqrt(dx * dx + dy * dy)
        tt.append(t0 + cum * inv)
    return tt


def _movers_before(sc, movers, P, t0, horizon):
    """Hits of the movers on the path travelled before ``t0 + horizon``, by the cost without
    a horizon."""
    tt = _times(P, t0, float(sc.robot_speed))
    cut = t0 + horizon
    j = next((k for k in range(1, len(P)) if tt[k] >= cut), len(P) - 1)
    P = P[: j + 1].copy()
    if tt[j] > cut:  # the straddling segment ends where the robot is at the cut
        f = (cut - tt[j - 1]) / (tt[j] - tt[j - 1])
        P[j] = P[j - 1] + f * (P[j] - P[j - 1])
        tt[j] = cut
    wp = np.concatenate([P[1 : j + 1].ravel()])  # P1 .. Pj, then the goal Pj: a repeat
    whole = PathCost(sc, "spacetime", n_waypoints=j, clearance=CLEARANCE, obstacles=movers,
                     border=False)  # fmt: skip
    n = int(whole.parts(wp, start=P[0], t0=t0, goal=P[j])[1])
    point = PathCost(sc, "spacetime", n_waypoints=1, clearance=CLEARANCE, obstacles=movers,
                     border=False)  # fmt: skip
    # two zero-length segments at Pj at time tt[j]: twice the repeat's hits
    twice = int(point.parts(P[j], start=P[j], t0=tt[j], goal=P[j])[1])
    assert twice % 2 == 0
    return n - twice // 2


@pytest.mark.parametrize("seed", [0, 1])
def test_movers_count_only_before_the_horizon_standing_obstacles_everywhere(seed):
    sc = _world(seed)
    movers = [o for o in sc.obstacles if not o.is_static]
    standing = [o for o in sc.obstacles if o.is_static]
    rng = np.random.default_rng([11, seed])
    X = _population(rng, 60)
    X = X[np.all(np.abs(X) < 2 * SIZE, axis=1)]  # (finite, in reach of the map)
    full = PathCost(sc, "spacetime", clearance=CLEARANCE)
    still = PathCost(sc, "spacetime", clearance=CLEARANCE, obstacles=standing)
    fewer = 0
    for t0 in (0.0, 17.5):
        start = np.array([10.0, 10.0]) + t0 % 7
        L, n_all, T = full.parts(X, start=start, t0=t0)
        n_still = still.parts(X, start=start, t0=t0)[1]
        for horizon in (0.75, 30.0, 95.0):
            cost = PathCost(sc, "spacetime", clearance=CLEARANCE, horizon=horizon)
            Lh, nh, Th = cost.parts(X, start=start, t0=t0)
            assert Lh.tobytes() == L.tobytes() and Th.tobytes() == T.tobytes()
            for c in range(len(X)):
                P = np.vstack([start, X[c].reshape(-1, 2), sc.goal])
                want = int(n_still[c]) + _movers_before(sc, movers, P, t0, horizon)
                assert int(nh[c]) == want, (t0, horizon, c)
            assert np.all(nh <= n_all)
            fewer += int(np.sum(nh < n_all))
            w = cost.weights
            x = nh.astype(float)
            want_cost = w.alpha * L + w.beta * w.k * x * x * x * x + w.lam * T
            np.testing.assert_array_equal(cost(X, start=start, t0=t0), want_cost)
    assert fewer > 20  # the horizons leave hits out, often


def test_a_horizon_past_every_path_changes_nothing_and_bad_ones_are_refused():
    sc = _world(3)
    X = _population(np.random.default_rng(5), 40)
    base = PathCost(sc, "spacetime", clearance=CLEARANCE)
    far = PathCost(sc, "spacetime", clearance=CLEARANCE, horizon=1e9)
    for a, b in zip(base.parts(X, t0=3.0), far.parts(X, t0=3.0), strict=True):
        assert np.asarray(a).tobytes() == np.asarray(b).tobytes()
    # NaN candidates keep their NaN cost under a horizon too
    X[2, 3] = np.nan
    assert np.isnan(PathCost(sc, "spacetime", horizon=5.0)(X, t0=0.0)[2])
    for bad in (0.0, -3.0, math.inf, math.nan):
        with pytest.raises(ValueError, match="horizon must be None"):
            PathCost(sc, "spacetime", horizon=bad)
