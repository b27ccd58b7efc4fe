"""The inevitable-collision rule under kinematic limits.

Without limits :class:`~mawdo.planning.safety.ics.SafeContinuation` lets the robot stop, start and
turn at once. With an acceleration or turn-rate limit (:class:`~mawdo.planning.safety.kinematics.
Limits`) that witness may not exist: a robot at speed ``u`` needs about ``|u|^2 / (2 a)`` px
and ``|u| / a`` steps to stop, and turns at most ``max_turn`` per step. :func:`limited_find`
is then the rule's search: every continuation starts from the robot's velocity ``vel`` (px per
step) and is *simulated* step by step through :func:`~mawdo.planning.safety.kinematics.project`, so
it meets every limit by construction (the projection's guarantee), and it ends at rest:

``"goal"``
    the plan's rest, followed as the run follows it (:func:`~mawdo.planning.safety.kinematics.
    wanted_step`: a carrot ``v`` px ahead, braking to stop at the goal, slowing for turns);
``"wait"``
    braking along the current heading (``project(0, u)``: ``|u|`` falls by ``max_accel`` per
    step) until rest, then standing;
``"spot"``
    ``k`` steps (``k`` in ``hops``) wanting full speed along one of the headings, then braking
    to rest, then standing.

The executed motion is straight and uniform between integer steps, so the simulated polyline,
timed one step per vertex, *is* the motion the run could drive; it is tested exactly as the
rule tests any timed polyline (:meth:`~mawdo.planning.safety.ics.SafeContinuation.path_safe`, then
:meth:`~mawdo.planning.safety.ics.SafeContinuation.wait_safe` at the point of rest). So a
continuation found here is a witness that a motion within the limits stays safe until the
horizon's end: conservative (the rule may miss a cleverer motion), never optimistic.

A robot on a followed timed route that the safe-interval guide timed within the limits (its
waits included) first offers that route's rest as the continuation (``TimedRun._timed_keeps``
in :mod:`mawdo.planning.guide.timeguide`), tested with the same exact ``path_safe``; the kinds above
come after it.
"""

from __future__ import annotations

import numpy as np

from mawdo.planning.safety.kinematics import project, turned, wanted_step
from mawdo.planning.world.path import advance, polyline_length

__all__ = ["limited_find"]


def _brake(points: list, u: np.ndarray, limits, cap: int) -> list:
    """``points`` extended by the steps that brake velocity ``u`` to rest (at most ``cap``)."""
    zero = np.zeros(2)
    for _ in range(cap):
        if not (u[0] or u[1]):
            break
        u = project(zero, u, limits)
        points.append(points[-1] + u)
    return points


def _ends_at_rest(ics, kind: str, points: list, t: float, end: float, t0: float, mv):
    """The continuation ``points`` (one per step from ``t``; statics, border and movers),
    the last one at rest until ``end``, when it is safe; else None."""
    pts = np.asarray(points, dtype=float)
    times = t + np.arange(len(pts), dtype=float)
    if len(pts) > 1 and not ics.path_safe(pts, times, t0, mv):
        return None
    if times[-1] < end:
        if not ics.wait_safe(pts[-1], times[-1], end, t0, mv):
            return None
        pts, times = np.vstack([pts, pts[-1]]), np.append(times, end)
    return kind, pts, times


def _follow(ics, route, p, vel, t: float, end: float, t0: float, mv, turn):
    """The plan's rest from ``p`` followed within the limits until the goal or ``end``."""
    lim, v = ics.limits, ics.v
    pts, u, rest = [np.asarray(p, float)], np.asarray(vel, float), np.asarray(route, float)
    heading, still = turn
    goal = rest[-1]
    for _ in range(int(np.ceil(max(end - t, 0.0)))):
        if np.hypot(*(goal - pts[-1])) <= 1e-9:
            break
        target, after, _, _ = advance(rest, v)
        want = target - pts[-1]
        left = float(np.hypot(*want)) + polyline_length(after)
        u = project(wanted_step(want, left, u, lim), u, lim, heading, still)
        heading, still = turned(u, heading, still)
        to = pts[-1] + u
        pts.append(to)
        rest = after if np.max(np.abs(to - target)) <= 1e-12 else np.vstack([to, after])
    arr = np.asarray(pts)
    times = t + np.arange(len(arr), dtype=float)
    if len(arr) > 1 and not ics.path_safe(arr, times, t0, mv):
        return None
    return "goal", arr, times


def limited_find(
    ics, p, t: float, t0: float, vel, route=None, wait_first=False, mv=None, turn=None
):  # fmt: skip
    """:meth:`~mawdo.planning.safety.ics.SafeContinuation.find` for a robot at ``p`` (pixels) moving
    at ``vel`` (px per step) at time ``t``, under ``ics.limits`` (module docstring); the same
    order: the plan's rest (unless ``wait_first``), braking, escape moves. ``turn``: the robot's
    ``(heading, still)`` (:func:`~mawdo.planning.safety.kinematics.turned`; None: not moved
    yet), so that a continuation from rest turns in place as the run would. Returns ``(kind,
    points, times)`` (a :class:`~mawdo.planning.safety.ics.Continuation`'s fields) or None."""
    p, vel = np.asarray(p, dtype=float), np.asarray(vel, dtype=float)
    turn = (None, 0) if turn is None else turn
    end = t0 + ics.horizon
    mv = ics.movers(t0, near=(p, t)) if mv is None else mv
    cap = int(np.ceil(end - t)) + 1
    along = None if route is None else _follow(ics, route, p, vel, t, end, t0, mv, turn)
    if along is not None and not wait_first:
        return along
    found = _ends_at_rest(ics, "wait", _brake([p], vel, ics.limits, cap), t, end, t0, mv)
    if found is not None:
        return found
    for k, offsets in ics._moves:
        if t + k >= end:
            break
        for off in offsets / k:
            pts, u, (heading, still) = [p], vel, turn
            for _ in range(k):
                u = project(off, u, ics.limits, heading, still)
                heading, still = turned(u, heading, still)
                pts.append(pts[-1] + u)
            pts = _brake(pts, u, ics.limits, cap)
            found = _ends_at_rest(ics, "spot", pts, t, end, t0, mv)
            if found is not None:
                return found
    return along
