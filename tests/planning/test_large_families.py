"""The scene families at scale (``crowd-large``, ``warehouse-large``): seeded, valid, exact L*,
consistent T*, and what each family promises.

Validity is measured here with shapely on the raw shapes and with the independent checker;
``L*`` is recomputed by the brute-force visibility graph of ``tests/planning/reference_oracle.py``
(every node pair tested with shapely), once on the oracle's own inflated obstacles and once on
obstacles inflated here with shapely's buffer, from inside and from outside.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from mawdo.experiments.kinds.arena import arena_preset
from mawdo.planning.guide.sipp.optimum import scenario_time_optimum
from mawdo.planning.judge.check import check_static_path, check_trajectory
from mawdo.planning.scenes import (
    FAMILIES,
    TIMED_FAMILIES,
    describe_family,
    generate_scene,
    generate_scenes,
)
from mawdo.planning.world.geometry import inflated_obstacles
from tests.planning.reference_oracle import brute_force_length

LARGE = ("crowd-large", "warehouse-large")
SEED = 4
# a sparse warehouse (10 shelves) for the brute-force L* in the fast tier
SPARSE = {"aisle": 8.0, "cross": 8.0, "shelf": 12.0, "blocks": 2}


@pytest.fixture(scope="module", params=LARGE)
def family_scenes(request):
    return request.param, generate_scenes(request.param, 2, seed=SEED)


def _shape(spec: dict):
    if spec["shape"] == "circle":
        return shapely.Point(spec["center"]).buffer(spec["radius"], 256)
    return shapely.Polygon(spec["vertices"])


def _static(ob: dict) -> bool:
    return ob.get("motion", {}).get("model", "static") == "static"


def _statics(data: dict) -> list[dict]:
    return [o for o in data["obstacles"] if _static(o)]


def _movers(data: dict) -> list[dict]:
    return [o for o in data["obstacles"] if not _static(o)]


def _check_valid(scene) -> None:
    """Start and goal free, every obstacle's count, the stored optimum a real route of
    length L*, T* no earlier than L*/v and its route clean under the independent checker."""
    sc, p = scene.scenario, scene.params
    data, r, v = sc.to_dict(), sc.robot_radius, sc.robot_speed
    assert sc.width == sc.height == p["size"]
    assert len(_movers(data)) == p["n"]
    for q in (sc.start, sc.goal):
        assert r + p["clearance"] <= min(q[0], q[1], sc.width - q[0], sc.height - q[1])
        for ob in data["obstacles"]:  # (the disc buffer is inscribed: distance >= true)
            assert _shape(ob).distance(shapely.Point(q)) > r + p["clearance"] - 1e-6
    np.testing.assert_allclose(scene.optimum[[0, -1]], [sc.start, sc.goal])
    assert np.sum(np.hypot(*np.diff(scene.optimum, axis=0).T)) == pytest.approx(scene.l_star)
    assert check_static_path(scene.optimum, [_shape(o) for o in _statics(data)], radius=r).ok
    # T*: finite, never before the static optimum driven at full speed, and its route collides
    # with nothing, static or moving, exact in time (the route's ends and speed: the timed
    # families' contract, tests/planning/test_scene_families_time.py)
    route = scene.time_route
    assert math.isfinite(scene.t_star) and scene.t_star >= scene.l_star / v - 1e-9
    rep = check_trajectory(route.points, sc, times=route.times)
    assert rep.ok and route.times[-1] == scene.t_star, rep.describe()
    assert f"L*={scene.l_star:.6f}" in sc.spec.description
    assert f"T*={scene.t_star:.6f}" in sc.spec.description


def _box(scene) -> tuple[float, float, float, float]:
    """The map box of the robot's centre: its radius from the border (pixels)."""
    r, s = scene.scenario.robot_radius, scene.scenario.width
    return (r, r, s - r, s - r)


def _brute_same(scene) -> float:
    """The brute-force shortest path on the oracle's own inflated obstacles."""
    sc = scene.scenario
    same = inflated_obstacles(sc, 0.0, indices=sc.static_indices)
    return brute_force_length(sc.start, sc.goal, same, _box(scene))


def _brute_bracket(scene) -> tuple[float, float]:
    """The brute-force shortest path on the static shapes buffered by shapely from inside
    (a 32-gon per corner inscribed in the robot's disc: no longer than the true optimum) and
    from outside (containing the oracle's circumscribed 32-gon: no shorter than L*)."""
    sc, r = scene.scenario, scene.scenario.robot_radius
    statics = [_shape(o) for o in _statics(sc.to_dict())]
    q = 8  # shapely: q segments per quarter circle, vertices on the buffer distance
    outer = r / math.cos(math.pi / 32) / math.cos(math.pi / (4 * q))
    return tuple(
        brute_force_length(
            sc.start, sc.goal, [g.buffer(d, quad_segs=q) for g in statics], _box(scene)
        )
        for d in (r, outer)
    )


def _check_l_star(scene) -> None:
    assert scene.l_star == pytest.approx(_brute_same(scene), rel=1e-9, abs=1e-6)
    inner, outer = _brute_bracket(scene)
    assert inner - 1e-6 <= scene.l_star <= outer + 1e-6
    assert outer - inner < 1.0  # the bracket is tight: the test could fail
    assert scene.l_star >= scene.scenario.straight_line_length() - 1e-9


# ---------------------------------------------------------------------------------------------
# the contract: registered, seeded, parameters with ranges


def test_registered_as_timed_families_with_large_defaults():
    for fam in LARGE:
        assert fam in FAMILIES and fam in TIMED_FAMILIES and FAMILIES[fam].timed
        p = FAMILIES[fam].resolve()
        assert p["size"] == 1000.0 and p["n"] == 200
        text = describe_family(fam)
        assert text.startswith(f"{fam}: ")
        for q in FAMILIES[fam].all_params:
            rng = f"one of {list(q.choices)}" if q.choices else f"[{q.low:g}, {q.high:g}]"
            assert f"  {q.name} = {q.default!r}  {rng}" in text
        assert "  size = 1000.0  [1000, 2000]" in text and text.count("  size = ") == 1
        assert "  n = 200  [100, 500]" in text and "lattice = 6" in text


def test_same_seed_same_scene_whatever_the_order(family_scenes):
    fam, scenes = family_scenes
    again = generate_scene(fam, 1, seed=SEED)
    assert again.to_toml() == scenes[1].to_toml() and again.t_star == scenes[1].t_star
    assert generate_scenes(fam, 1, seed=SEED, first=1)[0].to_toml() == scenes[1].to_toml()
    assert scenes[0].to_toml() != scenes[1].to_toml()
    assert generate_scene(fam, 1, seed=SEED + 1).to_toml() != scenes[1].to_toml()
    # T* is the exact search on the scene's own scenario and waiting spots, nothing else
    assert scenario_time_optimum(scenes[1].scenario, spots=scenes[1].spots).t_star == (
        scenes[1].t_star
    )


@pytest.mark.parametrize("fam", LARGE)
@pytest.mark.parametrize(
    ("params", "match"),
    [
        ({"size": 999.0}, r"'size' = 999.0 is out of range \[1000, 2000\]"),
        ({"size": 2500.0}, r"'size' = 2500.0 is out of range \[1000, 2000\]"),
        ({"n": 99}, r"'n' = 99 is out of range \[100, 500\]"),
        ({"n": 501}, r"'n' = 501 is out of range \[100, 500\]"),
        ({"n": 150.5}, "'n' must be an integer"),
        ({"rmin": 1.5, "rmax": 1.0}, "rmin = 1.5 must be <= rmax = 1"),
        ({"speed_min": 0.9, "speed_max": 0.5}, "speed_min = 0.9 must be <= speed_max = 0.5"),
        ({"lattice": 13}, r"'lattice' = 13 is out of range \[0, 12\]"),
        ({"sise": 1200.0}, "Did you mean 'size'"),
    ],
)
def test_parameters_out_of_range_are_refused_with_the_range(fam, params, match):
    with pytest.raises(ValueError, match=match):
        generate_scene(fam, 0, params=params)


@pytest.mark.parametrize(
    ("fam", "params", "match"),
    [
        ("crowd-large", {"aimed": 0.6, "patrols": 0.5}, "aimed \\+ patrols = 1.1 must be <= 1"),
        ("crowd-large", {"statics": 61}, r"'statics' = 61 is out of range \[0, 60\]"),
        ("warehouse-large", {"robot_radius": 0.0}, "robot_radius must be > 0"),
        ("warehouse-large", {"aisle": 1.5, "clearance": 3.0}, "aisle = 1.5 robot diameters"),
        ("warehouse-large", {"cross": 1.6, "rmax": 1.7}, "rmax = 1.7 robot radii is wider"),
        ("warehouse-large", {"blocks": 12, "cross": 20.0}, "shelves shorter than the robot"),
        (
            "warehouse-large",
            {"shelf": 40.0, "aisle": 20.0, "robot_radius": 8.0},
            "no row of shelves",
        ),
        ("warehouse-large", {"cross_share": 1.5}, r"'cross_share' = 1.5 is out of range \[0, 1\]"),
    ],
)
def test_impossible_combinations_are_clear_errors(fam, params, match):
    with pytest.raises(ValueError, match=match):
        generate_scene(fam, 0, params=params)


# ---------------------------------------------------------------------------------------------
# every scene valid, L* exact, T* consistent


def test_scenes_are_valid_with_a_consistent_t_star(family_scenes):
    _, scenes = family_scenes
    for scene in scenes:
        _check_valid(scene)
    # the layouts differ between scenes, not only the movers
    assert len({tuple(np.round(s.scenario.start, 6)) for s in scenes}) == len(scenes)


def test_crowd_l_star_equals_the_brute_force_visibility_graph():
    for scene in generate_scenes("crowd-large", 2, seed=SEED):
        _check_l_star(scene)


def test_sparse_warehouse_is_valid_and_its_l_star_exact():
    scene = generate_scene("warehouse-large", 0, seed=SEED, params=SPARSE)
    assert len(scene.scenario.static_indices) == 10  # 5 rows of 2 shelves (see the layout test)
    _check_valid(scene)
    _check_l_star(scene)


@pytest.mark.slow
def test_default_warehouse_l_star_equals_the_brute_force_visibility_graph():
    """60 shelves: about 2200 corner nodes for the brute force (a minute or more); the
    bracket by shapely's buffers is checked on the sparse warehouse."""
    scene = generate_scene("warehouse-large", 0, seed=SEED)
    assert scene.l_star == pytest.approx(_brute_same(scene), rel=1e-9, abs=1e-6)


@pytest.mark.slow
@pytest.mark.parametrize("fam", LARGE)
def test_the_largest_worlds_are_valid(fam):
    """2000 px with 500 movers: still generated with T* (seconds), valid and clean."""
    scene = generate_scene(fam, 0, seed=SEED, params={"size": 2000.0, "n": 500})
    _check_valid(scene)


# ---------------------------------------------------------------------------------------------
# what each family promises


def _meets_the_robot(ob: dict, start, goal, v: float) -> bool:
    """A constant-velocity disc whose centre is where a robot driving straight from ``start``
    at full speed is, at some time before it arrives (no border reflection before)."""
    c, w = np.asarray(ob["center"]), np.asarray(ob["motion"]["velocity"])
    dist = math.dist(start, goal)
    rel = (goal - start) / dist * v - w  # c + w t = start + v t d  <=>  c - start = rel t
    t = float(rel @ (c - start) / (rel @ rel))
    return 0.0 < t < dist / v and np.hypot(*(c - start - rel * t)) < 1e-6


def test_crowd_discs_cross_the_robots_line_in_their_shares():
    """n = 200, aimed 0.1, patrols 0.3 (defaults): exactly 20 discs reach the straight line
    when a robot driving it does, 60 patrol back and forth across it, 120 move freely."""
    for scene in generate_scenes("crowd-large", 2, seed=SEED):
        sc, data = scene.scenario, scene.scenario.to_dict()
        start, goal = np.asarray(sc.start), np.asarray(sc.goal)
        line = shapely.LineString([start, goal])
        movers = _movers(data)
        linear = [o for o in movers if o["motion"]["model"] == "constant_velocity"]
        patrols = [o for o in movers if o["motion"]["model"] == "patrol"]
        assert len(linear) == 140 and len(patrols) == 60
        assert sum(_meets_the_robot(o, start, goal, sc.robot_speed) for o in linear) == 20
        for o in patrols:
            a, b = (np.asarray(o["center"]) + w for w in o["motion"]["waypoints"])
            assert o["motion"]["cycle"] == "back_and_forth"
            assert line.distance(shapely.Point(0.5 * (a + b))) < 1e-6  # centred on the line
            u = (b - a) / np.hypot(*(b - a))
            assert abs(u @ (goal - start)) / math.dist(start, goal) <= 0.5 + 1e-9  # <= 30 deg off
        r = sc.robot_radius
        assert all(0.75 * r - 1e-9 <= o["radius"] <= 2.0 * r + 1e-9 for o in movers)
        assert 6 <= len(_statics(data)) <= 12  # statics = 12: at least half as many


def test_warehouse_layout_by_hand_and_movers_stay_in_the_aisles():
    """Defaults on 1000 px, robot radius 4: shelves 32 px deep, aisles >= 32 px, cross-aisles
    32 px, 4 blocks: rows = floor((1000 - 32) / (32 + 32)) = 15, so 60 shelves, each
    (1000 - 5 x 32) / 4 = 210 px long; 30 % of the 200 movers (60) patrol the cross-aisles,
    140 the aisles, and no mover's track ever overlaps a shelf."""
    for scene in generate_scenes("warehouse-large", 2, seed=SEED):
        data = scene.scenario.to_dict()
        shelves = [shapely.Polygon(o["vertices"]) for o in _statics(data)]
        assert len(shelves) == 60
        sides = [sorted(np.ptp(np.asarray(s.exterior.coords), axis=0)) for s in shelves]
        np.testing.assert_allclose(sides, [[32.0, 210.0]] * 60)
        long_axis = int(np.argmax(np.ptp(np.asarray(shelves[0].exterior.coords), axis=0)))
        gaps = [a.distance(b) for i, a in enumerate(shelves) for b in shelves[i + 1 :]]
        assert min(gaps) >= 32.0 - 1e-9
        union = shapely.union_all(shelves)
        along = 0
        for o in _movers(data):
            a, b = (np.asarray(o["center"]) + w for w in o["motion"]["waypoints"])
            assert np.count_nonzero(np.abs(b - a) > 1e-9) == 1  # along x or along y
            along += bool(abs(b - a)[long_axis] > 1e-9)
            track = shapely.LineString([a, b]).buffer(o["radius"], 64)
            assert track.intersection(union).area < 1e-6
        assert along == 140


def test_arena_large_preset():
    plan = arena_preset("arena-large")
    assert plan.families == LARGE and plan.planner == "large"
    assert "mawdo" in plan.algorithms and "guide_only" in plan.baselines
    assert plan.total_runs == len(plan.planners) * 2 * plan.n
