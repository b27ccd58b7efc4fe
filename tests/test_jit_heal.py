"""A damaged entry of Numba's cache (random bytes, truncated, empty; index or data file) is
dropped and compiled again with one warning line, and gives the same result; without mawdo's
wrapping the same damage fails every run (so the damage made here is real)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import mawdo
from mawdo.jit import heal
from mawdo.jit.warm import Entry, is_cached

KERNEL = """
from numba import njit

@njit(cache=True)
def f(x):
    return x * 2 + 1
"""
RUN = "import mawdo, kern; print(kern.f(20))"
BARE = "import kern; print(kern.f(20))"  # Numba alone


def _run(folder: Path, code: str) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    src = str(Path(mawdo.__file__).parents[1])
    env["PYTHONPATH"] = os.pathsep.join([str(folder), src])
    return subprocess.run(
        [sys.executable, "-c", code], cwd=folder, env=env, capture_output=True, text=True,
        timeout=300,
    )  # fmt: skip


@pytest.fixture(scope="module")
def warm_folder(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("heal-warm")
    (folder / "kern.py").write_text(KERNEL)
    first = _run(folder, RUN)
    assert first.returncode == 0 and first.stdout.strip() == "41", first.stderr
    return folder


def _damage(path: Path, how: str) -> None:
    data = path.read_bytes()
    if how == "random":
        path.write_bytes(np.random.default_rng(0).bytes(len(data)))
    elif how == "truncated":
        path.write_bytes(data[: len(data) // 2])
    else:
        path.write_bytes(b"")


def _copy(warm: Path, tmp_path: Path) -> Path:
    folder = tmp_path / "p"
    shutil.copytree(warm, folder)
    return folder


def _file(folder: Path, suffix: str) -> Path:
    (path,) = (folder / "__pycache__").glob(f"kern.f-*{suffix}")
    return path


@pytest.mark.parametrize("suffix", [".nbi", ".nbc"])
@pytest.mark.parametrize("how", ["random", "truncated", "empty"])
def test_a_damaged_entry_is_compiled_again_with_one_warning(warm_folder, tmp_path, suffix, how):
    folder = _copy(warm_folder, tmp_path)
    _damage(_file(folder, suffix), how)
    healed = _run(folder, RUN)
    assert healed.returncode == 0 and healed.stdout.strip() == "41", healed.stderr
    warnings = [ln for ln in healed.stderr.splitlines() if ln.startswith("warning: ")]
    assert len(warnings) == 1 and "kern.f-" in warnings[0] and "damaged" in warnings[0]
    again = _run(folder, RUN)  # saved anew: no warning, same value
    assert again.returncode == 0 and again.stdout.strip() == "41"
    assert "warning" not in again.stderr


def test_the_same_damage_fails_numba_alone(warm_folder, tmp_path):
    folder = _copy(warm_folder, tmp_path)
    _damage(_file(folder, ".nbi"), "random")
    bare = _run(folder, BARE)
    assert bare.returncode != 0 and "Error" in bare.stderr


def test_the_install_check_reads_the_data_file_back(warm_folder, tmp_path, monkeypatch):
    # is_cached (the install step's check) sees a damaged data file as missing and drops it;
    # an index alone is not enough
    folder = _copy(warm_folder, tmp_path)
    monkeypatch.syspath_prepend(str(folder))
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    sys.modules.pop("kern", None)
    entry = Entry("kern", "f", 0.1, "-", "(int64,)")
    assert is_cached(entry)
    data = _file(folder, ".nbc")
    _damage(data, "truncated")
    sys.modules.pop("kern", None)
    assert not is_cached(entry)
    assert not data.exists() and not list((folder / "__pycache__").glob("kern.f-*.nbi"))
    sys.modules.pop("kern", None)


def test_the_wrapping_is_installed_once_and_leaves_other_numbas_alone():
    import numba.core.caching as caching

    assert heal.patch(caching) and caching.IndexDataCacheFile._load_index._mawdo_heals
    before = caching.IndexDataCacheFile._load_index
    assert heal.patch(caching) and caching.IndexDataCacheFile._load_index is before

    class Other:  # a Numba without these internals: nothing is changed
        pass

    assert heal.patch(Other) is False


def _metrics(folder: Path) -> dict:
    import json

    data = json.loads((folder / "metrics.json").read_text())
    timed = ("latency", "seconds")  # wall times: first_plan_s, latency_*
    keep = {k: v for k, v in data.items() if not k.endswith("_s")}
    return {k: v for k, v in keep.items() if not any(w in k for w in timed)}


@pytest.mark.slow
def test_a_damaged_planner_kernel_is_recompiled_once_and_plans_the_same(tmp_path):
    # a fresh cache filled by the install step, the paper plan, then tangent_edges' data file
    # overwritten: the install step finds it (one kernel to compile, one warning), and after
    # emptying its index too, the plan recompiles it with one warning and the same numbers
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"))
    env["PYTHONPATH"] = str(Path(mawdo.__file__).parents[1])

    def run(*args):
        cmd = [sys.executable, "-m", *args]
        return subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=900)

    assert run("mawdo.jit", "--jobs", "2").returncode == 0
    plan = ("mawdo.cli", "plan", "paper", "--no-figures", "--no-progress", "--out")
    first = run(*plan, str(tmp_path / "a"))
    assert first.returncode == 0, first.stderr
    (data,) = (tmp_path / "numba").rglob("visgraph_kernels.tangent_edges-*.nbc")
    _damage(data, "random")
    install = run("mawdo.jit")
    assert install.returncode == 0 and "compiling 1 kernels" in install.stdout, install.stdout
    assert install.stderr.count("warning: Numba's cache entry") == 1, install.stderr
    (index,) = (tmp_path / "numba").rglob("visgraph_kernels.tangent_edges-*.nbi")
    _damage(index, "empty")
    second = run(*plan, str(tmp_path / "b"))
    assert second.returncode == 0, second.stderr
    assert second.stderr.count("warning: Numba's cache entry") == 1, second.stderr
    assert _metrics(tmp_path / "a") == _metrics(tmp_path / "b")
