"""Numba's BLAS check loads scipy's BLAS wrappers alone, not all of scipy.linalg (issue 28
item 2: 0.25-0.3 s of every planning command's start-up), and nothing else changes.

Each case runs in a fresh interpreter: what is imported is the point."""

from __future__ import annotations

import json
import subprocess
import sys

PROBE = """
import json, sys
{first}
import numba, numpy as np
import numba.np.arraymath as am  # what the first kernel load imports

@numba.njit(cache=False)
def product(a, b):
    return np.dot(a, b)  # a BLAS call through the preloaded module

a = np.arange(12.0).reshape(3, 4)
out = {{
    "linalg_before": "scipy.linalg" in sys.modules,
    "have_blas": bool(am._HAVE_BLAS),
    "dot": bool(np.array_equal(product(a, a.T), a @ a.T)),
    "blas_file": sys.modules["scipy.linalg.cython_blas"].__file__,
}}
import scipy.linalg  # the whole package, later: as usual, with the module bound to it
out["bound"] = scipy.linalg.cython_blas is sys.modules["scipy.linalg.cython_blas"]
out["solve"] = scipy.linalg.solve(np.diag([2.0, 4.0]), np.array([2.0, 8.0])).tolist()
print(json.dumps(out))
"""


def _probe(first: str) -> dict:
    code = PROBE.format(first=first)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


def test_numba_alone_imports_all_of_scipy_linalg():
    """The reference: without mawdo, Numba's check pulls in the package."""
    out = _probe("")
    assert out["linalg_before"] is True
    assert out["have_blas"] and out["dot"] and out["bound"]


def test_after_import_mawdo_the_check_loads_the_wrappers_alone():
    plain = _probe("")
    out = _probe("import mawdo")
    assert out["linalg_before"] is False  # scipy.linalg's package was not run
    assert out["have_blas"] is True  # Numba found BLAS
    assert out["dot"] is True  # and compiled code calls it
    assert out["blas_file"] == plain["blas_file"]  # the same extension module file
    assert out["bound"] is True  # scipy.linalg imported later has it as an attribute
    assert out["solve"] == [1.0, 2.0] == plain["solve"]
