"""The SQLite results store: round trip, atomic tasks, refusals and bad files."""

from __future__ import annotations

import os
import sqlite3
import stat

import numpy as np
import pytest

from mawdo.experiments import Store, StoreError, Task, run_plan
from mawdo.experiments.kinds.benchmark import BenchmarkRow
from mawdo.experiments.kinds.benchmark.data import curves

from .conftest import small_plan


def outcome(plan, task: Task, value: float = 1.5, bad_run: int | None = None) -> dict:
    """A synthetic executed task (what a worker returns)."""
    rows = []
    for k in task.runs:
        rows.append(
            BenchmarkRow(
                run=bad_run if (bad_run is not None and k == task.runs[-1]) else k,
                fun=value + k,
                error=value + k + 1.0,
                f_star=-1.0,
                nfev=60 + k,
                nit=5,
                status=0,
                wall_time=0.01,
                params={"pop_size": np.int64(12)},
                curve=np.linspace(10.0, value + k, 5),
                curve_nfev=np.arange(12, 61, 12),
                seed_entropy=[123, 456],
                shift_seed=None,
                error_text=None,
            )
        )
    return {
        "task": {
            "algorithm": task.algorithm,
            "problem": task.problem,
            "first_run": task.first_run,
            "n_runs": task.n_runs,
        },
        "rows": rows,
        "wall": 0.02,
        "worker": "test:1",
    }


def test_round_trip(tmp_path):
    plan = small_plan()
    task = Task("gwo", "quartic", 2, 2)
    with Store.open(tmp_path / "s.db", plan) as store:
        store.write_task(outcome(plan, task))
        assert store.done_keys() == {("gwo", "quartic", 2), ("gwo", "quartic", 3)}
    with Store.read(tmp_path / "s.db") as store:
        assert store.plan == plan
        recs = [r for _, _, r in store.rows()]
        assert all(type(r) is BenchmarkRow for r in recs)
        assert [r.run for r in recs] == [2, 3]
        np.testing.assert_array_equal(recs[1].curve, np.linspace(10.0, 4.5, 5))
        np.testing.assert_array_equal(recs[1].curve_nfev, [12, 24, 36, 48, 60])
        assert recs[0].fun == 3.5 and recs[0].params == {"pop_size": 12}
        assert recs[0].seed_entropy == [123, 456] and not recs[0].failed
        assert store.task_log()[0]["n_runs"] == 2
        c, n, f_star = curves(store, "gwo", "quartic")
        assert c.shape == n.shape == (2, 5) and f_star == -1.0


def test_closed_store_is_one_file(tmp_path):
    plan = small_plan()
    with Store.open(tmp_path / "s.db", plan) as store:
        assert store.conn.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.db"]


def test_a_task_is_written_atomically(tmp_path):
    plan = small_plan()
    with Store.open(tmp_path / "s.db", plan) as store:
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
        # second task's last row collides with stored run 0: the whole task must roll back
        with pytest.raises(StoreError, match="computed twice"):
            store.write_task(outcome(plan, Task("gwo", "quartic", 2, 2), bad_run=0))
        assert store.done_keys() == {("gwo", "quartic", 0), ("gwo", "quartic", 1)}
        assert len(store.task_log()) == 1


def test_store_of_another_plan_is_refused_unless_forced(tmp_path):
    path = tmp_path / "s.db"
    plan = small_plan()
    with Store.open(path, plan) as store:
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
    other = small_plan(runs=5)
    with pytest.raises(StoreError) as info:
        Store.open(path, other)
    msg = str(info.value)
    assert str(path) in msg and "another plan" in msg and "runs (4 -> 5)" in msg
    assert "--force" in msg and "2 stored runs" in msg
    # the refused store is untouched
    with Store.read(path) as store:
        assert store.count() == 2 and store.plan == plan
    with Store.open(path, other, force=True) as store:
        assert store.count() == 0 and store.plan == other
    with Store.read(path) as store:
        assert store.meta["plan_hash"] == other.plan_hash


def test_store_of_another_library_version_is_refused_unless_forced(tmp_path):
    path = tmp_path / "s.db"
    plan = small_plan()
    Store.open(path, plan).close()
    conn = sqlite3.connect(path)
    with conn:
        conn.execute("UPDATE meta SET library_version = '0.0.1'")
    conn.close()
    with pytest.raises(StoreError, match=r"belongs to mawdo 0\.0\.1 \(this is mawdo "):
        Store.open(path, plan)
    Store.open(path, plan, force=True).close()
    with Store.read(path) as store:
        assert store.meta["library_version"] != "0.0.1"


def test_same_plan_reopens_and_keeps_runs(tmp_path):
    path = tmp_path / "s.db"
    plan = small_plan()
    with Store.open(path, plan) as store:
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
    # batch size and name do not change numbers, so the store is the same sweep
    with Store.open(path, small_plan(batch_size=3, name="renamed")) as store:
        assert store.count() == 2


def test_a_store_made_before_a_column_existed_resumes_and_reads_it_as_none(tmp_path):
    # a store of the same plan and version whose runs table lacks a column the row type has
    # since gained (as when a column is added between releases): resuming it must add the
    # column, keep the old rows (None there) and write the new ones whole
    path = tmp_path / "s.db"
    plan = small_plan()
    with Store.open(path, plan) as store:
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
    con = sqlite3.connect(path)
    with con:
        con.execute("ALTER TABLE runs DROP COLUMN seed_entropy")
    con.close()
    with Store.open(path, plan) as store:
        store.write_task(outcome(plan, Task("gwo", "quartic", 2, 1)))
    with Store.read(path) as store:
        recs = {r.run: r for _, _, r in store.rows()}
    assert sorted(recs) == [0, 1, 2]
    assert recs[0].seed_entropy is None and recs[1].seed_entropy is None
    assert recs[2].seed_entropy == [123, 456] and recs[2].fun == 3.5


def test_a_store_made_before_tasks_had_a_platform_reads_none_and_records_it_when_resumed(
    tmp_path,
):
    path = tmp_path / "s.db"
    plan = small_plan()
    with Store.open(path, plan) as store:
        store.write_task({**outcome(plan, Task("gwo", "quartic", 0, 2)), "platform": "A"})
    con = sqlite3.connect(path)
    with con:
        con.execute("ALTER TABLE tasks DROP COLUMN platform")
    con.close()
    with Store.read(path) as store:  # a committed store of an older release, read-only
        (old,) = store.task_log()
    assert old["platform"] is None and old["algorithm"] == "gwo" and old["n_runs"] == 2
    with Store.open(path, plan) as store:
        store.write_task({**outcome(plan, Task("gwo", "quartic", 2, 1)), "platform": "B"})
    with Store.read(path) as store:
        assert [t["platform"] for t in store.task_log()] == [None, "B"]
        assert store.count() == 3


def test_read_only_store_file_is_refused_for_writing(tmp_path):
    path = tmp_path / "s.db"
    plan = small_plan()
    Store.open(path, plan).close()
    os.chmod(path, stat.S_IRUSR | stat.S_IRGRP)
    try:
        with pytest.raises(StoreError) as info:
            Store.open(path, plan)
        assert str(path) in str(info.value) and "read-only" in str(info.value)
        with pytest.raises(StoreError, match="read-only"):
            run_plan(plan, path, progress=False)
        # reading (reports) still works
        with Store.read(path) as store:
            assert store.count() == 0
    finally:
        os.chmod(path, stat.S_IRUSR | stat.S_IWUSR)


def test_read_only_directory_is_refused(tmp_path):
    d = tmp_path / "ro"
    d.mkdir()
    os.chmod(d, stat.S_IRUSR | stat.S_IXUSR)
    try:
        with pytest.raises(StoreError) as info:
            Store.open(d / "s.db", small_plan())
        assert str(d) in str(info.value) and "read-only" in str(info.value)
    finally:
        os.chmod(d, stat.S_IRWXU)


def test_corrupt_store_file_gives_a_clear_error(tmp_path):
    path = tmp_path / "s.db"
    path.write_bytes(np.random.default_rng(0).bytes(4096))
    with pytest.raises(StoreError) as info:
        Store.open(path, small_plan())
    assert str(path) in str(info.value) and "corrupt" in str(info.value)
    with pytest.raises(StoreError, match="corrupt"):
        Store.read(path)


def test_truncated_store_file_gives_a_clear_error(tmp_path):
    path = tmp_path / "s.db"
    plan = small_plan()
    with Store.open(path, plan) as store:
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
    data = path.read_bytes()
    path.write_bytes(b"garbage!" * 16 + data[128:])  # header destroyed
    with pytest.raises(StoreError, match="corrupt"):
        Store.read(path)


def test_foreign_sqlite_file_is_refused(tmp_path):
    path = tmp_path / "other.db"
    conn = sqlite3.connect(path)
    conn.execute("CREATE TABLE songs (title TEXT)")
    conn.commit()
    conn.close()
    with pytest.raises(StoreError, match="not a mawdo results store"):
        Store.open(path, small_plan())


def test_missing_store_and_directory_path(tmp_path):
    with pytest.raises(StoreError, match="no results store"):
        Store.read(tmp_path / "absent.db")
    with pytest.raises(StoreError, match="is a directory"):
        Store.open(tmp_path, small_plan())
