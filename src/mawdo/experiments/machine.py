"""What computed a task: the processor features and numerical libraries that can change the
last bits of a result.

A seeded run of mawdo's own optimizers gives the same numbers on any x86-64 CPU, but the
library references do not: `cmaes`'s eigendecomposition runs in OpenBLAS, whose kernels depend
on the CPU (docs/deviations.md#d-cpu). The store keeps this line beside each task
(``tasks.platform``), so a row that cannot be computed again can be traced to its machine.
"""

from __future__ import annotations

import functools
import platform

import numpy as np

# the NumPy CPU features that decide which SIMD loops (and so which last bits) a call takes
_SIMD = ("AVX512F", "AVX2", "FMA3", "ASIMD", "SVE")


@functools.cache
def platform_summary() -> str:
    """One line naming the machine's architecture, the C library, NumPy and its SIMD features,
    and the BLAS with the kernels it chose, e.g. ``x86_64; glibc 2.36; numpy 2.4.6 (AVX2,
    FMA3); openblas 0.3.31 (Haswell)``. Computed once per process."""
    parts = [platform.machine() or "unknown machine"]
    libc, version = platform.libc_ver()
    if libc:
        parts.append(f"{libc} {version}")
    parts.append(f"numpy {np.__version__} ({', '.join(_simd_features()) or 'baseline'})")
    parts.extend(_blas())
    return "; ".join(parts)


def _simd_features() -> list[str]:
    try:  # NumPy's own record of what it found; private, so read defensively
        from numpy._core._multiarray_umath import __cpu_features__ as found
    except ImportError:  # pragma: no cover - NumPy < 2 or a future layout
        return []
    return [name for name in _SIMD if found.get(name)]


def _blas() -> list[str]:
    from threadpoolctl import threadpool_info

    return [
        f"{lib.get('internal_api', '?')} {lib.get('version', '?')} "
        f"({lib.get('architecture') or 'unknown kernels'})"
        for lib in threadpool_info()
        if lib.get("user_api") == "blas"
    ]
