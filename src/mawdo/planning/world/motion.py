"""Obstacle motion models: pure translations of a rigid shape over time.

Every model maps a time ``t`` (time steps, real, ``t >= 0`` for the random walk) to a translation
offset ``(dx, dy)`` in pixels, relative to the shape as written in the scenario (offset ``(0, 0)``
at ``t = 0``). Shapes never rotate.

Every model is piecewise linear in time, and :meth:`knots` returns the pieces of a time interval:
between consecutive knots the obstacle moves with constant velocity. The cost kernel and the
independent checker use the knots to turn "moving segment vs moving obstacle" into an exact static
test in the obstacle's frame.

Models
------
``Static``
    Offset is always ``(0, 0)``.
``ConstantVelocity``
    Moves at a fixed velocity and reflects at the map border. The position is the unfolded
    straight-line motion folded by a triangle wave (:func:`fold`), so it is exact at any ``t``
    without simulating the bounces.
``Patrol``
    Moves at a fixed speed along a closed route of offsets ``(0, 0) -> w1 -> ... -> wm -> (0, 0)``
    and repeats, optionally standing still at each point for a given time (a mover that parks).
``Track``
    Moves through given offsets at given times, linearly in between, and stands at the first
    (last) offset before (after) them: a realised trajectory recorded by the stepped world, or a
    predictor's forecast.
``BoundedRandomWalk``
    Every ``hold`` steps a new velocity is drawn uniformly from the disc of radius ``step``; the
    unfolded walk is folded into the map (:func:`fold`) at those times and the obstacle moves
    linearly in between. Deterministic for a given seed.
"""

from __future__ import annotations

import math
from bisect import bisect_left, bisect_right
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

__all__ = [
    "BoundedRandomWalk",
    "ConstantVelocity",
    "Motion",
    "Patrol",
    "Static",
    "Track",
    "fold",
    "fold_turn_times",
]

# Random-walk displacements are drawn in blocks of this many steps, each block from its own
# spawned seed, so the walk up to step n does not depend on how far ahead anyone asked.
_WALK_BLOCK = 256


def fold(u, lo, hi):
    """Fold unfolded positions ``u`` into ``[lo, hi]`` by a triangle wave (reflection).

    A point moving on the real line and reflecting elastically at ``lo`` and ``hi`` is at
    ``fold(u)`` when its unfolded (never reflected) position is ``u``. Requires ``lo <= u0 <= hi``
    for the starting point to be meaningful; works elementwise and broadcasts.

    Parameters
    ----------
    u : array_like
        Unfolded positions (pixels).
    lo, hi : array_like
        Reflection bounds (pixels), ``lo <= hi``. If ``hi == lo`` the result is ``lo``.

    Returns
    -------
    numpy.ndarray
        Folded positions (pixels), in ``[lo, hi]``.
    """
    u = np.asarray(u, dtype=float)
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    span = hi - lo
    safe = np.where(span > 0, span, 1.0)  # avoid 0/0; zero-span axes are pinned to lo below
    s = np.mod(u - lo, 2.0 * safe)
    folded = lo + np.where(s > safe, 2.0 * safe - s, s)
    return np.where(span > 0, np.clip(folded, lo, hi), lo)


def fold_turn_times(velocity: float, lo: float, hi: float, t0: float, t1: float) -> np.ndarray:
    """Times in the open interval ``(t0, t1)`` when a folded 1-D motion reverses direction.

    The unfolded position is ``velocity * t`` (it is 0 at ``t = 0``); it turns whenever it
    crosses ``lo + k (hi - lo)`` for an integer ``k``.

    Parameters
    ----------
    velocity : float
        Velocity component (pixels per time step).
    lo, hi : float
        Reflection bounds of the offset (pixels).
    t0, t1 : float
        Interval (time steps), ``t0 <= t1``.

    Returns
    -------
    numpy.ndarray
        Sorted turning times (time steps).
    """
    span = hi - lo
    if velocity == 0.0 or span <= 0.0 or t1 <= t0:
        return np.empty(0)
    a = (velocity * t0 - lo) / span
    b = (velocity * t1 - lo) / span
    ka, kb = min(a, b), max(a, b)
    if math.floor(ka) + 1.0 >= math.ceil(kb):  # no integer inside: the usual short interval
        return np.empty(0)
    k = np.arange(np.floor(ka) + 1.0, np.ceil(kb))  # integers strictly inside (ka, kb)
    times = (lo + k * span) / velocity
    times = times[(times > t0) & (times < t1)]  # guard against rounding at the ends
    return np.sort(times)


def _interval_knots(motion: Motion, inner: np.ndarray, t0: float, t1: float):
    """Knot times ``[t0, *inner, t1]`` (deduplicated) and the offsets there."""
    t0 = float(t0)
    t1 = float(t1)
    if t1 < t0:
        raise ValueError(f"knots need t0 <= t1, got t0={t0}, t1={t1}")
    if t1 == t0:
        times = np.array([t0])
    elif not inner.size:  # the usual piece: what np.unique gives, without the sort
        times = np.array([t0, t1])
    else:
        times = np.unique(np.concatenate(([t0], inner, [t1])))
    return times, motion.offset(times)


class Motion:
    """Base class: a piecewise-linear translation ``offset(t)`` (pixels) of a shape.

    Subclasses implement :meth:`offset` and :meth:`_inner_knots`.
    """

    #: True when the offset never changes (lets callers skip time handling).
    is_static: bool = False

    def offset(self, t) -> np.ndarray:
        """Translation at times ``t`` (time steps): shape ``t.shape + (2,)``, pixels."""
        raise NotImplementedError

    def _inner_knots(self, t0: float, t1: float) -> np.ndarray:
        raise NotImplementedError

    def knots(self, t0: float, t1: float) -> tuple[np.ndarray, np.ndarray]:
        """Constant-velocity pieces of ``[t0, t1]``.

        Parameters
        ----------
        t0, t1 : float
            Interval (time steps), ``t0 <= t1``.

        Returns
        -------
        times : numpy.ndarray, shape (m,)
            Strictly increasing knot times with ``times[0] == t0`` and ``times[-1] == t1``
            (``m == 1`` when ``t0 == t1``). Between consecutive knots the velocity is constant.
        offsets : numpy.ndarray, shape (m, 2)
            Offsets at the knots (pixels).
        """
        return _interval_knots(self, self._inner_knots(float(t0), float(t1)), t0, t1)


@dataclass(frozen=True)
class Static(Motion):
    """An obstacle that never moves."""

    is_static = True

    def offset(self, t) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        return np.zeros(t.shape + (2,))

    def _inner_knots(self, t0: float, t1: float) -> np.ndarray:
        return np.empty(0)


@dataclass(frozen=True)
class ConstantVelocity(Motion):
    """Constant velocity with elastic reflection at the map border (closed form).

    Parameters
    ----------
    velocity : array_like, shape (2,)
        Velocity (pixels per time step).
    lo, hi : array_like, shape (2,)
        Per-axis bounds of the offset that keep the shape inside the map (pixels):
        ``lo = -shape_min``, ``hi = map_size - shape_max``; ``lo <= 0 <= hi``.
    """

    velocity: tuple[float, float]
    lo: tuple[float, float]
    hi: tuple[float, float]

    @cached_property  # asked at every step and piece; the fields never change (frozen)
    def is_static(self) -> bool:  # type: ignore[override]
        span = np.subtract(self.hi, self.lo)
        return not np.any((np.asarray(self.velocity) != 0.0) & (span > 0.0))

    def offset(self, t) -> np.ndarray:
        t = np.asarray(t, dtype=float)[..., None]
        return fold(t * np.asarray(self.velocity), self.lo, self.hi)

    def _inner_knots(self, t0: float, t1: float) -> np.ndarray:
        turns = [
            fold_turn_times(self.velocity[a], self.lo[a], self.hi[a], t0, t1) for a in range(2)
        ]
        return np.concatenate(turns)


@dataclass(frozen=True, eq=False)
class Patrol(Motion):
    """Patrol at constant speed along a closed route of offsets, repeating forever.

    Parameters
    ----------
    route : array_like, shape (m, 2)
        Offsets visited in order (pixels); ``route[0]`` must be ``(0, 0)`` (where the shape is
        written). After the last point the obstacle returns to ``route[0]`` and starts again.
    speed : float
        Speed along the route (pixels per time step), ``>= 0``.
    waits : array_like, shape (m,), optional
        Time steps (>= 0) spent standing at each route point before leaving it (``waits[0]``
        at the start of every lap, from ``t = 0``): a mover that parks. ``None``: no stops.
    """

    route: np.ndarray
    speed: float
    waits: np.ndarray | None = None
    _cum: np.ndarray = field(init=False, repr=False)
    _lap: tuple = field(init=False, repr=False, default=())

    def __post_init__(self) -> None:
        route = np.asarray(self.route, dtype=float).reshape(-1, 2)
        closed = np.vstack([route, route[:1]])
        cum = np.concatenate(([0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))))
        object.__setattr__(self, "route", route)
        object.__setattr__(self, "_cum", cum)
        if self.waits is not None:
            waits = np.asarray(self.waits, dtype=float).reshape(-1)
            if waits.shape != (len(route),) or np.any(~np.isfinite(waits)) or np.any(waits < 0):
                raise ValueError(f"waits must be {len(route)} finite times >= 0, got {waits!r}")
            object.__setattr__(self, "waits", waits)
            if self.speed > 0 and cum[-1] > 0:
                object.__setattr__(self, "_lap", self._lap_table(closed, cum, waits))

    def _lap_table(self, closed, cum, waits) -> tuple[np.ndarray, np.ndarray]:
        """Knot times of one lap from 0 to the period and the offsets there: a stop is two
        knots at one position; zero-time entries (no wait, an empty leg) are dropped."""
        legs = np.diff(cum) / self.speed
        dt = np.ravel(np.column_stack([waits, legs]))  # wait at point j, then leg j -> j + 1
        after = np.stack([closed[:-1], closed[1:]], axis=1).reshape(-1, 2)  # where each ends
        keep = np.r_[True, dt > 0]
        times = np.concatenate(([0.0], np.cumsum(dt)))
        return times[keep], np.vstack([closed[:1], after])[keep]

    @property
    def period(self) -> float:
        """Time for one lap (time steps), stops included; ``inf`` for a static patrol."""
        total = self._cum[-1]
        if not (self.speed > 0 and total > 0):
            return np.inf
        return self._lap[0][-1] if self._lap else total / self.speed

    @cached_property  # asked at every step and piece; the fields never change (frozen)
    def is_static(self) -> bool:  # type: ignore[override]
        return not np.isfinite(self.period)

    @property
    def waypoint_times(self) -> np.ndarray:
        """Times in the first lap when the velocity changes (time steps): when each route
        point is reached and, with stops, when it is left."""
        if self._lap:
            return self._lap[0][:-1]
        return self._cum[:-1] / self.speed if not self.is_static else np.zeros(len(self.route))

    def offset(self, t) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        if self.is_static:
            return np.zeros(t.shape + (2,)) + self.route[0]
        if self._lap:
            lt, lp = self._lap
            u = np.mod(t, lt[-1])
            return np.stack([np.interp(u, lt, lp[:, 0]), np.interp(u, lt, lp[:, 1])], axis=-1)
        closed = np.vstack([self.route, self.route[:1]])
        s = np.mod(t * self.speed, self._cum[-1])
        # piece index: the last route point whose arc length is <= s
        i = np.clip(np.searchsorted(self._cum, s, side="right") - 1, 0, len(self.route) - 1)
        seg = self._cum[i + 1] - self._cum[i]
        frac = np.where(seg > 0, (s - self._cum[i]) / np.where(seg > 0, seg, 1.0), 0.0)
        return closed[i] + frac[..., None] * (closed[i + 1] - closed[i])

    def _inner_knots(self, t0: float, t1: float) -> np.ndarray:
        if self.is_static or t1 <= t0:
            return np.empty(0)
        period = self.period
        laps = np.arange(np.floor(t0 / period), np.floor(t1 / period) + 1.0)
        times = (laps[:, None] * period + self.waypoint_times[None, :]).ravel()
        return times[(times > t0) & (times < t1)]


@dataclass(frozen=True, eq=False)
class BoundedRandomWalk(Motion):
    """Seeded random walk folded into the map, piecewise linear in time.

    Every ``hold`` time steps a new velocity is drawn uniformly from the disc of radius ``step``
    and held; the unfolded positions at multiples of ``hold`` are folded into the map
    (:func:`fold`) and the obstacle moves linearly between them. Folding never lengthens a
    move, so the obstacle stays in the map and moves at most ``step`` pixels per time step.

    Parameters
    ----------
    step : float
        Largest speed (pixels per time step).
    lo, hi : array_like, shape (2,)
        Per-axis bounds of the offset that keep the shape in the map (pixels).
    seed : numpy.random.SeedSequence
        Source of the walk; the same seed gives the same walk.
    hold : int
        Time steps between velocity draws (>= 1).
    """

    step: float
    lo: tuple[float, float]
    hi: tuple[float, float]
    seed: np.random.SeedSequence
    hold: int = 1
    _walk: list = field(init=False, repr=False, default_factory=list)  # unfolded blocks cache
    # the folded positions of every block drawn so far (a one-item list, the dataclass is
    # frozen): cumsum and fold work element by element, so a prefix of them is what a shorter
    # walk gives, and offset() need not redo them over the whole walk at each call
    _folded: list = field(init=False, repr=False, default_factory=list)

    @cached_property  # asked at every step and piece; the fields never change (frozen)
    def is_static(self) -> bool:  # type: ignore[override]
        return self.step == 0.0 or bool(np.all(np.subtract(self.hi, self.lo) <= 0.0))

    def _block(self, b: int) -> np.ndarray:
        rng = np.random.default_rng(
            np.random.SeedSequence(self.seed.entropy, spawn_key=(*self.seed.spawn_key, b))
        )
        speed = self.step * np.sqrt(rng.random(_WALK_BLOCK))  # uniform in the disc
        angle = rng.uniform(0.0, 2.0 * np.pi, _WALK_BLOCK)
        return self.hold * np.stack([speed * np.cos(angle), speed * np.sin(angle)], axis=1)

    def unfolded(self, n: int) -> np.ndarray:
        """Unfolded positions at times ``0, hold, ..., n * hold`` (pixels), shape ``(n + 1, 2)``."""
        while len(self._walk) * _WALK_BLOCK < n:
            self._walk.append(self._block(len(self._walk)))
        moves = np.concatenate(self._walk)[:n] if n > 0 else np.empty((0, 2))
        return np.vstack([np.zeros((1, 2)), np.cumsum(moves, axis=0)])

    def offset(self, t) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        if t.size and np.min(t) < 0:
            raise ValueError("a random-walk obstacle is defined for t >= 0 only")
        if self.is_static:
            return np.zeros(t.shape + (2,))
        q = t / self.hold
        n = int(np.ceil(np.max(q))) + 1 if t.size else 1
        if not self._folded or len(self._folded[0]) < n + 1:
            self.unfolded(n)  # draws the blocks that cover n
            whole = fold(self.unfolded(len(self._walk) * _WALK_BLOCK), self.lo, self.hi)
            self._folded[:] = [whole]
        pos = self._folded[0]
        i = np.minimum(np.floor(q).astype(np.int64), n - 1)
        frac = (q - i)[..., None]
        return pos[i] + frac * (pos[i + 1] - pos[i])

    def _inner_knots(self, t0: float, t1: float) -> np.ndarray:
        if self.is_static:
            return np.empty(0)
        k = np.arange(np.floor(t0 / self.hold) + 1.0, np.ceil(t1 / self.hold))
        times = k * self.hold
        return times[(times > t0) & (times < t1)]


@dataclass(frozen=True, eq=False)
class Track(Motion):
    """Piecewise-linear motion through offsets at given times, at rest outside them.

    Parameters
    ----------
    times : array_like, shape (k,)
        Strictly increasing knot times (time steps), ``k >= 1``.
    offsets : array_like, shape (k, 2)
        Offsets at those times (pixels). Before ``times[0]`` the offset is ``offsets[0]``, after
        ``times[-1]`` it is ``offsets[-1]``.
    """

    times: np.ndarray
    offsets: np.ndarray

    def __post_init__(self) -> None:
        t = np.asarray(self.times, dtype=float).reshape(-1)
        o = np.asarray(self.offsets, dtype=float).reshape(-1, 2)
        if len(t) == 0 or len(o) != len(t):
            raise ValueError(f"a track needs k >= 1 times and k offsets, got {len(t)}, {len(o)}")
        # (a predicted track is made some forty times a step: the checks use array methods,
        # not NumPy's functions, whose wrappers cost more than the checks on a few knots)
        if not (np.isfinite(t).all() and np.isfinite(o).all()):
            raise ValueError("track times and offsets must be finite")
        if not (t[1:] > t[:-1]).all():  # finite: the same test as diff > 0
            raise ValueError("track times must be strictly increasing")
        object.__setattr__(self, "times", t)
        object.__setattr__(self, "offsets", o)
        # (the planner asks a predicted track for knots and offsets about a hundred times a
        # step: contiguous columns and a list of times spare each call its conversions)
        object.__setattr__(self, "_x", np.ascontiguousarray(o[:, 0]))
        object.__setattr__(self, "_y", np.ascontiguousarray(o[:, 1]))
        object.__setattr__(self, "_tlist", t.tolist())

    @property
    def is_static(self) -> bool:  # type: ignore[override]
        """Always False: a tracked or predicted agent is a mover even while it stands (a
        person at rest is not part of the map the guides are built on)."""
        return False

    @property
    def top_speed(self) -> float:
        """Largest speed between knots (pixels per time step)."""
        if len(self.times) < 2:
            return 0.0
        v = np.hypot(*np.diff(self.offsets, axis=0).T) / np.diff(self.times)
        return float(v.max())

    def offset(self, t) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        out = np.empty(t.shape + (2,))
        out[..., 0] = np.interp(t, self.times, self._x)
        out[..., 1] = np.interp(t, self.times, self._y)
        return out

    def _inner_knots(self, t0: float, t1: float) -> np.ndarray:
        # the knots strictly inside (t0, t1): the times are strictly increasing
        return self.times[bisect_right(self._tlist, t0) : bisect_left(self._tlist, t1)]

    def knots(self, t0: float, t1: float) -> tuple[np.ndarray, np.ndarray]:
        """Constant-velocity pieces of ``[t0, t1]`` (see :meth:`Motion.knots`); the same
        arrays, built without a sort: the inner knots already lie strictly between the ends."""
        t0, t1 = float(t0), float(t1)
        if not t1 > t0:  # a point, or the error
            return super().knots(t0, t1)
        inner = self._inner_knots(t0, t1)
        times = np.empty(len(inner) + 2)
        times[0], times[-1] = t0, t1
        times[1:-1] = inner
        return times, self.offset(times)
