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


def test_separation_is_the_smallest_during_a_step_not_at_its_ends():
    from mawdo.planning.run.episode import run_episode
    from mawdo.planning.world.scenario import scenario_from_dict
    from mawdo.planning.world.stepped import SteppedWorld

    # a disc of radius 2 crossing x = 50 at 16 px per step (at t = 2.5), 10 px above a robot of
    # radius 3 that stands at (50, 50): at the ends of step 2 it is 8 px to either side (gap
    # 12.8 - 5), mid-step right above it (gap 10 - 5 = 5 px)
    sc = scenario_from_dict({
        "schema_version": 1, "width": 200.0, "height": 100.0, "start": [50.0, 50.0],
        "goal": [150.0, 50.0], "robot": {"radius": 3.0, "speed": 4.0},
        "obstacles": [{"shape": "circle", "center": [10.0, 60.0], "radius": 2.0,
                       "motion": {"velocity": [16.0, 0.0]}}],
    })  # fmt: skip

    class Stand:
        def reset(self, scenario, seed): ...

        def act(self, reading):
            return np.zeros(2)

    res = run_episode(SteppedWorld(sc), Stand(), 3, seed=0)
    sep = separations(res)
    assert sep[2] == pytest.approx(5.0)
    ends = np.hypot(8.0, 10.0) - 5.0  # at either end of the step
    assert sep[1] == pytest.approx(ends) and sep[2] < ends  # step 1 is closest at its end


def test_a_running_study_says_how_many_episodes_each_figure_rests_on(store, tmp_path):
    # one policy has fewer episodes than the others (a study still running): the sentence
    # names the count most policies have and the one that differs, not one count for all
    import shutil
    import sqlite3

    from mawdo.experiments.kinds.crowd.figures import rates_title
    from mawdo.experiments.kinds.crowd.report import crowd_headline, episodes_phrase

    assert episodes_phrase({"a": 3, "b": 3}) == "3 episodes"
    assert episodes_phrase({"a": 50, "b": 90, "c": 50}) == (
        "50 episodes (b 90; the study is incomplete)")  # fmt: skip
    part = tmp_path / "part.db"
    shutil.copy(store, part)
    con = sqlite3.connect(part)
    with con:
        con.execute("DELETE FROM runs WHERE algorithm = 'straight' AND run = 2")
    con.close()
    with Store.read(part) as s:
        (line,) = crowd_headline(s)
        title = rates_title(s.plan, crowd_summary(s))
    assert line.startswith(
        "- circle-3-invisible, 3 episodes (straight 2; the study is incomplete):"
    )
    assert title == "tiny: 2-3 of 3 episodes per setting and policy (incomplete)"
    with Store.read(store) as s:
        (line,) = crowd_headline(s)
        title = rates_title(s.plan, crowd_summary(s))
    assert line.startswith("- circle-3-invisible, 3 episodes:")
    assert title == "tiny: 3 episodes per setting"
