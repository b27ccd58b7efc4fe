"""Shared plans and helpers for the experiments tests (tiny budgets: the suite runs in seconds)."""

from __future__ import annotations

import sqlite3
import subprocess
import time
from pathlib import Path

import pytest

from mawdo.experiments import ExperimentPlan, run_plan

# Covers a noisy function (F6 draws noise from the run's stream), a low-dimensional one (MAWDO's
# stabilisation) and a multimodal one; max_iter > 50 so MAWDO's restart + OBL happens once.
SMALL = {
    "name": "small",
    "algorithms": ["gwo", "mewdo", "mawdo"],
    "functions": ["quartic", "six_hump_camel", "rastrigin"],
    "runs": 4,
    "pop_size": 12,
    "max_iter": 60,
    "seed": 123,
    "batch_size": 2,
}


def small_plan(**changes) -> ExperimentPlan:
    return ExperimentPlan.from_dict({**SMALL, **changes})


# Columns that are the same whoever computed a run and when (not wall times, not task ids).
VALUE_COLUMNS = (
    "plan_hash, algorithm, problem, run, params, seed_entropy, shift_seed, fun, "
    "error, f_star, nfev, nit, status, curve, curve_nfev, library_version, error_text"
)


def stored_values(path, columns: str = VALUE_COLUMNS) -> list[tuple]:
    """Every run's value columns, in key order (comparable across stores)."""
    conn = sqlite3.connect(path)
    try:
        return conn.execute(
            f"SELECT {columns} FROM runs ORDER BY algorithm, problem, run"
        ).fetchall()
    finally:
        conn.close()


@pytest.fixture(scope="session")
def reference_store(tmp_path_factory):
    """The SMALL plan computed in process, uninterrupted: the reference for every comparison."""
    path = tmp_path_factory.mktemp("ref") / "ref.db"
    summary = run_plan(small_plan(), path, workers=1, progress=False)
    assert summary.complete and summary.failed == 0
    return path


def wait_for_tasks(db: Path, proc: subprocess.Popen, at_least: int, timeout: float = 60) -> int:
    """Wait until a runner process has stored ``at_least`` tasks in ``db``; returns the count."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise AssertionError(f"runner exited early: {proc.communicate()}")
        if db.exists():
            try:
                conn = sqlite3.connect(f"{db.resolve().as_uri()}?mode=ro", uri=True, timeout=1)
                try:
                    n = conn.execute("SELECT COUNT(*) FROM tasks").fetchone()[0]
                finally:
                    conn.close()
                if n >= at_least:
                    return n
            except sqlite3.OperationalError:
                pass  # tables not created yet
        time.sleep(0.01)
    raise AssertionError("runner stored no task in time")


def gwo_fails_on_camel(monkeypatch):
    """Make the benchmark kind's ``minimize`` raise for gwo on six_hump_camel (an error row);
    returns the real ``minimize`` so a test can put it back."""
    from mawdo.experiments.kinds.benchmark import execute as bench_exec_mod

    real = bench_exec_mod.minimize

    def flaky(fun, **kw):
        if fun == "six_hump_camel" and kw["algorithm"] == "gwo":
            raise FloatingPointError("objective exploded")
        return real(fun, **kw)

    monkeypatch.setattr(bench_exec_mod, "minimize", flaky)
    return real
