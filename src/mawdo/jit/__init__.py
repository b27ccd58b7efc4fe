"""Numba compile machinery: what keeps the first planning command from waiting on the compiler.

* :mod:`~mawdo.jit.cache` - drops stale Numba caches (a changed kernel source) before any
  kernel loads, and the BLAS preload hook;
* :mod:`~mawdo.jit.warm` - the jit table (every kernel and signature the commands compile) and
  its parallel compile into Numba's cache: ``python -m mawdo.jit [--jobs N]``, which
  ``make install`` runs;
* :mod:`~mawdo.jit.record` - the table's upkeep: record what a command compiles, re-time rows;
* :mod:`~mawdo.jit.schedule` - which kernel a free compiling process takes next;
* :mod:`~mawdo.jit.inline` - Numba's IR inlining without copies of a callee's fresh IR, where
  mawdo compiles its own kernels.
"""
