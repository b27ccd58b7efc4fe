"""The planner's run as a policy and its world: :meth:`DecidingRun.decide` is the decision of
one step (hold the plan, keep a followed timed route, or search; the guard's choice, the timed
choice, the fallback, giving up; the step the kinematic limits allow), :meth:`DecidingRun.step`
the world's step (the decided moves recorded in the run's
:class:`~mawdo.planning.run.result.Drive`). :meth:`~mawdo.planning.run.execute.Run.execute`
drives them with the one run loop, :func:`~mawdo.planning.run.loop.run_loop`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.planning.refine.cost import assemble_paths
from mawdo.planning.run.gate import near_shortest
from mawdo.planning.run.loop import GOAL_TOL
from mawdo.planning.run.result import Drive
from mawdo.planning.world.path import polyline_length

__all__ = ["NO_ROUTE", "STRAIGHT_TOL", "Decision", "DecidingRun", "Legs", "RunState"]

NO_ROUTE = "no collision-free route found"
# a plan whose waypoints lie within this of the straight line to the goal (px), and no longer
# than it by more than this, is straight (see DecidingRun._holds)
STRAIGHT_TOL = 1e-6


@dataclass
class RunState:
    """What the run carries from one step to the next.

    Attributes
    ----------
    position : ndarray, shape (2,)
        Where the robot is (pixels); set by the world's step.
    remainder : ndarray, shape (k, 2), or None
        The plan's rest from ``position`` to the goal (pixels); ``None`` before the first plan.
    stuck : int
        Steps of waiting or evading since the guard last accepted a plan (>= 0).
    force : bool
        The next step replans whatever the replanning period says (after a fallback).
    """

    position: np.ndarray
    remainder: np.ndarray | None
    stuck: int = 0
    force: bool = False


class Legs(list):
    """The moves of one decision, ``(step, position, passed, frac)`` each, recorded with the
    signature of :meth:`Drive.move <mawdo.planning.run.result.Drive.move>`: the fallback and
    the give-up's settling record into it as they would into the drive, and the world's step
    replays them there."""

    def move(self, step: int, pos: np.ndarray, passed=(), frac=()) -> None:
        """Record the move of ``step`` to ``pos`` (pixels) through ``passed`` (at ``frac``)."""
        self.append((step, pos.copy(), passed, frac))


@dataclass(frozen=True)
class Decision:
    """What the run decided at one step.

    Attributes
    ----------
    legs : Legs
        The moves the world makes: one per step (several when the run gives up and settles
        where waiting is safe), none when the run ends without moving.
    end : str or None
        The reason the run ends after these moves, or ``None``.
    """

    legs: Legs
    end: str | None = None

    @property
    def position(self) -> np.ndarray | None:
        """Where the robot ends the decided moves (pixels); ``None`` without a move."""
        return self.legs[-1][1] if self.legs else None


class DecidingRun:
    """The decision and the world's step of the planner's run (mixed into
    :class:`~mawdo.planning.run.execute.Run`, which provides the search, the guard's choice and
    the other mixins' fallbacks and limits). :meth:`begin` sets up ``state`` and ``drive``;
    :meth:`~mawdo.planning.run.execute.Run.execute` then drives :meth:`decide` and :meth:`step`
    with :func:`~mawdo.planning.run.loop.run_loop`."""

    def begin(self) -> None:
        """Put the robot at the start with the warm start as its plan (if any), no moves made.
        The drive is kept on the run: a progress callback may read the moves so far (the GIF's
        frames are drawn while the run goes on: :mod:`mawdo.planning.render.live`)."""
        self.state = RunState(self.sc.start.copy(), self.warm_start)
        self.drive = Drive(self.state.position)

    def at_goal(self) -> bool:
        """The robot stands at the goal."""
        return bool(np.hypot(*(self.sc.goal - self.state.position)) <= GOAL_TOL)

    def step(self, decision: Decision) -> str | None:
        """The world's step: the decided moves are made (recorded in the drive); the decision's
        end reason, if any."""
        for leg in decision.legs:
            self.drive.move(*leg)
        if decision.legs:
            self.state.position = decision.position
        return decision.end

    def decide(self, step: int) -> Decision:
        """The run's decision at ``step`` from :attr:`state`: replan when there is no plan,
        after a fallback, or at the replanning period (a straight or stalled plan is held; a
        followed timed route is kept), then one step along the plan within the limits."""
        s, cfg = self.state, self.cfg
        replan = s.remainder is None or s.force or (self.dynamic and step % cfg.replan_every == 0)
        if replan and self._holds(s.remainder, s.force, step):
            self.counts["holds"] += 1
        elif replan and (chosen := self._kept_route(s.position, step)) is not None:
            s.stuck, s.remainder, s.force = 0, chosen, False  # (no search: it would be ignored)
        elif replan:
            other = self._search(step)
            if other is not None:
                return other
        return Decision(self._along(step))

    def _search(self, step: int) -> Decision | None:
        """Search from the robot's position and let the guard (and the timed guide) choose;
        ``None`` when a plan was chosen (it becomes the remainder), else the decision without
        one: the end of a single-shot run, or the fallback."""
        s, cfg = self.state, self.cfg
        cands, _ = self.optimise(s.position, step, s.remainder)
        left = cfg.replan_every - step % cfg.replan_every if self.dynamic else 0
        chosen = self.choose(cands, s.position, step, self.sc.robot_speed * left)
        if self.timer is not None:
            chosen = self._timed_choice(chosen, s.position, step)
        if chosen is None and not self.dynamic:
            n = self.replans[-1].collisions
            return Decision(Legs(), f"{NO_ROUTE}: the best plan hits obstacles {n} times")
        if chosen is None:
            return self._fall_back(step, cands)
        self.stalled = self.stalled and self.chosen_index == 0
        s.stuck, s.remainder, s.force = 0, chosen, False
        return None

    def _fall_back(self, step: int, cands) -> Decision:
        """No candidate is safe: the fallback's move, and the next step replans; after
        ``give_up_steps`` such steps the run gives up where waiting is safe."""
        s, legs = self.state, Legs()
        pos = self._fallback(legs, s.position, step, cands)
        s.stuck, s.force = s.stuck + 1, True
        if s.stuck >= self.cfg.give_up_steps:
            _, note = self._settle(legs, pos, step + 1)
            reason = f"{NO_ROUTE}: gave up after {s.stuck} steps of waiting or evading"
            return Decision(legs, reason + note)
        s.remainder = assemble_paths(cands[:1], pos, self.sc.goal)[0]
        return Decision(legs)

    def _along(self, step: int) -> Legs:
        """One step along the plan (the timed route's clock when one is followed), as the
        kinematic limits allow; the plan's rest becomes the remainder."""
        s = self.state
        prev, (pos, remainder, passed, frac) = s.position, self._drive(s.remainder, step)
        if self.limits is not None:  # the step the kinematic limits allow
            pos, remainder, passed, frac = self._limited_step(prev, pos, remainder, step)
        s.remainder = remainder
        legs = Legs()
        legs.move(step, pos, passed, frac)
        return legs

    def _fallback(self, drive, pos, step: int, cands):
        """No candidate is safe: wait if that is safe, else the least-bad evasive move (with
        the rule on, one that keeps a safe continuation if any does: :class:`SafeRun`), recorded
        in ``drive``; where the robot ends."""
        to, waited, kept = self._pending_escape(pos, step, self._target(pos, cands))
        to = self._limited(pos, to, step)
        self.counts["inevitable"] += not kept
        self.counts["waits" if waited else "evasions"] += 1
        drive.move(step, to.copy())
        return to

    def _holds(self, remainder, force: bool, step: int) -> bool:
        """Keep the plan without optimising: it runs straight to the goal
        (:attr:`PlannerConfig.hold_straight`) or the last search could not improve it and it is
        near the shortest static route (:attr:`PlannerConfig.hold_gap`), and the guard finds it
        collision-free to its end.

        A straight plan has the least cost any candidate can have: C1 equals the straight-line
        distance, its lower bound, and C2 = C3 = 0. The predictions a plan was verified against
        are the same at every later step, so it stays verified until the goal.
        """
        if remainder is None or force or not self.dynamic or self.following is not None:
            return False
        if self.cfg.mode != "spacetime":  # the frozen-map planner judges by another model
            return False
        length = polyline_length(remainder)
        if not (self._straight(remainder, length) or self._near_shortest(remainder, length)):
            return False
        return self.guard.stretch_hits(remainder, float(step), length) == 0

    def _straight(self, remainder, length: float) -> bool:
        if not self.cfg.hold_straight:
            return False
        a, b = remainder[0], remainder[-1]
        d = b - a
        direct = float(np.hypot(d[0], d[1]))
        if len(remainder) > 2:
            inner = remainder[1:-1] - a
            off = np.abs(inner[:, 0] * d[1] - inner[:, 1] * d[0]) / max(direct, 1e-300)
            if off.max() > STRAIGHT_TOL:
                return False
        return length <= direct + STRAIGHT_TOL  # else collinear but doubling back

    def _near_shortest(self, remainder, length: float) -> bool:
        if not (self.stalled and self.guide is not None):
            return False
        return near_shortest(self, remainder, length)
