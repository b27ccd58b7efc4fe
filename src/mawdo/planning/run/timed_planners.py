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

import numpy as np

from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.execute import Run
from mawdo.planning.run.result import PlanResult, Replan
from mawdo.planning.world.path import densify

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

    def _plain_seeds(self, pos, step: int, remainder) -> np.ndarray:
        m = self.m
        rows = [densify(r, m).reshape(-1) for r in (self.guide.routes(pos) if self.guide else [])]
        if remainder is not None:
            rows.append(densify(remainder, m).reshape(-1))
        rows.append(densify(np.array([pos, self.sc.goal]), m).reshape(-1))
        X = np.vstack([self._timed_seeds(pos, step, remainder is None), np.array(rows)])
        return np.clip(X, *self.cost.bounds)

    def optimise(self, pos, step: int, remainder):
        """Rank the seeds from ``pos`` at time ``step`` by the cost; best first."""
        t_start = time.perf_counter()
        X = self._plain_seeds(pos, step, remainder)
        f = np.asarray(self.cost(X, start=pos, t0=float(step)), dtype=float)
        order = np.argsort(f, kind="stable")
        best = X[order[0]]
        length, ncol, _ = self.cost.parts(best[None, :], start=pos, t0=float(step))
        self.replans.append(
            Replan(step=step, position=np.array(pos, dtype=float),
                   waypoints=best.reshape(-1, 2).copy(), cost=float(f[order[0]]),
                   length=float(length[0]), collisions=int(ncol[0]),
                   latency=time.perf_counter() - t_start, nfev=len(X),
                   history=np.array([f[order[0]]]))
        )  # fmt: skip
        return X[order], self.replans[-1].latency


def guide_only_run(scenario, seed, config: PlannerConfig) -> PlanResult:
    """The guides' best seed executed as is (no optimizer), safe-interval guide on; ``seed``
    changes nothing (no random draw)."""
    from mawdo.planning.guide.passage import fit_config
    from mawdo.planning.run.config import resolve_scenario

    sc = resolve_scenario(scenario)
    cfg = fit_config(sc, replace(config, time_guide=True))
    return GuideOnlyRun(sc, "guide_only", seed, cfg, True).execute()
