"""The command layer (top floor): ``mawdo`` and its sub-commands, calling the library only.

``mawdo = "mawdo.cli:app"`` is the console entry point; ``python -m mawdo.cli`` is the same.
"""

from mawdo.cli.main import app

__all__ = ["app"]
