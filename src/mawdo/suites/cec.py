"""CEC 2017 and CEC 2022 single-objective bound-constrained suites through ``opfunu``.

The values are ``opfunu``'s (``F{k}{year}(ndim=D).evaluate(x)``, one point per call; a batch is
a loop over its rows). Each suite defines only some dimensions (the shift and rotation data
exist only for those), and ``opfunu`` calls ``exit()`` on any other, so we check the dimension
before building. CEC suites have one instance. Bounds are ``[-100, 100]^D``; ``f_star`` is the
function's bias (``f_global``).
"""

from __future__ import annotations

import functools

import numpy as np

from mawdo.suites.base import SuiteFunction, SuiteSpec, register_suite, require

# The dimensions each suite's data define (opfunu 1.0.4's dim_supported; tests check them).
CEC2017_DIMS = (2, 10, 20, 30, 50, 100)
CEC2017_HYBRID_DIMS = (10, 30, 50, 100)  # no D=2 or D=20 data for these (hybrid, F28, F29)
CEC2017_HYBRID = (*range(10, 20), 28, 29)
CEC2022_DIMS = (2, 10, 20)
CEC2022_NO_D2 = (6, 7, 8)  # hybrid functions


def cec_dims(year: int, fid: int) -> tuple[int, ...]:
    """Dimensions defined for CEC ``year`` function ``fid``."""
    if year == 2017:
        return CEC2017_HYBRID_DIMS if fid in CEC2017_HYBRID else CEC2017_DIMS
    return CEC2022_DIMS[1:] if fid in CEC2022_NO_D2 else CEC2022_DIMS


@functools.lru_cache(maxsize=64)
def _opfunu_function(year: int, fid: int, dim: int):
    mod = require(f"opfunu.cec_based.cec{year}", f"cec{year}")
    return getattr(mod, f"F{fid}{year}")(ndim=dim)


class OpfunuFormula:
    """``X (n, D) -> (n,)`` through ``opfunu``'s CEC function; picklable (rebuilt per process)."""

    def __init__(self, year: int, fid: int, dim: int) -> None:
        self.year, self.fid, self.dim = year, fid, dim

    @property
    def function(self):
        """The ``opfunu`` function object (cached per process)."""
        return _opfunu_function(self.year, self.fid, self.dim)

    def __call__(self, X: np.ndarray) -> np.ndarray:
        f = self.function
        X = np.asarray(X, dtype=float)
        return np.fromiter((f.evaluate(x) for x in X), dtype=float, count=X.shape[0])

    def __repr__(self) -> str:
        return f"OpfunuFormula(CEC{self.year} F{self.fid}, D={self.dim})"


def _builder(year: int):
    def build(fid: int, iid: int, dim: int) -> SuiteFunction:
        formula = OpfunuFormula(year, fid, dim)
        f = formula.function
        lb, ub = np.asarray(f.bounds, dtype=float).T
        name = str(f.name).split(":", 1)[-1].strip()
        return SuiteFunction(
            name=f"cec{year}_f{fid}_d{dim}",
            paper_id=None,
            dim=dim,
            lb=lb,
            ub=ub,
            f_star=float(f.f_global),
            x_star=np.asarray(f.x_global, dtype=float),
            func=formula,
            multimodal=not getattr(f, "unimodal", False),
            description=f"CEC {year} F{fid} {name} (opfunu)",
            suite=f"cec{year}",
            function_id=fid,
            instance=iid,
            function_name=name,
        )

    return build


CEC2017 = register_suite(
    SuiteSpec(
        name="cec2017",
        description="CEC 2017 bound-constrained, 29 functions, D in {2,10,20,30,50,100}, opfunu",
        function_names=tuple(f"F{k}" for k in range(1, 30)),
        dims=lambda fid: cec_dims(2017, fid),
        build=_builder(2017),
        library="opfunu.cec_based.cec2017",
        label="CEC2017",
        max_instance=1,
    )
)
CEC2022 = register_suite(
    SuiteSpec(
        name="cec2022",
        description="CEC 2022 bound-constrained, 12 functions, D in {2,10,20}, via opfunu",
        function_names=tuple(f"F{k}" for k in range(1, 13)),
        dims=lambda fid: cec_dims(2022, fid),
        build=_builder(2022),
        library="opfunu.cec_based.cec2022",
        label="CEC2022",
        max_instance=1,
    )
)
