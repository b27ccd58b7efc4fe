"""The one way tests run the real command line: ``python -m mawdo.cli`` in a subprocess."""

from __future__ import annotations

import os
import subprocess
import sys

ENV = {**os.environ, "MPLBACKEND": "Agg"}


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


def group_gone(pgid: int, within: float = 10.0) -> bool:
    """Whether every process of the group ``pgid`` has ended within ``within`` seconds."""
    import time

    end = time.monotonic() + within
    while time.monotonic() < end:
        try:
            os.killpg(pgid, 0)
        except ProcessLookupError:
            return True
        time.sleep(0.1)
    return False


def children(pid: int) -> list[int]:
    """The process ids of ``pid``'s children (Linux ``/proc``; none elsewhere)."""
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            return [int(p) for p in f.read().split()]
    except OSError:
        return []


def ctrl_c(proc: subprocess.Popen) -> str:
    """Send SIGINT to ``proc``'s group (a terminal's Ctrl-C; ``proc`` from
    :func:`interruptible`) and check what a user must see: exit 130, no traceback, and no
    process of the command left. Returns its stderr."""
    import signal

    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "Traceback" not in err
    assert group_gone(proc.pid), "a process of the command outlived Ctrl-C"
    return err
