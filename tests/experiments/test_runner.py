"""The runner: identical stored values for every backend, resume after kill -9 and Ctrl-C,
failures as rows, budgets."""

from __future__ import annotations

import os
import platform
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from threadpoolctl import threadpool_info

from mawdo import minimize
from mawdo.experiments import ExperimentPlan, Store, Task, execute_task, run_plan
from mawdo.experiments import runner as runner_mod
from mawdo.experiments.kinds.benchmark import execute as bench_exec_mod

from .conftest import gwo_fails_on_camel, small_plan, stored_values, wait_for_tasks

# A plan whose tasks are slow enough (~0.1 s each, batch of one run) to kill the runner
# between tasks, and numerous enough that a kill after the first task leaves most undone.
SLOW_TOML = """
name = "slow"
algorithms = ["wdo", "mawdo"]
functions = ["sphere", "rastrigin"]
runs = 6
pop_size = 20
max_iter = 300
seed = 7
batch_size = 1
"""


def test_execute_task_matches_a_direct_minimize_call():
    plan = small_plan()
    out = execute_task(plan.task_spec(Task("mawdo", "quartic", 2, 2)))
    res = minimize(
        "quartic",
        algorithm="mawdo",
        runs=1,
        first_run=3,
        seed=np.random.SeedSequence(plan.function_seed("quartic")),
        max_iter=plan.max_iter,
        pop_size=plan.pop_size,
    )
    row = out["rows"][1]
    assert row.run == 3 and row.error_text is None
    assert row.fun == res.fun[0] and row.nfev == res.nfev[0]
    np.testing.assert_array_equal(row.curve, res.history[0])


def _blas_threads() -> list[int]:
    from threadpoolctl import threadpool_info

    return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]


def test_a_task_runs_its_blas_on_one_thread_and_gives_the_threads_back():
    from threadpoolctl import threadpool_limits

    seen = []

    def execute(spec):
        seen.append(_blas_threads())
        return []

    plan = small_plan()
    with threadpool_limits(limits=2, user_api="blas"):  # as on any machine of 2 cores or more
        before = _blas_threads()
        assert before and max(before) == 2  # numpy's BLAS is loaded and would use two
        execute_task(plan.task_spec(Task("mawdo", "quartic", 0, 1)), execute)
        assert _blas_threads() == before
    assert seen == [[1] * len(before)]


def test_workers_do_not_change_stored_values(reference_store, tmp_path):
    ref = stored_values(reference_store)
    assert len(ref) == small_plan().total_runs
    summary = run_plan(small_plan(), tmp_path / "w2.db", workers=2, progress=False)
    assert summary.complete and summary.tasks == len(small_plan().tasks())
    with Store.read(tmp_path / "w2.db") as store:
        workers = {t["worker"] for t in store.task_log()}
        platforms = {t["platform"] for t in store.task_log()}
    # computed in pool processes, not here (how many of the two got work depends on timing)
    assert 1 <= len(workers) <= 2 and not any(w.endswith(f":{os.getpid()}") for w in workers)
    assert stored_values(tmp_path / "w2.db") == ref
    # each task names what computed it: this machine's NumPy, SIMD features and BLAS kernels
    (line,) = platforms
    assert line.startswith(platform.machine()) and f"numpy {np.__version__} (" in line
    from numpy._core._multiarray_umath import __cpu_features__

    assert ("AVX2" in line) == bool(__cpu_features__.get("AVX2"))
    for lib in threadpool_info():
        if lib["user_api"] == "blas":
            assert f"{lib['internal_api']} {lib['version']} ({lib['architecture']})" in line


def test_dask_local_cluster_gives_identical_values(reference_store, tmp_path):
    from distributed import Client, LocalCluster

    with (
        LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
        ) as cluster,
        Client(cluster) as client,
    ):
        summary = run_plan(small_plan(), tmp_path / "dask.db", dask=client, progress=False)
        # the runner leaves a client it was given open
        assert client.status == "running"
        # and connects (then disconnects) by itself given the scheduler's address
        by_address = run_plan(
            small_plan(), tmp_path / "addr.db", dask=cluster.scheduler_address, progress=False
        )
    assert summary.complete and by_address.complete
    assert stored_values(tmp_path / "addr.db") == stored_values(reference_store)
    with Store.read(tmp_path / "dask.db") as store:
        assert all(
            not w.endswith(f":{os.getpid()}") for w in (t["worker"] for t in store.task_log())
        )
    assert stored_values(tmp_path / "dask.db") == stored_values(reference_store)


def test_a_finished_store_is_skipped(reference_store, tmp_path):
    copy = tmp_path / "copy.db"
    copy.write_bytes(Path(reference_store).read_bytes())
    summary = run_plan(small_plan(), copy, progress=False)
    assert (summary.done, summary.skipped, summary.tasks) == (0, small_plan().total_runs, 0)


def _sigint_default() -> None:
    """Python's Ctrl-C in the child, whatever this process inherited: a suite started in the
    background of a non-interactive shell ignores SIGINT, and its children with it."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _start(plan_file: Path, db: Path, *extra: str) -> subprocess.Popen:
    return subprocess.Popen(
        [
            sys.executable,
            "-m",
            "mawdo.cli",
            "bench",
            "run",
            "--plan",
            str(plan_file),
            "--out",
            str(db),
            "--no-progress",
            *extra,
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=_sigint_default,
    )


@pytest.fixture(scope="module")
def slow_plan_file(tmp_path_factory) -> Path:
    f = tmp_path_factory.mktemp("plans") / "slow.toml"
    f.write_text(SLOW_TOML)
    return f


def test_kill_9_then_resume_equals_an_uninterrupted_run(slow_plan_file, tmp_path):
    plan = ExperimentPlan.from_toml(slow_plan_file)
    db = tmp_path / "killed.db"
    proc = _start(slow_plan_file, db)
    try:
        wait_for_tasks(db, proc, at_least=1)
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.communicate(timeout=30)
    assert proc.returncode == -signal.SIGKILL

    with Store.read(db) as store:
        before = store.done_keys()
        first_session = store.task_log()
    assert 0 < len(before) < plan.total_runs  # really interrupted in the middle

    summary = run_plan(plan, db, progress=False)
    assert summary.complete and summary.skipped == len(before)
    with Store.read(db) as store:
        log = store.task_log()
    resumed = [
        (t["algorithm"], t["problem"], k)
        for t in log[len(first_session) :]
        for k in range(t["first_run"], t["first_run"] + t["n_runs"])
    ]
    # no stored run computed twice, every missing run computed once
    assert len(resumed) == len(set(resumed)) == plan.total_runs - len(before)
    assert not set(resumed) & before

    clean = tmp_path / "clean.db"
    run_plan(plan, clean, progress=False)
    assert stored_values(db) == stored_values(clean)

    from mawdo.experiments import write_report

    a = write_report(db, tmp_path / "rep_killed", plots=False)
    b = write_report(clean, tmp_path / "rep_clean", plots=False)
    deterministic = [p.name for p in a if p.name != "timing.csv"]
    assert "results_raw.tex" in deterministic and "report.md" in deterministic
    for name in deterministic:
        assert (tmp_path / "rep_killed" / name).read_text() == (
            tmp_path / "rep_clean" / name
        ).read_text(), name
    assert len(a) == len(b)


def test_ctrl_c_stops_the_pool_keeps_finished_tasks_and_says_how_to_resume(
    slow_plan_file, tmp_path
):
    plan = ExperimentPlan.from_toml(slow_plan_file)
    db = tmp_path / "sigint.db"
    proc = _start(slow_plan_file, db, "--workers", "2")
    try:
        wait_for_tasks(db, proc, at_least=1)
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 130, err
    assert "Interrupted" in err and "run the same command again to resume" in err
    with Store.read(db) as store:
        stored = store.count()
        log = store.task_log()
    # only whole tasks are stored, and the run stopped before the end
    assert stored == sum(t["n_runs"] for t in log) and 0 < stored < plan.total_runs
    summary = run_plan(plan, db, progress=False)
    assert summary.complete and summary.skipped == stored


def test_a_failing_task_becomes_error_rows(monkeypatch, tmp_path):
    real = gwo_fails_on_camel(monkeypatch)
    plan = small_plan()
    db = tmp_path / "fail.db"
    summary = run_plan(plan, db, progress=False)
    assert summary.complete and summary.failed == plan.runs
    with Store.read(db) as store:
        failed = [(a, f, r) for a, f, r in store.rows() if r.failed]
        assert {(a, f) for a, f, _ in failed} == {("gwo", "six_hump_camel")}
        assert all(
            r.fun is None and "FloatingPointError: objective exploded" in r.error_text
            for _, _, r in failed
        )
        assert store.count(failed=False) == plan.total_runs - plan.runs

    # failed runs are stored (a re-run skips them) until asked to retry
    assert run_plan(plan, db, progress=False).done == 0
    monkeypatch.setattr(bench_exec_mod, "minimize", real)
    again = run_plan(plan, db, progress=False, retry_failed=True)
    assert (again.done, again.failed) == (plan.runs, 0)


def test_results_from_another_library_version_are_not_stored(monkeypatch, tmp_path):
    real = runner_mod.execute_task
    monkeypatch.setattr(
        runner_mod,
        "execute_task",
        lambda spec, execute=None: {**real(spec, execute), "library_version": "9.9.9"},
    )
    plan = small_plan(functions=["rastrigin"], runs=2)
    summary = run_plan(plan, tmp_path / "v.db", progress=False)
    assert (summary.lost, summary.done, summary.complete) == (plan.total_runs, 0, False)
    with Store.read(tmp_path / "v.db") as store:
        assert store.count() == 0
    monkeypatch.setattr(runner_mod, "execute_task", real)
    assert run_plan(plan, tmp_path / "v.db", progress=False).complete


def test_equal_evaluation_budget_is_exact_for_every_algorithm(tmp_path):
    # max_iter 60 > restart period 50: MAWDO's OBL spends extra evaluations in iteration mode
    plan = small_plan(budget="evals", functions=["rastrigin"], runs=2)
    run_plan(plan, tmp_path / "evals.db", progress=False)
    run_plan(plan.with_overrides(budget="iterations"), tmp_path / "iters.db", progress=False)
    with Store.read(tmp_path / "evals.db") as store:
        evals = store.rows()
    with Store.read(tmp_path / "iters.db") as store:
        iters = store.rows()
    budget = plan.pop_size * plan.max_iter
    assert all(r.nfev == budget for _, _, r in evals)
    assert all(r.nit == plan.max_iter for _, _, r in iters)
    assert any(r.nfev > budget for a, _, r in iters if a == "mawdo")
    assert all(r.curve_nfev[-1] == r.nfev for _, _, r in evals + iters)


def test_shifted_plan_stores_the_shift_seed(tmp_path):
    plan = small_plan(shifted=True, functions=["rastrigin"], runs=2, algorithms=["gwo", "mawdo"])
    run_plan(plan, tmp_path / "sh.db", progress=False)
    with Store.read(tmp_path / "sh.db") as store:
        recs = [r for _, _, r in store.rows()]
        assert store.plan.shifted
    assert {r.shift_seed for r in recs} == {plan.shift_seed("rastrigin")}
    unshifted = execute_task(
        small_plan(functions=["rastrigin"]).task_spec(Task("gwo", "rastrigin", 0, 1))
    )["rows"][0].fun
    assert recs[0].fun != unshifted


def test_bad_runner_arguments(tmp_path):
    with pytest.raises(ValueError, match="workers=0"):
        run_plan(small_plan(), tmp_path / "x.db", workers=0)
    with pytest.raises(ValueError, match="not both"):
        run_plan(small_plan(), tmp_path / "x.db", workers=2, dask="tcp://127.0.0.1:1")
