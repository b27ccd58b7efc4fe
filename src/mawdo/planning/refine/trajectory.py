"""A timed route re-driven under acceleration and turn-rate limits: corners rounded, speed kept.

The safe-interval guide times a route under ``max_accel`` / ``max_turn`` from rest to rest on
every edge and turns in place at every vertex (:mod:`mawdo.planning.guide.sipp.profile`). This
module drives the same vertices along a *corner-smoothed path*: the corner at vertex ``V`` with
turn angle ``theta`` is replaced by the circular arc tangent to both legs at distance ``e``
from ``V`` (radius ``R = e / tan(theta / 2)``), crossed at a constant *carried speed*
``c <= c_max(R)``, and the speed along the path comes from a discrete forward pass with look-ahead
(:func:`speed_pass`). Vertices where the robot must stop (the route's waits, corners left sharp,
half turns) split the path into stretches driven from rest to rest; at a stop the robot stands
as long as the turn needs (and, at a wait, until the route's own departure).

Per step ``k`` (positions at integer steps, ``w_k`` px covered along the path), with ``a`` the
acceleration limit and ``v`` the speed cap (both less the projection's slack):

* ``w_k <= min(v, w_{k-1} + a)`` (``0.8 a`` for a step that touches an arc or follows one:
  the chords' own change of direction uses the rest of the budget);
* on an arc (a step overlapping it): ``w_k <= c``, where ``c_max = min(v, 0.9 R max_turn,
  sqrt(0.55 a R))``: consecutive chords of an arc turn by ``w / R`` (within ``max_turn``) and
  change the velocity by ``w^2 / R`` (within ``0.55 a``);
* before an arc starting ``d`` px ahead: ``w_k <= W(d, c, 0.8 a)`` (Eq. 1,
  :func:`brake_bound`): the most speed from which braking by ``b`` per step,
  ``w, w - b, ...``, makes every step faster than ``c`` end before the arc. Braking hard from
  ``w_k`` is then a feasible continuation, so the next step's bound is at least ``w_k - b``:
  the pass never has to brake harder than ``b``;
* before the stretch's end ``d`` px ahead: ``w_k <= min(W(d, 0, 0.95 a), d)``: it lands on
  the end with a last step of at most ``0.95 a``. ``W(d, 0, b)`` needs at least the distance
  of the run's continuous stopping speed
  (:func:`~mawdo.planning.safety.kinematics.stopping_speed`, ``n b`` with ``n (n + 1) b / 2 =
  d``): at ``w = (j - 1 + f) b`` the discrete braking covers ``b f (1 - f) / 2`` px more, so a
  step the pass allows is one the run's stopping test allows; ``0.95`` covers the chords
  being shorter than the arcs they cut, which that test measures.

These keep the limits with margin; whether a trajectory meets them exactly is then decided by
the run's own step (:func:`~mawdo.planning.refine.trajectory_search.replay`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["SmoothPath", "brake_bound", "route_stops", "speed_pass", "turn_angle"]

#: Share of the acceleration limit a step touching an arc may use for its change of speed.
ARC_ACCEL = 0.8
#: Share of the acceleration limit the centripetal change of velocity on an arc may use.
ARC_CENTRIPETAL = 0.55
#: Share of the turn-rate limit an arc's chords may use.
ARC_TURN = 0.9
#: Share of the acceleration limit of the braking to a stop (the chords are shorter than the
#: arcs they cut, and the run's stopping test measures chords).
END_BRAKE = 0.95
#: Turn angle (radians) above which a corner is always a stop (no useful arc fits).
MAX_ROUND_TURN = 2.6
#: Turn angle (radians) at or below which a vertex is no corner: it is driven straight through.
STRAIGHT = 1e-9


def turn_angle(a, b) -> float:
    """Angle (radians, in [0, pi]) between two directions ``a`` and ``b`` (any lengths > 0)."""
    return abs(math.atan2(a[0] * b[1] - a[1] * b[0], float(a @ b)))


@njit(cache=True)
def brake_bound(d: float, c: float, b: float, v: float) -> float:
    """Eq. 1: the most speed ``w <= v`` (px per step) from which braking by ``b`` (px per step
    squared) per step makes every step faster than ``c`` end within ``d`` px; at least ``c``.

    Braking from ``w in (c + (j - 1) b, c + j b]`` takes ``j`` steps faster than ``c``, which
    cover ``j w - b j (j - 1) / 2`` px, so the bound is the largest ``min(c + j b, (d + b j
    (j - 1) / 2) / j)`` over the ``j`` where it exceeds ``c + (j - 1) b`` (a condition that,
    once false, stays false for larger ``j``). Without a braking limit (``b = inf``) a step
    either ends within ``d`` or is at most ``c``: ``max(d, c)``."""
    if not math.isfinite(b):
        return min(v, max(d, c))
    best, j = min(c, v), 1
    while c + (j - 1) * b < v:
        top = min(c + j * b, (d + 0.5 * b * j * (j - 1)) / j, v)
        if top <= c + (j - 1) * b:
            break
        best, j = max(best, top), j + 1
    return best


def route_stops(points, times, eps: float = 1e-9):
    """The vertices of a timed route (pixels, time steps): ``(V, arrive, depart)``, each group of
    equal consecutive points one vertex (``arrive`` its first time, ``depart`` its last), collinear
    vertices where the route does not stand dropped (the profile's piece boundaries)."""
    P, T = np.asarray(points, float), np.asarray(times, float)
    groups = []
    for p, t in zip(P, T, strict=True):
        if groups and np.max(np.abs(p - groups[-1][0])) <= eps:
            groups[-1][2] = t
        else:
            groups.append([p, t, t])
    keep = [groups[0]]
    for g, nxt in zip(groups[1:-1], groups[2:], strict=True):
        a, b = g[0] - keep[-1][0], nxt[0] - g[0]
        if turn_angle(a, b) > 1e-6 or g[2] - g[1] > eps:
            keep.append(g)
    if len(groups) > 1:
        keep.append(groups[-1])
    V = np.array([g[0] for g in keep])
    return V, np.array([g[1] for g in keep]), np.array([g[2] for g in keep])


class SmoothPath:
    """A polyline ``V`` (pixels, shape (n, 2)) with its inner corners ``i`` rounded by arcs
    tangent at distance ``e[i - 1]`` px from the vertex (0: not rounded; the corner must then
    be straight). ``regions``: per piece ``(start, end, R)`` along the path (px; ``R = inf``
    for a line), in order; ``leg``: the leg (or, for an arc, the corner) of each."""

    def __init__(self, V: np.ndarray, e: np.ndarray) -> None:
        d = np.diff(V, axis=0)
        lens = np.hypot(d[:, 0], d[:, 1])
        u = d / lens[:, None]
        # pieces: ("line", a, b) or ("arc", centre, start point, sign, R, angle)
        self.pieces, starts, s, at = [], [], 0.0, V[0]
        self.regions, self.leg = [], []
        for i in range(len(V) - 1):
            e_out = e[i] if i + 1 < len(V) - 1 else 0.0
            if e_out > 0.0 and turn_angle(u[i], u[i + 1]) <= STRAIGHT:  # no corner to round (a
                e_out = 0.0  # wait on a straight line): an arc would have an infinite radius
            end = V[i + 1] - u[i] * e_out
            self._add(("line", at, end), starts, s)
            n = float(np.hypot(*(end - at)))
            self.regions.append((s, s + n, math.inf))
            self.leg.append(i)
            s += n
            if e_out > 0.0:
                din, dout = u[i], u[i + 1]
                cross = din[0] * dout[1] - din[1] * dout[0]
                theta = turn_angle(din, dout)
                R = e_out / math.tan(0.5 * theta)
                sign = 1.0 if cross > 0 else -1.0
                centre = end + R * sign * np.array([-din[1], din[0]])
                self._add(("arc", centre, end, sign, R, theta), starts, s)
                self.regions.append((s, s + R * theta, R))
                self.leg.append(i + 1)
                s += R * theta
                at = V[i + 1] + dout * e_out
            else:
                at = end
        self.starts, self.length = np.array(starts), s

    def _add(self, piece, starts, s) -> None:
        self.pieces.append(piece)
        starts.append(s)

    def at(self, s: np.ndarray) -> np.ndarray:
        """Points (pixels, shape (len(s), 2)) at arc lengths ``s`` (px, in ``[0, length]``)."""
        s = np.asarray(s, float)
        idx = np.clip(np.searchsorted(self.starts, s, side="right") - 1, 0, len(self.pieces) - 1)
        out = np.empty((len(s), 2))
        for j in np.unique(idx):
            sel = idx == j
            piece, x = self.pieces[j], s[sel] - self.starts[j]
            if piece[0] == "line":
                a, b = piece[1], piece[2]
                n = float(np.hypot(*(b - a)))
                w = np.minimum(x / n, 1.0) if n > 0 else np.zeros_like(x)
                out[sel] = a + w[:, None] * (b - a)
            else:
                _, c, p0, sign, R, theta = piece
                phi = np.minimum(x / R, theta) * sign
                r0 = p0 - c
                cs, sn = np.cos(phi), np.sin(phi)
                out[sel] = c + np.stack([cs * r0[0] - sn * r0[1], sn * r0[0] + cs * r0[1]], 1)
        return out


def speed_pass(length: float, regions, caps, w0: float, v: float, a: float, max_steps: int):
    """The distance along a stretch (px) reached after each step, from speed ``w0`` (px per
    step) to rest at ``length``, within the bounds of the module docstring; ``regions``
    ``(start, end, R)`` (``R = inf``: a line) with top speeds ``caps`` (px per step: on an arc
    its carried speed, on a line its cruise); ``a`` the acceleration (``inf`` for none). Each
    step takes the largest speed from which braking hard still meets every bound ahead
    (:func:`brake_bound`), so the next step can always brake: None only when ``w0`` is too
    fast for what lies ahead or the pass takes more than ``max_steps`` steps."""
    reg = np.asarray(regions, float).reshape(-1, 3)
    out = np.empty(max_steps)
    k = _speed_pass(float(length), reg, np.asarray(caps, float), float(w0), float(v), float(a), out)
    return None if k < 0 else out[:k].copy()


@njit(cache=True)
def _speed_pass(length, reg, caps, w0, v, a, out):
    """:func:`speed_pass` into ``out``: the steps taken, or -1."""
    s, w, touched, k = 0.0, w0, False, 0
    arc_a, end_b = ARC_ACCEL * a, END_BRAKE * a
    first = 0  # regions before it end behind the robot
    reach = v * (v / arc_a + 1.0)  # beyond it a region cannot bind (braking from v to rest)
    while s < length:
        if k >= len(out):
            return -1
        d_end = length - s
        bound = min(brake_bound(d_end, 0.0, end_b, v), d_end)
        while first < len(reg) and reg[first, 1] <= s:
            first += 1
        for j in range(first, len(reg)):
            st = reg[j, 0]
            bound = min(bound, caps[j] if s >= st else brake_bound(st - s, caps[j], arc_a, v))
            if st - s > reach:  # nor can any later one
                break
        nxt = min(w + a, bound)
        touch = False
        for j in range(first, len(reg)):
            if reg[j, 0] >= s + nxt:
                break
            touch |= reg[j, 2] < math.inf
        if touch or touched:  # a step on an arc or just after one: its chord turns too
            nxt = min(nxt, w + arc_a)
        touched = touch
        if nxt < w - a * (1.0 + 1e-9) or nxt <= 1e-12:
            return -1
        w = nxt
        s = length if w >= d_end - 1e-10 else s + w  # (a rounding short of the end: at it)
        out[k] = s
        k += 1
    return k
