"""ORCA people: avoidance, the robot seen or not, unit invariance, and CrowdNav's per-human
simulators (ported from crowd_sim/envs/policy/orca.py of vita-epfl/CrowdNav)."""

import numpy as np
import pyrvo
import pytest

from mawdo.planning.people import OrcaParams, OrcaPeople, circle_crossing

RES, DT = 0.05, 0.25
SPEED = DT / RES
PARAMS = OrcaParams.from_metres(RES, DT)


def people(pos, goals, **kw):
    n = len(pos)
    return OrcaPeople(
        pos,
        goals,
        np.full(n, 6.0),
        np.full(n, SPEED),
        params=PARAMS,
        bounds=(200.0, 200.0),
        arrival_time=1 / DT,
        **kw,
    )


def test_params_from_metres():
    p = OrcaParams.from_metres(0.05, 0.25)
    assert (p.neighbor_dist, p.max_neighbors, p.time_horizon, p.time_horizon_obst) == (
        pytest.approx(200.0),
        10,
        20.0,
        20.0,
    )
    assert p.safety == pytest.approx(0.2)
    with pytest.raises(ValueError, match="max_neighbors"):
        OrcaParams(10.0, 0, 1.0, 1.0, 0.0)


def test_head_on_walkers_pass_without_contact():
    # a pixel apart sideways: exact symmetry is a deadlock for ORCA, and CrowdNav's noise breaks it
    crowd = people([[30.0, 100.0], [170.0, 101.0]], [[170.0, 100.0], [30.0, 101.0]])
    gaps = []
    for _ in range(70):
        crowd.step([100.0, 10.0], [0.0, 0.0], 6.0, False)
        x = crowd.positions()
        gaps.append(np.hypot(*(x[0] - x[1])) - 12.0)
    assert min(gaps) >= 0.0
    np.testing.assert_allclose(crowd.positions(), [[170.0, 100.0], [30.0, 101.0]], atol=0.1)
    assert np.all(np.hypot(*crowd.velocities().T) <= SPEED * (1 + 1e-12))


@pytest.mark.parametrize("visible", [True, False])
def test_people_yield_to_a_visible_robot_and_walk_into_an_invisible_one(visible):
    crowd = people([[30.0, 100.0]], [[170.0, 100.5]])
    gaps = []
    for _ in range(80):
        crowd.step([100.0, 100.0], [0.0, 0.0], 6.0, visible)
        gaps.append(np.hypot(*(crowd.positions()[0] - [100.0, 100.0])))
    np.testing.assert_allclose(crowd.positions()[0], [170.0, 100.5], atol=0.1)  # it got there
    if visible:
        assert min(gaps) >= 12.0  # passed around the robot's disc
    else:
        assert min(gaps) < 1.0  # walked through the robot's place


def crowdnav_orca_humans(starts, goals, robot_path, robot_vel, steps, dt=DT):
    """CrowdNav's ORCA humans in metres: one simulator per human, made at its first step and
    reused; the others (humans, then the visible robot) have zero preferred velocity."""
    params = 10, 10, 5, 5
    n = len(starts)
    px, vel = np.array(starts, float), np.zeros((n, 2))
    sims = [None] * n
    out = []
    for t in range(steps):
        actions = []
        for i in range(n):
            others = [(px[j], vel[j], 0.3) for j in range(n) if j != i]
            others.append((robot_path[t], robot_vel, 0.3))
            if sims[i] is None:
                sim = pyrvo.RVOSimulator(dt, *params, 0.3, 1.0)
                sim.add_agent(tuple(px[i]), *params, 0.3 + 0.01, 1.0, tuple(vel[i]))
                for p, v, r in others:
                    sim.add_agent(tuple(p), *params, r + 0.01, 1.0, tuple(v))
                sims[i] = sim
            else:
                sim = sims[i]
                sim.set_agent_position(0, tuple(px[i]))
                sim.set_agent_velocity(0, tuple(vel[i]))
                for k, (p, v, _) in enumerate(others):
                    sim.set_agent_position(k + 1, tuple(p))
                    sim.set_agent_velocity(k + 1, tuple(v))
            velocity = goals[i] - px[i]
            speed = np.linalg.norm(velocity)
            pref = velocity / speed if speed > 1 else velocity
            sim.set_agent_pref_velocity(0, tuple(pref))
            for k in range(len(others)):
                sim.set_agent_pref_velocity(k + 1, (0.0, 0.0))
            sim.do_step()
            a = sim.get_agent_velocity(0)
            actions.append([a.x, a.y])
        vel = np.array(actions)
        px = px + vel * dt
        out.append(px.copy())
    return np.array(out)


@pytest.mark.parametrize("res, dt", [(0.05, 0.25), (0.02, 0.1)])
def test_one_shared_pixel_simulator_matches_crowdnavs_metre_simulators(res, dt):
    scene = circle_crossing(5, seed=11, visible=True, res=res, dt=dt, goal_changing=False)
    crowd = scene.make_people()
    steps = 30
    robot = np.c_[np.zeros(steps), -4.0 + 0.5 * dt * np.arange(steps)]  # 0.5 m/s up the axis
    ref = crowdnav_orca_humans(
        scene.to_metres(scene.positions), scene.to_metres(scene.goals), robot, [0.0, 0.5], steps, dt
    )
    got = []
    for t in range(steps):
        crowd.step(
            scene.to_pixels(robot[t]), [0.0, 0.5 * dt / res], scene.scenario.robot_radius, True
        )
        got.append(scene.to_metres(crowd.positions()))
    # single precision inside RVO2, in metres there and in pixels here
    np.testing.assert_allclose(np.array(got), ref, atol=2e-4)
    assert np.abs(np.diff(ref, axis=0)).max() > 0.2 * dt  # they walked


def test_walls_are_orca_obstacles():
    block = np.array([[80.0, 60.0], [120.0, 60.0], [120.0, 140.0], [80.0, 140.0]])
    crowd = people([[30.0, 100.0]], [[170.0, 100.0]], obstacles=[block])
    for _ in range(60):
        crowd.step([100.0, 10.0], [0.0, 0.0], 6.0, False)
    x = crowd.positions()[0]
    # it stopped in front of the wall (ORCA is local and does not plan around it), untouched
    assert 30.0 < x[0] <= 80.0 - 6.0 + 1e-6 and abs(x[1] - 100.0) < 1e-6
