"""Inflation by the robot radius and the flat arrays handed to the kernel."""

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from mawdo.planning import get_scenario, inflate
from mawdo.planning.world.geometry import (
    CIRCLE_SEGMENTS,
    FlatObstacles,
    MotionTable,
    circumscribed_polygon,
    inflated_obstacles,
)
from mawdo.planning.world.scenario import CircleObstacle, PolygonObstacle

EXCESS = 1.0 / np.cos(np.pi / CIRCLE_SEGMENTS)


@st.composite
def simple_polygons(draw):
    """Star-shaped (so simple), often non-convex polygons around (50, 50)."""
    k = draw(st.integers(3, 9))
    angles = np.sort(draw(st.lists(st.floats(0, 2 * np.pi), min_size=k, max_size=k, unique=True)))
    gaps = np.diff(np.r_[angles, angles[0] + 2 * np.pi])
    # star-shaped about the centre only if every angular gap is below pi
    if gaps.min() < 0.05 or gaps.max() > 0.9 * np.pi:
        angles = np.linspace(0, 2 * np.pi, k, endpoint=False)
    radii = draw(st.lists(st.floats(5, 40), min_size=k, max_size=k))
    pts = np.column_stack([50 + radii * np.cos(angles), 50 + radii * np.sin(angles)])
    assert shapely.Polygon(pts).is_valid
    return PolygonObstacle(shape="polygon", vertices=[tuple(p) for p in pts])


@given(shape=simple_polygons(), r=st.floats(0.5, 10))
@settings(max_examples=60, deadline=None)
def test_inflated_polygon_contains_the_true_inflation_and_is_tight(shape, r):
    raw = shapely.Polygon(shape.vertices)
    ours = inflate(shape, r)
    assert ours.is_valid
    # the true Minkowski sum, approximated from inside by a fine buffer, lies within ours
    assert ours.buffer(1e-7).contains(raw.buffer(r, quad_segs=64))
    # and ours exceeds it by at most r (1/cos(pi/n) - 1): every vertex is that close to raw
    v = shapely.points(np.asarray(ours.exterior.coords))
    assert np.max(shapely.distance(v, raw)) <= r * EXCESS + 1e-9


def test_inflated_box_has_flat_sides_at_exactly_r():
    box = PolygonObstacle(shape="polygon", vertices=[(10, 10), (30, 10), (30, 20), (10, 20)])
    assert inflate(box, 4.0).bounds == pytest.approx((6, 6, 34, 24))
    assert inflate(box, 0.0).equals(shapely.box(10, 10, 30, 20))


def test_inflated_circle_is_circumscribed():
    c = CircleObstacle(shape="circle", center=(0, 0), radius=6)
    poly = inflate(c, 4.0, offset=(100, 50))
    assert poly.buffer(1e-9).contains(shapely.Point(100, 50).buffer(10.0, quad_segs=64))
    d = np.hypot(*(np.asarray(poly.exterior.coords) - (100, 50)).T)
    np.testing.assert_allclose(d, 10.0 * EXCESS)
    assert circumscribed_polygon((0, 0), 0.0).geom_type == "Point"


def test_inflated_obstacles_follow_the_motion():
    sc = get_scenario("paper")
    at0 = inflated_obstacles(sc, 0.0)
    at30 = inflated_obstacles(sc, 30.0)
    off = sc.offsets(30.0)
    for i, (a, b) in enumerate(zip(at0, at30, strict=True)):
        shifted = shapely.affinity.translate(a, *off[i])
        assert shifted.symmetric_difference(b).area == pytest.approx(0.0, abs=1e-6)
    assert len(inflated_obstacles(sc, 0.0, indices=sc.static_indices)) == 2


def test_flat_obstacles_arrays():
    sc = get_scenario("paper")
    flat = FlatObstacles.from_scenario(sc)
    r = sc.robot_radius
    n = len(sc.obstacles)
    assert flat.is_circle.shape == (n,) and flat.bound.shape == (n, 7)
    for o in sc.obstacles:
        i = o.index
        if o.is_circle:
            assert flat.thresh[i] == o.shape.radius + r and flat.nverts[i] == 0
            assert tuple(flat.bound[i, 4:6]) == tuple(o.shape.center)
        else:
            v = np.asarray(o.shape.vertices)
            assert flat.thresh[i] == r and flat.nverts[i] == len(v)
            np.testing.assert_array_equal(flat.verts[i, : len(v)], v)
            # bounding circle holds the inflated polygon, hull half-planes hold every vertex
            c, rho = flat.bound[i, 4:6], flat.bound[i, 6]
            assert np.all(np.hypot(*(v - c).T) + r <= rho)
            h = flat.hull[i, : flat.nhull[i]]
            np.testing.assert_allclose(np.hypot(h[:, 0], h[:, 1]), 1.0)
            assert np.all(v @ h[:, :2].T <= h[:, 2] - r)
            # every hull edge touches the polygon: the half-planes are tight
            assert np.allclose(np.max(v @ h[:, :2].T - (h[:, 2] - r), axis=0), -1e-9, atol=1e-8)


def test_motion_table_knots_and_start_indices():
    sc = get_scenario("paper")
    table = MotionTable.build(sc.obstacles, 3.0, 200.0)
    assert table.covers(3.0, 200.0) and not table.covers(2.0, 50.0)
    for o in sc.obstacles:
        nk = table.nknots[o.index]
        t = table.times[o.index, :nk]
        if o.is_static:
            assert nk == 1
            continue
        assert t[0] == 3.0 and t[-1] == 200.0
        np.testing.assert_allclose(table.offsets[o.index, :nk], o.offset(t), atol=1e-9)
        v = table.velocity[o.index, : nk - 1]
        np.testing.assert_allclose(
            v * np.diff(t)[:, None], np.diff(table.offsets[o.index, :nk], axis=0), atol=1e-9
        )
    k = table.start_indices(57.5)
    for o in sc.moving_indices:
        assert table.times[o, k[o]] <= 57.5 < table.times[o, k[o] + 1]


def _per_obstacle_table(pieces, n):
    """The motion table's velocities as one np.diff per obstacle (the reference)."""
    K = max([len(t) for t, _ in pieces] + [1])
    velocity = np.zeros((n, K, 2))
    for i, (t, off) in enumerate(pieces):
        velocity[i, : len(t) - 1] = np.diff(off, axis=0) / np.diff(t)[:, None]
    return velocity


def test_the_motion_tables_velocities_are_one_diff_per_obstacle():
    from mawdo.planning.world.geometry import MotionTable
    from mawdo.planning.world.motion import Track
    from mawdo.planning.world.scenario import Obstacle

    rng = np.random.default_rng(2)
    for _ in range(30):
        obstacles = []
        for j in range(int(rng.integers(1, 6))):
            k = int(rng.integers(1, 6))
            times = np.cumsum(rng.uniform(0.01, 9.0, k)) - rng.uniform(0, 5)
            motion = Track(times, rng.normal(0, 30, (k, 2)))
            obstacles.append(Obstacle(j, f"m{j}", None, motion))
        t0, t1 = sorted(rng.uniform(-5, 40, 2))
        table = MotionTable.build(tuple(obstacles), t0, t1)
        pieces = [o.knots(t0, t1) for o in obstacles]
        assert np.array_equal(table.velocity, _per_obstacle_table(pieces, len(obstacles)))
