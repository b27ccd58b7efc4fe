"""Scenes serialise to the scenario schema (TOML) and read back equal."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from mawdo.planning.guide.oracle import scenario_optimum
from mawdo.planning.scenes import FAMILIES, generate_scene, scenario_to_toml
from mawdo.planning.scenes.toml import toml_value
from mawdo.planning.world.scenario import get_scenario, load_scenario

FAST = {"forest": {"n": 8}, "rooms": {"rows": 2, "cols": 3}, "dense": {"n": 10}}


@pytest.mark.parametrize("family", list(FAMILIES))
def test_round_trip_write_load_equal(family, tmp_path):
    sc = generate_scene(family, 1, seed=3, params=FAST.get(family))
    path = sc.write(tmp_path)
    assert path == tmp_path / f"{sc.name}.toml"
    back = load_scenario(path)
    assert back.to_dict() == sc.scenario.to_dict()
    # the same world: obstacle motion (random walks included) and the optimum
    t = np.array([0.0, 7.5, 123.0])
    np.testing.assert_array_equal(back.offsets(t), sc.scenario.offsets(t))
    assert scenario_optimum(back).length == sc.l_star
    # `mawdo plan FILE` resolves files through get_scenario
    assert get_scenario(str(path)).to_dict() == sc.scenario.to_dict()


def test_writer_to_an_explicit_file_and_reader_agree_on_text(tmp_path):
    sc = generate_scene("crossing", 0, seed=1)
    path = sc.write(tmp_path / "x.toml")
    assert path.read_text() == sc.to_toml()
    assert tomllib.loads(sc.to_toml()) == sc.scenario.to_dict()


@pytest.mark.parametrize(
    "value",
    [
        "plain",
        'quote " and \\ backslash',
        "new\nline\ttab",
        "unicode é ✓",
        "",
        0.1,
        1e-300,
        -2.5e17,
        366.0,
        7,
        -3,
        True,
        [1.5, [2, 3]],
        {"a": 1, "b": [0.25]},
    ],
)
def test_toml_values_read_back_exactly(value):
    assert tomllib.loads(f"x = {toml_value(value)}")["x"] == value


@pytest.mark.parametrize("bad", [math.inf, math.nan])
def test_non_finite_numbers_are_refused(bad):
    with pytest.raises(ValueError, match="non-finite"):
        toml_value(bad)


def test_scenario_to_toml_accepts_a_dict():
    d = {"schema_version": 1, "start": [1.0, 2.0], "goal": [3.0, 4.0], "obstacles": []}
    assert tomllib.loads(scenario_to_toml(d)) == {k: v for k, v in d.items() if k != "obstacles"}
