"""The component study (issue 29): its presets, and the effect measures against values worked out
independently (numerical integration of the ECDF, aRT by hand, a store run through the CLI)."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from mawdo import make_optimizer
from mawdo.experiments.kinds.suite import PRESETS, preset_plan
from mawdo.experiments.kinds.suite.components import (
    BASE_SWITCHES,
    component_variants,
    parse_label,
    switch_options,
)
from mawdo.experiments.kinds.suite.data import StoredRun, StudyRuns
from mawdo.experiments.kinds.suite.effects import (
    EffectData,
    centre_pull,
    effect_tables,
    run_area,
)
from mawdo.experiments.kinds.suite.metrics import aggregate_runtime, runtime_ecdf


def test_component_presets_build_and_every_variant_is_its_base_with_the_switch():
    full, quick = preset_plan("wdo-components"), preset_plan("wdo-components-quick")
    assert full.dims == (5, 20) and full.instances == (1, 2, 3, 4, 5)
    assert full.functions == tuple(range(1, 25)) and quick.dims == (5,)
    for label, base in full.variants.items():
        b, names = parse_label(label)
        assert b == base and names
        want = make_optimizer(base, **switch_options(base, names)).params
        got = make_optimizer(base, **full.options[label]).params
        assert got == want != make_optimizer(base).params  # each variant changes something
    singles = {v for v in quick.variants}
    assert singles == {f"{b}-{s}" for b, ss in BASE_SWITCHES.items() for s in ss}
    pairs = [v for v in full.variants if "+" in v]
    assert "mawdo-grav_none+grav_mean" not in pairs  # two gravity targets: not a pair
    assert "mawdo-norestart+noobl" not in pairs  # norestart already drops OBL
    assert "mawdo-flat+noclamp" in pairs
    assert len(pairs) == math.comb(12, 2) - 3 - 1
    assert {"wdo-components", "wdo-components-quick"} <= set(PRESETS)


def test_bad_component_labels_are_refused():
    for bad in ("gwo-flat", "wdo-nogroups", "mawdo-wings"):
        with pytest.raises(ValueError, match="not a component variant"):
            parse_label(bad)
    assert component_variants(pairs=False, bases=("wdo",))["algorithms"][0] == "wdo"


def test_run_area_is_the_mean_height_of_the_runtime_ecdf():
    # the closed form against a numerical integral of runtime_ecdf over log(evaluations / D)
    rng = np.random.default_rng(3)
    dim, budget = 5, 1000.0
    rt = np.where(rng.random((4, 51)) < 0.6, 10 ** rng.uniform(0, 4, (4, 51)), np.inf)
    grid = np.exp(np.linspace(0, math.log(budget), 200001))
    heights = np.array([runtime_ecdf([r[None, :]], grid, dim) for r in rt])
    np.testing.assert_allclose(run_area(rt, dim, budget), heights.mean(axis=1), atol=2e-5)


def test_stacked_aggregate_runtime_equals_one_call_per_sample():
    rng = np.random.default_rng(4)
    rt = np.where(rng.random((7, 6, 3)) < 0.5, rng.uniform(1, 100, (7, 6, 3)), np.inf)
    spent = rng.uniform(100, 200, (7, 6))
    stacked = aggregate_runtime(rt, spent)
    for k in range(7):
        np.testing.assert_array_equal(stacked[k], aggregate_runtime(rt[k], spent[k]))


def _run(algo, fid, inst, run, evals, values, budget=100, best_x=(0.0, 0.0)):
    return StoredRun(algo, fid, inst, 2, run, "f", 0.0, np.array(evals), np.array(values),
                     budget, budget, np.array(best_x))  # fmt: skip


def _study(runs) -> StudyRuns:
    algos = tuple(dict.fromkeys(r.algorithm for r in runs))
    return StudyRuns("bbob", algos, (1, 2), (2,), 50.0, runs, 0)


def test_effects_by_hand_on_a_two_unit_study():
    # base reaches 1e-8 at 40 evaluations on f1 (both units) and never on f2; the variant is
    # twice as fast on f1, and on f2 reaches 1.0 at 10 evaluations in unit (1, 0) only.
    runs = []
    for inst, run in ((1, 0), (2, 0)):
        runs += [_run("wdo", 1, inst, run, [40], [0.0]), _run("wdo", 2, inst, run, [1], [500.0])]
        runs += [_run("wdo-flat", 1, inst, run, [20], [0.0])]
        f2 = ([1, 10], [500.0, 1.0]) if inst == 1 else ([1], [500.0])
        runs += [_run("wdo-flat", 2, inst, run, *f2)]
    runs += [_run("random", f, i, 0, [1], [500.0]) for f in (1, 2) for i in (1, 2)]
    study = _study(runs)
    data = EffectData(study, 2, ["wdo", "wdo-flat"])
    budget, dim = 50.0, 2
    # f1: every target at 40 (base) or 20 (variant) evaluations: area 1 - log(rt/D)/log(budget)
    a_base = 1 - math.log(40 / dim) / math.log(budget)
    a_var = 1 - math.log(20 / dim) / math.log(budget)
    np.testing.assert_allclose(data.area["wdo", 1], [a_base] * 2)
    np.testing.assert_allclose(data.area["wdo-flat", 1], [a_var] * 2)
    # f2: the variant's unit (1, 0) reaches the 11 targets 1e2..1e0 at 10 evaluations
    a2 = 11 / 51 * (1 - math.log(10 / dim) / math.log(budget))
    np.testing.assert_allclose(data.area["wdo-flat", 2], [a2, 0.0])
    mean, lo, hi = data.area_effect("wdo-flat", "wdo", (1, 2))
    assert mean == pytest.approx(100 * ((a_var - a_base) + a2 / 2) / 2)
    # two units: a resample holds both, or one twice; the CI spans those three means
    per_unit = 100 * (np.array([a_var - a_base] * 2) + np.array([a2, 0.0])) / 2
    assert lo >= per_unit.min() - 1e-12 and hi <= per_unit.max() + 1e-12 and lo < mean < hi
    ratio, rlo, rhi, cells, gained, lost = data.art_ratio("wdo-flat", "wdo", (1, 2))
    assert ratio == pytest.approx(0.5) and rlo == pytest.approx(0.5) == rhi
    assert (cells, gained, lost) == (5, 1, 0)  # f1 at its 5 targets; f2 at 1e1 by the variant
    tables = {t.name: t for t in effect_tables(study, 2)}
    assert set(tables) == {"effects_area_d2", "effects_art_d2", "effects_bases_d2",
                           "effects_centre_d2"}  # fmt: skip
    assert tables["effects_centre_d2"].rows[0][1:] == [0.0, 0.0]  # every best_x at the centre
    assert tables["effects_area_d2"].rows == [tables["effects_area_d2"].rows[0]]
    assert tables["effects_area_d2"].rows[0][:2] == ["wdo-flat", "wdo"]
    levels = tables["effects_bases_d2"].rows  # the base and the other algorithms, not variants
    assert [row[0] for row in levels] == ["wdo", "random"]
    assert levels[0][1] == pytest.approx(100 * a_base / 2) and levels[1][1] == 0.0


def test_centre_pull_is_the_position_along_centre_to_optimum():
    import ioh  # the bbob extra, installed with the dev extras

    x1 = np.asarray(ioh.get_problem(1, 1, 2, ioh.ProblemClass.REAL).optimum.x)
    x2 = np.asarray(ioh.get_problem(1, 2, 2, ioh.ProblemClass.REAL).optimum.x)
    ortho = np.array([-x1[1], x1[0]])  # a step across the line does not count
    runs = [
        _run("wdo", 1, 1, 0, [1], [1.0], best_x=0.25 * x1 + ortho),
        _run("wdo", 1, 1, 1, [1], [1.0], best_x=x1),
        _run("wdo", 1, 2, 0, [1], [1.0], best_x=0.5 * x2),
    ]
    study = StudyRuns("bbob", ("wdo",), (1,), (2,), 50.0, runs, 0)
    assert centre_pull(study, "wdo", (1,), 2) == pytest.approx(0.5)  # median of 0.25, 1, 0.5


@pytest.mark.slow
def test_component_study_report_through_the_cli(tmp_path):
    store, out = tmp_path / "c.db", tmp_path / "rep"
    cli = [sys.executable, "-m", "mawdo.cli", "study"]
    sets = ["functions=1,15", "instances=1", "runs=2", "budget=30"]
    run = subprocess.run(
        [*cli, "run", "wdo-components-quick", "--out", str(store), "--no-progress",
         *(a for s in sets for a in ("--set", s))],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr
    rep = subprocess.run([*cli, "report", str(store), "--out", str(out), "--option", "plots=false"],
                         capture_output=True, text=True, timeout=600)  # fmt: skip
    assert rep.returncode == 0, rep.stderr
    text = (out / "effects_area_d5.md").read_text()
    for label in ("mawdo-grav_best", "awdo-coef_mean", "wdo-noclamp", "mawdo-norestart"):
        assert f"| {label} |" in text
    assert "aRT(variant) / aRT(base)" in (out / "report.md").read_text()
    assert (out / "effects_art_d5.csv").exists() and (out / "effects_bases_d5.md").exists()
