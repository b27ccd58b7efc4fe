"""The kind is called ``suite``; stores and plans made when it was called ``bbob`` are still read,
keep their plan hash, and resume without computing anything again."""

from __future__ import annotations

import json
import lzma
import shutil
import sqlite3
from pathlib import Path

import pytest

from mawdo.experiments import STUDY_KINDS, Store, StoreError, run_plan
from mawdo.experiments.kinds.suite import KIND, SuitePlan
from mawdo.experiments.protocol import plan_from_json

from .conftest import TINY, stored_values, tiny_plan

ROOT = Path(__file__).resolve().parents[3]
COMMITTED = ROOT / "docs" / "results" / "bbob" / "store-d5.db.xz"


def test_the_kind_is_suite_and_bbob_is_its_former_name():
    assert KIND == "suite" and tiny_plan().kind == "suite"
    assert STUDY_KINDS["bbob"] is STUDY_KINDS["suite"]
    assert "bbob" not in list(STUDY_KINDS)  # listed once, under its name
    old = SuitePlan.from_dict({**TINY, "kind": "bbob"})
    assert old == tiny_plan() and old.plan_hash == tiny_plan().plan_hash
    assert json.loads(old.to_json())["kind"] == "suite"


def test_the_committed_store_made_under_the_old_name_is_read_with_its_hash(tmp_path):
    db = tmp_path / "store-d5.db"
    with lzma.open(COMMITTED) as src, open(db, "wb") as dst:
        shutil.copyfileobj(src, dst)
    with sqlite3.connect(db) as conn:
        kind, stored_hash, plan_json = conn.execute(
            "SELECT study_kind, plan_hash, plan_json FROM meta"
        ).fetchone()
    assert kind == "bbob" and json.loads(plan_json)["kind"] == "bbob"  # made by the old name
    plan = plan_from_json(plan_json, stored=True)
    assert plan.kind == "suite" and plan.plan_hash == stored_hash  # the hash is unchanged
    with Store.read(db) as store:
        assert store.plan.kind == "suite"
        assert len(store.done_keys()) == 4800


def _rename_kind_to_bbob(path: Path) -> None:
    """What a store written under the old kind name holds: ``bbob`` in its meta row."""
    with sqlite3.connect(path) as conn:
        (plan_json,) = conn.execute("SELECT plan_json FROM meta").fetchone()
        old = json.dumps({**json.loads(plan_json), "kind": "bbob"}, sort_keys=True)
        conn.execute("UPDATE meta SET study_kind = 'bbob', plan_json = ?", (old,))
    conn.close()


def test_resuming_a_store_of_the_old_name_computes_nothing(tmp_path):
    plan = tiny_plan(functions=[1], instances=[1], dims=[2], algorithms=["random"], runs=2)
    path = tmp_path / "old.db"
    assert run_plan(plan, path, workers=1, progress=False).done == 2
    _rename_kind_to_bbob(path)
    before = stored_values(path)
    again = run_plan(plan, path, workers=1, progress=False)
    assert again.done == 0 and again.skipped == 2 and again.complete
    assert stored_values(path) == before
    with sqlite3.connect(path) as conn:  # the store is left as it was made
        assert conn.execute("SELECT study_kind FROM meta").fetchone() == ("bbob",)
    conn.close()


def test_a_store_of_another_kind_is_still_refused(tmp_path):
    plan = tiny_plan(functions=[1], instances=[1], dims=[2], algorithms=["random"], runs=1)
    path = tmp_path / "other.db"
    run_plan(plan, path, workers=1, progress=False)
    with sqlite3.connect(path) as conn:
        conn.execute("UPDATE meta SET study_kind = 'benchmark'")
    conn.close()
    with pytest.raises(StoreError, match="another study kind"):
        run_plan(plan, path, workers=1, progress=False)
