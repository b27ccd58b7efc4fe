"""How the inevitable-collision rule's continuations are driven, with or without kinematic limits.

:meth:`~mawdo.planning.safety.ics.SafeContinuation.find` is one search (the plan's rest, a stop,
escape moves; each checked exactly, then a rest until the horizon's end); what a continuation
drives is the *drive* :func:`continuation_drive` returns for the rule's limits:

:class:`InstantDrive` (no acceleration or turn-rate limit, or no velocity given)
    the robot stops, starts and turns at once at up to its full speed ``v``: ``"goal"`` is the
    plan's rest driven as it is, ``"wait"`` stands where it is, ``"spot"`` is one straight move
    of ``k`` whole steps along one of the headings;
:class:`LimitedDrive` (an acceleration or turn-rate limit, :class:`~mawdo.planning.safety.
kinematics.Limits`)
    a robot at speed ``u`` needs about ``|u|^2 / (2 a)`` px and ``|u| / a`` steps to stop and
    turns at most ``max_turn`` per step, so every continuation starts from the robot's velocity
    and is *simulated* step by step through :func:`~mawdo.planning.safety.kinematics.project`
    (it meets every limit by construction) and ends at rest: ``"goal"`` follows the plan's rest
    as the run follows it (:func:`~mawdo.planning.safety.kinematics.wanted_step`: a carrot ``v``
    px ahead, braking to stop at the goal, slowing for turns), ``"wait"`` brakes along the
    current heading (``project(0, u)``: ``|u|`` falls by ``max_accel`` per step) until rest,
    ``"spot"`` wants full speed along one of the headings for ``k`` steps, then brakes.

The executed motion is straight and uniform between whole steps, so a simulated polyline, timed
one step per vertex, *is* a motion the run could drive; checked exactly like any continuation,
it is a witness that a motion within the limits stays safe until the horizon's end:
conservative (the rule may miss a cleverer motion), never optimistic. A robot on a followed
timed route that the safe-interval guide timed within the limits first offers that route's rest
(``TimedRun._timed_keeps`` in :mod:`mawdo.planning.guide.timeguide`); the kinds above come after.

The two drives keep two formulas for "follow" and "escapes": a simulation with no limit would
drive the same routes in whole steps (cutting the plan's corners by its carrot, adding ``k``
equal steps instead of one move of ``k`` steps), which is other points and other floating-point
values, so other verdicts at touching contacts. The braking is one (none at all without limits).
"""

from __future__ import annotations

import numpy as np

from mawdo.planning.safety.kinematics import project, turned, wanted_step
from mawdo.planning.world.path import advance, polyline_length, segment_lengths

__all__ = ["InstantDrive", "LimitedDrive", "continuation_drive"]


def continuation_drive(limits, v: float, vel, turn, cap: int):
    """The drive of continuations under ``limits`` (None: :class:`InstantDrive` at speed ``v``,
    px per step), else :class:`LimitedDrive` from velocity ``vel`` and heading state ``turn``,
    braking within ``cap`` steps."""
    return InstantDrive(v) if limits is None else LimitedDrive(limits, v, vel, turn, cap)


class InstantDrive:
    """Continuations without limits: full speed ``v`` (px per step) at once, stops at once."""

    def __init__(self, v: float) -> None:
        self.v = v

    def follow(self, route, p, t: float, end: float):
        """The plan's rest at full speed (straight and uniform between its vertices), cut at
        ``end``: ``(points, times)``."""
        pts = np.asarray(route, dtype=float)
        times = t + np.concatenate([[0.0], np.cumsum(segment_lengths(pts))]) / self.v
        if times[-1] > end:  # cut at the horizon's end
            k = int(np.searchsorted(times, end, side="right"))
            last, _, _, _ = advance(pts, (end - t) * self.v)
            pts, times = np.vstack([pts[:k], last]), np.append(times[:k], end)
        return pts, times

    def brake(self, points: list) -> list:
        return points  # a stop takes no time

    def escapes(self, p, t: float, k: int, offsets):
        """Per heading, the straight move of ``k`` steps by ``offsets[i]`` (pixels):
        ``[(points, times)]`` and the moves' starts and ends."""
        times, paths = np.array([t, t + k]), np.empty((len(offsets), 2, 2))
        paths[:, 0], paths[:, 1] = p, p + offsets
        return [(q, times) for q in paths], paths[:, 0], paths[:, 1]


class LimitedDrive:
    """Continuations within ``limits`` from velocity ``vel`` (px per step) and heading state
    ``turn`` (``(heading, still)``; None: not moved yet), one vertex per step; braking takes
    at most ``cap`` steps."""

    def __init__(self, limits, v: float, vel, turn, cap: int) -> None:
        self.limits, self.v, self.cap = limits, v, cap
        self.vel = np.asarray(vel, dtype=float)
        self.turn = (None, 0) if turn is None else turn

    def brake(self, points: list, u=None) -> list:
        """``points`` extended by the steps that brake velocity ``u`` (default ``vel``) to
        rest."""
        u, zero = self.vel if u is None else u, np.zeros(2)
        for _ in range(self.cap):
            if not (u[0] or u[1]):
                break
            u = project(zero, u, self.limits)
            points.append(points[-1] + u)
        return points

    def follow(self, route, p, t: float, end: float):
        """The plan's rest from ``p`` followed as the run follows it until the goal or
        ``end``: ``(points, times)``."""
        lim, v = self.limits, self.v
        pts, u, rest = [np.asarray(p, float)], self.vel, np.asarray(route, float)
        heading, still = self.turn
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
        return arr, t + np.arange(len(arr), dtype=float)

    def escapes(self, p, t: float, k: int, offsets):
        """Per heading, ``k`` steps wanting ``offsets[i] / k`` each, then braking to rest;
        with every step's start and end (as :meth:`InstantDrive.escapes`)."""
        out = []
        for off in offsets / k:
            pts, u, (heading, still) = [p], self.vel, self.turn
            for _ in range(k):
                u = project(off, u, self.limits, heading, still)
                heading, still = turned(u, heading, still)
                pts.append(pts[-1] + u)
            pts = np.asarray(self.brake(pts, u), dtype=float)
            out.append((pts, t + np.arange(len(pts), dtype=float)))
        a = np.concatenate([pts[:-1] for pts, _ in out])
        return out, a, np.concatenate([pts[1:] for pts, _ in out])
