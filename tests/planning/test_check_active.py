"""Active (robot moving) and passive (robot at rest) collisions in the checker (issue 27).

Hand-built trajectories whose collision steps follow from the geometry by hand.
"""

from __future__ import annotations

import math

import numpy as np

from mawdo.planning import check_static_path, check_trajectory, scenario_from_dict


def _scene(obstacles, radius=4.0):
    return scenario_from_dict(
        {
            "schema_version": 1,
            "width": 200.0,
            "height": 100.0,
            "start": [20.0, 50.0],
            "goal": [180.0, 50.0],
            "robot": {"radius": radius, "speed": 2.0},
            "obstacles": obstacles,
        }
    )


def _disc(c, r, v):
    return {"shape": "circle", "center": list(c), "radius": r, "motion": {"velocity": list(v)}}


WALL = {"shape": "polygon", "vertices": [[60, 0], [70, 0], [70, 100], [60, 100]]}


def test_robot_at_rest_hit_by_a_disc_is_passive():
    """Disc (r 5) from x = 80 at -2 px/step onto a robot (r 4) standing at x = 50: centre
    distance 30 - 2 t drops below 9 after t = 10.5, inside step 10 = [10, 11]."""
    sc = _scene([_disc((80.0, 50.0), 5.0, (-2.0, 0.0))])
    rep = check_trajectory(np.tile([50.0, 50.0], (20, 1)), sc)
    assert not rep.ok
    assert rep.active == ()
    assert rep.passive == rep.collisions
    assert rep.passive[0] == (10, 0)
    assert rep.passive_time == 10.0
    assert math.isnan(rep.active_time)
    assert "0 active, " in rep.describe() and f"{len(rep.passive)} passive" in rep.describe()


def test_robot_driving_into_a_wall_is_active():
    """Robot (r 4) from x = 40 at 2 px/step toward the wall at x = 60: step s ends at
    42 + 2 s, overlapping once 42 + 2 s > 56, so s = 8 first (s = 7 only touches)."""
    sc = _scene([WALL])
    x = 40.0 + 2.0 * np.arange(12)
    rep = check_trajectory(np.column_stack([x, np.full(12, 50.0)]), sc, t0=3.0)
    assert rep.passive == () and math.isnan(rep.passive_time)
    assert rep.active == rep.collisions
    assert rep.active[0] == (8, 0)
    assert rep.active_time == 3.0 + 8


def test_moving_then_stopping_splits_the_two_kinds():
    """The robot drives at 2 px/step from x = 20 for 5 steps (to 30), then waits (to t = 15).
    A disc (r 5) falling from (26, 68) at 6 px/step is at centre distance sqrt(40) |t - 3| from
    it while it moves: under 9 for t in (1.58, 4.42), steps 1-4, all moving; a second disc from
    x = 90 at -4 px/step meets it at rest (60 - 4 t < 9 after t = 12.75: step 12 on)."""
    sc = _scene(
        [_disc((26.0, 68.0), 5.0, (0.0, -6.0)), _disc((90.0, 50.0), 5.0, (-4.0, 0.0))],
    )
    x = np.concatenate([20.0 + 2.0 * np.arange(6), np.full(10, 30.0)])
    rep = check_trajectory(np.column_stack([x, np.full(len(x), 50.0)]), sc)
    assert set(rep.active) | set(rep.passive) == set(rep.collisions)
    assert not set(rep.active) & set(rep.passive)
    assert rep.active == ((1, 0), (2, 0), (3, 0), (4, 0))
    assert rep.passive == ((12, 1), (13, 1), (14, 1))
    assert rep.active_time == 1.0 and rep.passive_time == 12.0


def test_a_clean_run_has_neither_kind():
    sc = _scene([WALL])
    rep = check_trajectory([[20.0, 50.0], [30.0, 50.0], [30.0, 50.0]], sc)
    assert rep.ok and rep.active == () and rep.passive == ()
    assert math.isnan(rep.active_time) and math.isnan(rep.passive_time)


def test_static_path_segments_are_active_a_lone_point_passive():
    sc = _scene([WALL])
    moving = check_static_path([[50.0, 50.0], [80.0, 50.0]], [sc.obstacles[0].shape], radius=4)
    assert moving.active == ((0, 0),) and moving.passive == ()
    assert math.isnan(moving.active_time)  # a static path has no times
    point = check_static_path([[62.0, 50.0]], [sc.obstacles[0].shape], radius=4)
    assert point.passive == ((0, 0),) and point.active == ()
