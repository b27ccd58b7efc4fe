"""The sweep's progress bar: runs done of the runs to compute, with an ETA (rich, stderr)."""

from __future__ import annotations


class RunBar:
    """A progress bar over a sweep's runs with an ETA, on stderr (nothing when disabled)."""

    def __init__(self, enabled: bool, total: int, label: str) -> None:
        self.progress = None
        if not enabled or total == 0:
            return
        from rich.console import Console
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )

        self.progress = Progress(
            TextColumn("[bold]{task.description}"),
            BarColumn(),
            MofNCompleteColumn(),
            TextColumn("runs"),
            TimeElapsedColumn(),
            TextColumn("ETA"),
            TimeRemainingColumn(),
            TextColumn("{task.fields[note]}"),
            console=Console(stderr=True),
        )
        self.task = self.progress.add_task(label, total=total, note="")
        self.progress.start()

    def advance(self, n: int, note: str) -> None:
        if self.progress is not None:
            self.progress.update(self.task, advance=n, note=note)

    def close(self) -> None:
        if self.progress is not None:
            self.progress.stop()
