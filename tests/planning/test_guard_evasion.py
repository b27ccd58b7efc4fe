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


def _eager_evasive_move(guard, pos, target, t, dt, admit=None):
    """The guard's evasive move as it was first written: every move checked, then chosen (the
    reference for the version that checks nearest first and stops early)."""
    from mawdo.planning.safety.guard import TIE_TOL
    from mawdo.planning.world.path import unit_headings

    v = guard.scenario.robot_speed * dt
    dirs = unit_headings(16)
    moves = np.vstack([pos, pos + v * dirs, pos + 0.5 * v * dirs])
    checks = [guard._step_check(pos, m, t, dt) for m in moves]
    clear, walls = np.array([guard._clearances(c[2]) for c in checks]).T
    safe = clear >= guard.clearance
    if safe.any():
        idx = np.nonzero(safe)[0]
        near = idx[np.argsort(np.hypot(*(moves[idx] - target).T), kind="stable")]
        best = near[0]
        if admit is not None:
            first = next((i for i in near if admit(moves[i])), None)
            if first is None:
                return moves[best], float(clear[best]), False
            best = first
    else:
        out = walls >= 0.0
        free = out & ~np.array([guard._own_contact(*c) for c in checks])
        out = free if free.any() else out
        ahead = np.array([guard.ahead_clearance(pos, m, t, dt) for m in moves])
        key = np.where(out, ahead, -np.inf) if out.any() else ahead
        top = np.nonzero(key >= key.max() - TIE_TOL)[0]
        best = int(top[int(np.argmax(clear[top]))])
    return moves[best], float(clear[best]), bool(safe[best])


@pytest.mark.parametrize("seed", range(60))
def test_the_evasive_move_is_the_one_every_move_checked_first_gives(seed):
    # the guard checks moves nearest the target first and stops early: on random crowds (some
    # where no move is safe), with and without a rule that refuses half the headings, it must
    # choose what checking all 33 first chooses
    rng = np.random.default_rng(seed)
    pos = np.array([200.0, 200.0])
    spread = 40.0 if seed % 3 else 15.0  # every third crowd packed round the robot
    discs = [(tuple(pos + rng.uniform(-spread, spread, 2)), float(rng.uniform(4, 12)),
              tuple(rng.uniform(-5, 5, 2))) for _ in range(int(rng.integers(1, 9)))]  # fmt: skip
    sc = _scene(discs, robot=tuple(pos))
    guard = Guard(sc, clearance=float(rng.uniform(0.0, 2.0)))
    target = pos + rng.uniform(-6, 6, 2)
    banned = rng.uniform(0, 2 * np.pi)  # a half-plane of headings the rule refuses

    def admit(to):
        d = np.asarray(to) - pos
        return not np.any(d) or np.cos(np.arctan2(d[1], d[0]) - banned) < 0.3

    def narrow(to):  # only a cone of about 50 degrees: often no safe move in it
        d = np.asarray(to) - pos
        return bool(np.any(d)) and np.cos(np.arctan2(d[1], d[0]) - banned) > 0.9

    for rule in (None, admit, narrow):
        to, clear, safe = guard.evasive_move(pos, target, 0.0, 1.0, admit=rule)
        ref_to, ref_clear, ref_safe = _eager_evasive_move(guard, pos, target, 0.0, 1.0, rule)
        assert np.array_equal(to, ref_to) and clear == ref_clear and safe == ref_safe
