"""The official CEC 2017 / CEC 2022 C code (tests/data/cec), compiled here and called by ctypes.

The official sources are used unchanged: ``cec22_test_func.cpp`` includes ``<WINDOWS.H>``, which
is an empty header in the build folder, and both open ``input_data/...`` relative to the
working directory, which is a folder whose ``input_data`` links to the data mawdo reads.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np

from mawdo.suites.cec_data import data_folder

SOURCES = Path(__file__).resolve().parent.parent / "data" / "cec"


def compiler() -> str | None:
    """A C++ compiler on PATH, or None."""
    for name in ("g++", "c++", "clang++"):
        path = shutil.which(name)
        if path:
            return path
    return None


class OfficialCEC:
    """The official ``cec17_test_func`` / ``cec22_test_func`` of ``year`` as a function of a
    batch ``X (n, D)``."""

    def __init__(self, year: int, build: Path) -> None:
        self.year = year
        short = year % 100
        (build / "inc").mkdir(parents=True, exist_ok=True)
        (build / "inc" / "WINDOWS.H").write_text("")
        lib = build / f"libcec{short}.so"
        cmd = [
            compiler(), "-O2", "-shared", "-fPIC", "-fvisibility=hidden", "-w",
            f"-I{build / 'inc'}", f"-DYEAR={short}", str(SOURCES / "cec_driver.cpp"),
            str(SOURCES / f"cec{short}_test_func.cpp"), "-o", str(lib),
        ]  # fmt: skip
        done = subprocess.run(cmd, capture_output=True, text=True)
        if done.returncode != 0:
            raise RuntimeError(f"building the official CEC {year} code failed: {done.stderr}")
        self.lib = ctypes.CDLL(str(lib))
        self.run_dir = build / f"run{short}"
        self.run_dir.mkdir(exist_ok=True)
        (self.run_dir / "input_data").symlink_to(data_folder(year), target_is_directory=True)

    def __call__(self, fid: int, X: np.ndarray) -> np.ndarray:
        X = np.ascontiguousarray(X, dtype=float)
        f = np.zeros(X.shape[0])
        ptr = ctypes.POINTER(ctypes.c_double)
        with contextlib.chdir(self.run_dir), _quiet():
            self.lib.evaluate(
                X.ctypes.data_as(ptr), f.ctypes.data_as(ptr), X.shape[1], X.shape[0], fid
            )
        return f


@contextlib.contextmanager
def _quiet():
    """Silence the C code's printf warnings (e.g. 'NOT defined for D=2' for F21/F22, which it
    computes anyway)."""
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), 1)
            yield
    finally:
        libc = ctypes.CDLL(None)
        libc.fflush(None)
        os.dup2(saved, 1)
        os.close(saved)
