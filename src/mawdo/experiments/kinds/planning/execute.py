"""One planning-study task on a worker: ``n_runs`` planning runs of one algorithm on a scenario.

Each stored run keeps its metrics (JSON) and its executed route and replans (``.npz`` bytes),
so the report draws every figure from the store without planning again.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

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
        :func:`mawdo.planning.judge.metrics.run_metrics` of the run (length, gap, smoothness,
        collisions, latency ...); None for a failed run.
    route : bytes or None
        The serialised :class:`~mawdo.planning.run.planner.PlanResult` (``result_to_bytes``).
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
    metrics: dict | None = column("json", required=True)
    route: bytes | None = column("blob", required=True)
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
    """Plan ``n_runs`` runs of one planner; a run that raises becomes a row with its error.

    A computed run is never thrown away by its metrics: the route is
    stored first, and metrics that fail (the oracle on a huge map, say) fall back to those
    that need no oracle, with the failure in ``metrics["metrics_error"]``
    (:func:`~mawdo.planning.judge.metrics.run_metrics_kept`).
    """
    from mawdo.planning import scenario_from_dict
    from mawdo.planning.judge.metrics import static_optimum
    from mawdo.planning.run.planners import PLANNERS

    sc = scenario_from_dict(spec["scenario"], source=f"scenario {spec['problem']!r}")
    try:
        l_star = static_optimum(sc)
    except Exception:  # noqa: BLE001 - each run's metrics try again and keep the reason
        l_star = None
    planner = PLANNERS[spec["algorithm"]]
    settings = {"planner": spec["planner"], **spec["overrides"]}
    rows = []
    for i, seed in enumerate(spec["seeds"]):
        run = spec["first_run"] + i
        t1 = time.perf_counter()
        try:
            res = _plan_one(planner, sc, spec, seed)
        except Exception as exc:  # noqa: BLE001 - a failing run is a row, not a dead study
            from mawdo.planning.judge.metrics import one_line

            rows.append(
                PlanningRow(
                    run=run,
                    wall_time=time.perf_counter() - t1,
                    error_text=one_line(exc),
                    seed=seed,
                    settings=settings,
                )
            )
            continue
        row = _row(run, t1, seed, settings, res, l_star, spec["snapshots"])
        rows.append(_with_first_plan(row, res, sc, planner.optimizer is None))
    return rows


def _plan_one(planner, sc, spec: dict[str, Any], seed: int):
    """One run of ``planner`` (:class:`~mawdo.planning.run.planners.PlannerSpec`); the task's
    overrides already hold a variant's optimizer options."""
    from mawdo.planning.run.config import resolve_config

    return planner.run(sc, seed, resolve_config(spec["planner"], spec["overrides"]))


def _row(run, t1, seed, settings, res, l_star, snapshots) -> PlanningRow:
    """The stored row of a computed run: route first, then whatever metrics can be had."""
    from mawdo.planning.judge.metrics import run_metrics_kept
    from mawdo.planning.run.result import result_to_bytes

    route = result_to_bytes(res)
    curve = res.replans[0].history if res.replans else np.zeros(0)
    metrics, error = run_metrics_kept(res, l_star=l_star, snapshots=snapshots)
    return PlanningRow(
        run=run,
        wall_time=time.perf_counter() - t1,
        error_text=None if metrics is not None else f"metrics: {error}",
        seed=seed,
        settings=settings,
        metrics=metrics,
        route=route,
        first_plan_curve=np.asarray(curve, dtype=float),
    )


def _with_first_plan(row: PlanningRow, res, sc, baseline: bool) -> PlanningRow:
    """Add the first plan's smoothness (Eq. 28, rad) and its dimension to a stored row."""
    from mawdo.planning.world.path import turning_angles

    first = first_plan_path(res, sc)
    smooth = None if first is None else float(turning_angles(first).sum())
    dim = 2 * len(res.replans[0].waypoints) if res.replans else None
    return replace(row, first_plan_smoothness_rad=smooth, plan_dim=None if baseline else dim)
