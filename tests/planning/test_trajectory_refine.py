"""The swarm's refinement of limited timed routes (:mod:`mawdo.planning.refine.trajectory`,
:mod:`mawdo.planning.refine.trajectory_search`): corners rounded and speed carried through them,
limits met as the run drives (checked against the independent
:func:`~mawdo.planning.judge.kincheck.check_kinematics`), never later than the guide's route, and
runs without acceleration or turn limits unchanged."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mawdo.planning.guide.sipp.guide import TimedRoute
from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.judge.kincheck import check_kinematics
from mawdo.planning.refine.trajectory import SmoothPath, brake_bound, route_stops
from mawdo.planning.refine.trajectory_search import RoutePlan, replay
from mawdo.planning.run.config import PRESETS, PlannerConfig
from mawdo.planning.run.execute import Run
from mawdo.planning.run.planner import plan
from mawdo.planning.safety.kinematics import SLACK, Limits
from mawdo.planning.world.scenario import scenario_from_dict
from mawdo.streams import trajectory_seed_sequences

LIMITS = {"max_speed": 3.0, "max_accel": 1.0, "max_turn": 0.6}


def _ell():
    """An L-shaped corridor, 50 px wide, in a 200 x 200 map: a block fills x < 150, y > 50;
    start (20, 25) -> goal (175, 180), a right-angle turn around the block's corner (150, 50).
    One slow mover pacing 2 px in the far corner (195, 5), off every route (the safe-interval
    guide is consulted only with movers)."""
    return scenario_from_dict({
        "schema_version": 1, "width": 200.0, "height": 200.0, "start": [20.0, 25.0],
        "goal": [175.0, 180.0], "robot": {"radius": 4.0, "speed": 4.0},
        "obstacles": [
            {"shape": "polygon", "vertices": [[0, 50], [150, 50], [150, 200], [0, 200]]},
            {"shape": "circle", "center": [194.0, 6.0], "radius": 3.0,
             "motion": {"model": "patrol", "speed": 0.5, "waypoints": [[0.0, 2.0]]}},
        ],
    })  # fmt: skip


def _cfg(**kw) -> PlannerConfig:
    base = PRESETS["quick"]
    return PlannerConfig(**{**base.__dict__, "time_guide": True, **kw})


def test_brake_bound_is_the_largest_speed_braking_can_bring_down_in_time():
    """Eq. 1 against a brute-force search: the largest ``w`` on a fine grid whose braking
    sequence ``w, w - b, ...`` keeps every step faster than ``c`` within ``d`` px."""

    def fits(w, d, c, b):
        pos = 0.0
        while w > c:
            pos += w
            if pos > d:
                return False
            w -= b
        return True

    rng = np.random.default_rng(7)
    for _ in range(100):
        d, c, b, v = rng.uniform(0, 30), rng.uniform(0, 2), rng.uniform(0.2, 1.5), 3.0
        grid = np.linspace(0.0, v, 6001)
        brute = max(w for w in grid if w <= c or fits(w, d, c, b))
        assert brake_bound(d, c, b, v) == pytest.approx(brute, abs=v / 6000 + 1e-12)


def test_smooth_path_arc_is_tangent_to_both_legs():
    """A right angle at (10, 0) rounded 4 px from the vertex: radius 4 / tan(45 deg) = 4, arc
    length 2 pi, from (6, 0) to (10, 4); centre (6, 4)."""
    V = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]])
    path = SmoothPath(V, np.array([4.0]))
    assert path.length == pytest.approx(6.0 + 2.0 * math.pi + 6.0)
    (_, _, _), (st, en, R), _ = path.regions
    assert (st, R) == (pytest.approx(6.0), pytest.approx(4.0))
    mid = path.at(np.array([st + 0.5 * (en - st)]))[0]
    np.testing.assert_allclose(np.hypot(*(mid - [6.0, 4.0])), 4.0)
    np.testing.assert_allclose(path.at(np.array([st, en, path.length])),
                               [[6, 0], [10, 4], [10, 10]], atol=1e-12)  # fmt: skip


def test_right_angle_turn_keeps_speed_and_passes_both_checkers():
    sc = _ell()
    run = Run(sc, "mawdo", 0, _cfg(**LIMITS), dynamic=True)
    (route, *_) = run.timer.routes(sc.start, 0.0)
    V, arrive, depart = route_stops(route.points, route.times)
    assert np.max(depart[1:-1] - arrive[1:-1]) >= 1.0  # the guide stops at its corner
    state = (np.zeros(2), None, 0)
    faster = run.refiner.refine(route, sc.start, 0, state, run.timer.last._mv,
                                trajectory_seed_sequences(0, 0))  # fmt: skip
    assert faster is not None and faster.arrival < route.arrival
    P = faster.points
    speed = np.hypot(*np.diff(P, axis=0).T)
    corner = V[1 + int(np.argmax(depart[1:-1] - arrive[1:-1]))]
    near = np.hypot(*(P[:-1] - corner).T) < 15.0  # the steps through the corner
    assert near.sum() >= 3 and speed[near].min() > 0.0
    assert check_kinematics(P, **LIMITS).ok
    rep = check_trajectory(P, sc, t0=0.0)
    assert rep.ok and rep.min_clearance >= run.cfg.clearance - 1e-9
    assert replay(P, state, run.limits)


def test_a_refined_run_is_earlier_and_keeps_the_limits():
    sc = _ell()
    on = plan(sc, "mawdo", seed=0, config=_cfg(**LIMITS))
    off = plan(sc, "mawdo", seed=0, config=_cfg(refine_trajectory=False, **LIMITS))
    assert on.success and off.success, (on.reason, off.reason)
    assert on.steps < off.steps
    assert on.kinematic_violations == 0 and off.kinematic_violations == 0
    rep = check_trajectory(on.route, sc, times=on.route_times)
    assert rep.ok and not rep.active


def _random_route(rng, v):
    """A random polyline of 3-6 vertices in a 300 px box, timed slowly (no waits)."""
    n = int(rng.integers(3, 7))
    pts = rng.uniform(20.0, 280.0, (n, 2))
    times = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))]) / (0.2 * v)
    return TimedRoute(pts, np.round(times) + np.arange(n), ())


def test_accepted_trajectories_meet_the_limits_on_random_inputs():
    """On random routes, limits and decisions: every trajectory :func:`replay` accepts (the
    run would drive it as planned) passes the independent checker, and the margins of the
    speed pass make most of them accepted."""
    rng = np.random.default_rng(11)
    built = accepted = 0
    for _ in range(60):
        top = rng.uniform(1.0, 4.0)
        lim = Limits(top, rng.uniform(0.1, 0.6) * top, rng.uniform(0.2, 1.2))
        route = _random_route(rng, top)
        planned = RoutePlan(route, route.points[0], 0, (np.zeros(2), None, 0), lim,
                            top * (1.0 - SLACK))  # fmt: skip
        P = planned.trajectory(rng.uniform(0.0, 1.0, planned.dim))
        if P is None:
            continue
        built += 1
        np.testing.assert_allclose(P[-1], route.points[-1], atol=1e-9)
        if replay(P, (np.zeros(2), None, 0), lim):
            accepted += 1
            assert check_kinematics(P, lim.speed, lim.accel, lim.turn).ok
    assert built >= 50 and accepted >= 0.8 * built, (built, accepted)


@pytest.mark.parametrize("limits", [{}, {"max_speed": 3.0}])
def test_runs_without_accel_or_turn_limits_are_unchanged(limits):
    """The switch is looked at only with an acceleration or turn-rate limit: a run without
    one is bit for bit the same with it on or off, and has no refiner."""
    sc = _ell()
    a = plan(sc, "mawdo", seed=3, config=_cfg(**limits))
    b = plan(sc, "mawdo", seed=3, config=_cfg(refine_trajectory=False, **limits))
    np.testing.assert_array_equal(a.trajectory, b.trajectory)
    np.testing.assert_array_equal(a.route_times, b.route_times)
    assert Run(sc, "mawdo", 3, _cfg(**limits), dynamic=True).refiner is None


def test_the_switch_is_validated_and_off_in_the_paper_preset():
    with pytest.raises(ValueError, match="refine_trajectory"):
        PlannerConfig(refine_trajectory="yes")
    assert not PRESETS["paper"].refine_trajectory and PRESETS["realtime"].refine_trajectory


def test_a_wait_on_a_straight_line_is_driven_through_when_not_held():
    """A route that waits mid-way on a straight line (the vertex turns by 0): rounding that
    "corner" would need an infinite radius; passing it, the drive goes straight through it,
    within the limits, and earlier than the route that waits."""
    ys = [60.0, 61.1, 63.4, 66.8, 71.3, 84.8, 89.3, 92.6, 94.9, 96.0, 96.0, 97.2, 99.7, 103.4,
          108.4, 207.6, 212.6, 216.3, 218.8, 220.0]  # fmt: skip
    times = [0, 1, 2, 3, 4, 7, 8, 9, 10, 11, 21, 22, 23, 24, 25, 45, 46, 47, 48, 49]
    route = TimedRoute(np.array([[140.0, y] for y in ys]), np.array(times, float), ())
    lim = Limits(5.0, 1.25, 0.6)
    state = (np.zeros(2), None, 2)
    rp = RoutePlan(route, np.array([140.0, 60.0]), 0, state, lim, 5.0)
    assert len(rp.V) == 3 and rp.waits.size == 1  # start, the wait, the goal
    x = np.ones(rp.dim)
    x[2 * len(rp.corners)] = 0.0  # the wait not held; "corners" rounded as wide as allowed
    traj = rp.trajectory(x)
    assert traj is not None and np.all(np.isfinite(traj))
    assert np.allclose(traj[:, 0], 140.0) and np.allclose(traj[-1], [140.0, 220.0])
    assert len(traj) - 1 < times[-1]
    assert check_kinematics(traj, 5.0, 1.25, 0.6).ok
