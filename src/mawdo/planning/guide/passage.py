"""The planner's safety margin fitted to the scene's narrowest passage (one clearance model).

The planner keeps ``robot radius + clearance`` from every obstacle in the cost, both guides and
the guard; the checker only forbids overlap (touching is allowed). A scene whose only route
passes a gap narrower than ``2 (r + clearance)`` is then closed to the planner, though open to
the checker: the slalom family's gaps are at most 1 px wider than the robot.

:func:`passage_margin` measures the scene's own slack: the largest margin ``b`` at which the
static guide (the same octagon inflation and slack as :class:`~mawdo.planning.guide.homotopy.Guide`)
still joins the start to the goal. :func:`fitted_clearance` then uses
``min(clearance, b / 2)``: never more than the configured margin, never more than half of the
scene's slack, so that a passage the guide needs keeps ``b / 2`` px of room on each side for
the guard and the cost. Where the scene has at least twice the margin of slack (every scene
of the static families measured, and the paper scenario) the margin is unchanged.
"""

from __future__ import annotations

import math
from dataclasses import replace

from mawdo.planning.world.scenario import Scenario

__all__ = ["fit_config", "fitted_clearance", "passage_margin"]

#: Bisection steps of :func:`passage_margin`: the slack is found to ``upto / 2**STEPS`` px.
STEPS = 7


def _joins(scenario: Scenario, margin: float) -> bool:
    """True iff the static guide at ``margin`` has a route from the start to the goal."""
    from mawdo.planning.guide.homotopy import Guide

    try:
        guide = Guide(scenario, clearance=margin, k=1)
    except ValueError:  # the goal inside an inflated obstacle or outside the shrunk map
        return False
    return math.isfinite(guide.shortest(scenario.start))


def passage_margin(scenario: Scenario, upto: float) -> float:
    """The scene's static slack: the largest margin (px) in ``[0, upto]`` at which the static
    guide joins start and goal (to ``upto / 2**STEPS`` px, rounded down).

    Parameters
    ----------
    scenario : Scenario
    upto : float
        Largest margin asked about (px, >= 0): the answer is ``upto`` when it joins there.

    Returns
    -------
    float
        The margin (px); 0.0 when even the bare radius (plus the guide's slack) closes the way.
    """
    if not math.isfinite(upto) or upto < 0:
        raise ValueError(f"upto must be finite and >= 0 px, got {upto!r}")
    if _joins(scenario, upto):
        return float(upto)
    lo, hi = 0.0, float(upto)
    if not _joins(scenario, lo):
        return 0.0
    for _ in range(STEPS):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _joins(scenario, mid) else (lo, mid)
    return lo


def fitted_clearance(scenario: Scenario, clearance: float) -> float:
    """The margin a run uses: ``min(clearance, passage_margin / 2)`` (px; see the module
    docstring)."""
    return min(float(clearance), 0.5 * passage_margin(scenario, 2.0 * clearance))


def fit_config(scenario: Scenario, config):
    """``config`` (a :class:`~mawdo.planning.run.config.PlannerConfig`) with its clearance fitted
    to the scenario (:func:`fitted_clearance`); the same object when nothing changes, so that
    the run's recorded config shows the margin it used."""
    c = fitted_clearance(scenario, config.clearance)
    return config if c == config.clearance else replace(config, clearance=c)
