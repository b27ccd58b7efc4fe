"""Obstacle motion is bounded as the robot's speed is: a mover faster than the map's diagonal
per step, one that bounces or turns more than 16 times a step, and a patrol of more than
10 000 waypoints are refused naming the field and the bound; anything inside loads."""

from __future__ import annotations

import math

import pytest

from mawdo.planning import ScenarioError, scenario_from_dict


def _scene(motion, shape=None):
    ob = shape or {"shape": "circle", "center": [100.0, 100.0], "radius": 5.0}
    return {
        "schema_version": 1, "width": 200.0, "height": 200.0, "start": [10.0, 10.0],
        "goal": [190.0, 190.0], "robot": {"radius": 2.0, "speed": 4.0},
        "obstacles": [ob | {"motion": motion}],
    }  # fmt: skip


DIAG = math.hypot(200.0, 200.0)  # 282.8 px


@pytest.mark.parametrize(
    "motion, field, bound",
    [
        ({"velocity": [1e5, 0.0]}, "obstacles[0].motion.velocity", f"{DIAG:.4g}"),
        ({"velocity": [1e6, 1e6]}, "obstacles[0].motion.velocity", f"{DIAG:.4g}"),
        (
            {"model": "patrol", "waypoints": [[10.0, 0.0]], "speed": 1e9},
            "obstacles[0].motion.speed",
            f"{DIAG:.4g}",
        ),
        ({"model": "bounded_random_walk", "step": 1e4}, "obstacles[0].motion.step", f"{DIAG:.4g}"),
        # a 20 px lap with 2 corners: 16 corners a step at 160 px per step
        (
            {"model": "patrol", "waypoints": [[10.0, 0.0]], "speed": 200.0},
            "obstacles[0].motion.speed",
            "at most 160 px",
        ),
    ],
)
def test_a_mover_too_fast_for_the_map_is_refused_with_the_bound(motion, field, bound):
    with pytest.raises(ScenarioError) as err:
        scenario_from_dict(_scene(motion))
    text = str(err.value)
    assert field in text and bound in text, text


def test_a_mover_bouncing_in_a_narrow_span_is_refused():
    # a 190 px wide bar in a 200 px map has 10 px to move in x: 16 bounces a step at 160 px
    bar = {"shape": "polygon", "vertices": [[5, 90], [195, 90], [195, 110], [5, 110]]}
    with pytest.raises(ScenarioError, match=r"at most 160 px per step along x"):
        scenario_from_dict(_scene({"velocity": [170.0, 0.0]}, bar))
    assert scenario_from_dict(_scene({"velocity": [150.0, 0.0]}, bar)) is not None


def test_a_patrol_with_too_many_waypoints_is_refused():
    pts = [[float(i % 50), 0.0] for i in range(10_001)]
    with pytest.raises(ScenarioError, match=r"10,001 waypoints; a patrol may have 10,000"):
        scenario_from_dict(_scene({"model": "patrol", "waypoints": pts, "speed": 1.0}))


def test_fast_movers_within_the_bounds_load():
    for motion in (
        {"velocity": [200.0, 0.0]},
        {"model": "patrol", "waypoints": [[50.0, 0.0]], "speed": 280.0},
        {"model": "bounded_random_walk", "step": 280.0},
    ):
        assert scenario_from_dict(_scene(motion)).moving_indices == [0]
