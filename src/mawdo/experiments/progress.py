"""Progress bars on stderr (rich): the sweep's runs with an ETA, and the one shape every bar of
the package shares (:func:`start_bar`, also used by the planner's step bar in the commands);
and :func:`say`, with which a long step (a report drawing hundreds of figures) tells whoever
shows progress what it is doing now, without knowing who that is."""

from __future__ import annotations

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
    """A progress bar over a sweep's runs with an ETA, on stderr (nothing when disabled)."""

    def __init__(self, enabled: bool, total: int, label: str) -> None:
        self.progress: Any = None
        if not enabled or total == 0:
            return
        from rich.progress import TimeElapsedColumn, TimeRemainingColumn

        columns = ["runs", TimeElapsedColumn(), "ETA", TimeRemainingColumn(), "{task.fields[note]}"]
        self.progress, self.task = start_bar(label, columns, total=total, note="")

    def advance(self, n: int, note: str) -> None:
        if self.progress is not None:
            self.progress.update(self.task, advance=n, note=note)

    def close(self) -> None:
        if self.progress is not None:
            self.progress.stop()
