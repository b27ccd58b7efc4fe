"""Motion models: closed forms against simulation, bounds, knots, determinism."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mawdo.planning.world.motion import (
    BoundedRandomWalk,
    ConstantVelocity,
    Patrol,
    Static,
    fold,
    fold_turn_times,
)
from mawdo.planning.world.scenario import scenario_from_dict

finite = st.floats(-50, 50, allow_nan=False)


def simulate_reflection(x0, v, lo, hi, steps):
    """Step-by-step elastic reflection in 1-D (at most one bounce per step)."""
    x, out = x0, [x0]
    for _ in range(steps):
        x += v
        if x > hi:
            x, v = 2 * hi - x, -v
        elif x < lo:
            x, v = 2 * lo - x, -v
        out.append(x)
    return np.array(out)


@given(
    v=st.floats(-9.9, 9.9),
    lo=st.floats(-200, 0),
    span=st.floats(10, 300),
)
@settings(max_examples=60, deadline=None)
def test_fold_equals_step_by_step_reflection(v, lo, span):
    hi = lo + span
    if hi < 0:  # the offset starts at 0, which must lie in [lo, hi]
        lo, hi = -span / 2, span / 2
    steps = 400
    sim = simulate_reflection(0.0, v, lo, hi, steps)
    closed = fold(v * np.arange(steps + 1), lo, hi)
    np.testing.assert_allclose(closed, sim, atol=1e-8)


@given(
    box=st.tuples(st.floats(0, 300), st.floats(0, 300), st.floats(1, 60), st.floats(1, 60)),
    velocity=st.tuples(finite, finite),
    times=st.lists(st.floats(0, 1e4), min_size=1, max_size=20),
)
@settings(max_examples=60, deadline=None)
def test_reflection_keeps_the_shape_in_the_map(box, velocity, times):
    W = H = 366.0
    x, y, w, h = box
    w, h = min(w, W - x), min(h, H - y)
    lo = np.array([-x, -y])
    hi = np.array([W - (x + w), H - (y + h)])
    motion = ConstantVelocity(velocity, tuple(lo), tuple(hi))
    off = motion.offset(np.array(times))
    assert np.all(off >= lo - 1e-9) and np.all(off <= hi + 1e-9)
    assert np.all(x + off[:, 0] >= -1e-9) and np.all(x + w + off[:, 0] <= W + 1e-9)
    assert np.all(y + off[:, 1] >= -1e-9) and np.all(y + h + off[:, 1] <= H + 1e-9)


def test_fold_turn_times_are_the_bounces():
    # lo=-10, hi=20, v=3: turns when 3t hits 20 (t=20/3), then -10 (t=50/3 ... 3t = 50 = 20+30)
    times = fold_turn_times(3.0, -10.0, 20.0, 0.0, 40.0)
    np.testing.assert_allclose(times, [20 / 3, 50 / 3, 80 / 3, 110 / 3])
    assert fold_turn_times(0.0, -10.0, 20.0, 0.0, 40.0).size == 0


def _assert_linear_between_knots(motion, t0, t1):
    kt, ko = motion.knots(t0, t1)
    assert kt[0] == t0 and kt[-1] == t1
    assert np.all(np.diff(kt) > 0)
    np.testing.assert_allclose(ko, motion.offset(kt), atol=1e-9)
    for frac in (0.25, 0.5, 0.8):
        mid = kt[:-1] + frac * np.diff(kt)
        expect = ko[:-1] + frac * np.diff(ko, axis=0)
        np.testing.assert_allclose(motion.offset(mid), expect, atol=1e-7)


def test_knots_split_every_model_into_constant_velocity_pieces():
    seed = np.random.SeedSequence(5, spawn_key=(0,))
    models = [
        Static(),
        ConstantVelocity((2.5, -1.3), (-40.0, -30.0), (100.0, 60.0)),
        Patrol(np.array([[0.0, 0.0], [30.0, 0.0], [30.0, 40.0]]), 1.7),
        BoundedRandomWalk(2.0, (-40.0, -30.0), (100.0, 60.0), seed, hold=3),
        BoundedRandomWalk(2.0, (-40.0, -30.0), (100.0, 60.0), seed, hold=1),
    ]
    for motion in models:
        _assert_linear_between_knots(motion, 0.0, 157.3)
        _assert_linear_between_knots(motion, 12.6, 80.0)
    cv = models[1]
    kt, _ = cv.knots(0.0, 157.3)
    assert len(kt) > 4  # the bounces are knots


def test_patrol_visits_its_waypoints_in_order_and_repeats():
    route = np.array([[0.0, 0.0], [30.0, 0.0], [30.0, 40.0]])
    motion = Patrol(route, 2.0)
    # legs 30, 40 and 50 px at 2 px/step: waypoints at t = 0, 15, 35; lap 60 steps
    assert motion.period == pytest.approx(60.0)
    np.testing.assert_allclose(motion.waypoint_times, [0.0, 15.0, 35.0])
    np.testing.assert_allclose(motion.offset([0.0, 15.0, 35.0]), route, atol=1e-12)
    np.testing.assert_allclose(motion.offset([60.0, 75.0, 95.0]), route, atol=1e-9)
    np.testing.assert_allclose(motion.offset(25.0), [30.0, 20.0])
    speeds = np.hypot(*np.diff(motion.offset(np.arange(0, 120.0, 0.5)), axis=0).T) / 0.5
    assert np.all(speeds <= 2.0 + 1e-9)


def test_patrol_back_and_forth_from_a_scenario_retraces():
    sc = scenario_from_dict(
        {
            "schema_version": 1,
            "start": [5, 5],
            "goal": [360, 360],
            "obstacles": [
                {
                    "shape": "circle",
                    "center": [100, 100],
                    "radius": 5,
                    "motion": {
                        "model": "patrol",
                        "waypoints": [[50, 0], [50, 50]],
                        "speed": 5,
                        "cycle": "back_and_forth",
                    },
                }
            ],
        }
    )
    ob = sc.obstacles[0]
    # 0 -> (50,0) -> (50,50) -> (50,0) -> 0: legs of 50 px at 5 px/step
    np.testing.assert_allclose(
        ob.offset([0, 10, 20, 30, 40]), [[0, 0], [50, 0], [50, 50], [50, 0], [0, 0]]
    )


def test_random_walk_is_deterministic_per_seed_bounded_and_in_the_map():
    lo, hi = (-40.0, -30.0), (100.0, 60.0)
    a = BoundedRandomWalk(2.0, lo, hi, np.random.SeedSequence(11, spawn_key=(3,)), hold=4)
    b = BoundedRandomWalk(2.0, lo, hi, np.random.SeedSequence(11, spawn_key=(3,)), hold=4)
    c = BoundedRandomWalk(2.0, lo, hi, np.random.SeedSequence(12, spawn_key=(3,)), hold=4)
    t = np.arange(0.0, 2000.0, 0.5)
    oa = a.offset(t)
    np.testing.assert_array_equal(oa, b.offset(t))
    assert not np.allclose(oa, c.offset(t))
    # asking far ahead first does not change the early part (block-wise seeding)
    d = BoundedRandomWalk(2.0, lo, hi, np.random.SeedSequence(11, spawn_key=(3,)), hold=4)
    d.offset(5000.0)
    np.testing.assert_array_equal(d.offset(t), oa)
    assert np.all(oa >= np.array(lo) - 1e-9) and np.all(oa <= np.array(hi) + 1e-9)
    speed = np.hypot(*np.diff(oa, axis=0).T) / 0.5
    assert speed.max() <= 2.0 + 1e-9
    assert speed.max() > 0.5  # it does move
    with pytest.raises(ValueError, match="t >= 0"):
        a.offset(-1.0)


def test_scenario_offsets_are_vectorised_and_seeded():
    data = {
        "schema_version": 1,
        "seed": 4,
        "start": [5, 5],
        "goal": [360, 360],
        "obstacles": [
            {"shape": "circle", "center": [100, 100], "radius": 5},
            {"shape": "circle", "center": [200, 100], "radius": 5, "motion": {"velocity": [1, 2]}},
            {
                "shape": "circle",
                "center": [200, 200],
                "radius": 5,
                "motion": {"model": "bounded_random_walk", "step": 1.0},
            },
        ],
    }
    s1, s2 = scenario_from_dict(data), scenario_from_dict(data)
    t = np.array([[0.0, 1.5], [10.0, 99.0]])
    off = s1.offsets(t)
    assert off.shape == (2, 2, 3, 2)
    np.testing.assert_array_equal(off, s2.offsets(t))
    np.testing.assert_array_equal(off[..., 0, :], 0.0)  # static
    np.testing.assert_allclose(off[0, 1, 1], [1.5, 3.0])  # no bounce yet
    np.testing.assert_array_equal(s1.offsets(0.0), 0.0)
    data["seed"] = 5
    assert not np.allclose(scenario_from_dict(data).offsets(t)[..., 2, :], off[..., 2, :])
