"""The scene families where time decides (issue 27) and their earliest arrival T*.

Geometric properties are measured with shapely on the generated scenario (not with the
generators' helpers); T* is checked against the independent checker and against a brute-force
search on a fine time grid (tests/planning/sipp_reference.py).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
import shapely
import shapely.ops

from mawdo.planning import scenario_from_dict
from mawdo.planning.guide.oracle import scenario_optimum
from mawdo.planning.guide.sipp import SafeIntervalGuide
from mawdo.planning.guide.sipp.optimum import dodge_spots, scenario_time_optimum
from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.scenes import (
    TIMED_FAMILIES,
    describe_family,
    generate_scene,
    generate_scenes,
)
from mawdo.planning.world.motion import ConstantVelocity, Patrol
from tests.planning.sipp_reference import grid_earliest_arrival

SEED = 11


@pytest.fixture(scope="module", params=TIMED_FAMILIES)
def family_scenes(request):
    return request.param, generate_scenes(request.param, 3, seed=SEED)


def _statics(sc):
    return [shapely.Polygon(sc.obstacles[i].shape.vertices) for i in sc.static_indices]


def _movers(sc):
    return [sc.obstacles[i] for i in sc.moving_indices]


def _gaps(sc) -> list[float]:
    """Distances between static obstacles that do not touch (pixels)."""
    polys = _statics(sc)
    d = [a.distance(b) for a, b in itertools.combinations(polys, 2)]
    return [x for x in d if x > 1e-9]


def test_reproducible_from_the_seed(family_scenes):
    fam, scenes = family_scenes
    again = generate_scene(fam, 1, seed=SEED)
    assert again.to_toml() == scenes[1].to_toml()
    assert again.t_star == scenes[1].t_star
    other = generate_scene(fam, 1, seed=SEED + 1)
    assert other.to_toml() != scenes[1].to_toml()
    # T* is the search on the scene's scenario and spots, nothing else
    again = scenario_time_optimum(scenes[1].scenario, spots=scenes[1].spots)
    assert again.t_star == scenes[1].t_star
    assert describe_family(fam).startswith(f"{fam}: ") and "lattice = 6" in describe_family(fam)


def test_valid_scenes_have_t_star_and_a_clean_route(family_scenes):
    _, scenes = family_scenes
    for scene in scenes:
        sc, v = scene.scenario, scene.scenario.robot_speed
        assert scene.t_star is not None and math.isfinite(scene.t_star)
        # no timed route beats the static optimum driven at full speed
        assert scene.t_star >= scene.l_star / v - 1e-9
        route = scene.time_route
        assert route.arrival == scene.t_star
        np.testing.assert_allclose(route.points[[0, -1]], [sc.start, sc.goal])
        # never faster than the robot's speed
        step = np.hypot(*np.diff(route.points, axis=0).T)
        assert np.all(step <= v * np.diff(route.times) + 1e-6)
        rep = check_trajectory(route.points, sc, times=route.times)
        assert rep.ok, rep.describe()
        assert f"T*={scene.t_star:.6f}" in sc.spec.description


def test_geometry_varies_with_the_seed(family_scenes):
    """Scenes of one family differ in layout, not only in the movers."""
    _, scenes = family_scenes
    starts = {tuple(np.round(s.scenario.start, 3)) for s in scenes}
    sizes = {round(s.l_star, 3) for s in scenes}
    assert len(starts) == len(scenes) and len(sizes) == len(scenes)


def test_slalom_gaps_within_a_pixel_of_the_diameter():
    for scene in generate_scenes("slalom", 3, seed=SEED):
        sc = scene.scenario
        polys = _statics(sc)
        walls = len(polys) // 2
        assert 2 <= walls <= 4 and len(polys) == 2 * walls
        # each wall's two pieces are each other's nearest: the gap
        nearest = [min(p.distance(q) for q in polys if q is not p) for p in polys]
        d = 2 * sc.robot_radius
        assert all(d < g <= d + 1.0 + 1e-9 for g in nearest), nearest
        assert len(_movers(sc)) >= 1


def test_crowd_has_30_to_60_small_movers_at_constant_velocity():
    for scene in generate_scenes("crowd", 3, seed=SEED):
        sc = scene.scenario
        movers = _movers(sc)
        assert 30 <= len(movers) <= 60
        assert all(isinstance(o.motion, ConstantVelocity) for o in movers)
        assert all(o.shape.radius <= 1.25 * sc.robot_radius + 1e-9 for o in movers)


def test_chaser_is_faster_than_the_robot_and_comes_from_behind():
    for scene in generate_scenes("chaser", 3, seed=SEED):
        sc = scene.scenario
        d = (sc.goal - sc.start) / np.hypot(*(sc.goal - sc.start))
        for o in _movers(sc):
            vel = np.asarray(o.motion.velocity)
            assert np.hypot(*vel) > sc.robot_speed
            assert vel @ d > 0.99 * np.hypot(*vel)  # along the robot's line, same way
            assert (np.asarray(o.shape.center) - sc.start) @ d < 0  # behind the start


def _lane_blocked_by(sc, radius: float) -> bool:
    """A disc of ``radius`` in the corridor's middle leaves less than a robot diameter beside
    it: the corridor's width is the least distance between its two walls."""
    width = min(_gaps(sc))
    return (width - 2 * radius) / 2 < 2 * sc.robot_radius


def test_corridor_has_bays_and_oncoming_traffic_that_fills_it():
    for scene in generate_scenes("corridor", 3, seed=SEED):
        sc = scene.scenario
        d = sc.goal - sc.start
        # two walls, each bay adds a piece beside it and a cap behind it
        assert len(_statics(sc)) >= 4 and len(_statics(sc)) % 2 == 0
        movers = _movers(sc)
        assert 1 <= len(movers) <= 2
        for o in movers:
            assert np.asarray(o.motion.velocity) @ d < 0  # toward the start
            assert _lane_blocked_by(sc, o.shape.radius)
        # the static route alone is not safe: time decides
        assert scene.t_star > scene.l_star / sc.robot_speed + 1.0


def test_corridor_robot_waits_in_a_bay():
    """In at least one of a few corridors the optimal route stands still at a bay spot."""
    waits = []
    for scene in generate_scenes("corridor", 3, seed=SEED):
        r = scene.time_route
        same = np.all(r.points[1:] == r.points[:-1], axis=1)
        spots = {tuple(p) for p in scene.spots}
        waits += [tuple(p) in spots for p in r.points[1:][same]]
    assert any(waits)


def test_parked_mover_stops_in_the_corridor_then_leaves():
    for scene in generate_scenes("parked", 3, seed=SEED):
        sc = scene.scenario
        (car,) = [o for o in _movers(sc) if isinstance(o.motion, Patrol)]
        dwell = car.motion.waits[0]
        t = np.linspace(0.0, dwell, 50)
        np.testing.assert_array_equal(car.offset(t), np.zeros((50, 2)))
        assert _lane_blocked_by(sc, car.shape.radius)
        # then it drives off and stays away for longer than any run
        gone = dwell + car.motion.period / 1e3
        later = car.offset(np.array([gone, gone + 1e3]))
        assert np.hypot(*later[0]) > car.shape.radius and np.all(later[0] == later[1])
        # blocked at t = 0 (the disc as a static obstacle leaves no static route) ...
        frozen = sc.to_dict()
        frozen["obstacles"][car.index].pop("motion")
        frozen.pop("spots")  # a waiting spot in the corridor lies under the now static disc
        assert not scenario_optimum(scenario_from_dict(frozen)).reachable
        # ... so the robot waits, then goes
        assert scene.time_route.waiting > 0.0
        assert scene.t_star > scene.l_star / sc.robot_speed + 1.0


def test_doorway_patrol_crosses_the_only_door():
    for scene in generate_scenes("doorway", 3, seed=SEED):
        sc = scene.scenario
        a, b = _statics(sc)
        door = min(_gaps(sc))
        r = sc.robot_radius
        assert 2 * 1.2 * r - 1e-9 <= door <= 2 * 2.0 * r + 1e-9
        mid = np.mean([[p.x, p.y] for p in shapely.ops.nearest_points(a, b)], axis=0)
        (patrol,) = _movers(sc)
        t = np.linspace(0.0, patrol.motion.period, 400)
        centre = np.asarray(patrol.shape.center) + patrol.offset(t)
        # over a lap it covers the door for a robot standing in it
        assert np.min(np.hypot(*(centre - mid).T)) < patrol.shape.radius + r


def test_lattice_parameter_and_bad_params():
    scene = generate_scene("doorway", 0, seed=SEED, params={"lattice": 0})
    # no lattice: only the dodge spots along the static optimum (a doorway has no bays)
    np.testing.assert_array_equal(scene.spots, dodge_spots(scene.optimum, scene.scenario))
    assert len(scene.spots) > 0 and math.isfinite(scene.t_star)
    with pytest.raises(ValueError, match="speed_min"):
        generate_scene("corridor", 0, params={"speed_min": 0.9, "speed_max": 0.5})
    with pytest.raises(ValueError, match="slack_max"):
        generate_scene("slalom", 0, params={"slack_max": 1.5})


# ---------------------------------------------------------------------------------------------
# T* against brute force on a time grid


def _box(x0, y0, x1, y1):
    return {"shape": "polygon", "vertices": [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]}


def _small(seed, walker=False, parked=False):
    rng = np.random.default_rng(seed)
    c = rng.uniform(35, 60, 2)
    obs = [_box(*c, *(c + rng.uniform(8, 16, 2)))]
    for j in range(3):
        motion = {"velocity": list(rng.uniform(-1.5, 1.5, 2))}
        if walker and j == 0:
            motion = {"model": "bounded_random_walk", "step": 1.0, "hold": 4}
        centre = list(rng.uniform(25, 65, 2))
        if parked and j == 1:  # parked on the diagonal for 15 steps, then off to the side
            motion = {"model": "patrol", "waypoints": [[18.0, -18.0]], "speed": 1.0}
            motion["waits"], centre = [15.0, 1e4], [45.0, 45.0]
        obs.append(
            {
                "shape": "circle",
                "center": centre,
                "radius": float(rng.uniform(4, 7)),
                "motion": motion,
            }
        )
    data = {
        "schema_version": 1,
        "seed": seed,
        "width": 90.0,
        "height": 90.0,
        "start": [6.0, 6.0],
        "goal": [84.0, 84.0],
        "robot": {"radius": 2.0, "speed": 2.0},
        "obstacles": obs,
    }
    return scenario_from_dict(data)


def _grid(sc, walkers, h, segments):
    """T* and the grid search's earliest arrival on the same graph (no clearance)."""
    opt = scenario_time_optimum(sc, walkers=walkers, horizon=120.0, segments=segments)
    guide = SafeIntervalGuide(sc, clearance=0.0, horizon=120.0, walkers=walkers, segments=segments)
    edges = [
        (u, int(guide.indices[e]), float(guide.weights[e]))
        for u in range(len(guide.nodes))
        for e in range(guide.indptr[u], guide.indptr[u + 1])
    ]
    K = int(np.ceil((opt.t_star + h * len(opt.route.states)) / h)) + 1
    return opt, grid_earliest_arrival(sc, guide.nodes, edges, guide.start, 0, h, K, 0.0)


@pytest.mark.parametrize(
    ("seed", "walker", "parked"), [(5, False, False), (2, False, True), (9, True, False)]
)
def test_t_star_matches_time_grid_search(seed, walker, parked):
    """Same earliest arrival within the grid step per move: continuous waiting can only help
    (T* <= grid), and SIPP's route delayed to grid departures is one of the grid's. The seeds
    are scenes where the movers decide (T* at least 3 steps over the static optimum's time):
    bouncing discs; a disc parked on the diagonal; a seeded random walker (taken as known)."""
    sc = _small(seed, walker, parked)
    h = 0.5
    opt, grid = _grid(sc, "known", h, segments=8)
    assert opt.reachable
    assert opt.t_star > scenario_optimum(sc).length / sc.robot_speed + 3.0
    assert opt.t_star <= grid + 1e-6
    assert grid - opt.t_star <= h * (len(opt.route.states) - 1)


def test_reachable_walkers_are_conservative():
    sc = _small(1, walker=True)
    known = scenario_time_optimum(sc, walkers="known", horizon=120.0, segments=8)
    reach = scenario_time_optimum(sc, walkers="reachable", horizon=120.0, segments=8)
    assert known.reachable
    assert not reach.reachable or reach.t_star >= known.t_star - 1e-9
    # the reachable-set route is clean against the walk the checker sees
    if reach.reachable:
        assert check_trajectory(reach.route.points, sc, times=reach.route.times).ok


def test_dodge_spots_by_hand():
    """A 100 px route along y = 50 on an empty map, robot radius 2: every 12 px the point and
    points 5 and 12 px to either side; a square at (60..70, 55..75) removes those within 3 px."""
    sc = scenario_from_dict(
        {
            "schema_version": 1,
            "width": 120.0,
            "height": 100.0,
            "start": [10.0, 50.0],
            "goal": [110.0, 50.0],
            "robot": {"radius": 2.0, "speed": 2.0},
            "obstacles": [_box(60, 55, 70, 75)],
        }
    )
    pts = dodge_spots([[10.0, 50.0], [110.0, 50.0]], sc)
    xs = 10.0 + 12.0 * np.arange(1, 9)  # 22 .. 106
    grid = {(x, 50.0 + o) for x in xs for o in (-12.0, -5.0, 0.0, 5.0, 12.0)}
    gone = {(x, y) for x, y in grid if 57.0 <= x <= 73.0 and y >= 52.0}  # near the square
    assert {tuple(np.round(p, 9)) for p in pts} == grid - gone
    assert gone  # the square did remove some


def test_no_route_within_the_horizon_is_reported():
    sc = _small(0)
    opt = scenario_time_optimum(sc, horizon=5.0)
    assert not opt.reachable and opt.steps == -1 and "horizon" in opt.reason
    assert opt.t_star == math.inf


# ---------------------------------------------------------------------------------------------
# patrols that stop (the parked mover's motion)


def test_patrol_waits_by_hand():
    """Route (0, 0) -> (10, 0) at 2 px/step, 3 steps at the start, 4 at the far end: stands
    until t = 3, arrives at t = 8, leaves at t = 12, is back at t = 17 (the period)."""
    m = Patrol(np.array([[0.0, 0.0], [10.0, 0.0]]), 2.0, np.array([3.0, 4.0]))
    assert m.period == 17.0
    t = np.array([0.0, 2.0, 3.0, 4.0, 8.0, 10.0, 12.0, 14.5, 17.0, 20.0, 21.0])
    x = np.array([0.0, 0.0, 0.0, 2.0, 10.0, 10.0, 10.0, 5.0, 0.0, 0.0, 2.0])
    np.testing.assert_allclose(m.offset(t), np.column_stack([x, np.zeros_like(x)]))
    times, _ = m.knots(0.0, 20.0)
    np.testing.assert_allclose(times, [0.0, 3.0, 8.0, 12.0, 17.0, 20.0])


def _patrol_scene(motion):
    return scenario_from_dict(
        {
            "schema_version": 1,
            "start": [10.0, 10.0],
            "goal": [300.0, 300.0],
            "obstacles": [{"shape": "circle", "center": [100, 100], "radius": 5, "motion": motion}],
        }
    )


def test_patrol_waits_in_a_scenario_and_back_and_forth():
    """Back and forth retraces the waits: at 0 for [0, 2], leg to 20 [2, 7], at 20 [7, 12],
    leg to 40 [12, 17], at 40 [17, 18], leg to 20 [18, 23], at 20 [23, 28], leg to 0 [28, 33]."""
    motion = {
        "model": "patrol",
        "waypoints": [[20.0, 0.0], [40.0, 0.0]],
        "speed": 4.0,
        "cycle": "back_and_forth",
        "waits": [2.0, 5.0, 1.0],
    }
    (ob,) = _patrol_scene(motion).obstacles
    assert ob.motion.period == 2 + 5 + 5 + 5 + 1 + 5 + 5 + 5
    t = np.array([1.0, 7.0, 10.0, 13.5, 17.5, 22.0, 30.0, 34.0])
    x = np.array([0.0, 20.0, 20.0, 26.0, 40.0, 24.0, 12.0, 0.0])
    np.testing.assert_allclose(ob.offset(t)[:, 0], x)
    with pytest.raises(ValueError, match=r"motion\.waits.*needs 3 times"):
        _patrol_scene({**motion, "waits": [1.0, 2.0]})
    with pytest.raises(ValueError, match="waits"):
        _patrol_scene({**motion, "waits": [1.0, -2.0, 1.0]})
