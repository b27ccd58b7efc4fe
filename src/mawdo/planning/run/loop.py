"""The run loop every policy is driven by: each step the policy decides, the world steps.

:func:`run_loop` is the loop alone, with no knowledge of what decides or what steps: the world
runner (:func:`~mawdo.planning.run.episode.run_episode`: a stepped world, any
:class:`~mawdo.planning.sense.reading.Policy`), the planner that knows the obstacles' future
(:meth:`~mawdo.planning.run.execute.Run.execute`: its world is the scenario it knows, so the
world's step records the decided move) and the oracle follower
(:func:`~mawdo.planning.run.follower.follow_oracle`) all go through it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ["GOAL_REACHED", "GOAL_TOL", "run_loop"]

#: the end reason of a run that reached its goal (the checker's verdict may still refuse it)
GOAL_REACHED = "goal reached"
#: a planner's robot is at its goal within this (px): its plans end exactly on the goal
GOAL_TOL = 1e-9


def _no_decisions() -> int:
    return 0


def run_loop(
    max_steps: int,
    at_goal: Callable[[], bool],
    decide: Callable[[int], Any],
    step: Callable[[Any], str | None],
    limit_reason: str,
    progress: Callable[[int, int, int], Any] | None = None,
    decisions: Callable[[], int] = _no_decisions,
    *,
    progress_at_limit: bool = True,
) -> str:
    """Drive a run from step 0 until the goal, the step limit, or a step that ends it.

    Each step ``k`` (0, 1, ...): ``progress(k, max_steps, decisions())``; the goal test; the
    limit test (``k == max_steps``); ``d = decide(k)``; ``end = step(d)``.

    Parameters
    ----------
    max_steps : int
        Step limit (time steps), >= 0 (whole: ``int(max_steps)``): at most this many
        decisions are made.
    at_goal : callable
        ``at_goal() -> bool``: the robot stands at its goal now.
    decide : callable
        ``decide(k) -> decision``: the policy's decision at step ``k`` (anything ``step`` takes).
    step : callable
        ``step(decision) -> str | None``: the world carries the decision out (time advances
        one step); returns the reason the run ends there (a policy that gives up, a run that
        finds no route) or ``None`` to go on.
    limit_reason : str
        The end reason when the step limit is reached before the goal.
    progress : callable, optional
        ``progress(k, max_steps, decisions())`` before each step.
    decisions : callable
        ``decisions() -> int``: how many (re)plans the policy made so far, for ``progress``.
    progress_at_limit : bool
        Call ``progress`` at step ``max_steps`` too, before the last goal test (a planner's
        bar then ends at ``max_steps``; the world runner never reported that step).

    Returns
    -------
    str
        :data:`GOAL_REACHED`, ``limit_reason`` or the reason ``step`` returned.
    """
    limit = int(max_steps)  # (``progress`` is told ``max_steps`` as given)
    if limit < 0:
        raise ValueError(f"max_steps must be >= 0, got {max_steps!r}")
    k = 0
    while True:
        if progress is not None and (k < limit or progress_at_limit):
            progress(k, max_steps, decisions())
        if at_goal():
            return GOAL_REACHED
        if k == limit:
            return limit_reason
        end = step(decide(k))
        if end is not None:
            return end
        k += 1
