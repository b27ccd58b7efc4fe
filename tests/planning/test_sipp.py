"""Safe-interval guide (issue 27, item 1): exact departure sets, scenes where only timing works,
and the earliest arrival against a brute-force time-grid search judged by the shapely checker."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import shapely

from mawdo.planning import scenario_from_dict
from mawdo.planning.guide.sipp import SafeIntervalGuide
from mawdo.planning.guide.sipp.intervals import Movers, forbidden, segment_free
from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.world.motion import Motion
from mawdo.planning.world.scenario import Scenario
from tests.planning import maps
from tests.planning.sipp_reference import grid_earliest_arrival

CLEAR = 0.5  # the guide's default clearance (px)


def _box(x0, y0, x1, y1, **kw):
    return {"shape": "polygon", "vertices": [[x0, y0], [x1, y0], [x1, y1], [x0, y1]], **kw}


def _scene(w, h, start, goal, obstacles, radius=4.0, speed=4.0, seed=0):
    return scenario_from_dict(
        {
            "schema_version": 1,
            "seed": seed,
            "width": w,
            "height": h,
            "start": list(start),
            "goal": list(goal),
            "robot": {"radius": radius, "speed": speed},
            "obstacles": obstacles,
        }
    )


def _clean(route, sc, margin=CLEAR):
    """The independent checker passes the route, with the guide's clearance kept (to 1e-6)."""
    rep = check_trajectory(route.points, sc, times=route.times)
    return rep.ok and rep.min_clearance >= margin - 1e-6


# ---------------------------------------------------------------------------------------------
# the departure sets against the exact yes/no test, move by move


def _random_movers(rng, walk=False):
    obs = []
    for j in range(3):
        c = rng.uniform(30, 90, 2)
        motion = {"velocity": list(rng.uniform(-2, 2, 2))}
        if j == 1:
            motion = {"model": "patrol", "waypoints": [list(rng.uniform(-20, 20, 2))], "speed": 1.5}
        if walk and j == 2:
            motion = {"model": "bounded_random_walk", "step": 1.0, "hold": 3}
        if j == 0:
            obs.append({"shape": "circle", "center": list(c), "radius": 6.0, "motion": motion})
        else:  # an L: a non-convex polygon
            v = [[0, 0], [16, 0], [16, 6], [6, 6], [6, 14], [0, 14]]
            obs.append(
                {"shape": "polygon", "vertices": (np.array(v) + c).tolist(), "motion": motion}
            )
    return _scene(120, 120, (2, 2), (118, 118), obs, radius=2.0, speed=2.0, seed=3)


@pytest.mark.parametrize("walkers", ["known", "reachable"])
def test_forbidden_departures_agree_with_the_exact_check(walkers):
    """Departures inside the closed-form forbidden set collide, those outside do not, as the
    piece-by-piece test with the cost kernel's primitives says (sampled densely)."""
    rng = np.random.default_rng(11)
    disagree = checked = 0
    for trial in range(12):
        sc = _random_movers(rng, walk=walkers == "reachable")
        mv = Movers.from_scenario(sc, CLEAR, 0.0, 80.0, walkers).arrays()
        u, v = rng.uniform(5, 115, 2), rng.uniform(5, 115, 2)
        T = np.hypot(*(v - u)) / 2.0 if trial % 4 else 0.0  # every fourth: a point in time
        e = (v - u) / T if T > 0 else np.zeros(2)
        lo, hi = 0.0, 80.0 - T
        F = forbidden(u[0], u[1], e[0], e[1], T, lo, hi, mv)
        for tau in np.linspace(lo, hi, 801):
            inside = bool(np.any((F[:, 0] <= tau) & (tau <= F[:, 1])))
            near = np.min(np.abs(F - tau)) < 1e-6 if len(F) else False
            if near:
                continue
            free = segment_free(u[0], u[1], *(u + e * T), tau, tau + T, mv)
            checked += 1
            disagree += inside == free
    assert checked > 8000
    assert disagree == 0


def test_reachable_set_departures_against_shapely():
    """A walker seen as a reachable set forbids every departure from ``t0 + min_s (dist(u +
    s e, shape) - thr) / vmax - s`` on; the minimum here is over a fine grid of ``s``, with
    shapely distances (the function is Lipschitz, so the grid is within ``L ds`` of it)."""
    L = [[0, 0], [16, 0], [16, 6], [6, 6], [6, 14], [0, 14]]
    walker = {
        "shape": "polygon",
        "vertices": (np.array(L) + 50.0).tolist(),
        "motion": {"model": "bounded_random_walk", "step": 1.0, "hold": 3},
    }
    sc = _scene(120, 120, (2, 2), (118, 118), [walker], radius=2.0, speed=2.0)
    mv = Movers.from_scenario(sc, CLEAR, 0.0, 80.0, "reachable").arrays()
    shape = shapely.Polygon(np.array(L) + 50.0)
    rng = np.random.default_rng(6)
    for _ in range(30):
        u, v = rng.uniform(5, 115, 2), rng.uniform(5, 115, 2)
        T = np.hypot(*(v - u)) / 2.0
        s = np.linspace(0.0, T, 20001)
        pts = u + np.outer(s / T, v - u)
        first = np.min(shapely.distance(shapely.points(pts), shape) - (2.0 + CLEAR) - s)
        F = forbidden(*u, *((v - u) / T), T, -1e3, 1e3, mv)
        assert len(F) == 1 and F[0, 1] == 1e3  # forbidden from a time on, for good
        lip = 2.0 + 1.0  # |e| / vmax + 1
        assert first - lip * (s[1] - s[0]) - 1e-9 <= F[0, 0] <= first + 1e-9


def test_safe_intervals_by_hand():
    """A circle (radius 6, 2 px per step from x = 20) and a 40 x 40 square (1 px per step from
    x = 10..50) pass over the spot (100, 50); hit distance 4 + 0.5 beyond the shapes. Circle:
    |20 + 2 t - 100| <= 10.5, t in [34.75, 45.25]. Square: its right side reaches 100 - 4.5 at
    t = 45.5 and its left side leaves 100 + 4.5 at t = 94.5; between, the spot is deep inside
    (up to 20 px from every side), which only the inside test of the polygon catches."""
    circle = {"shape": "circle", "center": [20, 50], "radius": 6.0, "motion": {"velocity": [2, 0]}}
    square = _box(10, 30, 50, 70, motion={"velocity": [1.0, 0.0]})
    for mover, unsafe in ((circle, (34.75, 45.25)), (square, (45.5, 94.5))):
        sc = _scene(300, 100, (5, 5), (295, 95), [mover])
        guide = SafeIntervalGuide(sc, spots=[(100, 50)], horizon=120.0)
        iv = guide.intervals(1)  # the goal is node 0, the first spot node 1
        np.testing.assert_allclose(iv, [[0.0, unsafe[0]], [unsafe[1], 120.0]], atol=1e-9)


def test_without_movers_it_is_the_static_shortest_route():
    """No mover: no wait, the arrival is the route's length over the speed, and the route is
    the static optimum up to the guide's coarser inflation (octagons + 0.05 px vs 32-gons)."""
    from mawdo.planning.guide.oracle import scenario_optimum

    sc = maps.u_trap(3)
    (route,) = SafeIntervalGuide(sc, clearance=0.0).routes(k=1)
    length = np.sum(np.hypot(*np.diff(route.points, axis=0).T))
    assert route.waiting == 0.0
    assert route.arrival == pytest.approx(length / sc.robot_speed, rel=1e-12)
    best = scenario_optimum(sc).length
    assert best - 1e-6 <= length <= 1.01 * best
    assert _clean(route, sc, margin=0.0)


def test_alternatives_are_time_diverse_and_clean():
    """k = 3: the earliest route first, then alternatives that share no (vertex, interval)
    state inside them with the routes before, each passing the checker."""
    sc = _small_scene(0)
    routes = SafeIntervalGuide(sc, horizon=150.0).routes(k=3)
    assert len(routes) == 3
    arrivals = [r.arrival for r in routes]
    assert arrivals == sorted(arrivals) and arrivals[0] < arrivals[-1]
    inner = [set(r.states[1:-1]) for r in routes]
    assert all(not (inner[i] & inner[j]) for i in range(3) for j in range(i))
    assert all(_clean(r, sc) for r in routes)


def test_start_on_the_goal_or_a_corner():
    """A start on the goal arrives at once; a start on a corner goes on from it."""
    sc = _door_scene()
    guide = SafeIntervalGuide(sc, start=sc.goal, t0=3.0)
    (route,) = guide.routes(k=1)
    assert route.arrival == 3.0
    corner = guide.nodes[5]
    (route,) = SafeIntervalGuide(sc, start=corner).routes(k=1)
    assert _clean(route, sc) and route.arrival > 0.0


def test_bad_input_is_refused_with_the_fix():
    sc = _corridor(bay=True)
    with pytest.raises(ValueError, match="start .* inside an inflated static obstacle"):
        SafeIntervalGuide(sc, start=(20, 20))
    with pytest.raises(ValueError, match="spots\\[0\\]"):
        SafeIntervalGuide(sc, spots=[(145, 95)])
    with pytest.raises(ValueError, match="walkers must be one of"):
        SafeIntervalGuide(sc, walkers="guess")
    with pytest.raises(ValueError, match="horizon must be finite and > 0"):
        SafeIntervalGuide(sc, horizon=0.0)
    with pytest.raises(ValueError, match="t0 must be finite and >= 0"):
        SafeIntervalGuide(sc, t0=-1.0)
    with pytest.raises(ValueError, match="k must be an integer >= 1"):
        SafeIntervalGuide(sc).routes(k=0)
    # the mover reaches the start (x = 20) at t = 170: a start inside it cannot leave safely
    with pytest.raises(ValueError, match="start is inside a moving obstacle"):
        SafeIntervalGuide(sc, t0=170.0).routes()


# ---------------------------------------------------------------------------------------------
# scenes where only timing works


def _corridor(bay: bool):
    walls = [_box(0, 0, 400, 40)]
    if bay:  # a 30 x 30 bay above the corridor at x 130..160
        walls += [_box(0, 60, 130, 100), _box(160, 60, 400, 100), _box(130, 90, 160, 100)]
    else:
        walls += [_box(0, 60, 400, 100)]
    mover = {
        "shape": "circle",
        "center": [360, 50],
        "radius": 6.0,
        "motion": {"velocity": [-2.0, 0.0]},
    }
    return _scene(400, 100, (20, 50), (392, 50), [*walls, mover])


def test_corridor_only_waiting_in_the_bay_succeeds():
    sc = _corridor(bay=True)
    guide = SafeIntervalGuide(sc, spots=[(145, 78)])
    (route,) = guide.routes(k=1)
    assert _clean(route, sc)
    # it waits inside the bay (above the corridor's inflated wall) while the mover passes
    waits = [
        (p, t0, t1)
        for p, q, t0, t1 in zip(
            route.points[:-1], route.points[1:], route.times[:-1], route.times[1:], strict=True
        )
        if np.all(p == q) and t1 > t0
    ]
    in_bay = [(t0, t1) for p, t0, t1 in waits if p[1] > 60 + 4 + CLEAR]
    assert in_bay
    t_pass = (360 - 160 - 6 - 4 - CLEAR) / 2.0  # the mover's front clears the bay's right side
    assert any(t1 >= t_pass for _, t1 in in_bay)
    # the same corridor without the bay: no timed route exists
    assert SafeIntervalGuide(_corridor(bay=False)).routes(k=1) == []


def _door_scene():
    wall = [_box(190, 0, 210, 130), _box(190, 170, 210, 300)]
    blocker = _box(
        190, 170, 210, 210,
        motion={"model": "patrol", "waypoints": [[0, -40]], "speed": 1.0,
                "cycle": "back_and_forth"},
    )  # fmt: skip
    return _scene(400, 300, (20, 150), (380, 150), [*wall, blocker])


def _best_straight_arrival(sc):
    """Earliest arrival of the straight start-goal route departing at any tau on a 0.01 grid,
    each departure judged by the shapely checker."""
    T = np.hypot(*(sc.goal - sc.start)) / sc.robot_speed
    for tau in np.arange(0.0, 100.0, 0.01):
        rep = check_trajectory([sc.start, sc.start, sc.goal], sc, times=[0.0, tau, tau + T])
        if rep.ok and rep.min_clearance > CLEAR:
            return tau + T
    return np.inf


def test_patrol_door_is_timed():
    sc = _door_scene()
    (route,) = SafeIntervalGuide(sc).routes(k=1)
    assert _clean(route, sc)
    assert route.waiting > 0.0
    # the same path driven without waiting collides with the door's blocker
    pts = np.unique(route.points, axis=0, return_index=True)[1]
    path = route.points[np.sort(pts)]
    times = np.r_[0.0, np.cumsum(np.hypot(*np.diff(path, axis=0).T)) / sc.robot_speed]
    assert not check_trajectory(path, sc, times=times).ok
    # no later than the best timed straight route (a route of the graph), by the checker
    assert route.arrival <= _best_straight_arrival(sc) + 1e-6


class _Track(Motion):
    """Piecewise-linear waypoint track ``(time, dx, dy)``; holds the last offset."""

    def __init__(self, knots):
        self.k = np.asarray(knots, dtype=float)

    def offset(self, t):
        t = np.asarray(t, dtype=float)
        x = np.interp(t, self.k[:, 0], self.k[:, 1])
        y = np.interp(t, self.k[:, 0], self.k[:, 2])
        return np.stack([x, y], axis=-1)

    def _inner_knots(self, t0, t1):
        kt = self.k[:, 0]
        return kt[(kt > t0) & (kt < t1)]


def test_mover_parks_then_leaves():
    """A box parks across the corridor until t = 50, then rises out of it at 2 px per step:
    the robot waits, then goes. By hand: its centre cannot be over the box (x in 180..200)
    before the box's bottom clears the corridor's lowest line, 40 + 2 (t - 50) > 44.5 + 4.5,
    i.e. t > 54.5, so it arrives no earlier than 54.5 + 180 / 4 = 99.5; driving straight at
    y = 50 and reaching x = 175.5 when the bottom passes 54.5 (t = 57.25) is free, so it
    arrives no later than 57.25 + 204.5 / 4 = 108.375."""
    walls = [_box(0, 0, 400, 40), _box(0, 60, 400, 100)]
    sc0 = _scene(400, 100, (20, 50), (380, 50), [*walls, _box(180, 40, 200, 60)])
    track = _Track([(0, 0, 0), (50, 0, 0), (80, 0, 60), (1e9, 0, 60)])
    box = dataclasses.replace(sc0.obstacles[2], motion=track)
    sc = Scenario(sc0.spec, (*sc0.obstacles[:2], box))
    (route,) = SafeIntervalGuide(sc).routes(k=1)
    assert _clean(route, sc)
    assert route.waiting > 0.0
    assert 99.5 - 1e-9 <= route.arrival <= 108.375 + 1e-5


# ---------------------------------------------------------------------------------------------
# against brute force on a time grid


def _small_scene(seed):
    rng = np.random.default_rng(seed)
    obs = [
        _box(*(c := rng.uniform(25, 75, 2)), *(c + rng.uniform(8, 20, 2)))
        for _ in range(2)
    ]  # fmt: skip
    for _ in range(3):
        obs.append(
            {
                "shape": "circle",
                "center": list(rng.uniform(20, 80, 2)),
                "radius": float(rng.uniform(4, 8)),
                "motion": {"velocity": list(rng.uniform(-1.5, 1.5, 2))},
            }
        )
    return _scene(100, 100, (6, 6), (94, 94), obs, radius=2.0, speed=2.0)


def _against_grid(sc, h, horizon=None):
    """SIPP's route and the grid search's earliest arrival on the same graph; the grid runs
    to one step per departure past SIPP's arrival (an earlier grid arrival would be found)."""
    guide = SafeIntervalGuide(sc, horizon=horizon)
    (route,) = guide.routes(k=1)
    edges = [
        (u, int(guide.indices[e]), float(guide.weights[e]))
        for u in range(len(guide.nodes))
        for e in range(guide.indptr[u], guide.indptr[u + 1])
    ]
    K = int(np.ceil((route.arrival + h * len(route.states)) / h)) + 1
    grid = grid_earliest_arrival(sc, guide.nodes, edges, guide.start, 0, h, K, CLEAR)
    return route, grid


def _assert_same_within_grid(route, grid, sc, h):
    assert _clean(route, sc)
    # continuous waiting can only help; following SIPP's route on the grid delays each
    # departure by less than one step
    assert route.arrival <= grid + 1e-6
    assert grid - route.arrival <= h * (len(route.states) - 1)


def test_waiting_pocket_matches_time_grid_search():
    """The pocket (tests/planning/maps.py): a door box leaves slowly; SIPP waits, and the
    brute-force grid search (shapely checker on every wait and move) agrees within a step."""
    sc = maps.waiting_pocket()
    route, grid = _against_grid(sc, 0.5)
    assert route.waiting > 0.0
    _assert_same_within_grid(route, grid, sc, 0.5)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4))
def test_earliest_arrival_matches_time_grid_search(seed):
    """Small random scenes (2 boxes, 3 bouncing circles): about 30 s each on a shared core."""
    sc = _small_scene(seed)
    route, grid = _against_grid(sc, 0.25, horizon=150.0)
    _assert_same_within_grid(route, grid, sc, 0.25)


def test_the_movers_pieces_are_one_diff_per_mover():
    # the pieces of every mover are laid out at once; one np.diff per mover is the reference
    from mawdo.planning.guide.sipp.intervals import Movers
    from mawdo.planning.world.geometry import FlatObstacles

    rng = np.random.default_rng(4)
    for _ in range(30):
        pieces = []
        for _ in range(int(rng.integers(1, 6))):
            k = int(rng.integers(0, 5))
            t = np.cumsum(rng.uniform(0.01, 9.0, k))
            pieces.append((t, rng.normal(0, 30, (k, 2))))
        n = len(pieces)
        flat = FlatObstacles(np.ones(n, np.bool_), np.ones(n), np.zeros((n, 1, 2)),
                             np.zeros(n, np.int64), np.zeros((n, 7)), np.zeros((n, 1, 3)),
                             np.zeros(n, np.int64))  # fmt: skip
        mv = Movers._from_pieces(np.zeros(n, np.int64), flat, np.zeros(n), np.zeros((n, 2)),
                                 0.0, pieces, indexed=False)  # fmt: skip
        for m, (t, off) in enumerate(pieces):
            a, b = mv.pptr[m], mv.pptr[m + 1]
            assert b - a == max(len(t) - 1, 0)
            assert np.array_equal(mv.pt0[a:b], t[:-1]) and np.array_equal(mv.pt1[a:b], t[1:])
            assert np.array_equal(mv.po[a:b], off[:-1].reshape(-1, 2))
            want = np.diff(off, axis=0) / np.diff(t)[:, None]
            assert np.array_equal(mv.pv[a:b], want.reshape(-1, 2))
