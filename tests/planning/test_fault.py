"""Who is at fault: hand-made collisions, and the checker's verdict on realised trajectories
against a second, closed-form check."""

import numpy as np
import pytest

from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.judge.fault import blame
from mawdo.planning.world.scenario import scenario_from_dict
from mawdo.planning.world.stepped import with_movers

R = 3.0  # robot radius


def _map(obstacles=()):
    return scenario_from_dict({
        "schema_version": 1, "width": 200.0, "height": 200.0, "start": [10.0, 10.0],
        "goal": [190.0, 190.0], "robot": {"radius": R, "speed": 5.0}, "obstacles": list(obstacles),
    })  # fmt: skip


def _judge(route, person_centres, radius=4.0, sc=None):
    """Robot along ``route`` (one point per step), one person along ``person_centres``."""
    sc = _map() if sc is None else sc
    times = np.arange(len(route), dtype=float)
    real = with_movers(sc, [radius], [(times, np.asarray(person_centres, float))])
    rep = check_trajectory(np.asarray(route, float), real, times=times)
    return rep, blame(route, times, real, rep.collisions)


def test_robot_walking_into_a_standing_person_is_robot_caused():
    rep, (mine, theirs) = _judge([[50, 50], [55, 50], [60, 50]], [[63, 50]] * 3)
    assert rep.collisions and mine == rep.collisions and theirs == ()


def test_person_walking_into_a_standing_robot_is_not():
    rep, (mine, theirs) = _judge([[50, 50]] * 3, [[70, 50], [62, 50], [54, 50]])
    assert rep.collisions and mine == () and theirs == rep.collisions


def test_person_catching_up_from_behind_is_not_the_robots_fault():
    # robot walks right at 2 px/step, the person behind it at 6 px/step
    robot = [[50 + 2 * k, 50] for k in range(4)]
    person = [[38 + 6 * k, 50] for k in range(4)]
    rep, (mine, theirs) = _judge(robot, person)
    assert rep.collisions and mine == () and theirs == rep.collisions


def test_head_on_is_robot_caused():
    robot = [[50 + 4 * k, 50] for k in range(4)]
    person = [[80 - 4 * k, 50] for k in range(4)]
    rep, (mine, theirs) = _judge(robot, person)
    assert rep.collisions and mine == rep.collisions


def test_sideways_robot_hit_by_a_crossing_person_is_not_robot_caused():
    # the robot moves along +x, the person comes down -y onto it: at contact the person is
    # above the robot, the robot's velocity is perpendicular (no component toward it)
    robot = [[50 + 1 * k, 50] for k in range(3)]
    person = [[51, 70], [51, 60], [51, 50]]
    rep, (mine, theirs) = _judge(robot, person)
    assert rep.collisions and mine == ()


def test_driving_into_a_wall_is_robot_caused():
    wall = {"shape": "polygon", "vertices": [[60, 0], [70, 0], [70, 100], [60, 100]]}
    sc = _map([wall])
    route = np.array([[50.0, 50.0], [55.0, 50.0], [60.0, 50.0]])
    times = np.arange(3.0)
    rep = check_trajectory(route, sc, times=times)
    mine, theirs = blame(route, times, sc, rep.collisions)
    assert rep.collisions and mine == rep.collisions and theirs == ()


def _closest_approach(p0, p1, q0, q1) -> float:
    """Smallest distance of two points moving linearly over [0, 1] (closed form)."""
    d0, dv = q0 - p0, (q1 - q0) - (p1 - p0)
    a = dv @ dv
    u = 0.0 if a == 0 else float(np.clip(-(d0 @ dv) / a, 0.0, 1.0))
    return float(np.hypot(*(d0 + u * dv)))


@pytest.mark.parametrize("chunk", range(4))
def test_checker_on_realised_tracks_agrees_with_closed_form_discs(chunk):
    rng = np.random.default_rng(1000 + chunk)
    agree = 0
    for _ in range(250):  # 1000 random steps over the four chunks
        p = rng.uniform(40, 160, (2, 2))
        q = p + rng.normal(0, 8, (2, 2))
        rad = rng.uniform(1, 6)
        rep, _ = _judge(p, q, radius=rad)
        gap = _closest_approach(p[0], p[1], q[0], q[1]) - R - rad
        if abs(gap) < 1e-6:
            continue  # touching: either verdict is right within rounding
        assert bool(rep.collisions) == (gap < 0), (p, q, rad, gap)
        assert rep.min_clearance == pytest.approx(gap, abs=1e-9)
        agree += 1
    assert agree >= 245
