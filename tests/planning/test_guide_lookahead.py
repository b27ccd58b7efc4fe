"""The safe-interval guide's lookahead: the movers' predicted motion is trusted for
``lookahead`` steps and not after. Checked against independent references: the eager search
(a line-by-line port, ``test_sipp_lazy``), the exact segment test over the whole prediction,
the roadmap's kept moves against ``straight_moves`` of the whole graph, and runs judged by the
independent checker."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from benchmarks.bench_scaling import world

from mawdo.planning.guide.sipp import SafeIntervalGuide
from mawdo.planning.guide.sipp.departures import empty_memo
from mawdo.planning.guide.sipp.intervals import safe_intervals, segment_free
from mawdo.planning.guide.sipp.lazy import new_table
from mawdo.planning.guide.sipp.moves import straight_moves
from mawdo.planning.guide.sipp.search import timed_search
from mawdo.planning.run.config import PRESETS, PlannerConfig
from mawdo.planning.run.planner import plan
from tests.planning.test_sipp_index import _world
from tests.planning.test_sipp_lazy import _chain, _eager, _eager_numbers, _same


def _guide(seed: int, lookahead, t0: float = 0.0, walkers: str = "known"):
    sc = _world(seed, movers=25)
    spots = np.random.default_rng(seed).uniform(20, 280, (12, 2))
    return SafeIntervalGuide(
        sc, t0=t0, clearance=0.5, spots=spots, walkers=walkers, lookahead=lookahead
    )


@pytest.mark.parametrize("lookahead", [5.0, 20.0, 60.0])
@pytest.mark.parametrize("seed", range(3))
def test_search_past_the_lookahead_equals_the_eager_search(seed, lookahead):
    # the search takes a move from a vertex reached after the last mover piece as free at its
    # first departure, without the exact departure search: the eager port searches every one
    g = _guide(seed, lookahead, t0=float(seed))
    graph = (g.nodes, g.indptr, g.indices, g.weights, g.to_goal)
    v = float(g.scenario.robot_speed)
    moves = straight_moves(g.nodes, g.indptr, g.indices, g.weights, v)
    kin = (v, False, math.inf, None)
    args = (g.start, 0, g.t0, np.zeros(2), g.t_end)
    ptr, lo, hi = safe_intervals(g.nodes, g.t0, g.t_end, g._mv)
    table = new_table(len(g.nodes), g.t0, g.t_end)
    banned = np.zeros(len(lo), np.bool_)
    lazy = timed_search(graph, moves, kin, *args, table, banned, g._mv, empty_memo(),
                        len(g.weights))  # fmt: skip
    assert lazy[0] >= 0
    eager = _eager(graph, moves, kin, *args, ptr, lo, hi, banned, g._mv)
    assert _same(_chain(lazy, _eager_numbers(lazy[5], ptr)), _chain(eager))


@pytest.mark.parametrize("seed", range(4))
def test_routes_are_free_until_the_lookahead_and_never_later_than_the_full_search(seed):
    full = _guide(seed, None, t0=2.0)
    whole = full.routes(1)
    assert whole, "the world is solvable"
    for lookahead in (10.0, 40.0):
        g = _guide(seed, lookahead, t0=2.0)
        assert g.checked_until == 2.0 + lookahead
        route = g.routes(1)[0]
        assert route.checked_until == 2.0 + lookahead
        # fewer constraints: never later than the earliest arrival over the whole prediction
        assert route.arrival <= whole[0].arrival + 1e-9
        # every piece before checked_until is free under the whole prediction (full._mv)
        p, t = route.points, route.times
        for j in range(len(t) - 1):
            if t[j] >= g.checked_until:
                break
            b = min(t[j + 1], g.checked_until)
            w = 0.0 if t[j + 1] == t[j] else (b - t[j]) / (t[j + 1] - t[j])
            end = p[j] + w * (p[j + 1] - p[j])
            assert segment_free(p[j][0], p[j][1], end[0], end[1], t[j], b, full._mv)


def test_a_lookahead_past_the_horizon_changes_nothing():
    full, far = _guide(1, None), _guide(1, 1e6)
    assert far.checked_until == far.t_end
    a, b = full.routes(2), far.routes(2)
    assert len(a) == len(b) >= 1
    for r, s in zip(a, b, strict=True):
        assert np.array_equal(r.points, s.points) and np.array_equal(r.times, s.times)
        assert r.checked_until == s.checked_until == math.inf


def test_kept_moves_equal_the_whole_graphs_for_each_start():
    g = _guide(2, None)
    road, v = g.roadmap, float(g.scenario.robot_speed)
    # a start that sees many vertices, then one that sees fewer: the second call must not
    # read the first's rows
    for start in ([150.0, 150.0], [6.0, 8.0], [150.0, 151.0]):
        graph = road.with_start(start)
        kept = road.straight_moves(graph, v)
        ref = straight_moves(*graph[:4], v)
        for a, b in zip(kept, ref, strict=True):
            assert a.shape == b.shape and np.array_equal(a, b)


@pytest.mark.parametrize("bad", [0.0, -5.0, 30, True, "far"])
def test_config_refuses_a_lookahead_within_the_rules_horizon(bad):
    with pytest.raises(ValueError, match="lookahead"):
        PlannerConfig(lookahead=bad)


def test_guide_refuses_a_non_positive_lookahead():
    with pytest.raises(ValueError, match="lookahead must be > 0"):
        _guide(0, 0.0)


# guide_only follows the guide's timed routes throughout (mawdo without limits keeps its
# own candidates, which need only be free within the lookahead); under limits a kept route is
# asked again 20 steps before its checked end (the rule's horizon is 30), without the
# trajectory refiner (it would refine each route asked again)
@pytest.mark.parametrize(
    "lookahead, limits, planner",
    [(31, {}, "guide_only"),
     (50, {"max_accel": 0.5, "max_turn": 0.8, "refine_trajectory": False}, "mawdo")],
)  # fmt: skip
def test_a_run_with_a_short_lookahead_drives_only_checked_steps(
    lookahead, limits, planner, monkeypatch
):
    # every step along a followed route lies before its checked_until; the run is judged by
    # the independent checker (whole prediction)
    from mawdo.planning.guide.timeguide import TimedRun

    driven, drive = [], TimedRun._drive

    def watched(self, remainder, step):
        if self.following is not None:
            driven.append((step + 1.0, self.following.checked_until))
        return drive(self, remainder, step)

    monkeypatch.setattr(TimedRun, "_drive", watched)
    sc = world(400.0, 60, 8, seed=0)  # constant-velocity discs: no reachable set blocks it
    cfg = replace(PRESETS["realtime"], lookahead=lookahead, pop_size=40, first_iters=30, **limits)
    if planner == "guide_only":
        from mawdo.planning.run.timed_planners import guide_only_run

        res = guide_only_run(sc, 0, replace(cfg, max_steps=80))
    else:
        res = plan(sc, "mawdo", seed=0, config=cfg, max_steps=80)
    assert res.collision_free
    assert driven, "the run followed timed routes"
    assert all(t <= until for t, until in driven)
    assert any(math.isfinite(until) for _, until in driven)


@pytest.mark.parametrize(
    "preset, static, hinted", [("realtime", False, True), ("large", False, False),
                               ("realtime", True, False)]
)  # fmt: skip
def test_the_plan_command_suggests_the_large_preset_among_many_movers(
    preset, static, hinted, capsys
):
    from mawdo.cli.plan import LARGE_MOVERS, _prepare

    sc = world(400.0, LARGE_MOVERS, 8, seed=0)
    _prepare(sc, "mawdo", 0, preset, static, 1, 5)
    assert ("--preset large" in capsys.readouterr().err) is hinted
    few = world(400.0, LARGE_MOVERS - 1, 8, seed=0)
    _prepare(few, "mawdo", 0, preset, static, 1, 5)
    assert "--preset large" not in capsys.readouterr().err


@pytest.mark.parametrize("lookahead", [None, 60.0])
def test_under_a_lookahead_the_followed_route_is_kept_without_asking_the_guide_again(lookahead):
    # a disc crosses the straight route where the robot is about 70 steps from now: the straight
    # candidate is refused (it is checked to the goal) and the robot follows a timed route; a
    # step later, on that route, the whole prediction asks the guide again, a lookahead keeps
    # the route (checked 60 steps ahead, more than the next replan and the rule's horizon)
    from mawdo.planning import scenario_from_dict
    from mawdo.planning.guide.timeguide import position_at
    from mawdo.planning.run.planner import prepare

    speed = 4.0
    meet = 280.0 / speed  # the robot reaches x = 300 at this time
    spec = {"schema_version": 1, "seed": 0, "width": 400.0, "height": 400.0,
            "start": [20.0, 200.0], "goal": [380.0, 200.0], "robot": {"speed": speed},
            "obstacles": [{"shape": "circle", "center": [300.0, 40.0], "radius": 12.0,
                           "motion": {"model": "constant_velocity",
                                      "velocity": [0.0, 160.0 / meet]}}]}  # fmt: skip
    sc = scenario_from_dict(spec)
    run = prepare(sc, "mawdo", 0, replace(PRESETS["realtime"], lookahead=lookahead))
    run.begin()
    asked, routes = [], run.timer.routes
    run.timer.routes = lambda *a, **k: asked.append(a[1]) or routes(*a, **k)
    straight = np.array([sc.start, sc.goal])
    assert run.guard.stretch_hits(straight, 0.0, 360.0) > 0  # not free to the goal
    run._timed_choice(straight, sc.start.copy(), 0)
    first = run.following
    assert first is not None and asked == [0.0]
    pos = position_at(first, 1.0)
    rest = run._timed_choice(straight, pos, 1)
    np.testing.assert_array_equal(rest[0], pos)
    if lookahead is None:
        assert asked == [0.0, 1.0]
    else:
        assert asked == [0.0] and run.following is first
        assert first.checked_until == 60.0
