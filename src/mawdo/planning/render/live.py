"""A run under way, sent step by step to the figures' process so it draws GIF frames early.

A frame of the GIF at time ``t`` shows the route up to ``t`` and the last plan made at or before
``t``; once the planner has passed ``t`` no later step changes either. So the process that sets
the figures up while the run is planned (:mod:`.early`) can draw each frame as soon as the run
has passed its time, and after the run only the palette and the file are left (the
62 frames of ``plan paper`` were about 0.8 s of CPU after the run).

:class:`RunStream` is the planner's progress callback in the command's process: it hands what
the run added since its last call (route points, their times, new plans) to
:meth:`EarlyFigures.feed <.early.EarlyFigures.feed>`; :class:`PartialRun` gathers them in the
figures' process and reads like the :class:`~mawdo.planning.run.result.PlanResult` that
:func:`~.world.world_state` draws from.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class Plan(NamedTuple):
    """What a frame draws of a :class:`~mawdo.planning.run.result.Replan`: when it was made (time
    step) and from where (px) through which waypoints (``(m, 2)`` px)."""

    step: int
    position: np.ndarray
    waypoints: np.ndarray


class RunStream:
    """``progress(step, max_steps, replans)`` for ``run.execute`` that feeds ``job`` the run so
    far (:meth:`~.early.EarlyFigures.feed`), then calls ``then`` (a progress bar) if given.

    Parameters
    ----------
    run : prepared run
        From :func:`mawdo.planning.run.planner.prepare`; a run that keeps no ``drive`` (its moves)
        feeds nothing, and its frames are all drawn after it.
    job : EarlyFigures
    then : callable, optional
        Called with the same arguments.
    """

    def __init__(self, run, job, then=None) -> None:
        self.run, self.job, self.then = run, job, then
        self.routes = self.plans = 0  # route points and plans sent so far

    def __call__(self, step: int, max_steps: int, replans: int) -> None:
        self.job.feed(self.news)
        if self.then is not None:
            self.then(step, max_steps, replans)

    def news(self):
        """``(route points (k, 2), their times (k,), new plans)`` since the last call, or None."""
        drive = getattr(self.run, "drive", None)
        if drive is None or len(drive.stamps) <= self.routes:
            return None
        a, self.routes = self.routes, len(drive.stamps)
        route = np.array(drive.route[a : self.routes], dtype=float)
        stamps = np.array(drive.stamps[a : self.routes], dtype=float)
        new = self.run.replans[self.plans :]
        self.plans += len(new)
        return route, stamps, [Plan(int(p.step), p.position, p.waypoints) for p in new]


class PartialRun:
    """The run so far, gathered from :meth:`RunStream.news`; reads like a
    :class:`~mawdo.planning.run.result.PlanResult` for :func:`~.world.world_state` (not
    successful: a frame before the run's end draws no finish)."""

    success = False

    def __init__(self) -> None:
        self.route = np.empty((0, 2))
        self.route_times = np.empty(0)
        self.replans: list[Plan] = []

    @property
    def trajectory(self) -> np.ndarray:
        return self.route

    @property
    def end(self) -> float:
        """The time (time steps) the run has reached; frames before it are fixed."""
        return float(self.route_times[-1]) if len(self.route_times) else 0.0

    def add(self, news) -> None:
        """Append one :meth:`RunStream.news`."""
        route, stamps, plans = news
        self.route = np.concatenate([self.route, route])
        self.route_times = np.concatenate([self.route_times, stamps])
        self.replans.extend(plans)
