"""The planner registry (issue 26): a planner registered in this file alone runs through the
arena and its report; every registered planner returns a PlanResult whose metrics agree with
an independent check of its route; one step-limit rule; the run loop builds its optimizer once.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest

from mawdo.experiments import PlanError, Store, run_plan
from mawdo.experiments.kinds.arena import ArenaPlan, arena_tables, write_arena_report
from mawdo.planning import (
    PLANNERS,
    PlannerConfig,
    PlanResult,
    Replan,
    check_trajectory,
    plan,
    run_metrics,
    scenario_from_dict,
    scenario_optimum,
)
from mawdo.planning.baselines import ompl_available
from mawdo.planning.run.config import step_limit
from mawdo.planning.run.planners import PlannerSpec
from mawdo.planning.run.result import Drive
from mawdo.planning.world.path import advance

NAME = "static_optimum_follower"


def follow_static_optimum(scenario, seed, config: PlannerConfig) -> PlanResult:
    """A throw-away planner: drive the exact static optimum at the robot's speed, blind to
    the moving obstacles, under the shared step limit."""
    opt = scenario_optimum(scenario)  # static obstacles only
    v = scenario.robot_speed
    limit, _ = step_limit(config.max_steps, scenario.straight_line_length(), opt.length, v)
    pos, remainder, drive = scenario.start.copy(), opt.path, Drive(scenario.start)
    reason = "step limit reached before the goal"
    for step in range(limit + 1):
        if np.hypot(*(scenario.goal - pos)) <= 1e-9:
            reason = "goal reached"
            break
        if step == limit:
            break
        pos, remainder, passed, frac = advance(remainder, v)
        drive.move(step, pos, passed, frac)
    first = Replan(0, scenario.start.copy(), opt.path[1:-1], float("nan"), opt.length, 0, 0.0,
                   0, np.zeros(0))  # fmt: skip
    return drive.result(reason, scenario, algorithm=NAME, seed=seed, config=config,
                        replans=[first])  # fmt: skip


@pytest.fixture
def registered(monkeypatch):
    """The throw-away planner, registered for one test (the registry is left as it was)."""
    spec = PlannerSpec(NAME, follow_static_optimum, sees_time="no", seeded=False,
                       description="the static optimum, followed blind")  # fmt: skip
    monkeypatch.setitem(PLANNERS._items, NAME, spec)
    return spec


def test_a_planner_registered_here_runs_through_the_arena_and_its_report(registered, tmp_path):
    plan_ = ArenaPlan.from_dict({
        "name": "registry", "families": ["forest", "crossing"], "n": 2, "algorithms": [],
        "baselines": [NAME, "straight"], "planner": "quick", "overrides": {"max_steps": 300},
        "seed": 3, "batch_size": 1,
    })  # fmt: skip
    db = tmp_path / "arena.db"
    summary = run_plan(plan_, db, progress=False)
    assert summary.done == 8 and summary.failed == 0
    with Store.read(db) as store:
        rows = [r for _, _, r in store.rows(NAME)]
        table = arena_tables(store)[0]
    assert len(rows) == 4
    # the report (tables, figures, the failure gallery drawn from stored traces) takes it too
    report = write_arena_report(db, tmp_path / "report", gallery_limit=2).read_text()
    assert sum(line.startswith("|") and NAME in line for line in report.splitlines()) == 2
    from mawdo.experiments.kinds.arena.execute import scenario_from_toml
    from mawdo.planning.baselines import route_times

    for r in rows:
        assert r.status == "ok" and r.sees_time == "no"
        sc = scenario_from_toml(r.scene_toml, r.scene_name)
        opt = scenario_optimum(sc)
        # the stored numbers are the planner's: its route is the static optimum, driven blind
        assert r.length == pytest.approx(opt.length, rel=1e-9)
        assert r.l_star == pytest.approx(opt.length, rel=1e-12)
        rep = check_trajectory(opt.path, sc, times=route_times(opt.path, sc.robot_speed))
        assert r.collision_free == int(rep.ok)
        assert r.clearance == pytest.approx(rep.min_clearance, abs=1e-9)
        reached = np.ceil(opt.length / sc.robot_speed - 1e-9) <= 300
        assert r.success == int(rep.ok and reached)
        if r.success:
            assert r.gap == pytest.approx(1.0, abs=1e-9)
        assert r.waits == 0 and r.evasions == 0
    # the report's table lists it, on every family
    assert sum(NAME in str(row[1]) for row in table.rows) == 2


def test_a_registry_miss_suggests_the_close_name():
    with pytest.raises(KeyError, match="Did you mean 'straight'"):
        PLANNERS["straigth"]
    with pytest.raises(PlanError, match="Did you mean 'straight'"):
        ArenaPlan.from_dict({"families": ["forest"], "baselines": ["straigth"]})
    # an optimizer is a planner by its own name, a baseline is not an algorithm
    assert PLANNERS["GWO"].optimizer == "gwo"
    with pytest.raises(PlanError, match="is a baseline"):
        ArenaPlan.from_dict({"families": ["forest"], "algorithms": ["straight"]})


def _scene():
    """A wall between start and goal and a disc crossing the way (pixels, steps)."""
    return scenario_from_dict({
        "schema_version": 1, "name": "contract", "width": 120.0, "height": 80.0,
        "start": [10.0, 40.0], "goal": [110.0, 40.0], "robot": {"radius": 2.0, "speed": 4.0},
        "obstacles": [
            {"id": "wall", "shape": "polygon",
             "vertices": [[55.0, 20.0], [65.0, 20.0], [65.0, 60.0], [55.0, 60.0]]},
            {"id": "disc", "shape": "circle", "center": [85.0, 5.0], "radius": 5.0,
             "motion": {"model": "constant_velocity", "velocity": [0.0, 2.0]}},
        ],
    })  # fmt: skip


OPTIONS = {"time_limit": 0.2}


@pytest.mark.parametrize("name", list(PLANNERS))
def test_every_planner_returns_a_plan_result_its_metrics_agree_with_the_checker(name):
    spec = PLANNERS[name]
    sc = _scene()
    cfg = PlannerConfig(pop_size=30, first_iters=15, replan_iters=3, warm_copies=10,
                        max_steps=80, polish_rounds=1)  # fmt: skip
    opts = {k: v for k, v in OPTIONS.items() if k in spec.options}
    if spec.needs_extra == "ompl" and not ompl_available():
        with pytest.raises(ImportError, match="pip install"):
            spec.run(sc, 1, cfg, **opts)
        return
    res = spec.run(sc, 1, cfg, **opts)
    assert isinstance(res, PlanResult)
    l_star = scenario_optimum(sc).length
    m = run_metrics(res, l_star=l_star, snapshots=0)
    assert m["steps"] <= 80
    if not res.solved:  # a single-shot planner with no route: nothing to measure on it
        assert not m["success"] and m["length_px"] is None and m["collision_free"] is None
        return
    rep = check_trajectory(res.route, sc, times=res.route_times)
    assert m["collision_free"] == rep.ok
    assert m["collisions"] == rep.hits
    assert m["min_clearance_px"] == pytest.approx(rep.min_clearance, abs=1e-12)
    length = float(np.hypot(*np.diff(res.route, axis=0).T).sum())
    assert m["length_px"] == pytest.approx(length, rel=1e-12)
    at_goal = np.allclose(res.trajectory[-1], sc.goal, atol=1e-9)
    assert m["success"] == (at_goal and rep.ok)
    if m["success"]:
        assert m["gap"] == pytest.approx(length / l_star) and m["gap"] >= 1 - 1e-9
    assert (m["waits"] is None) == (not res.guarded)


def test_one_step_limit_for_every_kind_of_planner():
    sc = _scene()
    cfg = PlannerConfig(max_steps=5)
    for name in ("oracle_follower", "straight", "gwo"):
        res = PLANNERS[name].run(sc, 0, cfg)
        # 100 px at 4 px per step cannot be driven in 5 steps
        assert not res.success and res.reason.startswith("step limit reached"), name
        assert res.steps <= 5, name


def test_the_run_loop_builds_its_optimizers_once(monkeypatch):
    import mawdo.optimizers as optimizers

    made = []
    real = optimizers.make_optimizer

    def counting(*args, **kwargs):
        made.append(args[0])
        return real(*args, **kwargs)

    monkeypatch.setattr(optimizers, "make_optimizer", counting)
    res = plan(
        _scene(),
        "gwo",
        seed=2,
        config="quick",
        max_steps=30,
        first_pop_size=90,
        hold_straight=False,
        hold_gap=0.0,
    )
    assert len(res.replans) > 5  # many replans ...
    assert made == ["gwo", "gwo"]  # ... one optimizer for the first plan, one for the replans


def test_without_ompl_its_planners_say_how_to_install_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "ompl", None)  # "import ompl" now fails as if absent
    for name in (n for n in PLANNERS if PLANNERS[n].needs_extra == "ompl"):
        with pytest.raises(ImportError, match=r"pip install 'mawdo\[ompl\]'"):
            PLANNERS[name].run(_scene(), 0, PlannerConfig(), time_limit=0.1)


def test_every_registered_policy_is_a_planner_judged_by_the_checker():
    from mawdo.experiments.kinds.arena.plan import ArenaPlan
    from mawdo.planning.judge.check import check_trajectory
    from mawdo.planning.run.planners import PLANNERS, run_planner
    from mawdo.planning.scenes import generate_scene

    assert "policy:dwa" in PLANNERS and "policy:nope" not in PLANNERS
    plan = ArenaPlan.from_dict({"families": ["corridor"], "n": 1, "algorithms": [],
                                "baselines": ["policy:dwa", "policy:straight"]})  # fmt: skip
    assert plan.baselines == ("policy:dwa", "policy:straight")
    sc = generate_scene("corridor", 0, seed=0).scenario
    res = run_planner("policy:straight", sc, seed=0)
    rep = check_trajectory(res.route, res.scenario, times=res.route_times)
    assert res.algorithm == "policy:straight" and res.collision_free == rep.ok
    assert res.success == (res.reason == "goal reached" and rep.ok)
