"""The benchmark records: every formula with its paper bounds, dimension and optimum
(docs/functions.md#f-table).

This module only builds :class:`BenchmarkFunction` records; :mod:`mawdo.functions.registry`
puts them in the registry. Optima of the low-dimensional functions are hard-coded: ``f_star`` is
docs/functions.md#f-table's exact value (or, for alternates without one, the best known value), and
``x_star`` is a
float64 point within about 1e-9 of the minimiser refined with ``scipy.optimize.minimize`` at
which this package's evaluation returns exactly ``f_star`` (on any CPU: the formulas avoid
CPU-specific SIMD powers, and Hartmann's point was checked with both numpy's and libm's ``exp``).
"""

from __future__ import annotations

from functools import partial

import numpy as np

from . import alternates, low_dim, multimodal, unimodal
from .base import BenchmarkFunction

PAPER_DIM = 30
"""Dimension of the scalable paper functions F1-F11 (paper Table 2)."""


# --- optimum rules for scalable functions: (dim, lb, ub) -> (x_star, f_star) ---------------------


def uniform_optimum(dim: int, lb: np.ndarray, ub: np.ndarray, *, value: float, f_star: float):
    """Optimum at ``x_i = value`` for every ``i`` with a dimension-independent ``f_star``."""
    return np.full(dim, value), f_star


def f8_literal_optimum(dim: int, lb: np.ndarray, ub: np.ndarray):
    """Staircase minimiser ``x_i = c - 2.5 (i - 1)`` of ``f8_paper_literal``; ``f* = -1.25 (n-1)``.

    ``c`` is 0 when the staircase fits in the box (the json's ``literal_minimizer``), else the
    value nearest 0 that fits; a box narrower than the staircase has no closed-form minimum.
    """
    steps = -alternates.F8_LITERAL_STEP * np.arange(dim)  # 2.5 (i - 1)
    lo, hi = np.max(lb + steps), np.min(ub + steps)
    if lo > hi:
        raise ValueError(
            f"f8_paper_literal: the minimising staircase (span {steps[-1]}) does not fit in the "
            "box; its minimum there has no closed form"
        )
    c = float(np.clip(0.0, lo, hi))
    return c - steps, -1.25 * (dim - 1)


def f11_literal_optimum(dim: int, lb: np.ndarray, ub: np.ndarray):
    """``x_i = -1.30644...`` for all ``i``; ``f_star`` is the float evaluation there (about
    ``-0.79458 n``; the per-coordinate minimum has no closed form)."""
    x_star = np.full(dim, alternates.F11_LITERAL_XMIN)
    return x_star, float(alternates.f11_paper_literal(x_star[None, :])[0])


def _scalable(name, paper_id, func, lb, ub, x0, f_star, *, multimodal, description, **kw):
    """A scalable record at the paper dimension whose optimum is ``x_i = x0`` everywhere."""
    rule = partial(uniform_optimum, value=x0, f_star=f_star)
    return BenchmarkFunction(
        name=name,
        paper_id=paper_id,
        dim=PAPER_DIM,
        lb=lb,
        ub=ub,
        f_star=f_star,
        x_star=np.full(PAPER_DIM, x0),
        func=func,
        multimodal=multimodal,
        scalable=True,
        description=description,
        optimum=rule,
        **kw,
    )


def _fixed(name, paper_id, func, lb, ub, x_star, f_star, *, description, multimodal=True):
    """A fixed-dimension record (``dim = len(x_star)``)."""
    return BenchmarkFunction(
        name=name,
        paper_id=paper_id,
        dim=len(x_star),
        lb=lb,
        ub=ub,
        f_star=f_star,
        x_star=np.array(x_star),
        func=func,
        multimodal=multimodal,
        scalable=False,
        description=description,
    )


def paper_suite() -> list[BenchmarkFunction]:
    """F1-F16 with the paper's bounds and dimensions, in paper order (the table in
    docs/functions.md#f-table)."""
    return [
        _scalable("sphere", "F1", unimodal.sphere, -100, 100, 0.0, 0.0,
                  multimodal=False, description="sum x_i^2"),
        _scalable("schwefel_2_22", "F2", unimodal.schwefel_2_22, -100, 100, 0.0, 0.0,
                  multimodal=False, description="sum |x_i| + prod |x_i|"),
        _scalable("schwefel_1_2", "F3", unimodal.schwefel_1_2, -100, 100, 0.0, 0.0,
                  multimodal=False, description="sum_i (sum_{j<=i} x_j)^2"),
        _scalable("schwefel_2_21", "F4", unimodal.schwefel_2_21, -100, 100, 0.0, 0.0,
                  multimodal=False, description="max_i |x_i|"),
        _scalable("rosenbrock", "F5", unimodal.rosenbrock, -30, 30, 1.0, 0.0, multimodal=False,
                  min_dim=2, description="sum_{i<n} 100 (x_{i+1} - x_i^2)^2 + (x_i - 1)^2"),
        _scalable("quartic", "F6", unimodal.quartic, -1.28, 1.28, 0.0, 0.0, multimodal=False,
                  noise=True,
                  description="sum i x_i^4 + U[0,1) (one draw per evaluation; f* of the "
                  "noiseless part)"),
        _scalable("rastrigin", "F7", multimodal.rastrigin, -100, 100, 0.0, 0.0, multimodal=True,
                  description="sum x_i^2 - 10 cos(2 pi x_i) + 10"),
        _scalable("schaffer_f7", "F8", multimodal.schaffer_f7, -100, 100, 0.0, 0.0,
                  multimodal=True, min_dim=2,
                  description="[(1/(n-1)) sum_{i<n} sqrt(z_i) (1 + sin^2(50 z_i^0.2))]^2, "
                  "z_i = sqrt(x_i^2 + x_{i+1}^2) (CEC form)"),
        _scalable("penalized_1", "F9", multimodal.penalized_1, -50, 50, -1.0, 0.0,
                  multimodal=True,
                  description="(pi/n){10 sin^2(pi y_1) + sum_{i<n} (y_i-1)^2 [1 + 10 sin^2(pi "
                  "y_{i+1})] + (y_n-1)^2} + sum u(x_i,10,100,4), y = 1 + (x+1)/4"),
        _scalable("penalized_2", "F10", multimodal.penalized_2, -50, 50, 1.0, 0.0,
                  multimodal=True,
                  description="0.1{sin^2(3 pi x_1) + sum_{i<n} (x_i-1)^2 [1 + sin^2(3 pi "
                  "x_{i+1})] + (x_n-1)^2 [1 + sin^2(2 pi x_n)]} + sum u(x_i,5,100,4)"),
        _scalable("alpine_n1", "F11", multimodal.alpine_n1, -10, 10, 0.0, 0.0, multimodal=True,
                  description="sum |x_i sin(x_i) + 0.1 x_i|"),
        _fixed("six_hump_camel", "F12", low_dim.six_hump_camel, -5, 5,
               (0.08984201297760874, -0.712656403733768), -1.0316284534898774,
               description="4x1^2 - 2.1x1^4 + x1^6/3 + x1 x2 - 4x2^2 + 4x2^4"),
        _fixed("hartmann_6", "F13", low_dim.hartmann_6, 0, 1,
               (0.20168951197684198, 0.15001069405378037, 0.4768739780360168,
                0.27533243152039244, 0.31165161678169556, 0.657300534562226),
               -3.3223680114155147,
               description="-sum_{i=1..4} c_i exp(-sum_j a_ij (x_j - p_ij)^2), standard P"),
        _fixed("shekel_5", "F14", low_dim.shekel_5, 0, 10,
               (4.000037154191488, 4.000133278257923, 4.00003715057007, 4.000133273073),
               -10.153199679058227,
               description="-sum_{i=1..5} 1 / ((x - a_i)^T (x - a_i) + c_i)"),
        _fixed("shekel_7", "F15", low_dim.shekel_7, 0, 10,
               (4.000572915812876, 4.000689363563623, 3.9994897069549156, 3.999606160561094),
               -10.40294056681866,
               description="-sum_{i=1..7} 1 / ((x - a_i)^T (x - a_i) + c_i)"),
        _fixed("shekel_10", "F16", low_dim.shekel_10, 0, 10,
               (4.000746533338028, 4.000592933860526, 3.9996633978592273, 3.999509799668913),
               -10.536409816692043,
               description="-sum_{i=1..10} 1 / ((x - a_i)^T (x - a_i) + c_i)"),
    ]  # fmt: skip


def alternate_functions() -> list[BenchmarkFunction]:
    """Literal readings and forensic alternates (docs/functions.md#f-decisions), with their
    customary boxes."""
    f8_x, f8_f = f8_literal_optimum(
        PAPER_DIM, np.full(PAPER_DIM, -100.0), np.full(PAPER_DIM, 100.0)
    )
    f11_x, f11_f = f11_literal_optimum(
        PAPER_DIM, np.full(PAPER_DIM, -10.0), np.full(PAPER_DIM, 10.0)
    )
    return [
        _scalable("quartic_noiseless", None, unimodal.quartic, -1.28, 1.28, 0.0, 0.0,
                  multimodal=False, description="sum i x_i^4 (F6 without its noise)"),
        BenchmarkFunction(
            name="f8_paper_literal", paper_id=None, dim=PAPER_DIM, lb=-100, ub=100,
            f_star=f8_f, x_star=f8_x, func=alternates.f8_paper_literal, multimodal=False,
            scalable=True, min_dim=2, optimum=f8_literal_optimum,
            description="sum_{i=2..n} s_i + 0.2 s_i^2, s_i = x_i - x_{i-1} (paper F8 as "
            "printed; min -1.25 (n-1))",
        ),
        BenchmarkFunction(
            name="f11_paper_literal", paper_id=None, dim=PAPER_DIM, lb=-10, ub=10,
            f_star=f11_f, x_star=f11_x, func=alternates.f11_paper_literal, multimodal=True,
            scalable=True, optimum=f11_literal_optimum,
            description="sum sin(x_i) + 0.1 x_i^2 (paper F11 as printed; min about -0.7946 n)",
        ),
        _scalable("ackley", None, multimodal.ackley, -32, 32, 0.0, 0.0, multimodal=True,
                  description="-20 exp(-0.2 sqrt(mean x^2)) - exp(mean cos(2 pi x)) + 20 + e"),
        _scalable("penalized_1_no_pi_over_n", None, alternates.penalized_1_no_pi_over_n, -50, 50,
                  -1.0, 0.0, multimodal=True,
                  description="penalized_1 without the pi/n factor (paper F9 as printed)"),
        _fixed("six_hump_camel_no_cross", None, low_dim.six_hump_camel_no_cross, -5, 5,
               (0.0, 0.7071067811865476), -1.0,
               description="4x1^2 - 2.1x1^4 + x1^6/3 - 4x2^2 + 4x2^4 (camel without x1 x2)"),
        _fixed("hartmann_6_mirjalili_typo", None, low_dim.hartmann_6_mirjalili_typo, 0, 1,
               (0.20170761497818948, 0.1467809428783033, 0.4767448507125674,
                0.27534239286692397, 0.31165187630365676, 0.657275163211762),
               -3.3219951715842417,
               description="hartmann_6 with P[3][2] = 0.1415, 1-based (standard .1451; GWO code)"),
        _fixed("easom", None, low_dim.easom, -100, 100, (np.pi, np.pi), -1.0,
               description="-cos(x1) cos(x2) exp(-((x1 - pi)^2 + (x2 - pi)^2))"),
        _fixed("goldstein_price", None, low_dim.goldstein_price, -2, 2, (0.0, -1.0), 3.0,
               description="[1 + (x1+x2+1)^2 (19 - 14x1 + 3x1^2 - 14x2 + 6x1x2 + 3x2^2)] "
               "[30 + (2x1-3x2)^2 (18 - 32x1 + 12x1^2 + 48x2 - 36x1x2 + 27x2^2)]"),
        _fixed("kowalik", None, low_dim.kowalik, -5, 5,
               (0.19283345343783603, 0.19083623345623815, 0.12311729432845042,
                0.13576598791490968),
               0.0003074859878056061,
               description="sum_i [a_i - x1 (b_i^2 + b_i x2) / (b_i^2 + b_i x3 + x4)]^2, "
               "11-point data; best known f*"),
    ]  # fmt: skip
