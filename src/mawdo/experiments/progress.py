"""Progress bars on stderr (rich): the sweep's runs with an ETA, and the one shape every bar of
the package shares (:func:`start_bar`, also used by the planner's step bar in the commands);
and :func:`say`, with which a long step (a report drawing hundreds of figures) tells whoever
shows progress what it is doing now, without knowing who that is."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

_LISTENERS: list[Callable[[str], None]] = []


def say(message: str) -> None:
    """Tell the listeners (:func:`listening`) what the running step is doing now, e.g.
    ``"failure gallery: image 12 of 200"``; nothing happens when no one listens."""
    for listener in list(_LISTENERS):
        listener(message)


@contextmanager
def listening(listener: Callable[[str], None]) -> Iterator[None]:
    """Call ``listener(message)`` for every :func:`say` inside the ``with`` body."""
    _LISTENERS.append(listener)
    try:
        yield
    finally:
        _LISTENERS.remove(listener)


#: Seconds a log (stderr not a terminal) may go without a progress line during a long step.
EVERY = 2.0


class Heartbeat:
    """Call ``beat(seconds since start)`` every ``every`` seconds from a daemon thread until
    :meth:`stop`: a log gets a line while a step works, where a terminal has its spinner or
    bar (rich draws nothing on a non-terminal until the end)."""

    def __init__(self, beat: Callable[[float], None], every: float = EVERY) -> None:
        self.beat, self.every = beat, every
        self.t0 = time.perf_counter()
        self.done = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _run(self) -> None:
        while not self.done.wait(self.every):
            self.beat(time.perf_counter() - self.t0)

    def stop(self) -> None:
        self.done.set()
        self.thread.join()


def start_bar(label: str, columns: list, *, total=None, console=None, transient=False, **fields):
    """A started rich progress bar: ``label``, the bar, ``done/total``, then ``columns`` (text
    templates or rich columns); returns ``(progress, task)``.

    Parameters
    ----------
    label : str
        The bar's description.
    columns : list of str or rich column
        What follows the count; a string is a ``TextColumn`` template
        (``"{task.fields[note]}"`` reads a field given in ``fields``).
    total : int or None
        The count to reach (None: unknown yet).
    console : rich Console or None
        Where to draw (default: a new stderr console).
    transient : bool
        Remove the bar when it stops.
    """
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn

    head = [TextColumn("[bold]{task.description}"), BarColumn(), MofNCompleteColumn()]
    tail = [TextColumn(c) if isinstance(c, str) else c for c in columns]
    progress = Progress(*head, *tail, console=console or Console(stderr=True), transient=transient)
    task = progress.add_task(label, total=total, **fields)
    progress.start()
    return progress, task


class RunBar:
    """A progress bar over a sweep's runs with an ETA, on stderr (nothing when disabled); on a
    non-terminal (a log, a pipe) a line ``<label>: done/total runs after <s> s`` every
    :data:`EVERY` seconds instead (rich would draw the bar once, at the end)."""

    def __init__(self, enabled: bool, total: int, label: str) -> None:
        from rich.console import Console

        self.progress: Any = None
        self.heartbeat: Heartbeat | None = None
        if not enabled or total == 0:
            return
        console = Console(stderr=True, soft_wrap=True)
        if not console.is_terminal:
            self.done, self.total, self.label, self.console = 0, total, label, console
            self.heartbeat = Heartbeat(self._line)
            return
        from rich.progress import TimeElapsedColumn, TimeRemainingColumn

        columns = ["runs", TimeElapsedColumn(), "ETA", TimeRemainingColumn(), "{task.fields[note]}"]
        self.progress, self.task = start_bar(label, columns, total=total, note="", console=console)

    def _line(self, seconds: float) -> None:
        self.console.print(
            f"{self.label}: {self.done}/{self.total} runs after {seconds:.0f} s", highlight=False
        )

    def advance(self, n: int, note: str) -> None:
        if self.progress is not None:
            self.progress.update(self.task, advance=n, note=note)
        elif self.heartbeat is not None:
            self.done += n

    def close(self) -> None:
        if self.progress is not None:
            self.progress.stop()
        if self.heartbeat is not None:
            self.heartbeat.stop()
