"""The observation vector: ray ranges by hand, agent rows, unit conversions."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.gym.observation import Observer, ray_ranges, static_lines  # noqa: E402
from mawdo.planning.sense.reading import Reading  # noqa: E402
from mawdo.planning.sense.tracker import Tracker  # noqa: E402
from mawdo.planning.world.scenario import scenario_from_dict  # noqa: E402
from mawdo.planning.world.units import Units  # noqa: E402


def _scenario(obstacles=()):
    """A 200 x 100 px map at 0.05 m/px and 0.25 s/step, robot 6 px (0.3 m), 4 px/step (0.8 m/s)."""
    from dataclasses import replace

    spec = {
        "schema_version": 1, "name": "box", "seed": 0, "width": 200.0, "height": 100.0,
        "start": [20.0, 50.0], "goal": [180.0, 50.0],
        "robot": {"radius": 6.0, "speed": 4.0}, "obstacles": list(obstacles),
    }  # fmt: skip
    return replace(scenario_from_dict(spec), derived_units=Units("m", 0.25, 0.05))


def test_rays_in_an_empty_box_by_hand():
    lines, solid = static_lines([], 200.0, 100.0)
    # from (50, 30): east 150 px to x = 200, north 70 to y = 100, west 50, south 30
    got = ray_ranges([50.0, 30.0], 4, 1000.0, lines, solid, 200.0, 100.0)
    np.testing.assert_allclose(got, [150.0, 70.0, 50.0, 30.0], atol=1e-9)
    # capped at the reach
    got = ray_ranges([50.0, 30.0], 4, 60.0, lines, solid, 200.0, 100.0)
    np.testing.assert_allclose(got, [60.0, 60.0, 50.0, 30.0], atol=1e-9)
    # diagonal: 45 degrees from (50, 30) meets y = 100 at distance 70 sqrt(2)
    got = ray_ranges([50.0, 30.0], 8, 1000.0, lines, solid, 200.0, 100.0)
    assert got[1] == pytest.approx(70.0 * np.sqrt(2.0))


def test_rays_stop_at_the_first_wall():
    wall = np.array([[100.0, 20.0], [120.0, 20.0], [120.0, 80.0], [100.0, 80.0]])
    lines, solid = static_lines([wall], 200.0, 100.0)
    got = ray_ranges([50.0, 50.0], 4, 1000.0, lines, solid, 200.0, 100.0)
    # east: the wall's near side at x = 100 (not its far side nor the border)
    np.testing.assert_allclose(got, [50.0, 50.0, 50.0, 50.0], atol=1e-9)
    # inside the wall, or off the map: all zero
    assert not ray_ranges([110.0, 50.0], 4, 1000.0, lines, solid, 200.0, 100.0).any()
    assert not ray_ranges([-1.0, 50.0], 4, 1000.0, lines, solid, 200.0, 100.0).any()


def _reading(step, centers, radii, position=(20.0, 50.0), velocity=(0.0, 0.0)):
    return Reading(step, np.array(position), np.array(velocity), np.array([180.0, 50.0]),
                   np.array(centers, float).reshape(-1, 2), np.array(radii, float))  # fmt: skip


def test_agent_rows_nearest_first_in_metres_with_padding():
    sc = _scenario()
    obs = Observer(k=3, n_rays=0, max_range=4.0, tracker=Tracker(noise=0.0))
    obs.reset(sc, [])
    # agents at surface distances 40 - 6 = 34, 20 - 10 = 10 and 30 - 6 = 24 px
    centers = [[60.0, 50.0], [20.0, 70.0], [20.0, 20.0]]
    radii = [6.0, 10.0, 6.0]
    v = obs.observe(_reading(0, centers, radii, velocity=(2.0, -1.0)))
    assert v.dtype == np.float32 and v.shape == (6 + 18,)
    # robot: goal offset 160 px = 8 m; velocity (2, -1) px/step = (0.4, -0.2) m/s
    np.testing.assert_allclose(v[:6], [8.0, 0.0, 0.4, -0.2, 0.3, 0.8], rtol=1e-6)
    rows = v[6:].reshape(3, 6)
    np.testing.assert_allclose(rows[:, :2], [[0.0, 1.0], [0.0, -1.5], [2.0, 0.0]], atol=1e-6)
    np.testing.assert_allclose(rows[:, 4], [0.5, 0.3, 0.3], rtol=1e-6)
    np.testing.assert_array_equal(rows[:, 5], 1.0)
    np.testing.assert_array_equal(rows[:, 2:4], 0.0)  # a new track has velocity 0
    # k = 5 with three agents: two padding rows of zeros
    obs5 = Observer(k=5, n_rays=0, max_range=4.0, tracker=Tracker(noise=0.0))
    obs5.reset(sc, [])
    rows5 = obs5.observe(_reading(0, centers, radii))[6:].reshape(5, 6)
    np.testing.assert_array_equal(rows5[3:], 0.0)
    np.testing.assert_array_equal(rows5[:3], rows)


def test_agent_velocities_are_the_trackers_in_metres_per_second():
    sc = _scenario()
    obs = Observer(k=1, n_rays=0, max_range=4.0, tracker=Tracker(noise=0.0))
    ref = Tracker(noise=0.0)
    obs.reset(sc, [])
    for step in range(4):  # one agent walking +2 px/step in x
        r = _reading(step, [[60.0 + 2.0 * step, 50.0]], [6.0])
        v = obs.observe(r)
        tracks = ref.update(r)
    np.testing.assert_allclose(v[8:10], tracks.velocities[0] * 0.05 / 0.25, rtol=1e-6)
    assert v[8] == pytest.approx(0.4, abs=0.05)  # close to the true 2 px/step = 0.4 m/s


def test_actions_clip_per_axis_and_convert():
    sc = _scenario()
    obs = Observer(k=0, n_rays=0, max_range=4.0, tracker=Tracker(noise=0.0))
    obs.reset(sc, [])
    # robot speed 0.8 m/s: (2, -0.5) m/s -> (0.8, -0.5) m/s -> (4, -2.5) px/step
    np.testing.assert_allclose(obs.velocity_px([2.0, -0.5]), [4.0, -2.5])
    np.testing.assert_allclose(obs.action_of([4.0, -2.5]), [0.8, -0.5])
    with pytest.raises(ValueError, match="finite velocity"):
        obs.velocity_px([1.0, np.inf])


def test_observe_before_reset_says_so():
    obs = Observer(k=1, n_rays=1, max_range=1.0, tracker=Tracker(noise=0.0))
    with pytest.raises(RuntimeError, match="before reset"):
        obs.observe(_reading(0, [], []))


def test_bounds_hold_and_clip():
    sc = _scenario()
    obs = Observer(k=1, n_rays=2, max_range=4.0, tracker=Tracker(noise=0.0))
    low, high = obs.bounds(sc)
    obs.reset(sc, [])
    # a detection far off the map is clipped to twice the diagonal (2 * 11.18 m)
    v = obs.observe(_reading(0, [[5000.0, 50.0]], [6.0]))
    diag = np.hypot(200.0, 100.0) * 0.05
    assert v[6] == pytest.approx(2 * diag, rel=1e-6)
    assert np.all(v >= low) and np.all(v <= high)
