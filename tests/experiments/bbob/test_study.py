"""The suite study through the shared runner and store: what is stored is what the suite
pipeline computes for each run alone; resuming, worker counts and batches change nothing."""

from __future__ import annotations

import dataclasses
import sqlite3
import zlib

import numpy as np

from mawdo.experiments import Store, run_plan
from mawdo.experiments import runner as runner_mod
from mawdo.experiments.kinds.suite.plan import parse_key
from mawdo.suites import evaluation_budget, get_problem, run_problem

from .conftest import stored_values, tiny_plan


def test_store_round_trip_equals_each_run_computed_alone(tiny_store):
    plan = tiny_plan()
    with Store.read(tiny_store) as store:
        rows = store.rows()
        assert store.plan == plan
    assert len(rows) == plan.total_runs
    seen = set()
    for algo, problem, row in rows:
        fid, iid, dim = parse_key(problem)
        assert (row.function_id, row.instance, row.dim) == (fid, iid, dim)
        f = get_problem("bbob", fid, iid, dim)
        # run k alone, seeded from the plan's derivation (not through the kind's code)
        res = run_problem(
            f, algo, runs=1, budget=plan.budget,
            seed=np.random.SeedSequence([7, zlib.crc32(b"bbob"), zlib.crc32(problem.encode())]),
            first_run=row.run,
        )  # fmt: skip
        (tr,) = res.evaluation_trace
        np.testing.assert_array_equal(row.evals, tr.evals)
        np.testing.assert_array_equal(row.best_so_far, tr.best_y)
        np.testing.assert_array_equal(row.best_x, res.x[0])
        assert row.nfev == res.nfev[0]
        assert row.fun == res.fun[0] == row.best_so_far[-1]
        assert row.precision == row.fun - f.f_star and row.f_star == f.f_star
        assert row.max_evals == evaluation_budget(plan.budget, dim)
        # a run spends its whole budget unless it reached the final target
        if row.precision > 1e-8:
            assert row.nfev == row.max_evals
        else:
            assert row.nfev <= row.max_evals
        seen.add((algo, problem, row.run))
    assert len(seen) == plan.total_runs
    # the early stop is exercised (CMA-ES on the sphere in D=2)
    assert any(r.nfev < r.max_evals for a, _, r in rows if a == "cmaes")


def test_seeds_depend_on_problem_and_run_not_algorithm(tiny_store):
    with Store.read(tiny_store) as store:
        rows = store.rows()
    by_key: dict = {}
    for _algo, problem, row in rows:
        by_key.setdefault(problem, set()).add(tuple(row.seed_entropy))
    assert all(len(v) == 1 for v in by_key.values())
    assert len({next(iter(v)) for v in by_key.values()}) == len(by_key)


def test_two_workers_and_other_batches_store_identical_values(tiny_store, tmp_path):
    path = tmp_path / "w2.db"
    summary = run_plan(tiny_plan(batch_size=3), path, workers=2, progress=False)
    assert summary.complete
    assert stored_values(path) == stored_values(tiny_store)


def test_interrupted_run_resumes_without_recomputing(tiny_store, tmp_path, monkeypatch):
    path = tmp_path / "cut.db"
    real = runner_mod.kind_of(tiny_plan())
    calls = {"n": 0}

    def interrupting(spec):
        calls["n"] += 1
        if calls["n"] > 5:
            raise KeyboardInterrupt  # what Ctrl-C does in the middle of task 6
        return real.execute(spec)

    monkeypatch.setattr(
        runner_mod, "kind_of", lambda plan: dataclasses.replace(real, execute=interrupting)
    )
    first = run_plan(tiny_plan(), path, workers=1, progress=False)
    monkeypatch.undo()
    assert first.interrupted and 0 < first.done < first.total
    second = run_plan(tiny_plan(), path, workers=1, progress=False)
    assert second.complete and second.skipped == first.done
    assert second.done == first.total - first.done
    conn = sqlite3.connect(path)
    try:
        tasks = conn.execute("SELECT algorithm, problem, first_run, n_runs FROM tasks").fetchall()
    finally:
        conn.close()
    computed = [(a, p, k) for a, p, f, n in tasks for k in range(f, f + n)]
    assert len(computed) == len(set(computed)) == first.total  # nothing computed twice
    assert stored_values(path) == stored_values(tiny_store)


def test_cec_opfunu_study_values_are_opfunus(tmp_path):
    plan = tiny_plan(suite="cec2022-opfunu", functions=[1, 6], instances=None, dims=[10], budget=20,
                     algorithms=["random"], runs=2)  # fmt: skip
    assert plan.instances == (1,)
    path = tmp_path / "cec.db"
    assert run_plan(plan, path, progress=False).complete
    from opfunu.cec_based import cec2022

    with Store.read(path) as store:
        for _, _, row in store.rows():
            f = getattr(cec2022, f"F{row.function_id}2022")(ndim=10)
            assert row.f_star == f.f_global
            assert row.fun == f.evaluate(row.best_x)  # the stored best is opfunu's value
            assert row.nfev == 200
