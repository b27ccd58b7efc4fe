"""The ``mawdo`` program ends without the interpreter's teardown where a command allows it
(issue 28, item 2: 0.3-0.4 s of CPU after a warm ``plan paper`` had written everything), and
only then: its output complete, its exit code kept, a caller of the app in its own process
never ended, and never while a process or thread it started still runs.

Whether the teardown ran is seen from outside by an ``atexit`` handler that prints a line: the
interpreter runs it at a normal exit, ``os._exit`` skips it.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

from tests.cli_run import ENV

#: Runs the mawdo program as the console script does, with an atexit line to see the teardown.
PROGRAM = """
import atexit, sys
atexit.register(lambda: print("TEARDOWN", file=sys.stderr, flush=True))
sys.argv = ["mawdo", *sys.argv[1:]]
from mawdo.cli import program
program()
"""


def _program(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", PROGRAM, *args], capture_output=True, text=True, env=ENV,
        timeout=600,
    )  # fmt: skip


def test_plan_ends_without_teardown_and_with_all_its_output(tmp_path):
    out = tmp_path / "run"
    proc = _program("plan", "paper", "--preset", "quick", "--no-figures", "--no-progress",
                    "--max-steps", "30", "--out", str(out))  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert "TEARDOWN" not in proc.stderr  # ended by os._exit
    # the lines printed last reached the pipe, and the file is whole
    assert proc.stdout.rstrip().endswith(f"metrics: {out / 'metrics.json'}")
    assert json.loads((out / "metrics.json").read_text())["scenario"] == "paper"


def test_a_command_that_does_not_allow_it_and_an_error_end_as_usual(tmp_path):
    listed = _program("list", "scenarios")
    assert listed.returncode == 0 and "TEARDOWN" in listed.stderr and "paper" in listed.stdout
    bad = _program("plan", "paper", "--algorithm", "nosuch", "--out", str(tmp_path / "x"))
    assert bad.returncode == 2 and bad.stderr.startswith("error: ") and "TEARDOWN" in bad.stderr


def test_the_app_called_in_a_process_of_its_own_raises_system_exit(tmp_path):
    from mawdo.cli import app

    with pytest.raises(SystemExit) as done:
        app(["plan", "paper", "--preset", "quick", "--no-figures", "--no-progress",
             "--max-steps", "5", "--out", str(tmp_path / "run")], prog_name="mawdo")  # fmt: skip
    assert done.value.code == 0  # (this test process is still here to see it)


def test_a_profiled_program_ends_as_usual_with_its_report(tmp_path):
    out = tmp_path / "run"
    proc = subprocess.run(
        [sys.executable, "-m", "cProfile", "-m", "mawdo.cli", "plan", "paper", "--preset",
         "quick", "--no-figures", "--no-progress", "--max-steps", "5", "--out", str(out)],
        capture_output=True, text=True, env=ENV, timeout=600,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert "function calls" in proc.stdout  # cProfile's report, printed after the program


@pytest.mark.parametrize("running", ["process", "thread", "nothing"])
def test_end_waits_for_nothing_only_when_nothing_of_its_own_runs(running):
    script = textwrap.dedent(f"""
        import multiprocessing, sys, threading, time
        from mawdo.cli import quick_exit
        quick_exit.STATE.program = True
        quick_exit.allow()
        if {running!r} == "process":
            p = multiprocessing.get_context("fork").Process(target=time.sleep, args=(0.5,))
            p.start()
        elif {running!r} == "thread":
            threading.Thread(target=time.sleep, args=(0.5,)).start()
        print("before", flush=True)
        quick_exit.end(7)
        print("returned", flush=True)
        sys.exit(3)
    """)
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          env=ENV, timeout=60)  # fmt: skip
    if running == "nothing":
        assert (proc.returncode, proc.stdout) == (7, "before\n")
    else:
        assert (proc.returncode, proc.stdout) == (3, "before\nreturned\n"), proc.stderr
