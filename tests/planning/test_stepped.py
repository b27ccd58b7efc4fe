"""The stepped world and its runner: moves, speed limit, realised tracks, the oracle replay."""

import numpy as np
import pytest

from mawdo.planning.run.episode import run_episode
from mawdo.planning.run.planner import plan
from mawdo.planning.run.policy import PlannerPolicy, StraightLine, step_move
from mawdo.planning.world.scenario import scenario_from_dict
from mawdo.planning.world.stepped import Move, SteppedWorld, static_part, with_movers


def _scene(obstacles=()):
    return scenario_from_dict({
        "schema_version": 1, "name": "small", "width": 120.0, "height": 80.0,
        "start": [10.0, 40.0], "goal": [110.0, 40.0], "robot": {"radius": 3.0, "speed": 4.0},
        "obstacles": list(obstacles),
    })  # fmt: skip


MOVER = {"shape": "circle", "center": [60.0, 10.0], "radius": 6.0, "motion": {"velocity": [0, 1.5]}}
WALL = {"shape": "polygon", "vertices": [[50, 30], [56, 30], [56, 50], [50, 50]]}


class Recorder:
    """A policy that drives a fixed list of velocities (then stands)."""

    def __init__(self, velocities):
        self.velocities = [np.asarray(v, float) for v in velocities]

    def reset(self, scenario, seed):
        self.k = 0

    def act(self, reading):
        v = self.velocities[self.k] if self.k < len(self.velocities) else np.zeros(2)
        self.k += 1
        return v


def test_move_rejects_bad_fractions():
    with pytest.raises(ValueError, match="fractions"):
        Move([[1, 1], [2, 2]], [0.7, 0.5])
    with pytest.raises(ValueError, match="fractions"):
        Move([[1, 1]], [0.5])


def test_world_scales_a_too_fast_move_down_to_the_robot_speed():
    w = SteppedWorld(_scene())
    w.step([30.0, 40.0])  # 50 px asked, the robot drives 4
    assert np.allclose(w.position, [10 + 4 * 0.6, 40 + 4 * 0.8])
    assert np.hypot(*w.velocity) == pytest.approx(4.0)


def test_step_move_cuts_a_route_at_the_step_boundaries():
    route = np.array([[0, 0], [1, 0], [1, 2], [3, 2.0]])
    stamps = np.array([0.0, 0.5, 1.5, 2.5])
    m0, m1, m2 = (step_move(route, stamps, s) for s in range(3))
    # corner (1, 0) at 0.5; at t = 1 halfway up the leg to (1, 2)
    assert np.allclose(m0.points, [[1, 0], [1, 1]]) and np.allclose(m0.fracs, [0.5, 1.0])
    assert np.allclose(m1.points, [[1, 2], [2, 2]]) and np.allclose(m1.fracs, [0.5, 1.0])
    assert np.allclose(m2.points, [[3, 2], [3, 2]]) and np.allclose(m2.fracs, [0.5, 1.0])


def test_static_part_drops_the_movers_and_keeps_the_walls():
    sc = _scene([MOVER, WALL])
    known = static_part(sc)
    assert len(known.obstacles) == 1 and known.obstacles[0].index == 0
    assert known.obstacles[0].shape == sc.obstacles[1].shape


def test_realised_people_move_linearly_between_recorded_steps():
    sc = _scene()
    real = with_movers(sc, [5.0], [(np.arange(3.0), np.array([[30, 30], [34, 30], [34, 36]]))])
    ob = real.obstacles[-1]
    assert np.allclose(ob.offset([0.5, 1.5, 9.0]), [[2, 0], [4, 3], [4, 6]])
    assert ob.shape.center == (30.0, 30.0) and ob.shape.radius == 5.0


def test_straight_line_into_a_wall_is_a_robot_caused_failure():
    res = run_episode(SteppedWorld(_scene([WALL])), StraightLine(), 40, seed=0)
    assert res.reason.startswith("goal reached but the route collides")
    assert not res.success and res.robot_caused > 0 and res.other_collisions == 0


def test_a_mover_running_into_a_standing_robot_is_not_its_fault():
    sc = _scene([{"shape": "circle", "center": [10.0, 10.0], "radius": 5.0,
                  "motion": {"velocity": [0, 2.0]}}])  # fmt: skip
    res = run_episode(SteppedWorld(sc), Recorder([]), 30, seed=0)
    assert res.reason == "step limit reached before the goal"
    assert res.robot_caused == 0 and res.other_collisions > 0


@pytest.mark.slow
def test_oracle_policy_replays_the_plan_bit_for_bit():
    sc = _scene([MOVER, WALL])
    policy = PlannerPolicy(knowledge="oracle", config="quick")
    res = run_episode(SteppedWorld(sc), policy, 200, seed=3)
    ref = plan(sc, "mawdo", policy.seed, "quick")
    assert np.array_equal(res.route, ref.route) and np.array_equal(res.route_times, ref.route_times)
    assert res.success == ref.success and res.robot_caused == 0


def test_unknown_knowledge_is_refused():
    with pytest.raises(ValueError, match="knowledge must be one of"):
        PlannerPolicy(knowledge="psychic")
