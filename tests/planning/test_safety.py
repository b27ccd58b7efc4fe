"""The safety contract and the topological guide, on our own map families (tests/planning/maps)."""

import numpy as np
import pytest
import shapely

from mawdo.optimizers import OPTIMIZERS
from mawdo.planning import get_scenario
from mawdo.planning.guide.homotopy import GUIDE_SEGMENTS, SLACK, Guide, winding
from mawdo.planning.guide.oracle import shortest_path
from mawdo.planning.guide.visgraph import build
from mawdo.planning.judge.check import check_static_path, check_trajectory
from mawdo.planning.run.planner import plan
from mawdo.planning.safety.guard import Elite, Guard
from mawdo.planning.world.geometry import inflate

from . import maps
from .reference_oracle import brute_force_length

ALGORITHMS = list(OPTIMIZERS)


def assert_contract(res):
    """Success only with the checker's approval; the result's own verdict is the checker's."""
    rep = check_trajectory(res.route, res.scenario, times=res.route_times)
    assert res.collision_free == rep.ok
    if res.success:
        assert rep.ok, f"success with checker collisions {rep.collisions[:3]}"
        assert np.allclose(res.route[-1], res.scenario.goal)
    step = np.hypot(*np.diff(res.trajectory, axis=0).T)
    assert np.all(step <= res.scenario.robot_speed + 1e-9)
    return rep


# -- the oracle -----------------------------------------------------------------------------


def _random_polygons(rng, k):
    out = []
    for _ in range(k):
        c = rng.uniform(10, 356, 2)
        ang = np.sort(rng.uniform(0, 2 * np.pi, int(rng.integers(3, 7))))
        rad = rng.uniform(5, 40, len(ang))
        p = shapely.Polygon(c + np.c_[rad * np.cos(ang), rad * np.sin(ang)])
        out.append(p if p.is_valid else p.convex_hull)
    return out


@pytest.mark.parametrize("seed", range(6))
def test_tangent_graph_equals_the_all_pairs_reference(seed):
    # overlapping polygons, polygons crossing the border, unreachable goals all occur here
    rng = np.random.default_rng(seed)
    obs = [p.buffer(4, quad_segs=4) for p in _random_polygons(rng, 25)]
    for _ in range(3):
        s, g = rng.uniform(0, 366, 2), rng.uniform(0, 366, 2)
        res = shortest_path(s, g, obs, (0, 0, 366, 366))
        if res.reason != "ok" and "inside" in res.reason:
            continue
        ref = brute_force_length(s, g, obs, (0, 0, 366, 366))
        assert res.length == pytest.approx(ref, rel=1e-9, abs=1e-9) or res.length == ref == np.inf


def test_node_limit_is_a_clear_error_not_a_dense_matrix():
    obs = [shapely.box(x, y, x + 2, y + 2) for x in range(5, 360, 6) for y in range(5, 360, 6)]
    assert len(obs) > 3000
    with pytest.raises(ValueError, match="exceed the limit of 1000"):
        build(obs, (0, 0, 366, 366), points=[(1, 1)], max_nodes=1000)


# -- the guide ------------------------------------------------------------------------------


@pytest.mark.parametrize("family", ["u-trap", "rooms", "maze"])
def test_guide_routes_are_free_shortest_first_and_in_distinct_classes(family):
    sc = maps.FAMILIES[family](4)
    guide = Guide(sc, clearance=0.5, k=6)
    routes = guide.routes(sc.start)
    # maze walls leave the border: the free space is simply connected, one class only
    assert len(routes) == 1 if family == "maze" else len(routes) >= 2
    rho = sc.robot_radius + 0.5 + SLACK
    inflated = [inflate(sc.obstacles[i].shape, rho, n=GUIDE_SEGMENTS) for i in sc.static_indices]
    best = shortest_path(sc.start, sc.goal, inflated, sc.bounds)
    lengths = [float(np.hypot(*np.diff(r, axis=0).T).sum()) for r in routes]
    assert lengths[0] == pytest.approx(best.length, rel=1e-9)
    assert lengths == sorted(lengths)
    raw = [sc.obstacles[i].shape for i in sc.static_indices]
    classes = set()
    for r in routes:
        assert np.allclose(r[0], sc.start) and np.allclose(r[-1], sc.goal)
        assert check_static_path(r, raw, radius=sc.robot_radius + 0.5).min_clearance > 0
        w = (winding(r, guide.refs) - winding(routes[0], guide.refs)) / (2 * np.pi)
        assert np.allclose(w, np.round(w), atol=1e-6)  # same ends: whole turns apart
        classes.add(tuple(np.round(w).astype(int)))
    assert len(classes) == len(routes)


def test_guide_re_roots_at_the_robot():
    sc = get_scenario("paper")
    guide = Guide(sc, clearance=0.5, k=4)
    p = np.array([200.0, 60.0])
    r = guide.routes(p)[0]
    rho = sc.robot_radius + 0.5 + SLACK
    inflated = [inflate(sc.obstacles[i].shape, rho, n=GUIDE_SEGMENTS) for i in sc.static_indices]
    ref = brute_force_length(p, sc.goal, inflated, sc.bounds)
    assert np.allclose(r[0], p)
    assert float(np.hypot(*np.diff(r, axis=0).T).sum()) == pytest.approx(ref, rel=1e-9)


# -- elite and guard ------------------------------------------------------------------------


def test_elite_keeps_the_best_distinct_candidates():
    rng = np.random.default_rng(0)
    e = Elite(size=4, min_dist=1.0)
    X = rng.uniform(0, 100, (50, 6))
    f = rng.uniform(0, 1, 50)
    X[1], f[1] = X[0] + 0.1, f[0] + 1e-6  # a near-copy of candidate 0
    for chunk in np.array_split(np.arange(50), 5):
        e.add(X[chunk], f[chunk])
    order = [i for i in np.argsort(f) if i != (1 if f[0] < f[1] else 0)][:4]
    np.testing.assert_array_equal(e.f, f[order])


def test_guard_stretch_agrees_with_the_checker():
    sc = get_scenario("paper")
    guard = Guard(sc, clearance=0.5)
    rng = np.random.default_rng(1)
    for _ in range(60):
        t = float(rng.integers(0, 80))
        p0 = rng.uniform(10, 356, 2)
        route = np.vstack([p0, p0 + rng.normal(0, 6, (3, 2)).cumsum(axis=0)])
        hits = guard.stretch_hits(route, t, 8.0)
        from mawdo.planning.world.path import advance

        end, _, passed, frac = advance(route, 8.0)
        pts = np.vstack([route[:1], passed, end[None]])
        times = t + np.r_[0.0, frac * 2.0, 2.0]  # 8 px at 4 px per step: two steps
        if not np.all(np.isfinite(times)) or np.any(np.diff(times) < 0):
            continue
        clear = check_trajectory(pts, sc, times=times).min_clearance
        if abs(clear - 0.5) < 1e-6:
            continue  # a tangency: either verdict is right
        assert (hits > 0) == (clear < 0.5), (clear, hits)


# -- the planner's contract on our maps -----------------------------------------------------


@pytest.mark.parametrize("family", ["maze", "u-trap"])
@pytest.mark.parametrize("algorithm", ALGORITHMS)
def test_static_single_shot_every_optimizer(family, algorithm):
    sc = maps.FAMILIES[family](1)
    res = plan(sc, algorithm, seed=0, dynamic=False, config="fast")
    rep = assert_contract(res)
    assert res.success, res.reason  # a collision-free route exists
    assert rep.min_clearance >= 0.5 - 1e-6  # the margin holds against static obstacles


@pytest.mark.slow
@pytest.mark.parametrize("family", ["maze", "u-trap", "rooms"])
@pytest.mark.parametrize("algorithm", ALGORITHMS)
def test_dynamic_with_movers_every_optimizer(family, algorithm):
    sc = maps.FAMILIES[family](2, moving=3)
    res = plan(sc, algorithm, seed=1, config="quick")
    assert_contract(res)
    assert res.success, res.reason


@pytest.mark.parametrize("family", ["maze", "u-trap"])
def test_dynamic_with_movers_crossing_corridors(family):
    sc = maps.FAMILIES[family](3, moving=3)
    res = plan(sc, "mawdo", seed=0, config="quick")
    assert_contract(res)
    assert res.success and res.collision_free, res.reason


def test_a_plan_that_collides_is_reported_not_driven():
    # no guide, one iteration, no path-like seeds: the best random plan crosses the walls
    sc = maps.serpentine_maze(0)
    res = plan(
        sc,
        "gwo",
        seed=0,
        dynamic=False,
        config="quick",
        guide_routes=0,
        first_iters=1,
        seed_fraction=0.0,
    )
    assert_contract(res)
    assert not res.success and res.reason.startswith("no collision-free route found")
    assert res.replans[0].collisions > 0 and res.steps == 0


def test_the_only_safe_action_is_to_wait():
    sc = maps.waiting_pocket()
    # driving straight out of the pocket at once hits the door: waiting is needed
    line = sc.start + np.outer(np.arange(12), [sc.robot_speed, 0.0])
    assert not check_trajectory(line, sc).ok
    # the guard alone waits as a fallback (no candidate is safe) ...
    res = plan(sc, "mawdo", seed=0, config="quick", time_guide=False)
    assert_contract(res)
    assert res.success and res.waits >= 1, (res.reason, res.waits)
    # ... the time guide plans the wait: the robot holds its position, then drives out
    timed = plan(sc, "mawdo", seed=0, config="quick")
    assert_contract(timed)
    assert timed.success and timed.collision_free, timed.reason
    held = np.all(np.abs(np.diff(timed.trajectory, axis=0)) < 1e-9, axis=1)
    assert held.any()  # at least one step in place
    assert timed.steps <= res.steps


def test_give_up_after_the_configured_time():
    # the guard's give-up: with no timed route to follow it evades or waits, and stops
    res = plan(
        maps.waiting_pocket(), "mawdo", seed=0, config="quick", give_up_steps=2, time_guide=False
    )
    assert_contract(res)
    assert not res.success and "gave up after 2 steps" in res.reason
    # a planned wait is no stall: with the time guide the same limit does not stop the run
    timed = plan(maps.waiting_pocket(), "mawdo", seed=0, config="quick", give_up_steps=2)
    assert timed.success, timed.reason


def test_walled_in_goal_is_an_honest_failure():
    res = plan(maps.walled_in_goal(), "woa", seed=0, config="quick")
    assert_contract(res)
    assert not res.success and res.reason.startswith("no collision-free route found")
    assert res.collision_free and res.steps == 0
