"""The Numba cost kernel against a plain shapely computation, hand cases and the API."""

import numpy as np
import pytest

from mawdo.planning import (
    CostWeights,
    PathCost,
    assemble_paths,
    get_scenario,
    scenario_from_dict,
    scenario_optimum,
)

from .reference import border_hits, paths_from, reference_parts


def resample(path, m):
    """m points evenly spaced in arc length strictly between the ends of ``path``."""
    cum = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(path, axis=0).T))])
    u = np.linspace(0.0, cum[-1], m + 2)[1:-1]
    return np.column_stack([np.interp(u, cum, path[:, 0]), np.interp(u, cum, path[:, 1])]).ravel()


def candidates(sc, rng, n_uniform=700, n_near=700, n_dup=100, t0=0.0):
    """Uniform paths (crossing many obstacles), jittered optimal paths (near misses and
    grazing hits) and paths with repeated waypoints (zero-length segments)."""
    W, H = sc.width, sc.height
    uniform = rng.uniform(0, 1, (n_uniform, 40)) * np.tile([W, H], 20)
    # the optimum for a fatter robot among all obstacles frozen at t0 keeps ~3 px of
    # clearance, so small jitter can miss
    fat = scenario_from_dict({**sc.to_dict(), "robot": {"radius": sc.robot_radius + 3.0}})
    base = resample(scenario_optimum(fat, t=t0, static_only=False).path, 20)
    sigma = rng.choice([0.3, 1.0, 3.0, 8.0, 20.0], size=(n_near, 1))
    near = np.clip(base + rng.normal(0, 1, (n_near, 40)) * sigma, 0, np.tile([W, H], 20))
    dup = near[:n_dup].reshape(n_dup, 20, 2).copy()
    dup[:, 1::3] = dup[:, 0::3][:, : dup[:, 1::3].shape[1]]
    dup[:, 5] = dup[:, 4]
    return np.vstack([uniform, near, dup.reshape(n_dup, 40)])


def assert_matches_reference(sc, X, mode, t0, start):
    length, ncol, turning = PathCost(sc, mode=mode).parts(X, start=start, t0=t0)
    ref_len, ref_ncol, ref_turn, ambiguous = reference_parts(sc, X, start, mode, t0)
    np.testing.assert_allclose(length, ref_len, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(turning, ref_turn, atol=1e-6)
    assert ambiguous.mean() < 0.01  # tangency cases are rare; they are left out below
    keep = ~ambiguous
    mismatch = np.nonzero(ncol[keep] != ref_ncol[keep])[0]
    assert mismatch.size == 0, (mode, t0, mismatch[:10], ncol[keep][mismatch[:10]])
    # the sample exercises both outcomes (with obstacles: most off-map paths leave the map)
    obstacle = ref_ncol - border_hits(sc, paths_from(X, start, sc.goal))
    assert np.any(obstacle <= 1) and np.any(obstacle > 3)
    return ref_ncol


@pytest.mark.parametrize("mode", ["snapshot", "spacetime"])
@pytest.mark.parametrize(("t0", "start"), [(0.0, None), (17.25, (100.0, 30.0))])
def test_kernel_equals_shapely_on_the_paper_scenario(mode, t0, start):
    sc = get_scenario("paper")
    rng = np.random.default_rng(7)
    X = candidates(sc, rng, t0=t0)
    s = sc.start if start is None else np.asarray(start)
    assert_matches_reference(sc, X, mode, t0, s)


NONCONVEX = {
    "schema_version": 1,
    "seed": 3,
    "width": 300.0,
    "height": 200.0,
    "start": [10.0, 10.0],
    "goal": [290.0, 190.0],
    "robot": {"radius": 0.0, "speed": 3.0},
    "obstacles": [
        {  # static star (non-convex)
            "shape": "polygon",
            "vertices": [
                [150, 60], [160, 85], [190, 90], [165, 105], [175, 135],
                [150, 115], [125, 135], [135, 105], [110, 90], [140, 85],
            ],
        },
        {  # moving U shape (non-convex), patrols back and forth
            "shape": "polygon",
            "vertices": [[40, 120], [90, 120], [90, 170], [75, 170], [75, 135], [55, 135],
                         [55, 170], [40, 170]],
            "motion": {"model": "patrol", "waypoints": [[60, -40], [150, 0]], "speed": 2.5,
                       "cycle": "back_and_forth"},
        },
        {
            "shape": "circle",
            "center": [220, 60],
            "radius": 18,
            "motion": {"model": "bounded_random_walk", "step": 3.0, "hold": 1},
        },
        {
            "shape": "polygon",
            "vertices": [[230, 150], [260, 140], [250, 175]],
            "motion": {"velocity": [-2.2, -1.1]},
        },
    ],
}  # fmt: skip


@pytest.mark.parametrize("radius", [0.0, 2.5])
@pytest.mark.parametrize("mode", ["snapshot", "spacetime"])
def test_kernel_equals_shapely_with_nonconvex_moving_polygons(radius, mode):
    data = {**NONCONVEX, "robot": {"radius": radius, "speed": 3.0}}
    sc = scenario_from_dict(data)
    rng = np.random.default_rng(11)
    X = candidates(sc, rng, n_uniform=600, n_near=600, n_dup=50, t0=4.5)
    ref = assert_matches_reference(sc, X, mode, 4.5, sc.start)
    assert ref.max() >= 8


def empty(width=100.0, height=100.0, start=(1.0, 1.0), goal=(99.0, 1.0), radius=1.0, **extra):
    data = {"schema_version": 1, "width": width, "height": height, "start": list(start),
            "goal": list(goal), "robot": {"radius": radius, "speed": 4.0}}  # fmt: skip
    return scenario_from_dict({**data, **extra})


def test_hand_computed_length_and_turning():
    sc = empty(start=(0, 0), goal=(0, 10), radius=0.0)  # a point robot may run on the border
    cost = PathCost(sc, n_waypoints=2)
    # 0,0 -> 10,0 -> 10,10 -> 0,10: three sides of a square, two right-angle turns
    length, ncol, turning = cost.parts(np.array([10.0, 0.0, 10.0, 10.0]))
    assert length == pytest.approx(30.0) and ncol == 0 and turning == pytest.approx(np.pi)
    # collinear waypoints: no turning; a reversal turns by pi
    _, _, straight = cost.parts(np.array([0.0, 3.0, 0.0, 6.0]))
    assert straight == pytest.approx(0.0, abs=1e-12)
    _, _, back = cost.parts(np.array([0.0, 5.0, 0.0, 2.0]))
    assert back == pytest.approx(2 * np.pi)


def test_zero_length_segments_neither_add_nor_hide_turning():
    sc = empty(start=(0, 0), goal=(20, 20), radius=0.0)
    one = PathCost(sc, n_waypoints=1).parts(np.array([20.0, 0.0]))
    dup = PathCost(sc, n_waypoints=3).parts(np.array([20.0, 0.0, 20.0, 0.0, 20.0, 0.0]))
    at_start = PathCost(sc, n_waypoints=2).parts(np.array([0.0, 0.0, 20.0, 0.0]))
    for parts in (dup, at_start):
        assert parts[0] == pytest.approx(one[0]) and parts[2] == pytest.approx(one[2])
    assert one[2] == pytest.approx(np.pi / 2)


BOX = {"shape": "polygon", "vertices": [[30, 30], [70, 30], [70, 70], [30, 70]]}


def test_a_segment_wholly_inside_an_obstacle_counts():
    sc = empty(start=(1, 1), goal=(99, 99), obstacles=[BOX])
    cost = PathCost(sc, n_waypoints=2)
    # segments: start->(40,40) enters, (40,40)->(60,60) lies inside, (60,60)->goal leaves
    assert cost.parts(np.array([40.0, 40.0, 60.0, 60.0]))[1] == 3
    # passing at distance 0.5 < r = 1 from the edge is a hit; at 1.5 it is not
    assert cost.parts(np.array([1.0, 29.5, 99.0, 29.5]))[1] == 1
    assert cost.parts(np.array([1.0, 28.5, 99.0, 28.5]))[1] == 0
    # near a corner the inflated shape is round: a vertex at (71, 71) is 1.41 px from the
    # corner (70, 70), outside; at (70.6, 70.6) it is 0.85 px away, inside (both segments hit)
    side = empty(start=(99, 1), goal=(99, 99), obstacles=[BOX])
    one = PathCost(side, n_waypoints=1)
    assert one.parts(np.array([71.0, 71.0]))[1] == 0
    assert one.parts(np.array([70.6, 70.6]))[1] == 2


def test_total_cost_combines_the_parts_with_the_weights():
    sc = empty(start=(1, 1), goal=(99, 99), obstacles=[BOX])
    w = CostWeights(alpha=0.5, beta=0.2, lam=0.3, k=10.0)
    cost = PathCost(sc, weights=w, n_waypoints=2)
    X = np.array([[40.0, 40.0, 60.0, 60.0], [0.0, 50.0, 50.0, 100.0], [10.0, 80.0, 90.0, 20.0]])
    length, ncol, turning = cost.parts(X)
    np.testing.assert_allclose(cost(X), 0.5 * length + 0.2 * 10.0 * ncol**4 + 0.3 * turning)


def test_spacetime_sees_an_obstacle_that_snapshot_misses_and_vice_versa():
    # a circle rising at 2 px/step crosses the robot's line y = 100 at t = 35
    mover = {"shape": "circle", "center": [100, 30], "radius": 10, "motion": {"velocity": [0, 2]}}
    sc = empty(width=200, height=200, start=(10, 100), goal=(190, 100), obstacles=[mover])
    X = np.linspace(sc.start, sc.goal, 22)[1:-1].ravel()  # straight line; x = 100 at 22.5 px/4
    snap = PathCost(sc, mode="snapshot")
    st = PathCost(sc, mode="spacetime")
    # at t0 = 0 the robot passes x = 100 at t = 22.5, the obstacle is at y = 75 then: clear
    assert st.parts(X, t0=0.0)[1] == 0
    # ... but frozen at t0 = 35 the obstacle sits on the line
    assert snap.parts(X, t0=35.0)[1] >= 1
    # leaving at t0 = 13 the robot meets it (it is at y = 101 at t = 35.5)
    assert st.parts(X, t0=13.0)[1] >= 1
    # frozen at t0 = 0 it is far below the line
    assert snap.parts(X, t0=0.0)[1] == 0


def test_snapshot_and_spacetime_agree_without_moving_obstacles():
    sc = empty(start=(1, 1), goal=(99, 99), obstacles=[BOX])
    X = np.random.default_rng(0).uniform(0, 100, (300, 40))
    a = PathCost(sc, mode="snapshot").parts(X, t0=3.0)
    b = PathCost(sc, mode="spacetime").parts(X, t0=3.0)
    for x, y in zip(a, b, strict=True):
        np.testing.assert_array_equal(x, y)


def test_motion_table_reuse_across_calls_gives_fresh_results():
    sc = get_scenario("paper")
    X = candidates(sc, np.random.default_rng(3), 200, 200, 0)
    reused = PathCost(sc, mode="spacetime")
    for t0 in (0.0, 40.0, 41.5, 300.0, 2.0):
        expect = PathCost(sc, mode="spacetime").parts(X, t0=t0)
        got = reused.parts(X, t0=t0)
        np.testing.assert_array_equal(got[1], expect[1])


def test_default_weights_rank_every_collision_free_path_first():
    sc = get_scenario("paper")
    w = CostWeights()
    assert w.alpha + w.beta + w.lam == pytest.approx(1.0)
    assert w.dominates(sc.width, sc.height, 20)
    assert not CostWeights(0.45, 0.1, 0.45, k=100.0).dominates(sc.width, sc.height, 20)
    cost = PathCost(sc)
    X = candidates(sc, np.random.default_rng(5))
    f = cost(X)
    ncol = cost.parts(X)[1]
    assert np.any(ncol == 0) and np.any(ncol == 1)
    assert f[ncol == 0].max() < f[ncol > 0].min()
    # and fewer collisions rank better among the rest
    assert f[ncol == 1].max() < f[ncol >= 2].min()


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"alpha": 0.5, "beta": 0.5, "lam": 0.5}, "must equal 1"),
        ({"alpha": 1.2, "beta": -0.2, "lam": 0.0}, "beta must be finite and >= 0"),
        ({"k": -1.0}, "k must be finite and >= 0"),
        ({"k": float("nan")}, "k must be finite"),
    ],
)
def test_bad_weights(kwargs, fragment):
    with pytest.raises(ValueError, match=fragment):
        CostWeights(**kwargs)


def test_api_shapes_and_errors():
    sc = get_scenario("paper")
    cost = PathCost(sc, mode="spacetime")
    assert cost.dim == 40
    lb, ub = cost.bounds
    assert lb.shape == ub.shape == (40,) and ub[0] == 366 and ub[1] == 366
    x = resample(scenario_optimum(sc).path, 20)
    single = cost(x)
    assert np.ndim(single) == 0 and single == cost(x[None])[0]
    assert cost(np.empty((0, 40))).shape == (0,)
    with pytest.raises(ValueError, match=r"shape \(n, 40\)"):
        cost(np.zeros((3, 38)))
    with pytest.raises(ValueError, match="start must be"):
        cost(x, start=(1.0, 2.0, 3.0))
    with pytest.raises(ValueError, match="t0 must be"):
        cost(x, t0=-1.0)
    for bad in (np.nan, np.inf):  # each end and t0, each coordinate
        with pytest.raises(ValueError, match="start must be a finite"):
            cost(x, start=(20.0, bad))
        with pytest.raises(ValueError, match="start must be a finite"):
            cost(x, start=(bad, 20.0))
        with pytest.raises(ValueError, match="goal must be a finite"):
            cost.parts(x[None], goal=(bad, 300.0))
        with pytest.raises(ValueError, match="t0 must be"):
            cost(x, t0=bad)
    with pytest.raises(ValueError, match="mode must be one of"):
        PathCost(sc, mode="frozen")
    with pytest.raises(ValueError, match="n_waypoints"):
        PathCost(sc, n_waypoints=0)
    with pytest.raises(TypeError, match="CostWeights"):
        PathCost(sc, weights=(0.3, 0.3, 0.4))


def test_nan_candidates_get_nan_and_leave_the_others_alone():
    sc = get_scenario("paper")
    X = candidates(sc, np.random.default_rng(2), 5, 5, 0)
    for mode in ("snapshot", "spacetime"):
        cost = PathCost(sc, mode=mode)
        clean = cost(X)
        X2 = X.copy()
        X2[3, 7] = np.nan
        out = cost(X2)
        assert np.isnan(out[3])
        np.testing.assert_array_equal(np.delete(out, 3), np.delete(clean, 3))
        # a batch with no finite coordinate at all still evaluates (to NaN), no exception
        assert np.isnan(cost(np.full((2, X.shape[1]), np.nan))).all()


def test_assemble_paths():
    P = assemble_paths(np.arange(8.0).reshape(2, 4), (0, 0), (9, 9))
    assert P.shape == (2, 4, 2)
    np.testing.assert_array_equal(P[1], [[0, 0], [4, 5], [6, 7], [9, 9]])


def test_spacetime_takes_paths_up_to_one_map_size_off_the_map_and_refuses_farther():
    # a coordinate of 1e4 px on the 366 px map once asked for a 6 GiB motion table
    sc = get_scenario("paper")
    rng = np.random.default_rng(11)
    X = rng.uniform(-366.0, 732.0, (120, 40))  # the whole allowed range, edges included
    X[0, 0], X[1, 1] = -366.0, 732.0
    X[100:, 0::2] = rng.uniform(-366.0, -40.0, (20, 20))  # mostly west of the map: few hits
    assert_matches_reference(sc, X, "spacetime", 3.0, sc.start)
    cost = PathCost(sc, mode="spacetime")
    far = X.copy()
    far[20, 5] = 1e4
    with pytest.raises(
        ValueError,
        match=r"candidate coordinate is 10000 px, more than one map size outside .*bounds",
    ):
        cost.parts(far, t0=3.0)
    with pytest.raises(ValueError, match=r"start or goal is -400 px, more than one map size"):
        cost.parts(X, start=(-400.0, 20.0), t0=3.0)
    # snapshot mode tabulates nothing and takes any finite coordinate; other rows keep theirs
    far[20, 5] = 1e12
    snap = PathCost(sc).parts(far, t0=3.0)
    keep = np.arange(120) != 20
    for got, ref in zip(snap, PathCost(sc).parts(X[keep], t0=3.0), strict=True):
        np.testing.assert_array_equal(got[keep], ref)
