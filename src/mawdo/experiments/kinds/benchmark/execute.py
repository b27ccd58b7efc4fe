"""One benchmark task on a worker: a vectorised batch of runs of one algorithm on one function.

``mawdo.minimize`` makes run ``k`` identical whether it is computed alone or in any batch, so a
task's rows depend on its spec only.
"""

from __future__ import annotations

import time
import traceback
from dataclasses import dataclass
from typing import Any

import numpy as np

from mawdo.experiments.rows import RunRow, column
from mawdo.minimize import minimize


@dataclass(frozen=True)
class BenchmarkRow(RunRow):
    """One stored benchmark run.

    Attributes
    ----------
    seed_entropy : list of int
        Entropy of the seed sequence whose run-th child seeded the run.
    shift_seed : int or None
        Seed of the shifted optimum (shifted suite only).
    params : dict
        The optimizer's resolved parameters.
    fun, f_star, error : float or None
        Best value found, the function's optimum, and ``fun - f_star``.
    nfev, nit, status : int or None
        Evaluations, iterations and the termination status of ``minimize``.
    curve : numpy.ndarray
        Best-so-far value after each iteration.
    curve_nfev : numpy.ndarray
        Evaluations spent after each iteration (same length as ``curve``).
    """

    seed_entropy: list | None = column("json")
    shift_seed: int | None = column("int")
    params: dict | None = column("json")
    fun: float | None = column("real", required=True)
    error: float | None = column("real")
    f_star: float | None = column("real")
    nfev: int | None = column("int", required=True)
    nit: int | None = column("int", required=True)
    status: int | None = column("int", required=True)
    curve: np.ndarray | None = column("f64", required=True)
    curve_nfev: np.ndarray | None = column("i64", required=True)


def _budget(spec: dict[str, Any]) -> dict[str, int]:
    if spec["budget"] == "iterations":
        return {"max_iter": spec["max_iter"]}
    # Equal evaluations: pop_size * max_iter each; minimize derives T from it for schedules.
    return {"max_evals": spec["pop_size"] * spec["max_iter"]}


def execute_benchmark_task(spec: dict[str, Any]) -> list[BenchmarkRow]:
    """Compute one task (see :meth:`ExperimentPlan.task_spec`) and return its rows.

    Runs on a worker; module-level (pickled by reference). An exception from the algorithm or
    the objective becomes one row per run with ``error_text`` set, so a bad corner of a sweep is
    recorded rather than killing it.
    """
    t0 = time.perf_counter()
    first, n = spec["first_run"], spec["n_runs"]
    common = {"seed_entropy": spec["seed_entropy"], "shift_seed": spec["shift_seed"]}
    try:
        res = minimize(
            spec["problem"],
            algorithm=spec["algorithm"],
            runs=n,
            seed=np.random.SeedSequence(spec["seed_entropy"]),
            first_run=first,
            shifted=spec["shifted"],
            shift_seed=spec["shift_seed"] or 0,
            preset=spec["bounds_preset"],
            pop_size=spec["pop_size"],
            **spec["options"],
            **_budget(spec),
        )
    except Exception as exc:  # noqa: BLE001 - any failure of user/algorithm code is recorded
        wall = time.perf_counter() - t0
        text = "".join(traceback.format_exception_only(exc)).strip()
        params = {"pop_size": spec["pop_size"], **spec["options"]}
        return [
            BenchmarkRow(
                run=first + i, wall_time=wall / n, error_text=text, params=params, **common
            )
            for i in range(n)
        ]
    wall = time.perf_counter() - t0
    f_star = None if res.f_star is None else float(res.f_star)
    rows = []
    for i in range(n):
        fun = float(res.fun[i])
        rows.append(
            BenchmarkRow(
                run=first + i,
                # Runs share one vectorised batch; a run's time is the batch's share.
                wall_time=wall / n,
                fun=fun,
                f_star=f_star,
                error=None if f_star is None else fun - f_star,
                nfev=int(res.nfev[i]),
                nit=int(res.nit[i]),
                status=int(res.status[i]),
                params=res.params,
                curve=np.asarray(res.history[i], dtype=float),
                curve_nfev=np.asarray(res.history_nfev[i], dtype=np.int64),
                **common,
            )
        )
    return rows
