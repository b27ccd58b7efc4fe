"""The planning arena: seeded scene families x planners, as a study kind.

Plan (:class:`ArenaPlan`, presets ``arena-default``, ``arena-quick`` and ``arena-large``), one
task on a worker (:func:`execute_arena_task`, rows :class:`ArenaRow`: the scene's TOML and hash
beside each run's metrics) and the report (:func:`write_arena_report`: per family and planner
tables, runtime and gap ECDFs, a failure gallery). Importing this package registers the
``arena`` study kind.
"""

from mawdo.experiments.kinds.arena.execute import ArenaRow, execute_arena_task
from mawdo.experiments.kinds.arena.plan import (
    ARENA_PRESETS,
    ORACLE,
    ArenaPlan,
    arena_preset,
)
from mawdo.experiments.kinds.arena.report import arena_tables, write_arena_report
from mawdo.experiments.protocol import StudyKind, register_kind

KIND = "arena"

register_kind(
    StudyKind(
        name=KIND,
        plan=ArenaPlan,
        execute=execute_arena_task,
        row=ArenaRow,
        report=write_arena_report,
        description="planning arena: generated scene families x planners",
        presets=ARENA_PRESETS,
    )
)

__all__ = [
    "ARENA_PRESETS",
    "KIND",
    "ORACLE",
    "ArenaPlan",
    "ArenaRow",
    "arena_preset",
    "arena_tables",
    "execute_arena_task",
    "write_arena_report",
]
