"""Runs of other stores taken into a plan's store (``run_plan(..., reuse=...)``, ``mawdo study
run --reuse``): a copied run equals the run the plan computes itself, only runs that are the
same computation are taken, and a source that cannot serve is refused with what to do."""

from __future__ import annotations

import json
import shutil
import sqlite3

import pytest
from typer.testing import CliRunner

from mawdo.cli.main import app
from mawdo.experiments import run_plan
from mawdo.experiments.kinds.crowd.plan import CrowdPlan
from mawdo.experiments.protocol import plan_from_json
from mawdo.experiments.reuse import ReuseError

from .conftest import small_plan

CROWD = {"kind": "crowd", "name": "part", "settings": ["circle-5-invisible"], "n": 4,
         "policies": ["straight", "orca_robot"], "batch_size": 3}  # fmt: skip


# columns that name the plan or measure the machine, not the run
NOT_RESULTS = ("plan_hash", "wall_time", "task_id", "latency_p50_ms", "latency_p95_ms")


def values(path, skip=NOT_RESULTS) -> list[tuple]:
    """Every stored run's result columns, in key order."""
    con = sqlite3.connect(path)
    try:
        cols = [r[1] for r in con.execute("PRAGMA table_info(runs)") if r[1] not in skip]
        q = f"SELECT {', '.join(cols)} FROM runs ORDER BY algorithm, problem, run"
        return con.execute(q).fetchall()
    finally:
        con.close()


def test_a_bigger_crowd_study_grows_from_a_smaller_one(tmp_path):
    part = CrowdPlan.from_dict(CROWD)
    settings = ["circle-5-invisible", "square-5-visible"]
    whole = CrowdPlan.from_dict({**CROWD, "name": "whole", "n": 6, "batch_size": 4,
                                 "settings": settings})  # fmt: skip
    run_plan(part, tmp_path / "part.db", progress=False)
    grown = run_plan(whole, tmp_path / "grown.db", progress=False, reuse=[tmp_path / "part.db"])
    assert grown.reused == 8 and grown.done == 16 and grown.complete
    fresh = run_plan(whole, tmp_path / "fresh.db", progress=False)
    assert fresh.done == 24
    assert values(tmp_path / "grown.db") == values(tmp_path / "fresh.db")
    con = sqlite3.connect(tmp_path / "grown.db")
    log = con.execute("SELECT algorithm, first_run, n_runs FROM tasks WHERE worker = ?",
                      ("reused from part.db",)).fetchall()  # fmt: skip
    assert sorted(log) == [("orca_robot", 0, 4), ("straight", 0, 4)]
    # resuming the grown store computes and copies nothing more
    again = run_plan(whole, tmp_path / "grown.db", progress=False, reuse=[tmp_path / "part.db"])
    assert again.reused == 0 and again.done == 0 and again.skipped == 24


def test_runs_computed_another_way_are_not_taken(tmp_path):
    run_plan(CrowdPlan.from_dict(CROWD), tmp_path / "part.db", progress=False)
    other = CrowdPlan.from_dict({**CROWD, "name": "noisy", "sensor_noise": 0.05})
    got = run_plan(other, tmp_path / "noisy.db", progress=False, reuse=[tmp_path / "part.db"])
    assert got.reused == 0 and got.done == 8
    reseeded = CrowdPlan.from_dict({**CROWD, "name": "reseeded", "seed": 1})
    got = run_plan(reseeded, tmp_path / "re.db", progress=False, reuse=[tmp_path / "part.db"])
    assert got.reused == 0


def test_benchmark_runs_copied_from_other_batches_equal_the_plans_own(tmp_path):
    # 2 runs in batches of 2, copied into a 4-run plan cut into batches of 3: runs do not
    # depend on which runs share their task
    run_plan(small_plan(runs=2, batch_size=2, name="two"), tmp_path / "two.db", progress=False)
    four = small_plan(runs=4, batch_size=3, name="four")
    grown = run_plan(four, tmp_path / "grown.db", progress=False, reuse=[tmp_path / "two.db"])
    assert grown.reused == 2 * 9 and grown.done == 2 * 9
    run_plan(four, tmp_path / "fresh.db", progress=False)
    assert values(tmp_path / "grown.db") == values(tmp_path / "fresh.db")


def test_suite_runs_copied_from_a_smaller_study_equal_the_plans_own(tmp_path):
    spec = {"kind": "suite", "name": "one", "suite": "cec2017", "algorithms": ["gwo", "random"],
            "functions": [1, 5], "instances": [1], "dims": [10], "budget": 30.0, "runs": 2,
            "seed": 11, "batch_size": 2}  # fmt: skip
    run_plan(plan_from_json(json.dumps(spec)), tmp_path / "two.db", progress=False)
    three = plan_from_json(json.dumps({**spec, "name": "three", "runs": 3, "batch_size": 3}))
    grown = run_plan(three, tmp_path / "grown.db", progress=False, reuse=[tmp_path / "two.db"])
    assert grown.reused == 8 and grown.done == 4
    run_plan(three, tmp_path / "fresh.db", progress=False)
    assert values(tmp_path / "grown.db") == values(tmp_path / "fresh.db")


def test_a_store_of_another_kind_or_version_is_refused(tmp_path):
    run_plan(small_plan(name="bench"), tmp_path / "bench.db", progress=False)
    crowd = CrowdPlan.from_dict(CROWD)
    with pytest.raises(ReuseError, match=r"bench\.db: it holds a 'benchmark' study.*'crowd'"):
        run_plan(crowd, tmp_path / "c.db", progress=False, reuse=[tmp_path / "bench.db"])
    run_plan(crowd, tmp_path / "part.db", progress=False)
    shutil.copy(tmp_path / "part.db", tmp_path / "old.db")
    con = sqlite3.connect(tmp_path / "old.db")
    with con:
        con.execute("UPDATE meta SET library_version = '0.0.1'")
    con.close()
    with pytest.raises(ReuseError, match=r"old\.db: written by mawdo 0\.0\.1.*compute them"):
        run_plan(crowd, tmp_path / "d.db", progress=False, reuse=[tmp_path / "old.db"])


def test_the_cli_copies_runs_and_refuses_what_is_not_a_store(tmp_path):
    (tmp_path / "part.json").write_text(json.dumps(CROWD))
    whole = {**CROWD, "name": "whole", "n": 5}
    (tmp_path / "whole.json").write_text(json.dumps(whole))
    cli = CliRunner()
    first = cli.invoke(app, ["study", "run", str(tmp_path / "part.json"), "--out",
                             str(tmp_path / "part.db"), "--no-progress"])  # fmt: skip
    assert first.exit_code == 0, first.output
    grown = cli.invoke(app, ["study", "run", str(tmp_path / "whole.json"), "--out",
                             str(tmp_path / "whole.db"), "--reuse", str(tmp_path / "part.db"),
                             "--no-progress"])  # fmt: skip
    assert grown.exit_code == 0, grown.output
    assert "8 reused from other stores" in grown.output and "10/10 runs" in grown.output
    with_progress = cli.invoke(app, ["study", "run", str(tmp_path / "whole.json"), "--out",
                                     str(tmp_path / "again.db"), "--reuse",
                                     str(tmp_path / "part.db")])  # fmt: skip
    assert with_progress.exit_code == 0, with_progress.output
    assert "8 runs copied from" in with_progress.output  # a word before the bar, not silence
    (tmp_path / "junk.db").write_text("not a database")
    plan = str(tmp_path / "whole.json")
    bad = cli.invoke(app, ["study", "run", plan, "--out", str(tmp_path / "w2.db"),
                           "--reuse", str(tmp_path / "junk.db")])  # fmt: skip
    assert bad.exit_code == 2
    assert "junk.db" in bad.output
    missing = cli.invoke(app, ["study", "run", plan, "--out", str(tmp_path / "w3.db"),
                               "--reuse", str(tmp_path / "no.db")])  # fmt: skip
    assert missing.exit_code == 2 and "no results store at" in missing.output
