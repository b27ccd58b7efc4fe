"""The command layer's one error edge: expected errors become a message and an exit code.

Errors a user can cause and fix are printed as one plain ``error: ...`` line (a message of
several lines for a plan with several bad fields) on stderr, never a traceback or a rich panel,
whatever the terminal's width; anything else is a bug and keeps its traceback. Exit codes:

* 2: bad input: a flag, name or value, a plan file, a results store that cannot be used as
  given (missing, damaged, of another plan or kind);
* 1: a failure during the work: a file that cannot be written, a task lost, a missing
  optional library, writing into the store failed;
* 130: Ctrl-C.

Output paths are checked with :func:`check_output_file` / :func:`check_output_dir` before any
computing starts.
"""

from __future__ import annotations

import os
import sys
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import NoReturn

import typer
from typer.core import TyperGroup

from mawdo.cli import quick_exit
from mawdo.util.interrupts import INTERRUPT_EXIT, forget_caught_interrupt, is_interrupt

# Typer vendors its own click; its ClickException is what Typer's main loop shows and exits on.
_ClickException = next(c for c in typer.BadParameter.__mro__ if c.__name__ == "ClickException")
_Abort = typer.Abort


class CommandError(_ClickException):
    """An expected error, shown as ``error: <message>`` on stderr; exit code 1."""

    exit_code = 1

    def show(self, file=None) -> None:
        typer.echo(f"error: {self.format_message()}", err=True)


def bad_input(exc_or_msg: BaseException | str, code: int = 2) -> CommandError:
    """A :class:`CommandError` for a bad argument value: exit code 2, as click gives for
    any other bad argument (1 stays for a failure while running: a store, a file ...)."""
    text = exc_or_msg if isinstance(exc_or_msg, str) else message(exc_or_msg)
    err = CommandError(text)
    err.exit_code = code
    return err


def fail(exc_or_msg: BaseException | str, code: int = 2) -> NoReturn:
    """End the command: ``error: <message>`` on stderr and exit ``code`` (2: bad input,
    1: a failure while running)."""
    raise bad_input(exc_or_msg, code)


def exit_code_of(exc: BaseException) -> int | None:
    """The exit code of an expected error: 2 for bad input (a ``ValueError``, ``KeyError`` or
    a store that cannot be used as given), 1 for a failure during the work (an ``OSError``,
    writing into a store failed); None for anything else (a bug: its traceback is kept)."""
    # imported here: `mawdo list` should not pay for the experiments package
    from mawdo.experiments.sqlitefile import StoreError, StoreWriteError

    if isinstance(exc, OSError | StoreWriteError):
        return 1
    if isinstance(exc, ValueError | KeyError | StoreError):
        return 2
    return None


def message(exc: BaseException) -> str:
    """The text of an expected error (a KeyError's message without its quotes)."""
    if isinstance(exc, KeyError) and exc.args and isinstance(exc.args[0], str):
        return str(exc) if type(exc).__str__ is not KeyError.__str__ else exc.args[0]
    if isinstance(exc, OSError) and exc.filename is not None and exc.strerror:
        return f"{exc.filename}: {exc.strerror}"
    return str(exc) or type(exc).__name__


class Interrupted(_ClickException):
    """Ctrl-C: one line on stderr, exit code 130 (what a shell reports for SIGINT)."""

    exit_code = INTERRUPT_EXIT

    def show(self, file=None) -> None:
        typer.echo(f"interrupted: {self.format_message()}", err=True)


def show_error(exc) -> None:
    """Print a click error as ``error: <message>`` on stderr (never a rich box), with the
    usage line of a mistyped command after it."""
    if type(exc).__name__ == "NoArgsIsHelpError" or isinstance(exc, CommandError | Interrupted):
        exc.show()
        return
    typer.echo(f"error: {exc.format_message()}", err=True)
    ctx = getattr(exc, "ctx", None)
    if ctx is not None:
        typer.echo(f"{ctx.get_usage()}\nTry '{ctx.command_path} --help' for help.", err=True)


class GuardedGroup(TyperGroup):
    """A Typer group whose commands (sub-groups included) end in :class:`CommandError` on an
    expected error, and in :class:`Interrupted` on Ctrl-C; every error, click's own bad
    parameters included, is shown by :func:`show_error`."""

    def main(self, *args, standalone_mode: bool = True, **extra):
        if not standalone_mode:
            return super().main(*args, standalone_mode=False, **extra)
        try:
            code = super().main(*args, standalone_mode=False, **extra)
        except _ClickException as exc:
            show_error(exc)
            forget_caught_interrupt()  # every Ctrl-C that gets here was handled
            sys.exit(exc.exit_code)
        except _Abort:
            typer.echo("Aborted!", err=True)
            sys.exit(1)
        # non-standalone click returns an Exit's code, or the command's return value
        code = code if isinstance(code, int) else 0
        forget_caught_interrupt()
        quick_exit.end(code)  # (returns unless the program runs and the command allowed it)
        sys.exit(code)

    def invoke(self, ctx):
        try:
            return super().invoke(ctx)
        except _ClickException:
            raise
        except BaseException as exc:
            # also the SystemError that compiled code (Numba) makes of a Ctrl-C
            if is_interrupt(exc):
                raise Interrupted(interrupt_message()) from None
            code = exit_code_of(exc) if isinstance(exc, Exception) else None
            if code is not None:
                raise bad_input(exc, code) from None
            raise


_CTRL_C = {"note": ""}


def on_ctrl_c(note: str) -> None:
    """Say what a Ctrl-C during the running command leaves behind: the words after
    ``stopped by Ctrl-C; `` in its message (each command its own, true for it)."""
    _CTRL_C["note"] = note


def interrupt_message() -> str:
    """The Ctrl-C message of the running command (:func:`on_ctrl_c`)."""
    note = _CTRL_C["note"]
    return f"stopped by Ctrl-C; {note}" if note else "stopped by Ctrl-C"


STUDY_CTRL_C = "the runs finished before it are stored: run the same command again to resume"
"""What a Ctrl-C leaves of a study command (the runner stores each finished task)."""

REPORT_CTRL_C = (
    "the report was not finished (its folder may hold some of its files); the store is "
    "unchanged: run the same command again to write the report"
)
"""What a Ctrl-C leaves of a report command."""


class DefaultRunGroup(GuardedGroup):
    """A group whose first argument, when it names no command, is read as ``run``'s:
    ``mawdo plan paper`` means ``mawdo plan run paper``."""

    def parse_args(self, ctx, args):
        if args and args[0] not in self.commands and args[0] not in ("--help", "-h"):
            args = ["run", *args]
        return super().parse_args(ctx, args)


IMAGE_SUFFIXES = (".png", ".svg", ".pdf")

# shared by every study command
RETRY_HELP = (
    "compute again the stored runs that failed with an error (not those that ran and did not "
    "succeed)"
)
SCHEDULER_FILE_HELP = (
    "Dask scheduler file (dask scheduler --scheduler-file FILE), instead of an address"
)


@contextmanager
def writing_into(folder: Path, what: str = "report"):
    """Name ``folder`` in an ``OSError`` raised while writing into it without a file name
    (a full disk's ``[Errno 28]`` from ``write()`` or ``close()`` names no path)."""
    try:
        yield
    except OSError as exc:
        if exc.filename is not None:
            raise
        why = exc.strerror or str(exc) or type(exc).__name__
        code = f" (errno {exc.errno})" if exc.errno else ""
        raise OSError(
            f"cannot write the {what} into {folder}: {why}{code}; free some space or choose "
            "another --out folder"
        ) from None


class BadOutputPath(ValueError):
    """An output path given that cannot be written (checked before any work: bad input)."""


def check_output_dir(path: Path, what: str = "output folder") -> Path:
    """Make ``path`` (a directory) now, and make sure files can be written into it; else a
    :class:`BadOutputPath` (a bad argument: exit 2, as every input error)."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise BadOutputPath(f"{what} {path} is a file; give a folder")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise BadOutputPath(f"cannot create {what} ({path}): {exc.strerror or exc}") from None
    if not os.access(path, os.W_OK | os.X_OK):
        raise BadOutputPath(f"{what} ({path}) is not writable; choose another one")
    try:
        # os.access says yes to root everywhere, and knows nothing of read-only mounts
        with tempfile.TemporaryFile(dir=path):
            pass
    except OSError as exc:
        raise BadOutputPath(
            f"{what} ({path}) is not writable ({exc.strerror or exc}); choose another one"
        ) from None
    return path


def check_output_file(path: Path, suffixes: tuple[str, ...] | None = None, what="output") -> Path:
    """Check an output file before computing: its suffix, and a writable parent folder."""
    path = Path(path)
    if suffixes is not None and path.suffix.lower() not in suffixes:
        raise ValueError(
            f"{what} {path} must end in one of {', '.join(suffixes)} (got {path.suffix or 'none'})"
        )
    if path.is_dir():
        raise ValueError(f"{what} {path} is a folder; give a file name")
    check_output_dir(path.parent, what=f"the folder of {what} {path}")
    if path.exists() and not os.access(path, os.W_OK):
        raise BadOutputPath(f"{what} {path} is not writable")
    return path
