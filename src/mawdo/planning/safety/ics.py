"""Never drive into an inevitable collision.

A state (position, time) of the robot is an *inevitable collision state* when every motion
from it meets an obstacle. Before a stretch of a plan is driven, the run asks
:class:`SafeContinuation` whether the robot, at the stretch's end, still has a *safe
continuation* up to the end of the prediction horizon ``t0 + horizon`` (``t0``: the time of
the decision). Three kinds are tried, cheapest first:

``"goal"``
    the rest of the plan, driven at full speed, meets nothing until it reaches the goal or the
    horizon ends;
``"wait"``
    standing still where the stretch ends is safe until the horizon ends;
``"spot"``
    a straight move at full speed, ``k`` whole steps long (``k`` in ``hops``) along one of
    ``headings`` directions, to a spot where standing still is safe until the horizon ends.

Assumptions (what "safe" rests on):

* obstacles follow the motion model the planner predicts (constant velocity, patrol, waypoint
  tracks: exact); a random walker follows its seeded walk, as the cost kernel and the guard
  see it (``walkers = "known"``). ``walkers = "reachable"`` (the safe-interval guide's model:
  a disc growing ``step`` px per time step from where it is at ``t0``) is kept for
  comparison: among several walkers almost no spot stays clear of 30-step discs, so the rule
  then refused stretches the guard accepted (``dense``: 49 of 50 scenes, largest gap 1.911);
  with the seeded walk ``dense`` is back to 0.7.0's 50 of 50, largest gap 1.091;
* hit distance to a mover is ``r + clearance`` (as the guard's); to a static obstacle
  ``r + clearance / 2``, so that a plan sliding along the guide's inflated edges (exactly at
  ``r + clearance``) is not rejected by rounding; the disc must stay inside the map (a goal
  may lie ``r`` from the border);
* the robot may stop, start and turn at once, at up to its full speed, unless the run sets
  an acceleration or turn-rate limit (:attr:`SafeContinuation.limits`) and the rule is asked
  with the robot's velocity: then every continuation is simulated step by step within the
  limits from that velocity and ends at rest (:mod:`mawdo.planning.safety.ics_limits`: it
  brakes over about ``|u|^2 / (2 a)`` px, turns ``max_turn`` per step), and is checked as
  any other;
* the horizon is finite: what happens after ``t0 + horizon`` is not looked at. A continuation
  is a witness that a safe motion exists, not the motion the run will drive.

The tests are exact (the safe-interval guide's closed-form forbidden departures and its
segment test, shapely distances for the statics); no time sampling.

Only the movers that can take part are looked at (an exact prefilter, ``prune``): every
motion a continuation from ``p`` at time ``t`` can make runs at up to the robot's speed ``v``,
so until the horizon's end ``t0 + horizon`` the robot stays in the disc of radius ``v (t0 +
horizon - t)`` around ``p``; a mover stays in the disc of radius ``rho + w (s - T)`` around
where its inflated shape's bounding circle (radius ``rho``, hit distance included) was at the
tables' first time ``T <= t0``, ``w`` its top speed (constant velocity: its speed, folding at
the border never speeds it up; patrol: its speed; random walker: its step). A mover whose
centre lies farther from ``p`` than the sum of both radii plus ``PRUNE_TOL`` cannot come
within the hit distance, and each test of one mover reads only that mover's rows, so leaving
it out changes no verdict; a mover of an unknown motion model is always kept. With grown
walker discs the rule's tables are rebuilt at every decision; they reuse
the obstacles' shapes and tabulate the movers within reach only (the rule's CPU time per paper
replan 2.58 -> 1.87 ms at load ~8; docs/deviations.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from mawdo.planning.guide.sipp.intervals import Movers, forbidden, segment_free
from mawdo.planning.safety.ics_limits import continuation_drive
from mawdo.planning.world.geometry import FlatObstacles
from mawdo.planning.world.motion import BoundedRandomWalk, ConstantVelocity, Patrol, Track
from mawdo.planning.world.path import advance, segment_lengths, unit_headings
from mawdo.planning.world.scenario import CircleObstacle, Scenario

__all__ = ["Continuation", "SafeContinuation"]

#: Horizons of obstacle motion tabulated at once when no mover is a random walker.
REUSE = 8
#: Slack (px) of the mover prefilter: far above the tables' rounding (~1e-12 of the map's
#: size), far below any distance that matters.
PRUNE_TOL = 1e-3


@dataclass(frozen=True)
class Continuation:
    """A safe continuation: a timed polyline driven straight and uniformly between vertices.

    Attributes
    ----------
    kind : {"goal", "wait", "spot"}
        Along the plan (to the goal or to the horizon's end), standing still, or a move to a
        spot where standing still is safe.
    points : numpy.ndarray, shape (k, 2)
        Positions (pixels); a wait repeats a position.
    times : numpy.ndarray, shape (k,)
        Time at each position (time steps), non-decreasing, the last one the horizon's end
        (or the goal's arrival).
    """

    kind: str
    points: np.ndarray
    times: np.ndarray


class SafeContinuation:
    """Safe continuations of a scenario's robot (see the module docstring).

    ``prune`` (class attribute, True): look only at the movers that can take part (exact);
    False looks at all of them (the reference the tests compare with).

    Parameters
    ----------
    scenario : Scenario
    clearance : float
        Margin (px, >= 0) added to the robot radius for the movers (half of it for the
        statics; none for the border).
    horizon : int
        Prediction horizon (time steps, >= 1): a continuation must be safe up to
        ``t0 + horizon``.
    headings : int
        Directions of the escape moves (>= 1), evenly spaced.
    hops : tuple of int
        Lengths of the escape moves, in whole steps at full speed (each >= 1), tried shortest
        first.
    """

    prune = True
    walkers = "known"
    #: Kinematic limits (:class:`~mawdo.planning.safety.kinematics.Limits`) of the continuations
    #: asked with a velocity (``find(..., vel=...)``); None: instant stops and turns.
    limits = None

    def __init__(
        self,
        scenario: Scenario,
        clearance: float,
        horizon: int,
        headings: int = 16,
        hops: tuple = (1, 2, 4, 8),
    ) -> None:
        if int(horizon) < 1:
            raise ValueError(f"horizon={horizon!r} must be >= 1 time step")
        self.sc, self.clearance, self.horizon = scenario, float(clearance), int(horizon)
        self.v = scenario.robot_speed
        self.reach = scenario.robot_radius + 0.5 * self.clearance
        dirs = unit_headings(int(headings))
        self._moves = [(k, self.v * k * dirs) for k in sorted(int(h) for h in hops)]
        self._statics = [_geometry(scenario.obstacles[i].shape) for i in scenario.static_indices]
        moving = tuple(scenario.obstacles[i] for i in scenario.moving_indices)
        # a walker's seeded future, as the cost and the guard see it, is a fixed function of
        # time: only the growing-disc model makes the tables depend on the decision's time
        self._walkers = self.walkers == "reachable" and any(
            isinstance(o.motion, BoundedRandomWalk) for o in moving
        )
        # the shapes' tables never change: built once, not at every decision
        self._flat = FlatObstacles.from_obstacles(moving, scenario.robot_radius + self.clearance)
        self._moving, self._centre = moving, self._flat.bound[:, 4:6]
        self._rho = self._flat.bound[:, 6]
        self._speed = np.array([_top_speed(o.motion) for o in moving])
        # (first valid time, last, movers' centres then, their pieces, tables per mover set)
        self._mv = (0.0, 0.0, None, {}, {})

    # -- the model -------------------------------------------------------------------------

    def movers(self, t0: float, near=None):
        """The moving obstacles from ``t0`` to the horizon's end (compiled tables). Without
        random walkers the tables do not depend on ``t0`` beyond the window they cover, so one
        built for ``REUSE`` horizons serves every decision inside it (a crowd of 50 movers
        costs ~35 ms to tabulate on a shared core); a walker's reachable disc grows from
        ``t0``, so with walkers they are built per decision.

        ``near = (p, t)``: only the movers that can meet a robot leaving ``p`` (pixels) at
        ``t`` (time steps) at up to its speed before the horizon's end (the module
        docstring's prefilter); None: all of them. A mover's pieces are tabulated once per
        window, when a decision first needs them."""
        T0, T1, where, pieces, tables = self._mv
        inside = not self._walkers and T0 <= t0 and t0 + self.horizon + 1.0 <= T1
        if where is None or not (t0 == T0 or inside):
            T0, T1 = t0, t0 + (1 if self._walkers else REUSE) * self.horizon + 1.0
            where = self._centre + np.array([o.offset(T0) for o in self._moving]).reshape(-1, 2)
            pieces, tables = {}, {}
            self._mv = (T0, T1, where, pieces, tables)
        keep = np.ones(len(where), bool)
        if near is not None and self.prune:
            (px, py), t = near
            end = t0 + self.horizon
            reach = self._rho + self.v * (end - t) + self._speed * (end - T0) + PRUNE_TOL
            keep = np.hypot(where[:, 0] - px, where[:, 1] - py) <= reach
        key = keep.tobytes()
        if key not in tables:

            def knots(j, a, b):
                if j not in pieces:
                    pieces[j] = self._moving[j].knots(a, b)
                return pieces[j]

            mv = Movers.from_scenario(
                self.sc, self.clearance, T0, T1, walkers=self.walkers, knots=knots,
                flat=self._flat, only=None if keep.all() else np.flatnonzero(keep),
            )  # fmt: skip
            tables[key] = mv.arrays()
        return tables[key]

    def static_clear(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Per straight move ``a[i] -> b[i]`` (pixels, shape (n, 2)): it keeps ``r +
        clearance / 2`` from every static obstacle and the disc stays inside the map (the box
        is convex, so both ends decide; a goal may lie ``r`` from the border)."""
        a, b = np.atleast_2d(a), np.atleast_2d(b)
        lo, W, H = self.sc.robot_radius, self.sc.width, self.sc.height
        ok = np.ones(len(a), bool)
        for q in (a, b):
            ok &= (q[:, 0] >= lo) & (q[:, 0] <= W - lo) & (q[:, 1] >= lo) & (q[:, 1] <= H - lo)
        if self._statics and ok.any():
            lines = shapely.linestrings(np.stack([a, b], axis=1))
            for geom, grow in self._statics:
                ok &= shapely.distance(lines, geom) - grow >= self.reach
        return ok

    def wait_safe(self, p, ta: float, tb: float, t0: float, mv=None) -> bool:
        """Standing at ``p`` (pixels) from ``ta`` to ``tb`` (time steps) meets no mover
        (statics are not looked at: ``p`` is where a checked move ended); ``mv``: the tables
        to use (default :meth:`movers` of ``t0``, all movers)."""
        if tb <= ta:
            return True
        mv = self.movers(t0) if mv is None else mv
        F = forbidden(float(p[0]), float(p[1]), 0.0, 0.0, 0.0, ta, tb, mv)
        return len(F) == 0

    def path_safe(self, points, times, t0: float, mv=None, statics: bool = True) -> bool:
        """A timed polyline (pixels, time steps; straight and uniform between vertices) meets
        no mover and (unless ``statics`` is False) keeps clear of the statics and the border;
        ``mv`` as in :meth:`wait_safe`."""
        mv = self.movers(t0) if mv is None else mv
        P, T = np.asarray(points, dtype=float).tolist(), np.asarray(times, dtype=float).tolist()
        for (ux, uy), (vx, vy), ta, tb in zip(P, P[1:], T, T[1:], strict=False):
            if tb > ta and not segment_free(ux, uy, vx, vy, ta, tb, mv):
                return False
        return not statics or bool(np.all(self.static_clear(points[:-1], points[1:])))

    # -- continuations ---------------------------------------------------------------------

    def find(
        self, p, t: float, t0: float, route=None, wait_first: bool = False, vel=None, turn=None
    ):
        """A safe continuation from ``p`` (pixels) at time ``t`` up to ``t0 + horizon``, or
        ``None`` when there is none of the three kinds.

        ``route`` (pixels, from ``p``) is the plan's rest, tried first unless ``wait_first``
        (a run that gives up wants to stop, not to drive on); ``t0`` is the decision's time.
        ``vel`` (px per step): the robot's velocity at ``p``; with :attr:`limits` set, every
        continuation is simulated within the limits from that velocity (module docstring);
        otherwise it is not looked at. ``turn``: the robot's ``(heading, still)`` state
        (:func:`~mawdo.planning.safety.kinematics.turned`; None: no heading yet), for the
        turn-rate limit from rest.
        """
        p = np.asarray(p, dtype=float)
        end = t0 + self.horizon
        limits = None if vel is None else self.limits
        drive = continuation_drive(limits, self.v, vel, turn, int(np.ceil(end - t)) + 1)
        mv = self.movers(t0, near=(p, t))  # every continuation below leaves p at t
        along = None
        if route is not None:
            pts, times = drive.follow(route, p, t, end)
            along = self._rests("goal", pts, times, None, t0, mv)
        if along is not None and not wait_first:
            return along
        pts = drive.brake([p])
        found = self._rests("wait", pts, t + np.arange(len(pts), dtype=float), end, t0, mv)
        if found is not None:
            return found
        spot = self._spot(drive, p, t, end, t0, mv)
        return spot if spot is not None else along

    def after_stretch(self, route: np.ndarray, t: float, distance: float) -> bool:
        """True when the robot, having driven the first ``distance`` px of ``route`` (from
        its first point at time ``t``, full speed), has a safe continuation (:meth:`find`);
        a stretch that reaches the goal has one."""
        end, rest, _, _ = advance(route, distance)
        if len(rest) < 2 or float(np.sum(segment_lengths(rest))) <= 1e-9:
            return True  # the goal is reached within the stretch
        t1 = t + distance / self.v
        return self.find(end, t1, t, route=rest) is not None

    def _rests(self, kind: str, pts, times, end, t0: float, mv, statics: bool = True):
        """The continuation ``kind`` driving the timed polyline ``pts, times`` (movers, and
        the statics and border unless ``statics`` is False: already checked), then standing
        at its last point until ``end`` (None: no rest), when it is safe; else None. A lone
        point stands (a wait repeats a position); a motion past ``end`` does not."""
        pts = np.asarray(pts, dtype=float)
        if len(pts) > 1 and not self.path_safe(pts, times, t0, mv, statics):
            return None
        if end is not None and (times[-1] < end or len(pts) == 1):
            if not self.wait_safe(pts[-1], times[-1], end, t0, mv):
                return None
            pts, times = np.vstack([pts, pts[-1]]), np.append(times, max(times[-1], end))
        return Continuation(kind, pts, times)

    def _spot(self, drive, p, t: float, end: float, t0: float, mv):
        """The first escape (shortest hop first, then by heading) that ends where standing is
        safe until ``end``; the statics are checked for a hop's escapes at once."""
        for k, offsets in self._moves:
            if t + k >= end:
                break
            paths, a, b = drive.escapes(p, t, k, offsets)
            ok, i = self.static_clear(a, b).tolist(), 0
            for pts, times in paths:
                i += len(pts) - 1
                if all(ok[i - len(pts) + 1 : i]):
                    found = self._rests("spot", pts, times, end, t0, mv, statics=False)
                    if found is not None:
                        return found
        return None


def _top_speed(motion) -> float:
    """An upper bound of a motion's speed (px per time step); ``inf`` for a model it does
    not know (such a mover is never left out)."""
    if motion.is_static:
        return 0.0
    if isinstance(motion, ConstantVelocity):  # folding flips a component, keeps its size
        return float(np.hypot(*motion.velocity))
    if isinstance(motion, Patrol):  # at its speed along the legs, at rest in its stops
        return float(motion.speed)
    if isinstance(motion, BoundedRandomWalk):
        return float(motion.step)
    if isinstance(motion, Track):
        return motion.top_speed
    return float("inf")


def _geometry(shape):
    """A static shape as ``(geometry, grow)``: the distance to it is the shapely distance
    minus ``grow`` (a circle is its centre grown by its radius, exact)."""
    if isinstance(shape, CircleObstacle):
        return shapely.Point(shape.center), float(shape.radius)
    return shapely.Polygon(shape.vertices), 0.0
