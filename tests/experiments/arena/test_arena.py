"""The planning arena: bad input, rejected scenes, stored scenes re-run alone, report numbers
against the store, resume after kill -9, and 1 vs 2 workers."""

from __future__ import annotations

import hashlib
import signal
import sqlite3
import statistics
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

from mawdo.experiments import PlanError, Store, run_plan
from mawdo.experiments.kinds.arena import ArenaPlan, arena_tables, write_arena_report
from mawdo.experiments.kinds.arena.report import COLUMNS

from ..conftest import wait_for_tasks

# forest (static), crossing (moving discs only: no static obstacle at all), a short planner
TINY = {
    "name": "tiny",
    "families": ["forest", "crossing"],
    "n": 3,
    "algorithms": ["mawdo"],
    "baselines": ["straight"],
    "planner": "quick",
    "overrides": {"max_steps": 40},
    "seed": 5,
    "batch_size": 1,
}
TINY_CLI = [
    "--suite", "forest,crossing", "--n", "3", "--algorithms", "mawdo", "--baselines",
    "straight", "--planner", "quick", "--option", "max_steps=40", "--seed", "5",
    "--batch-size", "1",
]  # fmt: skip
# Columns that do not depend on who computed a run or when.
VALUES = (
    "algorithm, problem, run, status, reason, scene_name, scene_toml, scene_hash, l_star, "
    "planner_seed, success, collision_free, length, gap, clearance, turning, waits, evasions, "
    "nfev, error_text"
)


def tiny(**changes) -> ArenaPlan:
    return ArenaPlan.from_dict({**TINY, **changes})


def values(db) -> list[tuple]:
    conn = sqlite3.connect(db)
    try:
        return conn.execute(
            f"SELECT {VALUES} FROM runs ORDER BY algorithm, problem, run"
        ).fetchall()
    finally:
        conn.close()


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> Path:
    db = tmp_path_factory.mktemp("arena") / "ref.db"
    summary = run_plan(tiny(), db, progress=False)
    assert summary.complete
    return db


# ------------------------------------------------------------------ bad input
@pytest.mark.parametrize(
    ("changes", "needle"),
    [
        ({"families": ["forrest"]}, "Did you mean 'forest'"),
        ({"n": 0}, "n: must be >= 1"),
        ({"n": -3}, "n: must be >= 1"),
        ({"params": {"forest": {"n": 10_000}}}, "'n' = 10000 is out of range [5, 200]"),
        ({"params": {"forest": {"trees": 3}}}, "unknown forest parameter 'trees'"),
        ({"params": {"maze": {"n": 3}}}, "'maze' is not one of the plan's families"),
        ({"baselines": ["oracel"]}, "Did you mean 'oracle'"),
        ({"algorithms": ["mawdoo"]}, "mawdo"),
        ({"algorithms": [], "baselines": []}, "give at least one planner"),
    ],
)
def test_bad_plans_are_refused_with_the_field_and_the_fix(changes, needle):
    with pytest.raises(PlanError) as exc:
        tiny(**changes)
    assert needle in str(exc.value)


def test_cli_bad_family_exits_2_and_suggests(tmp_path):
    from typer.testing import CliRunner

    from mawdo.cli.main import app

    args = ["plan", "bench", "--suite", "crosing,maze", "--out", str(tmp_path / "x.db")]
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 2
    assert "Did you mean 'crossing'" in res.output
    assert not (tmp_path / "x.db").exists()


def test_a_rejected_scene_is_stored_apart_never_as_a_planner_failure(monkeypatch, tmp_path):
    import mawdo.planning.scenes as scenes

    real = scenes.generate_scene

    def flaky(family, index=0, seed=0, params=None):
        if index == 1:
            raise scenes.SceneRejected(family, seed, index, ["no static route (test)"] * 20)
        return real(family, index, seed=seed, params=params)

    monkeypatch.setattr(scenes, "generate_scene", flaky)
    plan = tiny(families=["forest"], algorithms=[])
    run_plan(plan, tmp_path / "r.db", progress=False)
    with Store.read(tmp_path / "r.db") as store:
        rows = {r.run: r for _, _, r in store.rows()}
        (table,) = arena_tables(store)
    assert rows[1].status == "rejected" and "no static route (test)" in rows[1].reason
    assert rows[1].error_text is None and rows[1].success is None
    row = dict(zip(COLUMNS, table.rows[0], strict=True))
    assert (row["scenes"], row["rejected"], row["errors"]) == (2, 1, 0)
    ok = [rows[0], rows[2]]
    assert row["success"] == sum(r.success for r in ok) / 2


# ------------------------------------------------------------------ stored scenes and metrics
def test_each_row_stores_its_scene_which_reruns_alone_to_the_same_numbers(reference):
    from mawdo.planning.run.planner import plan
    from mawdo.planning.scenes import generate_scene
    from mawdo.planning.world.scenario import scenario_from_dict

    with Store.read(reference) as store:
        rows = [(a, f, r) for a, f, r in store.rows()]
    assert len(rows) == tiny().total_runs
    assert all(r.error_text is None and r.status == "ok" for _, _, r in rows)
    for _, fam, r in rows:
        assert r.scene_hash == hashlib.sha256(r.scene_toml.encode()).hexdigest()
        assert r.scene_toml == generate_scene(fam, r.run, seed=5).to_toml()
    # a MAWDO run re-planned from the stored TOML alone gives the stored route's numbers
    a, fam, r = next(x for x in rows if x[0] == "mawdo" and x[1] == "crossing")
    sc = scenario_from_dict(tomllib.loads(r.scene_toml), source=r.scene_name)
    res = plan(sc, algorithm="mawdo", seed=r.planner_seed, config="quick", max_steps=40)
    assert int(res.success) == r.success
    assert res.nfev == r.nfev
    assert (r.replans, r.gated) == (len(res.replans), res.gated)
    from mawdo.planning.world.path import polyline_length

    assert polyline_length(res.route) == pytest.approx(r.length, rel=1e-12)
    # the stored verdict and clearance are the independent checker's on the re-planned route
    from mawdo.planning.judge.check import check_trajectory

    check = check_trajectory(res.route, sc, times=res.route_times)
    assert r.collision_free == int(check.ok)
    assert r.clearance == check.min_clearance


def test_rows_count_the_plans_the_guide_gate_took_without_a_search(tmp_path):
    from mawdo.planning.run.config import PRESETS

    # on a static map with the gate on, the guides certify every plan: no search at all, and
    # the row says so; guide_only's plans are never counted as gated
    plan = tiny(families=["forest"], n=2, baselines=["guide_only"],
                overrides={"max_steps": 40, "guide_gate": True})  # fmt: skip
    run_plan(plan, tmp_path / "g.db", progress=False)
    with Store.read(tmp_path / "g.db") as store:
        rows = [(a, r) for a, _, r in store.rows()]
    for a, r in rows:
        assert r.replans >= 1
        assert r.gated == (r.replans if a == "mawdo" else 0)
        if a == "mawdo":
            assert r.nfev < PRESETS["quick"].pop_size  # the seeds' costs, not a population's


def test_straight_baseline_numbers_match_a_hand_computation(reference):
    with Store.read(reference) as store:
        rows = [r for _, _, r in store.rows("straight")]
    for r in rows:
        data = tomllib.loads(r.scene_toml)
        length = float(np.hypot(*np.subtract(data["goal"], data["start"])))
        assert r.length == pytest.approx(length, rel=1e-12)
        assert r.turning == 0.0
        if r.success:
            assert r.gap == pytest.approx(length / r.l_star, rel=1e-12)
            assert r.gap >= 1.0 - 1e-9  # L* is a lower bound of every route


def test_report_numbers_equal_the_store(reference, tmp_path):
    path = write_arena_report(reference, tmp_path / "rep", figures=False)
    csv = (path.parent / "arena.csv").read_text().splitlines()
    assert len(csv) == 1 + 4
    with Store.read(reference) as store:
        (table,) = arena_tables(store)
    conn = sqlite3.connect(reference)
    try:
        for row in table.rows:
            got = dict(zip(COLUMNS, row, strict=True))
            fam = got["family"]
            alg = "straight" if got["planner"] == "straight" else "mawdo"
            q = conn.execute(
                "SELECT success, collision_free, gap, latency_p95_ms, latency_p99_ms FROM runs "
                "WHERE algorithm = ? AND problem = ? AND status = 'ok'",
                (alg, fam),
            ).fetchall()
            assert got["scenes"] == len(q)
            assert got["success"] == sum(s for s, *_ in q) / len(q)
            assert got["collisions"] == sum(c == 0 for _, c, *_ in q) / len(q)
            gaps = sorted(g for s, _, g, *_ in q if s)
            if gaps:
                assert got["gap median"] == pytest.approx(statistics.median(gaps), rel=1e-12)
                p90 = (
                    statistics.quantiles(gaps, n=10, method="inclusive")[8]
                    if len(gaps) > 1
                    else gaps[0]
                )
                assert got["gap p90"] == pytest.approx(p90, rel=1e-12)
                assert got["gap max"] == max(gaps)
            else:
                assert np.isnan(got["gap median"])
            p95 = [x for *_, x, _ in q if x is not None]
            if p95:
                assert got["latency p95 (ms)"] == pytest.approx(statistics.median(p95))
    finally:
        conn.close()


# ------------------------------------------------------------------ reproducibility
@pytest.mark.slow
def test_two_workers_store_the_same_values_as_one(reference, tmp_path):
    db = tmp_path / "w2.db"
    run_plan(tiny(), db, workers=2, progress=False)
    assert values(db) == values(reference)
    # and the batch size never changes a number
    db3 = tmp_path / "b3.db"
    run_plan(tiny(batch_size=3, name="other"), db3, progress=False)
    assert values(db3) == values(reference)


@pytest.mark.slow
def test_kill_9_then_resume_computes_nothing_twice(reference, tmp_path):
    db = tmp_path / "killed.db"
    cmd = [sys.executable, "-m", "mawdo.cli", "plan", "bench", *TINY_CLI, "--out", str(db),
           "--no-progress"]  # fmt: skip
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        wait_for_tasks(db, proc, at_least=1, timeout=120)
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.communicate(timeout=30)
    assert proc.returncode == -signal.SIGKILL
    plan = tiny(name="arena")
    with Store.read(db) as store:
        before = store.done_keys()
        first = len(store.task_log())
    assert 0 < len(before) < plan.total_runs

    summary = run_plan(plan, db, progress=False)
    assert summary.complete and summary.skipped == len(before)
    with Store.read(db) as store:
        log = store.task_log()
    resumed = [
        (t["algorithm"], t["problem"], k)
        for t in log[first:]
        for k in range(t["first_run"], t["first_run"] + t["n_runs"])
    ]
    assert len(resumed) == len(set(resumed)) == plan.total_runs - len(before)
    assert not set(resumed) & before
    assert values(db) == values(reference)


@pytest.mark.slow  # renders a snapshot per failed run
def test_gallery_has_one_image_and_scene_file_per_failed_or_colliding_run(reference, tmp_path):
    out = tmp_path / "rep"
    path = write_arena_report(reference, out)
    conn = sqlite3.connect(reference)
    try:
        bad = conn.execute(
            "SELECT algorithm, scene_name, scene_toml FROM runs WHERE status = 'ok' "
            "AND (success = 0 OR collision_free = 0)"
        ).fetchall()
    finally:
        conn.close()
    assert bad  # the straight line hits trees: the gallery is not empty
    images = sorted(p.name for p in (out / "gallery").glob("*.png"))
    assert images == sorted(f"{name}__{alg}.png" for alg, name, _ in bad)
    for _, name, toml in bad:
        assert (out / "scenes" / f"{name}.toml").read_text() == toml
        assert f"scenes/{name}.toml" in path.read_text()
    assert (out / "ecdf_runtime.png").stat().st_size > 10_000
