"""Robot baselines against ports of CrowdNav's ORCA robot policy (vita-epfl/CrowdNav,
crowd_sim/envs/policy/orca.py) and CrowdNav++'s social force policy
(Shuijing725/CrowdNav_Prediction_AttnGraph, crowd_nav/policy/social_force.py)."""

import numpy as np
import pyrvo
import pytest
import shapely

from mawdo.planning.people import (
    OrcaParams,
    OrcaRobot,
    SocialForceParams,
    SocialForceRobot,
    circle_crossing,
)
from mawdo.planning.sense.reading import Reading, Tracks
from mawdo.planning.world.scenario import scenario_from_dict

RES, DT = 0.05, 0.25


def tracks(centers, velocities, radii):
    n = len(centers)
    return Tracks(np.arange(n), centers, velocities, radii, np.zeros(n), np.zeros(n))


class CrowdNavOrcaRobot:
    """CrowdNav's ORCA.predict for the robot (metres, seconds; safety_space 0 as in test.py)."""

    def __init__(self, time_step):
        self.time_step, self.sim = time_step, None

    def predict(self, p, v, g, humans):
        params = 10, 10, 5, 5
        if self.sim is not None and self.sim.get_num_agents() != len(humans) + 1:
            self.sim = None
        if self.sim is None:
            self.sim = pyrvo.RVOSimulator(self.time_step, *params, 0.3, 1)
            self.sim.add_agent(tuple(p), *params, 0.3 + 0.01, 1.0, tuple(v))
            for hp, hv in humans:
                self.sim.add_agent(tuple(hp), *params, 0.3 + 0.01, 1, tuple(hv))
        else:
            self.sim.set_agent_position(0, tuple(p))
            self.sim.set_agent_velocity(0, tuple(v))
            for i, (hp, hv) in enumerate(humans):
                self.sim.set_agent_position(i + 1, tuple(hp))
                self.sim.set_agent_velocity(i + 1, tuple(hv))
        velocity = np.array((g[0] - p[0], g[1] - p[1]))
        speed = np.linalg.norm(velocity)
        pref_vel = velocity / speed if speed > 1 else velocity
        self.sim.set_agent_pref_velocity(0, tuple(pref_vel))
        for i in range(len(humans)):
            self.sim.set_agent_pref_velocity(i + 1, (0, 0))
        self.sim.do_step()
        a = self.sim.get_agent_velocity(0)
        return np.array([a.x, a.y])


def test_orca_robot_drives_as_crowdnavs():
    scene = circle_crossing(5, seed=21, res=RES, dt=DT)
    robot = OrcaRobot(OrcaParams.from_metres(RES, DT), arrival_time=1 / DT)
    robot.reset(scene.scenario, 0)
    ref = CrowdNavOrcaRobot(DT)
    # people walk straight to their goals at 1 m/s (scripted, so both robots see the same crowd)
    starts, goals = scene.to_metres(scene.positions), scene.to_metres(scene.goals)
    heading = (goals - starts) / np.linalg.norm(goals - starts, axis=1)[:, None]
    p_ref, v_ref = np.array([0.0, -4.0]), np.zeros(2)
    p, v = scene.scenario.start, np.zeros(2)
    speeds = []
    for t in range(60):
        hp, hv = starts + heading * t * DT, heading
        a_ref = ref.predict(p_ref, v_ref, [0.0, 4.0], list(zip(hp, hv, strict=True)))
        a = robot.decide(
            p, v, scene.scenario.goal,
            tracks(scene.to_pixels(hp), hv * DT / RES, scene.radii),
        )  # fmt: skip
        p_ref, v_ref = p_ref + a_ref * DT, a_ref
        p, v = p + a, a
        speeds.append(np.hypot(*a))
        np.testing.assert_allclose(scene.to_metres(p), p_ref, atol=2e-4)
    assert max(speeds) <= scene.scenario.robot_speed
    assert np.linalg.norm(p_ref - [0.0, 4.0]) < 0.3  # it arrived


def crowdnav_pp_social_force(p, v, g, v_pref, radius, humans, dt, KI=1.0, A=2.0, B=1.0):
    """CrowdNav++'s SOCIAL_FORCE.predict (metres, seconds; config sf.A = 2, sf.B = 1, sf.KI = 1)."""
    delta_x, delta_y = g[0] - p[0], g[1] - p[1]
    dist_to_goal = np.sqrt(delta_x**2 + delta_y**2)
    desired_vx = (delta_x / dist_to_goal) * v_pref
    desired_vy = (delta_y / dist_to_goal) * v_pref
    curr_delta_vx = KI * (desired_vx - v[0])
    curr_delta_vy = KI * (desired_vy - v[1])
    interaction_vx = interaction_vy = 0
    for hp, hr in humans:
        delta_x, delta_y = p[0] - hp[0], p[1] - hp[1]
        dist_to_human = np.sqrt(delta_x**2 + delta_y**2)
        interaction_vx += A * np.exp((radius + hr - dist_to_human) / B) * (delta_x / dist_to_human)
        interaction_vy += A * np.exp((radius + hr - dist_to_human) / B) * (delta_y / dist_to_human)
    total_delta_vx = (curr_delta_vx + interaction_vx) * dt
    total_delta_vy = (curr_delta_vy + interaction_vy) * dt
    new_vx, new_vy = v[0] + total_delta_vx, v[1] + total_delta_vy
    act_norm = np.linalg.norm([new_vx, new_vy])
    if act_norm > v_pref:
        return np.array([new_vx / act_norm * v_pref, new_vy / act_norm * v_pref])
    return np.array([new_vx, new_vy])


def test_social_force_robot_with_crowdnav_pp_settings_matches_its_policy():
    scene = circle_crossing(6, seed=5, res=RES, dt=DT)
    # CrowdNav++: relaxation 1/KI = 1 s, A = 2 m/s^2, B = 1 m, no field of view, one Euler step
    params = SocialForceParams.from_metres(
        RES, DT, tau=1.0, agent_strength=2.0, agent_range=1.0, fov_weight=1.0, substeps=1
    )
    robot = SocialForceRobot(params, arrival_time=1e-9)  # always the full preferred speed
    robot.reset(scene.scenario, 0)
    rng = np.random.default_rng(2)
    for _ in range(20):
        p = rng.uniform(-3, 3, 2)
        v = rng.uniform(-0.7, 0.7, 2)
        hp = rng.uniform(-4, 4, (6, 2))
        want = crowdnav_pp_social_force(p, v, [0.0, 4.0], 1.0, 0.3, [(h, 0.3) for h in hp], DT)
        got = robot.decide(
            scene.to_pixels(p), v * DT / RES, scene.scenario.goal,
            tracks(scene.to_pixels(hp), np.zeros((6, 2)), scene.radii),
        )  # fmt: skip
        np.testing.assert_allclose(got * RES / DT, want, rtol=1e-9, atol=1e-12)


WALLED = {
    "schema_version": 1,
    "width": 200.0,
    "height": 200.0,
    "start": [100.0, 20.0],
    "goal": [100.0, 180.0],
    "robot": {"radius": 6.0, "speed": 5.0},
    "obstacles": [
        {"shape": "polygon", "vertices": [[70, 90], [130, 90], [130, 110], [70, 110]]},
        {"shape": "circle", "center": [40, 60], "radius": 10},
        {"shape": "circle", "center": [150, 40], "radius": 8, "motion": {"velocity": [1.0, 0.0]}},
    ],
}


@pytest.mark.parametrize("kind", ["orca", "social_force"])
def test_robots_keep_off_the_static_walls(kind):
    sc = scenario_from_dict(WALLED)
    if kind == "orca":
        robot = OrcaRobot(OrcaParams.from_metres(RES, DT), arrival_time=4.0)
    else:
        robot = SocialForceRobot(SocialForceParams.from_metres(RES, DT), arrival_time=4.0)
    robot.reset(sc, 0)
    assert len(robot.polygons) == 2  # the moving circle is not a wall
    block = shapely.Polygon(WALLED["obstacles"][0]["vertices"])
    p, v = np.array([95.0, 20.0]), np.zeros(2)
    none = tracks(np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
    for _ in range(60):
        a = robot.decide(p, v, sc.goal, none)
        assert np.hypot(*a) <= 5.0 + 1e-12
        q = p + a
        swept = shapely.LineString([p, q]) if np.any(a) else shapely.Point(p)
        assert swept.distance(block) >= 6.0 - 1e-6
        p, v = q, a
    assert p[1] < 90.0  # local methods stop in front of the wall, they do not plan around it


class TrueTracker:
    """Hands the policy the true tracks it was given (the stepped world's tracker stands in)."""

    def __init__(self, tr):
        self.tr, self.resets, self.readings = tr, 0, []

    def reset(self):
        self.resets += 1

    def update(self, reading):
        self.readings.append(reading)
        return self.tr


@pytest.mark.parametrize("cls", [OrcaRobot, SocialForceRobot])
def test_act_uses_the_tracker(cls):
    sc = scenario_from_dict(WALLED)
    params = (OrcaParams if cls is OrcaRobot else SocialForceParams).from_metres(RES, DT)
    tr = tracks([[100.0, 50.0]], [[0.0, -2.0]], [6.0])
    reading = Reading(3, [100.0, 20.0], [0.0, 4.0], sc.goal, [[100.0, 50.0]], [6.0])
    lone = cls(params, arrival_time=4.0)
    lone.reset(sc, 0)
    with pytest.raises(RuntimeError, match="needs a tracker"):
        lone.act(reading)
    tracker = TrueTracker(tr)
    robot = cls(params, arrival_time=4.0, tracker=tracker)
    with pytest.raises(RuntimeError, match="before reset"):
        robot.decide([100.0, 20.0], [0.0, 4.0], sc.goal, tr)
    robot.reset(sc, 0)
    assert tracker.resets == 1
    np.testing.assert_array_equal(
        robot.act(reading), lone.decide([100.0, 20.0], [0.0, 4.0], sc.goal, tr)
    )
    assert tracker.readings == [reading]


@pytest.mark.parametrize(
    "cls, params", [(OrcaRobot, OrcaParams), (SocialForceRobot, SocialForceParams)]
)
def test_from_metres(cls, params):
    robot = (
        cls.from_metres(0.05, 0.25, time_horizon=2.0)
        if cls is OrcaRobot
        else cls.from_metres(0.05, 0.25, tau=1.0)
    )
    assert robot.arrival_time == pytest.approx(4.0) and robot.tracker is None
    if cls is OrcaRobot:
        assert robot.params == params.from_metres(0.05, 0.25, time_horizon=2.0)
    else:
        assert robot.params == params.from_metres(0.05, 0.25, tau=1.0)
