"""One task of the suite study on a worker: a vectorised batch of runs on one problem.

Each run's best-so-far record against evaluations (the driver's
:class:`~mawdo.result.EvaluationTrace`: the evaluation numbers where it improved and the values
from there on) is stored whole, so the runtime to any target and the value at any budget can be
read from the store, exactly. The driver runs the task in its blocks of runs (a run's numbers
do not depend on its block).
"""

from __future__ import annotations

import time
import traceback
from dataclasses import dataclass
from typing import Any

import numpy as np

from mawdo.experiments.rows import RunRow, column
from mawdo.suites import evaluation_budget, get_problem, run_problem


@dataclass(frozen=True)
class SuiteRow(RunRow):
    """One stored run on a suite problem.

    Attributes
    ----------
    suite : str
        ``"bbob"``, ``"cec2017"`` or ``"cec2022"``.
    function_id, instance, dim : int
        The problem.
    function_name : str
        The library's name of the function (IOHanalyzer shows it).
    seed_entropy : list of int
        Entropy of the seed sequence whose run-th child seeded the run.
    params : dict
        The optimizer's resolved parameters.
    f_star : float
        The problem's optimum value (the library's).
    fun : float
        Best value found; ``precision = fun - f_star`` (>= 0).
    nfev : int
        Evaluations spent (``<= max_evals``; fewer when the final target was reached).
    max_evals : int
        The run's budget, ``ceil(budget * D)``.
    status : int
        Termination status of ``minimize`` (see :mod:`mawdo.result`).
    evals : numpy.ndarray of int64
        1-based evaluation numbers at which the best-so-far improved, increasing.
    best_so_far : numpy.ndarray of float
        Best raw value ``f`` from each of those evaluations on, strictly decreasing.
    best_x : numpy.ndarray
        The best point, shape ``(D,)``.
    """

    suite: str | None = column("text")
    function_id: int | None = column("int")
    instance: int | None = column("int")
    dim: int | None = column("int")
    function_name: str | None = column("text")
    seed_entropy: list | None = column("json")
    params: dict | None = column("json")
    f_star: float | None = column("real")
    fun: float | None = column("real", required=True)
    precision: float | None = column("real", required=True)
    nfev: int | None = column("int", required=True)
    max_evals: int | None = column("int")
    status: int | None = column("int", required=True)
    evals: np.ndarray | None = column("i64", required=True)
    best_so_far: np.ndarray | None = column("f64", required=True)
    best_x: np.ndarray | None = column("f64")


def execute_suite_task(spec: dict[str, Any]) -> list[SuiteRow]:
    """Compute one task (see :meth:`SuitePlan.task_spec`) and return its rows.

    Module-level (pickled by reference). An exception of the algorithm becomes one row per run
    with ``error_text``; a missing library is not caught here (the command checks it first).
    """
    t0 = time.perf_counter()
    first, n = spec["first_run"], spec["n_runs"]
    problem = get_problem(spec["suite"], spec["function_id"], spec["instance"], spec["dim"])
    common = {
        "suite": spec["suite"],
        "function_id": spec["function_id"],
        "instance": spec["instance"],
        "dim": spec["dim"],
        "function_name": problem.function_name,
        "seed_entropy": spec["seed_entropy"],
        "f_star": float(problem.f_star),
        "max_evals": evaluation_budget(spec["budget"], spec["dim"]),
    }
    try:
        res = run_problem(
            problem,
            spec["optimizer"],  # a variant's label is the row's algorithm, not the optimizer
            runs=n,
            budget=spec["budget"],
            seed=np.random.SeedSequence(spec["seed_entropy"]),
            first_run=first,
            final_target=spec["final_target"],
            **spec["options"],
        )
    except Exception as exc:  # noqa: BLE001 - a failing algorithm is recorded, not fatal
        wall = time.perf_counter() - t0
        text = "".join(traceback.format_exception_only(exc)).strip()
        return [
            SuiteRow(run=first + i, wall_time=wall / n, error_text=text, **common) for i in range(n)
        ]
    wall = time.perf_counter() - t0
    rows = []
    for i, tr in enumerate(res.evaluation_trace):
        fun = float(res.fun[i])
        rows.append(
            SuiteRow(
                run=first + i,
                wall_time=wall / n,  # runs share one vectorised batch
                params=res.params,
                fun=fun,
                precision=fun - common["f_star"],
                nfev=int(res.nfev[i]),
                status=int(res.status[i]),
                evals=np.asarray(tr.evals, dtype=np.int64),
                best_so_far=np.asarray(tr.best_y, dtype=float),
                best_x=_best_x(res, i),
                **common,
            )
        )
    return rows


def _best_x(res, i: int) -> np.ndarray:
    """Run ``i``'s best point; NaN (shape ``(D,)``) for a run that saw no finite value."""
    x = np.asarray(res.x[i], dtype=float)
    return x if np.isfinite(res.fun[i]) else np.full_like(x, np.nan)
