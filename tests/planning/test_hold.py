"""Holding a straight plan (PlannerConfig.hold_straight): when, and what it changes."""

import numpy as np
import pytest

from mawdo.planning.run.config import PRESETS, PlannerConfig
from mawdo.planning.run.execute import Run
from mawdo.planning.run.planner import plan
from mawdo.planning.scenes import generate_scene
from mawdo.planning.world.path import polyline_length

from . import maps


def _crossing_scene(mover_y0: float):
    """Start and goal on y = 183; one disc moving down across x = 183 (time steps, 4 px each)."""
    obstacles = [
        {
            "id": "mover",
            "shape": "circle",
            "center": [183.0, mover_y0],
            "radius": 8.0,
            "motion": {"model": "constant_velocity", "velocity": [0.0, 2.0]},
        }
    ]
    return maps._scenario("cross", obstacles, (20.0, 183.0), (346.0, 183.0))


def _run(sc, **cfg):
    return Run(sc, "mawdo", 0, PlannerConfig(**cfg), dynamic=True)


def test_holds_only_a_straight_plan_the_guard_clears_to_the_goal():
    line = np.linspace([20.0, 183.0], [346.0, 183.0], 12)
    # the disc reaches y = 183 at t = 86.5, long after the robot (at x = 183 near t = 41) passed
    clear = _run(_crossing_scene(10.0))
    assert clear._holds(line, False, 0)
    # reaching y = 183 at t = 41 it hits the robot there: the plan is straight, but not held
    hit = _run(_crossing_scene(101.0))
    assert not hit._holds(line, False, 0)
    assert hit.guard.stretch_hits(line, 0.0, polyline_length(line)) > 0
    # not straight: one waypoint 1e-3 px off the line
    bent = line.copy()
    bent[5, 1] += 1e-3
    assert not clear._holds(bent, False, 0)
    # collinear but doubling back
    back = np.vstack([line[:6], line[3:4], line[6:]])
    assert not clear._holds(back, False, 0)
    # forced replans, the first plan, the frozen-map cost mode and the switch itself
    assert not clear._holds(line, True, 0)
    assert not clear._holds(None, False, 0)
    assert not _run(_crossing_scene(10.0), mode="snapshot")._holds(line, False, 0)
    assert not _run(_crossing_scene(10.0), hold_straight=False)._holds(line, False, 0)


@pytest.mark.parametrize("family", ["forest", "dense", "crossing"])
@pytest.mark.parametrize("algorithm", ["mawdo", "gwo"])
def test_holding_drives_the_same_length_with_fewer_replans(family, algorithm):
    # a held plan costs the least any candidate can: re-optimising it cannot shorten the route
    sc = generate_scene(family, 1, 0).scenario
    kept = plan(sc, algorithm, seed=1, config="quick", hold_gap=0.0)
    full = plan(sc, algorithm, seed=1, config="quick", hold_straight=False, hold_gap=0.0)
    assert kept.success and kept.collision_free and full.success
    assert polyline_length(kept.route) == pytest.approx(polyline_length(full.route), rel=1e-12)
    assert full.holds == 0
    assert len(kept.replans) + kept.holds == len(full.replans)
    assert kept.holds > 0 and kept.nfev < full.nfev


def test_the_paper_presets_replan_every_step():
    assert not PRESETS["paper"].hold_straight and not PRESETS["study"].hold_straight
    assert PRESETS["realtime"].hold_straight


def test_holds_are_stored_and_old_payloads_read_as_none_held():
    import io

    from mawdo.planning.run.result import result_from_bytes, result_to_bytes

    sc = generate_scene("forest", 1, 0).scenario
    res = plan(sc, "mawdo", seed=1, config="quick")
    assert res.holds > 0
    back = result_from_bytes(result_to_bytes(res), sc)
    assert back.holds == res.holds and back.waits == res.waits
    # a payload from before holds existed has four events
    z = dict(np.load(io.BytesIO(result_to_bytes(res)), allow_pickle=False))
    z["events"] = z["events"][:4]
    buf = io.BytesIO()
    np.savez_compressed(buf, **z)
    old = result_from_bytes(buf.getvalue(), sc)
    assert old.holds == 0 and old.near_misses == res.near_misses


def test_with_sparse_replans_only_replan_steps_can_be_held():
    sc = generate_scene("forest", 1, 0).scenario
    kept = plan(sc, "mawdo", seed=1, config="quick", replan_every=3, hold_gap=0.0)
    full = plan(
        sc, "mawdo", seed=1, config="quick", replan_every=3, hold_straight=False, hold_gap=0.0
    )
    assert kept.holds > 0 and kept.collision_free
    assert len(kept.replans) + kept.holds == len(full.replans) < full.steps
