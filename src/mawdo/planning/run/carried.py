"""What a stepped planner carries from one step's run to the next under kinematic limits.

An observing planner (:class:`~mawdo.planning.run.policy.PlannerPolicy`) runs one step of the
planner's loop per time step, each on a fresh prediction scenario whose time 0 is now. Without
limits nothing has to survive the step: the robot stops, starts and turns at once. With an
acceleration or turn-rate limit (:class:`~mawdo.planning.safety.kinematics.Limits`) the next step
must start from where this one left the robot's motion:

* the velocity of the last step (``u``, px per step: the next step's change of velocity is
  measured from it, and the inevitable-collision rule brakes from it);
* the heading of the last move and the steps stood since (the turn rate counts a turn in
  place against them);
* the timed route the robot follows. The safe-interval guide times its routes within the
  limits from rest to rest (:mod:`mawdo.planning.guide.sipp.profile`); a new query from a moving
  robot first brakes. So, as in a run with known futures, the robot keeps the route it is on,
  moved one step earlier (its times less 1), as long as the route's rest up to the rule's
  horizon still meets none of the new prediction's movers and keeps clear of the statics
  (:meth:`~mawdo.planning.safety.ics.SafeContinuation.path_safe`); else it is dropped and the
  step's run searches afresh. Every step driven is still the guard's and the rule's
  (:class:`~mawdo.planning.safety.kinematics.LimitedRun`), so keeping a route never skips a check.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mawdo.planning.safety.kinematics import Limits, turned

__all__ = ["CarriedMotion"]


@dataclass
class CarriedMotion:
    """The robot's motion state between two steps' runs (module docstring).

    Attributes
    ----------
    limits : Limits
        The limits it serves (at least one of acceleration and turn rate).
    velocity : numpy.ndarray, shape (2,)
        The last step's velocity (px per step); zero at rest.
    heading : numpy.ndarray or None
        Unit heading of the last move; None before the first.
    still : int
        Steps stood since the last move (>= 0).
    route : TimedRoute or None
        The timed route being followed, in the last step's time (0 = that step's start).
    """

    limits: Limits
    velocity: np.ndarray = field(default_factory=lambda: np.zeros(2))
    heading: np.ndarray | None = None
    still: int = 0
    route: object | None = None

    @classmethod
    def of(cls, config, speed: float) -> CarriedMotion | None:
        """The state to carry for ``config``'s limits (:meth:`Limits.of` with the robot's
        ``speed``, px per step), or None when no acceleration or turn-rate limit is set: a
        speed limit alone needs no memory (every step's run is timed at it)."""
        lim = Limits.of(config, speed)
        if lim is None or (lim.accel, lim.turn) == (None, None):
            return None
        return cls(lim)

    def stand(self) -> None:
        """The robot stood one step (a watch): at rest, one more step to turn in place."""
        self.velocity = np.zeros(2)
        self.heading, self.still = turned(self.velocity, self.heading, self.still)
        self.route = None

    def hand_to(self, run, position) -> None:
        """Start ``run`` (a step's :class:`~mawdo.planning.run.execute.Run`, time 0 = now) from
        this state: the velocity, heading and standing steps, and the followed route moved
        one step earlier when the robot is on it at ``position`` and its rest is still safe
        under ``run``'s prediction."""
        run._vel, run._heading, run._still = self.velocity.copy(), self.heading, self.still
        route = self._shifted(position)
        if route is not None and run.ics is not None and _rest_safe(run, route, position):
            run.following = route

    def take_from(self, run) -> None:
        """Keep what ``run`` (after its one step) leaves for the next step."""
        self.velocity = np.asarray(run._vel, dtype=float).copy()
        self.heading, self.still = run._heading, run._still
        self.route = run.following

    def _shifted(self, position):
        """The followed route in the new step's time, if the robot is on it now."""
        from mawdo.planning.guide.sipp.guide import TimedRoute
        from mawdo.planning.guide.timeguide import position_at

        route = self.route
        if route is None or route.times[-1] <= 1.0:
            return None
        moved = TimedRoute(route.points, route.times - 1.0, route.states, route.checked_until - 1.0)
        if np.max(np.abs(position_at(moved, 0.0) - np.asarray(position, float))) > 1e-9:
            return None
        return moved


def _rest_safe(run, route, position) -> bool:
    """``route``'s rest from time 0 to the rule's horizon meets none of ``run``'s predicted
    movers and keeps clear of the statics (the rule's exact tests)."""
    from mawdo.planning.guide.timeguide import position_at

    ics, end = run.ics, float(run.ics.horizon)
    ahead = (route.times > 0.0) & (route.times < end)
    pts = np.vstack([position, route.points[ahead]])
    times = np.concatenate([[0.0], route.times[ahead]])
    if route.times[-1] > end:
        pts, times = np.vstack([pts, position_at(route, end)]), np.append(times, end)
    mv = ics.movers(0.0, near=(np.asarray(position, float), 0.0))
    return bool(ics.path_safe(pts, times, 0.0, mv))
