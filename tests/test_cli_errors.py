"""The command's error edge, through the real command in a subprocess: expected errors end in a
message on stderr and a non-zero exit code, never a traceback, and bad output paths are refused
before any computing starts."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest


def mawdo(*args: str, cwd=None) -> subprocess.CompletedProcess:
    env = {**os.environ, "MPLBACKEND": "Agg"}
    # A budget that would run for hours: the command must stop before computing. (timeout ->
    # the test fails with TimeoutExpired, which is what computing first would mean)
    return subprocess.run(
        [sys.executable, "-m", "mawdo.cli", *args],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
        cwd=cwd,
    )


HOURS = ("--runs", "1000", "--iters", "100000000", "--no-progress")


@pytest.mark.parametrize(
    "args, words",
    [
        (("optimize", "sphere", *HOURS, "--plot", "out.xyz"), ["out.xyz", ".png"]),
        (("optimize", "sphere", *HOURS, "--json", "/proc/nope/x.json"), ["/proc/nope"]),
        (("bench", "report", "missing.db", "--out", "/proc/nope/rep"), ["/proc/nope/rep"]),
        (("plan", "missing.toml"), ["missing.toml"]),
        (("bench", "report", "missing.db", "--out", "rep"), ["no results store", "missing.db"]),
    ],
)
def test_expected_errors_are_a_message_not_a_traceback(args, words, tmp_path):
    res = mawdo(*args, cwd=tmp_path)
    assert res.returncode != 0
    assert "Traceback" not in res.stderr + res.stdout
    assert "╭─ Traceback" not in res.stderr
    for w in words:
        assert w in res.stderr, res.stderr
    assert not (tmp_path / "out.xyz").exists()


def test_an_unwritable_report_folder_is_refused_before_reading(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        if os.access(ro, os.W_OK):
            # root writes anywhere: a file where the folder should be is just as unwritable
            target = tmp_path / "afile"
            target.write_text("x")
        else:
            target = ro / "rep"
        res = mawdo("bench", "report", "missing.db", "--out", str(target), cwd=tmp_path)
    finally:
        ro.chmod(0o700)
    assert res.returncode == 2  # a bad --out is bad input, whoever runs the command
    assert str(target) in res.stderr and "Traceback" not in res.stderr
    assert "no results store" not in res.stderr  # the output was checked first


#: A command-line program on the project's error edge whose Ctrl-C lands inside code run by
#: ``exec`` of a string, as it does when it arrives while ``dataclasses`` builds a class.
EXEC_INTERRUPTED = """
import typer
from mawdo.cli.errors import GuardedGroup

app = typer.Typer(cls=GuardedGroup)

@app.command()
def raised():
    exec("raise KeyboardInterrupt")

@app.command()
def caught():
    try:
        exec("raise KeyboardInterrupt")
    except KeyboardInterrupt:
        raise typer.Exit(130) from None

if __name__ == "__main__":
    app()
"""


@pytest.mark.parametrize("command", ["raised", "caught"])
def test_ctrl_c_inside_exec_still_exits_130_under_python_m(tmp_path, command):
    # CPython marks such an interrupt as unhandled and, under ``python -m``, kills itself with
    # SIGINT after the program's own exit(130): a parent saw -2 about one run in ten
    (tmp_path / "prog.py").write_text(EXEC_INTERRUPTED)
    proc = subprocess.run(
        [sys.executable, "-m", "prog", command], capture_output=True, text=True, cwd=tmp_path,
        timeout=120,
    )  # fmt: skip
    assert proc.returncode == 130, (proc.returncode, proc.stderr)
    assert "Traceback" not in proc.stderr
