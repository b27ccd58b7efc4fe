"""Hostile inputs at the edges of the command line, plan files and stores: each ends in a
correct result or in plain ``error:`` lines with the documented exit code (2: bad input, 1: a
failure during the work, 130: Ctrl-C), never a traceback, a framed panel or a silent drop.
Every command runs the real CLI in a subprocess (:mod:`tests.cli_run`) on a tiny budget."""

from __future__ import annotations

import json
import os
import re
import signal
import sqlite3
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from tests.cli_run import interruptible, mawdo

FAST = 30  # seconds: every refusal here comes before any work


def refused(res, *words: str, code: int = 2) -> str:
    """``res`` ended with ``code`` and plain ``error:`` lines naming ``words``; their text."""
    assert res.returncode == code, (res.returncode, res.stderr)
    err = res.stderr
    assert "Traceback" not in err + res.stdout, err
    assert not any(c in err for c in "│╭╰"), err  # no rich panel, whatever the width
    assert "error: " in err, err
    text = " ".join(err.split())
    for w in words:
        assert w in text, err
    return text


def stored_plan(db: Path) -> dict:
    conn = sqlite3.connect(f"{db.resolve().as_uri()}?mode=ro", uri=True)
    try:
        return json.loads(conn.execute("SELECT plan_json FROM meta").fetchone()[0])
    finally:
        conn.close()


def edit_store(db: Path, sql: str) -> None:
    conn = sqlite3.connect(db)
    with conn:
        conn.execute(sql)
    conn.close()


# a suite study of one run of 10 evaluations (random search, BBOB f1, instance 1, D 2)
TINY_SUITE = ("--set", "runs=1", "--set", "functions=1", "--set", "instances=1",
              "--set", "dims=2", "--set", "algorithms=random", "--set", "budget=5")  # fmt: skip


@pytest.fixture(scope="module")
def smoke_store(tmp_path_factory) -> Path:
    """The smoke preset, one run per (algorithm, function): 12 benchmark runs."""
    db = tmp_path_factory.mktemp("smoke") / "smoke.db"
    res = mawdo("study", "run", "smoke", "--set", "runs=1", "--out", str(db), "--no-progress")
    assert res.returncode == 0, res.stderr
    return db


@pytest.fixture(scope="module")
def suite_store(tmp_path_factory) -> Path:
    db = tmp_path_factory.mktemp("suite") / "suite.db"
    res = mawdo("study", "run", "bbob-quick", *TINY_SUITE, "--out", str(db), "--no-progress")
    assert res.returncode == 0, res.stderr
    return db


# ---------------------------------------------------------------- 5: --set null, bools, options
def test_set_null_sets_none_and_replaces_an_earlier_set(tmp_path):
    db = tmp_path / "s.db"
    res = mawdo("study", "run", "bbob-quick", "--set", "final_target=1e-3",
                "--set", "final_target=null", *TINY_SUITE, "--out", str(db), "--no-progress",
                timeout=FAST * 2)  # fmt: skip
    assert res.returncode == 0, res.stderr
    # null is None (run the whole budget), and the later --set wins over the earlier one
    assert stored_plan(db)["final_target"] is None
    again = mawdo("study", "run", "bbob-quick", "--set", "final_target=1e-3", *TINY_SUITE,
                  "--out", str(tmp_path / "t.db"), "--no-progress", timeout=FAST * 2)  # fmt: skip
    assert again.returncode == 0 and stored_plan(tmp_path / "t.db")["final_target"] == 1e-3


@pytest.mark.parametrize(
    "setting, words",
    [
        ("runs=null", ["runs: must be an integer (got None)"]),
        ("name=null", ["name: must be a string (got None)"]),
        ("seed=true", ["seed: must be an integer, not true/false (got True)"]),
        ("runs=false", ["runs: must be an integer, not true/false"]),
        ("pop_size=true", ["pop_size: must be an integer, not true/false"]),
        ("functions=[true]", ["functions: must be a list of names, not true/false (got [True])"]),
    ],
)
def test_set_refuses_null_and_bools_where_the_field_does_not_take_them(tmp_path, setting, words):
    res = mawdo("study", "run", "smoke", "--set", setting, "--out", str(tmp_path / "x.db"),
                timeout=FAST)  # fmt: skip
    refused(res, *words)
    assert not (tmp_path / "x.db").exists()


@pytest.mark.parametrize(
    "setting, words",
    [
        ("n=true", ["n: must be an integer, not true/false (got True)"]),
        ("seed=true", ["seed: must be an integer, not true/false (got True)"]),
        ("ompl_time=true", ["ompl_time: must be a number, not true/false"]),
    ],
)
def test_arena_set_bools_are_no_numbers(tmp_path, setting, words):
    # n=true ran one scene per family before: a bool read as the integer 1
    res = mawdo("study", "run", "arena-quick", "--set", setting, "--out", str(tmp_path / "x.db"),
                timeout=FAST)  # fmt: skip
    refused(res, *words)


@pytest.mark.parametrize(
    "option, words",
    [
        ("plots=banana", ["--option plots='banana': must be true or false"]),
        ("plots=1", ["--option plots=1: must be true or false"]),
        ("svg=null", ["--option svg=None: this option cannot be null"]),
        ("reference=3", ["--option reference=3: must be a name or null"]),
        ("plots", ["--option 'plots' must look like key=value"]),
        ("nope=1", ["--option nope: the benchmark report has no such option"]),
    ],
)
def test_report_options_are_type_checked_and_exit_2(smoke_store, tmp_path, option, words):
    res = mawdo("study", "report", str(smoke_store), "--out", str(tmp_path / "r"),
                "--option", option, timeout=FAST)  # fmt: skip
    refused(res, *words)
    assert not (tmp_path / "r" / "report.md").exists()


# ---------------------------------------------------------------- 6: nesting
@pytest.mark.parametrize("depth", [2000, 100_000])
def test_deep_set_json_is_refused_with_its_depth(tmp_path, depth):
    t0 = time.monotonic()
    # one argument holds at most 128 KiB (Linux): the deepest one is left unclosed
    value = "[" * depth + "]" * depth if depth < 60_000 else "[" * depth
    res = mawdo("study", "run", "smoke", "--set", f"options={value}",
                "--out", str(tmp_path / "x.db"), timeout=FAST)  # fmt: skip
    refused(res, "--set options: arrays/tables are nested more than 32 deep")
    assert time.monotonic() - t0 < FAST


@pytest.mark.parametrize("depth", [2000, 100_000])
@pytest.mark.parametrize("suffix", [".toml", ".json"])
def test_deep_plan_files_are_refused_with_their_depth_and_line(tmp_path, depth, suffix):
    plan = tmp_path / f"deep{suffix}"
    deep = "[" * depth + "]" * depth
    if suffix == ".toml":
        plan.write_text(f'preset = "smoke"\n\nalgorithms = {deep}\n')
        line = 3
    else:
        plan.write_text(f'{{"preset": "smoke",\n "algorithms": {deep}}}\n')
        line = 2
    t0 = time.monotonic()
    res = mawdo("study", "run", str(plan), "--out", str(tmp_path / "x.db"), timeout=FAST)
    refused(res, f"{plan}: arrays/tables are nested more than 32 deep (line {line})",
            "a plan needs 3 levels at most")  # fmt: skip
    assert time.monotonic() - t0 < FAST  # the TOML parser took 65 s to fail before


def test_a_plan_nested_within_the_limit_is_read(tmp_path):
    plan = tmp_path / "ok.json"
    plan.write_text(json.dumps({"preset": "smoke", "runs": 1,
                                "options": {"mawdo": {"groups": 2}}}))  # fmt: skip
    res = mawdo("study", "run", str(plan), "--out", str(tmp_path / "x.db"), "--no-progress",
                timeout=FAST * 2)  # fmt: skip
    assert res.returncode == 0, res.stderr
    assert stored_plan(tmp_path / "x.db")["options"] == {"mawdo": {"groups": 2}}


# ---------------------------------------------------------------- 7: damaged rows
@pytest.mark.parametrize(
    "sql, words",
    [
        ("UPDATE runs SET fun = NULL WHERE algorithm = 'mawdo' AND problem = 'sphere'",
         ["mawdo on sphere run 0: fun is NULL"]),
        ("UPDATE runs SET fun = 'garbage' WHERE algorithm = 'mawdo' AND problem = 'rastrigin'",
         ["mawdo on rastrigin run 0: fun holds 'garbage' (str), not a value of a real column"]),
        ("UPDATE runs SET nfev = 2.5 WHERE algorithm = 'gwo' AND problem = 'sphere'",
         ["gwo on sphere run 0: nfev holds 2.5 (float)"]),
    ],
)  # fmt: skip
def test_study_report_names_damaged_rows_instead_of_dropping_them(
    smoke_store, tmp_path, sql, words
):
    db = tmp_path / "damaged.db"
    db.write_bytes(smoke_store.read_bytes())
    edit_store(db, sql)
    res = mawdo("study", "report", str(db), "--out", str(tmp_path / "r"),
                "--option", "plots=false", timeout=FAST)  # fmt: skip
    refused(res, f"results store {db} is damaged", *words, "changed outside mawdo")
    assert not (tmp_path / "r" / "report.md").exists()


def test_a_failed_run_without_values_is_no_damage(smoke_store, tmp_path):
    db = tmp_path / "failed.db"
    db.write_bytes(smoke_store.read_bytes())
    edit_store(db, "UPDATE runs SET fun = NULL, nfev = NULL, error_text = 'ValueError: x' "
                   "WHERE algorithm = 'mawdo' AND problem = 'sphere'")  # fmt: skip
    res = mawdo("study", "report", str(db), "--out", str(tmp_path / "r"),
                "--option", "plots=false", timeout=FAST)  # fmt: skip
    assert res.returncode == 0, res.stderr
    assert "1 failed" in (tmp_path / "r" / "report.md").read_text() or "failed" in res.stdout


def test_ioh_export_names_a_damaged_row(suite_store, tmp_path):
    db = tmp_path / "damaged.db"
    db.write_bytes(suite_store.read_bytes())
    edit_store(db, "UPDATE runs SET fun = NULL, best_so_far = 'x'")
    res = mawdo("bench", "export", "--format", "ioh", str(db), str(tmp_path / "logs"),
                timeout=FAST)  # fmt: skip
    refused(res, "random on f01_i01_d02 run 0: best_so_far holds 'x'", "fun is NULL")


# ---------------------------------------------------------------- 8: sizes
@pytest.mark.parametrize(
    "setting, total",
    [("n=1e10", "90,000,000,000 runs"), ("n=1e6", "9,000,000 runs"),
     ("n=10000000000", "90,000,000,000 runs")],
)  # fmt: skip
def test_huge_plans_are_refused_at_once_with_their_size(tmp_path, setting, total):
    t0 = time.monotonic()
    res = mawdo("study", "run", "arena-quick", "--set", setting, "--out", str(tmp_path / "x.db"),
                timeout=FAST)  # fmt: skip
    refused(res, f"the plan has {total}", "one plan holds at most 1,000,000")
    assert time.monotonic() - t0 < FAST
    assert not (tmp_path / "x.db").exists()


def test_huge_runs_of_a_benchmark_plan_are_refused(tmp_path):
    res = mawdo("study", "run", "smoke", "--set", "runs=100000000", "--out",
                str(tmp_path / "x.db"), timeout=FAST)  # fmt: skip
    refused(res, "the plan has 1,200,000,000 runs")


def test_more_threads_than_cpus_are_refused_before_any_work(tmp_path):
    from mawdo.cli.plan import usable_cpus  # (the same count the command uses)

    cpus = usable_cpus()
    for threads in sorted({64, cpus + 1} - set(range(cpus + 1))):
        res = mawdo("plan", "paper", "--threads", str(threads), "--out", str(tmp_path / "o"),
                    timeout=FAST)  # fmt: skip
        refused(res, f"--threads {threads}: this command may use {cpus} CPU(s)")
        assert not (tmp_path / "o").exists()


# ---------------------------------------------------------------- 9: width-free plain errors
@pytest.mark.parametrize("columns", ["40", "80", "200"])
def test_plan_file_errors_are_one_plain_line_at_any_width(tmp_path, columns):
    bad = tmp_path / "bad.toml"
    bad.write_text('algorithms = ["gwo"]\nfunctions = ["sphere"]\nruns = 0\n')
    out = str(tmp_path / "x.db")
    for args in (("study", "run", str(bad)), ("bench", "run", "--plan", str(bad))):
        res = mawdo(*args, "--out", out, env={"COLUMNS": columns}, timeout=FAST)
        text = refused(res, "runs: must be >= 1 (got 0)")
        assert "runs: must be >= 1 (got 0)" in res.stderr  # on one line, never wrapped
        assert text


def test_sub_apps_run_alone_print_plain_errors_at_80_columns(tmp_path):
    from typer.testing import CliRunner

    from mawdo.cli.bench import bench_app
    from mawdo.cli.study import study_app

    bad = tmp_path / "bad.toml"
    bad.write_text('algorithms = ["gwo"]\nfunctions = ["sphere"]\nruns = 0\n')
    runner = CliRunner(env={"COLUMNS": "80"})
    for app, args in ((bench_app, ["run", "--plan"]), (study_app, ["run"])):
        res = runner.invoke(app, [*args, str(bad), "--out", str(tmp_path / "x.db")])
        assert res.exit_code == 2 and "runs: must be >= 1" in res.output, res.output
        assert "╭" not in res.output


# ---------------------------------------------------------------- 10: exit codes, files, messages
def test_input_errors_exit_2_everywhere(smoke_store, tmp_path):
    refused(mawdo("study", "report", str(tmp_path / "nope.db"), timeout=FAST),
            "no such results store")  # fmt: skip
    corrupt = tmp_path / "c.db"
    corrupt.write_bytes(b"\x00not sqlite" * 100)
    refused(mawdo("study", "report", str(corrupt), "--out", str(tmp_path / "r"), timeout=FAST))
    other = mawdo("study", "run", "smoke", "--set", "runs=2", "--out", str(smoke_store),
                  timeout=FAST)  # fmt: skip
    refused(other, "another plan", "--force")
    afile = tmp_path / "afile"
    afile.write_text("x")
    refused(mawdo("study", "report", str(smoke_store), "--out", str(afile), timeout=FAST),
            "is a file; give a folder")  # fmt: skip


def test_a_plan_file_with_a_byte_order_mark_is_read(tmp_path):
    plan = tmp_path / "bom.toml"
    plan.write_bytes(b'\xef\xbb\xbfpreset = "smoke"\nruns = 1\n')
    res = mawdo("study", "run", str(plan), "--out", str(tmp_path / "x.db"), "--no-progress",
                timeout=FAST * 2)  # fmt: skip
    assert res.returncode == 0, res.stderr
    assert stored_plan(tmp_path / "x.db")["runs"] == 1
    assert "; 12 runs in all; plan " in res.stderr  # the size said before any work


@pytest.mark.parametrize(
    "spec, words",
    [
        ("plan.yaml", ["plan file plan.yaml does not exist"]),
        ("plans/mine", ["plan file plans/mine does not exist"]),
        ("smok", ["unknown preset 'smok'", "Did you mean 'smoke'"]),
    ],
)
def test_a_missing_plan_file_is_named_as_a_file(tmp_path, spec, words):
    refused(mawdo("study", "run", spec, "--out", "x.db", cwd=tmp_path, timeout=FAST), *words)


def test_an_existing_plan_of_another_format_is_named(tmp_path):
    (tmp_path / "plan.yaml").write_text("runs: 3\n")
    refused(mawdo("study", "run", "plan.yaml", "--out", "x.db", cwd=tmp_path, timeout=FAST),
            "plan files are TOML (.toml) or JSON (.json), not .yaml")  # fmt: skip


def test_ctrl_c_during_a_report_says_what_is_true_and_exits_130(smoke_store, tmp_path):
    out = tmp_path / "r"
    proc = interruptible(
        [*_cli(), "study", "report", str(smoke_store), "--out", str(out)],
    )
    lines: list[str] = []
    seen = threading.Event()

    def read() -> None:
        for line in proc.stderr:
            lines.append(line)
            if "writing the report" in line:
                seen.set()

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    assert seen.wait(FAST * 4), lines  # the state: the report is being written
    os.killpg(proc.pid, signal.SIGSTOP)  # held there while the interrupt is sent
    os.killpg(proc.pid, signal.SIGINT)
    os.killpg(proc.pid, signal.SIGCONT)
    proc.wait(timeout=FAST * 2)
    reader.join(5)
    err = "".join(lines)
    assert proc.returncode == 130, err
    assert "Traceback" not in err
    assert "interrupted: stopped by Ctrl-C; the report was not finished" in err
    assert "resume" not in err  # a report has nothing to resume


def _cli() -> list[str]:
    return [sys.executable, "-m", "mawdo.cli"]


def test_ctrl_c_messages_of_commands_that_save_nothing(monkeypatch, tmp_path):
    """optimize and demo: the message says nothing was saved (the real SIGINT path of plan and
    demo is tested in tests/planning/test_render_early.py)."""
    import importlib

    from typer.testing import CliRunner

    from mawdo.cli.main import app

    # the driver's module (``mawdo.minimize`` as an attribute is the function it holds)
    driver = importlib.import_module("mawdo.minimize")

    def stopped(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(driver, "minimize", stopped)
    res = CliRunner().invoke(app, ["optimize", "sphere", "--runs", "2", "--iters", "3"])
    assert res.exit_code == 130
    assert "stopped by Ctrl-C; no result was printed or saved" in res.output
    assert "resume" not in res.output

    import mawdo.planning.world.scenario as scenario

    monkeypatch.setattr(scenario, "get_scenario", stopped)  # demo's first step
    res = CliRunner().invoke(app, ["demo", "--out", str(tmp_path / "demo")])
    assert res.exit_code == 130
    assert "stopped by Ctrl-C; the run was not finished: no metrics or figures" in res.output
    assert "resume" not in res.output


def test_a_silent_step_still_says_something_every_2_s():
    """A report phase that says nothing gets a line from the step's heartbeat (in a log, where
    there is no spinner): waited for as a state, with no bound on the machine's speed."""
    from rich.console import Console

    from mawdo.cli import progress

    lines: list[str] = []

    class Capture(Console):
        def print(self, text, *a, **k):
            lines.append(str(text))

    old = progress.ERR
    progress.ERR = Capture(force_terminal=False)
    try:
        with progress.step("writing the report of a test"):
            end = time.monotonic() + FAST
            while not any(re.search(r": \d+ s$", ln) for ln in lines):
                assert time.monotonic() < end, lines
                time.sleep(0.05)
    finally:
        progress.ERR = old
    assert lines[0] == "writing the report of a test ..."
    assert any(ln.startswith("writing the report of a test: ") for ln in lines[1:])


def test_a_box_of_infinite_width_does_not_return_an_unevaluated_point_silently():
    from mawdo import minimize
    from mawdo.minimize import NoFiniteValueWarning

    with np.errstate(over="ignore"), pytest.warns(NoFiniteValueWarning, match="never evaluated"):
        res = minimize(lambda X: (X**2).sum(axis=1), bounds=[(-1e308, 1e308)] * 2, runs=2,
                       max_iter=5, pop_size=10, seed=0)  # fmt: skip
    assert np.all(np.isinf(res.fun))  # what it is: nothing finite was found
    # a box that fits the problem finds the optimum, and warns nothing
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", NoFiniteValueWarning)
        res = minimize(lambda X: (X**2).sum(axis=1), bounds=[(-1e3, 1e3)] * 2, runs=2,
                       max_iter=50, pop_size=10, seed=0)  # fmt: skip
    # x and fun agree: each run's x is a point it evaluated
    np.testing.assert_allclose((res.x**2).sum(axis=1), res.fun)
    assert np.all(np.isfinite(res.fun))
