"""The function benchmark (paper Tables 3 and 5): algorithms x functions x runs.

Protocol and its readings: ``docs/deviations.md#d-protocol``.

Plan (:class:`ExperimentPlan`, presets), one task on a worker (:func:`execute_benchmark_task`,
rows :class:`BenchmarkRow`), reading values back (:mod:`.data`), tables and report
(:mod:`.report`), figures (:mod:`.plots`) and the paper's published values (:mod:`.paper_values`).
Importing this package registers the ``benchmark`` study kind.
"""

from mawdo.experiments.kinds.benchmark.execute import BenchmarkRow, execute_benchmark_task
from mawdo.experiments.kinds.benchmark.plan import (
    PAPER_SEED,
    PRESET_HELP,
    PRESETS,
    ExperimentPlan,
    preset_plan,
)
from mawdo.experiments.kinds.benchmark.report import write_report
from mawdo.experiments.protocol import StudyKind, register_kind

KIND = "benchmark"

register_kind(
    StudyKind(
        name=KIND,
        plan=ExperimentPlan,
        execute=execute_benchmark_task,
        row=BenchmarkRow,
        report=write_report,
        description="benchmark functions: algorithms x functions x runs (Tables 3, 5)",
        presets=PRESETS,
        preset_help=PRESET_HELP,
    )
)

__all__ = [
    "KIND",
    "PAPER_SEED",
    "PRESETS",
    "PRESET_HELP",
    "BenchmarkRow",
    "ExperimentPlan",
    "execute_benchmark_task",
    "preset_plan",
    "write_report",
]
