"""The ``mawdo`` program's end without the interpreter's teardown, where a command allows it.

Once a warm ``mawdo plan paper`` has written its files and printed its lines, the interpreter
still tears itself down: it frees every module and object (NumPy, Numba's typing tables and
compiled kernels, matplotlib, the run), 0.3-0.4 s of CPU measured on this command, after
everything the user asked for is done. A command that has nothing left to finish (its files
closed, no process or thread of its own still running) calls :func:`allow`; the program then
ends with ``os._exit`` once the command has returned (:func:`end`), its output streams flushed.

Only the program itself ends so (:func:`mawdo.cli.program`, the console script and ``python -m
mawdo.cli``): a caller of the Typer app in its own process (a test's ``CliRunner``, a script)
gets the usual ``SystemExit``. Atexit handlers are not run; the conditions :func:`end` checks
(no child process started by :mod:`multiprocessing` alive, no thread that is not a daemon)
are those under which the handlers the commands rely on (multiprocessing joining its
children) have nothing to do, and a program watched by a tracer or a profiler (coverage,
``python -m cProfile``, a debugger), whose report comes at the end, ends as usual.
"""

from __future__ import annotations

import os
import sys
import threading


class _State:
    program = False  # set by mawdo.cli.program: this process is the mawdo program
    allowed = False  # set by a command that has nothing left to finish


STATE = _State()


def allow() -> None:
    """Let the program end without the interpreter's teardown once this command returns."""
    STATE.allowed = True


def _nothing_running() -> bool:
    if sys.gettrace() is not None or sys.getprofile() is not None:
        return False  # a tool watches the program (coverage, a profiler, a debugger): its end
    mp = sys.modules.get("multiprocessing")
    if mp is not None and mp.active_children():
        return False
    return all(t.daemon or t is threading.main_thread() for t in threading.enumerate())


def end(code: int) -> None:
    """End the process now with ``code`` if the program runs and the command allowed it
    (:func:`allow`) and nothing of its own still runs; otherwise return (the caller exits
    as usual)."""
    if not (STATE.program and STATE.allowed) or not _nothing_running():
        return
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a closed pipe: what exit's flush would have met
            code = code or 120  # (the code Python exits with when the final flush fails)
    os._exit(code)
