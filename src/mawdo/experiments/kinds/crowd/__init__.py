"""Crowd navigation, as a study kind: CrowdNav's settings x policies x seeded episodes.

Plan (:class:`CrowdPlan`, presets ``crowdnav`` and ``crowdnav-quick``), one task on a worker
(:func:`execute_crowd_task`, rows :class:`CrowdRow`) and the report
(:func:`write_crowd_report`). Importing this package registers the ``crowd`` study kind.
"""

from mawdo.experiments.kinds.crowd.execute import CrowdRow, execute_crowd_task
from mawdo.experiments.kinds.crowd.plan import CROWD_PRESETS, CrowdPlan, crowd_preset
from mawdo.experiments.kinds.crowd.report import crowd_summary, write_crowd_report
from mawdo.experiments.protocol import StudyKind, register_kind

KIND = "crowd"

register_kind(
    StudyKind(
        name=KIND,
        plan=CrowdPlan,
        execute=execute_crowd_task,
        row=CrowdRow,
        report=write_crowd_report,
        description="crowd navigation: CrowdNav settings x policies",
        presets=CROWD_PRESETS,
    )
)

__all__ = [
    "CROWD_PRESETS",
    "KIND",
    "CrowdPlan",
    "CrowdRow",
    "crowd_preset",
    "crowd_summary",
    "execute_crowd_task",
    "write_crowd_report",
]
