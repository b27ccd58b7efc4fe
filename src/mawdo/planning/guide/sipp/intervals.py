"""Moving obstacles as compiled tables, the departures that collide, and safe intervals.

:class:`Movers` holds every moving obstacle of a scenario over ``[t0, t_end]``: its shape and
hit distance (:class:`~mawdo.planning.world.geometry.FlatObstacles`, the cost kernel's own tables:
``R + r + clearance`` for circles, ``r + clearance`` from a polygon) and either its
constant-velocity pieces (the motion model's knots: constant velocity, patrol and, when the
walk is taken as known, the seeded random walk) or, for a random walker taken as unknown, its
reachable set (the shape where it is at ``t0``, growing at the walk's top speed).

:func:`forbidden` gives the closed departure intervals at which a straight timed move collides
(exact, :mod:`mawdo.planning.guide.sipp.geometry`); :func:`segment_free` is the independent yes/no
test of one timed move, piece by piece, with the cost kernel's exact primitives
(:mod:`mawdo.planning.refine.kernel.primitives`); the search accepts a departure only when that
test passes. :func:`safe_intervals` gives each vertex's open safe intervals (the gaps between
the forbidden intervals of a robot standing still).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from mawdo.planning.guide.sipp import index as _index
from mawdo.planning.guide.sipp.geometry import clip_range, cone_start, disc_missed, disc_range
from mawdo.planning.guide.sipp.index import PAD, candidates
from mawdo.planning.refine.kernel.primitives import (
    point_in_polygon,
    point_segment_d2,
    segment_hits_polygon,
)
from mawdo.planning.world.geometry import FlatObstacles
from mawdo.planning.world.motion import BoundedRandomWalk
from mawdo.planning.world.scenario import Scenario
from mawdo.util.stablesort import stable_argsort

__all__ = [
    "EPS", "Movers", "earliest_free", "forbidden", "forbidden_among", "safe_intervals",
    "segment_free", "segment_free_among", "vertex_intervals",
]  # fmt: skip

#: A departure just after a closed forbidden interval (time steps): the forbidden sets are
#: closed (touching counts as a hit, as in the cost kernel), the free ones open.
EPS = 1e-6
_WALKER_MODES = ("reachable", "known")


@dataclass(frozen=True)
class Movers:
    """Moving obstacles over ``[t0, t_end]`` as flat arrays (see the module docstring).

    ``box[m]`` is the inflated shape's bounding box at offset zero (pixels). ``kind[m]`` is 0
    for pieces (rows ``pptr[m]:pptr[m + 1]`` of ``pt0, pt1`` (times), ``po``
    (offset at ``pt0``, pixels) and ``pv`` (velocity, px per step)), 1 for a reachable set
    (shape at offset ``base[m]`` growing at ``vmax[m]`` px per step from ``t_base``).
    ``index``: which movers a move can meet (:mod:`mawdo.planning.guide.sipp.index`), or one
    slot holding all of them.
    """

    kind: np.ndarray
    box: np.ndarray
    circle: np.ndarray
    center: np.ndarray
    thr: np.ndarray
    verts: np.ndarray
    nverts: np.ndarray
    vmax: np.ndarray
    base: np.ndarray
    t_base: float
    pptr: np.ndarray
    pt0: np.ndarray
    pt1: np.ndarray
    po: np.ndarray
    pv: np.ndarray
    index: tuple

    @classmethod
    def from_scenario(
        cls,
        scenario: Scenario,
        margin: float,
        t0: float,
        t_end: float,
        walkers: str,
        knots=None,
        flat: FlatObstacles | None = None,
        only=None,
        indexed: bool = True,
    ) -> Movers:
        """Tables of the scenario's moving obstacles, hit distance grown by ``margin`` px.

        ``walkers`` is ``"reachable"`` (random walkers as growing reachable sets) or
        ``"known"`` (their seeded walk, as the cost kernel and the checker see it).
        ``knots(j, t0, t_end)`` may stand in for the ``j``-th moving obstacle's
        :meth:`~mawdo.planning.world.motion.Motion.knots` (pieces covering the interval; a cache),
        ``flat`` for their :class:`FlatObstacles` (all of them). ``only``: the indices
        (ascending, into the moving obstacles) of those to tabulate, default all; each
        mover's rows are what the full table holds for it, and every test of one mover reads
        only its own rows. ``indexed``: the tests look up the movers near a move in a grid
        over space and time (default; the same answers), or test every mover.
        """
        if walkers not in _WALKER_MODES:
            raise ValueError(f"walkers must be one of {_WALKER_MODES}, got {walkers!r}")
        moving = tuple(scenario.obstacles[i] for i in scenario.moving_indices)
        if flat is None:
            flat = FlatObstacles.from_obstacles(moving, scenario.robot_radius + margin)
        idx = np.arange(len(moving)) if only is None else np.asarray(only, np.int64)
        if only is not None:
            flat = FlatObstacles(*(a[idx] for a in flat.arrays()))
        n = len(idx)
        kind = np.zeros(n, np.int64)
        vmax = np.zeros(n)
        base = np.zeros((n, 2))
        pieces = []
        for m, j in enumerate(idx):
            o = moving[j]
            if walkers == "reachable" and isinstance(o.motion, BoundedRandomWalk):
                kind[m], vmax[m] = 1, o.motion.step
                base[m] = o.offset(float(t0))
                pieces.append((np.zeros(0), np.zeros((0, 2))))
            else:
                pieces.append(o.knots(t0, t_end) if knots is None else knots(j, t0, t_end))
        return cls._from_pieces(kind, flat, vmax, base, float(t0), pieces, indexed)

    @classmethod
    def _from_pieces(cls, kind, flat, vmax, base, t_base, pieces, indexed=True) -> Movers:
        n = len(kind)
        pptr = np.zeros(n + 1, np.int64)
        pptr[1:] = np.cumsum([max(len(t) - 1, 0) for t, _ in pieces])
        pt0, pt1 = np.zeros(pptr[-1]), np.zeros(pptr[-1])
        po, pv = np.zeros((pptr[-1], 2)), np.zeros((pptr[-1], 2))
        if pptr[-1]:
            # every mover's pieces at once (elementwise: the numbers of one np.diff per
            # mover): the knots laid end to end, a piece from each knot but a mover's last
            t_all = np.concatenate([t for t, _ in pieces])
            o_all = np.concatenate([np.reshape(off, (-1, 2)) for _, off in pieces])
            last = np.cumsum([len(t) for t, _ in pieces]) - 1
            first = np.ones(len(t_all), np.bool_)
            first[last[last >= 0]] = False
            k = np.flatnonzero(first)
            pt0[:], pt1[:], po[:] = t_all[k], t_all[k + 1], o_all[k]
            pv[:] = (o_all[k + 1] - o_all[k]) / (t_all[k + 1] - t_all[k])[:, None]
        box = np.ascontiguousarray(flat.bound[:, :4])
        center = np.ascontiguousarray(flat.bound[:, 4:6])
        if indexed:
            index = _index.build(kind, box, pptr, pt0, pt1, po, pv)
        else:
            index = _index.everything(kind)
        return cls(
            kind, box, flat.is_circle, center, flat.thresh, flat.verts, flat.nverts, vmax, base,
            t_base, pptr, pt0, pt1, po, pv, index,
        )  # fmt: skip

    def arrays(self) -> tuple:
        """The fields in order, as the compiled functions take them."""
        return (
            self.kind, self.box, self.circle, self.center, self.thr, self.verts, self.nverts,
            self.vmax, self.base, self.t_base, self.pptr, self.pt0, self.pt1, self.po, self.pv,
            self.index,
        )  # fmt: skip


@njit(cache=True)
def _sweep_order(buf, a, b):
    """Rows ``a..b-1`` of ``buf`` by their start (column 0), as indices of ``buf``.

    Was ``np.argsort`` (quick sort) of the starts; a stable sort instead spares every process
    compiling Numba's sort (1.7 s of CPU). Same order but among equal starts, which the sweeps
    over these intervals do not see: of a run of equal starts the first is tested against the
    end reached before the run (the others start before that end has grown past them), and the
    run's ends all go into one ``max`` (so at most the sign of a zero start could differ)."""
    keys = np.empty(b - a)
    for r in range(a, b):
        keys[r - a] = buf[r, 0]
    order = stable_argsort(keys)
    for r in range(b - a):
        order[r] += a
    return order


@njit(cache=True)
def _first_not_before(x, a, b, v):
    """``a + np.searchsorted(x[a:b], v)``: the first ``k`` in ``a..b`` whose ``x[k]`` is not
    below ``v`` (NaN above every number), by the same bisection as NumPy's and Numba's (the
    same ``k`` on any input), without compiling Numba's generic ``searchsorted``."""
    lo, hi = a, b
    while lo < hi:
        mid = lo + ((hi - lo) >> 1)
        if x[mid] < v or (v != v and x[mid] == x[mid]):
            lo = mid + 1
        else:
            hi = mid
    return lo


@njit(cache=True)
def _doubled(x):
    """``np.concatenate((x, np.empty(len(x))))`` without Numba's generic concatenate."""
    out = np.empty(2 * len(x))
    for i in range(len(x)):
        out[i] = x[i]
    return out


@njit(cache=True)
def _polygon_piece(d0x, d0y, ex, ey, wx, wy, T, ta, tb, verts, i, nv, thr, buf, n):
    """Forbidden departures of one piece against polygon ``i``: per vertex a disc, per edge a
    rectangle of half-width ``thr``, and the gaps between them whose moves run inside; written
    to ``buf`` from row ``n`` on while it has room. Returns the rows then filled: more than
    ``buf`` holds when it ran out of room (the rows past it are not written)."""
    first, room = n, buf.shape[0]
    planes = np.empty((4, 3))
    half = max(thr, 1e-9)  # a zero-width strip would lose touching to rounding
    for k in range(nv):
        kk = k + 1 if k + 1 < nv else 0
        ax, ay, bx, by = verts[i, k, 0], verts[i, k, 1], verts[i, kk, 0], verts[i, kk, 1]
        if thr > 0.0:
            lo, hi = disc_range(d0x - ax, d0y - ay, ex, ey, wx, wy, T, ta, tb, thr)
            if lo <= hi:
                if n < room:
                    buf[n, 0], buf[n, 1] = lo, hi
                n += 1
        length = math.hypot(bx - ax, by - ay)
        if length == 0.0:
            continue
        ux, uy = (bx - ax) / length, (by - ay) / length
        planes[0, 0], planes[0, 1], planes[0, 2] = -ux, -uy, -(ux * ax + uy * ay)
        planes[1, 0], planes[1, 1], planes[1, 2] = ux, uy, ux * bx + uy * by
        planes[2, 0], planes[2, 1], planes[2, 2] = -uy, ux, -uy * ax + ux * ay + half
        planes[3, 0], planes[3, 1], planes[3, 2] = uy, -ux, uy * ax - ux * ay + half
        lo, hi = clip_range(d0x, d0y, ex, ey, wx, wy, T, ta, tb, planes)
        if lo <= hi:
            if n < room:
                buf[n, 0], buf[n, 1] = lo, hi
            n += 1
    m = n - first
    if n + m + 1 > room:  # no room for the gaps (or the rows above): the caller grows buf
        return n + m + 1
    edges = buf[_sweep_order(buf, first, n)]
    cur = ta - T
    for j in range(m + 1):
        g1 = edges[j, 0] if j < m else tb
        if g1 > cur:  # a gap: one point of one move decides it
            tm = 0.5 * (cur + g1)
            s = 0.5 * (max(0.0, ta - tm) + min(T, tb - tm))
            t = tm + s
            if point_in_polygon(d0x + s * ex - t * wx, d0y + s * ey - t * wy, verts, i, nv):
                buf[n, 0], buf[n, 1] = cur, g1
                n += 1
        if j < m:
            cur = max(cur, edges[j, 1])
    return n


@njit(cache=True)
def forbidden(ux, uy, ex, ey, T, lo, hi, mv):
    """Departures in ``[lo, hi]`` (time steps) at which the move ``u + s e``, ``0 <= s <= T``,
    meets a mover: sorted, disjoint closed intervals, shape ``(k, 2)``."""
    # only the movers the move can meet (a superset: the same intervals, in the same order)
    return forbidden_among(
        ux, uy, ex, ey, T, lo, hi, mv, candidates(ux, uy, ex, ey, T, lo, hi, mv[15])
    )


@njit(cache=True)
def forbidden_among(ux, uy, ex, ey, T, lo, hi, mv, cands):
    """:func:`forbidden` with the movers to test given (ascending indices): those of
    :func:`~mawdo.planning.guide.sipp.index.candidates` for this move, or for one whose
    departures include these."""
    # The candidates' loop is written out here, the tables bound once before it and buf never
    # rebound inside it: Numba counts every binding of an array (an atomic increment and
    # decrement), and as an inlined function per candidate taking the tables, growing buf as it
    # went, this loop spent 60 % of the safe-interval search's CPU on those (1000 x 1000 px,
    # 200 movers); a function call binds each table once more (22 a call).
    kind, box, circle, center, thr, verts, nverts = mv[:7]
    vmax, base, t_base, pptr, pt0, pt1, po, pv = mv[7:15]
    # the move's bounding box: a piece whose swept box misses it cannot collide
    rx0, rx1 = min(ux, ux + T * ex), max(ux, ux + T * ex)
    ry0, ry1 = min(uy, uy + T * ey), max(uy, uy + T * ey)
    room = 16 + 2 * len(cands)
    while True:  # each candidate's departures, written while buf has room, else again with more
        buf = np.empty((room, 2))
        n = np.int64(0)  # (not a literal 0: Numba would compile _polygon_piece for its type)
        for m in cands:
            if kind[m] == 1:
                tc = cone_start(
                    ux, uy, ex, ey, T, circle[m], center[m, 0], center[m, 1], thr[m], verts, m,
                    nverts[m], base[m, 0], base[m, 1], vmax[m], t_base,
                )  # fmt: skip
                if tc <= hi:
                    if n < room:
                        buf[n, 0], buf[n, 1] = tc, math.inf
                    n += 1
                continue
            b = pptr[m + 1]
            k = _first_not_before(pt1, pptr[m], b, lo)
            while k < b and pt0[k] <= hi + T:
                ta, tb, wx, wy = pt0[k], pt1[k], pv[k, 0], pv[k, 1]
                ox0, ox1 = po[k, 0], po[k, 0] + wx * (tb - ta)
                oy0, oy1 = po[k, 1], po[k, 1] + wy * (tb - ta)
                k += 1
                if (
                    box[m, 0] + min(ox0, ox1) > rx1
                    or box[m, 2] + max(ox0, ox1) < rx0
                    or box[m, 1] + min(oy0, oy1) > ry1
                    or box[m, 3] + max(oy0, oy1) < ry0
                ):
                    continue
                d0x, d0y = ux - ox0 + wx * ta, uy - oy0 + wy * ta
                if not circle[m]:
                    if n < room:
                        n = _polygon_piece(d0x, d0y, ex, ey, wx, wy, T, ta, tb, verts, m,
                                           nverts[m], thr[m], buf, n)  # fmt: skip
                    else:
                        n += 1
                    continue
                dx, dy = d0x - center[m, 0], d0y - center[m, 1]
                # a disc no departure of the window comes near: its departures (the piece's
                # whole span) lie outside the window, where the merge drops them
                if disc_missed(dx, dy, ex, ey, wx, wy, T, lo, hi, thr[m] + PAD):
                    continue
                f0, f1 = disc_range(dx, dy, ex, ey, wx, wy, T, ta, tb, thr[m])
                if f0 <= f1:
                    if n < room:
                        buf[n, 0], buf[n, 1] = f0, f1
                    n += 1
        if n <= room:
            return _union_within(buf, n, lo, hi)
        room = 2 * n


@njit(cache=True)
def _union_within(buf, n, lo, hi):
    """The union of the closed intervals ``buf[:n]`` within ``[lo, hi]``: sorted, disjoint."""
    order = _sweep_order(buf, np.int64(0), n)  # (an int64: a literal 0 compiles it twice)
    out = np.empty((n, 2))
    k = 0
    for j in order:
        a, b = max(buf[j, 0], lo), min(buf[j, 1], hi)
        if a > b:
            continue
        if k > 0 and a <= out[k - 1, 1]:
            out[k - 1, 1] = max(out[k - 1, 1], b)
        else:
            out[k, 0] = a
            out[k, 1] = b
            k += 1
    return out[:k]


@njit(cache=True)
def earliest_free(F, x):
    """The earliest departure ``>= x`` outside the closed intervals ``F`` (sorted, disjoint);
    one just after an interval is ``EPS`` beyond its end."""
    tau = x
    for j in range(len(F)):
        if F[j, 1] < tau:
            continue
        if F[j, 0] > tau:
            break
        tau = F[j, 1] + EPS
    return tau


@njit(cache=True)
def segment_free(ux, uy, vx, vy, ta, tb, mv):
    """True iff the robot moving from ``u`` at ``ta`` to ``v`` at ``tb`` (straight, uniform;
    ``u == v`` is a wait) keeps clear of every mover (touching is a hit)."""
    dur = tb - ta
    ex = (vx - ux) / dur if dur > 0.0 else 0.0
    ey = (vy - uy) / dur if dur > 0.0 else 0.0
    return segment_free_among(
        ux, uy, vx, vy, ta, tb, mv, candidates(ux, uy, ex, ey, dur, ta, ta, mv[15])
    )


@njit(cache=True)
def segment_free_among(ux, uy, vx, vy, ta, tb, mv, cands):
    """:func:`segment_free` with the movers to test given (ascending indices): those of
    :func:`~mawdo.planning.guide.sipp.index.candidates` for this move, or for one whose
    departures include ``ta`` (the index's padding absorbs the rounding of ``tb - ta``)."""
    kind, _, circle, center, thr, verts, nverts = mv[:7]
    vmax, base, t_base, pptr, pt0, pt1, po, pv = mv[7:15]
    dur = tb - ta
    ex = (vx - ux) / dur if dur > 0.0 else 0.0
    ey = (vy - uy) / dur if dur > 0.0 else 0.0
    for m in cands:
        if kind[m] == 1:
            tc = cone_start(
                ux, uy, ex, ey, dur, circle[m], center[m, 0], center[m, 1], thr[m], verts, m,
                nverts[m], base[m, 0], base[m, 1], vmax[m], t_base,
            )  # fmt: skip
            if ta >= tc:
                return False
            continue
        a, b = pptr[m], pptr[m + 1]
        k = _first_not_before(pt1, a, b, ta)
        while k < b and pt0[k] <= tb:
            t1, t2 = max(ta, pt0[k]), min(tb, pt1[k])
            k += 1
            if t2 < t1:
                continue
            x1 = ux + ex * (t1 - ta) - po[k - 1, 0] - pv[k - 1, 0] * (t1 - pt0[k - 1])
            y1 = uy + ey * (t1 - ta) - po[k - 1, 1] - pv[k - 1, 1] * (t1 - pt0[k - 1])
            x2 = ux + ex * (t2 - ta) - po[k - 1, 0] - pv[k - 1, 0] * (t2 - pt0[k - 1])
            y2 = uy + ey * (t2 - ta) - po[k - 1, 1] - pv[k - 1, 1] * (t2 - pt0[k - 1])
            if circle[m]:
                if point_segment_d2(center[m, 0], center[m, 1], x1, y1, x2, y2) <= thr[m] ** 2:
                    return False
            elif segment_hits_polygon(x1, y1, x2, y2, verts, m, nverts[m], thr[m]):
                return False
    return True


@njit(cache=True)
def vertex_intervals(x, y, t0, t_end, mv, lo, hi, k):
    """Write the open safe intervals of a robot standing at ``(x, y)`` (pixels) over ``[t0,
    t_end]`` (time steps) into ``lo, hi`` from row ``k``; returns ``(lo, hi, k)``: the arrays
    (doubled where they were full) and the next free row. An interval starting at ``t0`` means
    the point is safe at ``t0``."""
    F = forbidden(x, y, 0.0, 0.0, 0.0, t0, t_end, mv)
    cur = t0
    for j in range(len(F) + 1):
        end = F[j, 0] if j < len(F) else t_end
        if end > cur:
            if k == len(lo):
                lo, hi = _doubled(lo), _doubled(hi)
            lo[k] = cur
            hi[k] = end
            k += 1
        if j < len(F):
            cur = F[j, 1]
    return lo, hi, k


@njit(cache=True)
def safe_intervals(nodes, t0, t_end, mv):
    """Open safe intervals of every node over ``[t0, t_end]``: CSR pointers ``(n + 1,)`` and
    the intervals' ends ``lo, hi`` (time steps); a node safe at ``t0`` starts with ``lo = t0``
    (each node's as :func:`vertex_intervals` gives them)."""
    n = len(nodes)
    ptr = np.zeros(n + 1, np.int64)
    lo = np.empty(16)
    hi = np.empty(16)
    k = 0
    for v in range(n):
        lo, hi, k = vertex_intervals(nodes[v, 0], nodes[v, 1], t0, t_end, mv, lo, hi, k)
        ptr[v + 1] = k
    return ptr, lo[:k], hi[:k]
