"""``retry_failed`` / ``--retry-failed`` (issue 28, item 1): runs stored with an error are
computed again on request, each one's new row replacing it in one transaction; a planner's
honest failure (no error) is a result and stays."""

from __future__ import annotations

import json
import os
import sqlite3
import subprocess
import sys
from pathlib import Path

from mawdo.experiments import Store, run_plan
from mawdo.experiments.kinds.benchmark import execute as bench_exec_mod

from .conftest import SMALL, gwo_fails_on_camel, small_plan, stored_values

SRC = str(Path(__file__).resolve().parents[2] / "src")
ENV = {**os.environ, "PYTHONPATH": SRC}


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "mawdo.cli", *args], capture_output=True, text=True, env=ENV
    )


def _sql(db: Path, sql: str, args=()) -> list[tuple]:
    conn = sqlite3.connect(db)
    try:
        with conn:
            return conn.execute(sql, args).fetchall()
    finally:
        conn.close()


def _with_failures(monkeypatch, tmp_path) -> Path:
    """A store of the small plan where gwo on six_hump_camel failed (2 tasks of 2 runs)."""
    real = gwo_fails_on_camel(monkeypatch)
    db = tmp_path / "fail.db"
    assert run_plan(small_plan(), db, progress=False).failed == small_plan().runs
    monkeypatch.setattr(bench_exec_mod, "minimize", real)
    return db


def test_error_rows_are_recomputed_only_when_asked(monkeypatch, tmp_path, reference_store):
    db = _with_failures(monkeypatch, tmp_path)
    again = run_plan(small_plan(), db, progress=False)
    assert again.done == 0 and again.skipped == small_plan().total_runs
    retried = run_plan(small_plan(), db, progress=False, retry_failed=True)
    assert (retried.done, retried.failed, retried.complete) == (small_plan().runs, 0, True)
    assert stored_values(db) == stored_values(reference_store)


def test_an_interrupted_retry_loses_no_row(monkeypatch, tmp_path, reference_store):
    """The error rows are replaced task by task, never deleted ahead of their new rows."""
    db = _with_failures(monkeypatch, tmp_path)
    real, calls = bench_exec_mod.minimize, []

    def stop_at_second(fun, **kw):
        calls.append(fun)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(fun, **kw)

    monkeypatch.setattr(bench_exec_mod, "minimize", stop_at_second)
    summary = run_plan(small_plan(), db, progress=False, retry_failed=True)
    assert summary.interrupted and summary.done == small_plan().batch_size
    with Store.read(db) as store:
        assert store.count() == small_plan().total_runs
        assert store.count(failed=True) == small_plan().runs - small_plan().batch_size
    monkeypatch.setattr(bench_exec_mod, "minimize", real)
    assert run_plan(small_plan(), db, progress=False, retry_failed=True).complete
    assert stored_values(db) == stored_values(reference_store)


# the arena with the straight-line baseline alone: instant runs, and some of them fail honestly
# (the straight line meets an obstacle): success 0 without an error
ARENA = [
    "plan", "bench", "--suite", "forest,crossing", "--n", "3", "--algorithms", "",
    "--baselines", "straight", "--seed", "0", "--no-progress",
]  # fmt: skip
VALUES = "algorithm, problem, run, status, reason, scene_hash, success, length, error_text"


def test_cli_retry_failed_recomputes_errors_not_honest_failures(tmp_path):
    fresh, db = tmp_path / "fresh.db", tmp_path / "a.db"
    for path in (fresh, db):
        r = _cli(*ARENA, "--out", str(path))
        assert r.returncode == 0, r.stderr
    honest = _sql(db, "SELECT problem, run, task_id FROM runs WHERE success = 0")
    assert honest, "the plan must hold an honest failure for this test to mean something"
    # what a Ctrl-C stored before the fix: a run marked as failed by an error
    broken = _sql(db, "SELECT problem, run FROM runs WHERE success = 1 ORDER BY problem, run")[0]
    _sql(
        db,
        "UPDATE runs SET error_text = ?, success = NULL, length = NULL WHERE problem = ? "
        "AND run = ?",
        ("SystemError: CPUDispatcher(...) returned a result with an exception set", *broken),
    )
    r = _cli(*ARENA, "--out", str(db))
    assert r.returncode == 0 and "0 runs computed" in r.stdout, r.stdout + r.stderr
    assert _sql(db, "SELECT COUNT(*) FROM runs WHERE error_text IS NOT NULL") == [(1,)]

    r = _cli(*ARENA, "--out", str(db), "--retry-failed")
    assert r.returncode == 0 and "1 runs computed" in r.stdout, r.stdout + r.stderr
    order = " ORDER BY algorithm, problem, run"
    assert _sql(db, f"SELECT {VALUES} FROM runs{order}") == _sql(
        fresh, f"SELECT {VALUES} FROM runs{order}"
    )
    # the honest failures were not recomputed: same rows from the same tasks
    assert _sql(db, "SELECT problem, run, task_id FROM runs WHERE success = 0") == honest


def test_cli_bench_run_retry_failed(monkeypatch, tmp_path, reference_store):
    db = _with_failures(monkeypatch, tmp_path)
    plan_file = tmp_path / "small.toml"
    plan_file.write_text("\n".join(f"{k} = {json.dumps(v)}" for k, v in SMALL.items()))
    args = ["bench", "run", "--plan", str(plan_file), "--out", str(db), "--no-progress"]
    r = _cli(*args)
    assert r.returncode == 0 and "0 runs computed" in r.stdout, r.stdout + r.stderr
    r = _cli(*args, "--retry-failed")
    assert r.returncode == 0, r.stderr
    assert f"{small_plan().runs} runs computed" in r.stdout
    assert stored_values(db) == stored_values(reference_store)
