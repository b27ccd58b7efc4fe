"""``mawdo plan run ... --record run.mcap``: the run recorded for Foxglove
(:func:`mawdo.planning.render.record.record_mcap`)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import typer

RECORD = typer.Option(
    None, "--record", help="also write the run to this MCAP file (open it in Foxglove)"
)


def check_record(path: Path | None) -> None:
    """Before the run: a ``.mcap`` file in a writable folder (``ValueError``), and the mcap
    library (exit 1 without it)."""
    if path is None:
        return
    from mawdo.cli.errors import check_output_file, fail

    check_output_file(path, (".mcap",), "--record file")
    if importlib.util.find_spec("mcap") is None:
        fail("--record needs the mcap library: pip install 'mawdo[record]'", code=1)


def write_record(result, path: Path | None, console) -> None:
    """After the run: write its recording to ``path`` (nothing when None) and say where."""
    if path is not None:
        from mawdo.planning.render.record import record_mcap

        console.print(f"recording: {record_mcap(result, path)}")
