"""CEC 2017 (F1-F30) and CEC 2022 (F1-F12) computed by mawdo on a whole population, in the
official numbering: the suites ``cec2017`` and ``cec2022``.

One call evaluates a batch ``(n, D)`` (:mod:`.cec_compose`: one compiled loop over the Numba
functions of :mod:`.cec_basic` and :mod:`.cec_kernels`), from the official input data
(:mod:`.cec_data`): the official C code's values, bit for bit on 6078 of 6080 probe points and
within 1.4e-16 relative on the others (tests/suites/test_cec_official.py). At batch 100 a point
costs about 0.3 us at D = 10 and 1 us at D = 30, some 100-250 times less than ``opfunu``'s
one-point calls (benchmarks/bench_cec.py; the ratio depends on the machine). Bounds are
``[-100, 100]^D``; ``f_star`` is the function's bias (``100 * F`` in CEC 2017). The dimensions
are those the official data cover.
"""

from __future__ import annotations

import numpy as np

from mawdo.suites.base import CompetitionScore, SuiteFunction, SuiteSpec, register_suite
from mawdo.suites.cec_compose import Composition, Hybrid, Plain, compile_function, run
from mawdo.suites.cec_data import CECDataError, load
from mawdo.suites.cec_tables import TABLES, CECFunction

BOUND = 100.0
CHECKPOINTS_2017 = (0.01, 0.02, 0.03, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)
"""CEC 2017's checkpoints, as fractions of the budget (its technical report, 2.2)."""
CEC2017_GROUPS: dict[str, tuple[int, ...]] = {
    "unimodal": (1, 2, 3),
    "simple multimodal": tuple(range(4, 11)),
    "hybrid": tuple(range(11, 21)),
    "composition": tuple(range(21, 31)),
}
"""CEC 2017's four function groups in the official numbering (Awad et al. 2016, the
competition's technical report, Table I: unimodal F1-F3, simple multimodal F4-F10, hybrid
F11-F20, composition F21-F30)."""
CEC2022_GROUPS: dict[str, tuple[int, ...]] = {
    "unimodal": (1,),
    "basic": (2, 3, 4, 5),
    "hybrid": (6, 7, 8),
    "composition": (9, 10, 11, 12),
}
"""CEC 2022's four function groups (Kumar, Price, Mohamed, Hadi and Awad 2021, the
competition's technical report, Table I: unimodal F1, basic F2-F5, hybrid F6-F8, composition
F9-F12)."""
GROUPS = {2017: CEC2017_GROUPS, 2022: CEC2022_GROUPS}
CEC2017_SCORE = CompetitionScore(
    name="CEC 2017 score",
    weights={10: 0.1, 30: 0.2, 50: 0.3, 100: 0.4},
    excluded=(2,),
    source="the CEC 2017 competition's ranking of its entries (Awad, Ali, Liang, Qu and "
    "Suganthan); F2 left out, as the competition dropped it for unstable behaviour",
)
"""CEC 2017's ranking of entries: Score1 from the weighted sum of mean errors, Score2 from the
weighted sum of ranks, 50 points each."""


def checkpoints(year: int, dim: int, max_evals: int) -> tuple[int, ...]:
    """Evaluations after which the competition records the error of a run.

    CEC 2017: ``(0.01, 0.02, 0.03, 0.05, 0.1, 0.2, ..., 1.0) * MaxFES`` (14). CEC 2022:
    ``D^(k/5 - 3) * MaxFES`` for ``k = 0..15`` (16; the report prints the formula as an image:
    this is CEC 2020's, which the 2022 text's ``k = 0, 1, ..., 15`` and last entry at MaxFES
    match; docs/deviations.md#d-cec-protocol). Rounded to whole evaluations, at least 1.
    """
    if year == 2017:
        fractions = CHECKPOINTS_2017
    else:
        fractions = tuple(float(dim) ** (k / 5 - 3) for k in range(16))
    return tuple(max(1, round(f * max_evals)) for f in fractions)


def cec_function(year: int, fid: int) -> CECFunction:
    """The table entry of CEC ``year`` F``fid`` (official numbering)."""
    table = TABLES[year]
    if not 1 <= fid <= len(table):
        raise CECDataError(f"CEC {year} has functions F1-F{len(table)}; got F{fid}")
    return table[fid - 1]


class CECFormula:
    """``X (n, D) -> (n,)`` for one official function; picklable (data reloaded per process)."""

    def __init__(self, year: int, fid: int, dim: int) -> None:
        self.year, self.fid, self.dim = year, fid, dim
        self.function = cec_function(year, fid)
        self._data = self._program = None

    @property
    def data(self):
        """The function's official data in this dimension (read at first use, once per
        process and data folder)."""
        if self._data is None:
            self._data = load(self.function.data, self.dim)
        return self._data

    def __call__(self, X: np.ndarray) -> np.ndarray:
        X = np.ascontiguousarray(X, dtype=np.float64)
        if X.ndim != 2 or X.shape[1] != self.dim:
            raise ValueError(
                f"CEC {self.year} F{self.fid} (D={self.dim}) takes points of shape (n, "
                f"{self.dim}); got {X.shape}"
            )
        if self._program is None:
            self._program = compile_function(self.function.node, self.data)
        return run(X, self._program, self.function.bias)

    def optimum(self) -> np.ndarray:
        """A point where the value is the bias: the (first component's) shift vector, or for
        CEC 2017's Levy (minimum at ``z = 1``) the shift plus ``M^-1 1``."""
        data = self.data
        if self.function.node == Plain("levy2017"):
            return data.shift[0] + np.linalg.solve(data.matrix[0], np.ones(self.dim))
        return data.shift[0].copy()

    def __getstate__(self) -> dict:
        return {"year": self.year, "fid": self.fid, "dim": self.dim}

    def __setstate__(self, state: dict) -> None:
        self.__init__(**state)

    def __repr__(self) -> str:
        return f"CECFormula(CEC{self.year} F{self.fid}, D={self.dim})"


def _builder(year: int):
    def build(fid: int, iid: int, dim: int) -> SuiteFunction:
        formula = CECFormula(year, fid, dim)
        fn = formula.function
        kind = {Composition: "composition", Hybrid: "hybrid"}.get(type(fn.node), "basic")
        return SuiteFunction(
            name=f"cec{year}_f{fid}_d{dim}",
            paper_id=None,
            dim=dim,
            lb=-BOUND,
            ub=BOUND,
            f_star=fn.bias,
            x_star=formula.optimum(),
            func=formula,
            multimodal=not (year == 2017 and fid <= 3) and not (year == 2022 and fid == 1),
            description=f"CEC {year} F{fid} {fn.name} ({kind}; official code, batched)",
            suite=f"cec{year}",
            function_id=fid,
            instance=iid,
            function_name=fn.name,
        )

    return build


def _prepare(fn: CECFunction, dim: int) -> None:
    load(fn.data, dim)  # reads and checks every file the function needs (cached)


def _spec(year: int) -> SuiteSpec:
    table = TABLES[year]
    n = len(table)
    dims = {f.fid: f.data.dims() for f in table}
    return SuiteSpec(
        name=f"cec{year}",
        description=f"CEC {year} bound-constrained, F1-F{n} (official numbering), batched "
        "NumPy port of the official code",
        function_names=tuple(f.name for f in table),
        dims=dims.__getitem__,
        build=_builder(year),
        library="numpy",
        label=f"CEC{year}",
        max_instance=1,
        prepare=lambda fid, dim: _prepare(table[fid - 1], dim),
        checkpoints=lambda dim, max_evals: checkpoints(year, dim, max_evals),
        groups=GROUPS[year],
        score=CEC2017_SCORE if year == 2017 else None,
    )


CEC2017 = register_suite(_spec(2017))
CEC2022 = register_suite(_spec(2022))
