"""Experiment plans: presets, tasks, hashing, seeding and field-level validation errors."""

from __future__ import annotations

import zlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mawdo.experiments import PRESETS, ExperimentPlan, PlanError, Task, preset_plan
from mawdo.functions import PAPER_SUITE, get_function
from mawdo.optimizers import ABLATION_ALGORITHMS, PAPER_ALGORITHMS

from .conftest import small_plan

BASE = {"algorithms": ["gwo", "mawdo"], "functions": ["sphere"]}


def errors_of(**fields) -> str:
    with pytest.raises(PlanError) as info:
        ExperimentPlan.from_dict({**BASE, **fields})
    return str(info.value)


# ---------------------------------------------------------------------------- presets
def test_paper_presets_follow_the_protocol():
    t3 = preset_plan("paper-table3")
    assert t3.algorithms == PAPER_ALGORITHMS
    assert t3.functions == PAPER_SUITE
    assert (t3.runs, t3.pop_size, t3.max_iter) == (30, 50, 500)
    assert (t3.shifted, t3.budget) == (False, "iterations")
    assert preset_plan("paper-ablation").algorithms == ABLATION_ALGORITHMS
    assert preset_plan("paper-table3-shifted").shifted is True
    assert preset_plan("paper-table3-evals").budget == "evals"
    # Variants of Table 3 share the master seed, so they differ only in what they say they do.
    seeds = {preset_plan(n).seed for n in PRESETS if n.startswith("paper")}
    assert len(seeds) == 1


@pytest.mark.parametrize("name", list(PRESETS))
def test_every_preset_is_valid_and_cuts_into_tasks(name):
    plan = preset_plan(name)
    tasks = plan.tasks()
    assert sum(t.n_runs for t in tasks) == plan.total_runs
    assert all(1 <= t.n_runs <= plan.batch_size for t in tasks)


def test_unknown_preset_suggests_a_name():
    with pytest.raises(PlanError, match="preset: unknown preset 'paper-tabel3'.*'paper-table3'"):
        preset_plan("paper-tabel3")


# ---------------------------------------------------------------------------- tasks
@settings(max_examples=60, deadline=None)
@given(runs=st.integers(1, 40), batch=st.integers(1, 12), data=st.data())
def test_tasks_cover_exactly_the_missing_runs(runs, batch, data):
    plan = ExperimentPlan.from_dict({**BASE, "runs": runs, "batch_size": batch})
    keys = [(a, f, k) for a in plan.algorithms for f in plan.functions for k in range(runs)]
    done = set(data.draw(st.lists(st.sampled_from(keys), unique=True)))
    tasks = plan.tasks(done)
    computed = [(t.algorithm, t.problem, k) for t in tasks for k in t.runs]
    assert len(computed) == len(set(computed))  # no run twice
    assert set(computed) == set(keys) - done  # exactly the missing ones
    assert all(1 <= t.n_runs <= batch for t in tasks)


def test_task_grid_without_resume():
    plan = ExperimentPlan.from_dict({**BASE, "runs": 5, "batch_size": 2})
    assert plan.tasks()[:3] == [
        Task("gwo", "sphere", 0, 2),
        Task("gwo", "sphere", 2, 2),
        Task("gwo", "sphere", 4, 1),
    ]


# ---------------------------------------------------------------------------- identity
def test_plan_hash_ignores_spelling_label_and_batching():
    a = ExperimentPlan.from_dict({**BASE, "options": {"mawdo": {"groups": 4, "eta": 0.3}}})
    b = ExperimentPlan.from_dict(
        {
            "algorithms": ["GWO", "MAWDO"],
            "functions": ["F1"],
            "name": "other",
            "batch_size": 3,
            "options": {"MAWDO": {"eta": 0.3, "groups": 4}, "gwo": {}},
        }
    )
    assert a.plan_hash == b.plan_hash
    assert len(a.plan_hash) == 64


@pytest.mark.parametrize(
    "change",
    [
        {"runs": 29},
        {"seed": 1},
        {"pop_size": 40},
        {"max_iter": 499},
        {"shifted": True},
        {"budget": "evals"},
        {"bounds_preset": "standard"},
        {"options": {"mawdo": {"groups": 4}}},
        {"functions": ["sphere", "rastrigin"]},
        {"algorithms": ["mawdo", "gwo"]},
    ],
)
def test_plan_hash_changes_with_anything_that_affects_numbers(change):
    assert (
        ExperimentPlan.from_dict({**BASE, **change}).plan_hash
        != ExperimentPlan.from_dict(BASE).plan_hash
    )


def test_plan_json_round_trip():
    plan = small_plan(options={"mawdo": {"groups": 4}})
    again = ExperimentPlan.from_json(plan.to_json())
    assert again == plan and again.plan_hash == plan.plan_hash


# ---------------------------------------------------------------------------- seeds
def test_function_seeds_are_distinct_and_shared_by_algorithms():
    plan = preset_plan("paper-table3")
    seeds = {tuple(plan.function_seed(f)) for f in PAPER_SUITE}
    assert len(seeds) == len(PAPER_SUITE)
    assert plan.function_seed("sphere") == [plan.seed, zlib.crc32(b"sphere")]
    specs = [plan.task_spec(Task(a, "sphere", 0, 10)) for a in plan.algorithms]
    assert len({tuple(s["seed_entropy"]) for s in specs}) == 1


def test_shift_seed_is_shared_by_algorithms_and_moves_the_optimum():
    plan = preset_plan("paper-table3-shifted")
    specs = [plan.task_spec(Task(a, "rastrigin", 0, 10)) for a in plan.algorithms]
    assert len({s["shift_seed"] for s in specs}) == 1
    assert specs[0]["shift_seed"] != plan.shift_seed("sphere")
    f = get_function("rastrigin", shifted=True, shift_seed=specs[0]["shift_seed"])
    assert not np.allclose(f.x_star, 0.0)
    # the unshifted plan never asks for a shift
    assert preset_plan("paper-table3").task_spec(Task("gwo", "sphere", 0, 1))["shift_seed"] is None


# ---------------------------------------------------------------------------- validation
def test_unknown_algorithm_names_index_and_suggests():
    msg = errors_of(algorithms=["gwo", "wdo", "mawod"])
    assert msg.startswith("algorithms[2]: unknown algorithm 'mawod'.")
    assert "Did you mean 'mawdo'" in msg


def test_unknown_function_names_index_and_suggests():
    msg = errors_of(functions=["sphere", "rastrign"])
    assert msg.startswith("functions[1]: unknown function 'rastrign'.")
    assert "'rastrigin'" in msg


@pytest.mark.parametrize("field", ["algorithms", "functions"])
def test_empty_lists_are_refused(field):
    assert errors_of(**{field: []}) == f"{field}: must not be empty: list at least one name"


@pytest.mark.parametrize(
    "fields, expected",
    [
        ({"runs": 0}, "runs: must be >= 1 (got 0)"),
        ({"pop_size": 1}, "pop_size: must be >= 2 (got 1)"),
        ({"max_iter": -5}, "max_iter: must be >= 1 (got -5)"),
        ({"seed": -1}, "seed: must be >= 0 (got -1)"),
        ({"runs": 2.5}, "runs: must be an integer (got 2.5)"),
        ({"runs": True}, "runs: must be an integer, not true/false (got True)"),
        ({"shifted": "yes"}, "shifted: must be true or false (got 'yes')"),
        ({"budget": "time"}, "budget: must be one of 'iterations' or 'evals' (got 'time')"),
        ({"batch_size": 0}, "batch_size: must be >= 1 (got 0)"),
    ],
)
def test_bad_scalar_fields_are_named(fields, expected):
    assert errors_of(**fields) == expected


def test_unknown_field_suggests_the_right_one():
    assert errors_of(runz=3).startswith("runz: unknown field. Did you mean 'runs'?")


def test_duplicates_are_refused():
    assert (
        errors_of(functions=["sphere", "F1"])
        == "functions[1]: 'sphere' is listed twice (also functions[0])"
    )


def test_options_are_checked_at_plan_time():
    assert "options.mawdo" in errors_of(options={"mawdo": {"grups": 4}})
    assert "Did you mean 'groups'" in errors_of(options={"mawdo": {"grups": 4}})
    assert errors_of(options={"wdo": {"alpha": 0.1}}).startswith(
        "options.wdo: 'wdo' is not one of the plan's algorithms"
    )
    assert errors_of(options={"mawdo": {"pop_size": 10}}).startswith("options.mawdo.pop_size:")


def test_several_errors_are_all_reported():
    msg = errors_of(runs=0, budget="x")
    assert "runs: must be >= 1" in msg and "budget: must be one of" in msg


def test_overrides_are_validated():
    plan = preset_plan("smoke")
    assert plan.with_overrides(runs=2, functions=["F7"]).functions == ("rastrigin",)
    with pytest.raises(PlanError, match=r"^runs: must be >= 1"):
        plan.with_overrides(runs=0)
    # options of algorithms dropped by an override go with them
    p = small_plan(options={"mawdo": {"groups": 4}}).with_overrides(algorithms=["gwo"])
    assert p.options == {}


# ---------------------------------------------------------------------------- TOML
def test_toml_plan_loads(tmp_path):
    f = tmp_path / "plan.toml"
    f.write_text(
        'algorithms = ["gwo", "MAWDO"]\nfunctions = ["F7", "F12"]\nruns = 3\n'
        "pop_size = 10\nmax_iter = 20\n[options.mawdo]\ngroups = 4\n"
    )
    plan = ExperimentPlan.from_toml(f)
    assert plan.algorithms == ("gwo", "mawdo")
    assert plan.functions == ("rastrigin", "six_hump_camel")
    assert plan.options == {"mawdo": {"groups": 4}}


def test_toml_preset_with_overrides(tmp_path):
    f = tmp_path / "plan.toml"
    f.write_text('[plan]\npreset = "paper-table3"\nruns = 5\n')
    plan = ExperimentPlan.from_toml(f)
    assert plan.runs == 5 and plan.algorithms == PAPER_ALGORITHMS


def test_toml_invalid_field_names_file_and_field(tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text('algorithms = ["gwo"]\nfunctions = ["sphere"]\nruns = 0\n')
    with pytest.raises(PlanError) as info:
        ExperimentPlan.from_toml(f)
    assert str(info.value) == f"{f}: runs: must be >= 1 (got 0)"


def test_toml_syntax_error_and_missing_file(tmp_path):
    f = tmp_path / "broken.toml"
    f.write_text("runs = = 3\n")
    with pytest.raises(PlanError, match="not valid TOML"):
        ExperimentPlan.from_toml(f)
    with pytest.raises(PlanError, match="cannot read plan file"):
        ExperimentPlan.from_toml(tmp_path / "absent.toml")
