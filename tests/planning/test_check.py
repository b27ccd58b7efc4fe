"""Independent collision checker (shapely, relative motion per constant-velocity piece)."""

import numpy as np
import pytest
import shapely
from hypothesis import example, given, settings
from hypothesis import strategies as st

from mawdo.planning import check_static_path, check_trajectory, scenario_from_dict
from mawdo.planning.world.scenario import PolygonObstacle


def scenario(obstacles, radius=2.0, width=200.0, height=200.0, start=(5, 5), goal=(195, 195)):
    return scenario_from_dict(
        {
            "schema_version": 1,
            "width": width,
            "height": height,
            "start": list(start),
            "goal": list(goal),
            "robot": {"radius": radius, "speed": 4.0},
            "obstacles": obstacles,
        }
    )


boxes = st.tuples(
    st.floats(40, 140), st.floats(40, 140), st.floats(5, 40), st.floats(5, 40), st.floats(0, 5)
)


@given(box=boxes, margin=st.floats(0.05, 5))
@example(box=(136.0, 40.0, 40.0, 5.0, 5.0), margin=1.0)  # the around path's end near the border
@settings(max_examples=60, deadline=None)
def test_flags_a_path_through_an_obstacle_and_passes_one_around_it(box, margin):
    x, y, w, h, r = box
    poly = PolygonObstacle(
        shape="polygon", vertices=[(x, y), (x + w, y), (x + w, y + h), (x, y + h)]
    )
    cy = y + h / 2
    through = np.array([[x - 20, cy], [x + w + 20, cy]])
    report = check_static_path(through, [poly], radius=r)
    assert not report.ok and report.collisions == ((0, 0),)
    # the centre line reaches min(w, h) / 2 deep (measured to within DEPTH_STEP / 4)
    assert report.min_clearance == pytest.approx(-r - min(w, h) / 2, abs=0.0625 + 1e-9)
    # around: below the box, then up past its right side, keeping r + margin clear
    d = r + margin
    around = np.array([[x - 20, cy], [x - d, y - d], [x + w + d, y - d], [x + w + 20, cy]])
    ok = check_static_path(around, [poly], radius=r)
    assert ok.ok and ok.min_clearance == pytest.approx(margin, abs=1e-9)
    # the same through the scenario/trajectory checker (static obstacle, any timing); the map
    # is wide enough that the paths' ends (up to x + w + 20 = 200 px) keep r off its border
    sc = scenario([{"shape": "polygon", "vertices": poly.vertices}], radius=r, width=240.0)
    assert not check_trajectory(np.linspace(*through, 30), sc).ok
    assert check_trajectory(around, sc, t0=3.0).ok


def test_relative_motion_catches_a_crossing_between_time_steps():
    # the robot waits at (100, 100); a circle of radius 5 flies past at 20 px/step along
    # y = 100: at the steps it is at x = 50, 70, 90, 110, ..., never within 6 px of the robot,
    # but between t = 2 and t = 3 it sweeps right through it
    mover = {"shape": "circle", "center": [50, 100], "radius": 5, "motion": {"velocity": [20, 0]}}
    sc = scenario([mover], radius=1.0)
    wait = np.tile([100.0, 100.0], (6, 1))
    report = check_trajectory(wait, sc)
    assert not report.ok
    assert report.collisions == ((2, 0),)  # between t = 2 (x = 90) and t = 3 (x = 110)
    assert report.min_clearance == pytest.approx(-6.0)  # centre passes right through
    # sampling only the positions at the steps would have missed it
    at_steps = [np.hypot(*(sc.obstacles[0].offset(t) + (50, 100) - (100, 100))) for t in range(6)]
    assert min(at_steps) - 6.0 > 0


def test_moving_polygon_and_moving_robot_exact_clearance():
    # a bar moving up at 1 px/step; the robot moves right at 2 px/step, 3 px under the bar's
    # path at first, and the bar moves away: smallest gap is at t = 0
    bar = {
        "shape": "polygon",
        "vertices": [[0, 50], [200, 50], [200, 52], [0, 52]],
        "motion": {"velocity": [0, 1]},
    }
    sc = scenario([bar], radius=1.0, start=(10, 40), goal=(190, 10))
    traj = np.column_stack([10 + 2 * np.arange(10), np.full(10, 47.0)])
    report = check_trajectory(traj, sc)
    assert report.ok and report.min_clearance == pytest.approx(2.0)
    np.testing.assert_allclose(report.clearance[:, 0], 2.0 + np.arange(9))
    # moving up at 2 px/step it catches the bar: gap (50 + t) - (47 + 2 t) - 1 = 2 - t,
    # touching at t = 2 (allowed), overlapping after
    up = np.column_stack([np.full(6, 100.0), 47.0 + 2 * np.arange(6)])
    hit = check_trajectory(up, sc)
    np.testing.assert_allclose(hit.clearance[:2, 0], [1.0, 0.0], atol=1e-12)
    assert not hit.ok and hit.collisions[0] == (2, 0)


def test_report_out_of_map_and_times():
    sc = scenario([], radius=1.0)
    report = check_trajectory([[10, 10], [-1, 10], [10, 210]], sc)
    assert not report.ok and report.out_of_map == (1, 2) and report.min_clearance == np.inf
    with pytest.raises(ValueError, match="non-decreasing"):
        check_trajectory([[10, 10], [20, 10]], sc, times=[3.0, 2.0])
    with pytest.raises(ValueError, match="shape"):
        check_trajectory([[10, 10, 1]], sc)
    single = check_trajectory([[10, 10]], sc)
    assert single.ok and single.clearance.shape == (1, 0)


def test_explicit_times_follow_a_path_at_constant_speed():
    mover = {"shape": "circle", "center": [100, 20], "radius": 5, "motion": {"velocity": [0, 2]}}
    sc = scenario([mover], radius=1.0, start=(20, 100), goal=(180, 100))
    path = np.array([[20.0, 100.0], [180.0, 100.0]])
    # at 4 px/step the robot reaches x = 100 at t = 20, the circle is at y = 60: clear
    assert check_trajectory(path, sc, times=[0.0, 40.0]).ok
    # slower (160 px in 80 steps) it arrives at t = 40 when the circle is at y = 100
    assert not check_trajectory(path, sc, times=[0.0, 80.0]).ok


def test_static_path_accepts_shapely_geometries():
    wall = shapely.box(40, 0, 60, 100)
    report = check_static_path([[0, 50], [100, 50]], [wall])
    assert not report.ok and report.min_clearance == -10.0  # reaches the wall's centre line
    assert check_static_path([[0, 50], [30, 50]], [wall], radius=5).min_clearance == 5.0


def test_moving_circles_measured_together_give_each_ones_own_distances():
    """The checker measures every moving circle in one shapely call, and every standing one in
    another; each clearance is the one the obstacle-by-obstacle measure gives (bit for bit),
    over every kind of motion, with and without the near-pairs index."""
    from mawdo.planning.judge.check import _relative_lines, _shape_distance

    rng = np.random.default_rng(4)
    movers = []
    for k in range(12):
        c = rng.uniform(20, 180, 2).tolist()
        motion = [
            {"velocity": rng.normal(0, 2, 2).tolist()},
            {"model": "patrol", "waypoints": [[0, 0], rng.uniform(-40, 40, 2).tolist()],
             "speed": 1.5, "cycle": "back_and_forth"},
            {"model": "bounded_random_walk", "step": 2.0, "hold": 1},
        ][k % 3]  # fmt: skip
        movers.append({"shape": "circle", "center": c, "radius": float(rng.uniform(3, 9)),
                       "motion": motion})  # fmt: skip
    movers.append({"shape": "polygon", "vertices": [[90, 90], [110, 92], [100, 110]],
                   "motion": {"velocity": [0.5, -0.3]}})  # fmt: skip
    movers.append({"shape": "circle", "center": [50.0, 150.0], "radius": 6.0})
    movers.append({"shape": "circle", "center": [150.0, 60.0], "radius": 4.5})
    movers.append({"shape": "polygon", "vertices": [[20, 20], [40, 20], [30, 35]]})
    sc = scenario(movers)
    for trial in range(20):
        k = 2 if trial % 2 else int(rng.integers(3, 40))
        pts = np.cumsum(rng.normal(0, 4, (k, 2)), axis=0) + rng.uniform(40, 160, 2)
        times = np.cumsum(rng.uniform(0.2, 1.5, k)) + rng.uniform(0, 30)
        for reach in (np.inf, 6.0):
            rep = check_trajectory(pts, sc, times=times, reach=reach)
            for o in sc.obstacles:
                if not o.is_static and not np.isinf(reach):
                    continue
                if o.is_static:  # the route itself
                    lines = shapely.linestrings(np.stack([pts[:-1], pts[1:]], axis=1))
                else:
                    lines = _relative_lines(o, pts, times, np.arange(k - 1))
                own = _shape_distance(o.shape, lines) - sc.robot_radius
                assert np.array_equal(rep.clearance[:, o.index], own), (trial, o.index)
            near = np.isfinite(rep.clearance)
            assert near.any()
