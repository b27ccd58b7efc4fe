"""What a command is doing, on stderr, whenever a step can take more than a couple of seconds.

One place for the commands' progress lines (results go to stdout; this goes to stderr):

* :func:`step` - a spinner with the step's name on a terminal, a plain ``"<step> ..."`` line
  otherwise (logs, pipes), then ``"<step>: done in <s> s"``;
* :func:`notice_compiles` - says once that Numba is compiling the kernels (only a first run
  after installing or upgrading compiles; later runs load them from Numba's cache), with the
  time that took when it stopped.

Every line goes through :data:`ERR`, the console the planner's step bar also draws on, so a
line printed while the bar is live appears above it instead of tearing it.
"""

from __future__ import annotations

import time
from contextlib import contextmanager

from rich.console import Console

ERR = Console(stderr=True, soft_wrap=True)  # a log line is never cut in two

#: What :func:`notice_compiles` prints (CPU seconds of a first ``mawdo plan paper``, measured
#: by ``python -m benchmarks startup``; a busy machine takes longer).
COMPILE_MESSAGE = "compiling kernels (first run only, about {s} s of CPU)"
COMPILE_CPU_S = 100


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
    t0 = time.perf_counter()
    if ERR.is_terminal:
        with ERR.status(message):
            yield
    else:
        ERR.print(f"{message} ...", highlight=False)
        yield
    ERR.print(f"{message}: done in {time.perf_counter() - t0:.1f} s", highlight=False)


class _CompileNotice:
    """A Numba compile listener: one line when the first kernel of the process starts compiling,
    one when the last compile ended before the work went on (see :func:`notice_compiles`)."""

    def __init__(self) -> None:
        self.depth = 0
        self.started: float | None = None
        self.compiled = 0.0  # seconds spent compiling so far

    def on_start(self, event) -> None:
        if self.depth == 0:
            if self.started is None:
                ERR.print(COMPILE_MESSAGE.format(s=COMPILE_CPU_S) + " ...", highlight=False)
            self.t0 = time.perf_counter()
            self.started = self.started or self.t0
        self.depth += 1

    def on_end(self, event) -> None:
        self.depth -= 1
        if self.depth == 0:
            self.compiled += time.perf_counter() - self.t0

    def summary(self) -> str | None:
        """``"kernels compiled in <s> s"`` if anything was compiled, else None."""
        if self.started is None:
            return None
        return f"kernels compiled in {self.compiled:.1f} s (cached for later runs)"


@contextmanager
def notice_compiles(enabled: bool = True):
    """Within the ``with`` body, say on stderr when Numba compiles kernels (a first run).

    Numba compiles a kernel on its first call when its on-disk cache misses; a listener on
    Numba's ``numba:compile`` event sees each compile start and end, so the line appears exactly
    when compiling starts, and the summary says how long all of it took.
    """
    if not enabled:
        yield
        return
    from numba.core import event

    notice = _CompileNotice()
    hooks = {"on_start": lambda _, e: notice.on_start(e), "on_end": lambda _, e: notice.on_end(e)}
    listener = type("CompileHook", (event.Listener,), hooks)()
    event.register("numba:compile", listener)
    try:
        yield
    finally:
        event.unregister("numba:compile", listener)
        if notice.summary():
            ERR.print(notice.summary(), highlight=False)
