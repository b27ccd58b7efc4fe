"""Fill Numba's on-disk cache before anyone waits for it, compiling kernels in parallel processes.

A first ``mawdo plan paper`` spends 40-75 s of CPU (by the machine) compiling kernels, one after
the other in one process, on one core. Numba caches each compiled function in its own files, so
several processes can fill one cache at once, each compiling different functions; a later
process then loads every kernel from the cache and compiles nothing.

What to compile is a table, :data:`SIGNATURES` (package data): per kernel its module, name,
argument types (``repr`` of Numba's types, read back with :func:`parse`), its compile's CPU
seconds and its caller. ``python -m mawdo.jit record -- ARGS`` writes it
(:mod:`mawdo.jit.record`: runs ``mawdo ARGS`` on an empty cache, keeps every compile that Numba
can compile again from the table, the commands' entry points and the functions they call that
take plain arrays, tuples and scalars, then times each row alone in a fresh process;
``python -m mawdo.jit retime`` re-times only). ``tests/test_jitwarm.py`` checks that a
warmed cache leaves nothing to compile for ``mawdo plan paper``, so a table that fell behind a
kernel's arguments fails a test.

Usage: ``python -m mawdo.jit [--jobs N]`` (what ``make install`` and ``make demo`` run after
installing), or :func:`warm` from a command that finds its kernels missing.
"""

from __future__ import annotations

import argparse
import importlib
import os
import queue
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path

from mawdo.jit.cache import numba_cache_folder
from mawdo.jit.inline import fresh_ir_inlining
from mawdo.jit.schedule import Schedule

_PACKAGE = Path(__file__).resolve().parent.parent  # the mawdo package
SIGNATURES = _PACKAGE / "data" / "jit_signatures.txt"


@dataclass(frozen=True)
class Entry:
    """One compile of the table: ``module.name`` for the argument types ``sig`` (a ``repr``)."""

    module: str
    name: str
    seconds: float  # CPU seconds of its compile alone, its callees compiled before (retime)
    caller: str  # "module.name" of the entry whose compile compiled it ("-": none, from Python)
    sig: str

    def line(self) -> str:
        return f"{self.module}\t{self.name}\t{self.seconds:.2f}\t{self.caller}\t{self.sig}"

    @classmethod
    def from_line(cls, line: str) -> Entry:
        module, name, seconds, caller, sig = line.split("\t", 4)
        return cls(module, name, float(seconds), caller, sig)

    @property
    def key(self) -> str:
        return f"{self.module}.{self.name}"


def load_table(path: Path = SIGNATURES) -> list[Entry]:
    """The entries of a signature table, in the order they were recorded (empty if none)."""
    try:
        text = path.read_text()
    except OSError:
        return []
    return [Entry.from_line(r) for r in text.splitlines() if r and not r.startswith("#")]


def parse(sig: str) -> tuple:
    """Numba argument types from their ``repr`` (``"(Array(float64, 2, 'C', ...), int64)"``)."""
    from numba.core import types

    names = dict(vars(types))
    names["bool"] = types.boolean  # repr(types.boolean) is "bool"
    value = eval(sig, {"__builtins__": {}}, names)  # noqa: S307 - our own table, no builtins
    return value if isinstance(value, tuple) else (value,)


def dispatcher(entry: Entry):
    """The Numba dispatcher an entry names."""
    return getattr(importlib.import_module(entry.module), entry.name)


def is_cached(entry: Entry) -> bool:
    """Whether Numba's cache already holds ``entry`` (so a process would load, not compile it)."""
    disp = dispatcher(entry)
    sig = parse(entry.sig)
    if sig in disp.overloads:
        return True
    cache = getattr(disp, "_cache", None)
    if cache is None or not hasattr(cache, "_index_key"):
        return False
    # Numba's own check without rebuilding the code: the index file lists (signature, machine)
    # and the data file unpickles (a damaged one is dropped: mawdo.jit.heal)
    key = cache._index_key(sig, disp.targetctx.codegen())
    name = cache._cache_file._load_index().get(key)
    if name is None:
        return False
    try:
        cache._cache_file._load_data(name)
    except OSError:  # missing, or damaged and dropped
        return False
    return True


def missing(entries: list[Entry] | None = None) -> list[Entry]:
    """The entries of the table (by default :data:`SIGNATURES`) that are not cached."""
    entries = load_table() if entries is None else entries
    return [e for e in entries if not is_cached(e)]


def _index_folder(e: Entry) -> tuple[Path, Path]:
    """Where Numba keeps ``e``'s index file if it caches beside the sources or under
    ``NUMBA_CACHE_DIR`` (no import), and ``e``'s source file."""
    base = os.environ.get("NUMBA_CACHE_DIR")
    source = _PACKAGE.parent.joinpath(*e.module.split(".")).with_suffix(".py")
    if not source.is_file():  # a package's __init__
        source = source.with_suffix("") / "__init__.py"
    folder = numba_cache_folder(source.parent, Path(base)) if base else None
    return folder or source.parent / "__pycache__", source


def _has_index(e: Entry) -> bool:
    folder, source = _index_folder(e)
    return any(folder.glob(f"{source.stem}.{e.name}-*.nbi"))


def looks_cached(entries: list[Entry]) -> bool:
    """Whether every entry has an index file where Numba caches it (a few ``stat`` calls, no
    import): in the ``__pycache__`` beside its module, or under ``NUMBA_CACHE_DIR``. False can
    be wrong (Numba may cache elsewhere, e.g. for a read-only install): check with
    :func:`missing`."""
    return all(_has_index(e) for e in entries)


def todo(entries: list[Entry] | None = None) -> list[Entry]:
    """The entries of the table (or ``entries``) a process would compile now (none when the
    cache is warm).

    A few ``stat`` calls where Numba's cache folders are known (``NUMBA_CACHE_DIR``, or the
    sources' folders writable): an entry without an index file there is missing; only those
    with one are checked by :func:`missing` (which imports Numba and the kernels' modules, 0.3 s
    on a cold cache, before the compiling processes could start). Elsewhere (a read-only
    install: Numba caches in its user folder) :func:`missing` checks all of them."""
    entries = load_table() if entries is None else entries
    if looks_cached(entries):
        return []
    known = "NUMBA_CACHE_DIR" in os.environ or all(
        os.access(_index_folder(e)[1].parent, os.W_OK) for e in entries
    )
    if not known:
        return missing(entries)
    unindexed = [e for e in entries if not _has_index(e)]
    indexed = [e for e in entries if e not in unindexed]
    left = set(unindexed) | (set(missing(indexed)) if indexed else set())
    return [e for e in entries if e in left]


def compile_entries(entries: list[Entry], done=None) -> None:
    """Compile ``entries`` in this process, in order (each into Numba's cache; one already
    cached loads instead); ``done(entry)`` after each."""
    for e in entries:
        try:
            with fresh_ir_inlining():
                dispatcher(e).compile(parse(e.sig))
        except Exception as exc:  # a stale row must not stop the others: the run compiles it
            print(f"warning: {e.module}.{e.name} did not compile ({exc})", file=sys.stderr)
        if done:
            done(e)


def warm(jobs: int = 2, entries: list[Entry] | None = None, tick=None, every: float = 2.0) -> int:
    """Compile the table's missing kernels into Numba's cache, in ``jobs`` processes at once.

    Each process is handed one entry at a time as it becomes free (:class:`mawdo.jit.schedule
    .Schedule`: the longest chain first, a kernel after the kernels it calls), so the actual
    compile times balance the processes.

    Parameters
    ----------
    jobs : int
        Processes compiling at once, >= 1 (about the number of free cores).
    entries : list of Entry, optional
        What to compile (default: the table's entries that are not cached).
    tick : callable, optional
        ``tick(done, total, seconds)`` every ``every`` seconds and once at the end: how many
        entries are compiled, of how many, after how long (for a progress line).
    every : float
        Seconds between ticks.

    Returns
    -------
    int
        Number of entries compiled.
    """
    pending = missing() if entries is None else entries
    if not pending:
        return 0
    t0 = last = time.perf_counter()
    sched = Schedule(pending)
    events: queue.Queue = queue.Queue()  # (process, "done" or "gone")
    procs = [_spawn(k, events) for k in range(min(max(1, jobs), len(pending)))]
    running: dict[int, Entry] = {}
    alive = set(range(len(procs)))
    count = 0
    try:
        while alive and (running or not sched.empty):
            for k in sorted(alive - set(running)):
                e = sched.next(busy=bool(running))
                if e is None:
                    break
                running[k] = e
                if not _hand(procs[k], e):
                    alive.discard(k)
                    sched.finish(running.pop(k))  # left to the command that needs it
            try:
                k, what = events.get(timeout=0.05)
            except queue.Empty:
                k, what = None, None
            if what == "done" and k in running:
                sched.finish(running.pop(k))
                count += 1
            elif what == "gone":  # a process that died: its entry is left to the command
                alive.discard(k)
                if k in running:
                    sched.finish(running.pop(k))
            if tick and time.perf_counter() - last >= every:
                last = time.perf_counter()
                tick(count, len(pending), last - t0)
    except BaseException:  # Ctrl-C: no child goes on compiling behind the user's back
        for p in procs:
            p.kill()
            p.wait()
        raise
    for p in procs:
        _hand(p, None)
        p.wait()
    if tick:
        tick(count, len(pending), time.perf_counter() - t0)
    return count


_CHILD = ["-m", "mawdo.jit", "compile"]  # a compiling process's arguments


def _spawn(k: int, events: queue.Queue):
    """Start compiling process ``k``: it compiles each entry written to its stdin (a line) and
    answers ``done``; a thread puts ``(k, "done")`` on ``events`` for each, ``(k, "gone")``
    when the process ends."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [src_folder(), env.get("PYTHONPATH")]))
    cmd = [sys.executable, *_CHILD]
    proc = subprocess.Popen(
        cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=env, text=True, bufsize=1
    )

    def read() -> None:
        for line in proc.stdout:
            if line.strip() == "done":
                events.put((k, "done"))
        events.put((k, "gone"))

    threading.Thread(target=read, daemon=True).start()
    return proc


def _hand(proc, entry: Entry | None) -> bool:
    """Write ``entry`` to a compiling process (None: no more, close its input); False if it
    has gone."""
    try:
        if entry is None:
            proc.stdin.close()
        else:
            proc.stdin.write(entry.line() + "\n")
            proc.stdin.flush()
        return True
    except (OSError, ValueError):  # a broken pipe, or closed already
        return False


def load_instead(disp, args) -> bool:
    """Make the compile Numba is about to run for ``disp`` at argument types ``args`` load the
    kernel from the cache instead, once (True), if the cache holds it (a warm-up begun by
    that compile's start event has just put it there); else change nothing (False).

    Numba looks in its cache before it announces a compile (the ``numba:compile`` event), so
    a listener that fills the cache then sees Numba compile that one kernel again in its own
    process: 0.8 s of CPU for ``plan paper``'s first kernel. This answers its compiler's next
    call with the cached result, inserted as Numba's cache hit inserts it.
    """
    cache, compiler = getattr(disp, "_cache", None), getattr(disp, "_compiler", None)
    if cache is None or compiler is None or "compile" in vars(compiler):
        return False
    if "save_overload" in vars(cache) or not hasattr(cache, "load_overload"):
        return False
    if tuple(args) in disp.overloads:  # Numba compiles nothing it has: no call would come
        return False
    try:
        cres = cache.load_overload(tuple(args), disp.targetctx)
    except Exception:  # an unreadable entry: Numba compiles, as it would have
        cres = None
    if cres is None or cres.objectmode:
        return False

    def compile(args, return_type):
        del compiler.compile  # once: the compiler's own method from now on
        disp.targetctx.insert_user_function(cres.entry_point, cres.fndesc, [cres.library])
        return cres

    def save_overload(sig, data):  # Numba's save after its compile: the entry is there
        del cache.save_overload

    compiler.compile, cache.save_overload = compile, save_overload
    return True


def src_folder() -> str:
    """The folder this copy of mawdo is imported from (children import the same code)."""
    return str(_PACKAGE.parent)


def _say_done(entry: Entry) -> None:
    print("done", flush=True)


def _line(done: int, total: int, seconds: float) -> None:
    print(f"compiling kernels: {done}/{total} done after {seconds:.0f} s", flush=True)


def main(argv: list[str] | None = None) -> int:
    """``python -m mawdo.jit [--jobs N] | record -- ARGS | retime | compile ROWS``."""
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["compile"]:  # a child of warm(): compile each row it is given
        # Ctrl-C reaches the whole group; the command ends this process and says it once (as
        # a KeyboardInterrupt it could land in an LLVM callback, which prints it and goes on)
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        for line in sys.stdin:
            if line.strip():
                compile_entries([Entry.from_line(line.rstrip("\n"))], done=_say_done)
        return 0
    if argv[:1] in (["record"], ["retime"]):  # the table's upkeep, a module above this one
        return subprocess.call([sys.executable, "-m", "mawdo.jit.record", *argv])
    parser = argparse.ArgumentParser(prog="python -m mawdo.jit", description=__doc__.split("\n")[0])
    parser.add_argument("--jobs", type=int, default=2, help="processes compiling at once (>= 1)")
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error(f"--jobs must be an integer >= 1, got {args.jobs}")
    t0 = time.perf_counter()
    pending = missing()  # every entry read back, so a damaged one is dropped and compiled
    if not pending:
        print("kernels already compiled (Numba's cache is warm)")
        return 0
    cpu = sum(e.seconds for e in pending)
    print(f"compiling {len(pending)} kernels into Numba's cache in {args.jobs} processes "
          f"(once per install; about {cpu:.0f} s of CPU)", flush=True)  # fmt: skip
    try:
        n = warm(args.jobs, pending, tick=_line)
    except KeyboardInterrupt:  # the compiling processes are ended; what they cached stays
        print("interrupted: run it again to compile the rest", file=sys.stderr)
        return 130
    print(f"{n} kernels compiled in {time.perf_counter() - t0:.1f} s", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
