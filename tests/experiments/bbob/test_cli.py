"""``mawdo bench run --suite`` / ``export`` / ``report`` through the real command in a
subprocess: bad input ends in a message naming the problem and the fix, never a traceback, and
before any computing (the budgets below would run for hours)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

from mawdo.experiments import Store
from mawdo.experiments.kinds.suite.ioh_logs import read_analyzer_logs

HOURS = ("--runs", "1000", "--budget", "1e7", "--algorithms", "mawdo", "--no-progress")


def mawdo(*args: str, cwd, env_extra=None) -> subprocess.CompletedProcess:
    env = {**os.environ, "MPLBACKEND": "Agg", **(env_extra or {})}
    return subprocess.run(
        [sys.executable, "-m", "mawdo.cli", *args],
        capture_output=True, text=True, timeout=120, env=env, cwd=cwd,
    )  # fmt: skip


@pytest.mark.parametrize(
    "args, words",
    [
        (("--suite", "bbbo", "--functions", "1"), ["unknown suite 'bbbo'", "Did you mean 'bbob'"]),
        (("--suite", "bbob", "--functions", "1-25"), ["functions[24]", "defines functions 1-24"]),
        (("--suite", "bbob", "--functions", "rastrgin"), ["Did you mean 'rastrigin'"]),
        (
            ("--suite", "cec2017", "--functions", "12", "--dims", "2"),
            ["f12 is not defined in dimension 2", "10, 30, 50, 100"],
        ),
        (("--suite", "cec2022", "--functions", "1", "--dims", "5"), ["2, 10, 20"]),
        (("--suite", "bbob", "--functions", "1", "--budget", "0"), ["budget", "> 0"]),
        (("--suite", "bbob", "--functions", "1", "--budget", "-5"), ["budget", "> 0"]),
        (("--suite", "bbob", "--functions", "1", "--budget", "lots"), ["--budget", "1e4"]),
        (("--suite", "bbob", "--functions", "5-1"), ["backwards", "1-5"]),
        (("--preset", "bbob-quik"), ["Did you mean 'bbob-quick'"]),
    ],
)
def test_bad_suite_input(tmp_path, args, words):
    # a later --budget wins in Typer, so the bad budgets replace HOURS' one
    r = mawdo("bench", "run", *HOURS, *args, "--out", "x.db", cwd=tmp_path)
    assert r.returncode != 0
    assert "Traceback" not in r.stderr
    for w in words:
        assert w in r.stderr, (w, r.stderr)
    assert not (tmp_path / "x.db").exists()


@pytest.mark.parametrize(
    ("suite", "module"), [("bbob", "ioh"), ("cec2017", "opfunu"), ("cec2017-opfunu", "opfunu")]
)
def test_missing_extra_names_the_pip_install(tmp_path, suite, module):
    # A package of that name that fails to import: what an environment without the extra sees.
    blocked = tmp_path / "blocked" / module
    blocked.mkdir(parents=True)
    (blocked / "__init__.py").write_text("raise ImportError('not installed (test)')\n")
    path = os.pathsep.join([str(tmp_path / "blocked"), os.environ.get("PYTHONPATH", "")])
    r = mawdo("bench", "run", *HOURS, "--suite", suite, "--functions", "1", "--dims", "10",
              "--instances", "1", "--out", "x.db", cwd=tmp_path,
              env_extra={"PYTHONPATH": path})  # fmt: skip
    assert r.returncode == 1 and "Traceback" not in r.stderr
    assert f"needs the package '{module}'" in r.stderr
    assert 'pip install "mawdo[bbob]"' in r.stderr
    assert not (tmp_path / "x.db").exists()


@pytest.mark.slow
def test_run_resume_export_report_through_the_command(tmp_path):
    run = ("bench", "run", "--suite", "bbob", "--functions", "1,8", "--instances", "1-2",
           "--dims", "2,3", "--budget", "40", "--runs", "2", "--algorithms", "random,gwo",
           "--workers", "2", "--out", "s.db", "--no-progress")  # fmt: skip
    first = mawdo(*run, cwd=tmp_path)
    assert first.returncode == 0, first.stderr
    assert "complete: 32 runs computed" in first.stdout
    again = mawdo(*run, cwd=tmp_path)
    assert "0 runs computed" in again.stdout and "32 already stored" in again.stdout
    exp = mawdo("bench", "export", "--format", "ioh", "s.db", "logs", cwd=tmp_path)
    assert exp.returncode == 0, exp.stderr
    logs = read_analyzer_logs(tmp_path / "logs" / "gwo")
    with Store.read(tmp_path / "s.db") as store:
        rows = [r for _, _, r in store.rows(algorithm="gwo")]
    best = sorted(float(log["precision"][-1]) for log in logs)
    np.testing.assert_array_equal(best, sorted(r.precision for r in rows))
    rep = mawdo("bench", "report", "s.db", "--out", "rep", "--no-plots", cwd=tmp_path)
    assert rep.returncode == 0, rep.stderr
    assert (tmp_path / "rep" / "art_d3.csv").is_file()
    bad = mawdo("bench", "export", "--format", "coco", "s.db", "logs", cwd=tmp_path)
    assert bad.returncode == 2 and "'coco' is not an export format; choose 'ioh'" in bad.stderr


def test_report_of_stores_run_per_dimension(tmp_path):
    for dim in ("2", "3"):
        run = ("bench", "run", "--suite", "bbob", "--functions", "1", "--instances", "1",
               "--dims", dim, "--budget", "20", "--runs", "2", "--algorithms", "random",
               "--out", f"d{dim}.db", "--no-progress")  # fmt: skip
        assert mawdo(*run, cwd=tmp_path).returncode == 0
    rep = mawdo("bench", "report", "d2.db", "d3.db", "--out", "rep", "--no-plots", cwd=tmp_path)
    assert rep.returncode == 0, rep.stderr
    assert {p.name for p in (tmp_path / "rep").glob("art_d*.csv")} == {"art_d2.csv", "art_d3.csv"}
    twice = mawdo("bench", "report", "d2.db", "d2.db", "--out", "r2", cwd=tmp_path)
    assert twice.returncode == 2 and "report them separately" in twice.stderr
    missing = mawdo("bench", "report", "d2.db", "nope.db", "--out", "r3", cwd=tmp_path)
    assert missing.returncode == 2 and "no such results store: nope.db" in missing.stderr


@pytest.mark.parametrize(
    ("damage", "words"),
    [
        ("missing", ["CEC 2022 F9 needs", "shift_data_9.txt", "does not exist"]),
        ("damaged", ["CEC 2022 F9 needs", "M_9_D10.txt", "damaged", "not the official file"]),
        ("no folder", ["MAWDO_CEC2022_DATA=", "is not a folder"]),
    ],
)
def test_bad_cec_data_is_named_and_exits_2(tmp_path, damage, words):
    from mawdo.suites.cec_data import data_folder

    data = tmp_path / "data"
    shutil.copytree(data_folder(2022), data)
    if damage == "missing":
        (data / "shift_data_9.txt").unlink()
    elif damage == "damaged":
        text = (data / "M_9_D10.txt").read_text()
        i = text.index("1")  # one digit changed: still numbers, no longer the official file
        (data / "M_9_D10.txt").write_text(text[:i] + "2" + text[i + 1 :])
    else:
        data = tmp_path / "nowhere"
    tiny = ("--runs", "1", "--budget", "2", "--algorithms", "random", "--no-progress")
    env = {"MAWDO_CEC2022_DATA": str(data)}
    r = mawdo("bench", "run", *tiny, "--suite", "cec2022", "--functions", "1,9", "--dims", "10",
              "--out", "x.db", cwd=tmp_path, env_extra=env)  # fmt: skip
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    for w in words:
        assert w in r.stderr, (w, r.stderr)
    assert not (tmp_path / "x.db").exists()
