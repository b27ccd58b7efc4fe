"""mawdo: wind driven optimization (WDO, AWDO, MAWDO) and real-time path planning.

>>> from mawdo import minimize
>>> res = minimize("sphere", algorithm="mawdo", runs=30, seed=1, max_iter=500)
>>> res.fun.shape
(30,)
"""

from mawdo.jitcache import drop_stale_caches

# before any kernel module loads: a cached kernel may hold an old version of a helper it inlined
drop_stale_caches()

from mawdo.minimize import make_problem, minimize  # noqa: E402
from mawdo.optimizers import OPTIMIZERS, make_optimizer  # noqa: E402
from mawdo.problem import ObjectiveError, Problem  # noqa: E402
from mawdo.result import OptimizeResult  # noqa: E402

__version__ = "0.9.0"


def __getattr__(name):
    # FUNCTIONS lives in mawdo.functions; imported lazily so that package stays independent.
    if name == "FUNCTIONS":
        from mawdo.functions import FUNCTIONS

        return FUNCTIONS
    raise AttributeError(f"module 'mawdo' has no attribute {name!r}")


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
