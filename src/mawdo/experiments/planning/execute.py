"""One planning-study task on a worker: ``n_runs`` planning runs of one algorithm on a scenario.

Each stored run keeps its metrics (JSON) and its executed route and replans (``.npz`` bytes),
so the report draws every figure from the store without planning again.
"""

from __future__ import annotations

import time
import traceback
from dataclasses import dataclass, replace
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
    """Plan ``n_runs`` runs of one algorithm; a run that raises becomes a row with its error.

    A computed run is never thrown away by its metrics (issue 12, defect 4): the route is
    stored first, and metrics that fail (the oracle on a huge map, say) fall back to those
    that need no oracle, with the failure in ``metrics["metrics_error"]``.
    """
    from mawdo.planning import scenario_from_dict
    from mawdo.planning.metrics import static_optimum

    sc = scenario_from_dict(spec["scenario"], source=f"scenario {spec['problem']!r}")
    try:
        l_star, l_star_error = static_optimum(sc), None
    except Exception as exc:  # noqa: BLE001 - the runs are still worth planning and storing
        l_star, l_star_error = float("nan"), f"static optimum: {_one_line(exc)}"
    settings = {"planner": spec["planner"], **spec["overrides"]}
    rows = []
    for i, seed in enumerate(spec["seeds"]):
        run = spec["first_run"] + i
        t1 = time.perf_counter()
        try:
            res = _plan_one(sc, spec, seed)
        except Exception as exc:  # noqa: BLE001 - a failing run is a row, not a dead study
            rows.append(
                PlanningRow(
                    run=run,
                    wall_time=time.perf_counter() - t1,
                    error_text=_one_line(exc),
                    seed=seed,
                    settings=settings,
                )
            )
            continue
        row = _row(run, t1, seed, settings, res, l_star, l_star_error, spec["snapshots"])
        rows.append(_with_first_plan(row, res, sc, spec["algorithm"] == BASELINE))
    return rows


def _plan_one(sc, spec: dict[str, Any], seed: int):
    from mawdo.planning.planner import follow_oracle, plan

    if spec["algorithm"] == BASELINE:
        return follow_oracle(sc)
    return plan(
        sc,
        algorithm=spec.get("optimizer", spec["algorithm"]),
        seed=seed,
        config=spec["planner"],
        **spec["overrides"],
    )


def _row(run, t1, seed, settings, res, l_star, l_star_error, snapshots) -> PlanningRow:
    """The stored row of a computed run: route first, then whatever metrics can be had."""
    from mawdo.planning.planner import result_to_bytes

    route = result_to_bytes(res)
    curve = res.replans[0].history if res.replans else np.zeros(0)
    metrics, error = _metrics(res, l_star, l_star_error, snapshots)
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
    from mawdo.planning.path import turning_angles

    first = first_plan_path(res, sc)
    smooth = None if first is None else float(turning_angles(first).sum())
    dim = 2 * len(res.replans[0].waypoints) if res.replans else None
    return replace(row, first_plan_smoothness_rad=smooth, plan_dim=None if baseline else dim)


def run_metrics_kept(res, snapshots: int = 8) -> tuple[dict | None, str | None]:
    """Metrics of a computed run that never throw the run away.

    Returns
    -------
    metrics : dict or None
        :func:`mawdo.planning.metrics.run_metrics`; when the oracle-based ones fail, those
        that need no oracle, with the reason in ``metrics["metrics_error"]``; None when even
        those fail.
    error : str or None
        Why ``metrics`` is None.
    """
    from mawdo.planning.metrics import static_optimum

    try:
        l_star, l_star_error = static_optimum(res.scenario), None
    except Exception as exc:  # noqa: BLE001 - metrics without L* are still worth having
        l_star, l_star_error = float("nan"), f"static optimum: {_one_line(exc)}"
    return _metrics(res, l_star, l_star_error, snapshots)


def _metrics(res, l_star: float, l_star_error: str | None, snapshots: int):
    """``(metrics, error)``: every metric, else those without oracle calls (with the reason
    in ``metrics_error``), else ``(None, reason)``."""
    from mawdo.planning.metrics import run_metrics

    errors = [l_star_error] if l_star_error else []
    try:
        m = run_metrics(res, l_star=l_star, snapshots=snapshots)
    except Exception as exc:  # noqa: BLE001 - keep the run, lose only the failing metric
        errors.append(f"full metrics: {_one_line(exc)}")
        try:
            m = run_metrics(res, l_star=l_star, snapshots=0)
        except Exception as exc2:  # noqa: BLE001
            errors.append(_one_line(exc2))
            return None, "; ".join(errors)
    if errors:
        m["metrics_error"] = "; ".join(errors)
    return m, None


def _one_line(exc: BaseException) -> str:
    return "".join(traceback.format_exception_only(exc)).strip()
