"""The command layer (top floor): ``mawdo`` and its sub-commands, calling the library only.

``mawdo = "mawdo.cli:program"`` is the console entry point; ``python -m mawdo.cli`` is the same.
"""

from mawdo.cli import quick_exit
from mawdo.cli.main import app

__all__ = ["app", "program"]


def program() -> None:
    """The ``mawdo`` program: the Typer :data:`app`, ended without the interpreter's teardown
    where the command allows it (:mod:`mawdo.cli.quick_exit`)."""
    quick_exit.STATE.program = True
    app(prog_name="mawdo")
