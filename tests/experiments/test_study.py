"""The planning study end to end on a tiny budget: runner -> store -> report (issue 6)."""

import csv

import numpy as np
import pytest
from PIL import Image

from mawdo.experiments import PlanError, Store, StoreError, run_plan
from mawdo.experiments.planning import BASELINE, StudyPlan, study_preset, write_study_report
from mawdo.experiments.planning.report import study_runs
from mawdo.planning import check_trajectory, get_scenario
from mawdo.planning.planner import result_from_bytes

PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    root = tmp_path_factory.mktemp("study")
    plan = study_preset("study-smoke")
    summary = run_plan(plan, root / "s.db", workers=1, progress=False)
    assert summary.complete and summary.failed == 0
    report = write_study_report(root / "s.db", root / "report")
    return plan, root / "s.db", report


def test_table_columns_and_values_come_from_the_store(study):
    plan, db, report = study
    rows = list(csv.reader((report.parent / "table6.csv").open()))
    header = rows[0]
    for col in (
        "algorithm",
        "length (px)",
        "gap L/L*",
        "smoothness (rad)",
        "paper length",
        "success",
        "collision-free",
        "min clearance (px)",
        "latency p95 (ms)",
        "nfev",
    ):
        assert col in header
    assert [r[0] for r in rows[1:]] == ["GWO", "MAWDO", "Oracle follower (frozen obstacles)"]
    with Store.read(db) as st:
        mawdo = study_runs(st, "mawdo")
        share = np.mean([r["metrics"]["collision_free"] for r in mawdo])
    row = rows[2]
    assert float(row[header.index("collision-free")]) == pytest.approx(share)
    assert float(row[header.index("paper length")]) == pytest.approx(469.28)
    text = report.read_text()
    assert "Wilcoxon" in text and "reconstruction" in text


def test_every_reported_run_passes_the_independent_checker(study):
    plan, db, _ = study
    sc = get_scenario(plan.scenario)
    with Store.read(db) as st:
        runs = study_runs(st, route=True)
    assert len(runs) == plan.total_runs == 5
    for r in runs:
        res = result_from_bytes(r["route"], sc)
        rep = check_trajectory(res.route, sc, times=res.route_times)
        assert rep.ok == r["metrics"]["collision_free"]
        assert rep.ok, f"{r['algorithm']} run {r['run']} collides"
        assert r["metrics"]["length_px"] == pytest.approx(
            float(np.hypot(*np.diff(res.route, axis=0).T).sum())
        )


def test_figures_are_valid_images(study):
    _, _, report = study
    out = report.parent
    pngs = sorted(out.glob("*.png"))
    assert {p.name for p in pngs} >= {
        "cost_convergence.png",
        "box_length_px.png",
        "snapshots_mawdo.png",
        "snapshots_gwo.png",
    }
    for p in pngs:
        assert p.read_bytes()[:8] == PNG
        w, h = Image.open(p).size
        assert w >= 400 and h >= 300
    grid = Image.open(out / "snapshots_mawdo.png").size
    assert grid[0] > grid[1]  # one 2x4 block: wider than tall
    gif = Image.open(out / "mawdo_median_run.gif")
    assert gif.format == "GIF" and gif.n_frames > 1


def test_resume_skips_stored_runs_and_other_plans_are_refused(study, tmp_path):
    plan, db, _ = study
    again = run_plan(plan, db, progress=False)
    assert again.done == 0 and again.skipped == plan.total_runs
    other = plan.with_overrides(runs=3)
    with pytest.raises(StoreError, match="force"):
        run_plan(other, db, progress=False)


def test_bad_study_plans_name_the_field():
    with pytest.raises(PlanError, match=r"algorithms\[1\]: unknown algorithm 'mawod'"):
        StudyPlan.from_dict({"algorithms": ["gwo", "mawod"]})
    with pytest.raises(PlanError, match="scenario"):
        StudyPlan.from_dict({"algorithms": ["gwo"], "scenario": "papr"})
    with pytest.raises(PlanError, match="overrides"):
        StudyPlan.from_dict({"algorithms": ["gwo"], "overrides": {"replan_iters": 0}})
    p = StudyPlan.from_dict({"algorithms": ["gwo", BASELINE], "runs": 4})
    assert p.total_runs == 5  # the deterministic baseline runs once
