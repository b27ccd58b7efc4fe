"""The safe-interval guide inside the run loop (``PlannerConfig.time_guide``).

At every (re)plan the run asks the :class:`~mawdo.planning.guide.sipp.guide.SafeIntervalGuide` for
the earliest-arrival timed route from the robot's position and time, and up to
``time_routes - 1`` time-diverse alternatives. Their geometry joins the seeds; the guard
follows the earliest one (waits included) when the candidate it accepted is not
collision-free to the goal when driven at full speed from now (:meth:`TimedRun._timed_choice`).

A candidate of the optimizer is a path driven at the robot's full speed: it cannot wait. A
timed route can, so the run drives it step by step from its clock (:func:`position_at`): a
wait is the robot holding its position for the steps the route says.

With an acceleration or turn-rate limit (``TimeGuide(limits=...)``) the routes are timed as
the robot drives them: each edge from rest to rest in whole steps under ``max_accel`` and the
speed cap, a turn in place of ``ceil(angle / max_turn)`` steps at its start vertex, a moving
robot braking first (:mod:`mawdo.planning.guide.sipp.profile`,
:mod:`mawdo.planning.guide.sipp.profiled`). The run then follows the earliest timed route whenever
the guide has one (a candidate is checked at full speed, not as the limited robot drives it), keeps
it while it is on it, and drives it by its clock: the positions at whole steps are the profile's,
so what the guide checked is what is driven (the rule still checks each step, with the route's rest
as its first continuation). With ``refine_trajectory`` the run's swarm first looks for a faster
drive of the same route (:mod:`mawdo.planning.refine.trajectory_search`: corners rounded, speed
carried), one point per step, and follows that one instead when it is strictly earlier and
verified as driven.

Waiting spots: the guide's roadmap has the static visibility graph's corners, the scenario's
own waiting spots (:attr:`~mawdo.planning.world.scenario.Scenario.spots`: bays, corners; the timed
scene families carry those their ``T*`` was computed with) and
:func:`~mawdo.planning.guide.sipp.optimum.dodge_spots` along each static guide route (points on the
route and beside it every few robot radii), where the robot may wait or step aside. Spots too
close to a wall for the run's margin are dropped
(:func:`~mawdo.planning.guide.sipp.roadmap.usable_spots`).
"""

from __future__ import annotations

import numpy as np

from mawdo.planning.safety.kinematics import SLACK, project
from mawdo.planning.world.path import advance, densify, polyline_length
from mawdo.planning.world.scenario import Scenario

__all__ = ["TimeGuide", "TimedRun", "position_at", "route_geometry"]


class TimeGuide:
    """Timed routes of a scenario from any state of a run.

    Parameters
    ----------
    scenario : Scenario
    clearance : float
        Margin (px, >= 0) added to the robot radius, as in the guard.
    k : int
        Most timed routes per query (>= 1): the earliest and ``k - 1`` time-diverse ones.
    static_routes : sequence of numpy.ndarray
        Static guide routes (pixels) along which waiting spots are placed, beside the
        scenario's own spots.
    limits : Limits, optional
        The run's kinematic limits (:class:`~mawdo.planning.safety.kinematics.Limits`). With an
        acceleration or turn-rate limit the routes are timed as driven within them: each
        edge from rest to rest in whole steps, turns in place, and a moving robot first
        brakes (``profile``; :mod:`mawdo.planning.guide.sipp.profiled`). Else (None, or a speed
        limit alone) instant starts, stops and turns at the scenario's speed.
    lookahead : float, optional
        Time steps (> 0) over which each query trusts the movers' predicted motion (the
        :class:`~mawdo.planning.guide.sipp.guide.SafeIntervalGuide`'s ``lookahead``); None: the
        whole horizon.
    """

    def __init__(
        self,
        scenario: Scenario,
        clearance: float,
        k: int,
        static_routes=(),
        limits=None,
        lookahead: float | None = None,
    ) -> None:
        from mawdo.planning.guide.sipp.optimum import dodge_spots
        from mawdo.planning.guide.sipp.roadmap import usable_spots

        self.scenario, self.clearance, self.k = scenario, float(clearance), int(k)
        self.lookahead = lookahead
        spots = np.vstack([scenario.spots] + [dodge_spots(r, scenario) for r in static_routes])
        self.spots = usable_spots(scenario, self.clearance, np.unique(spots, axis=0))
        self.limits, self.profile = limits, None
        self.last = None  # the guide of the last query (its movers' tables)
        if limits is not None and (limits.accel, limits.turn) != (None, None):
            free = np.inf
            # the projection's own margin, and as much again for rounding: a planned step is
            # never changed by the projection
            accel = free if limits.accel is None else limits.accel * (1.0 - 4.0 * SLACK)
            self.profile = (accel, free if limits.turn is None else float(limits.turn))

    def routes(self, pos, t: float, vel=None) -> list:
        """Timed routes (:class:`~mawdo.planning.guide.sipp.guide.TimedRoute`) from ``pos``
        (pixels) at time ``t`` (time steps), earliest arrival first; empty when none reaches
        the goal within the guide's horizon or the robot stands inside a grown mover (the
        guard then has only its old fallbacks). ``vel``: the robot's velocity (px per step;
        looked at only with a ``profile``: the route starts by braking from it)."""
        from mawdo.planning.guide.sipp.guide import SafeIntervalGuide

        lead = None if self.profile is None else self._brake(pos, vel)
        try:
            guide = SafeIntervalGuide(
                self.scenario, start=pos, t0=float(t), clearance=self.clearance,
                spots=self.spots, profile=self.profile, lead=lead, lookahead=self.lookahead,
            )  # fmt: skip
            self.last = guide
            return guide.routes(self.k)
        except ValueError:  # the start inside a grown obstacle: no safe timed route
            self.last = None
            return []

    def _brake(self, pos, vel) -> np.ndarray:
        """The robot's positions (pixels) at each step while it brakes from ``vel`` (px per
        step) to rest, within the limits (:func:`~mawdo.planning.safety.kinematics.project`)."""
        pts = [np.asarray(pos, dtype=float)]
        u = np.zeros(2) if vel is None else np.asarray(vel, dtype=float)
        for _ in range(64):  # |u| falls by max_accel per step (free: rest at once)
            if not (u[0] or u[1]):
                break
            u = project(np.zeros(2), u, self.limits)
            pts.append(pts[-1] + u)
        return np.array(pts)


def position_at(route, t: float) -> np.ndarray:
    """Where a timed route is at time ``t`` (time steps; clamped to its ends), pixels."""
    times, pts = route.times, route.points
    if t <= times[0]:
        return pts[0].copy()
    if t >= times[-1]:
        return pts[-1].copy()
    i = int(np.searchsorted(times, t, side="right")) - 1
    span = times[i + 1] - times[i]
    w = 0.0 if span <= 0 else (t - times[i]) / span
    return pts[i] + w * (pts[i + 1] - pts[i])


def passed_between(route, t0: float, t1: float):
    """Vertices of a timed route strictly between times ``t0`` and ``t1`` (a step), with the
    fractions of the step at which they are reached: ``(points (j, 2), fractions (j,))``."""
    inside = (route.times > t0) & (route.times < t1)
    return route.points[inside], (route.times[inside] - t0) / (t1 - t0)


def route_geometry(route, pos=None) -> np.ndarray:
    """A timed route's path without its waits (repeated points dropped), optionally from
    ``pos`` instead of its first point; pixels, shape (j, 2)."""
    return _without_waits(route.points if pos is None else np.vstack([pos, route.points[1:]]))


def _without_waits(pts: np.ndarray) -> np.ndarray:
    keep = np.ones(len(pts), bool)
    keep[1:] = np.any(np.abs(np.diff(pts, axis=0)) > 1e-12, axis=1)
    out = pts[keep]
    return out if len(out) >= 2 else np.vstack([out, out])


class TimedRun:
    """The run loop's use of a :class:`TimeGuide` (mixed into
    :class:`~mawdo.planning.run.execute.Run`, which sets ``timer``, ``following``, ``_timed``,
    ``timed_follows`` and ``refiner``, the trajectory refiner of limited runs or None)."""

    #: With a profile, follow the earliest timed route whenever the guide has one: it is the
    #: only plan timed as the robot drives it (a candidate is checked at full speed).
    timed_first = True

    def _timed_seeds(self, pos, step: int, first: bool) -> np.ndarray:
        """The timed routes' paths (waits dropped) as seeds: at the first plan and while the
        robot follows a timed route (elsewhere the guide is asked only when the guard needs
        it, :meth:`_timed_choice`)."""
        if self.timer is None or not (first or self.following is not None):
            return np.empty((0, 2 * self.m))
        # a route kept (_keeps_route): its rest is the seed, and no query is made
        on = self._keeps_route(pos, float(step))
        routes = [self._rest_of(step)] if on else self._timed_routes(pos, step)
        rows = [densify(route_geometry(r, pos), self.m).reshape(-1) for r in routes]
        return np.array(rows).reshape(-1, 2 * self.m)

    def _timed_routes(self, pos, step: int) -> list:
        if self._timed[0] != step:
            vel = (self._vel,) if self._profiled() else ()  # a profile starts by braking
            self._timed = (step, self.timer.routes(pos, float(step), *vel))
        return self._timed[1]

    def _profiled(self) -> bool:
        """The timed routes are timed within acceleration or turn-rate limits."""
        return self.timer is not None and self.timer.profile is not None

    def _keeps_route(self, pos, t: float) -> bool:
        """With a profile or a lookahead, the followed route is kept while the robot is on
        it (:meth:`_on_route`), not asked again: a crowd's profiled query at every step cost
        4x the run's CPU, and a large world's query costs seconds."""
        return (self._profiled() or self.cfg.lookahead is not None) and self._on_route(pos, t)

    def _on_route(self, pos, t: float) -> bool:
        """``pos`` is where the followed timed route is at time ``t``, and the route was
        checked against the movers' predicted motion far enough past ``t``
        (:meth:`_checked_past`)."""
        route = self.following
        if route is None or not self._checked_past(route, t):
            return False
        return bool(np.max(np.abs(pos - position_at(route, t))) <= 1e-9)

    def _checked_past(self, route, t: float) -> bool:
        """A route checked until its ``checked_until`` (a query's lookahead) is kept from time
        ``t`` only while that covers the next replan and the rule's horizon: after it the
        guide is asked again (the rule checks every step in any case)."""
        if route.checked_until == np.inf:
            return True
        ahead = max(self.cfg.replan_every, self.ics.horizon if self.ics is not None else 0)
        return route.checked_until >= t + ahead

    def _timed_keeps(self, to, step: int) -> bool:
        """With a profile: the step to ``to`` is the followed route's, and the route's rest
        from ``step + 1`` (cut at the horizon's end) is a safe continuation, tested by the
        rule's own exact tests (:meth:`~mawdo.planning.safety.ics.SafeContinuation.path_safe`)."""
        if not (self._profiled() and self._on_route(to, step + 1.0)):
            return False
        route, t, end = self.following, float(step), step + float(self.ics.horizon)
        ahead = route.times > t + 1.0
        pts = np.vstack([to, route.points[ahead]])
        times = np.concatenate([[t + 1.0], route.times[ahead]])
        if times[-1] > end:
            k = int(np.searchsorted(times, end, side="right"))
            pts = np.vstack([pts[:k], position_at(route, end)])
            times = np.append(times[:k], end)
        mv = self.ics.movers(t, near=(to, t + 1.0))
        return self.ics.path_safe(pts, times, t, mv)

    def _drive(self, remainder, step: int):
        """One step along the plan: ``(pos, remainder, passed, frac)`` (see
        :func:`~mawdo.planning.world.path.advance`); a followed timed route is driven by its clock,
        so that its waits hold the robot in place.

        No guard check precedes a step along a followed timed route: the route is already
        safe under the guard's model, at least as conservatively. It was returned by the
        safe-interval guide queried at the replan's step ``s0`` from the robot's position then,
        with the run's clearance, and each of its moves and waits passed the exact segment
        test (:func:`~mawdo.planning.guide.sipp.intervals.segment_free`: touching is a hit) against

        * the static obstacles inflated by ``r + clearance`` plus the static guide's slack
          (round corners by circumscribed polygons) and the map shrunk by as much: no
          closer than the guard allows;
        * the movers of known motion (constant velocity, patrol, waypoint tracks) on the same
          piecewise-linear knots the guard's kernel uses, hit distance ``r + clearance``;
        * each random walker as its reachable set from ``s0``: its shape where it is at
          ``s0``, grown by its top speed ``step`` per time step. The seeded walk the guard
          knows moves at most ``step`` px per step (folding at the border never lengthens a
          move), so at every later time the walker lies inside that grown shape, and a move
          clear of the grown shape is clear of the walker by the same hit distance.

        The run drives the route's own pieces at their own times (:func:`position_at`, the
        vertices passed at their fractions of the step), so every driven piece is part of a
        checked move or wait. With a lookahead (``lookahead``) the movers were tested
        only until the route's ``checked_until``; the route is asked again before a step
        could pass it (:meth:`_checked_past`; the configuration keeps the lookahead beyond a
        replan's period and the rule's horizon). The route is asked again at every replan,
        from where the robot is (with acceleration or turn limits, or a lookahead: kept while
        the robot is on it and it is checked far enough ahead). A speed limit alone never
        changes a route's step (the route is timed at it); with acceleration or turn limits
        the route is timed as driven (a rest-to-rest profile per edge, whole steps), so its
        steps are within the limits, and a step leaves the route only when the guard or the
        rule refuses it: it is then the guard-checked projection
        (:class:`~mawdo.planning.safety.kinematics.LimitedRun`). A route the swarm refined
        (``refine_trajectory``) has one point per step; before it replaced the guide's, each of
        its steps passed the guard's step test, the guide's mover test, the rule's route test
        and the run's own projection unchanged. Tested on corridor,
        doorway, parked and crowd scenes with the independent checker
        (``tests/planning/test_timed_follow.py``)."""
        if self.following is None:
            return advance(remainder, self.sc.robot_speed)
        route = self.following
        pos = position_at(route, step + 1.0)
        passed, frac = passed_between(route, float(step), step + 1.0)
        ahead = route.times > step + 1.0
        rest = _without_waits(np.vstack([pos, route.points[ahead]]))
        if not ahead.any():  # the route ends within this step: at the goal
            self.following = None
        return pos, rest, passed, frac

    def _rest_of(self, step: int):
        """The followed route from time ``step`` on (a
        :class:`~mawdo.planning.guide.sipp.guide.TimedRoute`)."""
        from mawdo.planning.guide.sipp.guide import TimedRoute

        route, t = self.following, float(step)
        ahead = route.times > t
        pts = np.vstack([position_at(route, t), route.points[ahead]])
        times = np.concatenate([[t], route.times[ahead]])
        return TimedRoute(pts, times, route.states, route.checked_until)

    def _kept_route(self, pos, step: int):
        """With a profile, the followed route's rest (a path from ``pos``) while the robot is
        on it, else ``None``. :meth:`_timed_choice` keeps such a route whatever the guard
        accepts, so the run makes no search for it: the swarm's plan would not be driven, and
        the guard's verdict on it would count waits or inevitable steps that never happen."""
        if not (self._profiled() and self._on_route(pos, float(step))):
            return None
        if self.following.times[-1] <= step:
            return None
        return self._timed_choice(None, pos, step)

    def _timed_choice(self, chosen, pos, step: int):
        """The guard's use of the safe-interval guide: a candidate the guard accepted is kept
        when it is collision-free to the goal (driven at full speed from now); else the robot
        follows the earliest timed route, when there is one (else the old fallbacks). With a
        ``lookahead`` the route the robot follows is kept while it is on it and the route is
        checked far enough ahead (:meth:`_on_route`), without asking the guide again: on a
        large world a query costs up to seconds, and the route's checked part holds.

        With a profile (acceleration or turn-rate limits) a route the robot is on is kept:
        it was timed as the robot drives it, from rest to rest, and stays safe under the
        predictions it was checked against; a new query from a moving robot would first
        brake."""
        if self._profiled() and self._on_route(pos, float(step)):
            if self.following.times[-1] > step:
                return self._follow_on(pos, step)
        # (a profiled route kept has been returned above: what is left is a lookahead's, which
        # the swarm's candidate replaces when it is free to the goal)
        kept = self._keeps_route(pos, float(step)) and self.following.times[-1] > step
        if chosen is not None and not (self._profiled() and self.timed_first):
            length = polyline_length(chosen)
            if self.guard.stretch_hits(chosen, float(step), length) == 0:
                self.following = None
                return chosen
        if kept:
            return self._follow_on(pos, step)
        self.following = None
        timed = self._timed_routes(pos, step)
        if not timed:
            return chosen
        self.following = self._refined(timed, pos, step)
        self.timed_follows += 1
        return route_geometry(self.following, pos)

    def _follow_on(self, pos, step: int):
        """The rest of the followed route from ``pos``, counted as a timed follow."""
        self.timed_follows += 1
        return route_geometry(self._rest_of(step), pos)

    def _refined(self, timed: list, pos, step: int):
        """The earliest timed route ``timed[0]``, or, when the run's trajectory refiner
        (``refiner``; None: off) finds verified faster drives of the routes, the one that
        arrives first (ties: the guide's order)."""
        from mawdo.streams import trajectory_seed_sequences

        refiner = getattr(self, "refiner", None)
        if refiner is None or self.timer.last is None:
            return timed[0]
        state = (self._vel, self._heading, self._still)
        best = timed[0]
        for j, route in enumerate(timed):
            seeds = trajectory_seed_sequences(self.seed, len(self.replans), j)
            faster = refiner.refine(route, pos, step, state, self.timer.last._mv, seeds)
            if faster is not None and faster.arrival < best.arrival:
                best = faster
        return best
