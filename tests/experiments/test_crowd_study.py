"""The crowd study end to end: stored rows against the same episodes recomputed directly, the
report's table against the rows, and hand-checkable metrics of the straight-line robot."""

import numpy as np
import pytest

from mawdo.experiments.kinds.crowd import CrowdPlan, crowd_summary, write_crowd_report
from mawdo.experiments.kinds.crowd.execute import episode_row, run_one, separations
from mawdo.experiments.runner import run_plan
from mawdo.experiments.store import Store

PLAN = {"name": "tiny", "settings": ["circle-3-invisible"], "n": 3,
        "policies": ["straight", "orca_robot"], "batch_size": 2}  # fmt: skip


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    path = tmp_path_factory.mktemp("crowd") / "tiny.db"
    run_plan(CrowdPlan.from_dict(PLAN), path, progress=False)
    return path


def test_stored_rows_are_the_episodes_recomputed_alone(store):
    plan = CrowdPlan.from_dict(PLAN)
    with Store.read(store) as s:
        rows = {(a, r.run): r for a, _, r in s.rows()}
    assert len(rows) == 6 and all(r.status == "ok" for r in rows.values())
    for (policy, k), r in rows.items():
        spec = plan.task_spec(next(t for t in plan.tasks() if t.algorithm == policy))
        res, scene = run_one(spec, "circle-3-invisible", plan.episode_seed("circle-3-invisible", k))
        m = episode_row(res, scene)
        assert (r.success, r.robot_caused, r.steps) == (m["success"], m["robot_caused"], m["steps"])
        assert r.min_separation_m == pytest.approx(m["min_separation_m"], abs=1e-12)


def test_the_report_table_averages_the_stored_rows(store, tmp_path):
    path = write_crowd_report(store, tmp_path, figures=False)
    text = path.read_text()
    with Store.read(store) as s:
        summary = crowd_summary(s)
        rows = [r for a, _, r in s.rows() if a == "orca_robot"]
    assert summary[("circle-3-invisible", "orca_robot")]["success"] == pytest.approx(
        np.mean([r.success for r in rows]))  # fmt: skip
    assert "| circle-3-invisible | orca_robot | 3 |" in text


def test_a_straight_line_robot_measures_as_by_hand():
    spec = {"algorithm": "straight", "preset": "realtime", "overrides": {}, "predictor": "stop",
            "sensor": {"noise": 0.0, "range": None, "miss_rate": 0.0}}  # fmt: skip
    res, scene = run_one(spec, "circle-0-invisible", 0)  # nobody in the way
    m = episode_row(res, scene)
    # 8 m from (0, -4) to (0, 4) at 1 m/s in 0.25 s steps; done within the robot's radius
    # (0.3 m) of the goal: after 31 steps, 7.75 m
    assert m["success"] == 1 and m["steps"] == 31
    assert m["time_s"] == pytest.approx(7.75) and m["length_m"] == pytest.approx(7.75)
    assert m["discomfort"] == 0.0 and np.all(np.isinf(separations(res)))
