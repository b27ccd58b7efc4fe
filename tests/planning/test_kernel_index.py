"""The kernel's indexes: the kernel that tests each moving obstacle (space-time index) or
standing obstacle (grid of a block's segments) only against the segments that can come near it
must give every output of the kernel that tests all of them (``fused_population_cost`` with
neither index), bit for bit, on worlds with every kind of motion and shape."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.planning import PathCost, scenario_from_dict
from mawdo.planning.refine.kernel.constants import INDEX_MOVERS
from mawdo.planning.refine.kernel.population import (
    fused_population_cost,
    population_cost,
    scratch_size,
)

# The index is used from 500 movers on (no world of the fast tier has as many) and its kernel
# compiles for about a minute: these run in `make test-all`, not in the fast tier.
pytestmark = pytest.mark.slow

SIZE = 400.0


def _motion(rng, kind):
    if kind == "constant_velocity":
        return {"model": kind, "velocity": rng.uniform(-2.5, 2.5, 2).round(3).tolist()}
    if kind == "patrol":
        k = int(rng.integers(1, 4))
        m = {
            "model": kind,
            "waypoints": rng.uniform(-45, 45, (k, 2)).round(2).tolist(),
            "speed": float(rng.uniform(0.5, 3.0)),
            "cycle": ["loop", "back_and_forth"][int(rng.integers(2))],
        }
        if rng.random() < 0.5:
            m["waits"] = rng.uniform(0, 6, k + 1).round(1).tolist()
        return m
    return {"model": kind, "step": float(rng.uniform(0.5, 2.5)), "hold": int(rng.integers(1, 6))}


def _polygon(rng, c, r):
    """A star-shaped polygon about ``c`` (its convex hull where rounding made it invalid)."""
    import shapely

    ang = np.sort(rng.uniform(0, 2 * np.pi, int(rng.integers(3, 7))))
    rad = rng.uniform(0.4 * r, r, ang.size)
    p = shapely.Polygon((c + np.c_[rad * np.cos(ang), rad * np.sin(ang)]).round(3))
    p = p if p.is_valid and p.area > 1.0 else p.convex_hull
    return np.asarray(p.exterior.coords)[:-1].tolist()


def _world(seed, movers=24, standing=5):
    """Movers of every kind (circles and polygons) and a few standing shapes."""
    rng = np.random.default_rng([7, seed])
    kinds = ("constant_velocity", "patrol", "bounded_random_walk")
    obstacles = []
    for j in range(movers):
        c = rng.uniform(70, SIZE - 70, 2)
        shape = (
            {"shape": "circle", "center": c.round(3).tolist(), "radius": float(rng.uniform(4, 14))}
            if j % 3
            else {"shape": "polygon", "vertices": _polygon(rng, c, float(rng.uniform(8, 20)))}
        )
        obstacles.append(shape | {"motion": _motion(rng, kinds[j % 3])})
    for _ in range(standing):
        c = rng.uniform(60, SIZE - 60, 2)
        obstacles.append({"shape": "polygon", "vertices": _polygon(rng, c, 25.0)})
    spec = {"schema_version": 1, "seed": seed, "width": SIZE, "height": SIZE,
            "start": [10.0, 10.0], "goal": [SIZE - 10.0, SIZE - 10.0],
            "obstacles": obstacles}  # fmt: skip
    return scenario_from_dict(spec)


def _population(rng, n, m=20):
    """Candidates of every sort: spread over the map, near the diagonal (many hits), repeated
    and zero-length waypoints, points outside the map, a few out of the sane range or NaN."""
    X = rng.uniform(-20, SIZE + 20, (n, 2 * m))
    diag = np.linspace(10, SIZE - 10, m + 2)[1:-1]
    near = np.repeat(diag, 2)[None, :] + rng.normal(0, 15, (n, 2 * m))
    X[: n // 2] = near[: n // 2]
    if n < 10:
        return X
    X[n // 2 : n // 2 + 3] = 10.0  # every waypoint at the start: zero-length segments
    X[n // 2 + 3, 2:4] = X[n // 2 + 3, 0:2]  # a repeated waypoint
    X[n // 2 + 4, 4:] = X[n // 2 + 4, 2:4].tolist() * (m - 2)  # stops half-way
    return X


def _calls(sc, rows, t0s, seed, horizon=None):
    """The kernel's arguments for populations at several start times (as PathCost passes them)."""
    cost = PathCost(sc, mode="spacetime", clearance=0.5, horizon=horizon)
    got = []
    kernel = cost._kernel

    def keep(*args):
        got.append(args)
        kernel(*args)

    cost._kernel = keep
    rng = np.random.default_rng([seed, 1])
    for t0 in t0s:
        for n in rows:
            cost.parts(_population(rng, n), start=np.array([10.0, 10.0]) + t0 % 7, t0=t0)
    return got


def _run(fn, args, *choice):
    """``fn`` (the kernel's public entry, or ``fused_population_cost`` with ``choice``: its
    ``min_movers`` and ``by_cells``) on ``args``; its four outputs."""
    X = args[0]
    n = X.shape[0]
    out = (np.empty(n), np.empty(n), np.empty(n, dtype=np.int64), np.empty(n))
    buf = np.empty(scratch_size(n, X.shape[1] // 2 + 2, args[8][3], args[5]))
    fn(*args[:12], out, buf, *choice)
    return out


def _assert_same(args):
    want = _run(fused_population_cost, args, None, None)  # neither index
    # the indexes forced on, the entry point (the moving index from INDEX_MOVERS movers on)
    # and the planner's choice with the standing obstacles' grid
    for choice in ((1, True), (), (INDEX_MOVERS, True)):
        got = _run(fused_population_cost if choice else population_cost, args, *choice)
        for a, b in zip(got, want, strict=True):
            assert a.dtype == b.dtype
            assert a.tobytes() == b.tobytes()
    return want


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_indexed_kernel_equals_the_unindexed_one_bit_for_bit(seed):
    sc = _world(seed)
    hits = 0
    for args in _calls(sc, rows=(1, 40, 300), t0s=(0.0, 13.25, 71.0), seed=seed):
        hits += int(_assert_same(args)[2].sum())
    assert hits > 100  # the worlds are crowded enough that the index has hits to keep


@pytest.mark.parametrize("horizon", [2.5, 40.0])
def test_under_a_horizon_the_indexed_kernel_equals_the_unindexed_one(horizon):
    # the index is built on the part of the block before the horizon (kernel.horizon)
    sc = _world(4)
    hits = 0
    for args in _calls(sc, rows=(40, 300), t0s=(0.0, 13.25), seed=4, horizon=horizon):
        hits += int(_assert_same(args)[2].sum())
    assert hits > 100


def test_blocks_out_of_the_sane_range_or_with_nan_give_the_same_numbers():
    # Such blocks take the unindexed pass; the other blocks of the call keep the index.
    sc = _world(5)
    for args in _calls(sc, rows=(200,), t0s=(0.0, 4.5), seed=5):
        X = args[0].copy()
        X[3, 5] = np.nan
        X[150, 0] = 3e7  # beyond the sane range (1e7 px)
        X[151, 1] = np.inf
        _assert_same((X, *args[1:]))


def test_a_crowd_of_movers_around_a_short_population():
    # Many movers, most of them far from the paths: the index leaves those out.
    sc = _world(9, movers=150, standing=0)
    for args in _calls(sc, rows=(130,), t0s=(2.0,), seed=9):
        X = args[0] * 0.3  # paths in the lower-left part of the map
        _assert_same((X, *args[1:]))


def test_the_guards_verdicts_with_the_index_are_those_without_it(monkeypatch):
    # a world past INDEX_MOVERS: the guard's kernel uses the index; forced to the unindexed
    # kernel, every stretch gets the same count
    from mawdo.planning.refine.kernel import threads
    from mawdo.planning.safety.guard import Guard

    sc = _world(11, movers=INDEX_MOVERS + 20, standing=3)
    rng = np.random.default_rng(12)
    stretches = []
    for _ in range(60):
        k = int(rng.integers(2, 7))
        route = np.vstack([rng.uniform(20, SIZE - 20, 2), rng.uniform(20, SIZE - 20, (k, 2))])
        stretches.append((route, float(rng.uniform(0, 40)), float(rng.uniform(10, 400))))

    def verdicts():
        guard = Guard(sc, clearance=0.5)
        return [guard.stretch_hits(route, t, d) for route, t, d in stretches]

    used, choose = [], threads.index_choice
    monkeypatch.setattr(threads, "index_choice", lambda *a: used.append(choose(*a)) or used[-1])
    indexed = verdicts()
    assert used and all(c[0] is not None for c in used)  # (the guard used the index)
    monkeypatch.setattr(threads, "index_choice", lambda nk, spacetime: (None, None))
    assert verdicts() == indexed
    assert len(set(indexed)) >= 5  # (a crowded map: counts of many sizes, not one verdict)


def test_movers_at_the_edge_of_a_blocks_reach_are_tested():
    # a flat population (its points' box has no height) and 600 movers gliding beside it, their
    # centres within a pixel of the hit distance: skipping a mover whose window box misses
    # the block's by less than the reach would lose hits
    rng = np.random.default_rng(5)
    r_mover, rho = 6.0, 6.0 + 4.0 + 0.5  # mover radius + robot radius + clearance
    obstacles = []
    for _ in range(600):
        side, d = rng.choice([-1.0, 1.0]), rho + rng.uniform(-1.0, 1.0)
        c = [float(rng.uniform(30, SIZE - 30)), 200.0 + side * d]
        v = [float(rng.uniform(-0.5, 0.5)), 0.0]
        obstacles.append({"shape": "circle", "center": c, "radius": r_mover,
                          "motion": {"velocity": v}})  # fmt: skip
    want = _flat_call(obstacles, "spacetime", (120.0, 180.0, 30.0), t0=3.0)
    assert want[2].sum() > 0  # the gliders do hit


def _flat_call(obstacles, mode, span, t0):
    """Six flat 4-waypoint paths along y = 200 px (the first from ``span[0]`` to ``span[1]``
    px, each next shifted by ``span[2]``) through the kernel on ``obstacles``: the outputs,
    checked against the unindexed kernel's."""
    sc = scenario_from_dict({"schema_version": 1, "width": SIZE, "height": SIZE,
                             "start": [10.0, 10.0], "goal": [390.0, 10.0],
                             "obstacles": obstacles})  # fmt: skip
    m = 4
    cost = PathCost(sc, n_waypoints=m, mode=mode, clearance=0.5)
    got, kernel = [], cost._kernel
    cost._kernel = lambda *a: (got.append(a), kernel(*a))
    X = np.tile(np.c_[np.linspace(span[0], span[1], m), np.full(m, 200.0)].ravel(), (6, 1))
    X[:, 0::2] += np.arange(6)[:, None] * span[2]
    start, goal = np.array([span[0] - 10.0, 200.0]), np.array([span[1] + 120.0, 200.0])
    cost.parts(X, start=start, t0=t0, goal=goal)
    return _assert_same(got[0])


def _standing_world(seed, shapes=180, movers=6):
    """Many standing shapes of every sort (convex and star-shaped polygons of several sizes,
    circles, one long wall) and a few movers."""
    rng = np.random.default_rng([17, seed])
    obstacles = []
    for j in range(shapes):
        c = rng.uniform(20, SIZE - 20, 2)
        r = float(rng.choice([3.0, 8.0, 20.0]))
        obstacles.append(
            {"shape": "circle", "center": c.round(3).tolist(), "radius": r}
            if j % 4 == 0
            else {"shape": "polygon", "vertices": _polygon(rng, c, r)}
        )
    obstacles.append(
        {"shape": "polygon", "vertices": [[50, 190], [350, 196], [350, 200], [50, 194]]}
    )
    for _ in range(movers):
        c = rng.uniform(70, SIZE - 70, 2)
        obstacles.append({"shape": "circle", "center": c.round(3).tolist(), "radius": 6.0,
                          "motion": _motion(rng, "constant_velocity")})  # fmt: skip
    spec = {"schema_version": 1, "seed": seed, "width": SIZE, "height": SIZE,
            "start": [10.0, 10.0], "goal": [SIZE - 10.0, SIZE - 10.0],
            "obstacles": obstacles}  # fmt: skip
    return scenario_from_dict(spec)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("mode", ["spacetime", "snapshot"])
def test_the_standing_obstacles_grid_gives_the_counts_of_the_full_pass(seed, mode):
    # past INDEX_STANDING standing shapes the kernel measures each one only against the
    # segments near it (kernel.static_index); every output equals the pass over all of them
    from mawdo.planning.refine.kernel.constants import INDEX_STANDING

    sc = _standing_world(seed)
    assert len(sc.obstacles) > INDEX_STANDING
    cost = PathCost(sc, mode=mode, clearance=0.5)
    got, kernel = [], cost._kernel
    cost._kernel = lambda *a: (got.append(a), kernel(*a))
    rng = np.random.default_rng([seed, 2])
    for t0 in (0.0, 9.5):
        for n in (1, 40, 300):
            cost.parts(_population(rng, n), start=np.array([10.0, 10.0]), t0=t0)
    hits = 0
    for args in got:
        want = _assert_same(args)
        hits += int(want[2].sum())
        X = args[0].copy()  # NaN and out-of-range blocks take the full pass
        X[0, 3] = np.nan
        _assert_same((X, *args[1:]))
    assert hits > 1000


def test_standing_shapes_at_the_edge_of_their_reach_are_measured():
    # standing circles whose centres lie within a pixel of the hit distance from a flat
    # population: a grid that left out a segment near its square's edge would lose hits
    from mawdo.planning.refine.kernel.constants import INDEX_STANDING

    rng = np.random.default_rng(8)
    r_disc, rho = 5.0, 5.0 + 4.0 + 0.5  # disc radius + robot radius + clearance
    obstacles = []
    for _ in range(INDEX_STANDING + 40):
        side, d = rng.choice([-1.0, 1.0]), rho + rng.uniform(-1.0, 1.0)
        c = [float(rng.uniform(30, SIZE - 30)), 200.0 + side * d]
        obstacles.append({"shape": "circle", "center": c, "radius": r_disc})
    want = _flat_call(obstacles, "snapshot", (40.0, 250.0, 3.0), t0=0.0)
    assert want[2].min() > 0  # the discs within reach do hit
