"""Scenarios in metres and seconds (``units = "m"``): the conversion to the planner's pixels and
time steps, checked against values computed by hand; the run identical to that of the pixel
scenario written by hand; metrics, messages and figures in metres and seconds; the file's
round trip; every refusal, in the library and through ``mawdo plan`` (exit 2)."""

from __future__ import annotations

import copy
import json
import math
import tomllib

import numpy as np
import pytest

from mawdo.planning import ScenarioError, get_scenario, load_scenario, scenario_from_dict
from mawdo.planning.judge.metrics import in_units, run_metrics
from mawdo.planning.run.planner import plan
from mawdo.planning.scenes.toml import scenario_to_toml
from mawdo.planning.world.units import PIXELS, Units
from tests.cli_run import mawdo

RES, DT = 0.05, 0.25  # metres per pixel, seconds per step

# 10 m x 8 m, a 0.3 m robot at 1 m/s, a static triangle, a disc moving at 0.5 m/s, a patrol
# that waits 1 s and 0.5 s, and a random walk holding each velocity 1 s.
METRE_TOML = """\
schema_version = 1
name = "metre-demo"
seed = 3
units = "m"
dt = 0.25
resolution = 0.05
width = 10.0
height = 8.0
start = [1.0, 1.0]
goal = [9.0, 7.0]
robot = { radius = 0.3, speed = 1.0 }

[[obstacles]]
shape = "polygon"
vertices = [[3.0, 2.0], [4.0, 2.0], [4.0, 3.5]]

[[obstacles]]
shape = "circle"
center = [5.0, 4.0]
radius = 0.4
motion = { velocity = [0.0, 0.5] }

[[obstacles]]
shape = "circle"
center = [7.0, 2.0]
radius = 0.4
motion = { model = "patrol", waypoints = [[1.0, 0.0]], speed = 0.5, waits = [1.0, 0.5] }

[[obstacles]]
shape = "circle"
center = [2.0, 6.0]
radius = 0.4
motion = { model = "bounded_random_walk", step = 0.4, hold = 1.0 }
"""

# The same scenario converted by hand: lengths / 0.05 m, speeds * 0.25 s / 0.05 m, times /
# 0.25 s. 0.3 / 0.05 is 6 exactly, but not in binary floating point: the nearest double of the
# quotient is 5.999999999999999, and it is what both files must plan with.
PIXEL_DICT = {
    "schema_version": 1,
    "name": "metre-demo",
    "seed": 3,
    "width": 200.0,
    "height": 160.0,
    "start": [20.0, 20.0],
    "goal": [180.0, 140.0],
    "robot": {"radius": 5.999999999999999, "speed": 5.0},
    "obstacles": [
        {"shape": "polygon", "vertices": [[60.0, 40.0], [80.0, 40.0], [80.0, 70.0]]},
        {"shape": "circle", "center": [100.0, 80.0], "radius": 8.0,
         "motion": {"velocity": [0.0, 2.5]}},
        {"shape": "circle", "center": [140.0, 40.0], "radius": 8.0,
         "motion": {"model": "patrol", "waypoints": [[20.0, 0.0]], "speed": 2.5,
                    "waits": [4.0, 2.0]}},
        {"shape": "circle", "center": [40.0, 120.0], "radius": 8.0,
         "motion": {"model": "bounded_random_walk", "step": 2.0, "hold": 4}},
    ],
}  # fmt: skip


def metre_dict() -> dict:
    return tomllib.loads(METRE_TOML)


def errors_of(data) -> list[tuple[str, str]]:
    with pytest.raises(ScenarioError) as info:
        scenario_from_dict(data)
    return info.value.errors


# --------------------------------------------------------------------------------------------
# Units


def test_units_convert_both_ways_with_hand_computed_values():
    u = Units("m", dt=DT, resolution=RES)
    assert u.length(20.0) == pytest.approx(1.0) and u.length_to_px(1.0) == pytest.approx(20.0)
    # 5 px per step = 5 * 0.05 m / 0.25 s = 1 m/s
    assert u.speed(5.0) == pytest.approx(1.0) and u.speed_to_px(1.0) == pytest.approx(5.0)
    assert u.time(4) == pytest.approx(1.0) and u.time_to_steps(1.0) == pytest.approx(4.0)
    # 1 px per step^2 = 0.05 m / 0.0625 s^2 = 0.8 m/s^2
    assert u.accel(1.0) == pytest.approx(0.8) and u.accel_to_px(0.8) == pytest.approx(1.0)
    # 0.1 rad per step = 0.4 rad/s
    assert u.rate(0.1) == pytest.approx(0.4) and u.rate_to_step(0.4) == pytest.approx(0.1)
    arr = u.length(np.array([0.0, 20.0, 40.0]))
    np.testing.assert_allclose(arr, [0.0, 1.0, 2.0])
    labels = (u.length_label, u.time_label, u.speed_label, u.accel_label, u.rate_label)
    assert labels == ("m", "s", "m/s", "m/s^2", "rad/s")


def test_pixel_units_are_the_identity_with_pixel_labels():
    u = PIXELS
    x = np.array([1.5, 2.5])
    for fn in (u.length, u.time, u.speed, u.accel, u.rate, u.length_to_px, u.time_to_steps,
               u.speed_to_px, u.accel_to_px, u.rate_to_step):  # fmt: skip
        assert fn(x) is x and fn(0.1) == 0.1
    assert (u.length_label, u.time_label, u.speed_label) == ("px", "steps", "px/step")
    assert get_scenario("paper").units == PIXELS


@pytest.mark.parametrize(
    "kw",
    [{"name": "m"}, {"name": "m", "dt": 0.1}, {"name": "m", "dt": 0.0, "resolution": 0.1},
     {"name": "m", "dt": math.inf, "resolution": 0.1}, {"name": "px", "dt": 0.1},
     {"name": "km", "dt": 0.1, "resolution": 0.1}],
)  # fmt: skip
def test_units_refuse_an_incomplete_or_wrong_description(kw):
    with pytest.raises(ValueError):
        Units(**kw)


# --------------------------------------------------------------------------------------------
# loading, planning, round trip


def test_a_metre_file_loads_with_the_hand_converted_pixel_values(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(METRE_TOML)
    sc = load_scenario(path)
    assert sc.units == Units("m", dt=0.25, resolution=0.05)
    # every caller reads pixels and steps: the spec is the hand-converted pixel scenario
    assert sc.spec == scenario_from_dict(PIXEL_DICT).spec
    assert (sc.width, sc.height, sc.robot_speed) == (200.0, 160.0, 5.0)
    assert sc.robot_radius == pytest.approx(6.0, abs=1e-12)
    hold = sc.spec.obstacles[3].motion.hold
    assert hold == 4 and isinstance(hold, int)
    assert sc.spec.obstacles[2].motion.waits == [4.0, 2.0]
    # the moving disc: 0.5 m/s = 2.5 px per step, so 10 px (0.5 m) after 4 steps (1 s)
    np.testing.assert_allclose(sc.offsets(4.0)[1], [0.0, 10.0])


def test_a_metre_scenario_round_trips_in_metres():
    sc = scenario_from_dict(metre_dict())
    d = sc.to_dict()
    assert d["units"] == "m" and (d["dt"], d["resolution"]) == (DT, RES)
    assert (d["width"], d["robot"]) == (10.0, {"radius": 0.3, "speed": 1.0})
    assert d["obstacles"][3]["motion"]["hold"] == 1.0
    assert json.loads(json.dumps(d)) == d
    again = scenario_from_dict(d)
    assert again.to_dict() == d and again.spec == sc.spec and again.units == sc.units
    # through the TOML writer as well
    assert scenario_from_dict(tomllib.loads(scenario_to_toml(sc))).to_dict() == d


def test_a_pixel_scenario_writes_no_unit_field():
    sc = scenario_from_dict(PIXEL_DICT)
    assert not {"units", "dt", "resolution"} & set(sc.to_dict())
    explicit = scenario_from_dict({**PIXEL_DICT, "units": "px"})
    assert explicit.to_dict() == sc.to_dict()


def test_replacing_the_pixel_spec_of_a_metre_scenario_is_refused():
    from dataclasses import replace

    sc = scenario_from_dict(metre_dict())
    moved = sc.spec.model_copy(update={"start": (30.0, 20.0)})
    with pytest.raises(ValueError, match="not the pixel conversion"):
        replace(sc, spec=moved)
    assert replace(sc, spec=sc.spec).to_dict() == sc.to_dict()


def test_a_metre_scenario_plans_as_its_pixel_twin_and_reports_metres_and_seconds():
    metre = scenario_from_dict(metre_dict())
    pixel = scenario_from_dict(PIXEL_DICT)
    a = plan(metre, "mawdo", seed=1, config="quick")
    b = plan(pixel, "mawdo", seed=1, config="quick")
    assert a.success and b.success
    np.testing.assert_array_equal(a.trajectory, b.trajectory)  # bit for bit, in px
    np.testing.assert_array_equal(a.route, b.route)
    m_px = run_metrics(b, snapshots=0)
    assert run_metrics(a, snapshots=0)["length_px"] == m_px["length_px"]
    m = in_units(run_metrics(a, snapshots=0), metre.units)
    assert "length_px" not in m and "min_clearance_px" not in m and "l_star_px" not in m
    assert m["length_m"] == pytest.approx(m_px["length_px"] * RES, rel=1e-15)
    assert m["min_clearance_m"] == pytest.approx(m_px["min_clearance_px"] * RES, rel=1e-15)
    assert m["l_star_m"] == pytest.approx(m_px["l_star_px"] * RES, rel=1e-15)
    assert m["steps"] == a.steps and m["arrival_s"] == pytest.approx(a.steps * DT)
    # the path is at least the straight line: hand-computed hypot(8, 6) = 10 m
    assert m["length_m"] >= 10.0 - 1e-9
    assert list(in_units(m_px, pixel.units)) == list(m_px)


def test_in_units_keeps_missing_values_and_converts_t_star():
    u = Units("m", dt=DT, resolution=RES)
    m = {"success": False, "length_px": None, "steps": 12, "t_star": 40.0, "time_gap": math.nan}
    out = in_units(m, u)
    assert out == {"success": False, "length_m": None, "steps": 12, "arrival_s": None,
                   "t_star_s": 10.0, "time_gap": out["time_gap"]}  # fmt: skip
    assert math.isnan(out["time_gap"])


# --------------------------------------------------------------------------------------------
# refusals


def _without(*keys):
    def change(d):
        for k in keys:
            d.pop(k)

    return change


BAD = {
    "dt zero": (lambda d: d.update(dt=0.0), [("dt", "must be > 0 (seconds per time step), got 0")]),
    "dt negative": (lambda d: d.update(dt=-0.5), [("dt", "must be > 0")]),
    "resolution zero": (lambda d: d.update(resolution=0), [("resolution", "must be > 0 (metres")]),
    "no dt": (_without("dt"), [("dt", 'required with units = "m" (seconds per time step')]),
    "no resolution": (_without("resolution"), [("resolution", 'required with units = "m"')]),
    "pixel with dt": (_without("units"), [("dt", 'only for units = "m"'),
                                          ("resolution", 'only for units = "m"')]),
    "unknown units": (lambda d: d.update(units="km"), [("units", 'must be "px"')]),
    "default width": (_without("width"), [("width", "its default is in pixels")]),
    "default speed": (lambda d: d["robot"].pop("speed"), [("robot.speed", "default is in pixel")]),
    "hold not whole steps": (
        lambda d: d["obstacles"][3]["motion"].update(hold=0.3),
        [("obstacles[3].motion.hold", "0.3 s is not a whole number of time steps of dt = 0.25 s; "
                                      "give a multiple of dt (e.g. 0.25 or 0.5 s)")],
    ),
    "hold not positive": (lambda d: d["obstacles"][3]["motion"].update(hold=0),
                          [("obstacles[3].motion.hold", "must be > 0")]),
    "map too fine": (lambda d: d.update(resolution=1e-5),
                     [("resolution", "1e-05 m per px makes the 10 x 8 m map 1e+06 x 8e+05 px, "
                                     "more than the 100000 px a side the planner takes; give a "
                                     "resolution of at least 0.0001 m per px")]),
}  # fmt: skip


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_unit_fields_are_named_with_the_fix(case):
    change, expected = BAD[case]
    data = metre_dict()
    change(data)
    errors = errors_of(data)
    assert [p for p, _ in errors] == [p for p, _ in expected]
    for (_, msg), (_, part) in zip(errors, expected, strict=True):
        assert part in msg


def test_whole_scenario_messages_of_a_metre_file_are_in_metres():
    data = metre_dict()
    data["start"] = [0.1, 1.0]
    ((path, msg),) = errors_of(data)
    assert path == "start"
    assert msg == ("(0.1, 1) is closer than the robot radius 0.3 m to the map border (the disc "
                   "would leave the map); allowed: [0.3, 9.7] x [0.3, 7.7]")  # fmt: skip
    data = metre_dict()
    data["robot"]["speed"] = 1e-7  # 1e-7 * 0.25 / 0.05 = 5e-7 px per step
    ((path, msg),) = errors_of(data)
    # the diagonal hypot(10, 8) = 12.81 m takes 12.81 / 1e-7 = 1.28e8 s
    assert path == "robot.speed" and msg.startswith("1e-07 m/s is too slow for a 10 x 8 m map")
    assert "(12.81 m) would take 1.28e+08 s" in msg and "m/s" in msg.rsplit("[", 1)[1]


def test_a_pixel_file_keeps_its_messages():
    data = copy.deepcopy(PIXEL_DICT)
    data["start"] = [2.0, 20.0]
    ((_, msg),) = errors_of(data)
    assert msg.startswith("(2, 20) is closer than the robot radius 6 px to the map border")


# --------------------------------------------------------------------------------------------
# the command line


def _write(tmp_path, data: dict):
    path = tmp_path / "s.json"
    path.write_text(json.dumps(data))
    return path


CLI_CASES = ["dt zero", "resolution zero", "no dt", "no resolution", "pixel with dt",
             "hold not whole steps"]  # fmt: skip


@pytest.mark.parametrize("case", CLI_CASES)
def test_plan_refuses_bad_unit_fields_with_exit_2(tmp_path, case):
    change, expected = BAD[case]
    data = metre_dict()
    change(data)
    out = tmp_path / "out"
    res = mawdo("plan", str(_write(tmp_path, data)), "--out", str(out), "--no-progress",
                "--no-figures")  # fmt: skip
    assert res.returncode == 2, (res.returncode, res.stderr)
    assert "Traceback" not in res.stderr + res.stdout
    for path, part in expected:
        assert path in res.stderr and part.split(";")[0] in " ".join(res.stderr.split())
    assert not out.exists()


def test_plan_prints_and_saves_metres_and_seconds(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(METRE_TOML)
    out = tmp_path / "out"
    res = mawdo("plan", str(path), "--preset", "quick", "--seed", "1", "--out", str(out),
                "--no-progress", "--no-figures")  # fmt: skip
    assert res.returncode == 0, res.stderr
    saved = json.loads((out / "metrics.json").read_text())
    assert (saved["units"], saved["dt_s"], saved["resolution_m"]) == ("m", DT, RES)
    assert "length_px" not in saved and "length_px" not in res.stdout
    direct = plan(scenario_from_dict(PIXEL_DICT), "mawdo", seed=1, config="quick")
    assert saved["steps"] == direct.steps and saved["arrival_s"] == direct.steps * DT
    assert saved["length_m"] == pytest.approx(run_metrics(direct, snapshots=0)["length_px"] * RES)
    assert "length_m:" in res.stdout and "arrival_s:" in res.stdout


# --------------------------------------------------------------------------------------------
# figures


def test_figures_of_a_metre_run_label_metres_and_seconds():
    import matplotlib

    matplotlib.use("Agg")
    from mawdo.planning import render
    from mawdo.planning.render.world import legend_handles

    sc = scenario_from_dict(metre_dict())
    res = plan(sc, "mawdo", seed=1, config="quick", max_steps=12)
    fig = render.snapshot_figure({"mawdo": res}, times=[0.0, 4.0, 6.0, 12.0],
                                 metrics={"mawdo": {"length_px": 200.0}})  # fmt: skip
    fig.canvas.draw()
    axes = [ax for ax in fig.axes if ax.get_visible() and ax.get_title()]
    assert [ax.get_title() for ax in axes] == ["t = 0 s", "t = 1 s", "t = 1.5 s", "t = 3 s"]
    assert {ax.get_xlabel() for ax in axes} - {""} == {"x (m)"}
    assert {ax.get_ylabel() for ax in axes} - {""} == {"y (m)"}
    # ticks at round metres, placed in the panel's pixels (1 m = 20 px)
    ax = axes[0]
    np.testing.assert_allclose(ax.get_xticks(), np.arange(0.0, 201.0, 40.0))
    assert [t.get_text() for t in ax.get_xticklabels()] == ["0", "2", "4", "6", "8", "10"]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["0", "2", "4", "6", "8"]
    assert "length 10.00 m" in fig.subfigs[0].get_suptitle()  # 200 px * 0.05 m
    labels = [h.get_label() for h in legend_handles(sc.robot_radius, sc.units)]
    assert "robot (to scale), r = 0.3 m" in labels and "obstacle track (6.25 s)" in labels
    pixel = [h.get_label() for h in legend_handles(4.0)]
    assert "robot (to scale), r = 4 px" in pixel and "obstacle track (25 steps)" in pixel
    from mawdo.planning.render.animation import GifFrame

    gif = GifFrame(sc, "MAWDO", 1, optimum=False)
    assert (gif.ax.get_xlabel(), gif.ax.get_ylabel()) == ("x (m)", "y (m)")
    assert [t.get_text() for t in gif.ax.get_xticklabels()] == ["0", "2", "4", "6", "8", "10"]


def test_the_documented_metre_example_is_the_hand_converted_map():
    import re
    from pathlib import Path

    page = Path(__file__).parents[2] / "docs" / "reference" / "scenario-schema.md"
    blocks = re.findall(r"```toml\n(.*?)```", page.read_text("utf-8"), re.S)
    (text,) = [b for b in blocks if 'units = "m"' in b]
    sc = scenario_from_dict(tomllib.loads(text))
    assert (sc.width, sc.height, sc.robot_speed) == (200.0, 160.0, 5.0)  # as its comments say
    assert sc.spec.obstacles[1].motion.velocity == (0.0, 2.5)


def test_waiting_spots_of_a_metre_file_are_converted_and_written_back():
    data = metre_dict()
    data["spots"] = [[6.0, 6.5]]
    sc = scenario_from_dict(data)
    np.testing.assert_array_equal(sc.spots, [[120.0, 130.0]])  # 6 / 0.05, 6.5 / 0.05
    assert sc.to_dict()["spots"] == [[6.0, 6.5]]
    data["spots"] = [[3.5, 2.5]]  # inside the triangle inflated by 0.3 m
    ((path, msg),) = errors_of(data)
    assert path == "spots[0]" and msg.startswith("(3.5, 2.5) is inside static obstacles[0]")
    assert "robot radius 0.3 m" in msg
