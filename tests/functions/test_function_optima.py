"""Optima: ``f(x_star) == f_star`` for every function, and docs/functions.md#f-table's table
(bounds, D, f*).

Equality is exact (``==``) for every registered function: the formulas are written so that the
optimum evaluates to the stated value bit for bit on any CPU (no SIMD ``pow``; Ackley, Easom and
the penalized functions use argument forms that are exact at the optimum; the low-dimensional
``x_star`` were picked within ~1e-9 of the refined minimiser where the evaluation is exact).
"""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.functions import ALTERNATES, FUNCTIONS, PAPER_SUITE, get_function

ALL = list(FUNCTIONS)

# docs/functions.md#f-table table, copied independently of the package: id -> (name, D, lb, ub, f*).
SPEC_TABLE = {
    "F1": ("sphere", 30, -100, 100, 0.0),
    "F2": ("schwefel_2_22", 30, -100, 100, 0.0),
    "F3": ("schwefel_1_2", 30, -100, 100, 0.0),
    "F4": ("schwefel_2_21", 30, -100, 100, 0.0),
    "F5": ("rosenbrock", 30, -30, 30, 0.0),
    "F6": ("quartic", 30, -1.28, 1.28, 0.0),
    "F7": ("rastrigin", 30, -100, 100, 0.0),
    "F8": ("schaffer_f7", 30, -100, 100, 0.0),
    "F9": ("penalized_1", 30, -50, 50, 0.0),
    "F10": ("penalized_2", 30, -50, 50, 0.0),
    "F11": ("alpine_n1", 30, -10, 10, 0.0),
    "F12": ("six_hump_camel", 2, -5, 5, -1.0316284534898774),
    "F13": ("hartmann_6", 6, 0, 1, -3.3223680114155147),
    "F14": ("shekel_5", 4, 0, 10, -10.153199679058227),
    "F15": ("shekel_7", 4, 0, 10, -10.40294056681866),
    "F16": ("shekel_10", 4, 0, 10, -10.536409816692043),
}

# Customary boxes and optima of the alternates (docs/functions.md#f-f12-f16 and the brief).
ALT_TABLE = {
    "easom": (2, -100, 100, -1.0),
    "goldstein_price": (2, -2, 2, 3.0),
    "kowalik": (4, -5, 5, 0.0003074859878056061),
    "ackley": (30, -32, 32, 0.0),
    "six_hump_camel_no_cross": (2, -5, 5, -1.0),
    "f8_paper_literal": (30, -100, 100, -36.25),
    "penalized_1_no_pi_over_n": (30, -50, 50, 0.0),
    "quartic_noiseless": (30, -1.28, 1.28, 0.0),
}


@pytest.mark.parametrize("name", ALL)
def test_f_of_x_star_is_f_star_exactly(name):
    f = FUNCTIONS[name]
    assert f.func(f.x_star[None, :])[0] == f.f_star
    if not f.noise:
        assert f(f.x_star) == f.f_star


@pytest.mark.parametrize("name", ALL)
def test_x_star_inside_box(name):
    f = FUNCTIONS[name]
    assert f.x_star.shape == f.lb.shape == f.ub.shape == (f.dim,)
    assert np.all(f.lb <= f.x_star) and np.all(f.x_star <= f.ub)


@pytest.mark.parametrize("name", ALL)
def test_x_star_is_a_local_minimiser(name):
    """No point in a small cloud around x_star is lower than f_star (beyond rounding)."""
    f = FUNCTIONS[name]
    rng = np.random.default_rng(7)
    for radius in (1e-6, 1e-4, 1e-2):
        X = np.clip(f.x_star + rng.uniform(-radius, radius, (2000, f.dim)), f.lb, f.ub)
        values = f.func(X)
        assert np.all(values >= f.f_star - 1e-12 * max(1.0, abs(f.f_star))), (name, radius)


@pytest.mark.parametrize("paper_id", list(SPEC_TABLE))
def test_paper_table_matches_spec(paper_id):
    name, dim, lo, hi, f_star = SPEC_TABLE[paper_id]
    f = get_function(paper_id)
    assert (f.name, f.paper_id, f.dim, f.f_star) == (name, paper_id, dim, f_star)
    np.testing.assert_array_equal(f.lb, np.full(dim, float(lo)))
    np.testing.assert_array_equal(f.ub, np.full(dim, float(hi)))


def test_paper_suite_order_and_flags():
    assert PAPER_SUITE == tuple(SPEC_TABLE[f"F{i}"][0] for i in range(1, 17))
    unimodal = [FUNCTIONS[n].multimodal for n in PAPER_SUITE[:6]]
    multimodal = [FUNCTIONS[n].multimodal for n in PAPER_SUITE[6:]]
    assert not any(unimodal) and all(multimodal)  # the paper's "Type" column
    assert [FUNCTIONS[n].scalable for n in PAPER_SUITE] == [True] * 11 + [False] * 5
    assert [n for n in FUNCTIONS if FUNCTIONS[n].noise] == ["quartic"]


@pytest.mark.parametrize("name", list(ALT_TABLE))
def test_alternate_boxes_and_optima(name):
    dim, lo, hi, f_star = ALT_TABLE[name]
    f = FUNCTIONS[name]
    assert f.paper_id is None and name in ALTERNATES
    assert (f.dim, f.f_star) == (dim, f_star)
    assert np.all(f.lb == lo) and np.all(f.ub == hi)


def test_known_minimisers_of_alternates():
    np.testing.assert_array_equal(FUNCTIONS["easom"].x_star, [np.pi, np.pi])
    np.testing.assert_array_equal(FUNCTIONS["goldstein_price"].x_star, [0.0, -1.0])
    lit = FUNCTIONS["f8_paper_literal"]
    np.testing.assert_array_equal(np.diff(lit.x_star), np.full(29, -2.5))
    f11 = FUNCTIONS["f11_paper_literal"]
    assert f11.f_star == pytest.approx(-23.837470126845847, rel=1e-12)
    # cos(x) + 0.2 x = 0 at the per-coordinate minimiser of sin(x) + 0.1 x^2
    assert abs(np.cos(f11.x_star[0]) + 0.2 * f11.x_star[0]) < 1e-15
    assert np.all(f11.x_star == f11.x_star[0])


def test_printed_f8_and_f11_are_not_minimised_at_the_origin():
    """Why docs/functions.md#f-f8 rejects the printed formulas: the paper's minf = 0 is not
    their minimum."""
    for name in ("f8_paper_literal", "f11_paper_literal"):
        f = FUNCTIONS[name]
        assert f(np.zeros(30)) == 0.0
        assert f.f_star < -20.0


def test_six_hump_camel_mirror_optimum():
    f = FUNCTIONS["six_hump_camel"]
    assert f(-f.x_star) == f.f_star  # the formula is symmetric under x -> -x


@pytest.mark.parametrize(
    ("name", "dim"),
    [("sphere", 1), ("sphere", 5), ("rosenbrock", 2), ("rosenbrock", 10), ("quartic", 50),
     ("rastrigin", 3), ("schaffer_f7", 2), ("penalized_1", 1), ("penalized_1", 7),
     ("penalized_2", 1), ("penalized_2", 12), ("alpine_n1", 100), ("ackley", 2),
     ("f8_paper_literal", 2), ("f8_paper_literal", 81), ("f11_paper_literal", 3),
     ("penalized_1_no_pi_over_n", 4), ("schwefel_1_2", 64)],
)  # fmt: skip
def test_with_dim_keeps_optimum_exact(name, dim):
    f = get_function(name, dim=dim)
    assert f.dim == dim and f.x_star.shape == (dim,)
    assert f.func(f.x_star[None, :])[0] == f.f_star
    assert np.all(f.lb <= f.x_star) and np.all(f.x_star <= f.ub)


def test_f8_literal_optimum_scales():
    for dim in (2, 10, 30, 81):
        assert get_function("f8_paper_literal", dim=dim).f_star == -1.25 * (dim - 1)
    with pytest.raises(ValueError, match="staircase"):
        get_function("f8_paper_literal", dim=82)  # span 2.5 * 81 > 200: no closed form
