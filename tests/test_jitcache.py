"""Stale Numba caches are dropped when any source of the package changes, and only then."""

from mawdo.jitcache import STAMP, drop_stale_caches, sources_digest


def _package(tmp_path):
    pkg = tmp_path / "pkg"
    (pkg / "sub" / "__pycache__").mkdir(parents=True)
    (pkg / "__pycache__").mkdir()
    (pkg / "kernel.py").write_text("def f():\n    return helper()\n")
    (pkg / "sub" / "helper.py").write_text("def helper():\n    return 1\n")
    return pkg


def _cache(pkg):
    files = [pkg / "__pycache__" / "kernel.f-1.py311.nbi", pkg / "sub" / "__pycache__" / "h.nbc"]
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
    files, _ = _cache(pkg)
    assert drop_stale_caches(pkg) == 0  # same sources: the caches stay
    assert all(f.exists() for f in files)
    (pkg / "sub" / "helper.py").write_text("def helper():\n    return 2\n")
    assert drop_stale_caches(pkg) == 2  # the caller's file did not change, its cache still goes
    assert not any(f.exists() for f in files)


def test_the_digest_sees_renames_and_new_files(tmp_path):
    pkg = _package(tmp_path)
    d0 = sources_digest(pkg)
    (pkg / "sub" / "helper.py").rename(pkg / "sub" / "helper2.py")
    d1 = sources_digest(pkg)
    (pkg / "new.py").write_text("")
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
