"""Standard black-box suites: BBOB via ``ioh``; CEC 2017 / CEC 2022 batched from the official
code (``cec2017``, ``cec2022``) and through ``opfunu`` (``cec2017-opfunu``, ``cec2022-opfunu``).

``get_problem("bbob", 3, instance=1, dim=20)`` returns a :class:`SuiteFunction` usable as the
objective of :func:`mawdo.minimize`; :func:`run_problem` runs an optimizer on it under COCO's
protocol (budget in evaluations per dimension), the driver recording per-run best-so-far
against evaluations. The libraries (and opfunu's copy of the official CEC data) come with the
optional extra: ``pip install "mawdo[bbob]"``.
"""

from mawdo.suites import bbob as _bbob  # noqa: F401  (registers "bbob")
from mawdo.suites import cec as _cec  # noqa: F401  (registers "cec2017-opfunu", "cec2022-opfunu")
from mawdo.suites import cec_native as _cec_native  # noqa: F401  (registers "cec2017", "cec2022")
from mawdo.suites.base import (
    SUITES,
    MissingExtraError,
    SuiteFunction,
    SuiteSpec,
    evaluation_budget,
    get_problem,
    run_problem,
)

__all__ = [
    "SUITES",
    "MissingExtraError",
    "SuiteFunction",
    "SuiteSpec",
    "evaluation_budget",
    "get_problem",
    "run_problem",
]
