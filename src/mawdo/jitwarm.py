"""Fill Numba's on-disk cache before anyone waits for it, compiling kernels in parallel processes.

A first ``mawdo plan paper`` spends 40-75 s of CPU (by the machine) compiling kernels, one after
the other in one process, on one core. Numba caches each compiled function in its own files, so
several processes can fill one cache at once, each compiling different functions; a later
process then loads every kernel from the cache and compiles nothing.

What to compile is a table, :data:`SIGNATURES` (package data): per kernel its module, name,
argument types (``repr`` of Numba's types, read back with :func:`parse`), its compile's CPU
seconds and its caller. ``python -m mawdo.jitwarm record -- ARGS`` writes it
(:mod:`mawdo.jitrecord`: runs ``mawdo ARGS`` on an empty cache, keeps every compile that Numba
can compile again from the table, the commands' entry points and the functions they call that
take plain arrays, tuples and scalars, then times each row alone in a fresh process;
``python -m mawdo.jitwarm retime`` re-times only). ``tests/test_jitwarm.py`` checks that a
warmed cache leaves nothing to compile for ``mawdo plan paper``, so a table that fell behind a
kernel's arguments fails a test.

Usage: ``python -m mawdo.jitwarm [--jobs N]`` (what ``make install`` and ``make demo`` run after
installing), or :func:`warm` from a command that finds its kernels missing.
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import subprocess
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path

from mawdo.jitcache import numba_cache_folder
from mawdo.jitinline import fresh_ir_inlining

_PACKAGE = Path(__file__).resolve().parent
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
    # Numba's own check without loading the code: the index file lists (signature, machine)
    key = cache._index_key(sig, disp.targetctx.codegen())
    return key in cache._cache_file._load_index()


def missing(entries: list[Entry] | None = None) -> list[Entry]:
    """The entries of the table (by default :data:`SIGNATURES`) that are not cached."""
    entries = load_table() if entries is None else entries
    return [e for e in entries if not is_cached(e)]


def looks_cached(entries: list[Entry]) -> bool:
    """Whether every entry has an index file where Numba caches it (a few ``stat`` calls, no
    import): in the ``__pycache__`` beside its module, or under ``NUMBA_CACHE_DIR``. False can
    be wrong (Numba may cache elsewhere, e.g. for a read-only install): check with
    :func:`missing`."""
    base = os.environ.get("NUMBA_CACHE_DIR")
    for e in entries:
        source = _PACKAGE.parent.joinpath(*e.module.split(".")).with_suffix(".py")
        if not source.is_file():  # a package's __init__
            source = source.with_suffix("") / "__init__.py"
        folder = numba_cache_folder(source.parent, Path(base)) if base else None
        folder = folder or source.parent / "__pycache__"
        if not any(folder.glob(f"{source.stem}.{e.name}-*.nbi")):
            return False
    return True


def todo() -> list[Entry]:
    """The table's entries a process would compile now (none when the cache is warm; the quick
    :func:`looks_cached` first, so that a warm start pays a few ``stat`` calls only)."""
    entries = load_table()
    return [] if looks_cached(entries) else missing(entries)


def shares(entries: list[Entry], jobs: int) -> list[list[Entry]]:
    """Split ``entries`` into at most ``jobs`` ordered lists, one per process, so that all end
    early: list scheduling by recorded compile time along the table's caller edges.

    Entries go in order of their longest chain (own time plus their callers' up to an entry
    nobody calls; so a kernel after its callees), each to the process that can start it
    first, no sooner than its callees end (a caller's process waits for callees another
    compiles, :func:`compile_entries`), of those the one that idles least. So the cost
    kernel's parts compile in both processes and the kernel after them.
    """
    keys = {e.key for e in entries}
    callees: dict[str, list[Entry]] = {}
    for e in entries:
        if e.caller in keys:
            callees.setdefault(e.caller, []).append(e)
    chain: dict[str, float] = {}

    def longest(e: Entry, seen: frozenset = frozenset()) -> float:
        if e.key not in chain:
            up = [c for c in entries if c.key == e.caller and c.key not in seen]
            chain[e.key] = e.seconds + max((longest(c, seen | {e.key}) for c in up), default=0)
        return chain[e.key]

    order = sorted(range(len(entries)), key=lambda i: (-longest(entries[i]), i))
    free = [0.0] * max(1, jobs)
    end: dict[str, float] = {}
    parts: list[list[Entry]] = [[] for _ in free]
    for i in order:
        e = entries[i]
        ready = max((end.get(c.key, 0.0) for c in callees.get(e.key, [])), default=0.0)
        k = min(range(len(free)), key=lambda k: (max(free[k], ready), -free[k]))
        end[e.key] = free[k] = max(free[k], ready) + e.seconds
        parts[k].append(e)
    return [p for p in parts if p]


def _below(entries: list[Entry]) -> dict[str, set[str]]:
    """Per entry's key, the keys of its callees in the table, theirs, and so on."""
    caller = {e.key: e.caller for e in entries}
    out: dict[str, set[str]] = {e.key: set() for e in entries}
    for e in entries:
        key, seen = e.caller, set()
        while key in out and key not in seen:
            seen.add(key)
            out[key].add(e.key)
            key = caller[key]
    return out


def _wait_for(others: list[Entry], below: dict[str, set[str]], current: list, timeout: float):
    """Make the dispatchers of ``others`` (another process compiles them), when needed while
    this process compiles a kernel above them (``current[0]``), wait until they are cached
    (at most ``timeout`` s), then load them (or compile, if they never came)."""
    for e in others:
        disp = dispatcher(e)
        own = disp.compile

        def compile(sig, e=e, own=own):
            if e.key in below.get(current[0], ()):
                limit = time.monotonic() + timeout
                while not is_cached(e) and time.monotonic() < limit:
                    time.sleep(0.02)
            return own(sig)

        disp.compile = compile


def compile_entries(
    entries: list[Entry], done=None, others: list[Entry] = (), timeout: float = 120.0
) -> None:
    """Compile ``entries`` in this process (each into Numba's cache); ``done(entry)`` after each.

    ``others`` are the entries other processes compile at the same time: a kernel here that
    calls one of them waits until it is cached instead of compiling it too (at most
    ``timeout`` seconds each; see :func:`shares` for the order that makes this safe).
    """
    current: list = [None]
    _wait_for(list(others), _below([*entries, *others]), current, timeout)
    for e in entries:
        disp = dispatcher(e)
        current[0] = e.key
        try:
            with fresh_ir_inlining():
                disp.compile(parse(e.sig))
        except Exception as exc:  # a stale row must not stop the others: the run compiles it
            print(f"warning: {e.module}.{e.name} did not compile ({exc})", file=sys.stderr)
        if done:
            done(e)


def warm(jobs: int = 2, entries: list[Entry] | None = None, tick=None, every: float = 2.0) -> int:
    """Compile the table's missing kernels into Numba's cache, in ``jobs`` processes at once.

    Parameters
    ----------
    jobs : int
        Processes compiling at once, >= 1 (each compiles its share; about the number of free
        cores).
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
    counts: list[int] = []
    parts = shares(pending, max(1, jobs))
    procs = [_spawn(part, [e for q in parts if q is not part for e in q], counts) for part in parts]
    try:
        while any(p.poll() is None for p, _ in procs):
            time.sleep(0.05)
            if tick and time.perf_counter() - last >= every:
                last = time.perf_counter()
                tick(len(counts), len(pending), last - t0)
    except BaseException:  # Ctrl-C: no child goes on compiling behind the user's back
        for p, _ in procs:
            p.kill()
            p.wait()
        raise
    for _, reader in procs:
        reader.join()
    if tick:
        tick(len(counts), len(pending), time.perf_counter() - t0)
    return len(counts)


def _spawn(part: list[Entry], others: list[Entry], counts: list[int]):
    """Start a process compiling ``part`` (waiting for what it needs of ``others``, compiled by
    other processes); a thread appends to ``counts`` per entry it did."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [src_folder(), env.get("PYTHONPATH")]))
    rows = json.dumps({"part": [e.line() for e in part], "others": [e.line() for e in others]})
    cmd = [sys.executable, "-m", "mawdo.jitwarm", "compile", rows]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, env=env, text=True)

    def read() -> None:
        for line in proc.stdout:
            if line.strip() == "done":
                counts.append(1)

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    return proc, reader


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


def _line(done: int, total: int, seconds: float) -> None:
    print(f"compiling kernels: {done}/{total} done after {seconds:.0f} s", flush=True)


def main(argv: list[str] | None = None) -> int:
    """``python -m mawdo.jitwarm [--jobs N] | record -- ARGS | retime | compile ROWS``."""
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["compile"]:  # a child of warm(): compile its rows, say "done" after each
        rows = json.loads(argv[1])
        part, others = ([Entry.from_line(r) for r in rows[k]] for k in ("part", "others"))
        compile_entries(part, done=lambda e: print("done", flush=True), others=others)
        return 0
    if argv[:1] in (["record"], ["retime"]):  # the table's upkeep, a module above this one
        return subprocess.call([sys.executable, "-m", "mawdo.jitrecord", *argv])
    parser = argparse.ArgumentParser(
        prog="python -m mawdo.jitwarm", description=__doc__.split("\n")[0]
    )
    parser.add_argument("--jobs", type=int, default=2, help="processes compiling at once (>= 1)")
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error(f"--jobs must be an integer >= 1, got {args.jobs}")
    t0 = time.perf_counter()
    pending = todo()
    if not pending:
        print("kernels already compiled (Numba's cache is warm)")
        return 0
    cpu = sum(e.seconds for e in pending)
    print(f"compiling {len(pending)} kernels into Numba's cache in {args.jobs} processes "
          f"(once per install; about {cpu:.0f} s of CPU)", flush=True)  # fmt: skip
    n = warm(args.jobs, pending, tick=_line)
    print(f"{n} kernels compiled in {time.perf_counter() - t0:.1f} s", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
