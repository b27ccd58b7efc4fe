"""Numba's IR inlining without its defensive copies of a callee's IR that nobody else holds.

For each call site of an ``inline="always"`` function, Numba's ``InlineWorker.inline_function``
builds the callee's IR afresh (``run_untyped_passes``) and hands it to ``inline_ir``, which
deep-copies it block by block twice: once to have an IR it may change, once more to return an
unchanged copy, which the inlining pass (``InlineInlinables``) throws away. A block's deep
copy also copies the function's whole scope (every ``Var`` copies its scope), so the cost
grows with blocks times variables: for the moving-obstacle pass it was about 3.5 of its 10 s
of compile (Numba issues 8989 and 9204; NVIDIA/numba-cuda issue 688 measures the same).

The IR is fresh and the copies are only thrown away, so skipping them changes nothing that is
compiled: :func:`fresh_ir_inlining` makes ``inline_function`` (and only it: other callers of
``inline_ir`` pass IR they keep, and still get their copies) skip them while the ``with`` body
runs. mawdo uses it where it compiles its own kernels (``mawdo.jit.warm``'s processes, the
command line), never on import, so the Numba of a program that imports mawdo is left as it is.
Where Numba's internals differ from what this expects it does nothing.
"""

from __future__ import annotations

import copy
import threading
import types
from contextlib import contextmanager

# ``deepcopy`` that hands back what it is given: what inline_ir's copy_ir sees instead of the
# copy module while it copies a fresh IR
_NO_COPY = types.SimpleNamespace(deepcopy=lambda x, memo=None: x)
_lock = threading.Lock()
_depth = [0]  # open ``with`` bodies
_own = []  # Numba's own inline_function while patched


def _worker_module():
    """Numba's ``inline_closurecall`` module if it looks as this module expects, else None."""
    try:
        from numba.core import inline_closurecall as ic
    except ImportError:  # pragma: no cover - Numba is a dependency
        return None
    worker = getattr(ic, "InlineWorker", None)
    needs = ("inline_function", "inline_ir", "run_untyped_passes")
    if getattr(ic, "copy", None) is not copy or not all(hasattr(worker, n) for n in needs):
        return None
    return ic


def _inline_function(self, caller_ir, block, i, function, arg_typs=None):
    """``InlineWorker.inline_function`` with the callee's fresh IR inlined uncopied."""
    from numba.core import inline_closurecall as ic

    callee_ir = self.run_untyped_passes(function)
    ic.copy = _NO_COPY  # only copy_ir reads it; Numba compiles under its global lock
    try:
        return self.inline_ir(
            caller_ir, block, i, callee_ir, function.__code__.co_freevars, arg_typs=arg_typs
        )
    finally:
        ic.copy = copy


@contextmanager
def fresh_ir_inlining():
    """Within the ``with`` body, Numba inlines ``inline="always"`` callees without copying
    their fresh IR (see the module's docstring). Nests; restores Numba's own method at the
    outermost exit; a no-op where Numba's internals are not the expected ones."""
    ic = _worker_module()
    if ic is None:
        yield False
        return
    with _lock:
        if _depth[0] == 0:
            _own.append(ic.InlineWorker.inline_function)
            ic.InlineWorker.inline_function = _inline_function
        _depth[0] += 1
    try:
        yield True
    finally:
        with _lock:
            _depth[0] -= 1
            if _depth[0] == 0:
                ic.InlineWorker.inline_function = _own.pop()
