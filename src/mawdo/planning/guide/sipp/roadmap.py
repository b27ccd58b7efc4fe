"""The safe-interval guide's roadmap: what depends on the map only, built once per scenario.

The static obstacles, inflated by robot radius + clearance (+ the static guide's slack, with
its polygon for round corners, as :class:`mawdo.planning.guide.homotopy.Guide` inflates them), give
the tangent visibility graph (:mod:`mawdo.planning.guide.visgraph`) with the goal and the waiting
spots as free vertices. A free point (goal, spot, and each query's start) is joined to *every*
vertex it sees, tangent at the corner or not: the tangent graph keeps every shortest path, but a
timed route may reach a corner, wait, and then head straight for the goal or a spot. The static
distance to the goal over this graph is the search's heuristic (admissible and consistent: no
timed route is shorter than the static one on the same graph). The moving obstacles' pieces are
cached over a growing window, so each query only slices them.
"""

from __future__ import annotations

import math
import weakref

import numpy as np
import shapely

from mawdo.planning.guide.homotopy import GUIDE_SEGMENTS, SLACK
from mawdo.planning.guide.sipp.intervals import Movers
from mawdo.planning.guide.visgraph import VisGraph, build, csr_dijkstra, visible_from_point
from mawdo.planning.world.geometry import FlatObstacles, centre_box, inflate
from mawdo.planning.world.scenario import Scenario
from mawdo.util.weak import WeakAttribute

__all__ = ["Roadmap", "usable_spots"]

_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _free_point(p, name: str, graph: VisGraph, scenario: Scenario) -> np.ndarray:
    p = np.asarray(p, dtype=float)
    if p.shape != (2,) or not np.all(np.isfinite(p)):
        raise ValueError(f"{name} must be a finite (x, y) pair, got {p!r}")
    x0, y0, x1, y1 = graph.bounds
    if not (x0 <= p[0] <= x1 and y0 <= p[1] <= y1) or graph.inside(p):
        raise ValueError(
            f"{name} {tuple(p)} is outside the map (shrunk by robot radius + clearance) or "
            "inside an inflated static obstacle; give a free point (or a smaller clearance)"
        )
    return p


def usable_spots(
    scenario: Scenario, clearance: float, spots, segments: int = GUIDE_SEGMENTS
) -> np.ndarray:
    """The spots (pixels, ``(k, 2)``) the roadmap at ``clearance`` can take: inside the map
    shrunk by ``rho`` and outside every static obstacle inflated by ``rho`` (as the roadmap
    inflates them; ``rho`` = robot radius + clearance + the guide's slack). A spot valid for the
    bare robot (:class:`~mawdo.planning.world.scenario.Scenario` checks that) may be too close to a
    wall for a larger margin; it is dropped rather than failing the whole guide."""
    pts = np.reshape(np.asarray(spots, dtype=float), (-1, 2))
    rho = scenario.robot_radius + clearance + SLACK
    x0, y0, x1, y1 = centre_box(scenario, rho)
    keep = (pts[:, 0] > x0) & (pts[:, 0] < x1) & (pts[:, 1] > y0) & (pts[:, 1] < y1)
    statics = [
        inflate(scenario.obstacles[i].shape, rho, n=segments) for i in scenario.static_indices
    ]
    if statics and keep.any():
        keep &= ~shapely.intersects(shapely.union_all(statics), shapely.points(pts))
    return pts[keep]


def _unique_pairs(src: np.ndarray, dst: np.ndarray, n: int) -> np.ndarray:
    """The distinct pairs ``(src, dst)`` (indices below ``n``), sorted by ``src``, then ``dst``:
    ``np.unique(np.column_stack([src, dst]), axis=0)``, as one int64 key per pair, sorted and
    its repeats dropped (the rows' sort of ``axis=0`` took 4.5 s of a 6.4 s roadmap at
    1000 x 1000 px, and NumPy's hashing ``np.unique`` of the keys 6 s of the 2.5 million pairs
    a map with 1200 spots has; a sort takes 0.2 s)."""
    key = np.sort(src.astype(np.int64) * n + dst.astype(np.int64))
    key = key[np.concatenate(([True], key[1:] != key[:-1]))] if len(key) else key
    return np.column_stack([key // n, key % n])


def _csr(pairs: np.ndarray, nodes: np.ndarray):
    """Directed pairs (sorted, unique) as CSR ``(indptr, indices, weights)``."""
    indptr = np.zeros(len(nodes) + 1, np.int64)
    np.add.at(indptr, pairs[:, 0] + 1, 1)
    w = np.hypot(*(nodes[pairs[:, 1]] - nodes[pairs[:, 0]]).T)
    return np.cumsum(indptr), np.ascontiguousarray(pairs[:, 1], dtype=np.int64), w


class Roadmap:
    """Map-only part of the safe-interval guide (see the module docstring).

    Parameters
    ----------
    scenario : Scenario
    clearance : float
        Margin (px, >= 0) added to the robot radius, for static and moving obstacles alike.
    spots : sequence of (x, y)
        Free vertices (pixels) where the robot may wait: bays, pockets.
    segments : int
        Sides (>= 3) of the polygon standing in for a disc in the inflation: the rounded
        corners are replaced by circumscribing ones, lengthening routes by up to
        ``rho (1 / cos(pi / segments) - 1)`` px per corner (``rho``: radius + clearance).

    Attributes
    ----------
    nodes : numpy.ndarray, shape (n, 2)
        Goal (index 0), spots, then static-obstacle corners (pixels).
    to_goal : numpy.ndarray, shape (n,)
        Static distance to the goal over the graph (pixels; ``inf`` if cut off).
    """

    # held weakly: the per-scenario cache must not keep its scenario alive
    scenario = WeakAttribute()

    def __init__(
        self, scenario: Scenario, clearance: float = 0.5, spots=(), segments: int = GUIDE_SEGMENTS
    ) -> None:
        if not math.isfinite(clearance) or clearance < 0:
            raise ValueError(f"clearance must be finite and >= 0 px, got {clearance!r}")
        if isinstance(segments, bool) or not isinstance(segments, int) or segments < 3:
            raise ValueError(f"segments must be an integer >= 3, got {segments!r}")
        self.scenario, self.clearance = scenario, float(clearance)
        rho = scenario.robot_radius + clearance + SLACK
        static = [
            inflate(scenario.obstacles[i].shape, rho, n=segments) for i in scenario.static_indices
        ]
        self._static, self._box = static, centre_box(scenario, rho)
        pts = np.reshape(np.asarray([scenario.goal, *spots], dtype=float), (-1, 2))
        # the map's border is a wall (as in the checker): the centre keeps rho from it
        self.graph = build(static, centre_box(scenario, rho), points=pts)
        names = ["goal"] + [f"spots[{j}]" for j in range(len(pts) - 1)]
        for p, name in zip(pts, names, strict=True):
            _free_point(p, name, self.graph, scenario)
        self.nodes = self.graph.nodes
        g = self.graph
        src = [np.repeat(np.arange(len(g.nodes)), np.diff(g.indptr))]
        dst = [g.indices]
        for i in range(len(pts)):
            seen = self.sees(g.nodes[i])
            seen = seen[seen != i]
            src += [np.full(len(seen), i), seen]
            dst += [seen, np.full(len(seen), i)]
        pairs = _unique_pairs(np.concatenate(src), np.concatenate(dst), len(g.nodes))
        self.indptr, self.indices, self.weights = _csr(pairs, self.nodes)
        self.to_goal = csr_dijkstra(
            self.indptr, self.indices, self.weights, np.zeros(1, np.int64), np.zeros(1)
        )[0]
        moving = tuple(scenario.obstacles[i] for i in scenario.moving_indices)
        self.flat = FlatObstacles.from_obstacles(moving, scenario.robot_radius + clearance)
        self._moving = moving
        self._knots: dict[int, tuple[float, np.ndarray, np.ndarray]] = {}
        self._moves: dict[float, tuple] = {}  # straight_moves per speed (and room for a start)
        self._departures: dict[tuple, object] = {}  # forbidden departures per speed and walkers
        self.queries = 0  # safe-interval queries made on this roadmap so far
        self.knots_made = 0  # times a mover's knots were made again over a longer window
        # pieces over a window that holds a usual query (twice the default horizon of a
        # route across the map), so that queries only slice them
        diag = math.hypot(scenario.width, scenario.height)
        reach = 2.0 * (2.0 * diag / scenario.robot_speed + 60.0)
        for m in range(len(moving)):
            self._pieces(m, 0.0, reach)

    @classmethod
    def of(
        cls, scenario: Scenario, clearance: float = 0.5, spots=(), segments: int = GUIDE_SEGMENTS
    ) -> Roadmap:
        """The roadmap of ``(scenario, clearance, spots, segments)``, built at the first call,
        then kept as long as the scenario lives."""
        spots_key = tuple(map(tuple, np.reshape(np.asarray(spots, float), (-1, 2))))
        key = (float(clearance), spots_key, segments)
        per = _CACHE.setdefault(scenario, {})
        if key not in per:
            per[key] = cls(scenario, clearance, spots, segments)
        return per[key]

    def sees(self, p) -> np.ndarray:
        """Indices of the nodes a free point ``p`` sees (tangent at the corner or not)."""
        g = self.graph
        plain = np.zeros(len(g.nodes), np.bool_)  # no corner rule: visibility alone decides
        p = np.ascontiguousarray(p, dtype=float)
        return visible_from_point(
            p, g.nodes, g.prev, g.nxt, plain, g.edges, g.ring_ptr, g.ring_box, g.eps2
        )

    def with_start(self, start) -> tuple:
        """The graph with ``start`` appended as the last node, joined to every node it sees
        by edges *out* of it (nothing leads back to it: a route that returns to its start to
        wait there could have waited there first): ``(nodes, indptr, indices, weights,
        to_goal)``; the start's heuristic is its shortest static distance to the goal."""
        start = _free_point(start, "start", self.graph, self.scenario)
        seen = self.sees(start)
        nodes = np.vstack([self.nodes, start])
        w = np.hypot(*(self.nodes[seen] - start).T)
        indptr = np.append(self.indptr, self.indptr[-1] + len(seen))
        indices = np.concatenate([self.indices, seen])
        weights = np.concatenate([self.weights, w])
        to_goal = np.append(self.to_goal, np.min(w + self.to_goal[seen]) if len(seen) else np.inf)
        return nodes, indptr, indices, weights, to_goal

    def segment_clear(self, a, b) -> bool:
        """The straight move ``a -> b`` (pixels) stays in the map shrunk by robot radius +
        clearance + slack and meets no static obstacle inflated by as much (touching is a
        hit), as the roadmap's edges do."""
        x0, y0, x1, y1 = self._box
        for p in (a, b):
            if not (x0 <= p[0] <= x1 and y0 <= p[1] <= y1):
                return False
        if not self._static:
            return True
        if not hasattr(self, "_union"):  # built at the first use: runs without limits never ask
            self._union = shapely.union_all(self._static)
        line = shapely.LineString([a, b]) if np.any(a != b) else shapely.Point(a)
        return not shapely.intersects(self._union, line)

    def _pieces(self, m: int, t0: float, t_end: float):
        """Knots of moving obstacle ``m`` covering ``[t0, t_end]`` (from a cached window)."""
        cap, t, off = self._knots.get(m, (-1.0, None, None))
        if cap < t_end:
            cap = max(2.0 * t_end, cap)
            t, off = self._moving[m].knots(0.0, cap)
            self._knots[m] = (cap, t, off)
            # the piece that ended at the old cap runs on now, its velocity rounded anew: the
            # forbidden departures kept so far were found on the old one
            self._departures.clear()
            self.knots_made += 1
        i0 = max(int(np.searchsorted(t, t0, side="right")) - 1, 0)
        i1 = int(np.searchsorted(t, t_end, side="left"))
        return t[i0 : i1 + 1], off[i0 : i1 + 1]

    def straight_moves(self, graph, speed: float) -> tuple:
        """:func:`~mawdo.planning.guide.sipp.moves.straight_moves` of ``graph`` (a
        :meth:`with_start` of this roadmap) at ``speed`` (px per step): the roadmap's own
        edges' rows are made once per speed and kept, the start's written at each call (into
        room kept after them). The rows are views of the kept tables, valid until the next
        call: hand them to one search, then drop them."""
        from mawdo.planning.guide.sipp.moves import straight_rows

        nodes, indptr, indices, weights, _ = graph
        E, n = len(self.weights), len(self.nodes)
        kept = self._moves.get(float(speed))
        if kept is None:
            edge, piece = np.zeros((E + n, 3)), np.zeros((E + n, 8))
            straight_rows(edge, piece, self.nodes, self.indptr, self.indices, self.weights,
                          float(speed), 0)  # fmt: skip
            kept = self._moves[float(speed)] = (np.arange(E + n + 1), edge, piece)
        eptr, edge, piece = kept
        top = len(weights)
        straight_rows(edge, piece, nodes, indptr, indices, weights, float(speed), n)
        return eptr[: top + 1], edge[:top], piece[:top]

    def departures(self, key: tuple):
        """The forbidden departures of this roadmap's edges found so far by the queries
        whose movers are slices of the same motion, ``key`` = (robot speed in px per step,
        how they take random walkers) (:mod:`~mawdo.planning.guide.sipp.departures`); a memo
        that ran out of room is replaced by an empty one."""
        from mawdo.planning.guide.sipp.departures import empty_memo, roomier

        memo = self._departures.get(key)
        memo = empty_memo(len(self.weights)) if memo is None else roomier(memo)
        self._departures[key] = memo
        return memo

    def keep_departures(self, key: tuple, memo, made: int) -> None:
        """Keep ``memo`` (grown by a search) as :meth:`departures` of ``key``, unless the
        movers' knots were made again since ``made`` (:attr:`knots_made` when its query took
        its tables)."""
        if made == self.knots_made:
            self._departures[key] = memo

    def movers(self, t0: float, t_end: float, walkers: str, cut: bool = False, only=None) -> Movers:
        """The moving obstacles over ``[t0, t_end]`` (see :class:`Movers`). ``cut``: their
        pieces end at ``t_end`` (a lookahead: nothing is tested after it), else the last piece
        runs to its own end (a knot at or after ``t_end``). ``only``: the indices (ascending,
        into the moving obstacles) of those to tabulate, default all."""
        knots = self._pieces if not cut else self._cut_pieces
        return Movers.from_scenario(
            self.scenario, self.clearance, t0, t_end, walkers, knots=knots, flat=self.flat,
            only=only,
        )  # fmt: skip

    @property
    def moving(self) -> tuple:
        """The scenario's moving obstacles, in order (those :meth:`movers` tabulates)."""
        return self._moving

    def _cut_pieces(self, m: int, t0: float, t_end: float):
        """:meth:`_pieces` with the last piece ending at ``t_end`` (its offset there
        interpolated on the piece)."""
        t, off = self._pieces(m, t0, t_end)
        if len(t) < 2 or t[-1] <= t_end:
            return t, off
        w = (t_end - t[-2]) / (t[-1] - t[-2])
        t, off = t.copy(), off.copy()
        t[-1], off[-1] = t_end, off[-2] + w * (off[-1] - off[-2])
        return t, off
