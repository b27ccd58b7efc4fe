"""The forbidden departures kept across searches and queries change no answer.

The memo (:mod:`mawdo.planning.guide.sipp.departures`) answers a departure window from the sets
found before; the claim is that this is bit for bit what a fresh computation over the window
gives, so that a query sharing the roadmap's memo with the queries before it (the robot's
replans) returns the same earliest arrival and the same routes as a fresh query.
"""

from __future__ import annotations

import numpy as np
import pytest
from benchmarks.bench_scaling import world

from mawdo.planning.guide.sipp import SafeIntervalGuide, departures
from mawdo.planning.guide.sipp import guide as guide_module
from mawdo.planning.guide.sipp.departures import _slot, new_memo, roomier, window_forbidden
from mawdo.planning.guide.sipp.index import candidates
from mawdo.planning.guide.sipp.intervals import forbidden_among
from mawdo.planning.guide.timeguide import position_at
from tests.planning.test_sipp_index import SIZE, _tables, _world


def _span(memo, key):
    """The span ``(c0, c1)`` the memo keeps for edge ``key``, or None."""
    h = _slot(memo[0], key)
    return tuple(memo[1][h]) if memo[0][h] == key else None


def _fresh(u, e, T, lo, hi, mv):
    near = candidates(u[0], u[1], e[0], e[1], T, lo, hi, mv[15])
    return forbidden_among(u[0], u[1], e[0], e[1], T, lo, hi, mv, near)


def _asks(rng, memo, key, mv, n: int = 25, answer=window_forbidden):
    """``n`` random windows of one random move, each answered from the memo (edge ``key``)
    and afresh (pairs), and the memo after them: windows nested in, overlapping, touching and
    apart from the kept span."""
    pairs = []
    u = rng.uniform(0, SIZE, 2)
    v = u + rng.uniform(-150, 150, 2)
    T = float(np.hypot(*(v - u)) / 4.0)
    e = (v - u) / T
    for _ in range(n):
        lo = float(rng.uniform(0, 200))
        hi = lo + float(rng.choice([0.0, 2.0, 8.0, 16.0, 60.0]))
        span = _span(memo, key)
        if span is not None and rng.random() < 0.3:  # start on the kept span's bound
            lo = float(span[rng.integers(2)])
            hi = lo + 8.0
        got, _, memo = answer(memo, key, u[0], u[1], e[0], e[1], T, lo, hi, mv)
        pairs.append((got, _fresh(u, e, T, lo, hi, mv)))
    return pairs, memo


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("walkers", ["reachable", "known"])
def test_kept_windows_equal_fresh_windows_bit_for_bit(seed, walkers):
    sc = _world(seed, 40)
    mv, _ = _tables(sc, walkers, t_end=300.0)
    rng = np.random.default_rng(seed)
    memo = new_memo(4, 8)  # room for two edges and 8 intervals: it grows as it goes
    for key in range(12):  # moves, one edge each
        pairs, memo = _asks(rng, memo, 100 * key + 3, mv)
        for got, want in pairs:
            assert got.shape == want.shape and np.array_equal(got, want)
    assert memo[5][0] == 12 and memo[5][1] > 0  # every edge kept, with forbidden departures
    assert len(memo[0]) >= 32 and memo[5][2] == 0


def test_a_full_memo_answers_as_a_fresh_one_and_the_next_query_gets_an_empty_one(monkeypatch):
    sc = _world(1, 40)
    mv, _ = _tables(sc, "known", t_end=300.0)
    rng = np.random.default_rng(1)
    memo = new_memo(4, 16)  # room for two edges and 16 intervals, and not a row more
    monkeypatch.setattr(departures, "MOST_EDGES", 4)
    monkeypatch.setattr(departures, "MOST_ROWS", 16)
    # the limits are read when a kernel compiles: the memo's two steps run as Python here
    monkeypatch.setattr(departures, "_keep", departures._keep.py_func)
    answer = departures.window_forbidden.py_func
    for key in range(6):
        pairs, memo = _asks(rng, memo, key, mv, n=10, answer=answer)
        for got, want in pairs:
            assert np.array_equal(got, want)
    assert memo[5][2] == 1 and memo[5][0] <= 2 and memo[5][1] <= 16
    fresh = roomier(memo)
    assert fresh[5][0] == 0 and fresh[5][2] == 0
    assert roomier(fresh) is fresh  # room left: kept


def _replans(sc, seed: int, n: int = 6):
    """``(position, time)`` of random replans: along the route found before, on its
    alternative, or back at the start, at random later times."""
    rng = np.random.default_rng(seed)
    pos, t = np.asarray(sc.start, float), 0.0
    for _ in range(n):
        routes = yield pos, t
        t += float(rng.uniform(1.0, 40.0))
        pick = int(rng.integers(3))
        pos = position_at(routes[pick], t) if pick < len(routes) else np.asarray(sc.start, float)


@pytest.mark.parametrize("seed", range(4))
def test_replans_sharing_the_memo_find_what_fresh_queries_find(seed):
    sc = world(400.0, 60, 8, seed=seed)
    plan = _replans(sc, seed)
    pos, t = next(plan)
    kept = []
    while True:
        shared = SafeIntervalGuide(sc, start=pos, t0=t)
        kept.append(shared._memo[5][0])  # edges kept when the query starts
        fresh = SafeIntervalGuide(sc, start=pos, t0=t, keep_departures=False)
        got, want = shared.routes(3), fresh.routes(3)
        assert len(got) == len(want)
        for a, b in zip(got, want, strict=True):
            assert a.arrival == b.arrival
            assert a.states == b.states
            assert np.array_equal(a.times, b.times) and np.array_equal(a.points, b.points)
        try:
            pos, t = plan.send(got)
        except StopIteration:
            break
    # the roadmap's first query keeps nothing, the second fills the memo, the rest carry it on
    assert kept[:2] == [0, 0] and kept[2] > 0 and kept == sorted(kept)


def test_only_queries_of_the_same_motion_share_a_memo():
    sc = world(300.0, 20, 4, seed=0)
    first = SafeIntervalGuide(sc, t0=0.0)
    assert first._kept == 0  # a roadmap's first query: it may be its only one
    a = SafeIntervalGuide(sc, t0=0.0)
    a.routes(2)
    b = SafeIntervalGuide(sc, t0=3.0, start=a.nodes[a.start])
    assert b._memo is a._memo and b._kept > 0 and a._memo[5][0] > 0  # carried on
    cut = SafeIntervalGuide(sc, t0=0.0, lookahead=30.0)
    assert cut._kept == 0 and cut._memo is not a._memo  # a lookahead cuts: its own, if any
    walk = _world(0, 40)  # random walkers, taken as reachable sets growing from t0
    for _ in range(2):
        c = SafeIntervalGuide(walk, t0=0.0)
        assert c._shares is None and c._kept == 0  # 40 movers: no memo of its own either
    known = SafeIntervalGuide(walk, t0=0.0, walkers="known")  # the seeded walks themselves
    assert known._shares is not None and known._shares != a._shares  # a memo of its own kind
    assert SafeIntervalGuide(sc, t0=0.0, keep_departures=False)._kept == 0


def test_movers_knots_made_again_drop_the_kept_departures():
    # a query far beyond the knots' window makes them again, the piece that ended at the old
    # window's end with its velocity rounded anew: what was kept is dropped, not reused
    sc = world(300.0, 20, 4, seed=2)
    for t0 in (0.0, 1.0):
        SafeIntervalGuide(sc, t0=t0).routes(2)
    early = SafeIntervalGuide(sc, t0=2.0)
    assert early._memo[5][0] > 0
    late = SafeIntervalGuide(sc, t0=5000.0)
    assert late._memo is not early._memo and late._memo[5][0] == 0
    early.routes(2)  # its search, on the old tables, keeps nothing in the roadmap
    assert late.roadmap.departures(late._shares)[5][0] == 0
    got = late.routes(2)
    want = SafeIntervalGuide(sc, t0=5000.0, keep_departures=False).routes(2)
    assert [r.arrival for r in got] == [r.arrival for r in want]


def test_a_query_among_many_movers_keeps_its_own_for_its_alternatives(monkeypatch):
    monkeypatch.setattr(guide_module, "MEMO_MOVERS", 20)
    sc = world(300.0, 20, 4, seed=1)
    cut = SafeIntervalGuide(sc, t0=0.0, lookahead=120.0)
    got = cut.routes(3)
    assert cut._kept > 0 and cut._memo[5][0] > 0
    monkeypatch.setattr(guide_module, "MEMO_MOVERS", 21)
    fresh = SafeIntervalGuide(sc, t0=0.0, lookahead=120.0)
    assert fresh._kept == 0
    want = fresh.routes(3)
    assert [r.states for r in got] == [r.states for r in want]
    assert [r.arrival for r in got] == [r.arrival for r in want]
