"""A followed timed route is safe under the guard's model (issue 27): between replans the run
drives the safe-interval guide's route by its clock without a guard check
(:meth:`~mawdo.planning.guide.timeguide.TimedRun._drive`). Every step it drives so is checked here
by the independent checker against the obstacles as they really move (random walkers on
their seeded walk): the robot keeps at least the run's margin, as the guard demands."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.planning.judge.check import check_trajectory
from mawdo.planning.run.execute import Run
from mawdo.planning.run.planner import plan
from mawdo.planning.scenes import generate_scene

ROUND = 1e-6  # px: the checker's rounding, far below any margin


def _followed_steps(sc, monkeypatch):
    """A time-guided realtime run of ``sc`` and the steps it drove along a timed route."""
    steps = []
    drive = Run._drive

    def recording(self, remainder, step):
        if self.following is not None:
            steps.append(step)
        return drive(self, remainder, step)

    monkeypatch.setattr(Run, "_drive", recording)
    return plan(sc, "mawdo", seed=0, config="realtime", time_guide=True), steps


def _worst_margin(res, steps) -> float:
    """Least clearance (px, true radius; the border counts) over the executed route during
    the given steps."""
    worst = np.inf
    for s in steps:
        inside = (res.route_times >= s) & (res.route_times <= s + 1)
        rep = check_trajectory(res.route[inside], res.scenario, times=res.route_times[inside])
        worst = min(worst, float(rep.min_clearance), -float(rep.border_excess))
    return worst


def _check(family, index, monkeypatch):
    sc = generate_scene(family, index, seed=0).scenario
    res, steps = _followed_steps(sc, monkeypatch)
    if steps:
        assert _worst_margin(res, steps) >= res.config.clearance - ROUND, (family, index)
    return len(steps)


def test_a_followed_timed_route_keeps_the_margin_corridor(monkeypatch):
    """Corridor-0: the robot waits in a bay by following a timed route."""
    assert _check("corridor", 0, monkeypatch) > 0


@pytest.mark.slow
@pytest.mark.parametrize("family", ["corridor", "doorway", "parked", "crowd"])
def test_followed_timed_routes_keep_the_margin(family, monkeypatch):
    followed = sum(_check(family, index, monkeypatch) for index in (1, 2, 3))
    print(f"{family}: {followed} steps along a timed route")
