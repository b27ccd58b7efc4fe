"""``mawdo bench`` commands, driven through the Typer app (as the main CLI mounts it)."""

from __future__ import annotations

import sqlite3

from typer.testing import CliRunner

from mawdo.cli.bench import bench_app
from mawdo.experiments import Store

runner = CliRunner()


def invoke(*args: str):
    return runner.invoke(bench_app, list(args))


def test_run_preset_with_overrides_then_report(tmp_path):
    db = tmp_path / "cli.db"
    res = invoke(
        "run",
        "--preset",
        "smoke",
        "--runs",
        "2",
        "--algorithms",
        "gwo,mewdo,mawdo",
        "--functions",
        "F1,six_hump_camel",
        "--iters",
        "12",
        "--out",
        str(db),
        "--workers",
        "1",
        "--no-progress",
    )
    assert res.exit_code == 0, res.output
    assert "complete: 12 runs computed" in res.stdout
    with Store.read(db) as store:
        assert store.count() == 3 * 2 * 2
        assert store.plan.max_iter == 12 and store.plan.functions == ("sphere", "six_hump_camel")

    again = invoke(
        "run",
        "--preset",
        "smoke",
        "--runs",
        "2",
        "--algorithms",
        "gwo,mewdo,mawdo",
        "--functions",
        "F1,six_hump_camel",
        "--iters",
        "12",
        "--out",
        str(db),
        "--no-progress",
    )
    assert again.exit_code == 0
    assert "0 runs computed" in again.stdout and "12 already" in again.stdout

    out = tmp_path / "rep"
    rep = invoke("report", str(db), "--out", str(out), "--no-plots")
    assert rep.exit_code == 0, rep.output
    header = (out / "results_raw.csv").read_text().splitlines()[0]
    assert header == "Function,Index,GWO,MEWDO (reconstructed),MAWDO"


def test_run_with_plan_file(tmp_path):
    plan = tmp_path / "p.toml"
    plan.write_text(
        'algorithms = ["wdo"]\nfunctions = ["F12"]\nruns = 2\npop_size = 8\nmax_iter = 10\n'
    )
    res = invoke("run", "--plan", str(plan), "--out", str(tmp_path / "p.db"), "--no-progress")
    assert res.exit_code == 0, res.output
    conn = sqlite3.connect(tmp_path / "p.db")
    assert conn.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 2
    conn.close()


def test_invalid_plan_names_the_field(tmp_path):
    res = invoke(
        "run", "--preset", "smoke", "--algorithms", "gwo,mawod", "--out", str(tmp_path / "x.db")
    )
    assert res.exit_code == 2
    assert "algorithms[1]: unknown algorithm 'mawod'" in res.output
    assert not (tmp_path / "x.db").exists()
    bad = tmp_path / "bad.toml"
    bad.write_text('algorithms = ["gwo"]\nfunctions = ["sphere"]\nruns = 0\n')
    res = invoke("run", "--plan", str(bad), "--out", str(tmp_path / "x.db"))
    assert res.exit_code == 2 and "runs: must be >= 1" in res.output


def test_plan_source_is_required_and_unique(tmp_path):
    res = invoke("run", "--out", str(tmp_path / "x.db"))
    assert res.exit_code == 2 and "give --preset NAME, --plan FILE.toml, or" in res.output
    res = invoke("run", "--preset", "smoke", "--plan", "p.toml", "--out", str(tmp_path / "x.db"))
    assert res.exit_code == 2 and "not both" in res.output


def test_plan_from_flags_alone(tmp_path):
    db = tmp_path / "flags.db"
    res = invoke(
        "run",
        "--algorithms",
        "wdo,awdo",
        "--functions",
        "F12",
        "--runs",
        "2",
        "--iters",
        "8",
        "--pop-size",
        "6",
        "--out",
        str(db),
        "--no-progress",
    )
    assert res.exit_code == 0, res.output
    with Store.read(db) as store:
        assert store.plan.algorithms == ("wdo", "awdo") and store.count() == 4
        assert store.plan.seed == 20251125  # the paper presets' master seed by default


def test_store_of_another_plan_is_refused_then_forced(tmp_path):
    db = tmp_path / "s.db"
    common = [
        "--preset",
        "smoke",
        "--algorithms",
        "gwo",
        "--functions",
        "F1",
        "--iters",
        "5",
        "--out",
        str(db),
        "--no-progress",
    ]
    assert invoke("run", *common, "--runs", "2").exit_code == 0
    res = invoke("run", *common, "--runs", "3")
    assert res.exit_code == 2 and "another plan" in res.output and "--force" in res.output
    res = invoke("run", *common, "--runs", "3", "--force")
    assert res.exit_code == 0 and "3 runs computed" in res.stdout


def test_report_of_a_corrupt_store_fails_clearly(tmp_path):
    db = tmp_path / "c.db"
    db.write_bytes(b"\x00not sqlite at all" * 100)
    res = invoke("report", str(db), "--out", str(tmp_path / "r"))
    assert res.exit_code == 2 and "corrupt" in res.output


def test_presets_lists_every_preset():
    res = invoke("presets")
    assert res.exit_code == 0
    for name in (
        "paper-table3",
        "paper-ablation",
        "paper-table3-shifted",
        "paper-table3-evals",
        "smoke",
    ):
        assert name in res.stdout
    assert "2880 runs" in res.stdout
