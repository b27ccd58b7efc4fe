"""Planners with the safe-interval guide switched on: ``mawdo_time`` and
``guide_only``.

``mawdo_time`` is the receding-horizon run loop driven by MAWDO with
:attr:`~mawdo.planning.run.config.PlannerConfig.time_guide` on. ``guide_only`` is the same loop with
the optimizer switched off: at each (re)plan its candidates are the seeds as they are (the
static guide's routes, the timed routes' paths, the previous plan's remainder and the straight
line, no perturbed copies), ranked by the planner's cost; the guard then treats them as it
treats an optimizer's elite. The difference between the two is the swarm's measured
contribution over the guides alone.
"""

from __future__ import annotations

import time
from dataclasses import replace

from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.execute import Run
from mawdo.planning.run.gate import rank_seeds, record
from mawdo.planning.run.result import PlanResult

__all__ = ["GuideOnlyRun", "guide_only_run", "mawdo_time_run"]


def mawdo_time_run(scenario, seed, config: PlannerConfig) -> PlanResult:
    """MAWDO's receding-horizon run with the safe-interval guide on (``time_guide=True``)."""
    from mawdo.planning.run.planner import plan

    return plan(scenario, algorithm="mawdo", seed=seed, config=replace(config, time_guide=True))


class GuideOnlyRun(Run):
    """The run loop without an optimizer: the seeds, ranked by the cost, are the candidates."""

    def _make_optimizers(self) -> dict:
        return {}  # none: the seeds are the candidates

    def _make_refiner(self):
        return None  # the guides alone: their timed routes are driven as they are

    def optimise(self, pos, step: int, remainder):
        """Rank the seeds from ``pos`` at time ``step`` by the cost; best first."""
        t_start = time.perf_counter()
        X, f = rank_seeds(self, pos, step, remainder)
        record(self, pos, step, X[0], float(f[0]), len(X), time.perf_counter() - t_start)
        return X, self.replans[-1].latency


def guide_only_run(scenario, seed, config: PlannerConfig) -> PlanResult:
    """The guides' best seed executed as is (no optimizer), safe-interval guide on; ``seed``
    changes nothing (no random draw)."""
    from mawdo.planning.guide.passage import fit_config
    from mawdo.planning.run.config import resolve_scenario

    sc = resolve_scenario(scenario)
    cfg = fit_config(sc, replace(config, time_guide=True))
    return GuideOnlyRun(sc, "guide_only", seed, cfg, True).execute()
