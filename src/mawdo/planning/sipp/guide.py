"""The safe-interval guide: earliest-arrival timed routes among moving obstacles (SIPP).

The graph is the tangent visibility graph of the static obstacles, inflated by robot radius +
clearance (+ the static guide's slack, as :class:`mawdo.planning.guide.Guide` inflates them),
with the start, the goal and any waiting spots (bays, pockets) as free vertices. Each vertex
gets its safe intervals from the moving obstacles' predicted motion over ``[t0, t0 +
horizon]``; A* over (vertex, safe interval) states gives the earliest arrival at the goal on
this graph (:mod:`mawdo.planning.sipp.search`), with waits explicit, and up to ``k - 1``
alternatives, each found with every interval state inside the routes before it barred, so that
each passes its vertices at other times (or other vertices: another homotopy class).

Guarantees and assumptions: see ``docs/planning.md`` (safe-interval guide).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mawdo.planning.geometry import inflate
from mawdo.planning.guide import GUIDE_SEGMENTS, SLACK
from mawdo.planning.scenario import Scenario
from mawdo.planning.sipp.intervals import Movers, safe_intervals
from mawdo.planning.sipp.search import search
from mawdo.planning.visgraph import VisGraph, _from_point, build

__all__ = ["SafeIntervalGuide", "TimedRoute"]


@dataclass(frozen=True)
class TimedRoute:
    """A timed route: straight moves at the robot's speed and explicit waits.

    Attributes
    ----------
    points : numpy.ndarray, shape (k, 2)
        Positions (pixels); a wait repeats a position.
    times : numpy.ndarray, shape (k,)
        Time at each position (time steps), non-decreasing.
    states : tuple of int
        The (vertex, safe interval) states passed, as interval indices of the guide.
    """

    points: np.ndarray
    times: np.ndarray
    states: tuple[int, ...]

    @property
    def arrival(self) -> float:
        """Arrival time at the goal (time steps)."""
        return float(self.times[-1])

    @property
    def waiting(self) -> float:
        """Total time spent waiting (time steps)."""
        same = np.all(self.points[1:] == self.points[:-1], axis=1)
        return float(np.sum(np.diff(self.times)[same]))


def _free_point_edges(graph: VisGraph, n_free: int):
    """The graph's edges plus every visible pair of a free point (start, goal, spot) and any
    node, tangent at the corner or not, as CSR ``(indptr, indices, weights)``.

    The tangent graph keeps every shortest path, but a timed route may reach a corner, wait
    there and then head straight for the goal or a spot; without these edges it would have to
    go on to another corner first.
    """
    g = graph
    n = len(g.nodes)
    src = [np.repeat(np.arange(n), np.diff(g.indptr))]
    dst = [g.indices]
    plain = np.zeros(n, np.bool_)  # no node is a corner: visibility alone decides
    for i in range(n_free):
        seen = _from_point(g.nodes[i], g.nodes, g.prev, g.nxt, plain, g.edges, g.ring_ptr,
                           g.ring_box, g.eps2)  # fmt: skip
        seen = seen[seen != i]
        src += [np.full(len(seen), i), seen]
        dst += [seen, np.full(len(seen), i)]
    pairs = np.unique(np.column_stack([np.concatenate(src), np.concatenate(dst)]), axis=0)
    indptr = np.zeros(n + 1, np.int64)
    np.add.at(indptr, pairs[:, 0] + 1, 1)
    w = np.hypot(*(g.nodes[pairs[:, 1]] - g.nodes[pairs[:, 0]]).T)
    return np.cumsum(indptr), np.ascontiguousarray(pairs[:, 1], dtype=np.int64), w


def _check_point(graph: VisGraph, p, name: str, scenario: Scenario) -> np.ndarray:
    p = np.asarray(p, dtype=float)
    if p.shape != (2,) or not np.all(np.isfinite(p)):
        raise ValueError(f"{name} must be a finite (x, y) pair, got {p!r}")
    x0, y0, x1, y1 = scenario.bounds
    if not (x0 <= p[0] <= x1 and y0 <= p[1] <= y1) or graph.inside(p):
        raise ValueError(
            f"{name} {tuple(p)} is outside the map or inside an inflated static obstacle; "
            "give a free point (or a smaller clearance)"
        )
    return p


class SafeIntervalGuide:
    """Safe intervals of a scenario's roadmap from one start and time, and the timed search.

    Parameters
    ----------
    scenario : Scenario
        Map, robot (radius, speed), obstacles and their motion.
    start : array_like, shape (2,), optional
        Robot position (pixels) at ``t0``; default the scenario's start.
    t0 : float
        Planning time (time steps), >= 0.
    clearance : float
        Margin (px, >= 0) added to the robot radius, for static and moving obstacles alike.
    spots : sequence of (x, y)
        Extra free vertices (pixels) where the robot may wait: bays, pockets, corners.
    horizon : float, optional
        Time steps planned ahead (> 0); default four times the static shortest route's time
        plus 100 steps. Nothing is known after ``t0 + horizon``: no route arrives later.
    walkers : {"reachable", "known"}
        Random walkers as discs (shapes) growing at their top speed from where they are at
        ``t0`` (default; conservative), or as their seeded walk (what the checker judges).

    Raises
    ------
    ValueError
        A bad argument, or a start, goal or spot outside the map or inside a static obstacle.
    """

    def __init__(
        self,
        scenario: Scenario,
        start=None,
        t0: float = 0.0,
        clearance: float = 0.5,
        spots=(),
        horizon: float | None = None,
        walkers: str = "reachable",
    ) -> None:
        if not math.isfinite(t0) or t0 < 0:
            raise ValueError(f"t0 must be finite and >= 0 time steps, got {t0!r}")
        if not math.isfinite(clearance) or clearance < 0:
            raise ValueError(f"clearance must be finite and >= 0 px, got {clearance!r}")
        self.scenario, self.t0 = scenario, float(t0)
        rho = scenario.robot_radius + clearance + SLACK
        static = [
            inflate(scenario.obstacles[i].shape, rho, n=GUIDE_SEGMENTS)
            for i in scenario.static_indices
        ]
        start = scenario.start if start is None else start
        pts = [start, scenario.goal, *spots]
        self.graph: VisGraph = build(static, scenario.bounds, points=np.reshape(pts, (-1, 2)))
        names = ["start", "goal"] + [f"spots[{j}]" for j in range(len(pts) - 2)]
        for p, name in zip(pts, names, strict=True):
            _check_point(self.graph, p, name, scenario)
        self.indptr, self.indices, self.weights = _free_point_edges(self.graph, len(pts))
        if horizon is None:
            dist, _ = self.graph.dijkstra([0], [0.0])
            reach = dist[1] if np.isfinite(dist[1]) else math.hypot(scenario.width, scenario.height)
            horizon = 4.0 * reach / scenario.robot_speed + 100.0
        if not math.isfinite(horizon) or horizon <= 0:
            raise ValueError(f"horizon must be finite and > 0 time steps, got {horizon!r}")
        self.t_end = self.t0 + float(horizon)
        self.movers = Movers.from_scenario(scenario, clearance, self.t0, self.t_end, walkers)
        self._mv = self.movers.arrays()
        self.ptr, self.lo, self.hi = safe_intervals(self.graph.nodes, self.t0, self.t_end, self._mv)

    @property
    def nodes(self) -> np.ndarray:
        """Graph vertices (pixels): start, goal, spots, then static-obstacle corners."""
        return self.graph.nodes

    def intervals(self, v: int) -> np.ndarray:
        """Safe intervals ``(lo, hi)`` of vertex ``v`` (open; time steps), shape ``(j, 2)``."""
        a, b = self.ptr[v], self.ptr[v + 1]
        return np.column_stack([self.lo[a:b], self.hi[a:b]])

    def _search(self, banned: np.ndarray):
        return search(
            self.nodes, self.indptr, self.indices, self.weights, float(self.scenario.robot_speed), 0, 1,
            self.t0, self.t_end, self.ptr, self.lo, self.hi, banned, self._mv,
        )  # fmt: skip

    def _route(self, goal_state, arrival, parent, depart) -> TimedRoute:
        chain = [int(goal_state)]
        while parent[chain[-1]] >= 0:
            chain.append(int(parent[chain[-1]]))
        chain.reverse()
        owner = np.searchsorted(self.ptr, chain, side="right") - 1
        pts, times = [self.nodes[owner[0]]], [self.t0]
        for j in range(1, len(chain)):
            if depart[chain[j]] > times[-1]:  # an explicit wait
                pts.append(pts[-1])
                times.append(float(depart[chain[j]]))
            pts.append(self.nodes[owner[j]])
            times.append(float(arrival[chain[j]]))
        return TimedRoute(np.array(pts), np.array(times), tuple(chain))

    def routes(self, k: int = 1) -> list[TimedRoute]:
        """The earliest-arrival route and up to ``k - 1`` time-diverse alternatives.

        Parameters
        ----------
        k : int
            Most routes (>= 1).

        Returns
        -------
        list of TimedRoute
            Earliest arrival first; empty when the goal cannot be reached within the horizon.

        Raises
        ------
        ValueError
            When the start is inside a mover (inflated) at ``t0``.
        """
        if isinstance(k, bool) or not isinstance(k, int | np.integer) or k < 1:
            raise ValueError(f"k must be an integer >= 1, got {k!r}")
        banned = np.zeros(len(self.lo), np.bool_)
        out: list[TimedRoute] = []
        for _ in range(int(k)):
            goal_state, arrival, parent, depart = self._search(banned)
            if goal_state == -2:
                raise ValueError(
                    f"the start is inside a moving obstacle (grown by robot radius + clearance) "
                    f"at t0 = {self.t0:g}; no timed route can leave it safely"
                )
            if goal_state < 0:
                break
            route = self._route(goal_state, arrival, parent, depart)
            out.append(route)
            banned[list(route.states[1:-1])] = True
            if len(route.states) <= 2:  # a direct move: nothing left to bar
                break
        return out
