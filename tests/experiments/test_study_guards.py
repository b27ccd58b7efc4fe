"""Guards of the planning study kind (issue 12): the plan holds its scenario, a computed run
survives failing metrics, and the planner reports progress without changing its result."""

from __future__ import annotations

import json

import numpy as np
import pytest

from mawdo.experiments import PlanError
from mawdo.experiments.kinds.planning import StudyPlan, execute_planning_task, study_preset
from mawdo.planning import get_scenario

SMOKE = study_preset("study-smoke")


def test_the_plan_holds_the_scenario_contents_and_their_hash():
    plan = SMOKE
    assert plan.scenario == "paper"
    assert plan.scenario_spec == get_scenario("paper").to_dict()
    assert len(plan.scenario_sha256) == 64
    again = StudyPlan.from_json(plan.to_json())
    assert again == plan and again.plan_hash == plan.plan_hash


def test_edited_contents_change_the_plan_hash_whatever_the_name():
    spec = get_scenario("paper").to_dict()
    moved = {**spec, "start": [spec["start"][0] + 5.0, spec["start"][1]]}
    data = {**SMOKE.model_dump(mode="json"), "scenario_spec": moved}
    data.pop("scenario_sha256")
    edited = StudyPlan.from_dict(data)
    assert edited.scenario == "paper"
    assert edited.plan_hash != SMOKE.plan_hash
    assert edited.scenario_object().start.tolist() == moved["start"]


def test_a_stored_plan_never_resolves_a_name_or_a_file(tmp_path):
    data = SMOKE.model_dump(mode="json")
    data.pop("scenario_spec")
    data.pop("scenario_sha256")
    assert StudyPlan.from_dict(data).plan_hash == SMOKE.plan_hash  # a user's plan: resolved
    with pytest.raises(PlanError, match="no scenario contents"):
        StudyPlan.from_dict(data, stored=True)


def test_a_scenario_hash_that_does_not_match_is_refused():
    data = {**SMOKE.model_dump(mode="json"), "scenario_sha256": "0" * 64}
    with pytest.raises(PlanError, match="scenario_sha256.*edited"):
        StudyPlan.from_dict(data)


def test_overriding_the_scenario_replaces_its_contents(tmp_path):
    spec = get_scenario("paper").to_dict()
    f = tmp_path / "other.json"
    f.write_text(json.dumps({**spec, "name": "other", "goal": [300.0, 340.0]}))
    plan = SMOKE.with_overrides(scenario=str(f))
    assert plan.scenario == "other" and plan.scenario_spec["goal"] == [300.0, 340.0]
    assert plan.tasks()[0].problem == "other"


def _spec(plan, algorithm="gwo"):
    (task, *_) = [t for t in plan.tasks() if t.algorithm == algorithm]
    return {**plan.task_spec(task), "seeds": plan.task_spec(task)["seeds"][:1], "n_runs": 1}


def _route(row) -> list:
    """The executed route of a stored row (its bytes also hold wall-clock latencies)."""
    from mawdo.planning.run.planner import result_from_bytes

    return result_from_bytes(row.route, SMOKE.scenario_object()).route.tolist()


def test_failing_snapshot_metrics_keep_the_run(monkeypatch):
    import mawdo.planning.judge.metrics as metrics

    real = metrics.run_metrics

    def flaky(res, l_star=None, snapshots=8):
        if snapshots:
            raise MemoryError("oracle wants 95 GiB")
        return real(res, l_star=l_star, snapshots=0)

    spec = _spec(SMOKE)
    (whole,) = execute_planning_task(spec)
    monkeypatch.setattr(metrics, "run_metrics", flaky)
    (row,) = execute_planning_task(spec)
    assert row.error_text is None and _route(row) == _route(whole)
    assert "oracle wants 95 GiB" in row.metrics["metrics_error"]
    assert row.metrics["length_px"] == whole.metrics["length_px"]
    assert np.isnan(row.metrics["snapshot_gap_median"])


def test_failing_metrics_and_oracle_still_store_the_route(monkeypatch):
    import mawdo.planning.judge.metrics as metrics

    def broken(*a, **k):
        raise MemoryError("no memory")

    spec = _spec(SMOKE)
    (whole,) = execute_planning_task(spec)
    monkeypatch.setattr(metrics, "run_metrics", broken)
    monkeypatch.setattr(metrics, "static_optimum", broken)
    (row,) = execute_planning_task(spec)
    assert row.metrics is None and _route(row) == _route(whole)
    assert "static optimum" in row.error_text and "no memory" in row.error_text
    assert np.array_equal(row.first_plan_curve, whole.first_plan_curve)


def test_planner_progress_is_called_per_step_and_changes_nothing():
    from mawdo.planning.run.planner import plan

    calls = []
    sc = get_scenario("paper")
    a = plan(sc, algorithm="gwo", seed=3, config="quick", max_steps=12)
    b = plan(
        sc,
        algorithm="gwo",
        seed=3,
        config="quick",
        max_steps=12,
        progress=lambda *args: calls.append(args),
    )
    assert np.array_equal(a.route, b.route)
    steps = [c[0] for c in calls]
    assert steps == list(range(len(steps))) and steps[-1] == 12
    assert {c[1] for c in calls} == {12}
    assert calls[-1][2] == len(b.replans)
    assert [c[2] for c in calls] == sorted(c[2] for c in calls)  # replans only grow
