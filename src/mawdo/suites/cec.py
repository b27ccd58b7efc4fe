"""CEC 2017 and CEC 2022 through ``opfunu``: the suites ``cec2017-opfunu`` and ``cec2022-opfunu``.

The values are ``opfunu``'s (``F{k}{year}(ndim=D).evaluate(x)``, one point per call; a batch is
a loop over its rows), kept as a second implementation beside the batched ``cec2017`` /
``cec2022`` (:mod:`.cec_native`). Function ids are the official ones: ``opfunu`` 1.0.4 numbers
CEC 2017 F1-F29 without the official F2 (sum of different powers), so its ``F{k}2017`` is
the official F(k+1) for k >= 2, and official F2 is refused with the fix. CEC 2022's numbering
is the official one. Each suite defines only some dimensions (the shift and rotation data
exist only for those), and ``opfunu`` calls ``exit()`` on any other, so we check the dimension
before building. CEC suites have one instance. Bounds are ``[-100, 100]^D``; ``f_star`` is the
function's bias (``f_global``).
"""

from __future__ import annotations

import functools

import numpy as np

from mawdo.suites.base import SuiteFunction, SuiteSpec, register_suite, require

# The dimensions opfunu 1.0.4 supports (its dim_supported; tests check them), by OFFICIAL id.
CEC2017_DIMS = (2, 10, 20, 30, 50, 100)
CEC2017_HYBRID_DIMS = (10, 30, 50, 100)  # no D=2 or D=20 in opfunu (hybrids, F29, F30)
CEC2017_HYBRID = (*range(11, 21), 29, 30)
CEC2022_DIMS = (2, 10, 20)
CEC2022_NO_D2 = (6, 7, 8)  # hybrid functions
OPFUNU_NUMBERING = (
    "opfunu 1.0.4 numbers CEC 2017 F1-F29 without the official F2: its F1 is official F1, "
    "its Fk (k >= 2) is official F(k+1)"
)


def opfunu_id(year: int, fid: int) -> int:
    """opfunu's number of the official CEC ``year`` function ``fid``.

    Raises
    ------
    ValueError
        Official CEC 2017 F2, which opfunu does not implement.
    """
    if year != 2017 or fid == 1:
        return fid
    if fid == 2:
        raise ValueError(
            "cec2017-opfunu has no F2: opfunu 1.0.4 does not implement the official CEC 2017 "
            "F2 (shifted and rotated sum of different powers); use the suite cec2017, which does"
        )
    return fid - 1


def official_id(year: int, opfunu_fid: int) -> int:
    """The official number of opfunu's CEC ``year`` function ``opfunu_fid`` (inverse of
    :func:`opfunu_id`)."""
    return opfunu_fid + 1 if year == 2017 and opfunu_fid >= 2 else opfunu_fid


def cec_dims(year: int, fid: int) -> tuple[int, ...]:
    """Dimensions opfunu defines for the official CEC ``year`` function ``fid``."""
    if year == 2017:
        opfunu_id(year, fid)  # official F2: the error says why
        return CEC2017_HYBRID_DIMS if fid in CEC2017_HYBRID else CEC2017_DIMS
    return CEC2022_DIMS[1:] if fid in CEC2022_NO_D2 else CEC2022_DIMS


@functools.lru_cache(maxsize=64)
def _opfunu_function(year: int, fid: int, dim: int):
    mod = require(f"opfunu.cec_based.cec{year}", f"cec{year}-opfunu")
    return getattr(mod, f"F{opfunu_id(year, fid)}{year}")(ndim=dim)


class OpfunuFormula:
    """``X (n, D) -> (n,)`` through ``opfunu``'s CEC function; picklable (rebuilt per process).
    ``fid`` is the official number."""

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
        return f"OpfunuFormula(CEC{self.year} F{self.fid} (official), D={self.dim})"


def _builder(year: int):
    def build(fid: int, iid: int, dim: int) -> SuiteFunction:
        formula = OpfunuFormula(year, fid, dim)
        f = formula.function
        lb, ub = np.asarray(f.bounds, dtype=float).T
        name = str(f.name).split(":", 1)[-1].strip()
        return SuiteFunction(
            name=f"cec{year}-opfunu_f{fid}_d{dim}",
            paper_id=None,
            dim=dim,
            lb=lb,
            ub=ub,
            f_star=float(f.f_global),
            x_star=np.asarray(f.x_global, dtype=float),
            func=formula,
            multimodal=not getattr(f, "unimodal", False),
            description=f"CEC {year} F{fid} {name} (opfunu F{opfunu_id(year, fid)})",
            suite=f"cec{year}-opfunu",
            function_id=fid,
            instance=iid,
            function_name=name,
        )

    return build


OPFUNU2017 = register_suite(
    SuiteSpec(
        name="cec2017-opfunu",
        description="CEC 2017 through opfunu, one point per call: official F1, F3-F30 (no F2)",
        function_names=tuple(f"F{k}" for k in range(1, 31)),
        dims=lambda fid: cec_dims(2017, fid),
        build=_builder(2017),
        library="opfunu.cec_based.cec2017",
        label="CEC2017",
        max_instance=1,
    )
)
OPFUNU2022 = register_suite(
    SuiteSpec(
        name="cec2022-opfunu",
        description="CEC 2022 through opfunu, one point per call: F1-F12",
        function_names=tuple(f"F{k}" for k in range(1, 13)),
        dims=lambda fid: cec_dims(2022, fid),
        build=_builder(2022),
        library="opfunu.cec_based.cec2022",
        label="CEC2022",
        max_instance=1,
    )
)
