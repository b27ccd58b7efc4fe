"""WDO+ as a base of the component study: its switches, labels and CEC 2017 preset."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from mawdo import make_optimizer
from mawdo.experiments.kinds.suite import PRESETS, preset_plan
from mawdo.experiments.kinds.suite.components import (
    PLUS_SWITCHES,
    component_presets,
    component_variants,
    parse_label,
    switch_options,
)
from mawdo.experiments.kinds.suite.data import StoredRun, StudyRuns
from mawdo.experiments.kinds.suite.effects import component_pairs
from mawdo.experiments.kinds.suite.measures import groups
from mawdo.optimizers.wdo_plus import WDOPlusParams

# Each switch by hand: the WDO+ field it turns and the value it gets (WDO's choice).
BY_HAND = {
    "origin": {"centre": "origin"},
    "best": {"centre": "best"},
    "nopressure": {"random_pressure": False},
    "noadapt": {"adapt": False, "sigma0": 0.0},
    "norestart": {"restart": False},
    "clip": {"boundary": "clip"},
}


@pytest.mark.parametrize("switch", sorted(BY_HAND))
def test_each_switch_turns_exactly_its_fields(switch):
    default = WDOPlusParams()
    got = make_optimizer("wdo_plus", **switch_options("wdo_plus", (switch,))).params
    changed = {k for k in BY_HAND[switch] if getattr(default, k) != BY_HAND[switch][k]}
    assert changed == set(BY_HAND[switch])  # every field differs from the default
    assert got == WDOPlusParams(**BY_HAND[switch])
    assert parse_label(f"wdo_plus-{switch}") == ("wdo_plus", (switch,))


def test_all_five_changes_off_is_wdo_s_move():
    """The five switches together are what wdo_plus.py names WDO's move."""
    five = ("origin", "nopressure", "noadapt", "norestart", "clip")
    p = make_optimizer("wdo_plus", **switch_options("wdo_plus", five)).params
    assert (p.centre, p.random_pressure, p.adapt, p.sigma0, p.restart, p.boundary) == (
        "origin", False, False, 0.0, False, "clip",
    )  # fmt: skip
    assert set(PLUS_SWITCHES) == set(BY_HAND)


def test_plus_labels_are_refused_on_other_bases_and_unknown_switches():
    for bad in ("wdo_plus-grav_best", "wdo_plus-wings", "wdo-origin", "mawdo-noadapt"):
        with pytest.raises(ValueError, match="not a component variant"):
            parse_label(bad)
    assert parse_label("wdo_plus") == ("wdo_plus", ())


def test_the_wind_bases_presets_do_not_change():
    """Adding WDO+ leaves the BBOB presets' variants (and so their stores' plans) alone."""
    assert component_variants(pairs=False)["algorithms"][:3] == ["wdo", "awdo", "mawdo"]
    assert not any(a.startswith("wdo_plus") for a in PRESETS["wdo-components"]["algorithms"])
    full, _ = component_presets(0)
    assert len(full["wdo-components"]["algorithms"]) == 3 + 6 + 7 + 12 + 62


def test_the_cec_preset_plans_the_documented_study():
    plan = preset_plan("wdo-plus-components-cec2017")
    singles = [f"wdo_plus-{s}" for s in PLUS_SWITCHES]
    assert plan.algorithms == ("wdo_plus", *singles, "wdo", "jso")
    assert (plan.suite, plan.functions, plan.dims, plan.instances) == (
        "cec2017", tuple(range(1, 31)), (10,), (1,),
    )  # fmt: skip
    assert plan.budget == 1e4 and plan.runs == 51 and plan.numbering == "official"
    assert plan.total_runs == 9 * 30 * 51 == 13770
    assert plan.total_evaluations == 13770 * 100_000
    for label in singles:
        got = make_optimizer(plan.variants[label], **plan.options[label]).params
        assert got == make_optimizer("wdo_plus", **BY_HAND[label.split("-")[1]]).params
    # the same seeds as the official preset at D = 10: WDO+, WDO and jSO make its runs
    official = preset_plan("cec2017-official")
    assert plan.problem_seed("f05_i01_d10") == official.problem_seed("f05_i01_d10")


def _study(algorithms) -> StudyRuns:
    runs = [
        StoredRun(a, f, 1, 10, 0, "F", 0.0, np.array([1]), np.array([1.0]), 1, 1, np.zeros(10))
        for a in algorithms
        for f in range(1, 31)
    ]
    return StudyRuns("cec2017", tuple(algorithms), tuple(range(1, 31)), (10,), 1e4, runs, 0)


def test_effects_pair_every_plus_variant_with_its_base_and_cec_groups_are_official():
    algos = ["wdo_plus", "wdo_plus-clip", "wdo_plus-origin", "wdo", "jso"]
    assert component_pairs(_study(algos)) == [
        ("wdo_plus-clip", "wdo_plus"), ("wdo_plus-origin", "wdo_plus"),
    ]  # fmt: skip
    # Awad et al. 2016, Table I: unimodal F1-F3, simple multimodal F4-F10, hybrid F11-F20,
    # composition F21-F30
    assert groups(_study(algos)) == {
        "all functions": tuple(range(1, 31)),
        "unimodal": (1, 2, 3),
        "simple multimodal": (4, 5, 6, 7, 8, 9, 10),
        "hybrid": tuple(range(11, 21)),
        "composition": tuple(range(21, 31)),
    }


def test_a_store_in_opfunu_numbering_gets_no_groups():
    """Its ids are opfunu's (F2 missing, the rest shifted): the official groups do not apply."""
    study = _study(["wdo_plus"])
    old = replace(study, numbering="opfunu")
    assert groups(old) == {"all functions": tuple(range(1, 31))}
