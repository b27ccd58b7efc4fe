"""The comfort term: a near pass costs exactly ``alpha * comfort_weight`` per (segment, mover)
pair, hand-counted; the paper's parts are untouched; and the refiner, given two equally short
routes around a block, takes the one farther from a walking person."""

import math

import numpy as np
import pytest

from mawdo.planning.refine.comfort import ComfortPathCost
from mawdo.planning.refine.cost import PathCost
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.planner import plan
from mawdo.planning.world.scenario import scenario_from_dict


def _scene(walker_y: float, block: bool = True):
    obstacles = [{"shape": "circle", "center": [100.0, walker_y], "radius": 5.0,
                  "motion": {"velocity": [0.02, 0.0]}}]  # fmt: skip
    if block:
        obstacles.insert(
            0, {"shape": "polygon", "vertices": [[90, 55], [110, 55], [110, 85], [90, 85]]}
        )
    return scenario_from_dict({
        "schema_version": 1, "name": "comfort", "width": 200.0, "height": 140.0,
        "start": [20.0, 70.0], "goal": [180.0, 70.0], "robot": {"radius": 4.0, "speed": 4.0},
        "obstacles": obstacles,
    })  # fmt: skip


def test_a_near_pass_costs_its_weight_per_pair_and_nothing_else_changes():
    sc = _scene(101.0, block=False)  # the walker 31 px above the straight line
    paper = PathCost(sc, "spacetime", n_waypoints=1, clearance=0.5)
    comfy = ComfortPathCost(sc, "spacetime", n_waypoints=1, clearance=0.5, comfort=6.0,
                            comfort_weight=8.0)  # fmt: skip
    # one waypoint: up to y = 88 (both segments reach within 13 px of the walker's centre:
    # no hit at r + R + clearance = 9.5, near within 9.5 + 6 = 15.5), or down to y = 52
    # (the mirror image: 49 px away, far)
    X = np.array([[100.0, 88.0], [100.0, 52.0]])
    c0, c1 = paper(X, t0=0.0), comfy(X, t0=0.0)
    assert np.array_equal(paper.parts(X)[1], [0, 0])  # collision-free, both
    assert c0[0] == pytest.approx(c0[1], rel=1e-12)  # equally long and turning
    assert list(comfy.near_pairs(X)) == [2, 0]
    assert c1[0] - c0[0] == pytest.approx(0.45 * 8.0 * 2, rel=1e-12)
    assert c1[1] == c0[1]
    for a, b in zip(paper.parts(X), comfy.parts(X), strict=True):  # the paper's terms
        assert np.array_equal(a, b)


def test_comfort_input_is_checked():
    sc = _scene(101.0)
    with pytest.raises(ValueError, match="comfort must be finite and > 0"):
        ComfortPathCost(sc, comfort=0.0, comfort_weight=1.0)
    with pytest.raises(ValueError, match="comfort_weight"):
        ComfortPathCost(sc, comfort=1.0, comfort_weight=-1.0)
    with pytest.raises(ValueError, match="PlannerConfig.comfort=-1"):
        PlannerConfig(comfort=-1.0)
    with pytest.raises(ValueError, match="PlannerConfig.comfort_weight=nan"):
        PlannerConfig(comfort_weight=math.nan)


def _crossing_height(result) -> float:
    route = np.asarray(result.route)
    return float(np.interp(100.0, route[:, 0], route[:, 1]))


def test_the_refiner_leaves_room_to_a_walker_when_asked():
    # two equally short ways round the block (above, below); a person walks slowly above it
    sc = _scene(101.0)
    plain = plan(sc, "mawdo", seed=0, config="quick")
    comfy = plan(sc, "mawdo", seed=0, config="quick", comfort=6.0)
    assert plain.success and comfy.success
    assert _crossing_height(plain) > 85.0  # above: close by the walker
    assert _crossing_height(comfy) < 55.0  # below: the far side
    assert comfy.collision_free
