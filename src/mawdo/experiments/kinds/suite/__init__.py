"""The standard black-box study: BBOB through ``ioh``, CEC 2017/2022 from the
official code (or through ``opfunu``), COCO's protocol and measures, the CEC competitions'
tables and presets (:mod:`.official`, :mod:`.competition`), IOHanalyzer and CEC exports.

Plan (:class:`SuitePlan`, presets ``bbob-quick`` and ``bbob-full``), one task on a worker
(:func:`execute_suite_task`, rows :class:`SuiteRow` holding each run's best-so-far against
evaluations), reading back (:mod:`.data`), measures (:mod:`.measures`), tables and report
(:mod:`.report`), figures (:mod:`.plots`), IOHanalyzer and CEC exports (:mod:`.export`,
:mod:`.cec_export`), COCO's measures
as array functions (:mod:`.metrics`) and ioh's log format (:mod:`.ioh_logs`); the WDO family's
component study (presets ``wdo-components`` and ``wdo-components-quick`` from
:mod:`.components`, each switch's effect per function group in :mod:`.effects`; WDO+'s on CEC
2017, preset ``wdo-plus-components-cec2017``, findings from :mod:`.plus_components_summary`) and the
hold-out study that judges WDO+ (presets in :mod:`.holdout`; its paragraph and rank tables from
the CEC and F1-F16 stores in :mod:`.holdout_summary`, read by :mod:`.holdout_data`). Importing this
package registers the ``suite`` study kind (called ``bbob`` before: stores and plans that say
``kind = "bbob"`` are read as it).
"""

from mawdo.experiments.kinds.suite.cec_export import export_cec
from mawdo.experiments.kinds.suite.execute import SuiteRow, execute_suite_task
from mawdo.experiments.kinds.suite.export import EXPORT_FORMATS, export_ioh
from mawdo.experiments.kinds.suite.keys import parse_ids
from mawdo.experiments.kinds.suite.plan import (
    KIND,
    OLD_KIND_NAMES,
    PRESET_HELP,
    PRESETS,
    SuitePlan,
    preset_plan,
)
from mawdo.experiments.kinds.suite.report import write_suite_report
from mawdo.experiments.protocol import StudyKind, register_kind

register_kind(
    StudyKind(
        name=KIND,
        plan=SuitePlan,
        execute=execute_suite_task,
        row=SuiteRow,
        report=write_suite_report,
        description="standard suites (BBOB via ioh, CEC 2017/2022) under COCO's protocol",
        aliases=OLD_KIND_NAMES,
        presets=PRESETS,
        preset_help=PRESET_HELP,
        report_merges_stores=True,
    )
)

__all__ = [
    "KIND",
    "OLD_KIND_NAMES",
    "PRESETS",
    "PRESET_HELP",
    "SuitePlan",
    "SuiteRow",
    "EXPORT_FORMATS",
    "execute_suite_task",
    "export_cec",
    "export_ioh",
    "parse_ids",
    "preset_plan",
    "write_suite_report",
]
