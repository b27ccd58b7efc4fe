"""Every scene family: validated scenes, exact L*, seeding, bad input.

Validation is re-done here with shapely directly (distances to the raw shapes) and the
independent checker, not with the generator's own helpers.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from scipy.optimize import brentq

from mawdo.planning.judge.check import check_static_path
from mawdo.planning.scenes import FAMILIES, SceneRejected, generate_scene, generate_scenes
from mawdo.planning.scenes.base import Family, Param, Redraw, build_scene, draft
from mawdo.registry import UnknownNameError
from mawdo.streams import keyed_seed_sequence, run_seed_sequences

# small, fast parameters per family (the defaults of the slow-oracle families are trimmed)
FAST = {"forest": {"n": 8}, "rooms": {"rows": 2, "cols": 3}, "dense": {"n": 10}}
ALL = list(FAMILIES)


def _shape(ob):
    if ob.is_circle:
        return shapely.Point(ob.shape.center).buffer(ob.shape.radius, 256)
    return shapely.Polygon(ob.shape.vertices)


@pytest.fixture(scope="module", params=ALL)
def scenes(request):
    fam = request.param
    return fam, generate_scenes(fam, 2, seed=5, params=FAST.get(fam))


def test_scenes_validate_and_have_exact_finite_optimum(scenes):
    fam, out = scenes
    for sc in out:
        s = sc.scenario
        r, clear = s.robot_radius, sc.params["clearance"]
        assert sc.family == fam and s.name == f"{fam}-s5-{sc.index}"
        for p in (s.start, s.goal):
            assert r <= p[0] <= s.width - r and r <= p[1] <= s.height - r
            for ob in s.obstacles:
                # the disc buffer is inscribed in the true disc: distance >= true distance
                assert _shape(ob).distance(shapely.Point(p)) > r + clear - 1e-6
        assert math.isfinite(sc.l_star)
        assert sc.l_star >= s.straight_line_length() - 1e-9
        # the stored optimum is a real route: ends at start/goal, its length is L*, and the
        # independent checker accepts it against the static obstacles
        np.testing.assert_allclose(sc.optimum[[0, -1]], [s.start, s.goal])
        assert np.sum(np.hypot(*np.diff(sc.optimum, axis=0).T)) == pytest.approx(sc.l_star)
        statics = [s.obstacles[i].shape for i in s.static_indices]
        assert check_static_path(sc.optimum, statics, radius=r).ok
        assert (len(s.moving_indices) > 0) == FAMILIES[fam].moving
        assert f"L*={sc.l_star:.6f}" in s.spec.description


def test_obstacle_families_block_the_straight_line():
    """Families built to defeat a straight line really do (checked on the static shapes)."""
    for fam in ("maze", "narrow", "u_trap"):
        sc = generate_scene(fam, 0, seed=2, params=FAST.get(fam))
        s = sc.scenario
        line = shapely.LineString([s.start, s.goal])
        hit = min(_shape(s.obstacles[i]).distance(line) for i in s.static_indices)
        assert hit <= s.robot_radius
        assert sc.l_star > s.straight_line_length() + 1.0


def test_crossing_discs_reach_the_line_when_the_robot_does():
    sc = generate_scene("crossing", 3, seed=9)
    s = sc.scenario
    d = (s.goal - s.start) / s.straight_line_length()
    t_end = s.straight_line_length() / s.robot_speed
    for i in s.moving_indices:
        ob = s.obstacles[i]

        def side(t, ob=ob):  # signed distance of the disc's centre from the start-goal line
            c = np.asarray(ob.shape.center) + ob.offset(np.array([t]))[0] - s.start
            return c[0] * d[1] - c[1] * d[0]

        ts = np.linspace(0.0, t_end, 2001)
        signs = np.sign([side(t) for t in ts])
        k = int(np.flatnonzero(signs[:-1] != signs[1:])[0])
        t_cross = brentq(side, ts[k], ts[k + 1], xtol=1e-12)
        centre = np.asarray(ob.shape.center) + ob.offset(np.array([t_cross]))[0]
        robot = s.start + s.robot_speed * t_cross * d
        assert np.hypot(*(robot - centre)) < 1e-6  # the robot is exactly there then


def test_same_seed_same_scenes_independent_of_index_and_order():
    for fam in ("narrow", "dense", "movingai"):
        a = generate_scenes(fam, 3, seed=13, params=FAST.get(fam))
        b = [generate_scene(fam, i, seed=13, params=FAST.get(fam)) for i in (2, 0, 1)]
        c = generate_scenes(fam, 1, seed=13, params=FAST.get(fam), first=2)
        assert a[2].scenario.to_dict() == b[0].scenario.to_dict() == c[0].scenario.to_dict()
        assert a[0].scenario.to_dict() == b[1].scenario.to_dict()
        assert a[0].scenario.to_dict() != a[1].scenario.to_dict()
        other = generate_scene(fam, 0, seed=14, params=FAST.get(fam))
        assert other.scenario.to_dict()["start"] != a[0].scenario.to_dict()["start"]


def test_keyed_seed_sequence_matches_run_streams():
    for k in (0, 3, 17):
        a = keyed_seed_sequence(21, k).generate_state(4)
        b = run_seed_sequences(21, 1, first=k)[0].generate_state(4)
        np.testing.assert_array_equal(a, b)
    assert not np.array_equal(
        keyed_seed_sequence(21, 1, 2).generate_state(4),
        keyed_seed_sequence(21, 2, 1).generate_state(4),
    )
    with pytest.raises(ValueError, match="spawn key"):
        keyed_seed_sequence(1, -1)


def test_unknown_family_suggests_close_names():
    with pytest.raises(UnknownNameError, match="forest"):
        generate_scene("forrest")
    with pytest.raises(UnknownNameError, match="u_trap"):
        generate_scenes("u-trap", 2)


@pytest.mark.parametrize("n", [0, -3])
def test_n_must_be_positive(n):
    with pytest.raises(ValueError, match="n must be >= 1"):
        generate_scenes("open", n)


def test_bad_seed_and_index():
    with pytest.raises(ValueError, match="seed must be >= 0"):
        generate_scene("open", seed=-1)
    with pytest.raises(ValueError, match="index must be >= 0"):
        generate_scene("open", index=-2)
    with pytest.raises(TypeError, match="index must be an integer"):
        generate_scene("open", index=1.5)


def test_parameter_out_of_range_names_it_and_its_range():
    with pytest.raises(ValueError, match=r"forest parameter 'n' = 1000 is out of range \[5, 200\]"):
        generate_scenes("forest", 1, params={"n": 1000})
    with pytest.raises(ValueError, match=r"'speed_max' = 5.0 is out of range \[0.05, 2\]"):
        generate_scene("crossing", params={"speed_max": 5.0})
    with pytest.raises(ValueError, match="'walls' must be an integer"):
        generate_scene("maze", params={"walls": 2.5})
    with pytest.raises(ValueError, match=r"must be one of \['warehouse', 'rooms'\]"):
        generate_scene("movingai", params={"map": "berlin"})


def test_unknown_parameter_and_impossible_combinations():
    with pytest.raises(ValueError, match="Did you mean 'thickness'"):
        generate_scene("rooms", params={"thicknes": 4})
    with pytest.raises(ValueError, match="door = 6 px must be wider than the robot"):
        generate_scene("rooms", params={"door": 6.0, "robot_radius": 4.0})
    with pytest.raises(ValueError, match="rmin = 20 must be <= rmax = 10"):
        generate_scene("forest", params={"rmin": 20.0, "rmax": 10.0})


def test_a_draw_that_can_never_work_is_rejected_with_its_reason():
    with pytest.raises(SceneRejected, match="mouth would swallow the start") as err:
        generate_scene("u_trap", params={"depth": 600.0})
    assert len(err.value.reasons) == 20 and err.value.family == "u_trap"


def _family(draw):
    return Family("test", "test only", (Param("wall", 0.0, 0.0, 1.0),), draw)


def test_unsolvable_draft_is_never_returned():
    """A wall across the whole map: the oracle finds no route, every draw is rejected."""

    def draw(rng, p):
        wall = {"shape": "polygon", "vertices": [[150, 0], [160, 0], [160, 366], [150, 366]]}
        return draft(p, (20.0, 20.0), (340.0, 340.0), [wall])

    fam = _family(draw)
    with pytest.raises(SceneRejected, match="no static route") as err:
        build_scene(fam, fam.resolve(), seed=0, index=0)
    assert isinstance(err.value, ValueError)


def test_bad_draws_are_redrawn_deterministically():
    calls = []

    def draw(rng, p):
        calls.append(1)
        if rng.random() < 0.5:
            raise Redraw("unlucky")
        return draft(p, (20.0, 20.0), (340.0, 340.0), [])

    fam = _family(draw)
    scenes = [build_scene(fam, fam.resolve(), seed=1, index=i) for i in range(6)]
    again = [build_scene(fam, fam.resolve(), seed=1, index=i) for i in range(6)]
    assert [s.attempts for s in scenes] == [s.attempts for s in again]
    assert max(s.attempts for s in scenes) > 1
    assert all(s.l_star == pytest.approx(math.dist((20, 20), (340, 340))) for s in scenes)


def test_describe_family_lists_every_parameter_with_its_range():
    from mawdo.planning.scenes import describe_family

    text = describe_family("narrow")
    for p in FAMILIES["narrow"].all_params:
        assert f"  {p.name} = {p.default!r}  [{p.low:g}, {p.high:g}]" in text
    assert "one of ['warehouse', 'rooms']" in describe_family("movingai")


def test_rooms_too_small_for_the_robot_is_a_clear_error():
    with pytest.raises(ValueError, match="leave no room for the robot beside the walls"):
        generate_scene("rooms", params={"size": 100.0, "rows": 6, "clearance": 5.0})
