"""Study kinds: a test-only kind plugs into the same runner and store (issue 11), typed rows,
and the store schema bump.

The ``dice`` kind below is defined here and nowhere in the package: registering it touches no
shared module, and it is run (in process and on a local pool), resumed and reported through
``run_plan`` and ``Store`` exactly as the built-in kinds are.
"""

from __future__ import annotations

import dataclasses
import json
import sqlite3
from pathlib import Path
from typing import Any, ClassVar, Literal

import numpy as np
import pytest
from pydantic import Field

from mawdo.experiments import (
    STUDY_KINDS,
    RunRow,
    Store,
    StoreError,
    StudyKind,
    StudyPlanBase,
    Task,
    column,
    execute_task,
    register_kind,
    run_plan,
)
from mawdo.experiments.kinds.benchmark import BenchmarkRow
from mawdo.experiments.kinds.planning import PlanningRow
from mawdo.experiments.rows import schema
from mawdo.streams import name_word, seed_word

from .conftest import small_plan


# ---------------------------------------------------------------------- the test-only kind
class DicePlan(StudyPlanBase):
    """Each run rolls ``rolls`` dice with ``sides`` sides; algorithms are just labels."""

    study_kind: ClassVar[str] = "dice"
    kind: Literal["dice"] = "dice"
    algorithms: tuple[str, ...] = ("fair", "loaded")
    sides: int = Field(6, ge=2)
    rolls: int = Field(5, ge=1)
    runs: int = Field(4, ge=1)
    seed: int = 7
    batch_size: int = 1

    @property
    def total_runs(self) -> int:
        return len(self.algorithms) * self.runs

    def tasks(self, done=()) -> list[Task]:
        done = set(done)
        return [
            Task(a, f"d{self.sides}", k, 1)
            for a in self.algorithms
            for k in range(self.runs)
            if (a, f"d{self.sides}", k) not in done
        ]

    def task_spec(self, task: Task) -> dict[str, Any]:
        return {
            "kind": self.kind,
            **task.key(),
            "sides": self.sides,
            "rolls": self.rolls,
            "seeds": [seed_word([self.seed, name_word(task.algorithm), k]) for k in task.runs],
        }

    def describe(self) -> str:
        return f"{self.name}: {len(self.algorithms)} dice x {self.runs} runs"


@dataclasses.dataclass(frozen=True)
class DiceRow(RunRow):
    total: int | None = column("int")
    faces: np.ndarray | None = column("i64")


def execute_dice(spec: dict[str, Any]) -> list[DiceRow]:
    rows = []
    for i, seed in enumerate(spec["seeds"]):
        faces = np.random.default_rng(seed).integers(1, spec["sides"] + 1, spec["rolls"])
        if spec["algorithm"] == "loaded":
            faces = np.maximum(faces, spec["sides"] - 1)
        rows.append(
            DiceRow(run=spec["first_run"] + i, wall_time=0.0, total=int(faces.sum()), faces=faces)
        )
    return rows


def report_dice(store_path, out_dir) -> Path:
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with Store.read(store_path) as store:
        means = {}
        for a, _, r in store.rows():
            means.setdefault(a, []).append(r.total)
    path = out / "dice.json"
    path.write_text(json.dumps({a: float(np.mean(v)) for a, v in means.items()}))
    return path


register_kind(StudyKind("dice", DicePlan, execute_dice, DiceRow, report=report_dice))


def expected_totals(plan: DicePlan) -> dict[tuple[str, int], int]:
    """The same numbers computed directly (no runner, no store)."""
    out = {}
    for a in plan.algorithms:
        for k in range(plan.runs):
            rng = np.random.default_rng(seed_word([plan.seed, name_word(a), k]))
            faces = rng.integers(1, plan.sides + 1, plan.rolls)
            if a == "loaded":
                faces = np.maximum(faces, plan.sides - 1)
            out[a, k] = int(faces.sum())
    return out


# ---------------------------------------------------------------------- the kind end to end
def test_a_test_only_kind_runs_resumes_and_reports_through_the_shared_harness(tmp_path):
    plan = DicePlan()
    db = tmp_path / "dice.db"
    # "interrupted" session: only three tasks were stored
    with Store.open(db, plan) as store:
        for task in plan.tasks()[:3]:
            store.write_task(execute_task(plan.task_spec(task)))
    summary = run_plan(plan, db, progress=False)
    assert (summary.skipped, summary.done, summary.complete) == (3, 5, True)
    with Store.read(db) as store:
        assert isinstance(store.plan, DicePlan) and store.plan == plan
        got = {(a, r.run): r.total for a, _, r in store.rows()}
        assert all(type(r) is DiceRow for _, _, r in store.rows())
        faces = [r.faces for _, _, r in store.rows()]
    assert got == expected_totals(plan)
    assert all(f.dtype == np.int64 and f.shape == (plan.rolls,) for f in faces)
    means = json.loads(STUDY_KINDS["dice"].report(db, tmp_path / "rep").read_text())
    exp = expected_totals(plan)
    assert means["loaded"] == pytest.approx(np.mean([exp["loaded", k] for k in range(4)]))
    # resuming a complete store computes nothing
    assert run_plan(plan, db, progress=False).done == 0


def test_a_test_only_kind_runs_on_a_local_pool(tmp_path):
    plan = DicePlan(runs=3)
    summary = run_plan(plan, tmp_path / "pool.db", workers=2, progress=False)
    assert summary.complete and summary.lost == 0
    with Store.read(tmp_path / "pool.db") as store:
        got = {(a, r.run): r.total for a, _, r in store.rows()}
        workers = {t["worker"] for t in store.task_log()}
    assert got == expected_totals(plan)
    assert len(workers) >= 1 and all(":" in w for w in workers)


# ---------------------------------------------------------------------- typed rows
def test_rows_of_different_kinds_share_only_the_common_fields():
    common = {n for n, _ in schema(RunRow)}
    bench = {n for n, _ in schema(BenchmarkRow)}
    planning = {n for n, _ in schema(PlanningRow)}
    assert bench & planning == common == {"run", "wall_time", "error_text"}
    assert {"fun", "nit", "curve"} <= bench and {"metrics", "route"} <= planning


def test_a_store_refuses_rows_of_another_kind(tmp_path):
    plan = small_plan()
    with Store.open(tmp_path / "b.db", plan) as store:
        bad = {
            "task": Task("gwo", "quartic", 0, 1).key(),
            "rows": [DiceRow(run=0, total=3)],
            "wall": 0.0,
        }
        with pytest.raises(StoreError, match="BenchmarkRow was expected, got DiceRow"):
            store.write_task(bad)
        assert store.count() == 0


def test_a_store_of_another_kind_is_refused(tmp_path):
    run_plan(DicePlan(runs=1), tmp_path / "k.db", progress=False)
    with pytest.raises(StoreError, match="another study kind"):
        Store.open(tmp_path / "k.db", small_plan())


def test_a_plugin_kind_must_declare_its_row_fields():
    @dataclasses.dataclass(frozen=True)
    class Sloppy(RunRow):
        value: float | None = None  # not declared with column()

    with pytest.raises(ValueError, match="Sloppy.value is not declared"):
        StudyKind("dice", DicePlan, execute_dice, Sloppy)


# ---------------------------------------------------------------------- schema bump
def _old_store(path: Path) -> None:
    """A schema-2 store as mawdo wrote it before study kinds (meta without study_kind)."""
    conn = sqlite3.connect(path)
    conn.executescript(
        "CREATE TABLE meta (id INTEGER PRIMARY KEY, schema_version INTEGER, plan_hash TEXT, "
        "plan_json TEXT, library_version TEXT, created TEXT);"
        "CREATE TABLE runs (plan_hash TEXT, algorithm TEXT, function TEXT, shifted INTEGER, "
        "run INTEGER, fun REAL, error_text TEXT);"
        "CREATE TABLE tasks (id INTEGER PRIMARY KEY, algorithm TEXT);"
    )
    conn.execute(
        "INSERT INTO meta VALUES (1, 2, 'abc', ?, '0.1.0', 'then')", (small_plan().to_json(),)
    )
    conn.execute("INSERT INTO runs VALUES ('abc', 'gwo', 'quartic', 0, 0, 1.5, NULL)")
    conn.commit()
    conn.close()


def test_an_old_store_is_refused_with_what_to_do(tmp_path):
    db = tmp_path / "old.db"
    _old_store(db)
    for opener in (lambda: Store.read(db), lambda: Store.open(db, small_plan())):
        with pytest.raises(StoreError, match="store schema 2") as err:
            opener()
        msg = str(err.value)
        assert "Re-run" in msg and "--force" in msg and "schema 3" in msg
    # --force rebuilds it in the new layout
    plan = small_plan(functions=["quartic"], algorithms=["gwo"], runs=2)
    assert run_plan(plan, db, progress=False, force=True).complete
    with Store.read(db) as store:
        assert store.meta["schema_version"] == 3 and store.count() == 2


def test_a_store_of_an_unregistered_kind_says_what_to_import(tmp_path, monkeypatch):
    run_plan(DicePlan(runs=1), tmp_path / "u.db", progress=False)
    items = {k: v for k, v in STUDY_KINDS._items.items() if k != "dice"}
    monkeypatch.setattr(STUDY_KINDS, "_items", items)
    with pytest.raises(StoreError, match="unknown study kind 'dice'.*import the module"):
        Store.read(tmp_path / "u.db")


def test_missing_run_tasks_cut_contiguous_stretches_into_batches():
    from mawdo.experiments.protocol import Task, missing_run_tasks

    done = {("a", "p", 0), ("a", "p", 1), ("a", "p", 3), ("b", "p", 4)}
    got = missing_run_tasks("a", "p", 7, done, batch_size=2)
    # missing 2 | 4 5 6 -> (2), (4, 5), (6)
    assert got == [Task("a", "p", 2, 1), Task("a", "p", 4, 2), Task("a", "p", 6, 1)]
    assert missing_run_tasks("a", "p", 3, set(), batch_size=5) == [Task("a", "p", 0, 3)]
    assert missing_run_tasks("a", "p", 2, {("a", "p", 0), ("a", "p", 1)}, 4) == []


def test_registering_a_kind_again_keeps_the_first_and_a_name_clash_is_refused():
    first = STUDY_KINDS["dice"]
    again = register_kind(StudyKind("dice", DicePlan, execute_dice, DiceRow))  # as after a reload
    assert again is first and STUDY_KINDS["dice"] is first

    class OtherPlan(DicePlan):
        pass

    with pytest.raises(ValueError, match="already registered"):
        register_kind(StudyKind("dice", OtherPlan, execute_dice, DiceRow))
    assert STUDY_KINDS["dice"] is first
