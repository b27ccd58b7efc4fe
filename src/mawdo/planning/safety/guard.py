"""The guard: nothing is driven before it is verified against the predicted obstacles.

Before each move the planner checks the part of a plan it will drive before the next replan,
with the exact space-time kernel (the robot at speed ``v`` along the path, obstacles along their
piecewise-linear motion, hit distance ``r + clearance``). The fallback order is:

1. the optimizer's best candidate, then the other members of a small *elite* of distinct
   candidates collected while the optimizer ran (:class:`Elite`), best first;
2. waiting in place, if the robot's disc plus the margin stays clear over the interval (checked
   by the independent checker, as the kernel measures time by distance travelled), and keeps
   the margin from the map's border;
3. the least-bad evasive move: of 16 headings at full and half speed (and waiting), one whose
   step keeps the margin (from the obstacles and the map's border) and gets closest to the
   plan's next point, else the one with the largest clearance among those that stay off the
   static obstacles and inside the map (a collision there is always the robot's own doing:
   :mod:`mawdo.planning.judge.fault`) and that touch no obstacle while moving toward it (at
   its modelled size; waiting never does: if contact cannot be avoided, the robot is not the
   one who makes it), else any; ranked by the clearance the robot keeps after the move if it
   holds the move's velocity a few steps more (:data:`AHEAD`: running straight away from a
   faster pursuer loses to stepping aside), the step's own clearance breaking ties.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.refine.cost import PathCost
from mawdo.planning.world.path import advance, densify, segment_lengths, unit_headings
from mawdo.planning.world.scenario import Scenario
from mawdo.util.stablesort import stable_argsort

__all__ = ["Elite", "Guard"]

_MIN = np.minimum.reduce  # (what ndarray.min calls, without its Python wrapper)
#: Clearances (px) this close are a tie between evasive moves (then the step's own decides).
TIE_TOL = 1e-9
#: Moves the least-bad evasion looks ahead: it ranks moves by how clear the robot stays if it
#: keeps the move's velocity that long (a step's own clearance only breaks ties).
AHEAD = 4


@njit(cache=True)
def _distinct_first(X, order, size, min_dist):
    """Indices, in ``order``, of the first ``size`` rows of ``X`` that differ from every row
    already taken by more than ``min_dist`` in some coordinate (a NaN difference never counts as
    distinct, as with ``numpy.max``); replaces a NumPy loop of small calls that cost ~5 ms per
    replan."""
    keep = np.empty(size, np.int64)
    k = 0
    for i in order:
        distinct = True
        for a in range(k):
            j, far = keep[a], 0.0
            for d in range(X.shape[1]):
                gap = abs(X[j, d] - X[i, d])
                if gap != gap:  # NaN: numpy's max and min would propagate it
                    far = gap
                    break
                far = max(far, gap)
            if not far > min_dist:
                distinct = False
                break
        if distinct:
            keep[k] = i
            k += 1
            if k == size:
                break
    return keep[:k]


@njit(cache=True)
def _merge(EX, ef, X, fv, part, size, min_dist):
    """The elite ``(EX, ef)`` merged with the batch rows ``part`` (best first, stable order on
    ties, then :func:`_distinct_first`); one compiled call instead of a dozen small NumPy ones
    per batch. ``part`` comes from NumPy's ``argpartition``, so ties at its cut are broken as
    before."""
    # stable_argsort, and loops, not np.argsort(kind="mergesort") and slice assignments: the
    # same order, and each process compiles 4-5 s less of Numba's own helpers
    take = part[stable_argsort(fv[part])]
    n0, d = EX.shape[0], X.shape[1]
    allx = np.empty((n0 + len(take), d))
    allf = np.empty(n0 + len(take))
    for a in range(n0):
        allf[a] = ef[a]
        for c in range(d):
            allx[a, c] = EX[a, c]
    for a in range(len(take)):
        allf[n0 + a] = fv[take[a]]
        for c in range(d):
            allx[n0 + a, c] = X[take[a], c]
    keep = _distinct_first(allx, stable_argsort(allf), size, min_dist)
    return allx[keep], allf[keep]


class Elite:
    """The ``size`` best distinct candidates seen by a cost function (lowest cost first).

    Two candidates are distinct when some coordinate differs by more than ``min_dist`` px.
    """

    def __init__(self, size: int = 8, min_dist: float = 2.0) -> None:
        self.size, self.min_dist = int(size), float(min_dist)
        self.X = np.empty((0, 0))
        self.f = np.empty(0)

    def add(self, X: np.ndarray, f: np.ndarray) -> np.ndarray:
        """Offer a batch (candidates ``(n, D)``, costs ``(n,)``); returns ``f`` unchanged."""
        # (the usual batch, a 1-D float64 array, goes through without numpy's conversions)
        fv = f
        if not (type(f) is np.ndarray and f.dtype == np.float64 and f.ndim == 1):
            fv = np.atleast_1d(np.asarray(f, dtype=float))
        # nothing in this batch would enter (the usual case late in a run): decided before any
        # other work. The elite holds finite costs only, so an inf here changes nothing, and a
        # NaN fails the test and takes the full path below.
        if len(self.f) == self.size and _MIN(fv) >= self.f[-1]:
            return f
        if not (type(X) is np.ndarray and X.ndim == 2):
            X = np.atleast_2d(X)
        ok = np.isfinite(fv)
        if not ok.all():  # the usual batch is all finite: no masked copy of it then
            if not ok.any():
                return f
            X, fv = X[ok], fv[ok]
            if len(self.f) == self.size and _MIN(fv) >= self.f[-1]:
                return f  # -inf hid it above
        if len(fv) > self.size:  # the batch's best few, without sorting it all
            part = fv.argpartition(self.size - 1)[: self.size]
        else:
            part = np.arange(len(fv))
        old = self.X if self.X.size else np.empty((0, X.shape[1]))  # (C-contiguous float64)
        if not (X.dtype == np.float64 and X.flags.c_contiguous):
            X = np.ascontiguousarray(X, dtype=float)
        self.X, self.f = _merge(
            old,
            self.f,
            X,
            fv,
            part,
            self.size,
            self.min_dist,
        )
        return f


class Guard:
    """Exact checks of the next driven stretch (see the module docstring).

    Parameters
    ----------
    scenario : Scenario
    clearance : float
        Margin (px) added to the robot radius, >= 0.
    n_check : int
        Waypoints of the kernel's stretch encoding (a stretch with more vertices is cut).
    """

    def __init__(self, scenario: Scenario, clearance: float, n_check: int = 8) -> None:
        self.scenario, self.clearance = scenario, float(clearance)
        self.cost = PathCost(scenario, mode="spacetime", n_waypoints=n_check, clearance=clearance)
        self.n_check = n_check

    def stretch_hits(self, route: np.ndarray, t: float, distance: float) -> int:
        """Kernel hits ``n`` of the first ``distance`` px of ``route``, driven from time ``t``."""
        end, _, passed, _ = advance(route, distance)
        pts = np.concatenate((route[:1], passed, end[None]))
        if len(pts) - 2 > self.n_check:  # more vertices than the encoding: check it in pieces
            half = len(pts) // 2
            d0 = float(segment_lengths(pts[: half + 1]).sum())
            first = self.stretch_hits(pts[: half + 1], t, d0)
            v = self.scenario.robot_speed
            return first + self.stretch_hits(pts[half:], t + d0 / v, distance - d0)
        X = densify(pts, self.n_check).reshape(1, -1)
        _, ncol, _ = self.cost.parts(X, start=pts[0], t0=t, goal=pts[-1])
        return int(ncol[0])

    def step_clearance(self, pos: np.ndarray, to: np.ndarray, t: float, dt: float) -> float:
        """Smallest clearance (px, true radius) over a straight move ``pos -> to`` in ``dt``,
        to the obstacles and to the map's border (negative where the disc leaves the map)."""
        return self.step_clearances(pos, to, t, dt)[0]

    def step_clearances(self, pos, to, t: float, dt: float) -> tuple[float, float]:
        """:meth:`step_clearance`, and the same to the static obstacles and the border only
        (px): the part of it that only the robot's own motion can make negative."""
        return self._clearances(self._step_check(pos, to, t, dt)[2])

    def causes_contact(self, pos, to, t: float, dt: float) -> bool:
        """The straight move ``pos -> to`` over ``dt`` steps touches an obstacle (at its
        modelled size) while moving toward it: a contact the judge would put down to the robot
        (:func:`~mawdo.planning.judge.fault.blame`); a wait never does."""
        return self._own_contact(*self._step_check(pos, to, t, dt))

    def _step_check(self, pos, to, t: float, dt: float):
        """The checker's report on the straight move ``pos -> to`` over ``dt`` steps from
        ``t``: ``(points, times, report)``."""
        pts, times = np.vstack([pos, to]), np.array([t, t + dt])
        return pts, times, check_trajectory(pts, self.scenario, times=times)

    def _clearances(self, rep) -> tuple[float, float]:
        border = -rep.border_excess
        static = self.scenario.static_indices
        walls = float(rep.clearance[:, static].min()) if static and rep.clearance.size else np.inf
        return min(float(rep.min_clearance), border), min(walls, border)

    def _own_contact(self, pts, times, rep) -> bool:
        from mawdo.planning.judge.fault import blame

        return bool(rep.collisions) and bool(blame(pts, times, self.scenario, rep.collisions)[0])

    def ahead_clearance(self, pos, to, t: float, dt: float) -> float:
        """Smallest clearance (px) after a move ``pos -> to`` over ``dt`` steps if the robot
        then keeps that velocity for :data:`AHEAD` more moves (a wait keeps waiting): where a
        move leads, the obstacles' and the border's."""
        step = np.asarray(to, float) - np.asarray(pos, float)
        pts = np.asarray(to, float) + np.arange(AHEAD + 1)[:, None] * step
        times = t + dt * (1.0 + np.arange(AHEAD + 1))
        rep = check_trajectory(pts, self.scenario, times=times)
        return min(float(rep.min_clearance), -rep.border_excess)

    def evasive_move(self, pos: np.ndarray, target: np.ndarray, t: float, dt: float, admit=None):
        """Best move over ``dt`` steps: ``(to, clearance, safe)`` (see the module docstring).

        ``admit(to) -> bool`` (optional): of the safe moves, only those it admits count, tried
        nearest the target first; ``safe`` is then False when it admits none (the move
        returned is the one without ``admit``).

        The moves are checked nearest the target first, and the checks stop at the first
        safe one (with ``admit``: the first safe one it admits): all 33 are checked only
        where that one is far down the order or missing, as the least-bad move needs them
        all. Same answer as checking them all first (a test keeps that version).
        """
        v = self.scenario.robot_speed * dt
        dirs = unit_headings(16)
        moves = np.vstack([pos, pos + v * dirs, pos + 0.5 * v * dirs])
        order = np.argsort(np.hypot(*(moves - target).T), kind="stable")
        checks: list = [None] * len(moves)
        clear, walls = np.full(len(moves), -np.inf), np.full(len(moves), -np.inf)
        best = None  # the nearest safe move, admitted or not
        for i in order:
            checks[i] = self._step_check(pos, moves[i], t, dt)  # each move checked once
            clear[i], walls[i] = self._clearances(checks[i][2])
            if clear[i] < self.clearance:
                continue
            best = i if best is None else best
            if admit is None or admit(moves[i]):
                return moves[i], float(clear[i]), True
        if best is not None:  # safe moves, none admitted
            return moves[best], float(clear[best]), False
        return self._least_bad(pos, moves, checks, clear, walls, t, dt)

    def _least_bad(self, pos, moves, checks, clear, walls, t: float, dt: float):
        """None of ``moves`` keeps the margin: never into a wall or off the map if any move
        stays out, nor into a contact of its own making if any move is free of one (waiting
        is); then the most room ahead (:meth:`ahead_clearance`), the step's own breaking
        ties. ``(to, clearance, False)``."""
        out = walls >= 0.0
        free = out & ~np.array([self._own_contact(*c) for c in checks])
        out = free if free.any() else out
        ahead = np.array([self.ahead_clearance(pos, m, t, dt) for m in moves])
        key = np.where(out, ahead, -np.inf) if out.any() else ahead
        top = np.nonzero(key >= key.max() - TIE_TOL)[0]
        best = int(top[int(np.argmax(clear[top]))])
        return moves[best], float(clear[best]), False
