"""The run loop's use of the inevitable-collision rule (:mod:`mawdo.planning.safety.ics`): which of
the guard's options keep a safe continuation, the fallback when none does, and where a run that
gives up stops."""

from __future__ import annotations

from mawdo.planning.refine.cost import assemble_paths
from mawdo.planning.world.path import advance

__all__ = ["SafeRun"]


class SafeRun:
    """The run loop's use of a :class:`SafeContinuation` (mixed into
    :class:`~mawdo.planning.run.execute.Run`, which sets ``ics`` (None: the rule is off),
    ``guard``, ``cfg``, ``sc`` and ``counts``).

    Its moves go through ``_limited`` (:class:`~mawdo.planning.safety.kinematics.LimitedRun`).

    The rule filters the guard's options: a candidate, a wait or an evasive move is taken only
    when the robot keeps a safe continuation after it. When no option keeps one, the run does
    what it would do without the rule (the least bad) and counts the step in
    ``counts["inevitable"]``.
    """

    _pending = None  # (step, escape) found by _least_bad, made by the fallback

    def _target(self, pos, cands):
        """Where the best candidate takes the robot in one step (pixels)."""
        route = assemble_paths(cands[:1], pos, self.sc.goal)[0]
        return advance(route, self.sc.robot_speed)[0]

    def _continues(self, route, step: int, distance: float) -> bool:
        """The stretch of ``distance`` px of ``route`` driven from ``step`` keeps a safe
        continuation (always, with the rule off)."""
        return self.ics is None or self.ics.after_stretch(route, float(step), distance)

    def _keeps(self, step: int):
        """``admit(to)`` for the moves of ``step``: True when ``to`` at ``step + 1`` has a
        safe continuation (None with the rule off)."""
        if self.ics is None:
            return None
        t = float(step)
        return lambda to: self.ics.find(to, t + 1.0, t) is not None

    def _may_wait(self, pos, step: int) -> bool:
        """Waiting one step at ``pos`` keeps the margin (the checker) and, with the rule on,
        a safe continuation."""
        if self.guard.step_clearance(pos, pos, float(step), 1.0) < self.cfg.clearance:
            return False
        keeps = self._keeps(step)
        return keeps is None or keeps(pos)

    def _escape(self, pos, step: int, target):
        """The fallback's move of ``step`` from ``pos``: ``(to, waited, kept)``: a wait that
        keeps a continuation, else the evasive move nearest ``target`` that keeps one, else
        (``kept`` False) the old fallback's move (wait if safe, else the least-bad evasion)."""
        if self._may_wait(pos, step):
            return pos.copy(), True, True
        to, _, kept = self.guard.evasive_move(pos, target, float(step), 1.0, self._keeps(step))
        if kept or self.ics is None:
            return to, False, True
        if self.guard.step_clearance(pos, pos, float(step), 1.0) >= self.cfg.clearance:
            return pos.copy(), True, False
        return to, False, False

    def _least_bad(self, least, pos, step: int, target):
        """No safe candidate keeps a continuation: ``None`` when none is safe at all or when a
        wait or an evasive move keeps one (the fallback then makes it), else ``least``'s
        route (``(index, route)``: the first safe candidate), counted as inevitable."""
        if least is None:
            return None
        escape = self._escape(pos, step, target)
        if escape[2]:
            self._pending = (step, escape)
            return None
        self.counts["inevitable"] += 1
        self.counts["fallbacks"] += least[0] > 0
        self.chosen_index = least[0]
        return least[1]

    def _pending_escape(self, pos, step: int, target):
        """:meth:`_escape`, or the one :meth:`_least_bad` found at this step."""
        pending, self._pending = self._pending, None
        if pending is not None and pending[0] == step:
            return pending[1]
        return self._escape(pos, step, target)

    def _settle(self, drive, pos, step: int):
        """A run that gives up at ``step`` stops where waiting is safe: it stays, or drives
        the shortest escape move to a spot where standing is safe until the horizon's end.
        Returns ``(pos, note)``, the note for the run's reason."""
        if self.ics is None:
            return pos, ""
        t = float(step)
        turn = (self._heading, self._still)
        c = self.ics.find(pos, t, t, wait_first=True, vel=self._vel, turn=turn)
        if c is None:
            self.counts["inevitable"] += 1
            return pos, "; it found no spot where waiting is safe"
        if self.ics.limits is not None:  # a motion within the limits, step by step
            for j, q in enumerate(c.points[1:-1]):
                pos = self._limited(pos, q, step + j)
                drive.move(step + j, pos)
        elif c.kind == "spot":
            a, b = c.points[0], c.points[1]
            k = int(round(c.times[1] - c.times[0]))
            for j in range(1, k + 1):  # as the kinematic limits allow, if any
                pos = self._limited(pos, a + (b - a) * (j / k), step + j - 1)
                drive.move(step + j - 1, pos)
        return pos, f"; it stopped where waiting is safe for {self.ics.horizon} steps"
