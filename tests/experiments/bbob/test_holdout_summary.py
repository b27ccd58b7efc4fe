"""The hold-out summary's statistics on a suite small enough to rank by hand, and its command's
refusal of a store that is not a hold-out store."""

from __future__ import annotations

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

from mawdo.experiments.kinds.suite.holdout_data import HoldoutSuite
from mawdo.experiments.kinds.suite.holdout_summary import (
    _gap,
    full_evaluations,
    mean_ranks,
    place,
    suite_sentence,
    versus,
)


@pytest.fixture
def suite() -> HoldoutSuite:
    """Three algorithms, three functions, two runs asked.

    Medians, floored at 1e-8: F1 cmaes 1e-8 (0, 0), wdo_plus 1e-8 (1e-9, 3e-9: below the floor),
    gwo 2; F2 cmaes 1, wdo_plus 3, gwo 0.5; F3 only cmaes (one run), so F3 is not ranked.
    Ranks by hand: F1 cmaes 1.5, wdo_plus 1.5, gwo 3; F2 gwo 1, cmaes 2, wdo_plus 3;
    means cmaes 1.75, gwo 2.0, wdo_plus 2.25.
    """
    a = np.array
    finals = {
        ("cmaes", "F1"): a([0.0, 0.0]),
        ("wdo_plus", "F1"): a([1e-9, 3e-9]),
        ("gwo", "F1"): a([1.0, 3.0]),
        ("cmaes", "F2"): a([1.0, 1.0]),
        ("wdo_plus", "F2"): a([4.0, 2.0]),
        ("gwo", "F2"): a([0.5, 0.5]),
        ("cmaes", "F3"): a([5.0]),
    }
    return HoldoutSuite(
        key="cec2017",
        title="CEC 2017 F1-F3, D = 10",
        protocol="10000 evaluations per run (1000 x D), 2 runs",
        algorithms=("cmaes", "wdo_plus", "gwo"),
        functions=("F1", "F2", "F3"),
        finals=finals,
        runs=2,
        dims=(10,),
        evals=10_000,
        store="x.db",
    )


def test_ranks_places_and_ties_match_the_hand_count(suite):
    ranks, n = mean_ranks(suite)
    assert n == 2
    assert ranks == pytest.approx({"cmaes": 1.75, "wdo_plus": 2.25, "gwo": 2.0})
    assert [place(ranks, a) for a in ("cmaes", "gwo", "wdo_plus")] == [1, 2, 3]
    # F1: both below the 1e-8 floor, a tie; F3: wdo_plus has no run, left out
    assert versus(suite, "wdo_plus", "cmaes") == ([], ["F2"], ["F1"])
    assert versus(suite, "wdo_plus", "gwo") == (["F1"], ["F2"], [])
    assert _gap(suite) == "F3 (cmaes, wdo_plus, gwo)"


def test_missing_functions_are_named_and_untouched_ones_given_as_ranges(suite):
    finals = {k: v for k, v in suite.finals.items() if k[1] == "F1"}
    finals["gwo", "F2"] = np.array([1.0, 2.0])
    cut = dataclasses.replace(suite, functions=("F1", "F2", "F3", "F4", "F5"), finals=finals)
    assert _gap(cut) == "F2 (cmaes, wdo_plus); no run on F3-F5"
    assert _gap(dataclasses.replace(suite, finals={}, functions=("F1", "F3"))) == (
        "no run on F1, F3"
    )


def test_the_sentence_names_who_is_ahead_and_the_goal(suite):
    line = suite_sentence(suite)
    assert line.startswith(
        "CEC 2017 F1-F3, D = 10, 10000 evaluations per run (1000 x D), 2 runs, 2 functions: "
        "WDO+ 2.25, place 3 of 3, behind CMA-ES 1.75, GWO 2.00 (WDO+'s design goal, second only "
        "to CMA-ES, is not met)"
    )
    assert line.endswith(
        "better / worse / tied on 0 / 1 / 1 against CMA-ES, 1 / 1 / 0 against GWO."
    )


def test_full_protocol_evaluations_counted_from_the_presets():
    # CEC 2017: 29 functions x 10 algorithms x 10 runs x (10 000 x 10 + 10 000 x 30)
    assert full_evaluations("cec2017") == 29 * 10 * 10 * 400_000
    # CEC 2022: 12 x 10 x 10 x (200 000 at D = 10 + 1 000 000 at D = 20)
    assert full_evaluations("cec2022") == 12 * 10 * 10 * 1_200_000


def test_a_store_of_another_study_is_refused_with_the_fix(tmp_path):
    from mawdo.experiments import Store
    from mawdo.experiments.kinds.suite import preset_plan

    db = tmp_path / "bbob.db"
    Store.open(db, preset_plan("bbob-quick")).close()
    cmd = [sys.executable, "-m", "mawdo.experiments.kinds.suite.holdout_summary", str(db)]
    done = subprocess.run([*cmd, "--out", str(tmp_path / "out")], capture_output=True, text=True)
    assert done.returncode == 2
    assert "error:" in done.stderr and "not a hold-out store" in done.stderr
    assert "CEC 2017 / 2022 suite stores" in done.stderr and "Traceback" not in done.stderr
    assert not (tmp_path / "out" / "summary.md").exists()


def test_a_missing_store_is_named_without_a_traceback(tmp_path):
    missing = tmp_path / "cec2017.db"
    cmd = [sys.executable, "-m", "mawdo.experiments.kinds.suite.holdout_summary", str(missing)]
    done = subprocess.run([*cmd, "--out", str(tmp_path / "out")], capture_output=True, text=True)
    assert done.returncode == 2
    assert f"error: no results store at {missing}" in done.stderr
    assert "Traceback" not in done.stderr
    assert not (tmp_path / "out").exists()
