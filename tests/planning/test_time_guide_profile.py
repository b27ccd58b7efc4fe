"""The safe-interval guide timed within acceleration and turn-rate limits (issue 27, item 3):
each edge from rest to rest in whole steps, turns in place, and the run drives that profile.

Hand values used below, speed cap ``v = 3`` px per step, acceleration ``a = 1`` px per step
squared: a rest-to-rest profile of ``n`` steps covers at most ``1 + 2 + 3 (n - 4) + 2 + 1 =
3 n - 6`` px (``n >= 5``); 200 px need ``3 n - 6 >= 200``, ``n = 69`` (``L / v + v / a - 1 =
68.7`` rounded up), 100 px need ``n = 36`` (``3 * 36 - 6 = 102 >= 100 > 99``). A quarter turn
at 0.6 rad per step takes ``ceil(1.5708 / 0.6) = 3`` steps in place.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mawdo.planning.guide.sipp.intervals import Movers
from mawdo.planning.guide.sipp.lazy import new_table
from mawdo.planning.guide.sipp.profile import edge_pieces, edge_steps, profile_table
from mawdo.planning.guide.sipp.search import search_limited
from mawdo.planning.guide.timeguide import position_at
from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.judge.kincheck import check_kinematics
from mawdo.planning.run.planner import plan, prepare
from mawdo.planning.scenes import generate_scene
from mawdo.planning.world.scenario import scenario_from_dict

LIMITS = {"max_speed": 3.0, "max_accel": 1.0, "max_turn": 0.6}  # robot speed 4 px per step


def _lane(mover):
    """A 240 x 160 map, start (20, 60) -> goal (220, 60): 200 px straight; one disc mover."""
    return scenario_from_dict({
        "schema_version": 1, "width": 240.0, "height": 160.0, "start": [20.0, 60.0],
        "goal": [220.0, 60.0], "robot": {"radius": 4.0, "speed": 4.0}, "obstacles": [mover],
    })  # fmt: skip


FAR = {"shape": "circle", "center": [120.0, 140.0], "radius": 5.0,
       "motion": {"model": "patrol", "speed": 1.0, "waypoints": [[10.0, 0.0]]}}  # fmt: skip
# a disc patrolling down across the lane at x = 120 (1.5 px per step from y = 121 to y = 10)
DOOR = {"shape": "circle", "center": [120.0, 121.0], "radius": 5.0,
        "motion": {"model": "patrol", "speed": 1.5, "waypoints": [[0.0, -111.0]]}}  # fmt: skip


def _profile_positions(n: int, length: float, x0: float):
    """The hand formula: step s at speed min(3, s + 1, n - s), scaled to cover ``length``."""
    w = np.array([min(3.0, s + 1.0, n - s) for s in range(n)])
    x = x0 + np.concatenate([[0.0], np.cumsum(w * length / w.sum())])
    return np.column_stack([x, np.full(n + 1, 60.0)])


def test_profile_steps_match_the_hand_formula():
    assert edge_steps(200.0, 3.0, 1.0)[0] == 69 and edge_steps(100.0, 3.0, 1.0)[0] == 36
    assert edge_steps(199.0, 3.0, 1.0)[0] == 69 and edge_steps(198.0, 3.0, 1.0)[0] == 68
    assert edge_steps(200.0, 3.0, math.inf)[0] == 67  # no acceleration limit: ceil(200 / 3)
    k0, c0, dur, w = edge_pieces(200.0, 3.0, 1.0)
    # speeding up 1, 2; cruising 65 steps at 3; slowing 2, 1 (all scaled by 200 / 201)
    np.testing.assert_array_equal(dur, [1, 1, 65, 1, 1])
    np.testing.assert_allclose(w, np.array([1, 2, 3, 2, 1]) * 200 / 201, rtol=1e-15)
    np.testing.assert_allclose(c0[-1] + w[-1] * dur[-1], 200.0, rtol=1e-14)


def test_a_quarter_turn_adds_its_turn_time_to_the_arrival():
    """Start (0, 0) -> corner (100, 0) -> goal (100, 100) (no direct edge), no movers:
    36 + 3 + 36 = 75 steps with max_turn 0.6; without a turn limit the acceleration limit
    still rests one step at the corner: 73; arrivals at whole steps."""
    sc = scenario_from_dict({
        "schema_version": 1, "width": 200.0, "height": 200.0, "start": [10.0, 10.0],
        "goal": [150.0, 150.0], "robot": {"radius": 4.0, "speed": 3.0}, "obstacles": [],
    })  # fmt: skip
    mv = Movers.from_scenario(sc, 0.5, 0.0, 200.0, "known").arrays()
    nodes = np.array([[100.0, 100.0], [100.0, 0.0], [0.0, 0.0]])  # goal, corner, start
    indptr = np.array([0, 0, 1, 2])
    indices = np.array([0, 1])
    weights = np.array([100.0, 100.0])
    to_goal = np.array([0.0, 100.0, 200.0])
    profile = profile_table(weights, 3.0, 1.0)
    graph = (nodes, indptr, indices, weights, to_goal)
    for turn, expected in ((0.6, 75.0), (math.inf, 73.0)):
        banned = np.zeros(0, np.bool_)
        goal, arrival, parent, depart, _ = search_limited(
            graph, profile, (3.0, True, turn), 2, 0, 0.0, np.zeros(2), 200.0,
            new_table(len(nodes), 0.0, 200.0), banned, mv,
        )  # fmt: skip
        assert goal >= 0 and arrival[goal] == expected
        corner = parent[goal]
        assert arrival[corner] == 36.0 and depart[goal] == expected - 36.0


def test_the_run_drives_the_guides_profile_and_arrives_when_it_said():
    """The free lane: the guide's route is the 69-step profile (hand formula); the run follows
    it step for step (positions equal at every whole step), arrives at step 69 and keeps every
    limit (the independent checker)."""
    sc = _lane(FAR)
    run = prepare(sc, "mawdo", seed=0, config="quick", **LIMITS)
    route = run.timer.routes(sc.start, 0.0)[0]
    assert route.arrival == 69.0
    res = run.execute()
    assert res.success and run.timed_follows >= 1, res.reason
    assert res.steps == 69
    hand = _profile_positions(69, 200.0, 20.0)
    np.testing.assert_allclose(res.trajectory, hand, atol=1e-9)
    np.testing.assert_allclose([position_at(route, s) for s in range(70)], hand, atol=1e-9)
    kin = check_kinematics(res.trajectory, **LIMITS)
    assert kin.ok, kin.describe()


def test_no_search_while_the_robot_is_kept_on_its_timed_route(monkeypatch):
    """With a profile the followed route is kept whatever the swarm finds, so the run
    searches only for its first plan (before: a search at each of the 69 steps, its plan
    ignored) and drives exactly what it drove with the searches."""
    from mawdo.planning.guide.timeguide import TimedRun

    for mover in (FAR, DOOR):
        res = prepare(_lane(mover), "mawdo", seed=0, config="quick", **LIMITS).execute()
        assert res.success and len(res.replans) == 1 and res.replans[0].step == 0
        assert res.fallbacks == res.inevitable == res.waits == res.evasions == 0
        with monkeypatch.context() as m:  # the search at every step, as before
            m.setattr(TimedRun, "_kept_route", lambda self, pos, step: None)
            old = prepare(_lane(mover), "mawdo", seed=0, config="quick", **LIMITS).execute()
        assert len(old.replans) == old.steps
        np.testing.assert_array_equal(res.trajectory, old.trajectory)
        np.testing.assert_array_equal(res.route_times, old.route_times)


def test_the_limited_guide_times_the_door_later_and_the_run_passes_it():
    """The disc crosses the lane at x = 120 around t = 37. At full speed from rest at once
    (the unlimited guide) the robot passes ahead of it: direct, arrival 200 / 3 = 66.7. The
    limited robot driving that timing (the 69-step profile from t = 0) is hit (the
    checker); the limited guide lets the disc pass first and arrives later, and the run
    drives that with no collision and no violation: as the guide timed it with
    ``refine_trajectory`` off, and no later with it on (the swarm's faster drive of the same
    route, 70 steps here, carries speed through its dodge)."""
    sc = _lane(DOOR)
    free = prepare(sc, "mawdo", seed=0, config="quick", max_speed=3.0)
    unlimited = free.timer.routes(sc.start, 0.0)[0]
    assert len(unlimited.points) == 2 and unlimited.arrival == pytest.approx(200.0 / 3.0)
    late = check_trajectory(_profile_positions(69, 200.0, 20.0), sc)
    assert late.collisions
    run = prepare(sc, "mawdo", seed=0, config="quick", **LIMITS)
    limited = run.timer.routes(sc.start, 0.0)[0]
    # a later timing (here: a step aside to a dodge spot, a wait there, then on) than the
    # 69 steps of the direct profile, which the disc would hit
    assert limited.waiting > 0 and limited.arrival > 69.0
    for refine in (False, True):
        run = prepare(sc, "mawdo", seed=0, config="quick", refine_trajectory=refine, **LIMITS)
        res = run.execute()
        rep = check_trajectory(res.route, sc, times=res.route_times)
        assert res.success and not rep.collisions, (res.reason, rep.describe())
        assert run.timed_follows >= 1 and check_kinematics(res.trajectory, **LIMITS).ok
        assert res.steps == limited.arrival if not refine else res.steps < limited.arrival


def test_without_acceleration_or_turn_limits_the_profile_is_never_used(monkeypatch):
    """No limit, or a speed limit alone: the guide keeps its instant starts (no profile) and
    the limited search is never called (it would raise here); runs as before."""
    import mawdo.planning.guide.sipp.profiled as profiled

    def refuse(*args, **kwargs):
        raise AssertionError("the profiled search ran without acceleration or turn limits")

    monkeypatch.setattr(profiled, "search_limited", refuse)
    for overrides in ({}, {"max_speed": 3.0}):
        run = prepare(_lane(DOOR), "mawdo", seed=0, config="quick", **overrides)
        assert run.timer.profile is None
        assert run.execute().success
    sc = generate_scene("doorway", 0, seed=0).scenario
    assert plan(sc, "mawdo", seed=0, config="quick").steps > 0
