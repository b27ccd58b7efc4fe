"""Edge timing of the safe-interval guide under acceleration and turn-rate limits.

With ``max_accel`` or ``max_turn`` set (:class:`~mawdo.planning.safety.kinematics.Limits`), each
edge of a timed route is driven from rest to rest in whole time steps, as the run's discrete time
does it: the robot's positions at integer steps, straight and uniform in between, step ``s``
covering ``w_s`` px along the edge. The fastest such profile over ``n`` steps covers

``D(n) = sum_s min(v, (s + 1) a, (n - s) a)``  (``s = 0 .. n - 1``)

px: it speeds up by ``a`` per step from rest, cruises at ``v``, and slows down by ``a`` per
step so that its last step is at most ``a`` (the next one may then be rest). An edge of ``L``
px takes the least ``n`` with ``D(n) >= L`` steps (:func:`edge_steps`), each step's speed
scaled by ``L / D(n) <= 1``, which keeps every limit: speeds, changes of speed and the last
step only shrink. For ``v = 3``, ``a = 1``: ``D(n) = 3 n - 6`` (``n >= 5``), so 200 px take
``ceil(206 / 3) = 69`` steps, ``L / v + v / a - 1`` rounded up (the continuous trapezoid's
``L / v + v / a``, less one step: a discrete step at speed ``a`` already counts whole).
Without an acceleration limit (``a = inf``) an edge takes ``ceil(L / v)`` uniform steps.

A profile is a few uniform pieces (:func:`edge_pieces`: one per step of speeding up and of
slowing down, one for the cruise), so the guide checks it exactly, piece by piece, with the
same closed-form tests as a straight uniform move (:mod:`mawdo.planning.guide.sipp.search`).

At a vertex where the heading changes the robot stands :func:`rest_steps` whole steps: it
turns in place at ``max_turn`` (``ceil(angle / max_turn)`` steps), and with an acceleration
limit it stands at least one step (its last step in, at up to ``a`` px, and its first step
out, at up to ``a``, would differ by up to ``2 a``). The checker counts a turn made at rest
against the steps it took (:mod:`mawdo.planning.judge.kincheck`): ``k`` steps at rest between
the last step in and the first step out allow ``(k + 1) max_turn``, one step more than this
turn time needs.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["edge_pieces", "edge_steps", "profile_table", "rest_steps"]


@njit(cache=True)
def _reach(n, v, a):
    """Most distance (px) ``n`` steps can cover from rest to rest: ``D(n)``."""
    d = 0.0
    for s in range(n):
        d += min(v, (s + 1) * a, (n - s) * a)
    return d


@njit(cache=True)
def edge_steps(L, v, a):
    """Whole steps ``n`` of the rest-to-rest profile over ``L`` px (speed cap ``v`` px per
    step, acceleration ``a`` px per step squared, ``inf`` for none) and the scale ``L / D(n)``
    of its speeds; ``(0, 0.0)`` for ``L <= 0``."""
    if L <= 0.0:
        return 0, 0.0
    # D(n) <= n v and D(n) <= a (n + 1)^2 / 4: the least n is at least either bound
    n = max(1, int(math.ceil(L / v)), int(math.ceil(2.0 * math.sqrt(L / a) - 1.0)) - 1)
    while _reach(n, v, a) < L:
        n += 1
    return n, L / _reach(n, v, a)


@njit(cache=True)
def edge_pieces(L, v, a):
    """The profile over ``L`` px as uniform pieces: arrays ``(k0, c0, dur, w)``; piece ``j``
    starts ``k0[j]`` steps after the departure, ``c0[j]`` px along the edge, and runs
    ``dur[j]`` steps at ``w[j]`` px per step (empty for ``L <= 0``)."""
    n, scale = edge_steps(L, v, a)
    k0, c0, dur, w = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    m, c, prev = 0, 0.0, -1.0
    for s in range(n):
        raw = min(v, (s + 1) * a, (n - s) * a)
        if m > 0 and raw == prev:  # the cruise (or a flat top): one piece
            dur[m - 1] += 1.0
        else:
            k0[m], c0[m], dur[m], w[m] = s, c, 1.0, scale * raw
            m += 1
        c += scale * raw
        prev = raw
    return k0[:m], c0[:m], dur[:m], w[:m]


@njit(cache=True)
def profile_table(weights, v, a):
    """:func:`edge_pieces` of every edge (lengths ``weights``, px) in one table: CSR pointers
    ``(len(weights) + 1,)``, the pieces' ``k0, c0, dur, w`` and each edge's steps ``T``."""
    E = len(weights)
    ptr = np.zeros(E + 1, np.int64)
    steps = np.zeros(E)
    for e in range(E):
        n, _ = edge_steps(weights[e], v, a)
        steps[e] = n
        ptr[e + 1] = ptr[e] + n  # at most n pieces (compacted below)
    k0, c0, dur, w = np.empty(ptr[-1]), np.empty(ptr[-1]), np.empty(ptr[-1]), np.empty(ptr[-1])
    for e in range(E):
        pk, pc, pd, pw = edge_pieces(weights[e], v, a)
        j = ptr[e]
        k0[j : j + len(pk)], c0[j : j + len(pk)] = pk, pc
        dur[j : j + len(pk)], w[j : j + len(pk)] = pd, pw
        ptr[e + 1] = j + len(pk)
    return ptr, k0, c0, dur, w, steps


@njit(cache=True)
def rest_steps(hx, hy, dx, dy, accel_on, turn):
    """Whole steps at rest at a vertex entered with unit heading ``h`` (zero: none, the robot
    was at rest with no heading) and left with unit heading ``d`` (zero: no move):
    ``ceil(angle / turn)`` (``turn`` in radians per step, ``inf`` for none), at least one with
    an acceleration limit (``accel_on``); none where the heading does not change, and none
    without limits (instant turns and stops)."""
    if turn == math.inf and not accel_on:
        return 0.0
    if (hx == 0.0 and hy == 0.0) or (dx == 0.0 and dy == 0.0):
        return 0.0
    ang = abs(math.atan2(hx * dy - hy * dx, hx * dx + hy * dy))
    if ang <= 1e-9:
        return 0.0
    k = math.ceil(ang / turn)
    return float(max(k, 1) if accel_on else k)
