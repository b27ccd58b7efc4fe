"""Never drive into an inevitable collision (issue 27, item 2): :mod:`mawdo.planning.safety.ics` in
the run loop.

Hand-built scenes whose outcome follows from the geometry by hand: a bar spanning the map's
height cannot be passed around, so only the robot's x motion matters. References are the
independent checker (shapely) on trajectories written out by hand.
"""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.refine.cost import assemble_paths
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.execute import Run
from mawdo.planning.run.planner import plan
from mawdo.planning.run.result import Drive
from mawdo.planning.safety.guard import Guard
from mawdo.planning.safety.ics import SafeContinuation
from mawdo.planning.scenes import generate_scene
from mawdo.planning.world.path import densify
from mawdo.planning.world.scenario import scenario_from_dict

R, V, C = 4.0, 4.0, 0.5  # robot radius, speed (px, px per step), the planner's margin (px)


def _bar(x0: float, motion: dict, width: float = 400.0, start=100.0, goal=300.0):
    """A 10 px wide bar over the whole height (100 px), left edge at ``x0``."""
    bar = [[x0, 0.0], [x0 + 10, 0.0], [x0 + 10, 100.0], [x0, 100.0]]
    return scenario_from_dict({
        "schema_version": 1, "width": width, "height": 100.0,
        "start": [start, 50.0], "goal": [goal, 50.0], "robot": {"radius": R, "speed": V},
        "obstacles": [{"shape": "polygon", "id": "bar", "vertices": bar, "motion": motion}],
    })  # fmt: skip


def _closing_bar():
    """The bar's left edge: 115 at t = 0, 6 px per step toward the robot (x = 100), parked
    at 105 from t = 10/6 for 30 steps, then off to 380. At t = 1 it is at 109."""
    motion = {"model": "patrol", "speed": 6.0, "waypoints": [[-10.0, 0.0], [265.0, 0.0]],
              "waits": [0.0, 30.0, 1e6]}  # fmt: skip
    return _bar(115.0, motion)


def _standing(p, t0: float, steps: int) -> np.ndarray:
    return np.repeat(np.asarray(p, float)[None], steps + 1, axis=0), t0


def test_the_rule_refuses_a_safe_stretch_into_an_inevitable_collision():
    """One step forward (x 100 -> 104) keeps 109 - 104 = 5 >= r + margin from the bar: the
    guard alone drives it. From x = 104 at t = 1 the bar (6 px per step) parks at 105, and a
    retreat at full speed leaves a gap of 5 - 2 s (s steps after t = 1): the discs overlap at
    s = 0.5, whatever the robot does. Standing at x = 100 keeps 105 - 100 = 5 > r."""
    sc = _closing_bar()
    start, fwd = sc.start, np.array([sc.start, sc.goal])
    assert Guard(sc, C).stretch_hits(fwd, 0.0, V) == 0
    ics = SafeContinuation(sc, C, horizon=30)
    assert not ics.after_stretch(fwd, 0.0, V)
    # the checker: every 2-step motion from (104, 50) at t = 1 (17 headings x speeds 0, 2, 4
    # per step) collides, the full-speed retreat included; standing at the start never does
    ang = np.linspace(0.0, 2.0 * np.pi, 17)
    steps = np.vstack([[0.0, 0.0], *(s * np.column_stack([np.cos(ang), np.sin(ang)])
                                      for s in (2.0, 4.0))])  # fmt: skip
    here = np.array([104.0, 50.0])
    for a in steps:
        for b in steps:
            traj = np.array([here, here + a, here + a + b])
            assert not check_trajectory(traj, sc, t0=1.0).ok, (a, b)
    assert check_trajectory(*_standing(start, 0.0, 100)[:1], sc).ok
    # the real planner's guard: offered only that stretch, it waits (the rule on) or drives it
    for horizon, waits in ((30, 1), (0, 0)):
        run = Run(sc, "mawdo", 0, PlannerConfig(ics_horizon=horizon), dynamic=True)
        cands = densify(fwd, run.m).reshape(1, -1)
        chosen = run.choose(cands, start.copy(), 0, V)
        drive = Drive(start)
        if chosen is None:
            assert np.array_equal(run._fallback(drive, start.copy(), 0, cands), start)
        else:
            np.testing.assert_allclose(chosen, assemble_paths(cands, start, sc.goal)[0])
        assert run.counts["waits"] == waits and run.counts["inevitable"] == 0


def _creeping_bar():
    """The bar (left edge 100) blocks the way for good and creeps 8 px toward the robot and
    back at 0.1 px per step (edge at 100 - 0.1 t until t = 80): a robot stopped at the bar's
    margin is hit later."""
    motion = {"model": "patrol", "speed": 0.1, "waypoints": [[-8.0, 0.0]],
              "cycle": "back_and_forth"}  # fmt: skip
    return _bar(100.0, motion, width=200.0, start=40.0, goal=180.0)


def test_a_run_that_gives_up_stops_where_waiting_is_safe():
    sc = _creeping_bar()
    ends = {}
    for horizon in (30, 0):
        res = plan(sc, "mawdo", seed=0, config="realtime", ics_horizon=horizon, give_up_steps=5)
        assert "gave up" in res.reason
        rep = check_trajectory(res.route, sc, times=res.route_times)
        assert rep.ok, rep.describe()
        still, t0 = _standing(res.trajectory[-1], float(res.steps), 30)
        ends[horizon] = check_trajectory(still, sc, t0=t0)
    # with the rule the robot stands clear of the bar for the horizon; without it, where it
    # stopped the creeping bar runs into it (a passive hit after the run)
    assert ends[30].ok and ends[30].min_clearance >= 0.0
    assert not ends[0].ok and ends[0].passive


def test_settle_moves_off_a_spot_that_a_mover_will_hit():
    """The bar of :func:`_creeping_bar` at t = 20 has its edge at 98; a robot at x = 92 is hit
    when the edge passes 96 (t = 40). Settling drives back to a spot the checker finds clear
    for the horizon."""
    sc = _creeping_bar()
    run = Run(sc, "mawdo", 0, PlannerConfig(ics_horizon=30), dynamic=True)
    here = np.array([92.0, 50.0])
    assert not check_trajectory(*_standing(here, 20.0, 30)[:1], sc, t0=20.0).ok
    drive = Drive(here)
    pos, note = run._settle(drive, here.copy(), 20)
    assert "waiting is safe" in note and pos[0] < here[0]
    moved = np.array(drive.traj)
    assert check_trajectory(moved, sc, t0=20.0).ok
    t_end = 20.0 + len(moved) - 1
    assert check_trajectory(*_standing(pos, t_end, 30)[:1], sc, t0=t_end).ok


def test_chaser_is_evaded_without_an_active_collision():
    """A chaser scene: the disc behind the robot is faster than it and catches a robot that
    drives the straight line at full speed (the checker); the default planner evades."""
    scene = generate_scene("chaser", 0, seed=0)
    sc = scene.scenario
    d = float(np.hypot(*(sc.goal - sc.start)))
    n = int(np.ceil(d / sc.robot_speed))
    line = sc.start + np.minimum(np.arange(n + 1) * sc.robot_speed / d, 1.0)[:, None] * (
        sc.goal - sc.start
    )
    assert check_trajectory(line, sc).active
    res = plan(sc, "mawdo", seed=0, config="realtime")
    rep = check_trajectory(res.route, sc, times=res.route_times)
    assert not rep.active, rep.describe()
    assert res.success, res.reason
    assert res.inevitable == 0


def test_paper_scenario_runs_as_before_where_the_rule_never_fires():
    """On the paper's scenario every chosen stretch keeps a safe continuation, so the rule
    changes nothing: the run with it is the run without it, step for step."""
    on = plan("paper", "mawdo", seed=0, config="quick")
    off = plan("paper", "mawdo", seed=0, config="quick", ics_horizon=0)
    assert on.inevitable == 0 and on.success
    np.testing.assert_array_equal(on.trajectory, off.trajectory)
    assert (on.waits, on.evasions, on.fallbacks) == (off.waits, off.evasions, off.fallbacks)


def _dense_18():
    from mawdo.experiments.kinds.arena import arena_preset
    from mawdo.planning.scenes import generate_scene

    scene = generate_scene("dense", 18, seed=0)
    return scene.scenario, arena_preset("arena-default").planner_seed("dense", 18)


def test_the_rule_sees_random_walkers_as_the_guard_does():
    """A walker's seeded future, not a disc growing for ``ics_horizon`` steps: among seven
    walkers of ``dense`` no spot stays clear of 30-step discs, so with them the rule refused
    the stretches the guard accepted and the run gave up (arena-default, 0.9.0 before this)."""
    from mawdo.planning.world.motion import BoundedRandomWalk

    sc, seed = _dense_18()
    assert sum(isinstance(o.motion, BoundedRandomWalk) for o in sc.obstacles) >= 5
    assert SafeContinuation.walkers == "known"
    res = plan(sc, "mawdo", seed=seed)
    assert res.success and res.collision_free, res.reason
    assert res.inevitable == 0 and res.waits == 0


@pytest.mark.slow
def test_growing_walker_discs_make_the_rule_give_up_on_dense_18(monkeypatch):
    sc, seed = _dense_18()
    monkeypatch.setattr(SafeContinuation, "walkers", "reachable")
    res = plan(sc, "mawdo", seed=seed)
    assert not res.success and "gave up" in res.reason
