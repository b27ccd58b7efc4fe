"""Studies: plans -> runner -> SQLite store -> statistics, reports, plots
(docs/deviations.md#d-protocol).

>>> from mawdo.experiments import preset_plan, run_plan, write_report
>>> plan = preset_plan("smoke")
>>> summary = run_plan(plan, "smoke.db", workers=2)        # doctest: +SKIP
>>> write_report("smoke.db", "report/")                   # doctest: +SKIP

Data flows one way: a plan is cut into tasks, the runner computes them (in process, on a local
process pool or on a Dask cluster) and the parent process stores every finished task in one
transaction; reports and plots read the store only.

Layout: the harness (:mod:`.protocol` with the study-kind registry, :mod:`.plans`, :mod:`.rows`,
:mod:`.runner`, :mod:`.store`, :mod:`.stats`, :mod:`.tables`) knows no concrete kind; each kind
is a package under :mod:`.kinds` that registers itself (``benchmark``, ``planning``, ``suite``,
``arena``).
Importing this package registers the built-in kinds.
"""

# one line per study kind: importing its package registers it
from mawdo.experiments.kinds import arena, benchmark, crowd, planning, suite  # noqa: F401
from mawdo.experiments.kinds.benchmark import ExperimentPlan, preset_plan, write_report
from mawdo.experiments.kinds.benchmark.plan import PRESETS
from mawdo.experiments.plans import PlanError, StudyPlanBase
from mawdo.experiments.protocol import STUDY_KINDS, Study, StudyKind, Task, register_kind
from mawdo.experiments.rows import RunRow, column
from mawdo.experiments.runner import RunSummary, execute_task, run_plan
from mawdo.experiments.store import Store, StoreError

__all__ = [
    "PRESETS",
    "STUDY_KINDS",
    "ExperimentPlan",
    "PlanError",
    "RunRow",
    "RunSummary",
    "Store",
    "StoreError",
    "Study",
    "StudyKind",
    "StudyPlanBase",
    "Task",
    "column",
    "execute_task",
    "preset_plan",
    "register_kind",
    "run_plan",
    "write_report",
]
