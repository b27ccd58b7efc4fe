"""Long steps of a command say what they are doing on stderr (issue 28, item 2): compiling the
kernels, drawing the snapshot grid, writing the GIF. What is asserted is the messages, not
timings (those are in ``python -m benchmarks startup``)."""

from __future__ import annotations

import re
import sys
import time

import numpy as np
import pytest
from numba import njit

from mawdo.cli.progress import notice_compiles, step
from mawdo.planning import render
from tests.cli_run import ENV, children, ctrl_c, interruptible, mawdo


def test_a_compile_is_announced_once_with_its_total_time(capsys):
    @njit(cache=False)
    def twice(x):
        return 2 * x

    @njit(cache=False)
    def calls(x):
        return twice(x) + 1

    with notice_compiles(warm=False):  # (the kernels' warm-up: tests/test_jitwarm.py)
        assert calls(3) == 7  # compiles calls, and twice inside it
        assert calls(4.5) == 10.0  # a second signature: compiled, not announced again
    err = capsys.readouterr().err
    assert err.count("compiling kernels (first run only") == 1
    assert err.count("kernels compiled in") == 1
    with notice_compiles(warm=False):
        assert calls(5) == 11  # nothing left to compile: nothing said
    assert capsys.readouterr().err == ""


def test_a_long_compile_says_every_few_seconds_that_it_goes_on(capsys, monkeypatch):
    from mawdo.cli import progress

    monkeypatch.setattr(progress, "EVERY", 0.01)  # a line every 10 ms of compiling

    @njit(cache=False)
    def slow(x):
        return np.sort(x)[0] + np.argsort(x)[0]  # a few hundred ms of compiling

    with notice_compiles(warm=False):
        assert slow(np.array([3.0, 1.0])) == 2.0
    err = capsys.readouterr().err.splitlines()
    ticks = [line for line in err if line.startswith("compiling kernels: ")]
    assert len(ticks) >= 2 and all(line.endswith(" s") for line in ticks)
    assert err[0].startswith("compiling kernels (first run only")
    assert err[-1].startswith("kernels compiled in")


def test_a_step_names_itself_and_says_when_it_is_done(capsys):
    with step("writing the thing"):
        pass
    lines = capsys.readouterr().err.splitlines()
    assert lines[0] == "writing the thing ..."
    assert lines[1].startswith("writing the thing: done in ") and lines[1].endswith(" s")
    with step("quiet", enabled=False):
        pass
    assert capsys.readouterr().err == ""


@pytest.mark.slow  # two whole `plan paper` runs in subprocesses, 30-60 s on 2 cores
def test_plan_says_when_it_draws_the_grid_and_writes_the_gif(tmp_path):
    out = tmp_path / "run"
    r = mawdo("plan", "paper", "--preset", "quick", "--out", str(out))
    assert r.returncode == 0, r.stderr
    # on Linux the figures are set up in a second process while the run is planned: the line
    # says so
    early = ", set up while planning" if render.can_fork() else ""
    line = rf"drawing the snapshot grid and writing the GIF \(\d+ frames{early}\) \.\.\."
    assert re.search(line, r.stderr), r.stderr
    assert "writing the GIF" not in r.stdout  # results on stdout, progress on stderr
    assert (out / "run.gif").is_file() and (out / "snapshots.png").is_file()
    quiet = mawdo("plan", "paper", "--preset", "quick", "--no-progress", "--out", str(out))
    assert quiet.returncode == 0 and "writing the GIF" not in quiet.stderr


@pytest.mark.slow
def test_a_first_plan_on_an_empty_numba_cache_says_it_compiles(tmp_path):
    env = {**ENV, "NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    args = ("plan", "paper", "--preset", "quick", "--out", str(tmp_path))
    r = mawdo(*args, env=env)
    assert r.returncode == 0, r.stderr
    assert "compiling kernels (first run only" in r.stderr
    assert "kernels compiled in" in r.stderr
    # all in the warm-up's processes: the kernel that started it loads from their cache
    assert r.stderr.count("kernels compiled in") == 1, r.stderr
    assert "compiling kernels (first run only) ..." not in r.stderr, r.stderr
    assert "frames, set up while planning)" in r.stderr, r.stderr  # forked on a cold cache too
    again = mawdo(*args, env=env)
    assert again.returncode == 0 and "compiling kernels" not in again.stderr
    assert np.isfinite(float(again.stdout.split("length_px:")[1].split()[0]))


def test_ctrl_c_while_the_kernels_compile_stops_every_process(tmp_path):
    env = {**ENV, "NUMBA_CACHE_DIR": str(tmp_path / "numba")}
    cmd = [sys.executable, "-m", "mawdo.cli", "plan", "paper", "--out", str(tmp_path / "out")]
    proc = interruptible(cmd, env=env)
    for line in proc.stderr:  # the warm-up's processes are started
        if line.startswith("compiling kernels (first run only: about"):
            break
    time.sleep(2.0)
    assert len(children(proc.pid)) >= 2  # compiling (and the figures' process)
    ctrl_c(proc)  # exit 130, no traceback, no process of the command left
