"""The jit table's upkeep (:data:`mawdo.jit.warm.SIGNATURES`): record what a command compiles,
and time each row's compile alone in a fresh process.

``python -m mawdo.jit record -- ARGS`` (the same as ``python -m mawdo.jit.record record --
ARGS``) runs ``mawdo ARGS`` on an empty cache, adds every compile it made to the table, then
re-times the whole table (:func:`retime`); ``python -m mawdo.jit retime`` re-times it alone
(after a kernel changed).

Why a fresh process: a compile timed inside the command also pays for whatever the command
compiled first in that process (Numba's own helpers, shared callees), so ``moving_pass``
read 35.6 s in ``plan paper`` against 14.3 s compiled on its own. :class:`mawdo.jit.schedule
.Schedule` orders the work by these seconds (the longest chain first), and with the in-command
figures the critical chain looked far longer than it is. In table order on an empty cache,
each row's callees are compiled (and timed) before it, so a row's seconds are its own compile,
as a process of ``jitwarm`` will meet it.
"""

from __future__ import annotations

import importlib
import json
import os
import runpy
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from mawdo.jit.inline import fresh_ir_inlining
from mawdo.jit.warm import SIGNATURES, Entry, dispatcher, load_table, parse, src_folder

HEADER = "# module\tfunction\tCPU s\tcaller\targument types (python -m mawdo.jit)\n"


def write_table(entries: list[Entry], path: Path = SIGNATURES) -> None:
    """Write ``entries`` as a signature table at ``path`` (its header first)."""
    path.parent.mkdir(exist_ok=True)
    path.write_text(HEADER + "".join(e.line() + "\n" for e in entries))


def time_rows(entries: list[Entry], say=None) -> list[float]:
    """CPU seconds of each entry's compile, compiled in this process in the given order
    (run it on an empty ``NUMBA_CACHE_DIR``: a cached kernel loads instead); ``say(line)``
    after each row, when given."""
    spent = []
    for k, e in enumerate(entries, 1):
        disp, sig = dispatcher(e), parse(e.sig)
        t0 = time.process_time()
        with fresh_ir_inlining():  # as jitwarm's processes compile it
            disp.compile(sig)
        spent.append(time.process_time() - t0)
        if say:
            say(f"  [{k}/{len(entries)}] {e.key}: {spent[-1]:.2f} s")
    return spent


def retime(path: Path = SIGNATURES, progress=print) -> list[Entry]:
    """Re-time every row of the table at ``path`` in a fresh process on an empty cache (in
    table order: callees first) and write the seconds back; about a minute of CPU.

    Parameters
    ----------
    path : Path
        The table (default :data:`~mawdo.jit.warm.SIGNATURES`); rows keep their order.
    progress : callable, optional
        Called with a line of text before and after the compile (None: silent).

    Returns
    -------
    list of Entry
        The rows with their new seconds (CPU s, >= 0).
    """
    entries = load_table(path)
    if progress:
        cpu = sum(e.seconds for e in entries)
        progress(f"re-timing {len(entries)} rows in a fresh process ({cpu:.0f} s of CPU last time)")
    # the child says each row on stderr, shown as it goes when there is progress to show
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [src_folder(), env.get("PYTHONPATH")]))
        cmd = [sys.executable, "-m", "mawdo.jit.record", "time", str(path)]
        err = None if progress else subprocess.DEVNULL
        pipe = subprocess.PIPE
        out = subprocess.run(cmd, env=env, stdout=pipe, stderr=err, text=True, check=True)
    spent = json.loads(out.stdout.strip().splitlines()[-1])
    timed = [
        Entry(e.module, e.name, round(max(0.0, s), 2), e.caller, e.sig)
        for e, s in zip(entries, spent, strict=True)
    ]
    write_table(timed, path)
    if progress:
        progress(f"re-timed: {sum(spent):.1f} s of CPU in all")
    return timed


def record(argv: list[str], path: Path = SIGNATURES) -> list[Entry]:
    """Run ``mawdo ARGV`` in this process and add every compile it made to the table at ``path``.

    Run it on an empty cache (``NUMBA_CACHE_DIR`` a new folder): a kernel loaded from the cache
    is not compiled, so not seen. Compiles whose types do not read back from their ``repr``
    (named tuples) are left out: their callers compile them. The seconds written are timed
    within the command (less the recorded callees'); :func:`retime` replaces them with each
    row's compile alone (``python -m mawdo.jit record`` does both).
    """
    from numba.core import event

    seen: list[Entry] = []
    # per compile under way: [CPU at its start, its recorded callees' CPU, its key or None]
    stack: list[list] = []

    class Recorder(event.Listener):
        def on_start(self, ev) -> None:
            disp = ev.data["dispatcher"]
            func, args = disp.py_func, ev.data["args"]
            # only what the table can name (an overload's implementation cannot be looked up:
            # its caller compiles it), with types that read back
            named = getattr(sys.modules.get(func.__module__), func.__name__, None) is disp
            keep = (
                func.__module__.startswith("mawdo.")
                and named
                and _reads_back(repr(tuple(args)), args)
            )
            stack.append([time.process_time(), 0.0, keep and f"{func.__module__}.{func.__name__}"])

        def on_end(self, ev) -> None:
            start, children, key = stack.pop()
            spent = time.process_time() - start  # CPU: the same on a busy machine
            if not key:
                return  # its time counts as its caller's
            func = ev.data["dispatcher"].py_func
            caller = next((s[2] for s in reversed(stack) if s[2]), "-")
            sig = repr(tuple(ev.data["args"]))
            # its own share: less what its recorded callees took (compiled on their own)
            seen.append(Entry(func.__module__, func.__name__, spent - children, caller, sig))
            for s in reversed(stack):
                if s[2]:
                    s[1] += spent
                    break

    event.register("numba:compile", Recorder())
    # the command compiles in this process (not in warm()'s children, which it would start)
    os.environ["MAWDO_JIT_JOBS"] = "1"
    argv0, sys.argv = sys.argv, ["mawdo", *argv]
    # no end without teardown (mawdo.cli.quick_exit's os._exit) before the table is written
    importlib.import_module("mawdo.cli.quick_exit").end = lambda code: None
    try:  # the command as `python -m mawdo.cli ARGV` runs it (by name: commands sit above us)
        runpy.run_module("mawdo.cli", run_name="__main__")
    except SystemExit as exc:
        if exc.code:
            raise
    finally:
        sys.argv = argv0
        table = _merge(load_table(path), seen)
        write_table(table, path)
    return table


def _reads_back(sig: str, args) -> bool:
    try:
        return parse(sig) == tuple(args)
    except Exception:
        return False


def _merge(old: list[Entry], new: list[Entry]) -> list[Entry]:
    """``old`` then the entries of ``new`` it lacks (by module, name and types), in order."""
    keys = {(e.module, e.name, e.sig) for e in old}
    out = list(old)
    for e in new:
        if (e.module, e.name, e.sig) not in keys:
            keys.add((e.module, e.name, e.sig))
            out.append(e)
    return out


def main(argv: list[str]) -> int:
    """``record [--] ARGS`` | ``retime`` | ``time PATH`` (the child of :func:`retime`)."""
    if argv[:1] == ["time"]:
        say = lambda line: print(line, file=sys.stderr, flush=True)  # noqa: E731
        print(json.dumps(time_rows(load_table(Path(argv[1])), say)))
        return 0
    if argv[:1] == ["record"]:
        rest = argv[1:]
        record(rest[1:] if rest[:1] == ["--"] else rest)
    retime()
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
