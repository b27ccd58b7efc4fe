"""The one way tests run the real command line: ``python -m mawdo.cli`` in a subprocess."""

from __future__ import annotations

import os
import subprocess
import sys

ENV = {**os.environ, "MPLBACKEND": "Agg", "COLUMNS": "200"}


def mawdo(*args: str, cwd=None, env=None, timeout: float = 600) -> subprocess.CompletedProcess:
    """Run ``mawdo ARGS`` (text output captured); ``env`` entries go over :data:`ENV`."""
    return subprocess.run(
        [sys.executable, "-m", "mawdo.cli", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        env={**ENV, **(env or {})},
        cwd=cwd,
    )
