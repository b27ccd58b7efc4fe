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


def interruptible(cmd: list[str], env=None) -> subprocess.Popen:
    """Start ``cmd`` (text pipes) in its own process group with SIGINT restored, so that
    SIGINT to the group is what a terminal's Ctrl-C is: a background job of a non-interactive
    shell (CI, ``make test &``) starts its children with SIGINT ignored, which tests nothing."""
    import signal

    def child() -> None:
        signal.signal(signal.SIGINT, signal.SIG_DFL)

    return subprocess.Popen(
        cmd,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=ENV if env is None else env,
        start_new_session=True,
        preexec_fn=child,
    )
