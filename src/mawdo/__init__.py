"""mawdo: wind driven optimization (WDO, AWDO, MAWDO) and real-time path planning.

>>> from mawdo import minimize
>>> res = minimize("sphere", algorithm="mawdo", runs=30, seed=1, max_iter=500)
>>> res.fun.shape
(30,)
"""

import sys
import types

from mawdo.jit import heal
from mawdo.jit.cache import drop_stale_caches, install_blas_hook

# before any kernel module loads: a cached kernel may hold an old version of a helper it inlined
drop_stale_caches()
# Numba's first kernel then loads scipy's BLAS wrappers, not all of scipy.linalg (0.3 s)
install_blas_hook()
# a damaged entry of Numba's cache is dropped and compiled again, not a traceback in every run
heal.install()

__version__ = "0.9.0"

#: The facade's names and the module each comes from. They are imported on first use (PEP 562),
#: so that a command (``mawdo plan paper``) does not pay for the optimizers, the driver and Numba
#: before it has read its arguments: ``import mawdo`` alone costs milliseconds, not 1.4 s.
_LAZY = {
    "make_problem": "mawdo.minimize",
    "OPTIMIZERS": "mawdo.optimizers",
    "make_optimizer": "mawdo.optimizers",
    "ObjectiveError": "mawdo.problem",
    "Problem": "mawdo.problem",
    "OptimizeResult": "mawdo.result",
    "FUNCTIONS": "mawdo.functions",
}


def __getattr__(name):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value  # later look-ups skip this function
        return value
    raise AttributeError(f"module 'mawdo' has no attribute {name!r}")


class _Facade(types.ModuleType):
    """The package's module type: ``mawdo.minimize`` is the function, imported on first use.

    The submodule of the same name, once imported (by the planner, say), would otherwise be
    bound here in the function's place, as Python binds every imported submodule to its
    package: the setter keeps the function, as the eager import it replaces did.
    """

    @property
    def minimize(self):
        from mawdo.minimize import minimize

        return minimize

    @minimize.setter
    def minimize(self, value) -> None:
        pass  # the import system binding the submodule ``mawdo.minimize``


sys.modules[__name__].__class__ = _Facade


__all__ = [
    "FUNCTIONS",
    "OPTIMIZERS",
    "ObjectiveError",
    "OptimizeResult",
    "Problem",
    "make_optimizer",
    "make_problem",
    "minimize",
    "__version__",
]
