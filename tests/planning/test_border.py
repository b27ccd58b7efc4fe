"""Issue 30: the map's border is a wall. The robot's whole disc stays in the map, or the run is
not a success; start and goal closer than the radius to the border are refused."""

import math
import os
import subprocess
import sys

import numpy as np
import pytest

from mawdo.planning import PathCost, check_trajectory, scenario_optimum
from mawdo.planning.baselines.result import make_result, route_times
from mawdo.planning.guide.homotopy import SLACK, Guide
from mawdo.planning.guide.oracle import shortest_path
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.planner import plan
from mawdo.planning.run.result import Drive
from mawdo.planning.safety.guard import Guard
from mawdo.planning.world.path import polyline_length
from mawdo.planning.world.scenario import ScenarioError

from .test_check import scenario

R = 4.0


def world(width=200.0, height=100.0, start=(20, 20), goal=(180, 20), obstacles=(), radius=R):
    return scenario(list(obstacles), radius, width, height, start, goal)


def rect(x0, y0, x1, y1):
    return {"shape": "polygon", "vertices": [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]}


def around_corner(p, c, radius, corner_angle):
    """Length from ``p`` to the point at ``corner_angle`` on the circle (``c``, ``radius``),
    along the tangent from ``p`` and then the arc (hand geometry, counter-clockwise side)."""
    d = math.dist(p, c)
    tangent = math.sqrt(d * d - radius * radius)
    toward_p = math.atan2(p[1] - c[1], p[0] - c[0])
    touch = toward_p - math.acos(radius / d)  # the tangent point seen from the centre
    arc = (touch - corner_angle) % (2 * math.pi)
    return tangent + radius * arc


# -- start and goal -----------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("which", "point"),
    [("start", (3.9, 50)), ("start", (50, 96.5)), ("goal", (196.01, 50)), ("goal", (100, 0.0))],
)
def test_start_or_goal_within_the_radius_of_the_border_is_refused_with_the_range(which, point):
    kw = {"start": (50, 50), "goal": (150, 50), which: point}
    with pytest.raises(ScenarioError) as info:
        world(**kw)
    msg = str(info.value)
    assert f"{which}: " in msg and "closer than the robot radius 4 px to the map border" in msg
    assert "allowed: [4, 196] x [4, 96]" in msg


def test_start_and_goal_exactly_the_radius_from_the_border_are_accepted():
    sc = world(start=(4, 4), goal=(196, 96))
    assert tuple(sc.start) == (4, 4) and tuple(sc.goal) == (196, 96)
    with pytest.raises(ScenarioError, match="does not fit in the 6 x 100 px map"):
        world(width=6, start=(3, 50), goal=(3, 60))


def test_the_command_refuses_a_start_on_the_border(tmp_path):
    f = tmp_path / "edge.toml"
    f.write_text(
        "schema_version = 1\nwidth = 100.0\nheight = 100.0\nstart = [2.0, 50.0]\n"
        "goal = [90.0, 50.0]\n[robot]\nradius = 4.0\nspeed = 4.0\n"
    )
    env = {**os.environ, "MPLBACKEND": "Agg"}
    res = subprocess.run(
        [sys.executable, "-m", "mawdo.cli", "plan", str(f), "--preset", "quick"],
        capture_output=True, text=True, timeout=300, env=env, cwd=tmp_path,
    )  # fmt: skip
    assert res.returncode == 2, res.stderr
    assert "\u2502" not in res.stderr  # a plain error line at any terminal width, no panel
    text = " ".join(res.stderr.split())
    assert "start: (2, 50) is closer than the robot radius 4 px to the map border" in text
    assert "allowed: [4, 96] x [4, 96]" in text
    assert "Traceback" not in res.stderr + res.stdout


# -- the checker --------------------------------------------------------------------------------


def test_the_checker_counts_a_disc_leaving_the_map_as_a_border_collision():
    sc = world()
    # y = 2.5: the disc (r = 4) pokes 1.5 px out below; the centre never leaves the map
    route = np.array([[20.0, 20.0], [60.0, 2.5], [140.0, 2.5], [180.0, 20.0]])
    rep = check_trajectory(route, sc, times=route_times(route, sc.robot_speed))
    assert not rep.ok and rep.out_of_map == () and rep.collisions == ()
    assert rep.border == (0, 1, 2) and rep.hits == 3
    assert rep.border_excess == pytest.approx(1.5, abs=1e-12)
    assert rep.describe() == "route leaves the map by 1.5 px"
    # at exactly the radius the disc touches the border: allowed, as touching an obstacle is
    inside = route.copy()
    inside[1:3, 1] = 4.0
    ok = check_trajectory(inside, sc, times=route_times(inside, sc.robot_speed))
    assert ok.ok and ok.border == () and ok.border_excess == pytest.approx(0.0, abs=1e-12)
    # a single position near the right border
    one = check_trajectory(np.array([[197.0, 50.0]]), sc)
    assert one.border == (0,) and one.border_excess == pytest.approx(1.0)


def test_a_run_forced_against_the_border_is_no_success():
    # the shortest route for the centre alone (the map itself as its box, as before issue 30)
    # squeezes under the wall, 1 px from the border: its disc leaves the map by 3 px
    sc = world(obstacles=[rect(60, 7, 140, 80)])
    centre_only = shortest_path(sc.start, sc.goal, [_inflated(sc)], sc.bounds).path
    assert centre_only[:, 1].min() == pytest.approx(3.0, abs=0.05)
    drive = Drive(sc.start.copy())
    stamps = route_times(centre_only, sc.robot_speed)
    drive.route, drive.stamps = list(centre_only), list(stamps)
    res = drive.result(
        "goal reached", sc, algorithm="oracle", seed=0, config=PlannerConfig(), replans=[]
    )
    assert not res.success and not res.collision_free
    assert "route leaves the map by 1 px" in res.reason and "goal reached but" in res.reason
    # a baseline's route is judged by the same rule
    base = make_result("straight", sc, centre_only, 0.0)
    assert not base.success and base.solved
    assert base.reason == "checker rejects the timed route: route leaves the map by 1 px"


def _inflated(sc):
    from mawdo.planning.world.geometry import inflated_obstacles

    return inflated_obstacles(sc, indices=sc.static_indices)[0]


def test_the_guard_steps_keep_the_disc_in_the_map():
    sc = world()
    guard = Guard(sc, clearance=0.5)
    assert guard.step_clearance(np.array([10.0, 50.0]), np.array([6.0, 50.0]), 0.0, 1.0) == (
        pytest.approx(2.0)
    )
    assert guard.step_clearance(np.array([10.0, 50.0]), np.array([2.0, 50.0]), 0.0, 1.0) == (
        pytest.approx(-2.0)
    )


# -- the cost -----------------------------------------------------------------------------------


def test_the_cost_counts_segments_whose_disc_plus_margin_leaves_the_map():
    sc = world(start=(20, 50), goal=(180, 50))
    cost = PathCost(sc, n_waypoints=2, clearance=0.5)
    hit = cost.parts(np.array([100.0, 4.49, 150.0, 50.0]))[1]  # one vertex 4.49 < 4.5 from it
    assert hit == 2  # both its segments
    assert cost.parts(np.array([100.0, 4.5, 150.0, 50.0]))[1] == 0  # r + clearance: touching
    assert cost.parts(np.array([100.0, 95.6, 199.0, 50.0]))[1] == 3  # two vertices out
    # the margin moves the wall: with clearance 0 the 4.49 px vertex is free
    assert PathCost(sc, n_waypoints=2).parts(np.array([100.0, 4.49, 150.0, 50.0]))[1] == 0


def test_the_cost_is_unchanged_bit_for_bit_for_routes_inside_the_map():
    # the same obstacles on a map so large that no candidate comes near its border
    obs = [rect(60, 30, 90, 70), {"shape": "circle", "center": [140, 40], "radius": 12}]
    small = world(start=(20, 50), goal=(180, 50), obstacles=obs)
    large = world(width=4000, height=4000, start=(20, 50), goal=(180, 50), obstacles=obs)
    rng = np.random.default_rng(30)
    X = rng.uniform(4.6, 95.4, (500, 40)) * np.tile([2.0, 1.0], 20)  # inside [4.6, 195.4]
    X[:, 0::2] = np.clip(X[:, 0::2], 4.6, 195.4)
    for mode in ("snapshot", "spacetime"):
        a = PathCost(small, mode=mode, clearance=0.5)
        b = PathCost(large, mode=mode, clearance=0.5)
        np.testing.assert_array_equal(a(X, t0=2.0), b(X, t0=2.0))
        assert np.any(a.parts(X)[1] > 0)  # obstacle hits are in the sample


# -- the exact optimum and the planner ----------------------------------------------------------


def test_the_optimum_goes_around_a_gap_too_narrow_for_the_disc_beside_the_border():
    # under the wall the centre has 3 px (its inflated bottom at y = 3) but needs 4 from the
    # border: the shortest route goes over the top, around the rounded corners (60, 80) and
    # (140, 80), along y = 84
    sc = world(obstacles=[rect(60, 7, 140, 80)])
    opt = scenario_optimum(sc)
    hand = 2 * around_corner((20, 20), (60, 80), R, math.pi / 2) + 80.0
    assert opt.length == pytest.approx(hand, abs=0.05)  # the octagonal corners add a hair
    assert opt.path[:, 1].max() == pytest.approx(84.0, abs=0.05)
    # the centre alone would squeeze under it, much shorter
    below = shortest_path(sc.start, sc.goal, [_inflated(sc)], sc.bounds)
    assert below.length < opt.length - 50


def test_a_route_that_hugs_the_border_keeps_radius_plus_clearance_from_it():
    # a wall down from the top leaves a band y in [4, 5.8] under it for the centre (5.3 with
    # the planner's 0.5 px clearance): the shortest route runs along the bottom border
    sc = world(height=60, start=(20, 40), goal=(180, 40), obstacles=[rect(60, 9.8, 140, 60)])
    # mirrored in y, it is the route over a corner of the test above
    hand = 2 * around_corner((20, -40), (60, -9.8), R, math.pi / 2) + 80.0
    l_star = scenario_optimum(sc).length
    assert l_star == pytest.approx(hand, abs=0.05)
    guide = Guide(sc, clearance=0.5)
    lowest = guide.routes(sc.start)[0][:, 1].min()
    assert lowest >= R + 0.5 + SLACK - 1e-9 and lowest < 5.8
    res = plan(sc, algorithm="mawdo", seed=1, config="quick")
    assert res.success, res.reason
    assert res.route[:, 1].min() >= R + 0.5 - 1e-9  # r + clearance from the border
    assert res.route[:, 1].min() < 5.8  # and it did take the band along the border
    assert polyline_length(res.route) < 1.05 * l_star
