"""The path-planning study (paper Table 6, Figs. 2-3): algorithms x runs on a scenario.

Plan (:class:`StudyPlan`, presets), one task on a worker (:func:`execute_planning_task`, rows
:class:`PlanningRow`) and the report (:func:`write_study_report`). Importing this package
registers the ``planning`` study kind. (The planner itself is :mod:`mawdo.planning`, a floor
below.)
"""

from mawdo.experiments.kinds.planning.execute import PlanningRow, execute_planning_task
from mawdo.experiments.kinds.planning.plan import (
    BASELINE,
    STUDY_PRESETS,
    StudyPlan,
    study_preset,
)
from mawdo.experiments.kinds.planning.report import write_study_report
from mawdo.experiments.protocol import StudyKind, register_kind

KIND = "planning"

register_kind(
    StudyKind(
        name=KIND,
        plan=StudyPlan,
        execute=execute_planning_task,
        row=PlanningRow,
        report=write_study_report,
        description="path planning: algorithms x runs on a scenario (Table 6)",
        presets=STUDY_PRESETS,
    )
)

__all__ = [
    "BASELINE",
    "KIND",
    "STUDY_PRESETS",
    "PlanningRow",
    "StudyPlan",
    "execute_planning_task",
    "study_preset",
    "write_study_report",
]
