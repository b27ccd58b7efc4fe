"""The guard's least-bad evasive move: when every move breaks the margin, it never drives into
a contact of its own making (a move toward an obstacle it touches, as the judge's
:func:`~mawdo.planning.judge.fault.blame` defines it) while another move, waiting at least,
makes none."""

import numpy as np
import pytest

from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.judge.fault import blame
from mawdo.planning.safety.guard import Guard
from mawdo.planning.world.scenario import scenario_from_dict
from mawdo.planning.world.stepped import with_movers


def _scene(discs, robot=(137.3, 177.75)):
    """A 400 x 400 px map with constant-velocity discs (built without the file checks: a disc
    may start within the robot's margin, as a prediction may)."""
    base = scenario_from_dict({
        "schema_version": 1, "name": "squeeze", "width": 400.0, "height": 400.0,
        "start": list(robot), "goal": [380.0, 380.0], "robot": {"radius": 6.0, "speed": 5.0},
        "obstacles": [],
    })  # fmt: skip
    times = np.array([0.0, 20.0])
    tracks = [(times, np.array([c, np.add(c, np.multiply(20.0, v))])) for c, _, v in discs]
    return with_movers(base, [r for _, r, _ in discs], tracks)


def _blamed(sc, pos, to) -> bool:
    pts, times = np.vstack([pos, to]), np.array([0.0, 1.0])
    rep = check_trajectory(pts, sc, times=times)
    return bool(blame(pts, times, sc, rep.collisions)[0])


# a crowd's prediction at one step of a circle-crossing episode: a person walking down-left at
# the robot (margin cut to the gap), one coming from the right, one passing below; every move
# of the robot breaks the margin, and the move whose look-ahead keeps most room (up-right)
# crosses the first person's path toward her
SQUEEZE = [
    ((133.9, 190.3), 6.51, (-2.95, -4.04)),
    ((173.3, 183.4), 10.33, (-3.01, -1.67)),
    ((128.6, 163.2), 10.33, (4.98, -0.43)),
    ((188.6, 112.3), 10.33, (-4.44, -0.02)),
    ((153.4, 73.1), 10.33, (-3.13, 1.64)),
]


def test_in_a_squeeze_the_robot_does_not_move_into_a_contact():
    sc = _scene(SQUEEZE)
    guard, pos = Guard(sc, clearance=1.0), np.array([137.3, 177.75])
    to, clear, safe = guard.evasive_move(pos, np.array([141.1, 180.9]), 0.0, 1.0)
    assert not safe
    assert not _blamed(sc, pos, to)
    # the look-ahead alone would have crossed her path: that move is blamed
    assert _blamed(sc, pos, pos + np.array([3.54, 3.54]))
    assert guard.causes_contact(pos, pos + np.array([3.54, 3.54]), 0.0, 1.0)
    assert not guard.causes_contact(pos, pos, 0.0, 1.0)  # waiting never is


@pytest.mark.parametrize("seed", range(12))
def test_no_blamed_move_while_an_unblamed_one_exists(seed):
    rng = np.random.default_rng(seed)
    pos = np.array([200.0, 200.0])
    discs = []
    for _ in range(rng.integers(2, 6)):  # agents closing in from every side, near the robot
        ang = rng.uniform(0, 2 * np.pi)
        c = pos + rng.uniform(12.0, 20.0) * np.array([np.cos(ang), np.sin(ang)])
        v = (pos - c) / np.hypot(*(pos - c)) * rng.uniform(1.0, 5.0)
        discs.append((tuple(c), float(rng.uniform(4.0, 9.0)), tuple(v)))
    sc = _scene(discs, robot=tuple(pos))
    guard = Guard(sc, clearance=2.0)
    to, _, safe = guard.evasive_move(pos, pos + np.array([5.0, 0.0]), 0.0, 1.0)
    if not safe:
        assert not _blamed(sc, pos, to), (seed, to - pos)


@pytest.mark.parametrize("seed", range(40))
def test_the_nearest_admitted_move_is_the_evasive_move_with_the_same_rule(seed):
    # nearest_admitted stops at the first safe admitted move; evasive_move checks all 33 and
    # filters: both must pick the same move (or none), on random crowds and random rules
    rng = np.random.default_rng(seed)
    pos = np.array([200.0, 200.0])
    discs = [(tuple(pos + rng.uniform(-40, 40, 2)), float(rng.uniform(4, 12)),
              tuple(rng.uniform(-5, 5, 2))) for _ in range(int(rng.integers(1, 8)))]  # fmt: skip
    sc = _scene(discs, robot=tuple(pos))
    guard = Guard(sc, clearance=float(rng.uniform(0.0, 2.0)))
    target = pos + rng.uniform(-6, 6, 2)
    banned = rng.uniform(0, 2 * np.pi)  # a half-plane of headings the rule refuses

    def admit(to):
        d = np.asarray(to) - pos
        return not np.any(d) or np.cos(np.arctan2(d[1], d[0]) - banned) < 0.3

    to, clear, safe = guard.evasive_move(pos, target, 0.0, 1.0, admit=admit)
    found = guard.nearest_admitted(pos, target, 0.0, 1.0, admit)
    if safe:
        assert found is not None
        assert np.array_equal(found[0], to) and found[1] == clear
    else:
        assert found is None
