"""Stale Numba caches are dropped when a source the kernels depend on changes, and only then."""

import os

from mawdo.jit.cache import PACKAGE, STAMP, drop_stale_caches, kernel_sources, sources_digest


def _package(tmp_path):
    pkg = tmp_path / "pkg"
    (pkg / "sub" / "__pycache__").mkdir(parents=True)
    (pkg / "__pycache__").mkdir()
    (pkg / "kernel.py").write_text(
        "from numba import njit\n\nfrom pkg.sub.middle import helper\n\n"
        "@njit\ndef f():\n    return helper()\n"
    )
    (pkg / "sub" / "__init__.py").write_text("")
    (pkg / "sub" / "middle.py").write_text("from pkg.sub import helper as h\nhelper = h.helper\n")
    (pkg / "sub" / "helper.py").write_text("def helper():\n    return 1\n")
    (pkg / "cli.py").write_text("from pkg import kernel\n\nprint(kernel.f())\n")
    return pkg


def _cache(pkg):
    files = [
        pkg / "__pycache__" / "kernel.f-1.py311.nbi",
        pkg / "__pycache__" / "kernel.f-1.py311.1.nbc",
    ]
    for f in files:
        f.write_bytes(b"cached")
    keep = pkg / "__pycache__" / "kernel.cpython-311.pyc"
    keep.write_bytes(b"bytecode")
    return files, keep


def test_caches_go_when_a_helper_in_another_file_changes(tmp_path):
    pkg = _package(tmp_path)
    files, keep = _cache(pkg)
    assert drop_stale_caches(pkg) == 2  # no stamp yet: nothing cached can be trusted
    assert not any(f.exists() for f in files) and keep.exists()
    assert (pkg / "__pycache__" / STAMP).read_text() == sources_digest(pkg)
    assert sources_digest(pkg).startswith("kernel.py ")  # one line per module with kernels
    files, _ = _cache(pkg)
    assert drop_stale_caches(pkg) == 0  # same sources: the caches stay
    assert all(f.exists() for f in files)
    (pkg / "sub" / "helper.py").write_text("def helper():\n    return 2\n")
    assert drop_stale_caches(pkg) == 2  # the caller's file did not change, its cache still goes
    assert not any(f.exists() for f in files)


def test_caches_stay_when_a_module_no_kernel_imports_changes(tmp_path):
    pkg = _package(tmp_path)
    assert kernel_sources(pkg) == sorted(
        [pkg / "kernel.py", pkg / "sub" / "__init__.py", pkg / "sub" / "middle.py"]
        + [pkg / "sub" / "helper.py"]
    )
    drop_stale_caches(pkg)
    files, _ = _cache(pkg)
    (pkg / "cli.py").write_text("from pkg import kernel\n\nprint(2 * kernel.f())\n")
    (pkg / "report.py").write_text("import numpy\n")  # a new module, not a kernel's
    assert drop_stale_caches(pkg) == 0
    assert all(f.exists() for f in files)
    # the same sizes and times as last checked: the sources are not even read again
    (pkg / "sub" / "helper.py").write_text("def helper():\n    return 3\n")
    st = (pkg / "sub" / "helper.py").stat()
    assert drop_stale_caches(pkg) == 2
    files, _ = _cache(pkg)
    os.utime(pkg / "sub" / "helper.py", ns=(st.st_atime_ns, st.st_mtime_ns + 10**9))
    assert drop_stale_caches(pkg) == 0  # touched, same contents: the caches stay


def test_mawdo_kernels_sources_leave_out_the_commands_and_figures():
    names = {str(p.relative_to(PACKAGE)) for p in kernel_sources()}
    assert "planning/refine/kernel/moving.py" in names and "optimizers/wind_kernel.py" in names
    assert "planning/refine/kernel/constants.py" in names  # no Numba in it, but kernels read it
    assert not any(n.startswith(("cli/", "planning/render/", "experiments/")) for n in names)


def test_the_digest_sees_renames_and_new_files(tmp_path):
    pkg = _package(tmp_path)
    d0 = sources_digest(pkg)
    (pkg / "sub" / "helper.py").rename(pkg / "sub" / "helper2.py")
    (pkg / "sub" / "middle.py").write_text("from pkg.sub import helper2 as h\nhelper = h.helper\n")
    d1 = sources_digest(pkg)
    (pkg / "new.py").write_text("from numba import njit\n")
    assert len({d0, d1, sources_digest(pkg)}) == 3


def test_numba_cache_dir_mirrors_are_cleaned_too(tmp_path, monkeypatch):
    pkg = _package(tmp_path)
    base = tmp_path / "numba-cache"
    mirrored = base / str(pkg).lstrip("/") / "sub"
    mirrored.mkdir(parents=True)
    (mirrored / "helper.h-1.py311.nbi").write_bytes(b"cached")
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(base))
    assert drop_stale_caches(pkg) == 1
    assert not (mirrored / "helper.h-1.py311.nbi").exists()


def test_numba_cache_dir_folders_are_cleaned_too(tmp_path, monkeypatch):
    # where Numba itself puts a module's caches under NUMBA_CACHE_DIR (its locator, not ours)
    from numba.core.caching import _CacheLocator

    pkg = _package(tmp_path)
    base = tmp_path / "numba-cache"
    folder = base / _CacheLocator.get_suitable_cache_subpath(str(pkg / "sub" / "helper.py"))
    folder.mkdir(parents=True)
    (folder / "helper.h-1.py311.nbi").write_bytes(b"cached")
    (folder / "helper.h-1.py311.1.nbc").write_bytes(b"cached")
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(base))
    assert drop_stale_caches(pkg) == 2
    assert not any(folder.iterdir())


def test_a_kernel_module_that_does_not_import_the_edit_keeps_its_caches(tmp_path):
    pkg = _package(tmp_path)
    (pkg / "other.py").write_text("from numba import njit\n\n@njit\ndef g():\n    return 0\n")
    drop_stale_caches(pkg)
    files, _ = _cache(pkg)
    other = pkg / "__pycache__" / "other.g-1.py311.nbi"
    other.write_bytes(b"cached")
    (pkg / "sub" / "helper.py").write_text("def helper():\n    return 5\n")
    assert drop_stale_caches(pkg) == 2  # kernel.py's (it imports the helper), not other.py's
    assert not any(f.exists() for f in files) and other.exists()
    (pkg / "other.py").write_text("from numba import njit\n\n@njit\ndef g():\n    return 1\n")
    assert drop_stale_caches(pkg) == 1 and not other.exists()


def test_a_stamp_of_an_older_mawdo_drops_everything(tmp_path):
    pkg = _package(tmp_path)
    files, _ = _cache(pkg)
    (pkg / "__pycache__" / STAMP).write_text("0" * 64)  # one digest for all sources
    assert drop_stale_caches(pkg) == 2
