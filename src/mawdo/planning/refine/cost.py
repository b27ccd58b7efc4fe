"""Path cost of the paper (Eqs. 24-28) for a population of waypoint candidates.

``C = alpha C1 + beta C2 + lam C3`` (Eq. 24) with ``alpha + beta + lam = 1`` (Eq. 25):

* ``C1``: polyline length of ``start, w1..wm, goal`` (pixels, Eq. 26);
* ``C2 = k n^4`` (Eq. 27), ``n`` the number of (segment, obstacle) pairs whose segment hits the
  obstacle inflated by the robot radius, *including a segment lying wholly inside it* (the
  paper counts boundary crossings, which misses that case); the map's border is one more
  obstacle: a segment whose robot disc (radius plus ``clearance``) leaves the map counts once;
* ``C3 = sum |theta_i - pi|`` over interior vertices (radians, Eq. 28): the total turning angle;
  zero-length segments are skipped, so duplicated waypoints neither add nor hide turning.

Modes
-----
``snapshot`` (the paper)
    Obstacles frozen where they are at the planning time ``t0``.
``spacetime``
    The robot leaves ``start`` at ``t0`` and moves at its speed ``v`` along the path, so it is on
    segment ``j`` during ``[t0 + s_j / v, t0 + s_{j+1} / v]`` (``s`` arc length). Each segment is
    tested against each obstacle's motion over that interval, exactly (relative motion per
    constant-velocity piece; see :mod:`mawdo.planning.refine.kernel`).

Default weights (why)
---------------------
``alpha = 0.45, beta = 0.10, lam = 0.45, k = 1e5``.

* ``beta k = 1e4`` exceeds the cost of *any* collision-free path on the 366 x 366 map: with
  20 waypoints in the map box, ``C1 <= 21 * 517.6 = 10870`` px and ``C3 <= 20 pi``, so
  ``alpha C1 + lam C3 <= 4920 < 1e4``. Every collision-free candidate therefore ranks above every
  colliding one, and among colliding ones fewer hits rank better (``n^4``). The bound is
  ``beta k > alpha (m + 1) diag + lam m pi``; :meth:`CostWeights.dominates` checks it.
* ``lam = alpha``: one radian of turning costs as much as one pixel of length. Near an optimum a
  zig-zag of amplitude ``d`` on segments of length ``l`` adds about ``2 d^2 / l`` px of length but
  ``4 d / l`` rad of turning, so the turning term is what irons out small wiggles, while a
  detour of many pixels is still judged by its length. Turning that a detour needs cannot be
  avoided, so this weight barely moves the shortest collision-free path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mawdo.planning.refine.kernel.threads import ThreadedKernel
from mawdo.planning.world.geometry import FlatObstacles, MotionTable
from mawdo.planning.world.scenario import Scenario

__all__ = ["CostWeights", "PathCost", "assemble_paths"]

MODES = ("snapshot", "spacetime")
#: Start times whose kernel arrays a cost keeps at once, per motion table (see
#: ``PathCost._motion_arrays``).
MOTION_CACHE = 256
#: Motion tables a cost keeps at once: a guard asks short stretches and whole routes in turn,
#: and one table for both was built again at every other call (10 000 movers: 0.6 s each).
MOTION_TABLES = 4
_MIN, _MAX = np.minimum.reduce, np.maximum.reduce


@dataclass(frozen=True)
class CostWeights:
    """Weights of Eq. 24 and the collision scale of Eq. 27.

    Parameters
    ----------
    alpha : float
        Weight of the length C1 (per pixel), >= 0.
    beta : float
        Weight of the collision term C2, >= 0.
    lam : float
        Weight of the turning C3 (per radian), >= 0.
    k : float
        Scale of ``C2 = k n^4``, >= 0.

    Notes
    -----
    ``alpha + beta + lam`` must be 1 (Eq. 25; within 1e-9).
    """

    alpha: float = 0.45
    beta: float = 0.10
    lam: float = 0.45
    k: float = 1e5

    def __post_init__(self) -> None:
        for name in ("alpha", "beta", "lam", "k"):
            value = getattr(self, name)
            if not np.isfinite(value) or value < 0:
                raise ValueError(f"CostWeights.{name} must be finite and >= 0, got {value!r}")
        total = self.alpha + self.beta + self.lam
        if abs(total - 1.0) > 1e-9:
            raise ValueError(f"alpha + beta + lam must equal 1 (Eq. 25), got {total!r}")

    def dominates(self, width: float, height: float, n_waypoints: int = 20) -> bool:
        """True if one collision outweighs any collision-free path in a ``width x height`` map.

        That holds when ``beta k > alpha (m + 1) diag + lam m pi`` (``m`` waypoints in the map
        box, ``diag`` the map diagonal in pixels).
        """
        diag = float(np.hypot(width, height))
        bound = self.alpha * (n_waypoints + 1) * diag + self.lam * n_waypoints * np.pi
        return self.beta * self.k > bound


def assemble_paths(X, start, goal) -> np.ndarray:
    """Full paths ``start, w1..wm, goal`` from candidates.

    Parameters
    ----------
    X : array_like, shape (n, 2 m)
        Waypoints ``(x1, y1, ..., xm, ym)`` (pixels).
    start, goal : array_like, shape (2,)

    Returns
    -------
    numpy.ndarray, shape (n, m + 2, 2)
    """
    X = np.asarray(X, dtype=float)
    n = X.shape[0]
    pts = X.reshape(n, -1, 2)
    s = np.broadcast_to(np.asarray(start, dtype=float), (n, 1, 2))
    g = np.broadcast_to(np.asarray(goal, dtype=float), (n, 1, 2))
    return np.concatenate([s, pts, g], axis=1)


def _end(name: str, p) -> np.ndarray:
    """A path end as the kernel takes it (contiguous float64, shape (2,)), or a clear error."""
    if not (type(p) is np.ndarray and p.dtype == np.float64 and p.flags.c_contiguous):
        p = np.ascontiguousarray(p, dtype=np.float64)  # one compiled layout
    if p.shape != (2,) or not (math.isfinite(p[0]) and math.isfinite(p[1])):
        raise ValueError(f"{name} must be a finite (x, y) pair, got {p!r}")
    return p


def _check_reach(lo: float, hi: float, sc: Scenario, what: str) -> None:
    """Refuse candidate coordinates beyond one map size outside the map (spacetime mode).

    The motion of the obstacles is tabulated until the robot could reach the goal, which grows
    with the distances in the candidates: a coordinate of 1e4 px on a 366 px map asked for
    gigabytes. One map size around the map covers any detour a planner would take.
    """
    size = max(float(sc.width), float(sc.height))
    if lo < -size or hi > 2.0 * size:
        bad = lo if lo < -size else hi
        raise ValueError(
            f"{what} is {bad:.6g} px, more than one map size outside the "
            f"{sc.width:g} x {sc.height:g} px map ([{-size:g}, {2 * size:g}] px allowed in "
            "spacetime mode, whose obstacle motion is tabulated as far as the paths reach); "
            "keep them within that range (candidates within PathCost.bounds), or use "
            "mode='snapshot'"
        )


class PathCost:
    """The paper's path cost for a population, evaluated by one compiled kernel call.

    Parameters
    ----------
    scenario : Scenario
        World: map, goal, robot radius and speed, obstacles and their motion.
    mode : {"snapshot", "spacetime"}
        How moving obstacles are treated (see the module docstring).
    weights : CostWeights, optional
        Defaults to ``CostWeights()`` (alpha 0.45, beta 0.10, lam 0.45, k 1e5).
    n_waypoints : int
        Waypoints per candidate ``m``; the dimension is ``2 m`` (default 20 -> 40-D).
    clearance : float
        Margin (px, >= 0) added to the robot radius for the hit test of Eq. 27: a segment
        coming within ``r + clearance`` of an obstacle, or with an end closer than that to the
        map's border, counts as a collision (default 0).
    threads : int
        Threads a call may use (default 1: the calling thread only). Populations are split
        into chunks of rows of at least 16 candidates evaluated at once; the numbers are the
        same bit for bit whatever the count. Leave it at 1 where processes already share the
        cores (a study with several workers).
    obstacles : sequence of Obstacle, optional
        The obstacles ``n`` counts (default all of the scenario's), e.g. its movers only.
    border : bool
        Whether the map's border counts in ``n`` (default True).
    horizon : float, optional
        Lookahead (time steps, > 0) of the spacetime mode: moving obstacles count only on the
        segments the robot begins before ``t0 + horizon`` (the one that straddles that time
        whole); standing obstacles and the border on all of them. None (default): the whole
        path. For a planner that trusts its predictions only so far ahead; its safety check
        must not use it.

    Examples
    --------
    >>> cost = PathCost(get_scenario("paper"), mode="spacetime")      # doctest: +SKIP
    >>> f = cost(X, start=(20, 20), t0=12.0)                           # doctest: +SKIP
    """

    def __init__(
        self,
        scenario: Scenario,
        mode: str = "snapshot",
        weights: CostWeights | None = None,
        n_waypoints: int = 20,
        clearance: float = 0.0,
        threads: int = 1,
        obstacles=None,
        border: bool = True,
        horizon: float | None = None,
    ) -> None:
        if mode not in MODES:
            raise ValueError(f"mode must be one of {MODES}, got {mode!r}")
        if not isinstance(n_waypoints, int | np.integer) or n_waypoints < 1:
            raise ValueError(f"n_waypoints must be a positive integer, got {n_waypoints!r}")
        if weights is None:
            weights = CostWeights()
        if not isinstance(weights, CostWeights):
            raise TypeError(f"weights must be a CostWeights, got {type(weights).__name__}")
        self.scenario = scenario
        self.mode = mode
        self.weights = weights
        self.n_waypoints = int(n_waypoints)
        if not np.isfinite(clearance) or clearance < 0:
            raise ValueError(f"clearance must be finite and >= 0 px, got {clearance!r}")
        self.clearance = float(clearance)
        if horizon is not None and not (math.isfinite(horizon) and horizon > 0):
            raise ValueError(
                f"horizon must be None (the whole path) or a finite number of time steps > 0, "
                f"got {horizon!r}"
            )
        self.horizon = None if horizon is None else float(horizon)
        self._horizon = math.inf if horizon is None else float(horizon)
        # the margin widens the hit distance: touching the inflated-plus-margin shape is a hit
        self._obstacles = tuple(scenario.obstacles if obstacles is None else obstacles)
        self._rows = None if obstacles is None else [o.index for o in self._obstacles]
        self.flat = FlatObstacles.from_obstacles(
            self._obstacles, scenario.robot_radius + self.clearance
        )
        # the motion tables, the most recently used first, each with its kernel arrays per t0
        self._tables: list[tuple[MotionTable, dict]] = []
        # the kernel's per-t0 inputs, kept for the next call with the same t0 (an optimizer
        # calls many times per planning step; the guard checks a long stretch in pieces, each
        # from its own start time, and again at the next replan): (t0, offsets), and the
        # table's kernel arrays per t0 (a pure function of the table and t0)
        self._snap: tuple | None = None
        self._frozen = MotionTable.frozen(len(self.flat.thresh)).kernel_arrays(0.0)
        self._kernel = ThreadedKernel(threads)  # keeps the kernel's work space between calls
        self._no_offsets = np.zeros((len(self.flat.thresh), 2))
        # (a scenario is immutable: what every call reads of it, read once)
        self._goal = _end("goal", scenario.goal)
        self._speed = float(scenario.robot_speed)
        size = max(float(scenario.width), float(scenario.height))
        self._reach = (-size, 2.0 * size)  # coordinates _check_reach allows
        # the border, inflated like every obstacle: the centre must keep r + clearance from it
        # (a map narrower than that leaves an empty box, where every segment hits)
        reach = float(scenario.robot_radius) + self.clearance
        self._box = (reach, reach, float(scenario.width) - reach, float(scenario.height) - reach)
        if not border:
            self._box = (-math.inf, -math.inf, math.inf, math.inf)
        self._bounds: tuple | None = None
        w = self.weights
        self._weights = (float(w.alpha), float(w.beta), float(w.lam), float(w.k))
        self._obs = self.flat.arrays()  # (the kernel's shape arrays: one tuple, not one a call)

    @property
    def threads(self) -> int:
        """Threads a call may use (see the class parameters)."""
        return self._kernel.threads

    @property
    def dim(self) -> int:
        """Dimension of a candidate (``2 * n_waypoints``)."""
        return 2 * self.n_waypoints

    @property
    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Box ``(lb, ub)`` of a candidate: the map (pixels), each shape ``(dim,)``."""
        # laid out once (np.tile costs ~10 us, asked a few times per replan); each call gets
        # its own copies, which callers may change
        if self._bounds is None:
            lb = np.zeros(self.dim)
            ub = np.tile([self.scenario.width, self.scenario.height], self.n_waypoints)
            self._bounds = (lb, ub)
        return self._bounds[0].copy(), self._bounds[1].copy()

    def __call__(self, X, start=None, t0: float = 0.0) -> np.ndarray:
        """Total cost C (Eq. 24) of each candidate.

        Parameters
        ----------
        X : array_like, shape (n, dim) or (dim,)
            Candidates (pixels).
        start : array_like, shape (2,), optional
            Current robot position (pixels); default the scenario's start.
        t0 : float
            Planning time (time steps), >= 0.

        Returns
        -------
        numpy.ndarray, shape (n,) (a float for a single candidate)

        Raises
        ------
        ValueError
            In spacetime mode, for a finite coordinate (of a candidate, ``start`` or the goal)
            more than one map size outside the map; NaN and infinite candidates get a NaN cost.
        """
        cost, _, _, _ = self._evaluate(X, start, t0)
        return cost

    def parts(self, X, start=None, t0: float = 0.0, goal=None):
        """The three parts of the cost, unweighted.

        ``goal`` (pixels) replaces the scenario's goal as the path's last point, e.g. to test
        only the part of a plan the robot drives before its next replan.

        Returns
        -------
        length : numpy.ndarray, shape (n,)
            C1, polyline length (pixels, Eq. 26).
        n_collisions : numpy.ndarray of int64, shape (n,)
            ``n`` of Eq. 27 (``C2 = k n^4``), segments leaving the map included.
        turning : numpy.ndarray, shape (n,)
            C3, total turning (radians, Eq. 28).
        """
        _, length, ncol, turn = self._evaluate(X, start, t0, goal)
        return length, ncol, turn

    # ----------------------------------------------------------------------------------------

    def _motion_table(self, X, start, t0: float, goal) -> tuple:
        # Every segment is shorter than the diagonal of a box holding all points, so the robot
        # reaches the goal before t0 + (m + 1) diag / v: a table to there covers every query.
        # One min/max over all coordinates gives a (square) box cheaply; the rest is done on
        # Python floats, since numpy's scalar operations cost microseconds per call here.
        # (the ufuncs' reductions are what ndarray.min and max call, without their wrappers)
        lo, hi = float(_MIN(X, axis=None)), float(_MAX(X, axis=None))
        if not (math.isfinite(lo) and math.isfinite(hi)):  # NaN candidates get a NaN cost
            finite = X[np.isfinite(X)]
            lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 0.0)
        sx, sy = start.tolist()
        gx, gy = goal.tolist()
        elo, ehi = min(sx, sy, gx, gy), max(sx, sy, gx, gy)
        if lo < self._reach[0] or hi > self._reach[1]:  # (the check, without its call)
            _check_reach(lo, hi, self.scenario, "a candidate coordinate")
        if elo < self._reach[0] or ehi > self._reach[1]:
            _check_reach(elo, ehi, self.scenario, "a coordinate of start or goal")
        lo = min(lo, elo)
        hi = max(hi, ehi)
        diag = math.sqrt(2.0) * (hi - lo)
        t_need = t0 + (self.n_waypoints + 1) * diag / self._speed
        tables = self._tables
        for i, kept in enumerate(tables):
            if kept[0].covers(t0, t_need):
                if i:  # (the most recently used first)
                    tables.insert(0, tables.pop(i))
                return kept
        # a receding-horizon planner calls again with a later t0: cover twice what is needed
        table = MotionTable.build(self._obstacles, t0, t0 + 2.0 * (t_need - t0) + 1.0)
        tables.insert(0, (table, {}))
        del tables[MOTION_TABLES:]
        return tables[0]

    def _motion_arrays(self, kept: tuple, t0: float) -> tuple:
        """``table.kernel_arrays(t0)`` of a kept ``(table, per_t0)``, computed once per table
        and ``t0``."""
        table, per_t0 = kept
        arrays = per_t0.get(t0)
        if arrays is None:
            if len(per_t0) >= MOTION_CACHE:  # a long run asks ever later times: forget them
                per_t0.clear()
            arrays = per_t0[t0] = table.kernel_arrays(t0)
        return arrays

    def _evaluate(self, X, start, t0, goal=None):
        # (the planner calls ~20 times a replan, often with one candidate: the common case,
        # a C-contiguous float64 array and array ends, skips numpy's conversions)
        if not (type(X) is np.ndarray and X.dtype == np.float64 and X.flags.c_contiguous):
            X = np.asarray(X, dtype=np.float64)
        single = X.ndim == 1
        X2 = X if X.ndim == 2 else np.ascontiguousarray(np.atleast_2d(X))
        if X2.ndim != 2 or X2.shape[1] != self.dim:
            raise ValueError(
                f"X must have shape (n, {self.dim}) for {self.n_waypoints} waypoints, got {X.shape}"
            )
        start = _end("start", self.scenario.start if start is None else start)
        goal = self._goal if goal is None else _end("goal", goal)
        t0 = float(t0)
        if not math.isfinite(t0) or t0 < 0:
            raise ValueError(f"t0 must be finite and >= 0, got {t0!r}")
        n = X2.shape[0]
        out_cost = np.empty(n)
        out_len = np.empty(n)
        out_turn = np.empty(n)
        out_ncol = np.empty(n, dtype=np.int64)
        if n == 0:
            return out_cost, out_len, out_ncol, out_turn
        spacetime = self.mode == "spacetime"
        if spacetime:
            motion = self._motion_arrays(self._motion_table(X2, start, t0, goal), t0)
            snap = self._no_offsets  # read only by the kernel in spacetime mode
        else:
            motion = self._frozen
            if self._snap is None or self._snap[0] != t0:
                offsets = self.scenario.offsets(t0)
                offsets = offsets if self._rows is None else offsets[self._rows]
                offsets = np.ascontiguousarray(offsets, dtype=np.float64)
                self._snap = (t0, offsets)
            snap = self._snap[1]
        self._kernel(
            X2,
            start,
            goal,
            t0,
            self._speed,
            spacetime,
            self._obs,
            snap,
            motion,
            self._horizon,
            self._weights,
            self._box,
            (out_cost, out_len, out_ncol, out_turn),
        )
        if single:
            return out_cost[0], out_len[0], out_ncol[0], out_turn[0]
        return out_cost, out_len, out_ncol, out_turn
