"""Scenarios from occupancy images and MovingAI maps."""

import numpy as np
import pytest
import shapely
from PIL import Image

from mawdo.planning import ScenarioError, from_movingai_map, from_occupancy_image
from mawdo.planning.world.rasters import grid_to_polygons


def test_grid_to_polygons_merges_cells_and_flips_y():
    grid = np.zeros((4, 6), dtype=bool)
    grid[0, 1:3] = True  # top row -> y in [3, 4]
    grid[1, 1] = True  # makes an L with the row above
    grid[3, 5] = True  # bottom-right cell, separate
    polys = grid_to_polygons(grid, cell=2.0)
    assert len(polys) == 2
    areas = sorted(p.area for p in polys)
    assert areas == [4.0, 12.0]
    ell = max(polys, key=lambda p: p.area)
    expected = shapely.union_all([shapely.box(2, 6, 6, 8), shapely.box(2, 4, 4, 6)])
    assert ell.symmetric_difference(expected).area == pytest.approx(0.0)
    assert len(ell.exterior.coords) - 1 == 6  # collinear vertices removed
    small = min(polys, key=lambda p: p.area)
    assert small.bounds == (10.0, 0.0, 12.0, 2.0)


def test_diagonal_cells_are_separate_regions_and_holes_are_filled():
    grid = np.array([[1, 0], [0, 1]], dtype=bool)
    assert len(grid_to_polygons(grid)) == 2
    ring = np.ones((5, 5), dtype=bool)
    ring[2, 2] = False
    (poly,) = grid_to_polygons(ring)
    assert poly.area == pytest.approx(25.0) and len(poly.interiors) == 0


def test_occupancy_image(tmp_path):
    img = np.full((40, 60), 255, dtype=np.uint8)
    img[5:15, 20:30] = 0  # rows 5..14 from the top, columns 20..29
    path = tmp_path / "map.png"
    Image.fromarray(img).save(path)
    sc = from_occupancy_image(path, start=(2, 2), goal=(58, 38), robot_radius=1.0)
    assert (sc.width, sc.height) == (60.0, 40.0)
    assert len(sc.obstacles) == 1 and sc.name == "map"
    assert sc.obstacles[0].shape.bounds() == (20.0, 25.0, 30.0, 35.0)
    # the default robot (radius 4) keeps its disc in the map (issue 30)
    big = from_occupancy_image(path, start=(4, 4), goal=(116, 76), cell=2.0)
    assert big.obstacles[0].shape.bounds() == (40.0, 50.0, 60.0, 70.0)
    with pytest.raises(ScenarioError, match="start: inside obstacles"):
        from_occupancy_image(path, start=(25, 30), goal=(58, 38))


def test_unreadable_image_is_a_clear_error(tmp_path):
    fake = tmp_path / "not_an_image.png"
    fake.write_text("hello, I am text")
    with pytest.raises(ScenarioError, match="cannot read image"):
        from_occupancy_image(fake, start=(1, 1), goal=(2, 2))
    with pytest.raises(FileNotFoundError, match="no such image"):
        from_occupancy_image(tmp_path / "missing.png", start=(1, 1), goal=(2, 2))


MAP = """type octile
height 4
width 5
map
.....
.@@T.
...W.
.....
"""


def test_movingai_map(tmp_path):
    path = tmp_path / "tiny.map"
    path.write_text(MAP)
    sc = from_movingai_map(path, start=(0.5, 0.5), goal=(4.5, 3.5), cell=1.0, robot_radius=0.0)
    assert (sc.width, sc.height) == (5.0, 4.0)
    (ob,) = sc.obstacles  # '@@T' in row 1 and 'W' below its end form one region
    poly = shapely.Polygon(ob.shape.vertices)
    expected = shapely.union_all([shapely.box(1, 2, 4, 3), shapely.box(3, 1, 4, 2)])
    assert poly.symmetric_difference(expected).area == pytest.approx(0.0)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("type octile\nheight 2\nwidth 2\n", "missing the 'map' line"),
        ("type octile\nheight 2\nwidth 2\n..\n..\n", "line 4: expected 'key value'"),
        ("type octile\nwidth 2\nmap\n..\n..\n", "no 'height'"),
        ("type octile\nheight 2\nwidth 2\nmap\n..\n", "expected 2 map rows"),
        ("type octile\nheight 2\nwidth 2\nmap\n..\n...\n", "expected 2 characters"),
        ("type octile\nheight 2\nwidth 2\nmap\n..\n.x\n", "unknown terrain 'x'"),
        ("type octile\nheight two\nwidth 2\nmap\n..\n..\n", "must be integers"),
    ],
)
def test_malformed_movingai_maps(tmp_path, text, fragment):
    path = tmp_path / "bad.map"
    path.write_text(text)
    with pytest.raises(ScenarioError, match=fragment):
        from_movingai_map(path, start=(0.5, 0.5), goal=(1.5, 1.5))
