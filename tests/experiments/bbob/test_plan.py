"""Suite plans: validation messages, the problem grid, task cuts and seeds."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mawdo.experiments import PlanError
from mawdo.experiments.kinds.suite import SuitePlan, parse_ids, preset_plan
from mawdo.experiments.kinds.suite.plan import parse_key, problem_key

BASE = {"algorithms": ["mawdo"], "functions": [1]}


def bad(**fields) -> str:
    with pytest.raises(PlanError) as info:
        SuitePlan.from_dict({**BASE, **fields})
    return str(info.value)


def test_bad_fields_name_the_problem_and_the_fix():
    assert "Did you mean 'bbob'" in bad(suite="bbbo")
    assert "defines functions 1-24" in bad(functions=[25])
    assert "Did you mean 'rastrigin'" in bad(functions=["rastrgin"])
    msg = bad(suite="cec2017", functions=[11], dims=[20])  # official F11: the first hybrid
    assert "f11 is not defined in dimension 20" in msg and "10, 30, 50, 100" in msg
    assert "2, 10, 20" in bad(suite="cec2022", dims=[5])
    assert "only instance 1" in bad(suite="cec2022", instances=[1, 2])
    for b in (0, -1.0, float("nan"), float("inf"), "many"):
        assert "budget" in bad(budget=b) and "evaluations per dimension" in bad(budget=b)
    assert "listed twice" in bad(dims=[5, 5])
    assert "Did you mean 'mawdo'" in bad(algorithms=["mawod"])
    assert "options.mawdo" in bad(options={"mawdo": {"groups": -1}})


def test_names_and_ids_resolve_to_ids():
    plan = SuitePlan.from_dict({**BASE, "functions": ["f3", "sharpridge", 5], "dims": [2]})
    assert plan.functions == (3, 13, 5)
    assert "listed twice" in bad(functions=["f3", "Rastrigin"])
    assert plan.instances == (1, 2, 3, 4, 5)  # COCO's five by default
    assert SuitePlan.from_dict({**BASE, "suite": "CEC2017", "dims": [10]}).instances == (1,)


def test_parse_ids():
    assert parse_ids("1-3,7, 9-10") == [1, 2, 3, 7, 9, 10]
    assert parse_ids("rastrigin,2") == ["rastrigin", 2]
    with pytest.raises(ValueError, match="backwards"):
        parse_ids("5-1", "--functions")
    with pytest.raises(ValueError, match="at least one"):
        parse_ids(" , ", "--dims")


def test_tasks_cover_every_run_once_and_resume_cuts_the_rest():
    plan = SuitePlan.from_dict({**BASE, "functions": [1, 2], "instances": [1, 2],
                                "dims": [2, 5], "runs": 5, "batch_size": 2})  # fmt: skip
    assert plan.total_runs == 2 * 2 * 2 * 5
    keys = [(t.algorithm, t.problem, k) for t in plan.tasks() for k in t.runs]
    assert len(keys) == len(set(keys)) == plan.total_runs
    assert plan.problems[0] == problem_key(1, 1, 5)  # the larger dimension first
    done = set(keys[:7])
    rest = [(t.algorithm, t.problem, k) for t in plan.tasks(done) for k in t.runs]
    assert set(rest) == set(keys) - done and all(t.n_runs <= 2 for t in plan.tasks(done))
    assert parse_key(problem_key(24, 3, 40)) == (24, 3, 40)


def test_numbers_spec_ignores_name_and_batch_size_only():
    plan = SuitePlan.from_dict(BASE)
    assert plan.with_overrides(batch_size=1, name="x").plan_hash == plan.plan_hash
    for change in ({"budget": 2e4}, {"runs": 6}, {"seed": 1}, {"final_target": 1e-6},
                   {"dims": [5]}, {"pop_size": 20}, {"instances": [1]}):  # fmt: skip
        assert plan.with_overrides(**change).plan_hash != plan.plan_hash, change
    spec = plan.task_spec(plan.tasks()[0])
    assert spec["seed_entropy"] == plan.problem_seed(spec["problem"])
    assert spec["seed_entropy"] != plan.problem_seed(problem_key(1, 2, 5))


def test_presets():
    quick, full = preset_plan("bbob-quick"), preset_plan("bbob-full")
    assert full.budget == 1e4 and full.runs >= 5 and full.dims == (5, 20)
    assert full.functions == tuple(range(1, 25)) and full.instances == (1, 2, 3, 4, 5)
    assert {"mawdo", "wdo", "awdo", "gwo", "woa", "mewdo", "cmaes", "random"} <= set(
        full.algorithms
    )
    assert quick.functions == full.functions and quick.dims == full.dims
    with pytest.raises(PlanError, match="Did you mean 'bbob-quick'"):
        preset_plan("bbob-quik")


def test_a_store_of_opfunus_cec2017_keeps_its_plan_and_says_how_its_ids_map(tmp_path):
    import lzma

    from mawdo.experiments import Store
    from mawdo.experiments.kinds.suite import write_suite_report

    db = tmp_path / "old.db"
    root = Path(__file__).resolve().parents[3]
    db.write_bytes(lzma.decompress((root / "docs/results/holdout/cec2017.db.xz").read_bytes()))
    with Store.read(db) as store:  # its stored plan still hashes to its meta row's hash
        plan = store.plan
    assert plan.numbering == "opfunu" and plan.functions == tuple(range(1, 30))
    assert plan.computed_by(1) == ("cec2017-opfunu", 1)
    assert plan.computed_by(2) == ("cec2017-opfunu", 3)  # opfunu's F2 is official F3
    assert "its Fk (k >= 2) is official F(k+1)" in plan.numbering_note()
    with pytest.raises(ValueError, match="Run the official suite into a new store"):
        plan.check_libraries()
    report = write_suite_report(db, tmp_path / "report", plots=False).read_text()
    assert plan.numbering_note() in report
    # a new plan with the same fields means the official functions: another hash
    new = SuitePlan.from_dict(json.loads(plan.to_json()) | {"numbering": None})
    assert new.numbering == "official" and new.plan_hash != plan.plan_hash
    assert new.computed_by(2) == ("cec2017", 2) and new.numbering_note() == ""
    with pytest.raises(PlanError, match="marks stores written when cec2017"):
        SuitePlan.from_dict({**json.loads(plan.to_json()), "numbering": "opfunu"})
    with pytest.raises(PlanError, match="applies to the suites cec2017, cec2022 only"):
        SuitePlan.from_dict({"suite": "bbob", "algorithms": ["random"], "functions": [1],
                             "numbering": "official"})  # fmt: skip
