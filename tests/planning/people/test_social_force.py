"""Social force people against hand-computed forces and one hand-integrated step."""

import numpy as np
import pytest

from mawdo.planning.people import SocialForceParams, SocialForcePeople, preferred_velocities
from mawdo.planning.people.social_force import total_force
from mawdo.planning.people.walls import Walls

E04, E3 = np.exp(-0.4), np.exp(-3.0)
# tau 2 steps, A = 3 px/step^2, B = 5 px, A_W = 4 px/step^2, B_W = 2 px, phi = 100 deg, c = 0.5
PARAMS = SocialForceParams(2.0, 3.0, 5.0, 4.0, 2.0, np.deg2rad(100.0), 0.5, 1.3, 1)
FLOOR = np.array([[0.0, 0.0], [100.0, 0.0], [100.0, 40.0], [0.0, 40.0]])  # top edge y = 40


def row():
    # three people in a row on y = 50, 10 px apart, radius 4, all walking right at 1 px/step
    pos = np.array([[40.0, 50.0], [50.0, 50.0], [60.0, 50.0]])
    goals = np.array([[150.0, 50.0], [150.0, 50.0], [150.0, 50.0]])
    vel = np.array([[1.0, 0.0], [1.0, 0.0], [1.0, 0.0]])
    return pos, goals, vel, np.full(3, 4.0), np.full(3, 2.0)


def test_forces_against_a_hand_calculation():
    pos, goals, vel, radii, speed = row()
    walls = Walls.build([FLOOR], (200.0, 200.0))
    desired = preferred_velocities(pos, goals, speed, 1.0)  # (2, 0): the goals are far
    f = total_force(PARAMS, pos, vel, radii, desired, pos, radii, walls, np.eye(3, dtype=bool))
    # middle person: desired (2 - 1) / 2; the one ahead pushes back with 3 exp((8 - 10) / 5),
    # weight 1; the one behind pushes forward with the same, weight c = 0.5 (outside the
    # 100 deg half view); the floor 10 px below pushes up with 4 exp((4 - 10) / 2).
    assert f[1] == pytest.approx([0.5 - 3 * E04 + 0.5 * 3 * E04, 4 * E3])
    # front person: both others behind (weight 0.5), 10 and 20 px away; the floor as above
    assert f[2] == pytest.approx([0.5 + 0.5 * 3 * E04 + 0.5 * 3 * np.exp(-12 / 5), 4 * E3])
    # back person: both others ahead (weight 1)
    assert f[0] == pytest.approx([0.5 - 3 * E04 - 3 * np.exp(-12 / 5), 4 * E3])
    # a wall corner: the nearest point of the floor to (110, 50) is its corner (100, 40)
    p = np.array([[110.0, 50.0]])
    g = total_force(PARAMS, p, np.zeros((1, 2)), np.array([4.0]), np.zeros((1, 2)), p[:0],
                    radii[:0], walls)  # fmt: skip
    d = np.hypot(10.0, 10.0)
    assert g[0] == pytest.approx(4 * np.exp((4 - d) / 2) * np.array([10.0, 10.0]) / d)


def test_field_of_view_boundary():
    # a neighbour at 100 deg from the walking direction counts fully, at 101 deg half
    pos = np.array([[100.0, 100.0]])
    desired = np.array([[1.0, 0.0]])
    walls = Walls.build([], (200.0, 200.0))
    for deg, w in ((99.0, 1.0), (101.0, 0.5)):
        other = pos + 20.0 * np.array([[np.cos(np.deg2rad(deg)), np.sin(np.deg2rad(deg))]])
        f = total_force(
            PARAMS, pos, desired, np.array([4.0]), desired, other, np.array([4.0]), walls
        )
        mag = 3 * np.exp((8 - 20) / 5)
        np.testing.assert_allclose(f[0], -w * mag * (other[0] - pos[0]) / 20.0, rtol=1e-12)


def test_one_step_is_a_semi_implicit_euler_step():
    pos, goals, vel, radii, speed = row()
    crowd = SocialForcePeople(
        pos,
        goals,
        radii,
        speed,
        params=PARAMS,
        bounds=(200.0, 200.0),
        obstacles=[FLOOR],
        velocities=vel,
    )
    walls = Walls.build([FLOOR], (200.0, 200.0))
    desired = preferred_velocities(pos, goals, speed, 1.0)
    f = total_force(PARAMS, pos, vel, radii, desired, pos, radii, walls, np.eye(3, dtype=bool))
    crowd.step([150.0, 150.0], [0.0, 0.0], 5.0, False)
    v = vel + f
    v *= np.minimum(1.0, 1.3 * 2.0 / np.hypot(*v.T))[:, None]  # v_max = 1.3 v0
    np.testing.assert_allclose(crowd.velocities(), v, rtol=1e-12)
    np.testing.assert_allclose(crowd.positions(), pos + v, rtol=1e-12)


def test_a_visible_robot_repels_like_a_person():
    pos, goals, vel, radii, speed = row()
    one = slice(1, 2)
    crowds = [
        SocialForcePeople(pos[one], goals[one], radii[one], speed[one], params=PARAMS,
                          bounds=(200.0, 200.0), velocities=vel[one])
        for _ in range(2)
    ]  # fmt: skip
    crowds[0].step([60.0, 50.0], [0.0, 0.0], 4.0, True)
    crowds[1].step([60.0, 50.0], [0.0, 0.0], 4.0, False)
    # the robot 10 px ahead: 3 exp(-0.4) backwards, on top of the desired (2 - 1) / 2
    assert crowds[0].velocities()[0] == pytest.approx([1.0 + 0.5 - 3 * E04, 0.0])
    assert crowds[1].velocities()[0] == pytest.approx([1.5, 0.0])


def test_params_from_metres():
    p = SocialForceParams.from_metres(0.05, 0.25)
    assert p.tau == pytest.approx(2.0)  # 0.5 s
    assert p.agent_strength == pytest.approx(7.0 * 0.0625 / 0.05)  # 7 m/s^2 in px/step^2
    assert p.agent_range == pytest.approx(6.0) and p.wall_range == pytest.approx(4.0)
    assert p.wall_strength == pytest.approx(50.0 * 0.0625 / 0.05)
    with pytest.raises(ValueError, match="fov_weight"):
        SocialForceParams(2.0, 3.0, 5.0, 4.0, 2.0, 1.0, 1.5, 1.3, 1)
    with pytest.raises(ValueError, match="substeps"):
        SocialForceParams(2.0, 3.0, 5.0, 4.0, 2.0, 1.0, 0.5, 1.3, 0)


def test_head_on_walkers_pass_without_contact():
    p = SocialForceParams.from_metres(0.05, 0.25)
    crowd = SocialForcePeople(
        [[30.0, 100.0], [170.0, 101.0]],
        [[170.0, 100.0], [30.0, 101.0]],
        [6.0, 6.0],
        [5.0, 5.0],
        params=p,
        bounds=(200.0, 200.0),
        arrival_time=4.0,
    )
    gaps = []
    for _ in range(70):
        crowd.step([100.0, 10.0], [0.0, 0.0], 6.0, False)
        x = crowd.positions()
        gaps.append(np.hypot(*(x[0] - x[1])) - 12.0)
    assert min(gaps) > 0.0
    np.testing.assert_allclose(crowd.positions(), [[170.0, 100.0], [30.0, 101.0]], atol=1.0)
