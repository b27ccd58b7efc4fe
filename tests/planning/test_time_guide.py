"""The safe-interval guide in the run loop (issue 27): ``time_guide``, ``mawdo_time``,
``guide_only`` and the time metrics."""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest

from mawdo.planning.guide.timeguide import TimeGuide
from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.judge.metrics import run_metrics
from mawdo.planning.run.planner import plan
from mawdo.planning.run.planners import PLANNERS, run_planner
from mawdo.planning.safety.guard import Guard
from mawdo.planning.scenes import generate_scene


@cache
def _scene(family: str, index: int):
    return generate_scene(family, index, seed=0)


def _still_runs(traj: np.ndarray) -> list[tuple[int, int]]:
    """(first step, length) of each run of steps in which the robot does not move."""
    still = np.all(np.abs(np.diff(traj, axis=0)) < 1e-9, axis=1)
    runs, start = [], None
    for i, s in enumerate([*still, False]):
        if s and start is None:
            start = i
        elif not s and start is not None:
            runs.append((start, i - start))
            start = None
    return runs


def _active(result) -> int:
    return len(check_trajectory(result.route, result.scenario, times=result.route_times).active)


def _timed_success(family: str, index: int):
    """``mawdo_time`` on a scene: it must reach the goal without an active collision."""
    scene = _scene(family, index)
    res = run_planner("mawdo_time", scene.scenario, seed=0)
    assert res.success, res.reason
    assert _active(res) == 0
    return scene, res


def test_corridor_only_waiting_succeeds_and_mawdo_time_waits():
    scene = _scene("corridor", 0)
    sc = scene.scenario
    # the static optimum driven at full speed from t = 0 meets the oncoming traffic, and the
    # earliest arrival waits most of a hundred steps: waiting is the only way through
    length = float(np.hypot(*np.diff(scene.optimum, axis=0).T).sum())
    assert Guard(sc, 0.5).stretch_hits(scene.optimum, 0.0, length) > 0
    assert scene.time_route.waiting > 50
    _, res = _timed_success("corridor", 0)
    longest = max(n for _, n in _still_runs(res.trajectory))
    assert longest >= 50  # it held its position while the traffic passed
    assert res.steps <= 1.05 * scene.t_star


def test_parked_mover_robot_waits_then_goes():
    scene, res = _timed_success("parked", 0)
    first, n = max(_still_runs(res.trajectory), key=lambda r: r[1])
    assert n >= 20  # waits for the parked mover to leave ...
    moved = np.hypot(*(res.trajectory[-1] - res.trajectory[first + n]))
    assert moved > 100  # ... then drives on to the goal
    assert res.steps <= 1.05 * scene.t_star


def test_doorway_patrol_is_timed_through_the_door():
    scene, res = _timed_success("doorway", 2)
    # the door is passed when the patrol leaves it open: within 5 % of the roadmap's earliest
    # arrival T* (an upper bound of the free-space optimum, so no lower bound from it)
    assert res.steps <= 1.05 * scene.t_star


def test_time_guide_off_never_consults_the_guide(monkeypatch):
    sc = _scene("doorway", 0).scenario
    seen = plan(sc, "mawdo", seed=0, time_guide=False)

    def refuse(*args, **kwargs):
        raise AssertionError("a run with time_guide=False asked the safe-interval guide")

    monkeypatch.setattr(TimeGuide, "routes", refuse)
    again = plan(sc, "mawdo", seed=0, time_guide=False)
    assert np.array_equal(again.route, seen.route)
    assert [r.cost for r in again.replans] == [r.cost for r in seen.replans]


def test_the_default_planner_consults_the_time_guide_and_the_paper_presets_do_not(monkeypatch):
    """Issue 27: the guide seeds every (re)plan of the default planner; the ``paper`` and
    ``study`` presets keep the planner the paper measures."""
    from mawdo.planning.run.config import PRESETS, PlannerConfig

    assert PlannerConfig().time_guide
    assert all(PRESETS[k].time_guide for k in ("realtime", "quick", "fast"))
    assert not PRESETS["paper"].time_guide and not PRESETS["study"].time_guide
    asked = []
    real = TimeGuide.routes

    def spy(self, pos, t):
        asked.append(t)
        return real(self, pos, t)

    monkeypatch.setattr(TimeGuide, "routes", spy)
    sc = _scene("doorway", 0).scenario
    default = plan(sc, "mawdo", seed=0)
    assert asked and asked[0] == 0.0  # the first plan is seeded by the timed routes
    # mawdo_time only forces the switch on: under the default preset it is the same run
    timed = run_planner("mawdo_time", sc, seed=0)
    assert np.array_equal(default.route, timed.route)
    assert np.array_equal(default.route_times, timed.route_times)


def test_guide_only_is_registered_without_an_optimizer():
    spec = PLANNERS["guide_only"]
    assert spec.optimizer is None and not spec.seeded
    assert PLANNERS["mawdo_time"].optimizer == "mawdo"
    scene = _scene("doorway", 0)
    res = run_planner("guide_only", scene.scenario, seed=0)
    assert res.success, res.reason
    assert all(len(r.history) == 1 for r in res.replans)  # one ranking, no iterations


def test_run_metrics_time_gap_and_collision_split():
    scene = _scene("doorway", 0)
    res = run_planner("guide_only", scene.scenario, seed=0)
    m = run_metrics(res, l_star=scene.l_star, snapshots=0, t_star=scene.t_star)
    assert m["time_gap"] == pytest.approx((len(res.trajectory) - 1) / scene.t_star)
    # the static optimum's time L* / v is a lower bound of any arrival
    assert res.steps >= scene.l_star / scene.scenario.robot_speed - 1e-9
    assert m["active_collisions"] == 0 and m["passive_collisions"] == 0
    assert "time_gap" not in run_metrics(res, l_star=scene.l_star, snapshots=0)
    with pytest.raises(ValueError, match="t_star"):
        run_metrics(res, l_star=scene.l_star, snapshots=0, t_star=0.0)


def test_time_routes_must_be_positive():
    from mawdo.planning.run.config import PlannerConfig

    with pytest.raises(ValueError, match="time_routes"):
        PlannerConfig(time_routes=0)


def test_timed_route_clock_and_path_by_hand():
    from mawdo.planning.guide.sipp.guide import TimedRoute
    from mawdo.planning.guide.timeguide import passed_between, position_at, route_geometry

    # wait at the origin until t = 2, then drive to (3, 4) by t = 3
    r = TimedRoute(np.array([[0.0, 0.0], [0.0, 0.0], [3.0, 4.0]]), np.array([0.0, 2.0, 3.0]), ())
    assert np.array_equal(position_at(r, 1.0), [0.0, 0.0])  # waiting holds the position
    assert np.allclose(position_at(r, 2.5), [1.5, 2.0])
    assert np.array_equal(position_at(r, 9.0), [3.0, 4.0])
    assert np.array_equal(route_geometry(r), [[0.0, 0.0], [3.0, 4.0]])
    pts, frac = passed_between(r, 1.5, 2.5)
    assert np.array_equal(pts, [[0.0, 0.0]]) and np.allclose(frac, [0.5])


def test_slalom_gaps_within_a_pixel_of_the_diameter_are_timed_through():
    """slalom-0: every gap is 0.3-1 px wider than the robot. At the 0.5 px margin the safe-
    interval guide finds no route (the gaps are closed to it); at the margin the run fits to
    the scene (half its slack) it finds one, the checker accepts that timed route at the true
    radius, and the run reaches the goal without an active collision."""
    from mawdo.planning.guide.passage import fitted_clearance
    from mawdo.planning.guide.sipp.guide import SafeIntervalGuide

    scene = _scene("slalom", 0)
    sc = scene.scenario
    assert SafeIntervalGuide(sc, clearance=0.5).routes(1) == []
    c = fitted_clearance(sc, 0.5)
    assert 0.0 < c < 0.25  # at most half of at most 1 px of slack, less the guide's own
    (route,) = SafeIntervalGuide(sc, clearance=c).routes(1)
    assert check_trajectory(route.points, sc, times=route.times).ok
    assert scene.t_star <= route.arrival <= 1.02 * scene.t_star
    res = run_planner("guide_only", sc, seed=0)
    assert res.success, res.reason
    assert _active(res) == 0 and res.config.clearance == c


def test_a_scene_without_movers_never_consults_the_time_guide(monkeypatch):
    """Without moving obstacles the earliest arrival is the static shortest route at full
    speed, already a seed: the guide is not built, and the run is the one with it off."""
    sc = _scene("forest", 0).scenario
    assert not sc.moving_indices
    off = plan(sc, "mawdo", seed=0, time_guide=False)

    def refuse(*args, **kwargs):
        raise AssertionError("the time guide was consulted on a scene without movers")

    monkeypatch.setattr(TimeGuide, "routes", refuse)
    default = plan(sc, "mawdo", seed=0)
    assert np.array_equal(default.route, off.route)
    assert [r.cost for r in default.replans] == [r.cost for r in off.replans]
