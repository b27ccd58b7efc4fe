"""The checker's index (``check_trajectory(reach=...)``) against measuring every pair."""

import numpy as np
import pytest

from mawdo.planning import check_trajectory, scenario_from_dict
from mawdo.planning.judge import check as checkmod
from mawdo.planning.judge import check_index
from mawdo.planning.world.stepped import with_movers
from tests.planning.test_kernel_index import SIZE
from tests.planning.test_kernel_index import _world as kernel_world

W = H = SIZE


def _world(seed: int, movers: int = 40):
    """The kernel index's random worlds (every kind of motion, circles and polygons, a few
    standing shapes), people's recorded tracks, and a wandering route through them."""
    sc = kernel_world(seed, movers=movers, standing=2)
    rng = np.random.default_rng([seed, 5])
    # people as the stepped world records them: tracks through their centres, one a step
    times = np.arange(200.0)
    walks = [np.cumsum(rng.uniform(-2, 2, (200, 2)), axis=0) + rng.uniform(60, W - 60, 2)
             for _ in range(8)]  # fmt: skip
    sc = with_movers(sc, rng.uniform(3, 6, 8), [(times, w) for w in walks])
    # a wandering route: moves of up to 6 px, some rests, a few steps past the border
    steps = rng.uniform(-6, 6, (120, 2)) * (rng.random((120, 1)) > 0.15)
    route = np.clip(np.array([W / 2, H / 2]) + np.cumsum(steps, axis=0), -2, W + 2)
    times = 3.0 + np.cumsum(rng.uniform(0.3, 1.5, len(route)))
    return sc, route, times


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("reach", [0.0, 4.0, 25.0])
def test_indexed_check_equals_measuring_every_pair(seed, reach):
    sc, route, times = _world(seed)
    every = check_trajectory(route, sc, times=times, reach=np.inf)
    near = check_trajectory(route, sc, times=times, reach=reach)
    for field in ("ok", "collisions", "active", "passive", "border", "border_excess"):
        assert getattr(near, field) == getattr(every, field), field
    measured = np.isfinite(near.clearance)
    # what is measured is measured alike, bit for bit; what is left out is farther than reach
    np.testing.assert_array_equal(near.clearance[measured], every.clearance[measured])
    assert np.all(every.clearance[~measured] > reach - 1e-6)
    assert (~measured).any()  # the index does leave pairs out on these worlds
    if every.min_clearance <= reach:
        assert near.min_clearance == every.min_clearance


def test_the_worlds_have_collisions_to_find():
    worlds = map(_world, range(6))
    hits = [check_trajectory(r, sc, times=t, reach=np.inf).collisions for sc, r, t in worlds]
    assert sum(map(len, hits)) > 0  # the verdicts compared above are not all empty


def test_by_default_the_index_takes_over_among_many_movers(monkeypatch):
    sc, route, times = _world(3)
    every = check_trajectory(route, sc, times=times)
    assert np.isfinite(every.clearance).all()  # 40 movers: every pair measured
    monkeypatch.setattr(checkmod, "INDEX_MOVERS", 10)
    auto = checkmod.check_trajectory(route, sc, times=times)
    want = check_trajectory(route, sc, times=times, reach=checkmod.INDEX_REACH * sc.robot_radius)
    np.testing.assert_array_equal(auto.clearance, want.clearance)
    assert not np.isfinite(auto.clearance).all()
    short = checkmod.check_trajectory(route[:5], sc, times=times[:5])  # too few steps to sort
    assert np.isfinite(short.clearance).all()


@pytest.mark.parametrize("bad", [-1.0, float("nan")])
def test_a_negative_reach_is_refused(bad):
    sc, route, times = _world(0, movers=2)
    with pytest.raises(ValueError, match="reach"):
        check_trajectory(route, sc, times=times, reach=bad)


def test_an_obstacle_that_swings_out_and_back_within_one_step_is_not_missed():
    # out 50 px and back in one step of 10: at both ends of the step it is home, 50 px away
    swing = {"model": "patrol", "waypoints": [[50, 0]], "speed": 10.0, "cycle": "back_and_forth"}
    sc = scenario_from_dict({
        "schema_version": 1, "width": W, "height": H, "start": [8, 8], "goal": [292, 292],
        "robot": {"radius": 3.0, "speed": 4.0},
        "obstacles": [{"shape": "circle", "center": [100, 150], "radius": 5, "motion": swing}],
    })  # fmt: skip
    route, times = np.array([[150.0, 150.0], [150.0, 150.0]]), np.array([0.0, 10.0])
    every = check_trajectory(route, sc, times=times, reach=np.inf)
    near = check_trajectory(route, sc, times=times, reach=1.0)
    assert every.collisions == near.collisions == ((0, 0),)
    box = check_index.swept_boxes(sc.obstacles[0], times)
    np.testing.assert_allclose(box, [[95, 145, 155, 155]])
