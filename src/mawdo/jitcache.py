"""Drop Numba's on-disk kernel caches when any source of the package changed.

Numba's ``cache=True`` keys a cached kernel by the modification time and size of the one file
that defines it. Our kernels call (and inline) helpers from other files, so editing a helper, or
upgrading mawdo over an old install, can leave a caller's cache in place that still contains the
old helper: the kernel would silently compute with stale code. This module keeps one stamp, a
SHA-256 of every ``.py`` file of the package, beside the caches; when the stamp differs, every
cached kernel of the package (``*.nbi``, ``*.nbc``) is deleted before any kernel is loaded, so
each is compiled again from the current sources. Cost: hashing the sources once per process
(a few milliseconds).
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent
STAMP = "mawdo-sources.sha256"


def sources_digest(root: Path = PACKAGE) -> str:
    """SHA-256 (hex) of the relative paths and contents of every ``.py`` file under ``root``."""
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        h.update(str(path.relative_to(root)).encode())
        h.update(path.read_bytes())
    return h.hexdigest()


def cache_dirs(root: Path = PACKAGE) -> list[Path]:
    """Folders that may hold Numba caches of modules under ``root``.

    The ``__pycache__`` folders beside the sources, and, when ``NUMBA_CACHE_DIR`` is set, the
    folders Numba mirrors the package's path into under it.
    """
    dirs = [p for p in root.rglob("__pycache__") if p.is_dir()]
    base = os.environ.get("NUMBA_CACHE_DIR")
    if base:
        mirrored = Path(base) / str(root).lstrip(os.sep)
        if mirrored.is_dir():
            dirs += [mirrored, *(p for p in mirrored.rglob("*") if p.is_dir())]
    return dirs


def drop_stale_caches(root: Path = PACKAGE) -> int:
    """Delete every cached kernel under ``root`` if its sources changed since the last stamp.

    Parameters
    ----------
    root : Path
        The package folder (mawdo's own by default).

    Returns
    -------
    int
        Number of cache files deleted (0 when the stamp matched or nothing was cached).
    """
    digest = sources_digest(root)
    stamp_dir = root / "__pycache__"
    stamp = stamp_dir / STAMP
    try:
        if stamp.read_text().strip() == digest:
            return 0
    except OSError:
        pass  # no stamp yet: treat every cache as stale
    removed = 0
    for d in cache_dirs(root):
        for f in (*d.glob("*.nbi"), *d.glob("*.nbc")):
            try:
                f.unlink()
                removed += 1
            except OSError:
                pass  # another process removed it first, or a read-only install
    try:
        stamp_dir.mkdir(exist_ok=True)
        tmp = stamp.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(digest)
        os.replace(tmp, stamp)  # atomic: concurrent workers never read half a stamp
    except OSError:
        pass  # read-only install: Numba then caches elsewhere or not at all
    return removed
