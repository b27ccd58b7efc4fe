"""What a command is doing, on stderr, whenever a step can take more than a couple of seconds.

One place for the commands' progress lines (results go to stdout; this goes to stderr):

* :func:`step` - a spinner with the step's name on a terminal, a plain ``"<step> ..."`` line
  otherwise (logs, pipes), then ``"<step>: done in <s> s"``; what the step says it is doing
  (:func:`mawdo.experiments.progress.say`) follows the name on the spinner, or in a log a line
  ``"<step>: <what>"`` at most every 2 s;
* :func:`notice_compiles` - at the first compile on a cold Numba cache, compiles the kernels of
  :mod:`mawdo.jit.warm`'s table in two processes at once (a line every 2 s), then says when
  Numba compiles anything else, with a line every 2 s while it does and the time it took
  (only a first run after installing or upgrading compiles; later runs load from the cache).

Every line goes through :data:`ERR`, the console the planner's step bar also draws on, so a
line printed while the bar is live appears above it instead of tearing it.
"""

from __future__ import annotations

import os
import threading
import time
from contextlib import contextmanager

from rich.console import Console

ERR = Console(stderr=True, soft_wrap=True)  # a log line is never cut in two

#: What :func:`notice_compiles` prints when Numba compiles in this process.
COMPILE_MESSAGE = "compiling kernels (first run only)"
#: Seconds between two progress lines of a long step.
EVERY = 2.0


@contextmanager
def step(message: str, enabled: bool = True):
    """Show ``message`` on stderr while the ``with`` body runs, then how long it took.

    Parameters
    ----------
    message : str
        What the step does, e.g. ``"writing the GIF (123 frames)"``.
    enabled : bool
        False: print nothing (``--no-progress``).
    """
    if not enabled:
        yield
        return
    from mawdo.experiments.progress import Heartbeat, listening

    t0 = time.perf_counter()
    if ERR.is_terminal:
        with ERR.status(message) as status:
            with listening(lambda sub: status.update(f"{message}: {sub}")):
                yield
    else:
        ERR.print(f"{message} ...", highlight=False)
        log = _Log(message)
        beat = Heartbeat(log.beat, EVERY / 2)
        try:
            with listening(log.listener):
                yield
        finally:
            beat.stop()
    ERR.print(f"{message}: done in {time.perf_counter() - t0:.1f} s", highlight=False)


class _Log:
    """A long step's lines in a log: ``"<step>: <what now>"`` at most once per :data:`EVERY`
    seconds (not one per figure), and ``"<step>: <what last> (<s> s)"`` when nothing was said
    for :data:`EVERY` seconds (a phase that says nothing is not silent)."""

    def __init__(self, message: str) -> None:
        self.message, self.sub = message, ""
        self.t0 = self.last = time.perf_counter()

    def listener(self, sub: str) -> None:
        self.sub = sub
        now = time.perf_counter()
        if now - self.last >= EVERY:
            self.last = now
            ERR.print(f"{self.message}: {sub}", highlight=False)

    def beat(self, _seconds: float) -> None:
        now = time.perf_counter()
        if now - self.last >= EVERY:
            self.last = now
            what = f"{self.sub}, " if self.sub else ""
            ERR.print(f"{self.message}: {what}{now - self.t0:.0f} s", highlight=False)


def jit_jobs() -> int:
    """Processes that fill a cold kernel cache at once: ``MAWDO_JIT_JOBS`` if set (1: compile
    in the command's own process, as it needs them), else 2 where there are 2 cores or more."""
    value = os.environ.get("MAWDO_JIT_JOBS", "")
    if value.strip().isdigit():
        return max(1, int(value))
    return min(2, os.cpu_count() or 1)


def warm_kernels(enabled: bool = True) -> int:
    """Compile the missing kernels of :mod:`mawdo.jit.warm`'s table in :func:`jit_jobs`
    processes at once, saying so on stderr with a line every :data:`EVERY` seconds.

    Returns
    -------
    int
        Number of kernels compiled (0 on a warm cache, or with one job).
    """
    from mawdo.jit import warm as jitwarm

    jobs = jit_jobs()
    todo = jitwarm.todo() if jobs > 1 else []
    if not todo:
        return 0
    cpu = sum(e.seconds for e in todo)
    say = ERR.print if enabled else (lambda *a, **k: None)
    say(
        f"compiling kernels (first run only: about {cpu:.0f} s of CPU, in {jobs} processes) ...",
        highlight=False,
    )

    def tick(done: int, total: int, seconds: float) -> None:
        say(f"compiling kernels: {done}/{total} after {seconds:.0f} s", highlight=False)

    t0 = time.perf_counter()
    n = jitwarm.warm(jobs, todo, tick=tick, every=EVERY)
    say(f"kernels compiled in {time.perf_counter() - t0:.1f} s (cached for later runs)")
    return n


class _CompileNotice:
    """A Numba compile listener. At the first compile of the ``with`` body: the parallel warm-up
    of the missing kernels (if ``warm``), after which that first kernel loads from the cache
    the warm-up filled (:func:`mawdo.jit.warm.load_instead`) instead of compiling here again;
    then, if ``enabled``, one line when compiling in this process starts, a line every
    :data:`EVERY` seconds while it goes on, the total when asked."""

    def __init__(self, enabled: bool = True, warm: bool = True) -> None:
        self.enabled, self.warm = enabled, warm
        self.depth = 0
        self.warmed = False  # the warm-up ran (at the first compile)
        self.loading = False  # the compile under way is the first one, loaded instead
        self.started: float | None = None
        self.compiled = 0.0  # seconds spent compiling so far
        self.stop = threading.Event()

    def on_start(self, event) -> None:
        if self.depth == 0:
            if not self.warmed:
                self.warmed = True
                # the kernel whose compile starts now loads from the cache the warm-up fills
                self.loading = self.warm and self._warm_then_load(event.data)
            if not self.loading and self.started is None:
                self._announce()
            self.t0 = time.perf_counter()
            self.started = self.started or (None if self.loading else self.t0)
        self.depth += 1

    def _warm_then_load(self, data) -> bool:
        from mawdo.jit import warm as jitwarm

        return warm_kernels(self.enabled) > 0 and jitwarm.load_instead(
            data["dispatcher"], data["args"]
        )

    def _announce(self) -> None:
        if self.enabled:
            ERR.print(COMPILE_MESSAGE + " ...", highlight=False)
            threading.Thread(target=self._tick, daemon=True).start()

    def on_end(self, event) -> None:
        self.depth -= 1
        if self.depth == 0:
            if not self.loading:
                self.compiled += time.perf_counter() - self.t0
            self.loading = False

    def _tick(self) -> None:
        while not self.stop.wait(EVERY):
            if self.depth > 0:
                spent = self.compiled + time.perf_counter() - self.t0
                ERR.print(f"compiling kernels: {spent:.0f} s", highlight=False)

    def summary(self) -> str | None:
        """``"kernels compiled in <s> s"`` if anything was compiled, else None."""
        if self.started is None or not self.enabled:
            return None
        return f"kernels compiled in {self.compiled:.1f} s (cached for later runs)"


@contextmanager
def notice_compiles(enabled: bool = True, warm: bool = True):
    """Within the ``with`` body, say on stderr when Numba compiles kernels (a first run).

    Numba compiles a kernel on its first call when its on-disk cache misses; a listener on
    Numba's ``numba:compile`` event sees each compile start and end. At the first one, the
    missing kernels of :mod:`mawdo.jit.warm`'s table are compiled in parallel processes
    (:func:`warm_kernels`, also with ``enabled`` False: it is faster either way; not with
    ``warm=False``), so nothing is compiled before a command has checked its input. Then a line
    says that compiling goes on in this process, a line follows every :data:`EVERY` seconds
    while it does, and the summary says how long all of it took.
    """
    if not (enabled or warm):
        yield
        return
    from numba.core import event

    from mawdo.jit.inline import fresh_ir_inlining

    notice = _CompileNotice(enabled, warm)
    hooks = {"on_start": lambda _, e: notice.on_start(e), "on_end": lambda _, e: notice.on_end(e)}
    listener = type("CompileHook", (event.Listener,), hooks)()
    event.register("numba:compile", listener)
    try:
        with fresh_ir_inlining():  # what this process compiles, as jitwarm's processes do
            yield
    finally:
        event.unregister("numba:compile", listener)
        notice.stop.set()
        if notice.summary():
            ERR.print(notice.summary(), highlight=False)
