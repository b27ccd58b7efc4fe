"""Observed knowledge on scripted scenes that fool a constant-velocity predictor: a person who
stops in front of the robot, one who turns, a head-on walker, one hidden behind a wall. The
robot may wait or evade; it must never cause a collision, and a success must be real."""

import numpy as np
import pytest

from mawdo.planning.run.episode import run_episode
from mawdo.planning.run.policy import PlannerPolicy, closes_in_reach, dodge_ratio
from mawdo.planning.sense.sensor import Sensor
from mawdo.planning.sense.tracker import Tracker
from mawdo.planning.world.scenario import scenario_from_dict
from mawdo.planning.world.stepped import SteppedWorld


def _scene(obstacles, start=(20.0, 60.0), goal=(180.0, 60.0)):
    return scenario_from_dict({
        "schema_version": 1, "name": "observed-test", "width": 200.0, "height": 120.0,
        "start": list(start), "goal": list(goal), "robot": {"radius": 4.0, "speed": 4.0},
        "obstacles": obstacles,
    })  # fmt: skip


def _run(sc, algorithm="guide_only", sensor=None, steps=200, seed=0):
    tracker = None if sensor is None else Tracker.for_sensor(sensor)
    policy = PlannerPolicy(algorithm, "quick", "observed", time_guide=True, tracker=tracker)
    return run_episode(SteppedWorld(sc), policy, steps, seed=seed, sensor=sensor)


def _assert_safe(res):
    assert res.robot_caused == 0, res.reason
    if res.success:  # a success is checker-approved against the realised motion
        assert res.collision_free and res.other_collisions == 0


HEAD_ON = {"shape": "circle", "center": [150.0, 60.0], "radius": 8.0,
           "motion": {"velocity": [-2.5, 0.0]}}  # fmt: skip
# walks toward the robot's line, then stops on it for 40 steps, then walks on
STOPPER = {"shape": "circle", "center": [100.0, 100.0], "radius": 8.0, "motion": {
    "model": "patrol", "waypoints": [[0.0, -40.0], [0.0, -80.0]], "speed": 2.0,
    "waits": [0.0, 40.0, 0.0], "cycle": "back_and_forth"}}  # fmt: skip
# walks along the robot's line toward it, then turns across it
TURNER = {"shape": "circle", "center": [150.0, 60.0], "radius": 8.0,
          "motion": {"model": "patrol", "waypoints": [[-30.0, 0.0], [-30.0, 40.0]],
                     "speed": 2.5, "cycle": "back_and_forth"}}  # fmt: skip


@pytest.mark.parametrize("mover", [HEAD_ON, STOPPER, TURNER], ids=["head-on", "stops", "turns"])
def test_observed_robot_never_causes_a_collision(mover):
    res = _run(_scene([mover]))
    _assert_safe(res)
    assert res.success, res.reason  # room enough to evade in all three


@pytest.mark.slow
@pytest.mark.parametrize("mover", [HEAD_ON, STOPPER, TURNER], ids=["head-on", "stops", "turns"])
def test_observed_mawdo_never_causes_a_collision(mover):
    res = _run(_scene([mover]), algorithm="mawdo")
    _assert_safe(res)
    assert res.success, res.reason


def test_a_walker_hidden_behind_a_wall_appears_and_is_avoided():
    # a wall between the robot's start and a walker crossing its line further on; the sensor
    # sees 60 px: the walker is detected only late, from behind the wall's end
    wall = {"shape": "polygon", "vertices": [[60, 66], [110, 66], [110, 110], [60, 110]]}
    walker = {"shape": "circle", "center": [120.0, 110.0], "radius": 6.0,
              "motion": {"velocity": [0.0, -2.0]}}  # fmt: skip
    sensor = Sensor(range=60.0)
    res = _run(_scene([wall, walker], start=(20.0, 50.0), goal=(180.0, 50.0)), sensor=sensor)
    _assert_safe(res)
    assert res.success, res.reason


def test_noisy_sensor_keeps_the_robot_blameless():
    sc = _scene([HEAD_ON, TURNER])
    for seed in range(3):
        res = _run(sc, sensor=Sensor(noise=1.0), seed=seed)
        _assert_safe(res)


def test_observed_planner_ignores_the_scenarios_future():
    # two scenes whose movers are identical until step 10 and then differ: the first ten
    # decisions of an observing planner are the same (it cannot know what comes later)
    a = {
        "shape": "circle",
        "center": [120.0, 60.0],
        "radius": 8.0,
        "motion": {"model": "patrol", "waypoints": [[-20.0, 0.0], [-20.0, 40.0]], "speed": 2.0},
    }
    b = {
        "shape": "circle",
        "center": [120.0, 60.0],
        "radius": 8.0,
        "motion": {"model": "patrol", "waypoints": [[-20.0, 0.0], [-20.0, -40.0]], "speed": 2.0},
    }
    ra, rb = _run(_scene([a]), steps=10), _run(_scene([b]), steps=10)
    assert np.array_equal(ra.trajectory, rb.trajectory)


def test_the_robot_looks_once_before_it_plans_around_people():
    sc = _scene([HEAD_ON])
    policy = PlannerPolicy("guide_only", "quick", "observed", time_guide=True)
    res = run_episode(SteppedWorld(sc), policy, 3, seed=0)
    assert np.array_equal(res.trajectory[1], res.trajectory[0])  # step 0: it watches
    assert not np.array_equal(res.trajectory[2], res.trajectory[1])  # then it moves
    eager = PlannerPolicy("guide_only", "quick", "observed", look_first=0, time_guide=True)
    res = run_episode(SteppedWorld(sc), eager, 2, seed=0)
    assert not np.array_equal(res.trajectory[1], res.trajectory[0])


def _reading(step, centers, radii):
    from mawdo.planning.sense.reading import Reading

    c = np.asarray(centers, float).reshape(-1, 2)
    return Reading(step, np.array([20.0, 60.0]), np.zeros(2), np.array([180.0, 60.0]), c,
                   np.asarray(radii, float))  # fmt: skip


def test_the_robot_watches_only_while_it_could_still_step_out_of_everyone_s_way():
    policy = PlannerPolicy("guide_only", "quick", "observed", look_first=2, time_guide=True)
    policy.reset(_scene([HEAD_ON]), 0)
    # worst agent: straight at the robot at u = k_sd (2) x the tracker's speed prior (4 px per
    # step) = 8 px per step, twice the robot's speed v = 4, so the best escape passes it at
    # v / u = 1/2 of the centre distance left when the watch ends; that must exceed the agent's
    # radius (8) + the robot's (4) + the quick preset's clearance (0.5) = 12.5, i.e. 25 px
    assert policy.tracker.birth_speed_sd == 4.0 and policy.fitted.clearance == 0.5
    assert policy.may_watch(_reading(0, [[20.0 + 25.0 + 16.0 + 0.5, 60.0]], [8.0]))  # 2 steps
    assert not policy.may_watch(_reading(0, [[20.0 + 25.0 + 16.0 - 0.5, 60.0]], [8.0]))
    assert policy.may_watch(_reading(1, [[20.0, 60.0 + 25.0 + 8.0 + 0.5]], [8.0]))  # 1 step
    assert not policy.may_watch(_reading(1, [[20.0, 60.0 + 25.0 + 8.0 - 0.5]], [8.0]))
    assert not policy.may_watch(_reading(2, [[150.0, 60.0]], [8.0]))  # the watch is over
    assert not policy.may_watch(_reading(0, np.zeros((0, 2)), []))  # nobody to watch
    # one agent too close is enough to plan at once, and k_sd is the predictor's own
    two = [[150.0, 60.0], [20.0 + 30.0, 60.0]]
    assert not policy.may_watch(_reading(0, two, [8.0, 8.0]))  # (30 - 16) / 2 < 12.5
    loose = PlannerPolicy("guide_only", "quick", "observed", look_first=1, time_guide=True,
                          predictor_options={"k_sd": 1.0})  # fmt: skip
    loose.reset(_scene([HEAD_ON]), 0)
    # u = 4 = v: the robot outruns it, so 30 - 4 = 26 > 12.5 is enough
    assert loose.may_watch(_reading(0, two, [8.0, 8.0]))


@pytest.mark.parametrize(("u", "v"), [(8.0, 4.0), (6.6, 4.0), (4.5, 4.0), (4.0, 4.0), (2.0, 4.0)])
def test_the_best_escape_from_a_straight_walker_keeps_the_dodge_ratio(u, v):
    # brute force: every heading of the robot (0.01 degree apart), the closest approach over
    # time of the agent walking straight at the robot's start from 100 px away
    phi = np.radians(np.arange(0.0, 180.0, 0.01))
    rel_pos = np.array([100.0, 0.0])  # robot minus agent; the agent walks along +x
    rel_vel = np.stack([v * np.cos(phi) - u, v * np.sin(phi)], axis=1)
    t = np.clip(-(rel_vel @ rel_pos) / np.maximum(np.sum(rel_vel**2, axis=1), 1e-300), 0, None)
    closest = np.hypot(*(rel_pos + t[:, None] * rel_vel).T)
    assert closest.max() == pytest.approx(100.0 * dodge_ratio(u, v), rel=1e-6)


def test_a_fast_crosser_met_at_the_start_gets_no_watch_that_traps_the_robot():
    # a generated chaser scene (seed 7, scene 1): a disc of radius 11.9 at 6.6 px per step
    # (the robot makes 4) passes 2.8 px from the robot's start. A watch bounded by the reach
    # during the watch alone left it 25.7 px from the robot's centre after one step:
    # 25.7 x 4 / 6.6 = 15.6 < 11.9 + 4, no escape, and the robot was hit from the side.
    from mawdo.planning.scenes import generate_scene

    scene = generate_scene("chaser", 1, seed=7)
    policy = PlannerPolicy("guide_only", "realtime", "observed", time_guide=True)
    res = run_episode(SteppedWorld(scene.scenario), policy, 400, seed=3565384203)
    assert not np.array_equal(res.trajectory[1], res.trajectory[0])  # it moves at once
    _assert_safe(res)
    assert res.success and res.collision_free, res.reason


def test_a_pursuer_close_behind_at_the_start_gets_no_free_step():
    # a disc 1.3x the robot's speed, 6 px behind the robot's disc, on its line: watching one
    # step would let it close in (the fast chasers of the timed families)
    chaser = {"shape": "circle", "center": [40.0 - 4.0 - 6.0 - 6.0, 60.0], "radius": 6.0,
              "motion": {"velocity": [5.2, 0.0]}}  # fmt: skip
    sc = _scene([chaser], start=(40.0, 60.0), goal=(190.0, 60.0))
    policy = PlannerPolicy("guide_only", "quick", "observed", time_guide=True)
    res = run_episode(SteppedWorld(sc), policy, 200, seed=0)
    assert not np.array_equal(res.trajectory[1], res.trajectory[0])  # it moves at once
    _assert_safe(res)
    assert res.success, res.reason


class _Budgets:
    """A planner policy that records the evaluations of each plan it makes (None: no plan)."""

    def __init__(self, policy) -> None:
        self.policy, self.nfev = policy, []

    def reset(self, scenario, seed) -> None:
        self.policy.reset(scenario, seed)

    def act(self, reading):
        before = self.policy.last
        out = self.policy.act(reading)
        last = self.policy.last
        self.nfev.append(None if last is before else last.nfev)
        return out

    def __getattr__(self, name):
        return getattr(self.policy, name)


@pytest.mark.parametrize("movers", [[], [HEAD_ON]], ids=["plans-at-once", "watches-first"])
def test_only_the_first_plan_spends_a_first_plans_budget(movers):
    # with nobody in view the robot plans at step 0, with a walker far away it watches first:
    # either way every later decision is a replan (quick: 5 iterations against 60)
    rec = _Budgets(PlannerPolicy("mawdo", "quick", "observed"))
    run_episode(SteppedWorld(_scene(movers)), rec, 4, seed=0)
    plans = [n for n in rec.nfev if n is not None]
    assert len(plans) == (4 if not movers else 3), rec.nfev
    assert all(5 * n < plans[0] for n in plans[1:]), rec.nfev


def test_a_move_closes_in_on_an_agent_only_toward_it_and_within_its_reach():
    # robot at the origin, agent centre 20 px ahead, contact distance 12, reach 4 px a step:
    # driving to (4, 0) ends 16 px off = 12 + 1 x 4, within reach, heading at it
    c, contact, top = np.array([[20.0, 0.0]]), np.array([12.0]), np.array([4.0])
    o = np.zeros(2)

    def closes(*points, fracs=None):
        pts = np.asarray(points, float)
        fr = np.ones(1) if fracs is None else np.asarray(fracs, float)
        return closes_in_reach(o, pts, fr, c, contact, top)

    assert closes([4.0, 0.0])
    # 20 - 3 f > 12 + 4 f for every f in [0, 1]: never within reach
    assert not closes([3.0, 0.0])
    assert not closes([0.0, 0.0])  # standing
    assert not closes([-4.0, 0.0])  # backing away
    assert not closes([0.0, 4.0])  # sideways: the agent falls behind the robot's heading
    # a corner: sideways first, then at it; the second leg ends (2, 2) -> 18.1 px > 16 off,
    # but heads at it from within 12 + f x 4 only if it gets that close: it does not
    assert not closes([0.0, 2.0], [2.0, 2.0], fracs=[0.5, 1.0])
    # the same corner with the agent 17 px ahead: at f = 1, 15.1 px <= 16, heading at it
    c[0, 0] = 17.0
    assert closes([0.0, 2.0], [2.0, 2.0], fracs=[0.5, 1.0])
    # an agent behind the robot is never closed in on by a move ahead
    assert not closes_in_reach(o, np.array([[4.0, 0.0]]), np.ones(1), np.array([[-13.0, 0.0]]),
                               contact, top)  # fmt: skip


def test_the_robot_does_not_step_toward_someone_who_could_reach_it():
    # a person 3 px (surface to surface) ahead on the robot's line, slowly coming closer: the
    # plan goes round them, but no step may head toward where they are while they could
    # reach the robot within it (at the robot's speed, 4 px a step; contact at 8 + 4 px)
    person = {"shape": "circle", "center": [20.0 + 12.0 + 3.0, 60.0], "radius": 8.0,
              "motion": {"velocity": [-0.25, 0.0]}}  # fmt: skip
    sc = _scene([person])
    res = run_episode(SteppedWorld(sc), PlannerPolicy("guide_only", "quick", "observed",
                                                      time_guide=True), 200, seed=0)  # fmt: skip
    _assert_safe(res)
    assert res.success, res.reason
    ob = sc.obstacles[0]
    for t in range(len(res.trajectory) - 1):
        centre = (ob.shape.center + np.ravel(ob.offset(float(t))))[None, :]
        assert not closes_in_reach(
            res.trajectory[t],
            res.trajectory[t + 1][None, :],
            np.ones(1),
            centre,
            np.array([12.0]),
            np.array([4.0]),
        ), t


def test_a_missed_person_is_kept_off_from_where_the_sensor_last_saw_them():
    # a robot at (20, 60) driving +x at 4 px a step; two tracks reported at (50, 60): the first
    # detected now, the second missed for 2 steps and coasted at +3 px a step from (44, 60),
    # where it was last seen. A person who turned round meanwhile may be anywhere within 2
    # steps of reach of that place, so that is where the keep-off rule must measure from.
    from mawdo.planning.sense.reading import Tracks

    sc = _scene([])
    policy = PlannerPolicy("guide_only", "quick", "observed", time_guide=True)
    policy.reset(sc, 0)
    vel = np.array([[0.0, 0.0], [3.0, 0.0]])
    tracks = Tracks(np.arange(2), np.array([[50.0, 60.0], [50.0, 60.0]]), vel,
                    np.array([8.0, 8.0]), np.zeros(2), np.full(2, 0.5),
                    missed=np.array([0, 2]))  # fmt: skip
    centres, contact, top = policy._reach(tracks)
    k_sd = policy.predictor_options.get("k_sd", 2.0)
    # reach per step: the robot's speed or the tracked speed plus k_sd s.d.s, the larger
    expect_top = np.maximum(4.0, np.array([0.0, 3.0]) + k_sd * 0.5)
    near = 8.0 + 4.0  # person radius + robot radius (an exact sensor adds nothing)
    np.testing.assert_allclose(top, expect_top)
    np.testing.assert_allclose(centres, [[50.0, 60.0], [44.0, 60.0]])
    np.testing.assert_allclose(contact, [near, near + 2 * expect_top[1]])
    # without a miss the same tracks are taken where they are reported
    seen = Tracks(tracks.ids, tracks.centers, vel, tracks.radii, tracks.position_sd,
                  tracks.velocity_sd)  # fmt: skip
    c0, k0, _ = policy._reach(seen)
    np.testing.assert_allclose(c0, tracks.centers)
    np.testing.assert_allclose(k0, [near, near])
    # a step of 4 px toward it ends 20 px from the last-seen place, within 12 + 2 x 4 px and
    # the step's own 4; from the coasted centre it would end 26 px off, beyond 12 + 4
    here, step = np.array([20.0, 60.0]), np.array([[24.0, 60.0]])
    assert closes_in_reach(here, step, np.ones(1), centres[1:], contact[1:], top[1:])
    assert not closes_in_reach(here, step, np.ones(1), c0[1:], k0[1:], top[1:])


def test_tracks_report_how_long_each_was_missed():
    # a person seen at steps 0 and 1, missed at 2 and 3, seen again at 4
    from mawdo.planning.sense.reading import Reading
    from mawdo.planning.sense.tracker import Tracker

    trk = Tracker(noise=0.0)
    seen = {0: True, 1: True, 2: False, 3: False, 4: True}
    missed = []
    for step, visible in seen.items():
        c = np.array([[100.0 + 2.0 * step, 50.0]]) if visible else np.empty((0, 2))
        r = np.full(len(c), 5.0)
        reading = Reading(step, np.zeros(2), np.zeros(2), np.array([150.0, 50.0]), c, r)
        missed.append(int(trk.update(reading).missed[0]))
    assert missed == [0, 0, 1, 2, 0]


def test_a_tracker_that_trusts_a_noisy_sensor_is_warned_of():
    # the default tracker assumes an exact sensor: with a noisy one the episode says how to
    # tell it the noise; told, or with an exact sensor, nothing is said
    import warnings

    sc = _scene([HEAD_ON])
    sensor = Sensor(noise=1.0)
    policy = PlannerPolicy("guide_only", "quick", "observed", time_guide=True)
    with pytest.warns(UserWarning, match="Tracker.for_sensor"):
        run_episode(SteppedWorld(sc), policy, 2, seed=0, sensor=sensor)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        told = PlannerPolicy("guide_only", "quick", "observed", time_guide=True,
                             tracker=Tracker.for_sensor(sensor))  # fmt: skip
        run_episode(SteppedWorld(sc), told, 2, seed=0, sensor=sensor)
        run_episode(SteppedWorld(sc), policy, 2, seed=0)
