"""Benchmark sweeps (SPEC 3): plans -> runner -> SQLite store -> statistics, reports, plots.

>>> from mawdo.experiments import preset_plan, run_plan, write_report
>>> plan = preset_plan("smoke")
>>> summary = run_plan(plan, "smoke.db", workers=2)        # doctest: +SKIP
>>> write_report("smoke.db", "report/")                   # doctest: +SKIP

Data flows one way: a plan is cut into tasks, the runner computes them (in process, on a local
process pool or on a Dask cluster) and the parent process stores every finished task in one
transaction; reports and plots read the store only.
"""

from mawdo.experiments.plan import (
    PRESETS,
    ExperimentPlan,
    PlanError,
    Task,
    preset_plan,
)
from mawdo.experiments.report import write_report
from mawdo.experiments.runner import RunSummary, execute_task, run_plan
from mawdo.experiments.store import RunRecord, Store, StoreError

__all__ = [
    "PRESETS",
    "ExperimentPlan",
    "PlanError",
    "RunRecord",
    "RunSummary",
    "Store",
    "StoreError",
    "Task",
    "execute_task",
    "preset_plan",
    "run_plan",
    "write_report",
]
