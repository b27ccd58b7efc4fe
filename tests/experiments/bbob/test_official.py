"""The CEC competitions' protocols as presets, their checkpoints, and their result tables
recomputed from the raw stored rows."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from mawdo.experiments import Store, run_plan
from mawdo.experiments.kinds.suite import preset_plan, write_suite_report
from mawdo.experiments.kinds.suite.competition import competition_score
from mawdo.optimizers import HOLDOUT_ALGORITHMS
from mawdo.suites import SUITES, evaluation_budget
from tests.cli_run import mawdo

from .conftest import tiny_plan


@pytest.mark.parametrize(
    ("name", "suite", "n", "evals", "runs"),
    [
        ("cec2017-official", "cec2017", 30, {10: 100_000, 30: 300_000}, 51),
        ("cec2022-official-d10", "cec2022", 12, {10: 200_000}, 30),
        ("cec2022-official-d20", "cec2022", 12, {20: 1_000_000}, 30),
    ],
)
def test_presets_are_the_competitions_protocols(name, suite, n, evals, runs):
    plan = preset_plan(name)
    assert plan.suite == suite and plan.functions == tuple(range(1, n + 1))
    assert {d: evaluation_budget(plan.budget, d) for d in plan.dims} == evals
    assert plan.runs == runs and plan.final_target == 1e-8 and plan.numbering == "official"
    # judged against the competitions' winners as well as the hold-out field
    assert plan.algorithms == (*HOLDOUT_ALGORITHMS, "lshade", "jso", "nlshade_rsp", "ea4eig")


def test_checkpoints_are_the_reports():
    c17, c22 = SUITES["cec2017"].checkpoints, SUITES["cec2022"].checkpoints
    fractions = (0.01, 0.02, 0.03, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0)
    assert c17(10, 100_000) == tuple(int(f * 100_000) for f in fractions)
    marks = c22(10, 200_000)  # D^(k/5 - 3) MaxFES, k = 0..15
    assert len(marks) == 16 and marks[0] == 200 and marks[5] == 2000 and marks[-1] == 200_000
    assert list(marks) == sorted(marks)
    assert SUITES["bbob"].checkpoints is None


def _read_csv(path) -> dict:
    """``{(function, algorithm): row}`` of a report's table."""
    with open(path, newline="") as fh:
        return {(r["function"], r["algorithm"]): r for r in csv.DictReader(fh)}


def test_competition_tables_are_the_stored_runs_statistics(tmp_path):
    plan = tiny_plan(suite="cec2022", functions=[1, 6], instances=None, dims=[10], budget=30,
                     algorithms=["random", "cmaes"], runs=4)  # fmt: skip
    db = tmp_path / "cec.db"
    assert run_plan(plan, db, workers=1, progress=False).complete
    write_suite_report(db, tmp_path / "report", plots=False)
    marks = SUITES["cec2022"].checkpoints(10, 300)
    stats = _read_csv(tmp_path / "report" / "competition_d10.csv")
    cps = _read_csv(tmp_path / "report" / "checkpoints_d10.csv")
    with Store.read(db) as store:
        rows = [(a, r) for a, _, r in store.rows()]
    for fid in (1, 6):
        for algo in ("random", "cmaes"):
            mine = [r for a, r in rows if r.function_id == fid and a == algo]
            assert len(mine) == 4
            final = np.array([r.best_so_far[-1] - r.f_star for r in mine])
            final[final <= 1e-8] = 0.0
            got = stats[f"F{fid}", algo]
            want = [final.min(), final.max(), np.median(final), final.mean(), final.std()]
            have = [float(got[k]) for k in ("best", "worst", "median", "mean", "std")]
            np.testing.assert_allclose(have, want, rtol=1e-4)  # the csv's 5 significant digits
            assert float(got["FEs"]) == np.mean([r.nfev for r in mine])
            # error at a checkpoint: the best value among the evaluations up to it
            at = [
                [r.best_so_far[np.searchsorted(r.evals, m, side="right") - 1] - r.f_star
                 for m in marks] for r in mine
            ]  # fmt: skip
            have = [float(cps[f"F{fid}", algo][str(m)]) for m in marks]
            np.testing.assert_allclose(have, np.mean(at, axis=0), rtol=1e-3)


def test_the_cec2017_score_by_hand():
    # three algorithms, two functions at D = 10: SE = 5, 4, 10; ranks (2, 2), (3, 1), (1, 3)
    s = competition_score(np.array([[1.0, 2.0, 0.0], [4.0, 2.0, 10.0]]), np.array([0.1, 0.1]))
    np.testing.assert_allclose(s["SE"], [0.5, 0.4, 1.0])
    np.testing.assert_allclose(s["Score1"], [40.0, 50.0, 20.0])  # 50 (1 - (SE - 4) / SE)
    np.testing.assert_allclose(s["Score2"], [50.0, 50.0, 50.0])  # every rank sum is 4
    np.testing.assert_allclose(s["Score"], [90.0, 100.0, 70.0])
    # two dimensions weigh 0.1 and 0.2; ties share the mean of their ranks
    s = competition_score(np.array([[1.0, 1.0, 3.0], [5.0, 2.0, 2.0]]), np.array([0.1, 0.2]))
    np.testing.assert_allclose(s["SE"], [1.1, 0.5, 0.7])
    np.testing.assert_allclose(s["SR"], [0.75, 0.45, 0.6])  # (1.5, 3), (1.5, 1.5), (3, 1.5)
    np.testing.assert_allclose(s["Score1"], [50 * 0.5 / 1.1, 50.0, 50 * 0.5 / 0.7])
    np.testing.assert_allclose(s["Score2"], [30.0, 50.0, 37.5])
    # an algorithm with no error at all is the least SE: 50, not 0/0
    s = competition_score(np.array([[0.0, 1.0], [0.0, 2.0]]), np.array([0.1, 0.1]))
    np.testing.assert_array_equal(s["Score1"], [50.0, 0.0])


def test_the_score_table_is_the_competition_means_of_the_store(tmp_path):
    algos = ["random", "cmaes", "gwo"]
    plan = tiny_plan(suite="cec2017", functions=[1, 2, 4], instances=None, dims=[10],
                     budget=20, algorithms=algos, runs=3)  # fmt: skip
    db = tmp_path / "cec.db"
    assert run_plan(plan, db, workers=1, progress=False).complete
    write_suite_report(db, tmp_path / "report", plots=False)
    means = _read_csv(tmp_path / "report" / "competition_d10.csv")
    with open(tmp_path / "report" / "score.csv", newline="") as fh:
        score = {r["algorithm"]: r for r in csv.DictReader(fh)}
    # F2 is left out: the score reads F1 and F4 only, each weighing 0.1 at D = 10
    e = np.array([[float(means[f, a]["mean"]) for a in algos] for f in ("F1", "F4")])
    ranks = np.argsort(np.argsort(e, axis=1), axis=1) + 1.0  # no ties among random means
    se, sr = 0.1 * e.sum(axis=0), 0.1 * ranks.sum(axis=0)
    want = 50 * (1 - (se - se.min()) / se) + 50 * (1 - (sr - sr.min()) / sr)
    have = np.array([float(score[a]["Score"]) for a in algos])
    np.testing.assert_allclose(have, want, rtol=1e-3)  # the csv's rounding
    places = sorted(algos, key=lambda a: -want[algos.index(a)])
    assert [score[a]["place"] for a in places] == ["1", "2", "3"]
    report = (tmp_path / "report" / "report.md").read_text(encoding="utf-8")
    assert "D=10 (weight 0.1): 2 functions; F2 left out" in report


def test_a_suite_without_a_score_gets_no_score_table(tmp_path):
    plan = tiny_plan(suite="cec2022", functions=[1], instances=None, dims=[10], budget=10,
                     algorithms=["random", "gwo"], runs=2)  # fmt: skip
    db = tmp_path / "cec.db"
    assert run_plan(plan, db, workers=1, progress=False).complete
    write_suite_report(db, tmp_path / "report", plots=False)
    assert (tmp_path / "report" / "competition_d10.csv").exists()
    assert not (tmp_path / "report" / "score.csv").exists()
    assert SUITES["cec2022"].score is None and SUITES["bbob"].score is None


def _matrix(path) -> np.ndarray:
    return np.array([[float(v) for v in line.split()] for line in path.read_text().splitlines()])


@pytest.mark.parametrize(("suite", "rows"), [("cec2017", 14), ("cec2022", 17)])
def test_the_cec_files_are_the_stored_runs_errors_at_the_checkpoints(tmp_path, suite, rows):
    plan = tiny_plan(suite=suite, functions=[1, 3], instances=None, dims=[10], budget=30,
                     algorithms=["random", "gwo"], runs=3)  # fmt: skip
    db = tmp_path / "cec.db"
    assert run_plan(plan, db, workers=1, progress=False).complete
    res = mawdo("bench", "export", "--format", "cec", str(db), str(tmp_path / "cec"))
    assert res.returncode == 0, res.stderr
    assert "4 files" in res.stdout
    marks = SUITES[suite].checkpoints(10, 300)
    with Store.read(db) as store:
        rows_of = [(a, r) for a, _, r in store.rows()]
    for algo in ("random", "gwo"):
        for fid in (1, 3):
            m = _matrix(tmp_path / "cec" / algo / f"{algo}_{fid}_10.txt")
            assert m.shape == (rows, 3)  # one column per run, in run order
            mine = sorted((r for a, r in rows_of if a == algo and r.function_id == fid),
                          key=lambda r: r.run)  # fmt: skip
            for col, r in enumerate(mine):
                # the error after each checkpoint: the best value up to it, <= 1e-8 as 0
                at = [r.best_so_far[np.searchsorted(r.evals, k, side="right") - 1] - r.f_star
                      for k in marks]  # fmt: skip
                want = np.where(np.array(at) <= 1e-8, 0.0, at)
                np.testing.assert_allclose(m[: len(marks), col], want, rtol=1e-8)
                if rows > len(marks):  # CEC 2022's FEterm: the evaluations the run used
                    assert m[-1, col] == r.nfev


def test_only_a_cec_study_exports_the_competition_files(tiny_store, tmp_path):
    res = mawdo("bench", "export", "--format", "cec", str(tiny_store), str(tmp_path / "x"))
    assert res.returncode == 2
    assert "bbob study, which has no checkpoints (use --format ioh)" in res.stderr
    assert not (tmp_path / "x").exists() or not any((tmp_path / "x").iterdir())
