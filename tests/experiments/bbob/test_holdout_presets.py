"""Issue 29's hold-out presets: each CEC suite at its own budget, the paper's suite both ways,
the issue's ten algorithms everywhere."""

from __future__ import annotations

from mawdo.experiments.kinds.benchmark.plan import preset_plan as benchmark_preset
from mawdo.experiments.kinds.suite import preset_plan
from mawdo.suites import evaluation_budget

TEN = {"cmaes", "scipy_de", "random", "gwo", "woa", "wdo", "awdo", "mawdo", "mewdo", "wdo_plus"}


def test_cec_presets_use_each_suites_own_budget_and_dimensions():
    c17 = preset_plan("holdout-cec2017")
    assert c17.suite == "cec2017" and c17.dims == (10, 30) and len(c17.functions) == 29
    # CEC 2017: 10 000 D evaluations per run
    assert [evaluation_budget(c17.budget, d) for d in c17.dims] == [100_000, 300_000]
    # CEC 2022: 200 000 evaluations at D = 10, 1 000 000 at D = 20
    for name, dim, evals in (
        ("holdout-cec2022-d10", 10, 200_000),
        ("holdout-cec2022-d20", 20, 1_000_000),
    ):
        plan = preset_plan(name)
        assert plan.suite == "cec2022" and plan.dims == (dim,) and len(plan.functions) == 12
        assert evaluation_budget(plan.budget, dim) == evals
    for name in ("holdout-cec2017", "holdout-cec2022-d10", "holdout-cec2022-d20"):
        assert set(preset_plan(name).algorithms) == TEN


def test_paper_presets_cover_f1_f16_unshifted_and_shifted_at_equal_evaluations():
    plain, shifted = benchmark_preset("holdout-paper"), benchmark_preset("holdout-paper-shifted")
    for plan in (plain, shifted):
        assert set(plan.algorithms) == TEN and len(plan.functions) == 16
        assert plan.budget == "evals" and plan.pop_size * plan.max_iter == 25_000
        assert plan.options["cmaes"] == {"auto_pop_size": True}
    assert not plain.shifted and shifted.shifted


def test_quick_presets_are_the_full_ones_cut_only_in_dimension_budget_and_runs():
    """The committed study (docs/results/holdout) runs ``holdout-quick-*``: D = 10, 1000 x D
    evaluations, 2 runs; everything else (suite, functions, algorithms, seed) as the full
    presets, so its runs are those the full plans would make at these settings."""
    for quick, full in (
        ("holdout-quick-cec2017", "holdout-cec2017"),
        ("holdout-quick-cec2022", "holdout-cec2022-d10"),
    ):
        q, f = preset_plan(quick), preset_plan(full)
        assert q.dims == (10,) and q.runs == 2 and evaluation_budget(q.budget, 10) == 10_000
        for field in ("suite", "functions", "algorithms", "instances", "seed"):
            assert getattr(q, field) == getattr(f, field), field
