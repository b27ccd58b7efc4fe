"""Baselines: the straight line and OMPL RRT*/BIT*/PRM*, judged by the independent checker."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
import shapely

from mawdo.planning.baselines import BASELINES, plan_ompl, route_times, run_baseline
from mawdo.planning.guide.oracle import scenario_optimum
from mawdo.planning.scenes import generate_scene
from mawdo.planning.world.scenario import scenario_from_dict
from mawdo.registry import UnknownNameError

BOX = [[80.0, 70.0], [120.0, 70.0], [120.0, 130.0], [80.0, 130.0]]


def _easy(obstacles=None):
    return scenario_from_dict(
        {
            "schema_version": 1,
            "width": 200.0,
            "height": 200.0,
            "start": [20.0, 100.0],
            "goal": [180.0, 110.0],
            "robot": {"radius": 4.0, "speed": 4.0},
            "obstacles": [{"shape": "polygon", "vertices": BOX}]
            if obstacles is None
            else obstacles,
        }
    )


@pytest.mark.parametrize("name", ["rrtstar", "bitstar", "prmstar"])
def test_ompl_finds_a_route_the_checker_accepts(name):
    sc = _easy()
    # 0.25 s of solve, longer if a loaded machine gives the planner too little CPU to find one
    res = run_baseline(name, sc, time_limit=0.25, max_time=120.0)
    assert res.solved and res.collision_free and res.static_collision_free and res.success
    assert res.planner == name and not res.sees_time
    np.testing.assert_allclose(res.route[[0, -1]], [sc.start, sc.goal])
    # independent of the checker: the route keeps the robot disc off the box
    assert shapely.LineString(res.route).distance(shapely.Polygon(BOX)) >= 4.0
    l_star = scenario_optimum(sc).length
    assert l_star - 0.05 <= res.length <= 1.15 * l_star
    assert res.validity_checks > 100 and res.check_rate > 0
    assert res.min_clearance >= 0.0


def test_max_time_keeps_solving_past_the_time_limit_until_a_first_solution():
    # a 1 ms budget is too short to count on a solution; with max_time
    # the solve goes on to the first exact one, wherever the machine's speed puts it
    sc = _easy()
    res = run_baseline("bitstar", sc, time_limit=1e-3, max_time=120.0)
    assert res.solved and res.success and res.reason == "ok"
    with pytest.raises(ValueError, match=r"max_time must be None or in \[time_limit, 3600\]"):
        run_baseline("bitstar", sc, time_limit=1.0, max_time=0.5)


def test_straight_line_fails_on_a_blocked_scene_and_passes_an_empty_one():
    blocked = run_baseline("straight", _easy())
    assert blocked.solved and not blocked.collision_free and not blocked.static_collision_free
    assert not blocked.success and "collision" in blocked.reason
    assert blocked.min_clearance < 0
    free = run_baseline("straight", _easy([]))
    assert free.success and free.length == pytest.approx(math.hypot(160.0, 10.0))
    narrow = run_baseline("straight", generate_scene("narrow", 0, seed=4).scenario)
    assert not narrow.collision_free


def test_straight_line_is_judged_against_moving_obstacles_too():
    sc = generate_scene("crossing", 0, seed=2).scenario  # no statics: only the crossers block
    res = run_baseline("straight", sc)
    assert res.static_collision_free and not res.collision_free


def test_route_times_follow_the_robot_speed():
    np.testing.assert_allclose(route_times(np.array([[0, 0], [3, 4], [3, 10]]), 2.0), [0, 2.5, 5.5])


def test_no_route_when_the_goal_is_walled_off():
    wall = {"shape": "polygon", "vertices": [[100, 0], [110, 0], [110, 200], [100, 200]]}
    res = plan_ompl(_easy([wall]), "rrtstar", time_limit=0.1)
    assert not res.solved and res.route is None and math.isinf(res.length) and not res.success
    assert "time budget" in res.reason


def test_start_too_close_to_an_obstacle_is_reported():
    res = plan_ompl(_easy([{"shape": "circle", "center": [20.0, 110.0], "radius": 5.5}]))
    assert not res.solved and "start is within robot radius + clearance" in res.reason


def test_bad_options_and_names():
    sc = _easy()
    with pytest.raises(ValueError, match="resolution must be in"):
        plan_ompl(sc, resolution=0.0)
    with pytest.raises(ValueError, match=r"clearance must be in \[resolution / 2"):
        plan_ompl(sc, resolution=2.0, clearance=0.5)
    with pytest.raises(ValueError, match="time_limit"):
        plan_ompl(sc, time_limit=-1)
    with pytest.raises(ValueError, match="unknown OMPL planner"):
        plan_ompl(sc, planner="rrt")
    with pytest.raises(UnknownNameError, match="rrtstar"):
        run_baseline("rrt*", sc)
    assert set(BASELINES) == {"straight", "rrtstar", "bitstar", "prmstar"}
    assert not any(b.sees_time for b in BASELINES.values())


def test_missing_ompl_names_the_pip_command(monkeypatch):
    monkeypatch.setitem(sys.modules, "ompl", None)  # import ompl -> ImportError
    with pytest.raises(ImportError, match=r"pip install 'mawdo\[ompl\]'"):
        plan_ompl(_easy())


def test_validity_grid_agrees_with_shapely_everywhere():
    from mawdo.planning.baselines.sampling import _blocked, _Validity

    sc = generate_scene("open", 2, seed=8).scenario
    blocked = _blocked(sc, 0.5)
    valid = _Validity(blocked, sc.width, sc.height)
    rng = np.random.default_rng(0)
    pts = rng.uniform(0, sc.width, (20000, 2))
    # points on cell edges and corners, and on the obstacles' boundary
    edges = np.arange(0, valid.nx + 1) * valid.cell
    pts = np.vstack(
        [pts, np.column_stack([edges, edges]), np.column_stack([edges, pts[: len(edges), 1]])]
    )
    ring = shapely.get_coordinates(shapely.segmentize(blocked.boundary, 0.7))
    pts = np.vstack([pts, ring, ring + 1e-9, ring - 1e-9])
    ours = np.array([valid(p) for p in pts])
    truth = ~shapely.intersects_xy(blocked, pts[:, 0], pts[:, 1])
    np.testing.assert_array_equal(ours, truth)
    assert 0 < truth.mean() < 1 and valid.calls == len(pts)
    grid = np.array(valid.grid)
    assert (grid == 0).any() and (grid == 1).any() and (grid == 2).any()


def test_no_checked_route_beats_the_exact_optimum():
    """Independent of the oracle: any route the checker accepts is at least L* long (up to the
    inflation polygon's excess, < 0.05 px here), and BIT* gets close to it."""
    solved = 0
    for fam in ("open", "u_trap", "movingai"):
        sc = generate_scene(fam, 1, seed=6)
        res = run_baseline("bitstar", sc.scenario, time_limit=0.4, max_time=120.0)
        if res.solved and res.static_collision_free:
            solved += 1
            assert res.length >= sc.l_star - 0.05
            assert res.length <= 1.25 * sc.l_star
    assert solved >= 2
