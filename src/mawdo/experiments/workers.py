"""Local pool workers: leave Ctrl-C to the sweep's process, and die with it.

The runner's process pool starts each worker with :func:`worker_init`.
"""

from __future__ import annotations

import os
import signal
import sys
import threading
import time


def worker_init(parent: int) -> None:
    """Initializer of each pool worker: ignore Ctrl-C, and die with the sweep's process."""
    # Only the parent handles Ctrl-C: it stops the pool and keeps what finished. A terminal's
    # Ctrl-C reaches the whole process group, and a worker dying of it mid-task would break
    # the pool before the parent can shut it down in order.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _die_with(parent)


def _die_with(parent: int, poll: float = 0.5) -> None:
    """Make this worker exit when ``parent`` (the sweep's process) dies, even by ``kill -9``.

    A killed parent cannot stop its pool, and a worker busy in a task would otherwise compute
    on for minutes. Two lines of defence: on Linux
    ``prctl(PR_SET_PDEATHSIG, SIGKILL)`` (the worker's parent is the forkserver, which exits
    when the sweep's process dies), and everywhere a daemon thread that polls whether
    ``parent`` is still this worker's ancestor and alive.
    """
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, signal.SIGKILL, 0, 0, 0)  # 1 = PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass
    direct = os.getppid()

    def watch() -> None:
        while True:
            time.sleep(poll)
            if os.getppid() != direct or not _alive(parent):
                os._exit(70)  # no cleanup: the parent that would read our results is gone

    threading.Thread(target=watch, name="mawdo-parent-watch", daemon=True).start()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
