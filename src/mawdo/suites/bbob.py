"""BBOB (COCO's 24 noiseless functions) through IOHprofiler's ``ioh`` package.

The values are ``ioh``'s: we never reimplement a function. One ``problem(X)`` call evaluates a
whole batch ``(n, D)`` (all ``R x N`` candidates of an iteration). Bounds are BBOB's
``[-5, 5]^D``; ``f_star`` and ``x_star`` are the instance's optimum as ``ioh`` reports it.
"""

from __future__ import annotations

import numpy as np

from mawdo.suites.base import SuiteFunction, SuiteSpec, register_suite, require

# ioh's names of f1..f24 (the COCO order); fixed by the suite, listed here so ids and names
# resolve (with suggestions) without the extra installed.
BBOB_NAMES = (
    "Sphere",
    "Ellipsoid",
    "Rastrigin",
    "BuecheRastrigin",
    "LinearSlope",
    "AttractiveSector",
    "StepEllipsoid",
    "Rosenbrock",
    "RosenbrockRotated",
    "EllipsoidRotated",
    "Discus",
    "BentCigar",
    "SharpRidge",
    "DifferentPowers",
    "RastriginRotated",
    "Weierstrass",
    "Schaffers10",
    "Schaffers1000",
    "GriewankRosenbrock",
    "Schwefel",
    "Gallagher101",
    "Gallagher21",
    "Katsuura",
    "LunacekBiRastrigin",
)
BBOB_DIMS = tuple(range(2, 41))
BBOB_GROUPS: dict[str, tuple[int, ...]] = {
    "separable": (1, 2, 3, 4, 5),
    "low or moderate conditioning": (6, 7, 8, 9),
    "high conditioning, unimodal": (10, 11, 12, 13, 14),
    "multimodal, adequate global structure": (15, 16, 17, 18, 19),
    "multimodal, weak global structure": (20, 21, 22, 23, 24),
}
"""COCO's five BBOB function groups (f1-f24)."""
BBOB_BOUND = 5.0


class IOHFormula:
    """``X (n, D) -> (n,)`` through ``ioh.get_problem(fid, iid, D)``; picklable.

    The ``ioh`` problem is a C++ object: it is rebuilt lazily in each process from
    ``(fid, iid, dim)`` instead of being pickled.
    """

    def __init__(self, fid: int, iid: int, dim: int) -> None:
        self.fid, self.iid, self.dim = fid, iid, dim
        self._problem = None

    @property
    def problem(self):
        """The ``ioh`` problem (built on first use)."""
        if self._problem is None:
            ioh = require("ioh", "bbob")
            self._problem = ioh.get_problem(self.fid, self.iid, self.dim, ioh.ProblemClass.REAL)
        return self._problem

    def __call__(self, X: np.ndarray) -> np.ndarray:
        # ioh >= 0.4 takes a C-contiguous float64 batch directly: 1.42 us per D = 20 point over
        # f1-f24 against 1.72 through nested lists (0.3.22, where lists were faster: 1.89), same
        # values and problem state (benchmarks/bench_bbob.py times it beside the bare call)
        return np.asarray(self.problem(np.ascontiguousarray(X, dtype=float)), dtype=float)

    def __getstate__(self) -> dict:
        return {"fid": self.fid, "iid": self.iid, "dim": self.dim, "_problem": None}

    def __repr__(self) -> str:
        return f"IOHFormula(f{self.fid}, instance {self.iid}, D={self.dim})"


def build_bbob(fid: int, iid: int, dim: int) -> SuiteFunction:
    """BBOB function ``fid``, instance ``iid``, dimension ``dim`` (validated by the suite)."""
    formula = IOHFormula(fid, iid, dim)
    opt = formula.problem.optimum
    name = BBOB_NAMES[fid - 1]
    return SuiteFunction(
        name=f"bbob_f{fid}_i{iid}_d{dim}",
        paper_id=None,
        dim=dim,
        lb=-BBOB_BOUND,
        ub=BBOB_BOUND,
        f_star=float(opt.y),
        x_star=np.asarray(opt.x, dtype=float),
        func=formula,
        multimodal=fid in (3, 4, *range(15, 25)),
        description=f"BBOB f{fid} {name}, instance {iid} (ioh)",
        suite="bbob",
        function_id=fid,
        instance=iid,
        function_name=name,
    )


BBOB = register_suite(
    SuiteSpec(
        name="bbob",
        description="COCO BBOB noiseless, 24 functions, instances >= 1, D 2-40, via ioh",
        function_names=BBOB_NAMES,
        dims=lambda fid: BBOB_DIMS,
        build=build_bbob,
        library="ioh",
        label="BBOB",
        default_instances=(1, 2, 3, 4, 5),
        groups=BBOB_GROUPS,
    )
)
