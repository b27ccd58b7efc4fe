"""The planner's speed shortcuts outside the cost kernel give exactly what the plain code gave.

Each shortcut (the compiled elite merge, the random walk's kept folded positions, the early
exit of ``fold_turn_times``, the static obstacles inflated once) is compared bit for bit with a
literal port of the code it replaced, or with a fresh computation that takes no shortcut.
"""

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from mawdo.planning import get_scenario
from mawdo.planning.safety.guard import Elite
from mawdo.planning.world.geometry import inflate, inflated_obstacles
from mawdo.planning.world.motion import BoundedRandomWalk, fold_turn_times


class NumpyElite:
    """Literal port of ``Elite.add`` before it was compiled (mawdo 0.2.0)."""

    def __init__(self, size, min_dist):
        self.size, self.min_dist = size, min_dist
        self.X, self.f = np.empty((0, 0)), np.empty(0)

    def add(self, X, f):
        X, fv = np.atleast_2d(X), np.atleast_1d(np.asarray(f, dtype=float))
        ok = np.isfinite(fv)
        if not ok.any():
            return
        X, fv = X[ok], fv[ok]
        if len(self.f) == self.size and fv.min() >= self.f[-1]:
            return
        if len(fv) > self.size:
            part = np.argpartition(fv, self.size - 1)[: self.size]
            take = part[np.argsort(fv[part], kind="stable")]
        else:
            take = np.argsort(fv, kind="stable")
        allx = np.vstack([self.X, X[take]]) if self.X.size else X[take].copy()
        allf = np.r_[self.f, fv[take]]
        keep = []
        for i in np.argsort(allf, kind="stable"):
            if not keep or np.min(np.max(np.abs(allx[keep] - allx[i]), axis=1)) > self.min_dist:
                keep.append(int(i))
                if len(keep) == self.size:
                    break
        self.X, self.f = allx[keep].copy(), allf[keep]


def test_elite_equals_the_numpy_loop_it_replaced():
    rng = np.random.default_rng(3)
    for size, dist in ((1, 2.0), (4, 1.0), (8, 2.0), (8, 50.0)):
        fast, ref = Elite(size, dist), NumpyElite(size, dist)
        for _ in range(40):
            n = int(rng.integers(1, 30))
            X = rng.uniform(0, 100, (n, 6))
            f = rng.choice([0.5, 1.0, 2.0], n) if rng.random() < 0.3 else rng.random(n)
            X[: n // 3] = X[0] + rng.uniform(-1.5, 1.5, (n // 3, 6))  # near-copies
            f[rng.random(n) < 0.1] = np.nan  # failed evaluations are skipped
            if rng.random() < 0.1:
                f[:] = np.inf
            fast.add(X, f)
            ref.add(X, f)
            np.testing.assert_array_equal(fast.f, ref.f)
            np.testing.assert_array_equal(fast.X.reshape(-1, 6), ref.X.reshape(-1, 6))
        assert len(ref.f) == size  # the comparison reached a full elite


def test_full_elite_with_non_finite_costs_equals_the_numpy_loop():
    """The early exit is taken before the finite filter: a -inf or NaN in the batch must
    still end as the filtered test decided."""
    rng = np.random.default_rng(8)
    fast, ref = Elite(4, 1.0), NumpyElite(4, 1.0)
    for k in range(60):
        X = rng.uniform(0, 100, (12, 5))
        f = rng.random(12) + (1.0 if k > 3 else 0.0)  # after the first batches: nothing enters
        special = rng.choice([np.nan, -np.inf, np.inf], size=int(rng.integers(0, 4)))
        f[rng.choice(12, size=len(special), replace=False)] = special
        if k % 7 == 6:
            f[rng.integers(12)] = 0.01 * rng.random()  # a newcomer among the non-finite ones
        fast.add(X, f)
        ref.add(X, f)
        np.testing.assert_array_equal(fast.f, ref.f)
        np.testing.assert_array_equal(fast.X.reshape(-1, 5), ref.X.reshape(-1, 5))
    assert len(ref.f) == 4


def test_random_walk_queried_forward_equals_a_fresh_walk_per_query():
    seed = np.random.SeedSequence(5, spawn_key=(2,))
    kept = BoundedRandomWalk(1.5, (-30.0, -20.0), (80.0, 90.0), seed, hold=3)
    for t0 in (0.0, 7.5, 255.0, 256.5, 800.0, 12.0, 2000.25):
        times = t0 + np.linspace(0.0, 40.0, 17)
        fresh = BoundedRandomWalk(1.5, (-30.0, -20.0), (80.0, 90.0), seed, hold=3)
        np.testing.assert_array_equal(kept.offset(times), fresh.offset(times))


def reference_turn_times(velocity, lo, hi, t0, t1):
    """``fold_turn_times`` without its early exit (mawdo 0.2.0)."""
    span = hi - lo
    if velocity == 0.0 or span <= 0.0 or t1 <= t0:
        return np.empty(0)
    a, b = (velocity * t0 - lo) / span, (velocity * t1 - lo) / span
    ka, kb = min(a, b), max(a, b)
    k = np.arange(np.floor(ka) + 1.0, np.ceil(kb))
    times = (lo + k * span) / velocity
    return np.sort(times[(times > t0) & (times < t1)])


@given(
    v=st.floats(-6.0, 6.0),
    lo=st.floats(-100.0, 0.0),
    span=st.sampled_from([0.0, 1.0, 37.5, 200.0]) | st.floats(1.0, 200.0),
    t0=st.floats(0.0, 500.0),
    dt=st.sampled_from([0.0, 1e-9, 0.25, 1.0, 3.0, 50.0]),
)
@settings(max_examples=300, deadline=None)
def test_fold_turn_times_early_exit_changes_nothing(v, lo, span, t0, dt):
    got = fold_turn_times(v, lo, lo + span, t0, t0 + dt)
    np.testing.assert_array_equal(got, reference_turn_times(v, lo, lo + span, t0, t0 + dt))


def test_cached_static_inflation_equals_inflating_afresh():
    sc = get_scenario("paper")
    r = sc.robot_radius
    for t in (0.0, 13.0, 57.5, 13.0):
        got = inflated_obstacles(sc, t)
        offsets = sc.offsets(t)
        assert len(got) == len(sc.obstacles)
        for o, g in zip(sc.obstacles, got, strict=True):
            want = inflate(o.shape, r, offsets[o.index])
            assert shapely.equals_exact(g, want, tolerance=0.0)
