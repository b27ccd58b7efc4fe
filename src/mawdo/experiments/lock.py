"""The exclusive writer lock of a results store: one writing process per store, ever.

A lock file ``STORE.lock`` beside the SQLite file is held with ``fcntl.flock(LOCK_EX)`` for the
writer's whole lifetime. The kernel drops a ``flock`` when its holder exits however it exits
(``kill -9`` included), so a lock left by a dead process is never "held": the next writer takes
it over without any stale-lock heuristics. The file's contents only describe the holder (pid,
host, command, start time) so a refused writer can say who holds the store.

SQLite's own locks are per transaction; they cannot stop a second sweep from deleting
(``--force``) or interleaving rows between the first sweep's transactions, which is what
happened before this lock existed.
"""

from __future__ import annotations

import json
import os
import socket
import sys
from datetime import UTC, datetime
from pathlib import Path

try:  # POSIX; on other platforms the lock degrades to the per-row plan-hash checks
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None


class StoreLockedError(RuntimeError):
    """Another process holds the store's writer lock."""


def lock_path(store: Path) -> Path:
    """The lock file of a store: ``STORE.lock`` in the same folder."""
    return store.with_name(store.name + ".lock")


def _holder_text(fd: int) -> str:
    try:
        os.lseek(fd, 0, os.SEEK_SET)
        raw = os.read(fd, 65536).decode("utf-8", "replace")
        h = json.loads(raw)
        return (
            f"pid {h.get('pid')} on {h.get('host')}, started {h.get('started')}, "
            f"command: {h.get('command')}"
        )
    except (OSError, ValueError):
        return "a process that has not written its details yet"


class WriterLock:
    """Hold ``STORE.lock`` exclusively; :meth:`release` (or process exit) frees it.

    Parameters
    ----------
    store : pathlib.Path
        The results store the lock protects.

    Raises
    ------
    StoreLockedError
        Another live process holds the lock; the message names it (pid, host, command, start).
    """

    def __init__(self, store: Path) -> None:
        self.path = lock_path(Path(store))
        self.fd: int | None = None
        if fcntl is None:  # pragma: no cover
            return
        fd = self._acquire(store)
        self.fd = fd
        info = {
            "pid": os.getpid(),
            "host": socket.gethostname(),
            "command": " ".join(sys.argv) or sys.executable,
            "started": datetime.now(UTC).isoformat(timespec="seconds"),
        }
        os.ftruncate(fd, 0)
        os.pwrite(fd, json.dumps(info).encode(), 0)

    def _acquire(self, store: Path) -> int:
        # The file is removed on release (a closed store stays one file), so a lock taken on
        # a file that was unlinked meanwhile is no lock: check the locked inode is still the
        # one at the path, else try again.
        for _ in range(100):
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                holder = _holder_text(fd)
                os.close(fd)
                raise StoreLockedError(
                    f"results store {store} is being written by another process ({holder}). "
                    f"Two writers would mix or delete each other's runs: wait for it to "
                    f"finish (or stop it), or write to another --out file. The lock is "
                    f"released automatically when that process exits, even if killed."
                ) from None
            except BaseException:
                os.close(fd)
                raise
            try:
                same = os.stat(self.path).st_ino == os.fstat(fd).st_ino
            except FileNotFoundError:
                same = False
            if same:
                return fd
            os.close(fd)
        raise StoreLockedError(f"cannot take the writer lock {self.path}: it keeps changing")

    def release(self) -> None:
        """Free the lock and remove its file (idempotent)."""
        if self.fd is not None:
            try:
                os.unlink(self.path)  # while still held, so nobody locks the dying file
            except OSError:
                pass
            fcntl.flock(self.fd, fcntl.LOCK_UN)
            os.close(self.fd)
            self.fd = None
