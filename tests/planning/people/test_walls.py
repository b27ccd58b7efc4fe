"""Wall geometry and the move guard, against shapely and hand values."""

import numpy as np
import pytest
import shapely

from mawdo.planning.people.walls import Walls, point_segment_distance, segment_segment_distance

BLOCK = np.array([[80.0, 60.0], [120.0, 60.0], [120.0, 140.0], [80.0, 140.0]])
WEDGE = np.array([[30.0, 150.0], [60.0, 190.0], [20.0, 185.0]])


def test_point_segment_distance_hand_values():
    a = np.array([[0.0, 0.0], [5.0, 5.0]])
    b = np.array([[10.0, 0.0], [5.0, 5.0]])  # the second is a point
    p = np.array([[5.0, 3.0], [-4.0, 3.0]])
    d, near = point_segment_distance(p, a, b)
    np.testing.assert_allclose(d, [[3.0, 2.0], [5.0, np.hypot(9, 2)]])
    np.testing.assert_allclose(near[0, 0], [5.0, 0.0])
    np.testing.assert_allclose(near[1, 0], [0.0, 0.0])


def test_segment_segment_distance_matches_shapely():
    rng = np.random.default_rng(3)
    p0, p1 = rng.uniform(0, 50, (40, 2)), rng.uniform(0, 50, (40, 2))
    a, b = rng.uniform(0, 50, (7, 2)), rng.uniform(0, 50, (7, 2))
    got = segment_segment_distance(p0, p1, a, b)
    want = [
        [
            shapely.LineString([p0[i], p1[i]]).distance(shapely.LineString([a[j], b[j]]))
            for j in range(7)
        ]
        for i in range(40)
    ]
    np.testing.assert_allclose(got, want, atol=1e-9)


def test_guard_keeps_discs_out_of_walls_and_in_the_map():
    walls = Walls.build([BLOCK, WEDGE], (200.0, 200.0))
    rng = np.random.default_rng(7)
    radii = np.full(300, 5.0)
    pts = rng.uniform(0, 200, (3000, 2))
    pts = pts[walls.free(pts, np.full(len(pts), 5.0))][:300]
    assert len(pts) == 300
    union = shapely.union_all([shapely.Polygon(BLOCK), shapely.Polygon(WEDGE)])
    box = shapely.box(0, 0, 200, 200).exterior
    for _ in range(30):
        move = rng.normal(0, 15, (300, 2))
        new = walls.guard(pts, move, radii)
        for p, q in zip(pts, new, strict=True):
            swept = shapely.LineString([p, q]) if np.any(p != q) else shapely.Point(p)
            assert swept.distance(union) >= 5.0 - 1e-9
            assert swept.distance(box) >= 5.0 - 1e-9 and 0 <= q[0] <= 200 and 0 <= q[1] <= 200
        # a clear move is taken unchanged
        same = walls._clear_moves(pts, pts + move, radii)
        np.testing.assert_array_equal(new[same], (pts + move)[same])
        pts = new


def test_guard_slides_along_a_wall():
    walls = Walls.build([BLOCK], (200.0, 200.0))
    p = np.array([[70.0, 100.0]])  # 10 px left of the block, radius 5
    new = walls.guard(p, np.array([[8.0, 3.0]]), np.array([5.0]))
    np.testing.assert_allclose(new, [[70.0, 103.0]])  # the part into the wall is dropped


def test_clearance_signs():
    walls = Walls.build([BLOCK], (200.0, 200.0))
    np.testing.assert_allclose(
        walls.clearance([[100.0, 100.0], [70.0, 100.0], [-3.0, 50.0], [5.0, 190.0]]),
        [-20.0, 10.0, -3.0, 5.0],
    )


@pytest.mark.parametrize(
    "polys, bounds, match",
    [
        ([[[0, 0], [1, 1]]], (10, 10), r"obstacles\[0\] must be a \(k, 2\) array"),
        ([[[0, 0], [2, 2], [2, 0], [0, 2]]], (10, 10), r"obstacles\[0\] is not a simple polygon"),
        ([], (10, -1), "width and height must be finite and > 0"),
        ([], "wide", r"bounds must be \(width, height\)"),
    ],
)
def test_bad_walls(polys, bounds, match):
    with pytest.raises(ValueError, match=match):
        Walls.build(polys, bounds)
