"""Holding a plan after a stalled search (PlannerConfig.hold_gap): when, and what it costs."""

import numpy as np
import pytest

from mawdo.planning.run.config import PRESETS, PlannerConfig
from mawdo.planning.run.execute import Run
from mawdo.planning.run.planner import plan
from mawdo.planning.world.path import polyline_length

from . import maps
from .test_hold import _crossing_scene


def _run(sc, **cfg):
    return Run(sc, "mawdo", 0, PlannerConfig(**cfg), dynamic=True)


def _bent():
    """A plan with a corner at (183, 150): not straight, so only a stalled search can hold it."""
    return np.array([[20.0, 183.0], [183.0, 150.0], [346.0, 183.0]])


def test_holds_a_stalled_plan_only_near_the_shortest_route_and_cleared_to_the_goal():
    bent = _bent()  # 2 % longer than the straight line, which is free of static obstacles
    excess = polyline_length(bent) / 326.0 - 1
    clear = _run(_crossing_scene(10.0), hold_gap=0.03)
    assert not clear._holds(bent, False, 0)  # no stalled search yet
    clear.stalled = True
    assert clear._holds(bent, False, 0)
    # the same plan is too long for a tighter gap
    tight = _run(_crossing_scene(10.0), hold_gap=0.9 * excess)
    tight.stalled = True
    assert not tight._holds(bent, False, 0)
    # the same plan while a disc crosses it when the robot is there: replan
    hit = _run(_crossing_scene(67.0), hold_gap=0.03)
    hit.stalled = True
    assert hit.guard.stretch_hits(bent, 0.0, polyline_length(bent)) > 0
    assert not hit._holds(bent, False, 0)
    # forced replans, the first plan, the frozen-map cost mode, no guide, and the switch itself
    assert not clear._holds(bent, True, 0)
    assert not clear._holds(None, False, 0)
    for cfg in ({"mode": "snapshot"}, {"hold_gap": 0.0}, {"guide_routes": 0}):
        other = _run(_crossing_scene(10.0), **{"hold_gap": 0.03, **cfg})
        other.stalled = True
        assert not other._holds(bent, False, 0)


def test_a_search_that_returns_its_warm_start_is_stalled_and_one_that_improves_is_not():
    sc = maps._scenario("empty", [], (20.0, 183.0), (346.0, 183.0))
    run = _run(sc, pop_size=40, replan_iters=5)
    start = np.array([20.0, 183.0])
    # the straight line costs the least any path can: nothing beats the warm start
    run.optimise(start, 3, np.array([start, [346.0, 183.0]]))
    assert run.stalled
    # a detour through (183, 60) is easily shortened
    detour = np.array([start, [183.0, 60.0], [346.0, 183.0]])
    run.optimise(start, 3, detour)
    assert not run.stalled
    assert run.replans[-1].length < polyline_length(detour)


@pytest.mark.parametrize("build", [maps.serpentine_maze, maps.u_trap, maps.rooms])
@pytest.mark.parametrize("algorithm", ["mawdo", "woa"])
def test_stalled_holds_save_searches_on_static_maps_at_no_cost_in_length(build, algorithm):
    # with nothing moving, a search that found nothing better has nothing new to find later
    sc = build(3)
    kept = plan(sc, algorithm, seed=2, config="quick")
    full = plan(sc, algorithm, seed=2, config="quick", hold_gap=0.0)
    assert kept.success and kept.collision_free and full.success
    assert kept.holds > 0 and kept.nfev < full.nfev
    gap = kept.config.hold_gap
    assert polyline_length(kept.route) <= polyline_length(full.route) * (1 + gap)


def test_with_moving_obstacles_every_held_step_is_verified_and_the_run_stays_safe():
    sc = maps.serpentine_maze(4, moving=3)
    res = plan(sc, "mawdo", seed=0, config="quick")
    assert res.success and res.collision_free and res.holds > 0


def test_presets_and_validation():
    assert PRESETS["paper"].hold_gap == 0 and PRESETS["study"].hold_gap == 0
    assert PRESETS["realtime"].hold_gap > 0
    for bad in (-0.1, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="hold_gap"):
            PlannerConfig(hold_gap=bad)


def test_the_guides_shortest_length_is_its_first_routes():
    from mawdo.planning.run.execute import guide_for

    sc = maps.u_trap(1)
    guide = guide_for(sc, 0.5, 6)
    for pos in (sc.start, np.array([60.0, 300.0]), np.array([300.0, 40.0])):
        route = guide.routes(pos)[0]
        assert route[0] == pytest.approx(pos)
        assert guide.shortest(pos) == pytest.approx(polyline_length(route), rel=1e-12)
