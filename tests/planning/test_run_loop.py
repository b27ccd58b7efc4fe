"""The one run loop (:func:`~mawdo.planning.run.loop.run_loop`) and the planner's run split
into its decision and the world's step (:class:`~mawdo.planning.run.decide.DecidingRun`).

The loop is checked against hand-written event sequences; the split against the planner's own
``execute``: the run's decision stepped by hand, with a loop written out here, must give the
same trajectory, route, replans and reason, bit for bit.
"""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.planning import get_scenario
from mawdo.planning.run import episode, execute, follower, loop
from mawdo.planning.run.decide import Decision, Legs
from mawdo.planning.run.episode import run_episode
from mawdo.planning.run.follower import follow_oracle
from mawdo.planning.run.loop import GOAL_REACHED, run_loop
from mawdo.planning.run.planner import prepare
from mawdo.planning.scenes import generate_scene
from mawdo.planning.world.stepped import SteppedWorld
from tests.planning import maps
from tests.planning.test_stepped import Recorder, _scene

LIMITS = {"max_speed": 6.0, "max_accel": 1.0, "max_turn": 0.5}


class Line:
    """A robot on a line: at ``x``, one unit a step toward ``goal``; every call is logged."""

    def __init__(self, goal: int, stop_at: int | None = None) -> None:
        self.x, self.goal, self.stop_at, self.log = 0, goal, stop_at, []

    def progress(self, k, n, d):
        self.log.append(("progress", k, n, d))

    def at_goal(self):
        self.log.append(("goal?", self.x))
        return self.x == self.goal

    def decide(self, k):
        self.log.append(("decide", k))
        return k, 1

    def step(self, decision):
        k, dx = decision
        self.x += dx
        self.log.append(("step", k, self.x))
        return "stopped" if k == self.stop_at else None

    def decisions(self):
        return sum(e[0] == "decide" for e in self.log)

    def run(self, max_steps, **kw):
        return run_loop(max_steps, self.at_goal, self.decide, self.step, "limit", self.progress,
                        self.decisions, **kw)  # fmt: skip


def test_loop_reaches_the_goal_with_one_progress_call_per_step():
    line = Line(goal=2)
    assert line.run(5) == GOAL_REACHED
    assert line.log == [
        ("progress", 0, 5, 0), ("goal?", 0), ("decide", 0), ("step", 0, 1),
        ("progress", 1, 5, 1), ("goal?", 1), ("decide", 1), ("step", 1, 2),
        ("progress", 2, 5, 2), ("goal?", 2),
    ]  # fmt: skip


def test_loop_stops_at_the_limit_after_max_steps_decisions():
    line = Line(goal=10)
    assert line.run(2) == "limit"
    assert line.log == [
        ("progress", 0, 2, 0), ("goal?", 0), ("decide", 0), ("step", 0, 1),
        ("progress", 1, 2, 1), ("goal?", 1), ("decide", 1), ("step", 1, 2),
        ("progress", 2, 2, 2), ("goal?", 2),
    ]  # fmt: skip
    # the world runner's form: the limit step is tested for the goal but not reported
    quiet = Line(goal=10)
    assert quiet.run(2, progress_at_limit=False) == "limit"
    assert quiet.log == [e for e in line.log if e != ("progress", 2, 2, 2)]


def test_goal_reached_on_the_last_step_is_a_success_not_a_timeout():
    line = Line(goal=2)
    assert line.run(2, progress_at_limit=False) == GOAL_REACHED
    assert line.log[-1] == ("goal?", 2) and line.decisions() == 2


def test_a_step_that_ends_the_run_ends_it_there():
    line = Line(goal=10, stop_at=1)
    assert line.run(5) == "stopped"
    assert line.log[-1] == ("step", 1, 2) and line.decisions() == 2


def test_zero_steps_only_looks_and_a_negative_limit_is_refused():
    line = Line(goal=3)
    assert line.run(0) == "limit"
    assert line.log == [("progress", 0, 0, 0), ("goal?", 0)]
    with pytest.raises(ValueError, match="max_steps must be >= 0"):
        Line(goal=3).run(-1)


def test_every_run_path_calls_the_one_loop(monkeypatch):
    calls = []

    def spy(*args, **kw):
        calls.append(kw.get("progress_at_limit", True))
        return loop.run_loop(*args, **kw)

    for module in (execute, episode, follower):
        monkeypatch.setattr(module, "run_loop", spy)
    sc = _scene()
    prepare(sc, "mawdo", 0, "quick", max_steps=3).execute()
    run_episode(SteppedWorld(sc), Recorder([(4.0, 0.0)]), 3)
    follow_oracle(sc, max_steps=3)
    assert calls == [True, False, True]


def test_the_world_runner_reports_each_step_but_the_limit():
    seen = []
    res = run_episode(SteppedWorld(_scene()), Recorder([(4.0, 0.0)] * 3), 3,
                      progress=lambda *a: seen.append(a))  # fmt: skip
    assert seen == [(0, 3, 0), (1, 3, 1), (2, 3, 2)]
    assert res.reason == "step limit reached before the goal"
    assert np.array_equal(res.trajectory[:, 0], [10.0, 14.0, 18.0, 22.0])


def by_hand(run):
    """The run driven step by step through its decision and the world's step (the loop
    written out), checking the split's invariants on the way; ``(drive, reason, decisions)``."""
    max_steps, _ = run.step_limit()
    run.begin()
    decisions = []
    for k in range(max_steps + 1):
        assert len(run.drive.traj) == k + 1  # one move a step until the run ends
        assert np.array_equal(run.drive.traj[-1], run.state.position)
        if np.hypot(*(run.sc.goal - run.state.position)) <= 1e-9:
            return run.drive, GOAL_REACHED, decisions
        if k == max_steps:
            return run.drive, "limit", decisions
        d = run.decide(k)
        assert [leg[0] for leg in d.legs] == list(range(k, k + len(d.legs)))
        before = len(run.drive.traj)
        assert run.step(d) == d.end
        assert len(run.drive.traj) == before + len(d.legs)
        decisions.append(d)
        if d.end is not None:
            return run.drive, d.end, decisions
        # the plan goes on from where the robot stands (a stepped policy's warm start)
        assert len(d.legs) == 1 and np.array_equal(run.state.remainder[0], d.position)
    raise AssertionError("the loop must end at the step limit")


def _same_run(make, reason_prefix: str | None = None):
    ref_run = make()
    ref = ref_run.execute()
    drive, reason, decisions = by_hand(make())
    assert np.array_equal(np.array(drive.traj), ref.trajectory)
    assert np.array_equal(np.array(drive.route), ref.route)
    assert np.array_equal(np.array(drive.stamps), ref.route_times)
    if reason == "limit":
        assert ref.reason.startswith("step limit")
    elif reason == GOAL_REACHED:  # the checker may still refuse the route
        assert ref.reason.startswith(GOAL_REACHED)
    else:
        assert ref.reason == reason
    if reason_prefix is not None:
        assert ref.reason.startswith(reason_prefix)
    return ref_run, ref, decisions


def test_decide_by_hand_is_execute_on_the_paper_scenario():
    make = lambda: prepare(get_scenario("paper"), "mawdo", 0, "quick")  # noqa: E731
    run, ref, decisions = _same_run(make, GOAL_REACHED)
    assert ref.success and len(decisions) == ref.steps
    assert all(len(d.legs) == 1 and d.end is None for d in decisions)
    assert np.array_equal(run.remainder, run.state.remainder)


def test_progress_sees_the_moves_so_far_and_a_one_step_run_leaves_its_remainder():
    # the live GIF reads run.drive from the progress callback; a stepped policy runs one step
    # and starts the next from run.remainder
    run = prepare(get_scenario("paper"), "mawdo", 0, "quick")
    seen = []
    res = run.execute(lambda k, n, r: seen.append((k, len(run.drive.traj), r)))
    assert [(k, m) for k, m, _ in seen] == [(k, k + 1) for k in range(res.steps + 1)]
    assert seen[0][2] == 0 and seen[-1][2] == len(res.replans)
    one = prepare(get_scenario("paper"), "mawdo", 0, "quick", max_steps=1)
    first = one.execute()
    assert first.steps == 1 and np.array_equal(one.remainder[0], first.trajectory[-1])
    assert np.array_equal(one.remainder[-1], one.sc.goal)


def test_decide_by_hand_is_execute_under_kinematic_limits():
    scene = generate_scene("corridor", 0, seed=0).scenario
    make = lambda: prepare(scene, "mawdo", 0, "quick", **LIMITS)  # noqa: E731
    run, ref, _ = _same_run(make)
    assert run.limits is not None and ref.steps > 0


def test_decide_by_hand_is_execute_when_the_run_gives_up():
    # the guard's give-up in a pocket whose door a mover blocks (test_safety): fallback moves,
    # then, under acceleration and turn limits, the last fallback move, the settling moves and
    # the end, all in the last decision
    make = lambda: prepare(maps.waiting_pocket(), "mawdo", 0, "quick", give_up_steps=3,  # noqa: E731
                           time_guide=False, max_accel=1.0, max_turn=0.5)  # fmt: skip
    _, ref, decisions = _same_run(make, "no collision-free route found: gave up after 3 steps")
    last = decisions[-1]
    assert last.end == ref.reason and len(last.legs) >= 2  # settling moved the robot
    assert np.array_equal(last.position, ref.trajectory[-1])


def test_a_single_shot_plan_that_collides_ends_without_a_move():
    # one iteration without guide or path-like seeds: the best plan crosses walls (test_safety)
    make = lambda: prepare(maps.serpentine_maze(0), "gwo", 0, "quick", dynamic=False,  # noqa: E731
                           guide_routes=0, first_iters=1, seed_fraction=0.0)  # fmt: skip
    _, ref, decisions = _same_run(make, "no collision-free route found: the best plan hits")
    assert len(decisions) == 1 and decisions[0].legs == [] and ref.steps == 0


def test_decision_position_is_its_last_move():
    legs = Legs()
    assert Decision(legs).position is None
    a, b = np.array([1.0, 2.0]), np.array([3.0, 4.0])
    legs.move(0, a)
    legs.move(1, b, [[2.0, 3.0]], [0.5])
    a[0] = 9.0  # recorded as it was: the decision does not see later changes
    assert np.array_equal(legs[0][1], [1.0, 2.0])
    assert np.array_equal(Decision(legs, "end").position, b)
