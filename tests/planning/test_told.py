"""The observing planner told the future (mawdo.planning.run.told): its predictions are the
people's realised motion, it drives the same loop as the observing planner, and it refuses to
plan when it was not told the future."""

from __future__ import annotations

import numpy as np
import pytest

SETTING = "circle-5-invisible"


def _episode(policy_name: str, k: int):
    from mawdo.experiments.kinds.crowd.execute import episode_row, run_one
    from mawdo.streams import name_word, seed_word

    spec = {"algorithm": policy_name, "preset": "realtime", "overrides": {},
            "sensor": {"noise": 0.0, "range": None, "miss_rate": 0.0},
            "predictor": "constant_velocity"}  # fmt: skip
    res, scene = run_one(spec, SETTING, seed_word([0, name_word(SETTING), k]))
    return res, scene, episode_row(res, scene)


def test_the_told_predictions_are_where_the_unseeing_people_walk(monkeypatch):
    """Every step's prediction, 1 to 8 steps ahead, puts each person within 0.5 px of where the
    world then has it (people who do not see the robot walk the future the policy was told;
    RVO2's single precision lets the two runs drift by a hair)."""
    from mawdo.planning.run.told import ToldFuturePolicy

    seen = []
    original = ToldFuturePolicy.prediction

    def spy(self, reading):
        sc = original(self, reading)
        movers = [sc.obstacles[i] for i in sc.moving_indices]
        ahead = np.arange(1.0, 9.0)
        centres = np.stack([np.asarray(o.shape.center) + o.offset(ahead) for o in movers], 1)
        seen.append((reading.step, centres))
        return sc

    monkeypatch.setattr(ToldFuturePolicy, "prediction", spy)
    res, scene, row = _episode("mawdo_told", 3)
    assert row["success"] == 1 and len(seen) > 20
    realised = res.scenario
    people = [realised.obstacles[i] for i in realised.moving_indices]
    worst = 0.0
    for step, centres in seen:
        t = step + np.arange(1.0, 9.0)
        t = t[t <= len(res.trajectory) - 1]
        truth = np.stack([np.asarray(o.shape.center) + o.offset(t) for o in people], 1)
        diff = centres[: len(t), :, None, :] - truth[:, None, :, :]
        gap = np.hypot(diff[..., 0], diff[..., 1])
        worst = max(worst, float(gap.min(axis=2).max()))  # each predicted disc's nearest person
    assert worst < 0.5


def test_told_in_the_loop_is_faster_than_observing_and_slower_than_told_once():
    """On the same episodes, the step-by-step loop told the future arrives no later than the
    observing planner, and no earlier than the plan made once with that future."""
    told = [_episode("mawdo_told", k)[2] for k in range(4)]
    seen = [_episode("mawdo", k)[2] for k in range(4)]
    once = [_episode("mawdo_oracle", k)[2] for k in range(4)]
    assert all(r["success"] for r in told + once)
    assert sum(r["time_s"] for r in told) <= sum(r["time_s"] for r in seen)
    assert sum(r["time_s"] for r in told) >= sum(r["time_s"] for r in once)


def test_a_told_policy_reset_without_the_future_refuses_to_plan():
    """Reset with the world's own scenario (the people are not in it), the first decision
    raises and says what to hand it, instead of planning around nobody."""
    from mawdo.experiments.kinds.crowd.execute import scene_of, world_of
    from mawdo.planning.run.episode import run_episode
    from mawdo.planning.run.policies import make_policy

    scene = scene_of(SETTING, 5)
    policy = make_policy("mawdo_told", {"preset": "realtime"})
    with pytest.raises(ValueError, match="holds every agent's future"):
        run_episode(world_of(scene, 5), policy, 5, seed=5)


def test_the_told_policy_is_registered_as_told_the_future():
    from mawdo.planning.run.policies import POLICIES, make_policy
    from mawdo.planning.run.told import ToldFuturePolicy

    policy = make_policy("mawdo_told", {"preset": "realtime", "noise": 1.0})
    assert POLICIES["mawdo_told"].knowledge == "oracle"  # the study hands it the future
    assert isinstance(policy, ToldFuturePolicy) and policy.look_first == 0
    assert policy.config.time_guide and policy.tracker.noise == 1.0
