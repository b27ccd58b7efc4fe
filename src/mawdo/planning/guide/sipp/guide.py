"""The safe-interval guide: earliest-arrival timed routes among moving obstacles (SIPP).

The roadmap (:mod:`mawdo.planning.guide.sipp.roadmap`, built once per map) gets the query's start as
one more free vertex. Each vertex gets its safe intervals from the moving obstacles' predicted
motion over ``[t0, t0 + horizon]``; A* over (vertex, safe interval) states gives the earliest
arrival at the goal on this graph (:mod:`mawdo.planning.guide.sipp.search`), with waits explicit,
and up to ``k - 1`` alternatives, each found with every interval state inside the routes before it
barred, so that each passes its vertices at other times (or other vertices: another homotopy
class).

Guarantees and assumptions: see ``docs/planning.md`` (safe-interval guide).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mawdo.planning.guide.homotopy import GUIDE_SEGMENTS
from mawdo.planning.guide.sipp.departures import empty_memo, new_memo
from mawdo.planning.guide.sipp.lazy import new_table, touch
from mawdo.planning.guide.sipp.profile import profile_table
from mawdo.planning.guide.sipp.profiled import lead_clear, profile_points, profiled_search
from mawdo.planning.guide.sipp.roadmap import Roadmap
from mawdo.planning.guide.sipp.search import timed_search
from mawdo.planning.world.scenario import Scenario

__all__ = ["MEMO_MOVERS", "SafeIntervalGuide", "TimedRoute"]

#: Movers from which a query keeps its own forbidden departures for its alternatives (a memo
#: of one query costs about a tenth more search at 200 movers and saves a third at 1000).
MEMO_MOVERS = 500


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
    checked_until : float
        Time (time steps) up to which the route was checked against the movers' predicted
        motion: the query's ``t0 + lookahead`` (``inf``: to its end).
    """

    points: np.ndarray
    times: np.ndarray
    states: tuple[int, ...]
    checked_until: float = math.inf

    @property
    def arrival(self) -> float:
        """Arrival time at the goal (time steps)."""
        return float(self.times[-1])

    @property
    def waiting(self) -> float:
        """Total time spent waiting (time steps)."""
        same = np.all(self.points[1:] == self.points[:-1], axis=1)
        return float(np.sum(np.diff(self.times)[same]))


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
        Time steps planned ahead (> 0); default twice the static shortest route's time plus
        60 steps. Nothing is known after ``t0 + horizon``: no route arrives later.
    walkers : {"reachable", "known"}
        Random walkers as discs (shapes) growing at their top speed from where they are at
        ``t0`` (default; conservative), or as their seeded walk (what the checker judges).
    segments : int
        Sides (>= 3) of the polygons standing in for the inflated obstacles' rounded corners
        (:class:`~mawdo.planning.guide.sipp.roadmap.Roadmap`); more is closer to exact, slower.
    profile : tuple, optional
        ``(accel, turn)``: acceleration (px per step squared) and turn rate (radians per
        step), ``inf`` for a free one: every edge is driven from rest to rest in whole steps
        and the robot turns in place at its vertices
        (:func:`~mawdo.planning.guide.sipp.search.search_limited`); ``t0`` must then be a
        whole step.
        None (default): straight moves at full speed, instant starts, stops and turns.
    lead : array_like, shape (j, 2), optional
        With ``profile``: the robot's positions at ``t0, t0 + 1, ...`` before it comes to
        rest (braking from its velocity at ``t0``); the search starts at the last one,
        ``j - 1`` steps after ``t0``, heading as the last move. Each step is checked like an
        edge; ``start`` is then ignored.
    lookahead : float, optional
        Time steps (> 0) over which the movers' predicted motion is trusted: the movers of
        known motion are tested until ``t0 + lookahead`` and not after (the routes beyond it
        are timed on the static map; random walkers taken as reachable sets grow without
        end as before). None (default): the whole horizon. A route is then collision-free
        (under the predictions) only until ``t0 + lookahead``
        (:attr:`checked_until`); the run asks again well before then.
    keep_departures : bool
        Keep the forbidden departures the searches find and answer later searches from them
        (:mod:`~mawdo.planning.guide.sipp.departures`; the same routes, found faster): through
        the roadmap from query to query where every query slices the same motion (no
        ``lookahead``, no random walker taken as a reachable set) and the roadmap served a
        query before, else among :data:`MEMO_MOVERS` movers or more for this query's
        alternatives. False: every departure found afresh (for comparisons).

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
        segments: int = GUIDE_SEGMENTS,
        profile=None,
        lead=None,
        lookahead: float | None = None,
        keep_departures: bool = True,
    ) -> None:
        if not math.isfinite(t0) or t0 < 0:
            raise ValueError(f"t0 must be finite and >= 0 time steps, got {t0!r}")
        self.scenario, self.t0 = scenario, float(t0)
        self.roadmap = Roadmap.of(scenario, clearance, spots, segments)
        start = scenario.start if start is None else start
        self.profile, self.lead = profile, None
        if profile is not None:
            self.lead = np.reshape(np.asarray(start if lead is None else lead, float), (-1, 2))
            start = self.lead[-1]
        self.nodes, self.indptr, self.indices, self.weights, self.to_goal = self.roadmap.with_start(
            start
        )
        self.start = len(self.nodes) - 1
        if horizon is None:
            reach = self.to_goal[self.start]
            if not np.isfinite(reach):
                reach = math.hypot(scenario.width, scenario.height)
            horizon = 2.0 * reach / scenario.robot_speed + 60.0
        if not math.isfinite(horizon) or horizon <= 0:
            raise ValueError(f"horizon must be finite and > 0 time steps, got {horizon!r}")
        self.t_end = self.t0 + float(horizon)
        if lookahead is not None and not lookahead > 0:
            raise ValueError(f"lookahead must be > 0 time steps or None, got {lookahead!r}")
        self.checked_until = self.t_end if lookahead is None else min(self.t_end, t0 + lookahead)
        cut = self.checked_until < self.t_end  # a lookahead: no mover is tested after it
        self.walkers = walkers
        self.movers = self.roadmap.movers(self.t0, self.checked_until, walkers, cut)
        self._mv = self.movers.arrays()
        self._keeping(keep_departures, cut, walkers)
        # safe intervals made as the searches touch the vertices; the query's searches share
        # them, so that a state keeps its number from one search to the next
        self.safe = new_table(len(self.nodes), self.t0, self.t_end)
        self._v = float(scenario.robot_speed)
        if profile is not None:
            accel, turn = (float(x) for x in profile)
            self._lim = (self._v, bool(accel < math.inf), turn)
            self._table = profile_table(self.weights, self._v, accel)

    def _keeping(self, keep: bool, cut: bool, walkers: str) -> None:
        """Where the searches keep the forbidden departures they find (departures module):
        the roadmap's memo, carried from query to query, where every query slices the same
        motion (no lookahead cut, no reachable sets) and the roadmap has served a query
        before (a roadmap made for one query, as a crowd's per prediction, never repays the
        filling); else this query's own among :data:`MEMO_MOVERS` movers or more (its
        time-diverse alternatives reuse the first search's); else none."""
        keep = keep and self.profile is None  # (profiled moves are not one straight piece)
        roadmap, many = self.roadmap, len(self.movers.kind) >= MEMO_MOVERS
        same = keep and not cut and not np.any(self.movers.kind == 1)
        self._shares, kept = None, keep and many
        if same and (roadmap.queries > 0 or many):
            self._shares, kept = (float(self.scenario.robot_speed), walkers), True
            self._memo = roadmap.departures(self._shares)
        else:
            self._memo = empty_memo(len(roadmap.weights)) if kept else new_memo(2, 2)
        roadmap.queries += 1
        self._made = roadmap.knots_made  # (the tables' knots: a memo kept later must match)
        self._kept = len(roadmap.weights) if kept else 0  # (never the start's edges)

    @property
    def graph(self):
        """The static tangent visibility graph
        (:class:`~mawdo.planning.guide.visgraph.VisGraph`)."""
        return self.roadmap.graph

    def intervals(self, v: int) -> np.ndarray:
        """Safe intervals ``(lo, hi)`` of vertex ``v`` (open; time steps), shape ``(j, 2)``."""
        self.safe = touch(self.safe, int(v), self.nodes, self._mv)
        first, count, lo, hi = self.safe[2], self.safe[3], self.safe[4], self.safe[5]
        a, b = first[v], first[v] + count[v]
        return np.column_stack([lo[a:b], hi[a:b]])

    def explain(self) -> str:
        """Why :meth:`routes` finds no route, in one sentence: the first cause that holds, in
        the order :mod:`~mawdo.planning.guide.sipp.explain` lists them (goal cut off, horizon
        too short, braking lead blocked, start inside a mover, goal covered by named movers,
        every way barred); runs the search once
        (:func:`~mawdo.planning.guide.sipp.explain.why_no_route`)."""
        from mawdo.planning.guide.sipp.explain import why_no_route

        return why_no_route(self)

    def _search(self, banned: np.ndarray):
        if self.profile is not None:
            return profiled_search(self, banned)
        graph, v = (self.nodes, self.indptr, self.indices, self.weights, self.to_goal), self._v
        res = timed_search(
            graph, self.roadmap.straight_moves(graph, v), (v, False, math.inf, None),
            self.start, 0, self.t0, np.zeros(2), self.t_end, self.safe, banned, self._mv,
            self._memo, self._kept,
        )  # fmt: skip
        self._memo, self.safe = res[4], res[5]  # (both grow as they fill)
        if self._shares is not None:
            self.roadmap.keep_departures(self._shares, self._memo, self._made)
        return res[:4]

    def _route(self, goal_state, arrival, parent, depart) -> TimedRoute:
        """The route ending in ``goal_state``: the lead (without a profile: the start), then
        per edge its wait (rests and turns included), its profile's inner piece boundaries
        (:func:`~mawdo.planning.guide.sipp.profiled.profile_points`, at whole steps) and its
        end."""
        chain = [int(goal_state)]
        while parent[chain[-1]] >= 0:
            chain.append(int(parent[chain[-1]]))
        chain.reverse()
        owner = self.safe[6][chain]  # each state's vertex
        lead = self.nodes[owner[:1]] if self.profile is None else self.lead
        pts, times = list(lead), [self.t0 + i for i in range(len(lead))]
        for j in range(1, len(chain)):
            u, v = int(owner[j - 1]), int(owner[j])
            tau = float(depart[chain[j]])
            if tau > times[-1]:  # an explicit wait (a rest, a turn in place)
                pts.append(self.nodes[u])
                times.append(tau)
            if self.profile is not None:
                inner, at = profile_points(self, u, v, tau)
                pts, times = pts + inner, times + at
            pts.append(self.nodes[v])
            times.append(float(arrival[chain[j]]))
        until = self.checked_until if self.checked_until < self.t_end else math.inf
        pts, times = np.array(pts, dtype=float), np.array(times, dtype=float)
        return TimedRoute(pts, times, tuple(chain), until)

    def routes(self, k: int = 1) -> list[TimedRoute]:
        """The earliest-arrival route and up to ``k - 1`` time-diverse alternatives.

        Parameters
        ----------
        k : int
            Most routes (>= 1).

        Returns
        -------
        list of TimedRoute
            Earliest arrival first; empty when the goal cannot be reached within the horizon
            (:meth:`explain` says why).

        Raises
        ------
        ValueError
            When the start is inside a mover (inflated) at ``t0``.
        """
        if isinstance(k, bool) or not isinstance(k, int | np.integer) or k < 1:
            raise ValueError(f"k must be an integer >= 1, got {k!r}")
        banned = np.zeros(0, np.bool_)
        out: list[TimedRoute] = []
        if self.profile is not None and not lead_clear(self):
            return out
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
            # (the states made since the last search: not barred)
            banned = np.concatenate([banned, np.zeros(self.safe[7] - len(banned), np.bool_)])
            banned[list(route.states[1:-1])] = True
            if len(route.states) <= 2:  # a direct move: nothing left to bar
                break
        return out
