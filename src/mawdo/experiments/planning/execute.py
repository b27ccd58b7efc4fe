"""One planning-study task on a worker: ``n_runs`` planning runs of one algorithm on a scenario.

Each stored run keeps its metrics (JSON) and its executed route and replans (``.npz`` bytes),
so the report draws every figure from the store without planning again.
"""

from __future__ import annotations

import time
import traceback
from dataclasses import dataclass
from typing import Any

import numpy as np

from mawdo.experiments.planning.plan import BASELINE
from mawdo.experiments.rows import RunRow, column


@dataclass(frozen=True)
class PlanningRow(RunRow):
    """One stored planning run.

    Attributes
    ----------
    seed : int
        The run's planner seed (the same for every algorithm).
    settings : dict
        Planner preset and overrides the run used.
    metrics : dict or None
        :func:`mawdo.planning.metrics.run_metrics` of the run (length, gap, smoothness,
        collisions, latency ...); None for a failed run.
    route : bytes or None
        The serialised :class:`~mawdo.planning.planner.PlanResult` (``result_to_bytes``).
    first_plan_curve : numpy.ndarray
        Best-so-far cost after each iteration of the first replan (empty for the baseline).
    first_plan_smoothness_rad : float or None
        Eq. 28's total turning (rad, >= 0) of the first planned path, ``start, w1..wm, goal``
        as planned before the robot moved (the paper may report this rather than the executed
        route's, ``docs/deviations.md#d-smoothness``); None for a run without a plan.
    plan_dim : int or None
        Dimension D of the optimizer's first problem (2 x waypoints); None for the baseline.
    """

    seed: int | None = column("int")
    settings: dict | None = column("json")
    metrics: dict | None = column("json")
    route: bytes | None = column("blob")
    first_plan_curve: np.ndarray | None = column("f64")
    first_plan_smoothness_rad: float | None = column("real")
    plan_dim: int | None = column("int")


def first_plan_path(result, scenario) -> np.ndarray | None:
    """The first planned path ``(m + 2, 2)`` (pixels): the robot's position at the first
    replan, that replan's waypoints and the goal; None when the run made no plan."""
    if not result.replans:
        return None
    first = result.replans[0]
    return np.vstack([first.position, first.waypoints, scenario.goal])


def execute_planning_task(spec: dict[str, Any]) -> list[PlanningRow]:
    """Plan ``n_runs`` runs of one algorithm; a run that raises becomes a row with its error."""
    from mawdo.planning import get_scenario
    from mawdo.planning.metrics import run_metrics, static_optimum
    from mawdo.planning.path import turning_angles
    from mawdo.planning.planner import follow_oracle, plan, result_to_bytes

    sc = get_scenario(spec["problem"])
    l_star = static_optimum(sc)
    settings = {"planner": spec["planner"], **spec["overrides"]}
    rows = []
    for i, seed in enumerate(spec["seeds"]):
        run = spec["first_run"] + i
        t1 = time.perf_counter()
        try:
            if spec["algorithm"] == BASELINE:
                res = follow_oracle(sc)
            else:
                res = plan(
                    sc,
                    algorithm=spec.get("optimizer", spec["algorithm"]),
                    seed=seed,
                    config=spec["planner"],
                    **spec["overrides"],
                )
            m = run_metrics(res, l_star=l_star, snapshots=spec["snapshots"])
            curve = res.replans[0].history if res.replans else np.zeros(0)
            first = first_plan_path(res, sc)
            smooth = None if first is None else float(turning_angles(first).sum())
            dim = 2 * len(res.replans[0].waypoints) if res.replans else None
            rows.append(
                PlanningRow(
                    run=run,
                    wall_time=time.perf_counter() - t1,
                    seed=seed,
                    settings=settings,
                    metrics=m,
                    route=result_to_bytes(res),
                    first_plan_curve=np.asarray(curve, dtype=float),
                    first_plan_smoothness_rad=smooth,
                    plan_dim=None if spec["algorithm"] == BASELINE else dim,
                )
            )
        except Exception as exc:  # noqa: BLE001 - a failing run is a row, not a dead study
            rows.append(
                PlanningRow(
                    run=run,
                    wall_time=time.perf_counter() - t1,
                    error_text="".join(traceback.format_exception_only(exc)).strip(),
                    seed=seed,
                    settings=settings,
                )
            )
    return rows
