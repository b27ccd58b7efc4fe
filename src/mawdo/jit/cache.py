"""Drop Numba's on-disk kernel caches when a source the kernels depend on changed.

Numba's ``cache=True`` keys a cached kernel by the modification time and size of the one file
that defines it. Our kernels call (and inline) helpers from other files, so editing a helper, or
upgrading mawdo over an old install, can leave a caller's cache in place that still contains the
old helper: the kernel would silently compute with stale code. This module keeps one stamp, a
SHA-256 of the kernels' sources, beside the caches; when the stamp differs, every cached kernel
of the package (``*.nbi``, ``*.nbc``) is deleted before any kernel is loaded, so each is compiled
again from the current sources. Cost: a ``stat`` of each source file per process (about a
millisecond); the sources are read and parsed only when one of them changed (a few hundred ms).

The kernels' sources (:func:`kernel_sources`) are every module that uses Numba and every module
of the package those import, directly or not: all a compiled function can call, inline or
capture as a global constant. Editing any other module (the commands, figures, study harness)
keeps the caches, which spares the minute or two a full compile takes.
"""

from __future__ import annotations

import ast
import hashlib
import importlib.machinery
import importlib.util
import os
import sys
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent  # the mawdo package
STAMP = "mawdo-sources.sha256"
#: The files' sizes and times when the stamp was last checked, with the stamp: while they are
#: unchanged, a process skips reading the sources.
STAT_STAMP = "mawdo-sources.stat"


def _imported_files(path: Path, root: Path) -> set[Path]:
    """Files under ``root`` (the package ``root.name``) that the module at ``path`` imports."""
    pkg = root.name
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_bytes())):
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            names.add(node.module)
            names.update(f"{node.module}.{a.name}" for a in node.names)  # submodules
    found = set()
    for name in names:
        parts = name.split(".")
        if parts[0] != pkg:
            continue
        for k in range(2, len(parts) + 1):  # a module also runs its packages' __init__
            base = root.joinpath(*parts[1:k])
            for f in (base.with_suffix(".py"), base / "__init__.py"):
                if f.is_file():
                    found.add(f)
    return found


def _defines_kernels(path: Path) -> bool:
    text = path.read_bytes()
    if b"numba" not in text:
        return False
    for node in ast.parse(text).body:
        if isinstance(node, ast.Import) and any(
            a.name.split(".")[0] == "numba" for a in node.names
        ):
            return True
        if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "numba":
            return True
    return False


def kernel_modules(root: Path = PACKAGE) -> list[Path]:
    """The ``.py`` files under ``root`` that import Numba at their top level (where kernels are
    defined), sorted."""
    return sorted(p for p in root.rglob("*.py") if _defines_kernels(p))


def _closure(starts: list[Path], root: Path, graph: dict[Path, set[Path]]) -> set[Path]:
    """``starts`` and every module of the package they import, transitively (``graph`` caches
    each file's imports)."""
    todo, seen = list(starts), set()
    while todo:
        path = todo.pop()
        if path not in seen:
            seen.add(path)
            if path not in graph:
                graph[path] = _imported_files(path, root)
            todo.extend(graph[path] - seen)
    return seen


def kernel_sources(root: Path = PACKAGE) -> list[Path]:
    """The ``.py`` files under ``root`` a compiled kernel can depend on, sorted.

    Those that import Numba at their top level (where kernels are defined), and every module
    of the package they import, transitively.
    """
    return sorted(_closure(kernel_modules(root), root, {}))


def module_digests(root: Path = PACKAGE) -> dict[str, str]:
    """Per module defining kernels (path relative to ``root``), a SHA-256 (hex) of the paths and
    contents of the module and of every module of the package it imports, transitively: all
    that its compiled kernels can contain."""
    graph: dict[Path, set[Path]] = {}
    out = {}
    for module in kernel_modules(root):
        h = hashlib.sha256()
        for path in sorted(_closure([module], root, graph)):
            h.update(str(path.relative_to(root)).encode())
            h.update(path.read_bytes())
        out[str(module.relative_to(root))] = h.hexdigest()
    return out


def sources_digest(root: Path = PACKAGE) -> str:
    """The stamp's text: one line ``<module> <digest>`` per :func:`module_digests` entry."""
    return "\n".join(f"{m} {d}" for m, d in sorted(module_digests(root).items()))


def cache_dirs(root: Path = PACKAGE) -> list[Path]:
    """Folders that may hold Numba caches of modules under ``root``.

    The ``__pycache__`` folders beside the sources, and, when ``NUMBA_CACHE_DIR`` is set, the
    folders Numba keeps there for each source folder: ``<folder name>_<SHA-1 of its absolute
    path>`` (Numba >= 0.57, :func:`numba_cache_folder`), or the source path mirrored under it
    (older Numba).
    """
    dirs = [p for p in root.rglob("__pycache__") if p.is_dir()]
    base = os.environ.get("NUMBA_CACHE_DIR")
    if base:
        mirrored = Path(base) / str(root).lstrip(os.sep)
        if mirrored.is_dir():
            dirs += [mirrored, *(p for p in mirrored.rglob("*") if p.is_dir())]
        folders = [root, *(p for p in root.rglob("*") if p.is_dir() and p.name != "__pycache__")]
        dirs += [d for d in (numba_cache_folder(f, Path(base)) for f in folders) if d.is_dir()]
    return dirs


def numba_cache_folder(source_dir: Path, base: Path) -> Path:
    """Where Numba caches the kernels of the modules in ``source_dir`` when ``NUMBA_CACHE_DIR``
    is ``base`` (Numba's ``_CacheLocator.get_suitable_cache_subpath``)."""
    path = os.path.abspath(source_dir)
    return base / f"{os.path.basename(path)}_{hashlib.sha1(path.encode()).hexdigest()}"


def drop_stale_caches(root: Path = PACKAGE) -> int:
    """Delete every cached kernel under ``root`` if the kernels' sources changed since the last
    stamp.

    Parameters
    ----------
    root : Path
        The package folder (mawdo's own by default).

    Returns
    -------
    int
        Number of cache files deleted (0 when the stamp matched or nothing was cached).
    """
    stamp_dir = root / "__pycache__"
    stamp = stamp_dir / STAMP
    try:
        stamped = stamp.read_text().strip()
    except OSError:
        stamped = None  # no stamp yet: treat every cache as stale
    # fast path: no source file changed (path, size, mtime) since the stamp was checked
    files = _stat_signature(root)
    if stamped and _read(stamp_dir / STAT_STAMP) == f"{files} {_sha(stamped)}":
        return 0
    digest = sources_digest(root)
    removed = 0
    if stamped != digest:
        old = _parse_stamp(stamped)
        new = _parse_stamp(digest) or {}
        changed = None if old is None else {m for m in old.keys() | new if old.get(m) != new.get(m)}
        removed = _drop(root, changed)
        _write(stamp, digest)
    _write(stamp_dir / STAT_STAMP, f"{files} {_sha(digest)}")
    return removed


def _parse_stamp(text: str | None) -> dict[str, str] | None:
    """The ``{module: digest}`` of a stamp; None if absent or from an older mawdo (one digest)."""
    rows = [line.split(" ") for line in (text or "").splitlines()]
    if not rows or any(len(r) != 2 or not r[0].endswith(".py") for r in rows):
        return None
    return dict(rows)


def _drop(root: Path, modules: set[str] | None) -> int:
    """Delete the cached kernels of ``modules`` (paths relative to ``root``; None: of every
    module). Numba names a module's cache files ``<module name>.<function>-<line>...`` in the
    cache folder of the module's folder."""
    wanted = None if modules is None else {_cache_prefixes(root / m) for m in modules}
    wanted = None if wanted is None else {pair for pairs in wanted for pair in pairs}
    removed = 0
    for d in cache_dirs(root):
        for f in (*d.glob("*.nbi"), *d.glob("*.nbc")):
            if wanted is not None and (d, f.name.split(".")[0]) not in wanted:
                continue
            try:
                f.unlink()
                removed += 1
            except OSError:
                pass  # another process removed it first, or a read-only install
    return removed


def _cache_prefixes(module: Path) -> frozenset[tuple[Path, str]]:
    """(cache folder, file name prefix) pairs of the Numba caches of ``module``'s kernels."""
    folders = [module.parent / "__pycache__"]
    base = os.environ.get("NUMBA_CACHE_DIR")
    if base:
        folders += [numba_cache_folder(module.parent, Path(base))]
        folders += [Path(base) / str(module.parent).lstrip(os.sep)]
    return frozenset((f, module.stem) for f in folders)


def _sha(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()


def _stat_signature(root: Path) -> str:
    """SHA-256 of every ``.py`` file's relative path, size and modification time."""
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        st = path.stat()
        h.update(f"{path.relative_to(root)} {st.st_size} {st.st_mtime_ns}\n".encode())
    return h.hexdigest()


def _read(path: Path) -> str | None:
    try:
        return path.read_text().strip()
    except OSError:
        return None


def _write(path: Path, text: str) -> None:
    try:
        path.parent.mkdir(exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(text)
        os.replace(tmp, path)  # atomic: concurrent workers never read half a stamp
    except OSError:
        pass  # read-only install: Numba then caches elsewhere or not at all


#: scipy's BLAS wrappers, which Numba imports when its first kernel loads (:func:`preload_blas`).
BLAS = "scipy.linalg.cython_blas"
#: The Numba module whose import checks for BLAS (``numba.np.arraymath._HAVE_BLAS``).
BLAS_CHECK = "numba.np.arraymath"


def preload_blas() -> bool:
    """Load ``scipy.linalg.cython_blas`` from its file, without the rest of ``scipy.linalg``.

    Numba's ``numba.np.arraymath``, imported when the first kernel loads (from the cache too),
    checks that BLAS is there by importing ``scipy.linalg.cython_blas``; Python runs the
    package ``scipy.linalg`` first, all of it (decompositions, ``scipy._lib``'s array API
    layer): 0.25-0.3 s of CPU, a sixth of ``mawdo plan``'s start-up, for kernels of which none
    uses linear algebra. The extension module needs none of that: loaded by its file it is the
    module the import would give (compiled BLAS calls find their functions in it by name, in
    ``sys.modules``). ``scipy.linalg``, if imported later, is imported whole as usual and gets
    the module bound to it (:class:`BlasHook`).

    Returns
    -------
    bool
        True if the module was loaded now; False if there was nothing to do (Numba's check
        already ran, ``scipy.linalg`` or the module already imported) or it could not be
        loaded this way (then Numba imports it as before).
    """
    if BLAS in sys.modules or "scipy.linalg" in sys.modules or BLAS_CHECK in sys.modules:
        return False
    try:
        spec = importlib.util.find_spec("scipy")  # (finds the package, imports nothing)
        folder = Path(spec.submodule_search_locations[0]) / "linalg"
        files = [
            folder / f"cython_blas{suffix}" for suffix in importlib.machinery.EXTENSION_SUFFIXES
        ]
        blas = importlib.util.spec_from_file_location(BLAS, next(f for f in files if f.is_file()))
        module = importlib.util.module_from_spec(blas)
        sys.modules[BLAS] = module
        blas.loader.exec_module(module)
    except Exception:  # no scipy, another layout: Numba imports it the usual way
        sys.modules.pop(BLAS, None)
        return False
    return True


class BlasHook:
    """Import hook (``sys.meta_path``, :func:`install_blas_hook`): :func:`preload_blas` just
    before Numba's BLAS check is imported, and ``scipy.linalg``, when imported after that, given
    its attribute ``cython_blas`` (the import system binds a submodule to its package only when
    it loads it, and this one was loaded before the package). It finds no module itself: the
    next finders do, as without it."""

    def find_spec(self, name, path=None, target=None):
        if name == BLAS_CHECK:
            preload_blas()
        elif name == "scipy.linalg" and BLAS in sys.modules:
            sys.meta_path.remove(self)  # its work is done, and the next finders find the package
            spec = importlib.util.find_spec(name)
            if spec is not None and spec.loader is not None:
                spec.loader = AfterExec(spec.loader, _bind_blas)
            return spec
        return None


class AfterExec:
    """A module's loader that calls ``after(module)`` once the module has run (an import hook's
    way to change a module right after it is imported)."""

    def __init__(self, loader, after) -> None:
        self.loader, self.after = loader, after

    def create_module(self, spec):
        return self.loader.create_module(spec)

    def exec_module(self, module) -> None:
        self.loader.exec_module(module)
        self.after(module)


def _bind_blas(package) -> None:
    """Bind the preloaded BLAS module to the ``scipy.linalg`` package just loaded."""
    package.cython_blas = sys.modules[BLAS]


def install_blas_hook() -> None:
    """Put :class:`BlasHook` first on ``sys.meta_path`` (once; it costs a string comparison
    per import)."""
    if not any(isinstance(f, BlasHook) for f in sys.meta_path):
        sys.meta_path.insert(0, BlasHook())
