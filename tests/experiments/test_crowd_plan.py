"""The crowd study's plan: settings, policies, seeds and tasks."""

import pytest

from mawdo.experiments.kinds.crowd.plan import CROWD_PRESETS, CrowdPlan, crowd_preset, parse_setting
from mawdo.experiments.plans import PlanError


def test_settings_parse_and_normalise():
    assert parse_setting("Circle-5-Invisible") == ("circle", 5, False)
    assert parse_setting("square-20-visible") == ("square", 20, True)
    plan = CrowdPlan.from_dict({"settings": ["CIRCLE-5-visible"], "policies": ["straight"]})
    assert plan.settings == ("circle-5-visible",)


@pytest.mark.parametrize("bad", ["circle-51-visible", "circle-5", "ring-5-seen", "circle-5-x"])
def test_a_bad_setting_names_the_form(bad):
    with pytest.raises((ValueError, PlanError), match="<scene>-<people>-<visibility>"):
        CrowdPlan.from_dict({"settings": [bad]})


def test_unknown_policy_suggests_a_close_name():
    with pytest.raises((ValueError, PlanError), match="orca_robot"):
        CrowdPlan.from_dict({"settings": ["circle-5-visible"], "policies": ["orca"]})


def test_bad_sensor_settings_are_refused():
    for field, value in (("sensor_noise", -0.1), ("miss_rate", 1.0), ("sensor_range", 0.0)):
        with pytest.raises((ValueError, PlanError), match=field):
            CrowdPlan.from_dict({"settings": ["circle-5-visible"], field: value})


def test_episode_seeds_are_common_to_policies_and_distinct_across_episodes():
    plan = CrowdPlan.from_dict({"settings": ["circle-5-visible", "square-5-visible"], "n": 4,
                                "policies": ["straight", "mawdo"], "batch_size": 3})  # fmt: skip
    tasks = plan.tasks()
    assert len(tasks) == 2 * 2 * 2  # two batches (3 + 1) per (setting, policy)
    specs = [plan.task_spec(t) for t in tasks]
    by = {(s["algorithm"], s["problem"], s["first_run"]): s["seeds"] for s in specs}
    assert by[("straight", "circle-5-visible", 0)] == by[("mawdo", "circle-5-visible", 0)]
    assert by[("straight", "circle-5-visible", 0)] != by[("straight", "square-5-visible", 0)]
    seeds = by[("mawdo", "circle-5-visible", 0)] + by[("mawdo", "circle-5-visible", 3)]
    assert len(set(seeds)) == 4
    assert plan.total_runs == 16


def test_done_runs_are_not_planned_again():
    plan = CrowdPlan.from_dict({"settings": ["circle-5-visible"], "n": 3, "policies": ["straight"]})
    left = plan.tasks(done={("straight", "circle-5-visible", 1)})
    assert sorted(r for t in left for r in t.runs) == [0, 2]


def test_presets_build_and_an_unknown_one_lists_them():
    for name in CROWD_PRESETS:
        assert crowd_preset(name).name == name
    with pytest.raises(PlanError, match="crowdnav-quick"):
        crowd_preset("crowdnav-quik")


@pytest.mark.parametrize("name", ["woa", "gwo", "wdo_plus"])
def test_a_refiner_policy_is_the_mawdo_policy_with_its_optimizer(name):
    from mawdo.optimizers import OPTIMIZERS
    from mawdo.planning.run.policies import POLICIES, make_policy

    options = {"preset": None, "overrides": {}, "noise": 2.0, "predictor": "constant_velocity"}
    ours, base = make_policy(name, options), make_policy("mawdo", options)
    assert name in OPTIMIZERS and POLICIES[name].knowledge == "observed"
    assert (ours.algorithm, base.algorithm) == (name, "mawdo")
    assert ours.config == base.config and ours.config.time_guide  # the same planner settings
    assert (ours.knowledge, ours.predictor) == (base.knowledge, base.predictor) == (
        "observed", "constant_velocity")  # fmt: skip
    assert ours.tracker.noise == base.tracker.noise == 2.0
    plan = CrowdPlan.from_dict({"settings": ["circle-5-invisible"], "policies": ["mawdo", name]})
    assert plan.policies == ("mawdo", name)


def test_strays_reach_the_observing_trackers_and_only_a_plan_with_them_changes_hash(monkeypatch):
    from mawdo.experiments.kinds.crowd.execute import run_one
    from mawdo.planning.run import policies

    base = {"settings": ["circle-5-invisible"], "n": 1, "policies": ["dwa"]}
    plain, off = CrowdPlan.from_dict(base), CrowdPlan.from_dict({**base, "strays": False})
    on = CrowdPlan.from_dict({**base, "strays": True})
    # a plan made before the field existed keeps its hash; turning it on makes another plan
    assert "strays" not in plain.numbers_spec()
    assert plain.plan_hash == off.plan_hash != on.plan_hash
    assert "strays" in on.describe() and "strays" not in plain.describe()
    with pytest.raises((ValueError, PlanError), match="strays"):
        CrowdPlan.from_dict({**base, "strays": "yes"})
    for name in ("mawdo", "dwa"):
        assert policies.POLICIES[name].make({"strays": True}).tracker.strays is True
        assert policies.POLICIES[name].make({}).tracker.strays is False
    made = []
    tracker = policies.study_tracker
    monkeypatch.setattr(policies, "study_tracker", lambda o: made.append(tracker(o)) or made[-1])
    for plan, want in ((on, True), (plain, False)):
        spec = plan.task_spec(plan.tasks()[0])
        run_one(spec, "circle-5-invisible", spec["seeds"][0])  # the study's own path
        assert made[-1].strays is want
