"""``python benchmarks/plan_trace.py LOG ARGS...``: run ``mawdo ARGS`` (``plan paper ...``) in
this process with time marks at its phases, appended to ``LOG`` by every process of the command
(the command's, the figures' process it forks, and the GIF's process that one forks).

A mark is ``pid name wall cpu``: ``wall`` in seconds since ``TRACE_T0`` (the parent's
``time.perf_counter()`` when it started this process: Linux's monotonic clock is one clock for
all processes, so the interpreter's own start-up is counted), ``cpu`` the marking process's
CPU time (a forked process starts at 0). The hooks wrap functions of ``mawdo.cli.plan``,
``mawdo.planning.run.execute.Run`` and ``mawdo.planning.render.early`` and change nothing they do;
the command runs as the ``mawdo`` program does (:mod:`mawdo.cli.quick_exit`: ``end`` is marked
just before the program ends without its teardown);
:func:`phases` reads the marks back (:mod:`benchmarks.bench_startup`).
"""

from __future__ import annotations

import os
import sys
import time

T0 = float(os.environ.get("TRACE_T0", time.perf_counter()))


def mark(log: str, name: str) -> None:
    with open(log, "a") as f:
        f.write(f"{os.getpid()} {name} {time.perf_counter() - T0:.4f} {time.process_time():.4f}\n")


def _wrap(log, owner, name, label=None):
    fn = getattr(owner, name)

    def timed(*args, **kwargs):
        mark(log, f"{label or name}>")
        try:
            return fn(*args, **kwargs)
        finally:
            mark(log, f"{label or name}<")

    setattr(owner, name, timed)


def _figures(log, early) -> None:
    """Marks in the figures' process: its imports before the run is set up (``warm``), its
    set-up (``prepare``) and its work after the run."""
    run_figures = early.run_figures

    def traced(*args, **kwargs):
        prepare = run_figures(*args, **kwargs)

        def prepare_traced(*given):
            mark(log, "setup>")
            finish = prepare(*given)
            mark(log, "setup<")

            def finish_traced(payload):
                mark(log, "finish>")
                try:
                    return finish(payload)
                finally:
                    mark(log, "finish<")

            finish_traced.feed = finish.feed
            return finish_traced

        warm = getattr(prepare, "warm", None)
        if warm is not None:

            def warm_traced():
                mark(log, "warm>")
                warm()
                mark(log, "warm<")

            prepare_traced.warm = warm_traced
        return prepare_traced

    early.run_figures = traced


def main(log: str, args: list[str]) -> None:
    mark(log, "main")
    import mawdo.cli.main as cli  # noqa: I001  (the command's own imports, timed)

    mark(log, "imported")
    import mawdo.cli.plan as plan
    import mawdo.planning.render.animation as animation
    import mawdo.planning.render.early as early
    from mawdo.planning.run.execute import Run

    _wrap(log, plan, "_execute")
    _wrap(log, plan, "draw_figures")
    _wrap(log, Run, "execute", "run")
    _wrap(log, animation, "_write_gif", "gif")
    _figures(log, early)
    # as the mawdo program (mawdo.cli.program): the end without teardown where the command allows
    try:
        from mawdo.cli import quick_exit
    except ImportError:  # (sources from before it, STARTUP_BEFORE)
        quick_exit = None
    if quick_exit is not None:
        quick_exit.STATE.program = True
        end = quick_exit.end

        def marked_end(code):
            mark(log, "end")
            end(code)

        quick_exit.end = marked_end
    try:
        cli.app(prog_name="mawdo", args=args)
    except SystemExit as exc:
        if exc.code:
            raise
    mark(log, "end")  # (a version without the quick end, or a command that did not allow it)


def phases(log: str) -> dict:
    """The marks of ``log`` as ``{(role, name): (wall, cpu)}``, role ``main``, ``figures`` or
    ``gif`` (the process that marked it)."""
    rows = [line.split() for line in open(log) if line.strip()]
    main_pid = next(pid for pid, name, *_ in rows if name == "main")
    out = {}
    for pid, name, wall, cpu in rows:
        if pid == main_pid:
            role = "main"
        elif name.startswith("gif"):
            role = "gif"
        else:
            role = "figures"
        out[(role, name)] = (float(wall), float(cpu))
    return out


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
