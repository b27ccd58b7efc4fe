"""The movers' index of the safe-interval guide: every answer through it equals the answer over
all movers (forbidden departures, the yes/no test of a timed move, safe intervals), bit for bit,
on random worlds with bouncing discs, patrolling polygons and random walkers; and the
candidates it returns hold every mover a move really meets (judged by shapely)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
import shapely.affinity

from mawdo.planning import ScenarioError, scenario_from_dict
from mawdo.planning.guide.sipp.index import candidates
from mawdo.planning.guide.sipp.intervals import Movers, forbidden, safe_intervals, segment_free

SIZE = 300.0


def _world(seed: int, movers: int = 30):
    """Random movers on a ``SIZE`` px map; redrawn (same stream) until the start is free."""
    rng = np.random.default_rng(seed)
    while True:
        try:
            return scenario_from_dict(_spec(rng, seed, movers))
        except ScenarioError:
            continue


def _spec(rng, seed: int, movers: int) -> dict:
    obstacles = []
    for j in range(movers):
        c = rng.uniform(25, SIZE - 25, 2).round(3).tolist()
        if j % 5 == 3:  # a polygon on patrol
            ang = np.sort(rng.uniform(0, 2 * np.pi, 4))
            verts = (np.array(c) + 8 * np.c_[np.cos(ang), np.sin(ang)]).round(3).tolist()
            way = rng.uniform(-40, 40, (2, 2)).round(3).tolist()
            patrol = {"model": "patrol", "waypoints": way, "speed": 1.5}
            obstacles.append({"shape": "polygon", "vertices": verts, "motion": patrol})
            continue
        motion = {"velocity": rng.uniform(-3, 3, 2).round(3).tolist()}
        if j % 7 == 6:
            motion = {"model": "bounded_random_walk", "step": 1.0, "hold": 4}
        obstacles.append({"shape": "circle", "center": c, "radius": float(rng.uniform(3, 8)),
                          "motion": motion})  # fmt: skip
    spec = {"schema_version": 1, "seed": seed, "width": SIZE, "height": SIZE,
            "start": [5.0, 5.0], "goal": [SIZE - 5, SIZE - 5], "obstacles": obstacles}  # fmt: skip
    return spec


def _shape(o) -> shapely.Geometry:
    s = o.shape
    if o.is_circle:
        return shapely.Point(*s.center).buffer(s.radius, 256)
    return shapely.Polygon(s.vertices)


def _tables(sc, walkers: str, t0: float = 0.0, t_end: float = 150.0):
    kw = dict(margin=0.5, t0=t0, t_end=t_end, walkers=walkers)
    return (
        Movers.from_scenario(sc, **kw).arrays(),
        Movers.from_scenario(sc, **kw, indexed=False).arrays(),
    )


def _moves(rng, n: int):
    for _ in range(n):
        u = rng.uniform(-10, SIZE + 10, 2)
        v = u + rng.uniform(-120, 120, 2) * (rng.random() < 0.9)  # some waits
        T = float(np.hypot(*(v - u)) / 4.0)
        e = (v - u) / T if T > 0 else np.zeros(2)
        lo = float(rng.uniform(-5, 140))
        yield u, v, e, T, lo, lo + float(rng.choice([0.0, 3.0, 8.0, 40.0]))


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("walkers", ["reachable", "known"])
def test_indexed_answers_equal_those_over_all_movers(seed, walkers):
    sc = _world(seed)
    A, B = _tables(sc, walkers)
    rng = np.random.default_rng(100 + seed)
    hits = 0
    for u, v, e, T, lo, hi in _moves(rng, 400):
        fa = forbidden(u[0], u[1], e[0], e[1], T, lo, hi, A)
        fb = forbidden(u[0], u[1], e[0], e[1], T, lo, hi, B)
        assert np.array_equal(fa, fb)
        hits += len(fb) > 0
        free = segment_free(u[0], u[1], v[0], v[1], lo, lo + T, A)
        assert free == segment_free(u[0], u[1], v[0], v[1], lo, lo + T, B)
    assert hits > 50  # the worlds are crowded enough for the test to mean something
    nodes = rng.uniform(0, SIZE, (60, 2))
    ours, all_of_them = safe_intervals(nodes, 0.0, 150.0, A), safe_intervals(nodes, 0.0, 150.0, B)
    for x, y in zip(ours, all_of_them, strict=True):  # (ptr, lo, hi)
        assert np.array_equal(x, y)


def test_the_index_prunes_and_keeps_every_mover_met():
    """Judged by shapely at fine time steps: a mover whose inflated shape holds the robot at
    some time of the move is a candidate; and far fewer than all movers are."""
    sc = _world(7, movers=60)
    A, _ = _tables(sc, "known")
    moving = [sc.obstacles[i] for i in sc.moving_indices]
    shapes = [_shape(o) for o in moving]
    reach = sc.robot_radius + 0.5
    rng = np.random.default_rng(3)
    sizes = []
    for u, _, e, T, lo, hi in _moves(rng, 25):
        cand = set(candidates(u[0], u[1], e[0], e[1], T, lo, hi, A[15]).tolist())
        sizes.append(len(cand))
        for tau in np.linspace(lo, hi, 3):
            for s in np.linspace(0.0, T, 8):
                t = tau + s
                if not 0.0 <= t <= 150.0:  # (the tables cover 0..150)
                    continue
                p = shapely.Point(*(u + s * e))
                for m, o in enumerate(moving):
                    shape = shapely.affinity.translate(shapes[m], *o.offset(t))
                    if shape.distance(p) <= reach:
                        assert m in cand, (m, tau, s)
    assert np.median(sizes) < 0.5 * len(moving)


def test_an_open_ended_or_undefined_window_keeps_every_mover_a_finite_one_finds():
    sc = _world(2)
    A, _ = _tables(sc, "known")
    rng = np.random.default_rng(9)
    for u, _, e, T, lo, hi in _moves(rng, 50):
        finite = set(candidates(u[0], u[1], e[0], e[1], T, lo, hi, A[15]).tolist())
        for top in (np.inf, np.nan):
            wide = set(candidates(u[0], u[1], e[0], e[1], T, lo, top, A[15]).tolist())
            assert finite <= wide
        early = set(candidates(u[0], u[1], e[0], e[1], T, -np.inf, hi, A[15]).tolist())
        assert finite <= early
