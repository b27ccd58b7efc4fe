"""Opt-in kinematic limits of the robot: speed, acceleration, turn rate.

The executed motion is the robot's positions at integer time steps, straight and uniform in
between, so its velocity over step ``s`` is ``u_s = p[s + 1] - p[s]`` (px per step). The
limits (:class:`Limits`, from ``PlannerConfig.max_speed``, ``max_accel``, ``max_turn``) are

* speed: ``|u_s| <= max_speed``;
* acceleration: ``|u_s - u_{s-1}| <= max_accel`` (px per step squared; ``u_{-1} = 0``: the
  robot starts at rest);
* turn rate: the heading turns by at most ``max_turn`` radians per step, standing steps
  included: between two moves ``u_i`` and ``u_j`` (``i < j``, the robot at rest in between) the
  angle is at most ``(j - i) max_turn``. A robot at rest keeps the heading of its last move
  and turns in place; only before its first move may it take any heading.

:func:`project` turns a wanted velocity into the nearest one the limits allow, in that order
(speed clamp, acceleration projection, turn clamp): the acceleration projection stays inside
the speed disc (a point between two points of a disc), and turning toward the previous
heading at the same speed only brings the velocity closer to the previous one, so the result
meets all three. From rest, a move whose heading is beyond what the standing steps have turned
is not taken: the robot stands one more step, turning in place (:func:`turned` keeps the
heading and the standing steps). :class:`LimitedRun` drives every step of a run through it (the
guard checks the move actually driven); :func:`turn_penalty` is the refinement's share (the
candidate cost grows with each corner's turn beyond what one step allows). The independent
checker's verdict is :func:`mawdo.planning.judge.kincheck.check_kinematics`.

A speed limit below the scenario's robot speed is the robot's speed for the whole run
(:func:`at_speed`): the refinement's cost, the guard, the inevitable-collision rule and the
safe-interval guide all time their paths at ``max_speed`` (less :data:`SLACK`), so a stretch
is checked as it will be driven and the time guide's edges take ``length / max_speed`` steps.
With an acceleration or turn-rate limit the inevitable-collision rule checks every step as
driven: the projected step must leave a continuation simulated within the limits from the
new velocity (:mod:`mawdo.planning.safety.ics_limits`), else another projected heading that does,
else the robot brakes toward rest (a hit it cannot escape then finds it at rest: passive).
With an acceleration or turn-rate limit the safe-interval guide times its routes as the
robot drives them (:mod:`mawdo.planning.guide.sipp.profile`: each edge from rest to rest in whole
steps, turns in place at its vertices), the run follows such a route step for step, and the
rule takes the route's own rest as a continuation when the robot is on it; the refinement's
turn penalty only steers candidates away from sharp corners. With ``refine_trajectory`` (on by
default) the swarm first searches a faster drive of that route, corners rounded and speed
carried through them (:mod:`mawdo.planning.refine.trajectory_search`), which the run follows
instead when it is strictly earlier and every step passes this projection unchanged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mawdo.planning.world.path import polyline_length, unit_headings

__all__ = [
    "Limits",
    "LimitedRun",
    "at_speed",
    "limits_refusal",
    "project",
    "stopping_speed",
    "turn_penalty",
    "turned",
    "wanted_step",
]

#: Weight of :func:`turn_penalty` in the refinement's cost (px per radian of excess turn).
TURN_WEIGHT = 100.0
#: Slack (relative) left inside each limit, so that rounding never reads as a violation.
SLACK = 1e-9
#: A move this short (pixels) is the robot at rest: it keeps its heading.
REST_TOL = 1e-9


@dataclass(frozen=True)
class Limits:
    """Kinematic limits; ``None`` leaves a quantity free.

    Attributes
    ----------
    speed : float or None
        Most distance per step (px per step, > 0).
    accel : float or None
        Most change of velocity per step (px per step squared, > 0).
    turn : float or None
        Most change of heading per step between two moves (radians per step, in (0, pi]).
    """

    speed: float | None = None
    accel: float | None = None
    turn: float | None = None

    @classmethod
    def of(cls, config, speed: float | None = None) -> Limits | None:
        """The limits of a :class:`~mawdo.planning.run.config.PlannerConfig` that constrain
        anything, or ``None`` when none does (the planner then runs as without this module).

        With the robot's ``speed`` (px per step) given, a limit that constrains nothing is
        dropped: a speed cap at or above it, an acceleration of ``2 v`` or more (``v`` the
        speed within the cap: no change of velocity exceeds ``2 v``) and a turn rate of
        ``pi`` or more (no change of heading exceeds ``pi``).
        """
        top, accel, turn = config.max_speed, config.max_accel, config.max_turn
        if speed is not None:
            v = speed if top is None else min(speed, top)
            top = None if top is not None and top >= speed else top
            accel = None if accel is not None and accel >= 2.0 * v else accel
            turn = None if turn is not None and turn >= math.pi else turn
        lim = cls(top, accel, turn)
        return None if lim == cls() else lim


def at_speed(scenario, max_speed: float | None):
    """``scenario`` with its robot's speed lowered to ``max_speed`` (less :data:`SLACK`, the
    projection's own margin, so a planned step is never clamped) when that is slower; else
    ``scenario`` itself (the same object: a run without a speed limit is unchanged).

    Parameters
    ----------
    scenario : Scenario
    max_speed : float or None
        Speed limit (px per step, > 0), or None for none.
    """
    if max_speed is None:
        return scenario
    speed = float(max_speed) * (1.0 - SLACK)
    if speed >= scenario.robot_speed:
        return scenario
    robot = scenario.spec.robot.model_copy(update={"speed": speed})
    spec = scenario.spec.model_copy(update={"robot": robot})
    return type(scenario)(spec=spec, obstacles=scenario.obstacles)


def limits_refusal(limits: Limits, distance: float, steps: int) -> str | None:
    """Why ``limits`` cannot bring the robot to a goal ``distance`` px away (straight line, a
    lower bound on any route) within ``steps`` steps, naming the range that can; None when
    they can.

    From rest to rest in ``n`` steps the robot covers at most ``n max_speed`` px and, speeding
    up and slowing down by ``max_accel`` per step, at most ``max_accel (n + 1)^2 / 4`` px; every
    turn up to a half turn (``pi``) must fit in the step limit at ``max_turn`` per step.
    """
    n = int(steps)
    how = f"within the run's step limit of {n:,} steps"
    more = "; or allow more steps (max_steps, CLI --max-steps)"
    if limits.speed is not None and distance > n * limits.speed:
        return (
            f"max_speed={limits.speed:g} px per step cannot cover the {distance:.1f} px from "
            f"start to goal {how}: use max_speed >= {distance / n:.3g}{more}"
        )
    if limits.accel is not None and distance > limits.accel * (n + 1) ** 2 / 4.0:
        need = 2.0 * math.sqrt(distance / limits.accel) - 1.0
        return (
            f"max_accel={limits.accel:g} px per step squared cannot bring the robot from rest "
            f"over the {distance:.1f} px from start to goal {how} (it needs at least "
            f"{need:,.0f}): use max_accel >= {4.0 * distance / (n + 1) ** 2:.3g}{more}"
        )
    if limits.turn is not None and limits.turn * n < math.pi:
        return (
            f"max_turn={limits.turn:g} radians per step cannot fit a half turn {how} (it "
            f"needs {math.pi / limits.turn:,.0f}): use max_turn >= {math.pi / n:.3g}{more}"
        )
    return None


def _rotate(v: np.ndarray, ang: float) -> np.ndarray:
    c, s = math.cos(ang), math.sin(ang)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def project(want, prev, limits: Limits, heading=None, still: int = 0) -> np.ndarray:
    """The velocity (px per step) nearest ``want`` that ``limits`` allow after ``prev`` (the
    previous step's velocity; zeros at rest); see the module docstring for the order.

    ``heading`` (a unit vector, or None before the first move) and ``still`` (steps stood since
    the last move, >= 0) are the robot's :func:`turned` state: from rest a move is taken only
    within ``(still + 1) max_turn`` of the heading, else the robot stands (zero velocity).
    """
    u = np.asarray(want, dtype=float).copy()
    prev = np.asarray(prev, dtype=float)
    if limits.speed is not None:
        top = limits.speed * (1.0 - SLACK)
        n = math.hypot(*u)
        if n > top:
            u *= top / n
    if limits.accel is not None:
        top = limits.accel * (1.0 - SLACK)
        d = u - prev
        n = math.hypot(*d)
        if n > top:
            u = prev + d * (top / n)
    speed, before = math.hypot(*u), math.hypot(*prev)
    if limits.turn is None or speed <= REST_TOL:
        return u
    if before > REST_TOL:
        cross = prev[0] * u[1] - prev[1] * u[0]
        ang = math.atan2(cross, float(prev @ u))
        top = limits.turn * (1.0 - SLACK)
        if abs(ang) > top:
            u = _rotate(prev * (speed / before), math.copysign(top, ang))
    elif heading is not None:  # at rest: the standing steps turned it in place
        h = heading
        ang = abs(math.atan2(h[0] * u[1] - h[1] * u[0], h[0] * u[0] + h[1] * u[1]))
        if ang > (still + 1) * limits.turn * (1.0 - SLACK):
            return np.zeros(2)
    return u


def turned(u, heading, still: int):
    """The robot's heading state after a step of velocity ``u`` (px per step): ``(unit heading
    of u, 0)`` after a move, ``(heading, still + 1)`` after a standing step (a move of at most
    :data:`REST_TOL` px); ``heading`` None is a robot that has not moved yet."""
    n = math.hypot(*u)
    if n > REST_TOL:
        return np.asarray(u, dtype=float) / n, 0
    return heading, still + 1


def stopping_speed(distance: float, accel: float) -> float:
    """Most speed (px per step) from which the robot can stop within ``distance`` px, braking
    by ``accel`` per step: the speed ``n a`` whose steps ``n a, (n - 1) a, ..., a`` add up to
    ``distance``, i.e. ``n (n + 1) a / 2 = distance``."""
    return accel * (math.sqrt(2.0 * distance / accel + 0.25) - 0.5)


def wanted_step(want, left: float, prev, limits: Limits) -> np.ndarray:
    """The step (px) the run asks of the projection when the plan wants ``want`` with
    ``left`` px of plan to go (this step's included) after velocity ``prev`` (px per step):
    slower so as to stop at the goal within ``max_accel`` (:func:`stopping_speed`), and
    slower where the heading is beyond one step's ``max_turn`` (the last speed less
    ``max_accel``, or rest without an acceleration limit): the robot brakes while it turns,
    and from rest it turns in place (:func:`project`), so it never circles a point it cannot
    turn to."""
    want = np.asarray(want, dtype=float)
    n = float(np.hypot(*want))
    if limits.accel is not None and n > 0.0:
        want = want * min(1.0, stopping_speed(left, limits.accel) / n)
        n = float(np.hypot(*want))
    before = float(np.hypot(*prev))
    if limits.turn is None or n == 0.0 or before == 0.0:
        return want
    cos = float(want @ prev) / (n * before)
    if math.acos(max(-1.0, min(1.0, cos))) <= limits.turn:
        return want
    slow = 0.0 if limits.accel is None else max(before - limits.accel, 0.0)
    return want * min(1.0, slow / n)


def turn_penalty(X: np.ndarray, start, goal, max_turn: float, weight: float) -> np.ndarray:
    """Per candidate ``X`` (``(n, 2m)`` waypoints, pixels; the path start -> waypoints ->
    goal): ``weight`` (px per radian) times the sum over its corners of the turn beyond
    ``max_turn`` (radians); zero-length segments are skipped."""
    n = len(X)
    P = np.concatenate(
        [np.broadcast_to(start, (n, 1, 2)), X.reshape(n, -1, 2), np.broadcast_to(goal, (n, 1, 2))],
        axis=1,
    )
    d = np.diff(P, axis=1)
    a, b = d[:, :-1], d[:, 1:]
    cross = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    dot = np.sum(a * b, axis=-1)
    moving = (np.hypot(a[..., 0], a[..., 1]) > 0) & (np.hypot(b[..., 0], b[..., 1]) > 0)
    turn = np.where(moving, np.abs(np.arctan2(cross, dot)), 0.0)
    return weight * np.sum(np.maximum(turn - max_turn, 0.0), axis=1)


class LimitedRun:
    """The run loop's use of :class:`Limits` (mixed into :class:`~mawdo.planning.run.execute.Run`,
    which sets ``limits`` (None: off), ``guard``, ``cfg`` and ``sc``).

    Every executed step goes through :meth:`_limited`: the wanted move is projected onto the
    limits; when the guard finds the projected move unsafe (or, with the rule looking at
    acceleration or turn limits, it leaves no continuation within them), the projections of
    the evasive headings (16 directions at full and half speed, and braking) are tried,
    nearest the wanted end first; else, under that rule, the robot brakes toward rest where
    no safe move keeps a continuation or every move hits, otherwise the safe move nearest the
    wanted end or the one with the largest clearance is driven.
    """

    _vel = np.zeros(2)  # the last step's velocity (px per step)
    _heading = None  # the last move's unit heading (None before the first move)
    _still = 0  # steps stood since the last move

    def _limited(self, pos, to, step: int, remainder=None):
        """Where the robot ends the step from ``pos`` (pixels) that wanted to end at ``to``;
        ``remainder``: the plan's rest after ``to`` (pixels), for the rule's continuation
        along it."""
        if self.limits is None:
            return to
        t, lim = float(step), self.limits
        state = (self._heading, self._still)
        first = pos + project(to - pos, self._vel, lim, *state)
        keeps = self._keeps_driven(pos, step, remainder)
        if self.guard.step_clearance(pos, first, t, 1.0) >= self.cfg.clearance and keeps(first):
            return self._take(pos, first)
        v = self.sc.robot_speed
        dirs = unit_headings(16)
        wants = np.vstack([-self._vel, v * dirs, 0.5 * v * dirs])
        moves = np.array([pos + project(w, self._vel, lim, *state) for w in wants])
        clear = np.array([self.guard.step_clearance(pos, m, t, 1.0) for m in moves])
        ok = np.nonzero(clear >= self.cfg.clearance)[0]
        rest = pos + project(np.zeros(2), self._vel, lim)  # braking toward rest
        if not ok.size:  # every move breaks the margin: where every move hits, come to rest
            worst = self._ruled() and clear.max() <= 0.0  # (a hit then finds it at rest)
            return self._take(pos, rest if worst else moves[int(np.argmax(clear))])
        near = ok[np.argsort(np.hypot(*(moves[ok] - to).T), kind="stable")]
        best = next((i for i in near if keeps(moves[i])), None)
        if best is None and self._ruled():  # none keeps a continuation: come to rest
            return self._take(pos, rest)
        return self._take(pos, moves[near[0] if best is None else best])

    def _ruled(self) -> bool:
        """The inevitable-collision rule is on and looks at acceleration or turn limits."""
        return getattr(self, "ics", None) is not None and self.ics.limits is not None

    def _keeps_driven(self, pos, step: int, remainder=None):
        """``keeps(to)``: the step ``pos -> to`` (already within the limits) keeps a safe
        continuation within the limits from ``to`` at ``step + 1``
        (:mod:`~mawdo.planning.safety.ics_limits`); always True with the rule off or without an
        acceleration or turn-rate limit (then the rule's instant stops are within reach)."""
        if not self._ruled():
            return lambda to: True
        t = float(step)

        def keeps(to):
            if self._timed_keeps(to, step):  # the followed timed route's own rest
                return True
            route = None if remainder is None else np.vstack([to, remainder])
            turn = turned(to - pos, self._heading, self._still)
            return self.ics.find(to, t + 1.0, t, route=route, vel=to - pos, turn=turn) is not None

        return keeps

    def _turn_cost(self):
        """The refinement's share of a turn-rate limit (:func:`turn_penalty`), or None."""
        if self.limits is None or self.limits.turn is None:
            return None
        turn, goal = self.limits.turn, self.sc.goal
        return lambda X, start: turn_penalty(X, start, goal, turn, TURN_WEIGHT)

    def _limited_step(self, prev, pos, remainder, step: int):
        """The run loop's step ``prev -> pos`` (along the plan) as the limits allow: ``(to,
        remainder, passed, fractions)``, straight (no vertex passed); off the plan, the
        remainder starts where the robot is and rejoins the plan at ``pos``."""
        want = pos - prev
        left = float(np.hypot(*want)) + polyline_length(remainder)
        want = wanted_step(want, left, self._vel, self.limits)
        to = self._limited(prev, prev + want, step, remainder)
        if np.max(np.abs(to - pos)) > 1e-12:
            remainder = np.vstack([to, remainder])
        return to, remainder, np.zeros((0, 2)), np.zeros(0)

    def _take(self, pos, to):
        self._vel = to - pos
        self._heading, self._still = turned(self._vel, self._heading, self._still)
        return to
