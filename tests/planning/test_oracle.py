"""Exact shortest paths by visibility graph."""

import numpy as np
import pytest
import shapely
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mawdo.planning import check_static_path, get_scenario, scenario_optimum, shortest_path

BOUNDS = (0.0, 0.0, 366.0, 366.0)
HAND_MAP = [
    shapely.box(90, 40, 170, 230),
    shapely.box(200, 150, 320, 250),
    shapely.Polygon([(80, 280), (150, 260), (180, 310), (140, 350), (90, 340)]),
]


def test_pinned_hand_built_map():
    res = shortest_path((20, 20), (346, 346), HAND_MAP, BOUNDS)
    assert res.reachable and res.reason == "ok"
    assert res.length == pytest.approx(502.4146, rel=1e-6)
    # sqrt(70^2 + 210^2) + sqrt(256^2 + 116^2), around the corner (90, 230)
    assert res.length == pytest.approx(np.sqrt(49000) + np.sqrt(78992), rel=1e-12)
    np.testing.assert_allclose(res.path, [[20, 20], [90, 230], [346, 346]])


def test_empty_map_is_the_straight_line():
    res = shortest_path((10, 20), (300, 200), [], BOUNDS)
    assert res.length == pytest.approx(np.hypot(290, 180))
    np.testing.assert_allclose(res.path, [[10, 20], [300, 200]])


def test_symmetric_detour_by_hand():
    # a 20 x 20 square centred on the start-goal line y = 50: over the top corners (40, 60),
    # (60, 60) or under the bottom ones, both 2 sqrt(40^2 + 10^2) + 20 long
    square = shapely.box(40, 40, 60, 60)
    res = shortest_path((0, 50), (100, 50), [square], (0, 0, 100, 100))
    assert res.length == pytest.approx(2 * np.sqrt(1700) + 20, rel=1e-9)
    assert {tuple(p) for p in res.path[1:-1]} in ({(40, 40), (60, 40)}, {(40, 60), (60, 60)})
    # a wall on one side leaves the other route, same length
    wall = shapely.box(30, 60, 70, 100)
    res2 = shortest_path((0, 50), (100, 50), [square, wall], (0, 0, 100, 100))
    assert res2.length == pytest.approx(res.length, rel=1e-9)
    np.testing.assert_allclose(res2.path[1:-1], [[40, 40], [60, 40]])


def test_map_boundary_is_respected():
    # the obstacle reaches the top wall: the path must go below it
    wall = shapely.box(40, 30, 60, 120)
    res = shortest_path((0, 100), (100, 100), [wall], (0, 0, 100, 100))
    expected = 2 * np.hypot(40, 70) + 20
    assert res.length == pytest.approx(expected, rel=1e-9)
    # with a taller map it could go over the top instead (shorter)
    tall = shortest_path((0, 100), (100, 100), [wall], (0, 0, 100, 200))
    assert tall.length == pytest.approx(2 * np.hypot(40, 20) + 20, rel=1e-9)


def test_unreachable_cases_have_reasons():
    ring = shapely.box(100, 100, 200, 200).difference(shapely.box(120, 120, 180, 180))
    res = shortest_path((20, 20), (150, 150), [ring], BOUNDS)
    assert not res.reachable and res.length == np.inf and "not reachable" in res.reason
    inside = shortest_path((110, 110), (20, 20), [ring], BOUNDS)
    assert "start" in inside.reason and "inside an obstacle" in inside.reason
    outside = shortest_path((20, 20), (400, 20), [], BOUNDS)
    assert "goal" in outside.reason and "outside the map" in outside.reason
    # touching the boundary is allowed: a start on an obstacle's edge is fine
    assert shortest_path((90, 100), (20, 20), HAND_MAP, BOUNDS).reachable


def test_overlapping_obstacles_and_coincident_ends():
    # two overlapping boxes standing on the bottom wall: over the top, via (50, 90), (70, 90)
    a, b = shapely.box(40, 0, 60, 70), shapely.box(50, 60, 70, 90)
    res = shortest_path((0, 10), (100, 10), [a, b], (0, 0, 100, 100))
    assert res.length == pytest.approx(np.hypot(50, 80) + 20 + np.hypot(30, 80), rel=1e-9)
    np.testing.assert_allclose(res.path[1:-1], [[50, 90], [70, 90]])
    assert shortest_path((5, 5), (5, 5), [a], (0, 0, 100, 100)).length == 0.0


def grid(lo: float, hi: float):
    """Coordinates on a 1/8 px grid: two of them are equal or at least 0.125 px apart. The oracle
    decides visibility with a tolerance (``DEFAULT_TOL``, 1e-7 px), so a sliver thinner than it
    (say a box edge 1e-83 px off the map's border, as unconstrained floats produce) is open or
    closed by the tolerance, not by the geometry, and no property of the exact optimum holds
    there."""
    return st.integers(int(lo * 8), int(hi * 8)).map(lambda v: v / 8.0)


@st.composite
def maps(draw, max_boxes=4):
    boxes = []
    for _ in range(draw(st.integers(0, max_boxes))):
        x, y = draw(grid(0, 90)), draw(grid(0, 90))
        w, h = draw(grid(2, 40)), draw(grid(2, 40))
        boxes.append(shapely.box(x, y, min(x + w, 100), min(y + h, 100)))
    return boxes


points = st.tuples(grid(0, 100), grid(0, 100))


@given(obstacles=maps(), start=points, goal=points)
@settings(max_examples=80, deadline=None)
def test_oracle_is_never_shorter_than_the_straight_line(obstacles, start, goal):
    res = shortest_path(start, goal, obstacles, (0, 0, 100, 100))
    if res.reachable:
        assert res.length >= np.hypot(goal[0] - start[0], goal[1] - start[1]) - 1e-9
        assert check_static_path(res.path, obstacles).min_clearance >= -1e-6


@given(obstacles=maps(3), extra=maps(1), start=points, goal=points)
@settings(max_examples=80, deadline=None)
def test_adding_an_obstacle_never_shortens_the_path(obstacles, extra, start, goal):
    assume(extra)
    before = shortest_path(start, goal, obstacles, (0, 0, 100, 100))
    after = shortest_path(start, goal, obstacles + extra, (0, 0, 100, 100))
    assert after.length >= before.length - 1e-7


def test_paper_static_optimum_is_collision_free_for_the_robot_disc():
    sc = get_scenario("paper")
    res = scenario_optimum(sc)
    static = [sc.obstacles[i].shape for i in sc.static_indices]
    report = check_static_path(res.path, static, radius=sc.robot_radius)
    assert report.ok and -1e-9 <= report.min_clearance < 0.05  # it hugs the inflated shapes
    # all obstacles frozen at t = 0 make it longer (or equal), never shorter
    assert scenario_optimum(sc, static_only=False).length >= res.length - 1e-9
