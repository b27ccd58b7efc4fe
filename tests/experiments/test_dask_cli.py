"""Dask from the study commands (issue 28, item 9): ``--scheduler-file`` beside ``--dask``, and
``mawdo reproduce --dask`` no longer refused by its default of two local workers."""

from __future__ import annotations

import json
import os
import sqlite3
import subprocess
import sys
from pathlib import Path

import pytest

from mawdo.reproduce import reproduce

from .conftest import SMALL, stored_values

SRC = str(Path(__file__).resolve().parents[2] / "src")
ENV = {**os.environ, "PYTHONPATH": SRC}


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "mawdo.cli", *args], capture_output=True, text=True, env=ENV
    )


@pytest.fixture(scope="module")
def cluster_file(tmp_path_factory):
    """A real scheduler with one worker (threads of this process, so that the task log shows
    who computed), and the scheduler file it wrote."""
    from distributed import Client, LocalCluster

    path = tmp_path_factory.mktemp("dask") / "scheduler.json"
    with (
        LocalCluster(
            n_workers=1,
            threads_per_worker=1,
            processes=False,
            protocol="tcp",  # not in-process: the commands connect from their own process
            host="127.0.0.1",
            dashboard_address=None,
        ) as cluster,
        Client(cluster) as client,
    ):
        client.write_scheduler_file(str(path))
        yield path, cluster.scheduler_address


def _workers(db: Path) -> set[str]:
    conn = sqlite3.connect(db)
    try:
        return {w for (w,) in conn.execute("SELECT worker FROM tasks")}
    finally:
        conn.close()


def test_bench_run_on_a_scheduler_file(cluster_file, tmp_path, reference_store):
    path, _ = cluster_file
    plan = tmp_path / "small.toml"
    plan.write_text("\n".join(f"{k} = {json.dumps(v)}" for k, v in SMALL.items()))
    db = tmp_path / "sf.db"
    r = _cli("bench", "run", "--plan", str(plan), "--out", str(db), "--scheduler-file", str(path),
             "--no-progress")  # fmt: skip
    assert r.returncode == 0, r.stderr
    # computed by the cluster's worker (in this process), not by the command's own process
    workers = _workers(db)
    assert workers and all(w.endswith(f":{os.getpid()}") for w in workers)
    assert stored_values(db) == stored_values(reference_store)


@pytest.mark.slow
def test_plan_bench_on_a_scheduler_file_matches_in_process(cluster_file, tmp_path):
    path, _ = cluster_file
    args = ["plan", "bench", "--suite", "forest", "--n", "2", "--algorithms", "",
            "--baselines", "straight", "--seed", "3", "--no-progress"]  # fmt: skip
    local, remote = tmp_path / "local.db", tmp_path / "remote.db"
    assert _cli(*args, "--out", str(local)).returncode == 0
    r = _cli(*args, "--out", str(remote), "--scheduler-file", str(path))
    assert r.returncode == 0, r.stderr
    assert all(w.endswith(f":{os.getpid()}") for w in _workers(remote))
    cols = "algorithm, problem, run, status, scene_hash, success, length, error_text"
    assert stored_values(remote, cols) == stored_values(local, cols) != []


def test_scheduler_file_errors_name_the_fix(tmp_path):
    missing = str(tmp_path / "no.json")
    r = _cli(
        "reproduce", "--out", str(tmp_path / "r"), "--scheduler-file", missing, "--retry-failed"
    )
    # the default of two local workers gives way to the cluster: the missing file is the error
    assert r.returncode == 2 and "no Dask scheduler file at" in r.stderr, r.stderr
    assert "dask scheduler --scheduler-file" in r.stderr and "Traceback" not in r.stderr
    r = _cli("reproduce", "--out", str(tmp_path / "r"), "--dask", "tcp://127.0.0.1:1",
             "--workers", "3")  # fmt: skip
    assert r.returncode == 2 and "not both" in r.stderr, r.stderr
    r = _cli("plan", "study", "--out", str(tmp_path / "s.db"), "--dask", "tcp://127.0.0.1:1",
             "--scheduler-file", str(tmp_path / "no.json"), "--retry-failed")  # fmt: skip
    assert r.returncode == 2 and "address or its scheduler file, not both" in r.stderr, r.stderr


@pytest.mark.slow
def test_reproduce_on_dask_with_its_default_workers(cluster_file, tmp_path):
    _, address = cluster_file
    tiny = {"runs": 2, "max_iter": 8, "pop_size": 8, "functions": ["sphere"], "name": "tiny"}
    said: list[str] = []
    path = reproduce(
        tmp_path, dask=address, progress=False, say=said.append, bench_overrides=tiny,
        study="study-smoke",
    )  # fmt: skip
    assert path.is_file()
    done = [s for s in said if s.strip().startswith("complete")]
    assert len(done) == 4
    for db in (tmp_path / "results").glob("*.db"):
        assert all(w.endswith(f":{os.getpid()}") for w in _workers(db))
