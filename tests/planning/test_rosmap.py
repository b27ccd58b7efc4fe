"""ROS map_server maps: a hand-made map read at hand-computed metre coordinates, written back."""

import json

import numpy as np
import pytest
import shapely
from PIL import Image

from mawdo.planning.world.rosmap import load_ros_map, read_pgm, read_ros_map, save_ros_map
from mawdo.planning.world.scenario import ScenarioError

RES = 0.1
ORIGIN = (-2.0, 1.5)
ROWS, COLS = 40, 60


def hand_map() -> np.ndarray:
    """Obstacle cells (row 0 at the top): the top row, a two-cell wall at columns 30-31 with
    a door in rows 15-24, and an unknown (grey 205) block at rows 30-39, columns 50-59."""
    grey = np.full((ROWS, COLS), 254, dtype=np.uint8)  # free
    grey[0, :] = 0
    grey[:, 30:32] = 0
    grey[15:25, 30:32] = 254  # the door
    grey[30:40, 50:60] = 205  # unknown: p = 50/255 = 0.196..., between the thresholds
    return grey


#: The same cells in ROS world metres, by hand: row r spans y in [(39 - r), (40 - r)] * 0.1
#: above the origin's 1.5, column c spans x in [c, c + 1] * 0.1 right of its -2.0.
EXPECTED_ROS = shapely.union_all(
    [
        shapely.box(-2.0, 5.4, 4.0, 5.5),  # top row
        shapely.box(1.0, 4.0, 1.2, 5.4),  # wall above the door (rows 1-14)
        shapely.box(1.0, 1.5, 1.2, 3.0),  # wall below the door (rows 25-39)
        shapely.box(3.0, 1.5, 4.0, 2.5),  # unknown block
    ]
)


def write_pgm(path, grey, ascii_=False, header=None):
    rows, cols = grey.shape
    if ascii_:
        body = "\n".join(" ".join(str(int(v)) for v in row) for row in grey)
        path.write_text(f"P2\n# hand-made\n{cols} {rows}\n255\n{body}\n")
    else:
        head = header or f"P5\n# hand-made\n{cols} {rows}\n255\n"
        path.write_bytes(head.encode() + grey.astype(np.uint8).tobytes())


def write_yaml(path, image="map.pgm", **fields):
    meta = {
        "image": image,
        "resolution": RES,
        "origin": f"[{ORIGIN[0]}, {ORIGIN[1]}, 0.0]",
        "negate": 0,
        "occupied_thresh": 0.65,
        "free_thresh": 0.196,
        **fields,
    }
    path.write_text("".join(f"{k}: {v}\n" for k, v in meta.items() if v is not None))
    return path


def obstacles_ros(sc) -> shapely.Geometry:
    """The scenario's obstacles (metres, as its file says) moved into the ROS frame."""
    polys = [shapely.Polygon(np.asarray(o["vertices"]) + ORIGIN) for o in sc.to_dict()["obstacles"]]
    return shapely.union_all(polys)


@pytest.fixture
def ros_map(tmp_path):
    write_pgm(tmp_path / "map.pgm", hand_map())
    return write_yaml(tmp_path / "map.yaml")


def test_cells_land_at_hand_computed_metres(ros_map):
    sc = load_ros_map(ros_map, start=(-1.5, 2.0), goal=(3.0, 4.5))
    assert sc.units.name == "m" and sc.units.resolution == RES and sc.units.dt == 0.25
    d = sc.to_dict()
    assert (d["width"], d["height"]) == pytest.approx((6.0, 4.0))
    assert d["start"] == pytest.approx([0.5, 0.5]) and d["goal"] == pytest.approx([5.0, 3.0])
    assert (d["robot"]["radius"], d["robot"]["speed"]) == (0.3, 1.0)
    got = obstacles_ros(sc)
    assert got.symmetric_difference(EXPECTED_ROS).area == pytest.approx(0.0, abs=1e-9)
    wall, door, unknown = (1.05, 4.95), (1.05, 3.45), (3.5, 2.0)
    assert got.contains(shapely.Point(wall)) and got.contains(shapely.Point(unknown))
    assert not got.intersects(shapely.Point(door).buffer(0.3))  # the robot fits in the door
    m = read_ros_map(ros_map)
    assert m.origin == ORIGIN and m.to_scenario(wall) == pytest.approx([3.05, 3.45])
    assert m.to_ros(m.to_scenario(door)) == pytest.approx(door)


def test_negate_both_ways(tmp_path):
    inverted = 255 - hand_map()  # obstacles white, free black, unknown 50
    write_pgm(tmp_path / "inv.pgm", inverted)
    neg = read_ros_map(write_yaml(tmp_path / "neg.yaml", image="inv.pgm", negate=1))
    write_pgm(tmp_path / "map.pgm", hand_map())
    plain = read_ros_map(write_yaml(tmp_path / "map.yaml"))
    assert np.array_equal(neg.blocked, plain.blocked)
    assert plain.blocked.sum() == 60 + 2 * (39 - 10) + 100
    # the plain image read negated: only the black cells (p = 1) were occupied, the free
    # 254 ones are now occupied and the unknown 205 ones (p = 0.80) too: only black is free
    swapped = read_ros_map(write_yaml(tmp_path / "swap.yaml", negate=1))
    assert np.array_equal(swapped.blocked, hand_map() != 0)


def test_ascii_pgm_and_png_read_the_same(tmp_path):
    write_pgm(tmp_path / "map.pgm", hand_map())
    binary = read_ros_map(write_yaml(tmp_path / "map.yaml")).blocked
    write_pgm(tmp_path / "a.pgm", hand_map(), ascii_=True)
    assert np.array_equal(read_ros_map(write_yaml(tmp_path / "a.yaml", image="a.pgm")).blocked,
                          binary)  # fmt: skip
    Image.fromarray(hand_map()).save(tmp_path / "m.png")
    assert np.array_equal(read_ros_map(write_yaml(tmp_path / "p.yaml", image="m.png")).blocked,
                          binary)  # fmt: skip
    assert read_pgm(tmp_path / "a.pgm")[0, 0] == 0.0 and read_pgm(tmp_path / "a.pgm")[1, 0] == (
        254 / 255
    )


def test_modes_scale_and_raw(tmp_path):
    grey = np.array([[0, 100, 150, 254, 255]], dtype=np.uint8)
    write_pgm(tmp_path / "g.pgm", grey)
    # occupancy 1 - v/255: 1.0, 0.61, 0.41, 0.004, 0.0; free below 0.196
    scale = read_ros_map(write_yaml(tmp_path / "s.yaml", image="g.pgm", mode="scale"))
    assert scale.blocked.tolist() == [[True, True, True, False, False]]
    # raw: v / 100 is the occupancy, over 100 unknown; free below 0.196 -> only 0
    raw = read_ros_map(write_yaml(tmp_path / "r.yaml", image="g.pgm", mode="raw", negate=1))
    assert raw.blocked.tolist() == [[False, True, True, True, True]]
    # scale mode with a transparent pixel: unknown whatever its colour
    rgba = np.zeros((1, 2, 4), dtype=np.uint8)
    rgba[..., :3] = 254
    rgba[0, 0, 3], rgba[0, 1, 3] = 255, 0
    Image.fromarray(rgba, "RGBA").save(tmp_path / "t.png")
    t = read_ros_map(write_yaml(tmp_path / "t.yaml", image="t.png", mode="scale"))
    assert t.blocked.tolist() == [[False, True]]
    # trinary averages the opacity in: (254 * 3 + 0) / 4 = 190.5 -> p = 0.25: unknown
    t = read_ros_map(write_yaml(tmp_path / "t3.yaml", image="t.png"))
    assert t.blocked.tolist() == [[False, True]]


def test_round_trip(ros_map, tmp_path):
    sc = load_ros_map(ros_map, start=(-1.5, 2.0), goal=(3.0, 4.5))
    m = read_ros_map(ros_map)
    out = save_ros_map(sc, tmp_path / "out" / "saved.yaml", origin=m.origin)
    back = read_ros_map(out)
    assert np.array_equal(back.blocked, m.blocked)
    assert (back.resolution, back.origin) == (m.resolution, m.origin)
    assert (tmp_path / "out" / "saved.pgm").read_bytes().startswith(b"P5")
    again = load_ros_map(out, start=(-1.5, 2.0), goal=(3.0, 4.5), name=sc.name)
    assert again.to_dict() == sc.to_dict()
    # a coarser grid: a 0.5 m cell is blocked when its centre is, the centre of the 0.1 m
    # cell 2 + 5 k along each axis (x = 0.25 + 0.5 k; y from the top, 3.75 - 0.5 k)
    coarse = read_ros_map(save_ros_map(sc, tmp_path / "out" / "c.yaml", resolution=0.5))
    assert coarse.blocked.shape == (8, 12)
    assert np.array_equal(coarse.blocked, m.blocked[2::5, 2::5])


def test_save_rasterises_circles_and_refuses_pixels(tmp_path):
    from mawdo.planning.world.scenario import get_scenario, scenario_from_dict

    sc = scenario_from_dict({
        "schema_version": 1, "name": "disc", "units": "m", "dt": 0.1, "resolution": 0.05,
        "width": 1.0, "height": 0.5, "start": [0.1, 0.1], "goal": [0.9, 0.4],
        "robot": {"radius": 0.05, "speed": 1.0},
        "obstacles": [{"shape": "circle", "center": [0.5, 0.25], "radius": 0.12}],
    })  # fmt: skip
    m = read_ros_map(save_ros_map(sc, tmp_path / "d.yaml"))
    rows, cols = np.indices((10, 20))
    cx, cy = (cols + 0.5) * 0.05, (10 - rows - 0.5) * 0.05
    assert np.array_equal(m.blocked, np.hypot(cx - 0.5, cy - 0.25) < 0.12)
    with pytest.raises(ValueError, match="in pixels"):
        save_ros_map(get_scenario("paper"), tmp_path / "p.yaml")


def test_bad_maps_are_clear_errors(tmp_path):
    write_pgm(tmp_path / "map.pgm", hand_map())
    with pytest.raises(FileNotFoundError, match="'gone.pgm' is not there"):
        read_ros_map(write_yaml(tmp_path / "a.yaml", image="gone.pgm"))
    write_pgm(tmp_path / "short.pgm", hand_map()[:-1], header=f"P5\n{COLS} {ROWS}\n255\n")
    with pytest.raises(ScenarioError, match="2400 pixels, the file holds 2340"):
        read_ros_map(write_yaml(tmp_path / "b.yaml", image="short.pgm"))
    (tmp_path / "colour.pgm").write_bytes(b"P6\n2 1\n255\n" + bytes(6))
    with pytest.raises(ScenarioError, match="not a grey PGM"):
        read_ros_map(write_yaml(tmp_path / "c.yaml", image="colour.pgm"))
    (tmp_path / "deep.pgm").write_bytes(b"P5\n1 1\n65535\n\x00\x00")
    with pytest.raises(ScenarioError, match="only 8-bit"):
        read_ros_map(write_yaml(tmp_path / "d.yaml", image="deep.pgm"))
    cases = [
        ({"occupied_thresh": 0.1}, "occupied_thresh: 0.1 must be greater than free_thresh"),
        ({"occupied_thresh": 1.5}, r"occupied_thresh: must be a probability in \[0, 1\]"),
        ({"free_thresh": -0.1}, r"free_thresh: must be a probability in \[0, 1\]"),
        ({"mode": "fancy"}, "unknown mode 'fancy': use one of trinary, scale, raw"),
        ({"origin": "[-2.0, 1.5, 0.5]"}, "yaw 0.5 rad: rotated maps are not supported"),
        ({"origin": "[1, 2]"}, r"origin: must be \[x, y, yaw\]"),
        ({"resolution": 0}, "resolution: must be metres per cell, > 0"),
        ({"negate": 2}, "negate: must be 0 or 1"),
        ({"free_thresh": None}, "free_thresh: required"),
    ]
    for fields, message in cases:
        with pytest.raises(ScenarioError, match=message):
            read_ros_map(write_yaml(tmp_path / "e.yaml", **fields))
    with pytest.raises(ScenarioError, match="start: "):
        load_ros_map(write_yaml(tmp_path / "f.yaml"), start=(1.05, 4.95), goal=(3.0, 4.5))


def test_the_command_plans_on_a_ros_map(ros_map, tmp_path):
    from tests.cli_run import mawdo

    out = tmp_path / "out"
    done = mawdo("plan", "run", str(ros_map), "--start", "-1.5,2.0", "--goal", "3.0,4.5",
                 "--preset", "quick", "--max-steps", "3", "--no-figures", "--no-progress",
                 "--out", str(out))  # fmt: skip
    assert done.returncode == 0, done.stderr
    metrics = json.loads((out / "metrics.json").read_text())
    assert (metrics["units"], metrics["resolution_m"], metrics["dt_s"]) == ("m", RES, 0.25)
    bad = [
        ((str(ros_map), "--goal", "3,4.5"), "a ROS map needs --start as x,y in ROS world metres"),
        ((str(ros_map), "--start", "1;2", "--goal", "3,4.5"), "--start '1;2': give x,y"),
        (("paper", "--start", "1,2"), "--start: only for a ROS map (.yaml)"),
        ((str(write_yaml(tmp_path / "x.yaml", image="no.pgm")), "--start", "0,2", "--goal",
          "3,4.5"), "'no.pgm' is not there"),
        ((str(ros_map), "--start", "1.05,4.95", "--goal", "3,4.5"), "start: inside"),
    ]  # fmt: skip
    for args, message in bad:
        done = mawdo("plan", "run", *args, "--out", str(tmp_path / "never"))
        assert done.returncode == 2 and message in done.stderr, (args, done.stderr)
    assert not (tmp_path / "never").exists()
