"""Waiting spots carried by a scenario (``spots``): the file format, its validation, and the
run's safe-interval guide using them as ``T*``'s search does."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from mawdo.planning import ScenarioError, load_scenario, scenario_from_dict
from mawdo.planning.guide.sipp.optimum import dodge_spots
from mawdo.planning.guide.timeguide import TimeGuide
from mawdo.planning.scenes import generate_scene
from mawdo.planning.scenes.toml import write_scenario


def _spec(**extra) -> dict:
    return {
        "schema_version": 1, "width": 100.0, "height": 100.0, "start": [10.0, 10.0],
        "goal": [90.0, 90.0], "robot": {"radius": 4.0, "speed": 4.0},
        "obstacles": [{"shape": "polygon", "vertices": [[40, 40], [60, 40], [60, 60], [40, 60]]}],
        **extra,
    }  # fmt: skip


def test_spots_round_trip_through_toml_and_json(tmp_path):
    sc = scenario_from_dict(_spec(spots=[[20.0, 80.0], [75.5, 30.25]]))
    assert np.array_equal(sc.spots, [[20.0, 80.0], [75.5, 30.25]])
    back = load_scenario(write_scenario(sc, tmp_path / "s.toml"))
    assert np.array_equal(back.spots, sc.spots) and back.to_dict() == sc.to_dict()
    js = tmp_path / "s.json"
    js.write_text(__import__("json").dumps(sc.to_dict()))
    assert np.array_equal(load_scenario(js).spots, sc.spots)


def test_a_scenario_without_spots_reads_and_hashes_as_before():
    sc = scenario_from_dict(_spec())
    assert sc.spots.shape == (0, 2)
    assert "spots" not in sc.to_dict()  # files (and their SHA-256) without spots unchanged


@pytest.mark.parametrize(
    ("spot", "why"),
    [
        ([50.0, 50.0], r"spots\[1\]: \(50, 50\) is inside static obstacles\[0\]"),
        ([41.0, 37.0], r"spots\[1\]: \(41, 37\) is inside static obstacles\[0\] inflated"),
        ([2.0, 50.0], r"spots\[1\]: \(2, 50\) is closer than the robot radius 4 px to the map"),
        ([150.0, 50.0], r"spots\[1\]: \(150, 50\) is outside the map \[0, 100\] x \[0, 100\]"),
    ],
)
def test_a_spot_the_robot_cannot_hold_is_named_with_the_fix(spot, why):
    with pytest.raises(ScenarioError, match=why) as info:
        scenario_from_dict(_spec(spots=[[20.0, 80.0], spot]))
    assert "move or drop" in str(info.value)


def test_a_moving_obstacle_may_cross_a_spot():
    mover = {"shape": "circle", "center": [20.0, 80.0], "radius": 5.0,
             "motion": {"velocity": [1.0, 0.0]}}  # fmt: skip
    sc = scenario_from_dict({**_spec(spots=[[20.0, 80.0]]), "obstacles": [mover]})
    assert len(sc.spots) == 1


def test_a_bad_spot_in_a_file_is_a_cli_error(tmp_path):
    bad = tmp_path / "bad.toml"
    write_scenario(scenario_from_dict(_spec()), bad)
    bad.write_text(
        bad.read_text().replace("[[obstacles]]", "spots = [[50.0, 50.0]]\n\n[[obstacles]]", 1)
    )
    proc = subprocess.run(
        [sys.executable, "-m", "mawdo.cli", "plan", "run", str(bad)],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert proc.returncode == 2, proc.stderr
    assert "error:" in proc.stderr and "spots[0]" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_timed_scenes_carry_the_spots_their_t_star_used():
    scene = generate_scene("corridor", 2, seed=0)
    assert len(scene.spots) > 0
    assert np.array_equal(scene.scenario.spots, scene.spots)
    # the scene file keeps them (a planner given only the file sees what T* saw)
    assert np.array_equal(scenario_from_dict(scene.scenario.to_dict()).spots, scene.spots)


def test_the_run_guide_uses_the_scenarios_spots_and_still_dodges():
    scene = generate_scene("corridor", 2, seed=0)
    sc = scene.scenario
    route = scene.optimum
    with_spots = TimeGuide(sc, 0.5, 1, [route]).spots
    rows = {tuple(p) for p in with_spots}
    assert all(tuple(p) in rows for p in dodge_spots(route, sc))  # the dodge spots stay
    bays = [
        tuple(p) for p in sc.spots if tuple(p) not in {tuple(q) for q in dodge_spots(route, sc)}
    ]
    assert bays and all(p in rows for p in bays)  # every scene spot is usable at 0.5 px here
    bare = scenario_from_dict({k: v for k, v in sc.to_dict().items() if k != "spots"})
    assert {tuple(p) for p in TimeGuide(bare, 0.5, 1, [route]).spots} == {
        tuple(p) for p in dodge_spots(route, bare)
    }


def test_the_scenes_bays_bring_the_run_guide_to_t_star():
    """corridor-2: the earliest timed route from the start waits in a bay; with the
    scenario's spots the run's guide (0.5 px margin) arrives within 2 % of T*, without them
    (dodge spots only) it arrives over 20 % later."""
    from mawdo.planning.guide.sipp.guide import SafeIntervalGuide
    from mawdo.planning.run.execute import guide_for

    scene = generate_scene("corridor", 2, seed=0)
    sc = scene.scenario
    bare = scenario_from_dict({k: v for k, v in sc.to_dict().items() if k != "spots"})
    arrival = []
    for s in (sc, bare):
        spots = TimeGuide(s, 0.5, 1, guide_for(s, 0.5, 6).routes(s.start)).spots
        arrival.append(SafeIntervalGuide(s, clearance=0.5, spots=spots).routes(1)[0].arrival)
    assert scene.t_star <= arrival[0] <= 1.02 * scene.t_star
    assert arrival[1] >= 1.2 * scene.t_star
