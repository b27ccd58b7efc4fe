"""The guide gate (PlannerConfig.guide_gate): a (re)plan takes the guides' own answer without a
search exactly when the guides certify it, and the run stays as safe and as short."""

import numpy as np
import pytest

from mawdo.planning.run.config import PRESETS, PlannerConfig
from mawdo.planning.run.execute import Run
from mawdo.planning.run.gate import certifies, plain_seeds
from mawdo.planning.run.planner import plan
from mawdo.planning.run.result import result_from_bytes, result_to_bytes
from mawdo.planning.world.path import densify, polyline_length

from . import maps
from .test_hold import _crossing_scene

START, GOAL = np.array([20.0, 183.0]), np.array([346.0, 183.0])


def _run(sc, **cfg):
    return Run(sc, "mawdo", 0, PlannerConfig(**{"pop_size": 40, "first_iters": 20, **cfg}), True)


def test_certifies_exactly_the_routes_within_the_gap_of_the_shortest_and_free_to_the_goal():
    corner = np.array([START, [183.0, 150.0], GOAL])  # 2.0 % over the straight line
    excess = polyline_length(corner) / polyline_length(np.array([START, GOAL])) - 1
    x = densify(corner, 18).reshape(-1)  # a candidate: inner waypoints (start, goal added)
    for gap, expected in ((1.1 * excess, True), (0.9 * excess, False), (0.0, False)):
        run = _run(_crossing_scene(10.0), hold_gap=gap, n_waypoints=18, auto_waypoints=False)
        assert run.guide.shortest(START) == pytest.approx(326.0)  # nothing static in the way
        assert certifies(run, START, 0, x) is expected
    # the same route while the disc crosses it when the robot is there: not free to the goal
    hit = _run(_crossing_scene(67.0), hold_gap=1.1 * excess, n_waypoints=18, auto_waypoints=False)
    assert not certifies(hit, START, 0, x)


def test_the_first_plan_is_gated_where_the_shortest_route_is_free_and_searched_where_not():
    clear = _run(_crossing_scene(10.0), guide_gate=True)
    cands, _ = clear.optimise(START, 0, None)
    n_seeds = len(plain_seeds(clear, START, 0, None))
    assert clear.counts["gated"] == 1 and clear.stalled
    assert clear.replans[-1].nfev == n_seeds == len(cands)
    assert clear.replans[-1].length <= (1 + clear.cfg.hold_gap) * clear.guide.shortest(START)
    # the disc crosses the straight line as the robot gets there: the swarm searches
    blocked = _run(_crossing_scene(101.5), guide_gate=True)  # at y = 183 as the robot is
    blocked.optimise(START, 0, None)
    assert blocked.counts["gated"] == 0
    assert blocked.replans[-1].nfev > 20 * 40  # first_iters x pop_size, beside the seeds
    # the switch: without it the clear scene searches too
    off = _run(_crossing_scene(10.0))
    off.optimise(START, 0, None)
    assert off.counts["gated"] == 0 and off.replans[-1].nfev > 20 * 40


@pytest.mark.parametrize("build", [maps.serpentine_maze, maps.u_trap, maps.rooms])
def test_on_static_maps_the_gated_run_searches_nothing_and_is_no_longer(build):
    sc = build(3)
    gated = plan(sc, "mawdo", seed=2, config="quick", guide_gate=True)
    full = plan(sc, "mawdo", seed=2, config="quick")
    assert gated.success and gated.collision_free and full.success
    assert gated.gated >= 1 and full.gated == 0
    assert all(len(r.history) == 1 for r in gated.replans)  # no optimizer iteration at all
    assert gated.nfev < full.nfev / 20
    gap = gated.config.hold_gap
    assert polyline_length(gated.route) <= polyline_length(full.route) * (1 + gap)


def test_with_movers_every_gated_plan_is_certified_and_the_run_stays_safe():
    sc = maps.serpentine_maze(4, moving=3)
    res = plan(sc, "mawdo", seed=0, config="quick", guide_gate=True)
    assert res.success and res.collision_free and res.gated > 0
    run = Run(sc, "mawdo", 0, res.config, True)
    gap, gated = res.config.hold_gap, [r for r in res.replans if len(r.history) == 1]
    assert len(gated) == res.gated
    for r in gated:
        assert r.collisions == 0
        assert r.length <= (1 + gap) * run.guide.shortest(r.position) * (1 + 1e-12)


def test_the_count_is_stored_and_ungated_payloads_stay_as_they_were():
    sc = maps.u_trap(3)
    gated = plan(sc, "mawdo", seed=2, config="quick", guide_gate=True)
    assert result_from_bytes(result_to_bytes(gated), sc).gated == gated.gated > 0
    full = plan(sc, "mawdo", seed=2, config="quick")
    z = np.load(__import__("io").BytesIO(result_to_bytes(full)))
    assert len(z["events"]) == 7  # the layout every stored result was written with
    assert result_from_bytes(result_to_bytes(full), sc).gated == 0


def test_presets_and_validation():
    # the paper's planner and the study's measure the optimizer alone; the default one gates
    assert not PRESETS["paper"].guide_gate and not PRESETS["study"].guide_gate
    assert PRESETS["realtime"].guide_gate and not PRESETS["large"].guide_gate
    with pytest.raises(ValueError, match="guide_gate"):
        PlannerConfig(guide_gate="yes")


def test_no_gate_under_acceleration_or_turn_limits_where_the_shortest_route_is_not_fastest():
    # a speed cap alone scales every arrival alike: the gate applies
    capped = _run(_crossing_scene(10.0), guide_gate=True, max_speed=3.0)
    capped.optimise(START, 0, None)
    assert capped.counts["gated"] == 1
    for limit in ({"max_accel": 0.5}, {"max_turn": 0.6}):
        run = _run(_crossing_scene(10.0), guide_gate=True, **limit)
        assert run.limits is not None
        run.optimise(START, 0, None)
        assert run.counts["gated"] == 0 and run.replans[-1].nfev > 20 * 40
