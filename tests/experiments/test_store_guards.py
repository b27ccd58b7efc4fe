"""Guards of the shared store (issue 12): one writer, rows of one plan, corrupt files refused,
a clean file left on every exit path. Library level; the same cases through the real command
are in tests/test_cli_guards.py."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys

import pytest

from mawdo.experiments import Store, StoreError, Task
from mawdo.experiments.lock import lock_path

from .conftest import small_plan
from .test_store import outcome


def _header_journal(path) -> tuple[int, int]:
    """Bytes 18 and 19 of the SQLite header: 1 = rollback (DELETE) journal, 2 = WAL."""
    h = path.read_bytes()[:20]
    return h[18], h[19]


def test_a_second_writer_is_refused_naming_the_holder(tmp_path):
    plan = small_plan()
    path = tmp_path / "s.db"
    with Store.open(path, plan) as first:
        first.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
        with pytest.raises(StoreError) as info:
            Store.open(path, small_plan(max_iter=20), force=True)
        msg = str(info.value)
        assert "being written by another process" in msg
        assert f"pid {os.getpid()}" in msg and "started" in msg and "command:" in msg
        # the refused --force deleted nothing, and the first writer goes on writing
        first.write_task(outcome(plan, Task("gwo", "quartic", 2, 2)))
        assert first.count() == 4
    assert not lock_path(path).exists()  # a closed store is one file again
    with Store.read(path) as store:
        assert store.plan.plan_hash == plan.plan_hash
        assert store.count() == 4


_HOLD = """
import sys, time
from mawdo.experiments import Store
sys.path.insert(0, {tests!r})
from experiments.conftest import small_plan
s = Store.open({path!r}, small_plan())
print("locked", flush=True)
time.sleep(600)
"""


def test_the_lock_of_a_killed_writer_is_taken_over(tmp_path):
    path = tmp_path / "s.db"
    tests = os.path.dirname(os.path.dirname(__file__))
    code = _HOLD.format(tests=tests, path=str(path))
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "locked"
        with pytest.raises(StoreError, match=f"pid {proc.pid}"):
            Store.open(path, small_plan())
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=10)
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.stdout.close()
    assert lock_path(path).exists()  # left behind by kill -9, describing a dead process
    with Store.open(path, small_plan()) as store:  # taken over without any manual step
        store.write_task(outcome(store.plan, Task("gwo", "quartic", 0, 2)))
    with Store.read(path) as store:
        assert store.count() == 2


def _tamper(path, sql: str, *args) -> None:
    conn = sqlite3.connect(path)
    with conn:
        conn.execute(sql, args)
    conn.execute("PRAGMA journal_mode=DELETE")
    conn.close()


def test_rows_of_another_plan_are_refused_on_open_and_on_read(tmp_path):
    plan = small_plan()
    path = tmp_path / "s.db"
    with Store.open(path, plan) as store:
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
    _tamper(path, "UPDATE runs SET plan_hash = ? WHERE run = 1", "f" * 64)
    before = path.read_bytes()
    with pytest.raises(StoreError, match="mixes plans.*1 of plan ffffffffffff"):
        Store.read(path)
    with pytest.raises(StoreError, match="mixes plans.*--force"):
        Store.open(path, plan)
    assert path.read_bytes() == before
    with Store.open(path, plan, force=True) as store:  # --force starts over
        assert store.count() == 0


def test_a_task_computed_for_another_plan_is_not_written(tmp_path):
    plan = small_plan()
    path = tmp_path / "s.db"
    with Store.open(path, plan) as store:
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
        other = {**outcome(plan, Task("gwo", "quartic", 2, 2)), "plan_hash": "e" * 64}
        with pytest.raises(StoreError, match="computed for plan eeeeeeeeeeee"):
            store.write_task(other)
        assert store.count() == 2


def test_a_store_reset_behind_the_writer_gets_no_more_rows(tmp_path):
    # Something that ignores the lock (another program) re-plans the store mid-sweep: the
    # writer checks the meta row inside each write transaction and stops.
    plan = small_plan()
    path = tmp_path / "s.db"
    with Store.open(path, plan) as store:
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
        other = sqlite3.connect(path)
        with other:
            other.execute("UPDATE meta SET plan_hash = ?", ("d" * 64,))
        other.close()
        with pytest.raises(StoreError, match="reset to another plan"):
            store.write_task(outcome(plan, Task("gwo", "quartic", 2, 2)))
        assert store.count() == 2


def _corrupt_middle(path, size: int = 8192) -> bytes:
    data = bytearray(path.read_bytes())
    mid = len(data) // 2
    data[mid : mid + size] = os.urandom(size)
    path.write_bytes(bytes(data))
    return bytes(data)


def test_a_store_overwritten_mid_file_is_refused_with_a_recovery_hint(tmp_path):
    plan = small_plan()
    path = tmp_path / "s.db"
    with Store.open(path, plan) as store:
        for k in range(0, 4, 2):
            for a in plan.algorithms:
                for f in plan.functions:
                    store.write_task(outcome(plan, Task(a, f, k, 2)))
    assert path.stat().st_size > 4 * 8192
    damaged = _corrupt_middle(path)
    for action in (lambda: Store.open(path, plan), lambda: Store.read(path)):
        with pytest.raises(StoreError) as info:
            action()
        assert "corrupt" in str(info.value) and "Recover" in str(info.value)
    assert path.read_bytes() == damaged  # refused, not "repaired" or reset


def test_a_refused_open_leaves_the_file_as_it_was_in_delete_mode(tmp_path):
    plan = small_plan()
    path = tmp_path / "s.db"
    with Store.open(path, plan) as store:
        assert store.conn.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
    assert _header_journal(path) == (1, 1)
    before = path.read_bytes()
    with pytest.raises(StoreError, match="another plan"):
        Store.open(path, small_plan(max_iter=20))
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.db"]


def _left_in_wal_mode(path):
    plan = small_plan()
    with Store.open(path, plan) as store:
        store.write_task(outcome(plan, Task("gwo", "quartic", 0, 2)))
    conn = sqlite3.connect(path)
    conn.execute("PRAGMA journal_mode=WAL")  # as a writer killed with -9 leaves it
    conn.close()
    assert _header_journal(path) == (2, 2)


def _as_on_read_only_media(monkeypatch):
    # Root can always create the -shm file, so read-only media are simulated: the plain
    # read-only connection fails the way SQLite fails there.
    import mawdo.experiments.sqlitefile as sf

    real = sqlite3.connect

    def connect(database, *a, **k):
        if "mode=ro" in str(database):
            raise sqlite3.OperationalError("unable to open database file")
        return real(database, *a, **k)

    monkeypatch.setattr(sf.sqlite3, "connect", connect)


def test_a_store_left_in_wal_mode_reads_on_read_only_media(tmp_path, monkeypatch):
    path = tmp_path / "s.db"
    _left_in_wal_mode(path)
    _as_on_read_only_media(monkeypatch)
    with Store.read(path) as store:
        assert store.count() == 2


def test_a_pending_wal_on_read_only_media_is_named(tmp_path, monkeypatch):
    path = tmp_path / "s.db"
    _left_in_wal_mode(path)
    (tmp_path / "s.db-wal").write_bytes(b"x" * 100)
    _as_on_read_only_media(monkeypatch)
    with pytest.raises(StoreError, match="s.db-wal holds runs not yet folded"):
        Store.read(path)
