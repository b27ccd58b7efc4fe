"""The function tables of CEC 2017 (F1-F30) and CEC 2022 (F1-F12), in the official numbering,
as ``cec17_test_func.cpp`` and ``cec22_test_func.cpp`` define them (their ``switch`` on
``func_num`` and the ``hf*`` / ``cf*`` functions)."""

from __future__ import annotations

from dataclasses import dataclass

from mawdo.suites.cec_compose import Component, Composition, Hybrid, Plain
from mawdo.suites.cec_data import FunctionData


@dataclass(frozen=True)
class CECFunction:
    """One official function: number, name, formula tree, optimum value (its bias)."""

    year: int
    fid: int
    name: str
    node: Plain | Hybrid | Composition
    bias: float

    @property
    def data(self) -> FunctionData:
        """What it reads from the official input data."""
        node = self.node
        if isinstance(node, Composition):
            k = len(node.components)
            hyb = isinstance(node.components[0].function, Hybrid)
            return FunctionData(self.year, self.fid, k, k, k if hyb else 0, composition=True)
        return FunctionData(self.year, self.fid, shuffle=1 if isinstance(node, Hybrid) else 0)


def _cf(*parts) -> Composition:
    """``(function, delta, bias, scale)`` tuples -> a composition."""
    return Composition(tuple(Component(*p) for p in parts))


P = Plain
_HF17 = {
    1: Hybrid(("zakharov", "rosenbrock", "rastrigin"), (0.2, 0.4, 0.4)),
    2: Hybrid(("ellips", "schwefel", "bent_cigar"), (0.3, 0.3, 0.4)),
    3: Hybrid(("bent_cigar", "rosenbrock", "bi_rastrigin"), (0.3, 0.3, 0.4)),
    4: Hybrid(("ellips", "ackley", "schaffer_f7", "rastrigin"), (0.2, 0.2, 0.2, 0.4)),
    5: Hybrid(("bent_cigar", "hgbat", "rastrigin", "rosenbrock"), (0.2, 0.2, 0.3, 0.3)),
    6: Hybrid(("escaffer6", "hgbat", "rosenbrock", "schwefel"), (0.2, 0.2, 0.3, 0.3)),
    7: Hybrid(
        ("katsuura", "ackley", "grie_rosen", "schwefel", "rastrigin"), (0.1, 0.2, 0.2, 0.2, 0.3)
    ),
    8: Hybrid(("ellips", "ackley", "rastrigin", "hgbat", "discus"), (0.2,) * 5),
    9: Hybrid(("bent_cigar", "rastrigin", "grie_rosen", "weierstrass", "escaffer6"), (0.2,) * 5),
    10: Hybrid(
        ("hgbat", "katsuura", "ackley", "rastrigin", "schwefel", "schaffer_f7"),
        (0.1, 0.1, 0.2, 0.2, 0.2, 0.2),
    ),
}
# the composition scales, as the C code writes them: fit = a * fit / b
ELL, ACK, GRI, RAS3 = (1e4, 1e10), (1e3, 100.0), (1e3, 100.0), (1e4, 1e3)
HAP, DIS, ESC, HGB = (1e3, 1e3), (1e4, 1e10), (1e4, 2e7), (1e4, 1e3)
SCH4, BEN, ONE = (1e4, 4e3), (1e4, 1e30), (1.0, 1.0)
_CF17 = {
    1: _cf((P("rosenbrock"), 10, 0, ONE), (P("ellips"), 20, 100, ELL), (P("rastrigin"), 30, 200)),
    2: _cf((P("rastrigin"), 10, 0), (P("griewank"), 20, 100, GRI), (P("schwefel"), 30, 200)),
    3: _cf(
        (P("rosenbrock"), 10, 0),
        (P("ackley"), 20, 100, ACK),
        (P("schwefel"), 30, 200),
        (P("rastrigin"), 40, 300),
    ),  # fmt: skip
    4: _cf(
        (P("ackley"), 10, 0, ACK),
        (P("ellips"), 20, 100, ELL),
        (P("griewank"), 30, 200, GRI),
        (P("rastrigin"), 40, 300),
    ),  # fmt: skip
    5: _cf(
        (P("rastrigin"), 10, 0, RAS3),
        (P("happycat"), 20, 100, HAP),
        (P("ackley"), 30, 200, ACK),
        (P("discus"), 40, 300, DIS),
        (P("rosenbrock"), 50, 400),
    ),  # fmt: skip
    6: _cf(
        (P("escaffer6"), 10, 0, ESC),
        (P("schwefel"), 20, 100),
        (P("griewank"), 20, 200, GRI),
        (P("rosenbrock"), 30, 300),
        (P("rastrigin"), 40, 400, RAS3),
    ),  # fmt: skip
    7: _cf(
        (P("hgbat"), 10, 0, HGB),
        (P("rastrigin"), 20, 100, RAS3),
        (P("schwefel"), 30, 200, SCH4),
        (P("bent_cigar"), 40, 300, BEN),
        (P("ellips"), 50, 400, ELL),
        (P("escaffer6"), 60, 500, ESC),
    ),  # fmt: skip
    8: _cf(
        (P("ackley"), 10, 0, ACK),
        (P("griewank"), 20, 100, GRI),
        (P("discus"), 30, 200, DIS),
        (P("rosenbrock"), 40, 300),
        (P("happycat"), 50, 400, HAP),
        (P("escaffer6"), 60, 500, ESC),
    ),  # fmt: skip
    9: _cf((_HF17[5], 10, 0), (_HF17[6], 30, 100), (_HF17[7], 50, 200)),
    10: _cf((_HF17[5], 10, 0), (_HF17[8], 30, 100), (_HF17[9], 50, 200)),
}
_PLAIN17 = (
    ("BentCigar", "bent_cigar"),
    ("SumDiffPow", "sum_diff_pow"),
    ("Zakharov", "zakharov"),
    ("Rosenbrock", "rosenbrock"),
    ("Rastrigin", "rastrigin"),
    ("SchafferF7", "schaffer_f7"),
    ("LunacekBiRastrigin", "bi_rastrigin"),
    ("NonContRastrigin", "rastrigin"),  # step_rastrigin_func: its rounding is overwritten
    ("Levy", "levy2017"),
    ("Schwefel", "schwefel"),
)

CEC2017 = (
    *(CECFunction(2017, i + 1, nm, P(fn), 100.0 * (i + 1)) for i, (nm, fn) in enumerate(_PLAIN17)),
    *(CECFunction(2017, 10 + k, f"Hybrid{k}", _HF17[k], 100.0 * (10 + k)) for k in range(1, 11)),
    *(CECFunction(2017, 20 + k, f"Composition{k}", _CF17[k], 100.0 * (20 + k)) for k in _CF17),
)
"""CEC 2017 F1-F30 (official numbering; F2 is the official code's sum of different powers)."""

_CF22 = {
    1: _cf(
        (P("rosenbrock"), 10, 0, (1e4, 1e4)),
        (P("ellips"), 20, 200, ELL),
        (P("bent_cigar"), 30, 300, BEN),
        (P("discus"), 40, 100, DIS),
        (P("ellips", rotated=False), 50, 400, ELL),
    ),  # fmt: skip
    2: _cf((P("schwefel", rotated=False), 20, 0), (P("rastrigin"), 10, 200), (P("hgbat"), 10, 100)),
    3: _cf(
        (P("escaffer6"), 20, 0, ESC),
        (P("schwefel"), 20, 200),
        (P("griewank"), 30, 300, GRI),
        (P("rosenbrock"), 30, 400),
        (P("rastrigin"), 20, 200, RAS3),
    ),  # fmt: skip
    4: _cf(
        (P("hgbat"), 10, 0, HGB),
        (P("rastrigin"), 20, 300, RAS3),
        (P("schwefel"), 30, 500, SCH4),
        (P("bent_cigar"), 40, 100, BEN),
        (P("ellips"), 50, 400, ELL),
        (P("escaffer6"), 60, 200, ESC),
    ),  # fmt: skip
}
CEC2022 = (
    CECFunction(2022, 1, "Zakharov", P("zakharov"), 300.0),
    CECFunction(2022, 2, "Rosenbrock", P("rosenbrock"), 400.0),
    CECFunction(2022, 3, "SchafferF7", P("schaffer_f7"), 600.0),
    CECFunction(2022, 4, "NonContRastrigin", P("rastrigin"), 800.0),
    CECFunction(2022, 5, "Levy", P("levy2022"), 900.0),
    CECFunction(
        2022, 6, "Hybrid1", Hybrid(("bent_cigar", "hgbat", "rastrigin"), (0.4, 0.4, 0.2)), 1800.0
    ),
    CECFunction(
        2022,
        7,
        "Hybrid2",
        Hybrid(
            ("hgbat", "katsuura", "ackley", "rastrigin", "schwefel", "schaffer_f7"),
            (0.1, 0.2, 0.2, 0.2, 0.1, 0.2),
        ),
        2000.0,
    ),
    CECFunction(
        2022,
        8,
        "Hybrid3",
        Hybrid(
            ("katsuura", "happycat", "grie_rosen", "schwefel", "ackley"), (0.3, 0.2, 0.2, 0.1, 0.2)
        ),
        2200.0,
    ),
    *(
        CECFunction(2022, 8 + k, f"Composition{k}", _CF22[k], b)
        for k, b in zip(_CF22, (2300.0, 2400.0, 2600.0, 2700.0), strict=True)
    ),  # fmt: skip
)
"""CEC 2022 F1-F12 (official numbering)."""

TABLES = {2017: CEC2017, 2022: CEC2022}
