"""The registry: canonical names, paper-id aliases, presets and helpful errors."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.functions import ALTERNATES, FUNCTIONS, PAPER_SUITE, get_function
from mawdo.registry import Registry, UnknownNameError


def test_registry_lists_canonical_names_once():
    assert isinstance(FUNCTIONS, Registry)
    assert list(FUNCTIONS) == [*PAPER_SUITE, *ALTERNATES]
    assert len(FUNCTIONS) == len(PAPER_SUITE) + len(ALTERNATES) == 26
    assert len(PAPER_SUITE) == 16
    assert set(ALTERNATES) == {
        "quartic_noiseless", "f8_paper_literal", "f11_paper_literal", "ackley",
        "penalized_1_no_pi_over_n", "six_hump_camel_no_cross", "hartmann_6_mirjalili_typo",
        "easom", "goldstein_price", "kowalik",
    }  # fmt: skip
    for name in FUNCTIONS:
        assert FUNCTIONS[name].name == name


@pytest.mark.parametrize("i", range(1, 17))
def test_paper_ids_are_case_insensitive_aliases(i):
    f = FUNCTIONS[PAPER_SUITE[i - 1]]
    assert f.paper_id == f"F{i}"
    assert FUNCTIONS[f"F{i}"] is f and FUNCTIONS[f"f{i}"] is f
    assert f"f{i}" in FUNCTIONS and f"f{i}" not in list(FUNCTIONS)
    assert FUNCTIONS.canonical(f"f{i}") == f.name


def test_names_are_case_insensitive():
    assert FUNCTIONS["Rastrigin"] is FUNCTIONS["rastrigin"] is get_function("RASTRIGIN")


@pytest.mark.parametrize(
    ("typo", "suggestion"),
    [("rastrign", "rastrigin"), ("sphear", "sphere"), ("shekel5", "shekel_5"),
     ("penalised_2", "penalized_2")],
)  # fmt: skip
def test_unknown_name_suggests_close_names(typo, suggestion):
    with pytest.raises(UnknownNameError, match=f"Did you mean .*'{suggestion}'") as info:
        get_function(typo)
    assert isinstance(info.value, KeyError) and isinstance(info.value, ValueError)
    assert "F1..F16" in str(info.value)


def test_unknown_paper_id():
    with pytest.raises(KeyError, match="unknown function 'F17'"):
        FUNCTIONS["F17"]
    assert "F17" not in FUNCTIONS


def test_aliases_cannot_shadow_names():
    with pytest.raises(ValueError, match="already taken"):
        FUNCTIONS.add_alias("f1", "ackley")
    with pytest.raises(ValueError, match="already taken"):
        FUNCTIONS.add_alias("sphere", "ackley")
    with pytest.raises(ValueError, match="already an alias"):
        FUNCTIONS.register("F3", FUNCTIONS["ackley"])
    with pytest.raises(ValueError, match="already registered"):
        FUNCTIONS.register("Sphere", FUNCTIONS["ackley"])
    assert FUNCTIONS.aliases["f7"] == "rastrigin"
    assert len(FUNCTIONS) == 26  # the refused registrations left nothing behind


def test_standard_preset_bounds():
    f2 = get_function("F2", preset="standard")
    f7 = get_function("f7", preset="standard")
    assert np.all(f2.lb == -10) and np.all(f2.ub == 10) and f2.f_star == 0.0
    assert np.all(f7.lb == -5.12) and np.all(f7.ub == 5.12) and f7(f7.x_star) == 0.0
    # the preset changes F2 and F7 only
    for name in PAPER_SUITE:
        if name in ("schwefel_2_22", "rastrigin"):
            continue
        std, paper = get_function(name, preset="standard"), FUNCTIONS[name]
        np.testing.assert_array_equal(std.lb, paper.lb, err_msg=name)
        np.testing.assert_array_equal(std.ub, paper.ub, err_msg=name)
    # paper preset keeps Table 2's [-100, 100]
    assert np.all(get_function("F7", preset="paper").ub == 100)
    # presets apply after dim
    assert get_function("F2", dim=3, preset="standard").ub.tolist() == [10.0] * 3


def test_unknown_preset():
    with pytest.raises(ValueError, match="unknown preset 'cec'; choose one of paper, standard"):
        get_function("F1", preset="cec")


def test_get_function_default_is_the_registered_record():
    assert get_function("sphere") is FUNCTIONS["sphere"]
