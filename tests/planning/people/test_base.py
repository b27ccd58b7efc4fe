"""The common people interface: bad input, preferred velocities, new goals, seeds, walls."""

import numpy as np
import pytest
import shapely

from mawdo.planning.people import (
    CircleGoals,
    KeepGoal,
    OrcaParams,
    OrcaPeople,
    SocialForceParams,
    SocialForcePeople,
    preferred_velocities,
)

RES, DT = 0.05, 0.25
SPEED = DT / RES  # 1 m/s in px per step
MODELS = {
    "orca": (OrcaPeople, OrcaParams.from_metres(RES, DT)),
    "social_force": (SocialForcePeople, SocialForceParams.from_metres(RES, DT)),
}
BLOCK = np.array([[80.0, 60.0], [120.0, 60.0], [120.0, 140.0], [80.0, 140.0]])


def make(model, positions, goals, radii=None, speeds=None, **kw):
    cls, params = MODELS[model]
    n = len(positions)
    radii = np.full(n, 6.0) if radii is None else radii
    speeds = np.full(n, SPEED) if speeds is None else speeds
    kw.setdefault("bounds", (200.0, 200.0))
    kw.setdefault("arrival_time", 1 / DT)
    return cls(positions, goals, radii, speeds, params=params, **kw)


def test_preferred_velocities_hand_values():
    pos = np.array([[0.0, 0.0], [0.0, 0.0], [3.0, 4.0]])
    goals = np.array([[30.0, 40.0], [3.0, 4.0], [3.0, 4.0]])
    got = preferred_velocities(pos, goals, [5.0, 5.0, 5.0], arrival_time=4.0)
    # far: 5 px/step toward the goal; near: the distance over 4 steps; at the goal: 0
    np.testing.assert_allclose(got, [[3.0, 4.0], [0.75, 1.0], [0.0, 0.0]])


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize(
    "change, match",
    [
        (dict(radii=[6.0, -1.0]), r"radii\[1\] = -1 must be > 0; give the person's disc radius"),
        (dict(speeds=[5.0, np.nan]), r"preferred_speed\[1\] = nan is not finite"),
        (dict(goals=[[100.0, 100.0], [50.0, 50.0]]), r"goals\[0\] = \[100.0, 100.0\] is inside"),
        (dict(goals=[[250.0, 100.0], [50.0, 50.0]]), r"goals\[0\] .* is outside the map"),
        (dict(positions=[[100.0, 100.0], [20.0, 20.0]]), r"positions\[0\] .* inside or too near"),
        (
            dict(positions=[[20.0, 20.0], [25.0, 20.0]]),
            r"positions\[0\] and positions\[1\] overlap",
        ),
        (dict(goals=[[20.0, 180.0]]), r"goals must have shape \(2, 2\)"),
        (dict(goal_policy=KeepGoal()), "rng must be a numpy.random.Generator"),
        (dict(arrival_time=0.0), "arrival_time=0.0 must be > 0"),
    ],
)
def test_bad_input_names_the_field(model, change, match):
    kw = dict(
        positions=[[20.0, 20.0], [180.0, 20.0]],
        goals=[[20.0, 180.0], [180.0, 180.0]],
        obstacles=[BLOCK],
    )
    kw.update(change)
    with pytest.raises(ValueError, match=match):
        make(model, **kw)


@pytest.mark.parametrize("model", MODELS)
def test_bad_robot_state(model):
    people = make(model, [[20.0, 20.0]], [[20.0, 180.0]])
    with pytest.raises(ValueError, match="robot state must be finite with radius > 0"):
        people.step([100.0, 100.0], [0.0, 0.0], -2.0, True)


def test_missing_pyrvo_names_the_extra(monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "pyrvo", None)  # makes `import pyrvo` raise ImportError
    with pytest.raises(ImportError, match=r"pip install 'mawdo\[crowd\]'"):
        make("orca", [[20.0, 20.0]], [[20.0, 180.0]])


@pytest.mark.parametrize("model", MODELS)
def test_a_person_who_arrives_picks_a_new_goal_inside_the_map(model):
    centre = np.array([100.0, 100.0])
    policy = CircleGoals(centre, 80.0, 1 / DT, 1 / RES, 4.0, robot_goal=np.array([100.0, 180.0]))
    on_circle = np.array([[170.0, 90.0], [190.0, 90.0], [190.0, 110.0], [170.0, 110.0]])
    people = make(
        model,
        [[30.0, 30.0]],
        [[20.0, 100.0]],
        bounds=(200.0, 200.0),
        obstacles=[on_circle],
        goal_policy=policy,
        rng=np.random.default_rng(1),
    )
    first = people.goals.copy()
    goals = [first[0]]
    for _ in range(600):
        people.step([10.0, 190.0], [0.0, 0.0], 6.0, False)
        if np.any(people.goals[0] != goals[-1]):
            goals.append(people.goals[0].copy())
    assert len(goals) >= 3, "the person should have reached several goals"
    for g in goals[1:]:
        # on the 80 px circle up to the noise (half a metre = 10 px per axis), clear of the block
        assert abs(np.hypot(*(g - centre)) - 80.0) <= 10.0 * np.sqrt(2) + 1e-9
        assert people.free(g, [6.0])[0]
        assert 6 <= g[0] <= 194 and 6 <= g[1] <= 194


@pytest.mark.parametrize("model", MODELS)
def test_keep_goal_people_stay_at_their_goal(model):
    people = make(model, [[100.0, 20.0]], [[100.0, 50.0]])
    for _ in range(40):
        people.step([10.0, 190.0], [0.0, 0.0], 6.0, False)
    np.testing.assert_allclose(people.goals, [[100.0, 50.0]])
    assert np.hypot(*(people.positions()[0] - [100.0, 50.0])) < 0.5


def _crowd(model, seed):
    rng = np.random.default_rng(0)
    ang = rng.uniform(0, 2 * np.pi, 8)
    pos = 100 + 70 * np.c_[np.cos(ang), np.sin(ang)]
    keep = [0]
    for i in range(1, 8):
        if np.all(np.hypot(*(pos[keep] - pos[i]).T) > 14):
            keep.append(i)
    pos = pos[keep]
    policy = CircleGoals(
        np.array([100.0, 100.0]), 70.0, 1 / DT, 1 / RES, 4.0, np.array([100.0, 180.0])
    )
    return make(model, pos, 200 - pos, goal_policy=policy, rng=np.random.default_rng(seed))


def _run(people, steps=120):
    out = []
    for t in range(steps):
        people.step([100.0, 20.0 + t], [0.0, 1.0], 6.0, True)
        out.append(people.positions())
    return np.array(out)


@pytest.mark.parametrize("model", MODELS)
def test_same_seed_same_trajectories(model):
    a, b, c = _run(_crowd(model, 5)), _run(_crowd(model, 5)), _run(_crowd(model, 6))
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c), "another seed should give other new goals"


@pytest.mark.parametrize("model", MODELS)
def test_people_never_enter_a_wall(model):
    # people sent straight through a block and across it, with the robot pushing from the side
    pos = np.array([[20.0, 100.0], [20.0, 70.0], [180.0, 130.0], [100.0, 30.0], [100.0, 170.0]])
    goals = np.array([[180.0, 100.0], [180.0, 75.0], [20.0, 125.0], [100.0, 170.0], [100.0, 30.0]])
    people = make(model, pos, goals, obstacles=[BLOCK])
    block = shapely.Polygon(BLOCK)
    prev = people.positions()
    for t in range(150):
        people.step([60.0, 40.0 + t], [0.0, 1.0], 6.0, True)
        now = people.positions()
        for p, q in zip(prev, now, strict=True):
            path = shapely.LineString([p, q]) if np.any(p != q) else shapely.Point(p)
            assert path.distance(block) >= 6.0 - 1e-9
        assert np.all((now >= 6.0) & (now <= 194.0))
        prev = now


@pytest.mark.parametrize("model", MODELS)
def test_nobody_and_a_robot_that_comes_and_goes(model):
    empty = make(model, np.zeros((0, 2)), np.zeros((0, 2)))
    for visible in (True, False, True):
        empty.step([100.0, 100.0], [1.0, 0.0], 6.0, visible)
    assert empty.positions().shape == (0, 2) and empty.velocities().shape == (0, 2)
    # one person: the robot toggling visible/invisible (a parked ORCA agent) changes nothing
    # while it is far away
    runs = []
    for pattern in ((True, False) * 10, (False,) * 20):
        crowd = make(model, [[20.0, 20.0]], [[20.0, 180.0]])
        for visible in pattern:
            crowd.step([190.0, 100.0], [0.0, 0.0], 6.0, visible)
        runs.append(crowd.positions())
    np.testing.assert_allclose(runs[0], runs[1], atol=1e-4)
