"""A damaged entry in Numba's cache is dropped and compiled again, with one line saying so.

Numba reads its cache with ``pickle``: an index file (``.nbi``) or a data file (``.nbc``) that
was truncated, emptied or overwritten makes the read raise (``UnpicklingError``, ``EOFError``:
under Typer an ``EOFError`` even reads as "Aborted!"), and the kernel fails to load in every
process after that, for good. :func:`install` wraps the three reads of
``numba.core.caching`` (the index, a data file, the rebuild of the code from it) so that a read
that fails for any reason but a missing file or Ctrl-C drops the function's index and data
files, prints ``warning: ...`` on stderr, and lets Numba compile the kernel as on a cold cache
(it saves the fresh entry). The wrapping is installed when Numba's caching module is imported
(an import hook: ``import mawdo`` does not import Numba), and does nothing where Numba's
internals are not the expected ones.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

from mawdo.jit.cache import AfterExec
from mawdo.util.interrupts import is_interrupt

__all__ = ["CACHING", "HealHook", "drop_entry", "install", "patch"]

#: The Numba module that reads and writes its on-disk cache.
CACHING = "numba.core.caching"


def drop_entry(cache_file, exc: BaseException) -> None:
    """Remove the index file of ``cache_file`` (a ``numba.core.caching.IndexDataCacheFile``)
    and its data files, and say so once on stderr."""
    index = Path(cache_file._index_path)
    stem = index.name[: -len(".nbi")]
    dropped = [p for p in (index, *index.parent.glob(f"{stem}.*.nbc")) if p.exists()]
    for p in dropped:
        try:
            p.unlink()
        except OSError:  # read-only or gone: Numba then compiles in memory, as for any miss
            pass
    why = f"{type(exc).__name__}: {exc}" if str(exc) else type(exc).__name__
    print(
        f"warning: Numba's cache entry {stem} was damaged ({why}); dropped "
        f"{len(dropped)} file(s), compiling it again",
        file=sys.stderr,
        flush=True,
    )


def patch(caching) -> bool:
    """Wrap ``caching``'s cache reads (see the module docstring); True if they are wrapped now
    or were already, False if Numba's internals are not the expected ones (nothing changed)."""
    files, cache = getattr(caching, "IndexDataCacheFile", None), getattr(caching, "Cache", None)
    names = ((files, "_load_index"), (files, "_load_data"), (cache, "_load_overload"))
    if any(owner is None or not callable(getattr(owner, n, None)) for owner, n in names):
        return False
    if getattr(files._load_index, "_mawdo_heals", False):
        return True
    load_index, load_data, load_overload = (getattr(o, n) for o, n in names)

    def _load_index(self):
        try:
            return load_index(self)
        except Exception as exc:  # (a missing index is {} inside)
            if is_interrupt(exc):
                raise
            drop_entry(self, exc)
            return {}

    def _load_data(self, name):
        try:
            return load_data(self, name)
        except OSError:  # a missing file: Numba's load() returns None, as it always did
            raise
        except Exception as exc:
            if is_interrupt(exc):
                raise
            drop_entry(self, exc)
            raise OSError(f"damaged cache file {name}") from exc

    def _load_overload(self, sig, target_context):
        try:
            return load_overload(self, sig, target_context)
        except Exception as exc:  # the code did not rebuild from a data file that unpickled
            if is_interrupt(exc):
                raise
            drop_entry(self._cache_file, exc)
            return None

    for f in (_load_index, _load_data, _load_overload):
        f._mawdo_heals = True
    files._load_index, files._load_data, cache._load_overload = (
        _load_index,
        _load_data,
        _load_overload,
    )
    return True


class HealHook:
    """Import hook (``sys.meta_path``): :func:`patch` ``numba.core.caching`` right after it is
    imported; it finds no module itself."""

    def find_spec(self, name, path=None, target=None):
        if name != CACHING:
            return None
        sys.meta_path.remove(self)  # once; the next finders find the module
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.loader is not None:
            spec.loader = AfterExec(spec.loader, patch)
        return spec


def install() -> None:
    """Wrap Numba's cache reads now if its caching module is imported, else when it is."""
    if CACHING in sys.modules:
        patch(sys.modules[CACHING])
    elif not any(isinstance(f, HealHook) for f in sys.meta_path):
        sys.meta_path.insert(0, HealHook())
