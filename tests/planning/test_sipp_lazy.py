"""The safe-interval search settles each move's exact departure lazily (when its lower bound
comes off the heap) and the moves to the goal first, and makes each vertex's safe intervals
when it first touches the vertex: its routes are those of the eager search (each move settled
when its source is expanded, over the safe intervals of every vertex made beforehand: the
search before these changes), ported here line by line, bit for bit (goal state, and arrival,
parent and departure along the route, each state by its number in the eager table), with and
without acceleration and turn limits, for the earliest route and its alternatives."""

from __future__ import annotations

import heapq
import math

import numpy as np
import pytest

from mawdo.planning.guide.sipp import SafeIntervalGuide
from mawdo.planning.guide.sipp.departures import empty_memo, new_memo
from mawdo.planning.guide.sipp.intervals import safe_intervals
from mawdo.planning.guide.sipp.lazy import new_table
from mawdo.planning.guide.sipp.moves import profiled_moves, straight_moves
from mawdo.planning.guide.sipp.profile import profile_table, rest_steps
from mawdo.planning.guide.sipp.search import _depart, search_limited, start_state, timed_search
from tests.planning.test_sipp_index import _world


def _eager(graph, moves, kin, start, goal, t_start, h0, t_end, ptr, lo, hi, banned, mv):
    """The eager search: every move from a state settled when the state is expanded."""
    nodes, indptr, indices, weights, to_goal = graph
    S = len(lo)
    owner = np.repeat(np.arange(len(ptr) - 1), np.diff(ptr))
    arrival, parent, depart = np.full(S, np.inf), np.full(S, -1), np.full(S, np.nan)
    heading, closed = np.zeros((S, 2)), np.zeros(S, bool)
    s0 = start_state(ptr[start], ptr[start + 1], lo, hi, t_start, nodes[start], mv)
    if s0 < 0:
        return -2, arrival, parent, depart
    arrival[s0], heading[s0] = t_start, h0
    heap, bound, edge = [(t_start + to_goal[start] / kin[0], t_start, s0)], math.inf, moves[1]
    while heap:
        _, a, sid = heapq.heappop(heap)
        if closed[sid]:
            continue
        closed[sid] = True
        u = owner[sid]
        if u == goal:
            return sid, arrival, parent, depart
        for e in range(indptr[u], indptr[u + 1]):
            v, T = indices[e], edge[e, 0]
            if not to_goal[v] < math.inf:
                continue
            ready = a + rest_steps(*heading[sid], edge[e, 1], edge[e, 2], kin[1], kin[2])
            top, hv = min(hi[sid], t_end - T), to_goal[v] / kin[0]
            if top < ready:
                continue
            for J in range(ptr[v], ptr[v + 1]):
                if hi[J] <= ready + T or closed[J] or banned[J]:
                    continue
                if lo[J] >= top + T:
                    break
                x = max(ready, lo[J] - T)
                x = float(math.ceil(x)) if kin[3] else x
                if x + T >= arrival[J] or x + T + hv > bound:
                    continue
                # (no memo: every departure found afresh, window by window)
                tau = _depart(moves, e, nodes[u, 0], nodes[u, 1], a, T, x, top, hi[J], kin[3], mv,
                              new_memo(2, 2), -1)[0]  # fmt: skip
                if not tau + T < arrival[J]:
                    continue
                arrival[J], parent[J], depart[J] = tau + T, sid, tau
                heading[J] = edge[e, 1:3] if weights[e] > 0.0 else heading[sid]
                heapq.heappush(heap, (tau + T + hv, tau + T, J))
                if v == goal:
                    bound = min(bound, tau + T)
    return -1, arrival, parent, depart


def _chain(res, number=None) -> np.ndarray:
    """The route's states from the goal back, with their arrivals and departures (rows); each
    state as ``number`` numbers it (the eager table's numbers of the lazy table's states)."""
    goal, arrival, parent, depart = res[:4]
    out = [int(goal)]
    while goal >= 0 and parent[out[-1]] >= 0:
        out.append(int(parent[out[-1]]))
    if goal < 0:
        return np.array([[goal, np.nan, np.nan]])
    return np.array([[s if number is None else number[s], arrival[s], depart[s]] for s in out])


def _eager_numbers(table, ptr) -> np.ndarray:
    """Per row of a lazy table, its state's number in the eager table (CSR ``ptr``)."""
    first, owner, used = table[2], table[6], table[7]
    rows = np.arange(used)
    return ptr[owner[:used]] + rows - first[owner[:used]]


def _same(a, b) -> bool:
    return a.shape == b.shape and np.array_equal(a, b, equal_nan=True)


@pytest.mark.parametrize("limits", [None, (1.0, 0.6)])
@pytest.mark.parametrize("seed", range(4))
def test_lazy_search_finds_the_eager_searchs_routes_bit_for_bit(seed, limits):
    sc = _world(seed, movers=25)
    rng = np.random.default_rng(seed)
    spots = rng.uniform(20, 280, (12, 2))
    g = SafeIntervalGuide(sc, t0=float(seed), clearance=0.5, spots=spots, walkers="known")
    graph = (g.nodes, g.indptr, g.indices, g.weights, g.to_goal)
    v = float(sc.robot_speed)
    if limits is None:
        moves = straight_moves(g.nodes, g.indptr, g.indices, g.weights, v)
        kin = (v, False, math.inf, None)
    else:
        moves = profiled_moves(g.nodes, g.indptr, g.indices, g.weights,
                               profile_table(g.weights, v, limits[0]))  # fmt: skip
        kin = (v, True, limits[1], True)
    ptr, lo, hi = safe_intervals(g.nodes, g.t0, g.t_end, g._mv)
    args = (g.start, 0, g.t0, np.zeros(2), g.t_end)
    eager_args = (*args, ptr, lo, hi)
    table = new_table(len(g.nodes), g.t0, g.t_end)
    banned, eager_banned = np.zeros(0, np.bool_), np.zeros(len(lo), np.bool_)
    found = 0
    memo = empty_memo()  # the searches of one query share their forbidden departures
    for _ in range(3):  # the earliest route, then alternatives with its states barred
        res = timed_search(graph, moves, kin, *args, table, banned, g._mv, memo, len(g.weights))
        memo, table = res[4], res[5]
        number = _eager_numbers(table, ptr)
        # the lazy table's intervals are the eager table's
        assert np.array_equal(table[4][: table[7]], lo[number])
        assert np.array_equal(table[5][: table[7]], hi[number])
        eager = _eager(graph, moves, kin, *eager_args, eager_banned, g._mv)
        assert _same(_chain(res, number), _chain(eager))
        if res[0] < 0:
            break
        found += 1
        route = _chain(res)[1:-1, 0].astype(int)
        banned = np.concatenate([banned, np.zeros(table[7] - len(banned), np.bool_)])
        banned[route], eager_banned[number[route]] = True, True
    assert found >= 1
    assert table[7] <= len(lo)  # (never more rows than the eager table)
    if limits is not None:  # search_limited is this search under the limits
        profile = profile_table(g.weights, v, limits[0])
        res = search_limited(graph, profile, kin[:3], *args, table, banned, g._mv)
        number = _eager_numbers(res[4], ptr)
        eager = _eager(graph, moves, kin, *eager_args, eager_banned, g._mv)
        assert _same(_chain(res, number), _chain(eager))


def test_a_query_makes_the_safe_intervals_of_the_vertices_it_touches_only():
    # a wall hides twenty squares from the start and the goal: the search ends before it
    # reaches a vertex among them, and never makes their intervals
    from mawdo.planning import scenario_from_dict

    squares = [
        {"shape": "polygon", "vertices": [[x, y], [x + 8, y], [x + 8, y + 8], [x, y + 8]]}
        for x in (250.0, 300.0, 350.0, 400.0) for y in (40.0, 120.0, 200.0, 280.0, 360.0)
    ]  # fmt: skip
    wall = {"shape": "polygon", "vertices": [[200, 0], [210, 0], [210, 340], [200, 340]]}
    mover = {"shape": "circle", "center": [60.0, 100.0], "radius": 6.0,
             "motion": {"velocity": [0.0, -4.0]}}  # fmt: skip
    sc = scenario_from_dict({"schema_version": 1, "width": 450.0, "height": 400.0,
                             "start": [20.0, 60.0], "goal": [120.0, 60.0],
                             "obstacles": [wall, mover, *squares]})  # fmt: skip
    g = SafeIntervalGuide(sc, clearance=0.5)
    route = g.routes(1)[0]
    made = np.flatnonzero(g.safe[2] >= 0)
    assert len(made) < 10 < 4 * len(squares) <= len(g.nodes)
    ptr, lo, hi = safe_intervals(g.nodes, g.t0, g.t_end, g._mv)
    number = _eager_numbers(g.safe, ptr)
    assert np.array_equal(g.safe[4][: g.safe[7]], lo[number])
    assert route.times[-1] > 100.0 / float(sc.robot_speed)  # (the mover made it wait)
