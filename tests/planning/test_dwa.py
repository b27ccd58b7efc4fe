"""The sampling local planner: its exact closest approach against dense sampling, and its
behaviour (it never drives into a wall, it steps aside for a head-on walker)."""

import numpy as np

from mawdo.planning.run.dwa import DynamicWindow, closest_approach
from mawdo.planning.run.episode import run_episode
from mawdo.planning.sense.tracker import Tracker
from mawdo.planning.world.scenario import scenario_from_dict
from mawdo.planning.world.stepped import SteppedWorld


def test_closest_approach_matches_dense_sampling():
    rng = np.random.default_rng(3)
    p0 = rng.uniform(0, 50, 2)
    v = rng.normal(0, 3, (7, 2))
    c0, w = rng.uniform(0, 50, (5, 2)), rng.normal(0, 3, (5, 2))
    t = np.linspace(0, 6, 60001)
    robot = p0 + t[:, None, None] * v[None]  # (T, k, 2)
    agents = c0 + t[:, None, None] * w[None]  # (T, n, 2)
    dense = np.hypot(*np.moveaxis(agents[:, None] - robot[:, :, None], -1, 0)).min(axis=0)
    exact = closest_approach(p0, v, c0, w, 6)
    assert np.all(exact <= dense + 1e-9) and np.allclose(exact, dense, atol=1e-3)


def _scene(obstacles):
    return scenario_from_dict({
        "schema_version": 1, "width": 200.0, "height": 120.0, "start": [20.0, 60.0],
        "goal": [180.0, 60.0], "robot": {"radius": 4.0, "speed": 4.0}, "obstacles": obstacles,
    })  # fmt: skip


def test_dwa_steps_aside_for_a_head_on_walker_and_reaches_the_goal():
    walker = {"shape": "circle", "center": [150.0, 60.0], "radius": 8.0,
              "motion": {"velocity": [-2.5, 0.0]}}  # fmt: skip
    res = run_episode(SteppedWorld(_scene([walker])), DynamicWindow(Tracker(0.0)), 150, seed=0)
    assert res.success and res.robot_caused == 0
    assert np.abs(res.trajectory[:, 1] - 60.0).max() > 8.0  # it left the line to pass


def test_dwa_never_drives_into_a_wall():
    wall = {"shape": "polygon", "vertices": [[90, 0], [110, 0], [110, 100], [90, 100]]}
    res = run_episode(SteppedWorld(_scene([wall])), DynamicWindow(Tracker(0.0)), 150, seed=0)
    assert res.robot_caused == 0 and res.collision_free
