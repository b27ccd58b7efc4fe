"""People in scenario files: the ``[crowd]`` table, its errors, and ``mawdo plan run`` on it."""

import json
import os
import tomllib
from pathlib import Path

import numpy as np
import pytest

from mawdo.planning.people.from_scenario import people_of
from mawdo.planning.world.scenario import ScenarioError, scenario_from_dict
from tests.cli_run import mawdo

HALL = Path(__file__).resolve().parents[1] / "data" / "crowd" / "hall.toml"


def _hall(**crowd_changes) -> dict:
    data = tomllib.loads(HALL.read_text())
    data["crowd"] = {**data["crowd"], **crowd_changes}
    return data


def test_people_load_in_pixels_with_their_models_settings():
    sc = scenario_from_dict(_hall())
    # 0.05 m per px: 10 m -> 200 px, 0.3 m -> 6 px; 1 m/s at 0.25 s per step -> 5 px per step
    first = sc.spec.crowd.people[0]
    assert np.allclose(first.start, (200.0, 84.0)) and np.allclose(first.goal, (30.0, 80.0))
    assert first.radius == pytest.approx(6.0) and first.speed == pytest.approx(5.0)
    people = people_of(sc)
    assert np.allclose(people.positions(), [[200.0, 84.0], [180.0, 64.0]])
    assert np.allclose(people.preferred_speed, [5.0, 4.0])
    assert scenario_from_dict(sc.to_dict()).to_dict() == sc.to_dict()  # round trip, metres


def test_a_crowd_needs_metres():
    person = {"start": [50, 50], "goal": [80, 80], "radius": 5, "speed": 2}
    data = {"schema_version": 1, "start": [10, 10], "goal": [100, 100],
            "crowd": {"people": [person]}}  # fmt: skip
    with pytest.raises(ScenarioError, match="people need a metre scenario"):
        scenario_from_dict(data)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"model": "boids"}, "crowd.model"),
        (
            {"people": [{"start": [10.0, 4.0], "goal": [6.0, 1.0], "radius": 0.3, "speed": 1.0}]},
            "inside a wall",
        ),
        (
            {"people": [{"start": [10.0, 4.0], "goal": [2.0, 4.0], "radius": -0.3, "speed": 1.0}]},
            "radius",
        ),
        (
            {"people": [{"start": [1.2, 4.0], "goal": [2.0, 6.0], "radius": 0.3, "speed": 1.0}]},
            "overlaps the robot's start",
        ),
        (
            {"people": [{"start": [10.0, 7.9], "goal": [2.0, 6.0], "radius": 0.3, "speed": 1.0}]},
            "inside the map",
        ),
    ],
)
def test_bad_people_are_refused_naming_the_field(change, message):
    with pytest.raises(ScenarioError, match=message):
        scenario_from_dict(_hall(**change))


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    ("edit", "args", "message"),
    [
        (("goal = [1.5, 4.0]", "goal = [6.0, 1.0]"), (), "inside a wall"),
        (("", ""), ("--knowledge", "psychic"), "--knowledge 'psychic'"),
        (("visible = false", "visible = true"), ("--knowledge", "oracle"), "see the robot"),
        (("", ""), ("--knowledge", "oracle", "--sensor-noise", "0.1"), "--knowledge observed"),
    ],
)
def test_cli_bad_crowd_input_exits_2(tmp_path, edit, args, message):
    text = HALL.read_text().replace(*edit)
    path = _write(tmp_path / "hall.toml", text)
    proc = mawdo("plan", "run", str(path), "--out", str(tmp_path / "out"), *args)
    assert proc.returncode == 2, proc.stderr
    assert message in proc.stderr.replace("\n", " ")
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_cli_runs_a_crowd_scenario_observed_and_reports_metres(tmp_path):
    proc = mawdo("plan", "run", str(HALL), "--out", str(tmp_path), "--no-figures",
                 "--no-progress", "--preset", "quick")  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    m = json.loads((tmp_path / "metrics.json").read_text())
    assert m["units"] == "m" and m["success"] is True and m["algorithm"] == "mawdo"
    assert 10.0 <= m["length_m"] <= 14.0  # the 10 m straight line, detours around two people


def test_cli_unknown_or_oracle_predictor_exits_2(tmp_path):
    for name, message in (("psychic", "unknown predictor"), ("oracle", "true future")):
        proc = mawdo("plan", "run", str(HALL), "--out", str(tmp_path / "out"), "--predictor", name)
        assert proc.returncode == 2 and message in proc.stderr.replace("\n", " "), proc.stderr


def test_cli_without_pyrvo_names_the_extra_and_exits_2(tmp_path):
    # a pyrvo that cannot be imported, first on the path: what a machine without the extra sees
    (tmp_path / "pyrvo").mkdir()
    (tmp_path / "pyrvo" / "__init__.py").write_text("raise ImportError('no RVO2 here')\n")
    path = f"{tmp_path}{os.pathsep}{os.environ.get('PYTHONPATH', '')}"
    proc = mawdo("plan", "run", str(HALL), "--out", str(tmp_path / "out"),
                 env={"PYTHONPATH": path})  # fmt: skip
    assert proc.returncode == 2, proc.stderr
    assert "pip install 'mawdo[crowd]'" in proc.stderr.replace("\n", " ")
