"""Reports from a store: files, columns, labels, agreement with the stored numbers, figures."""

from __future__ import annotations

import csv
import math
import re
import struct

import numpy as np
import pytest

from mawdo.experiments import Store, run_plan, write_report
from mawdo.experiments import runner as runner_mod
from mawdo.experiments.kinds.benchmark import execute as bench_exec_mod
from mawdo.experiments.kinds.benchmark.paper_values import TABLE3, TABLE5, paper_entry
from mawdo.experiments.stats import ranksum

from .conftest import small_plan

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def read_csv(path) -> list[dict[str, str]]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def report_dir(reference_store, tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    files = write_report(reference_store, out, svg=True)
    return out, files


def test_report_files_are_written(report_dir):
    out, files = report_dir
    names = {p.name for p in files}
    for stem in (
        "results_raw",
        "results_error",
        "wilcoxon",
        "wilcoxon_totals",
        "friedman",
        "paper_comparison",
    ):
        assert {f"{stem}.md", f"{stem}.tex", f"{stem}.csv"} <= names
    assert {
        "report.md",
        "summary.csv",
        "timing.csv",
        "convergence.png",
        "boxplots.png",
        "convergence.svg",
        "boxplots.svg",
    } <= names
    assert all(p.stat().st_size > 0 for p in files)
    assert "ablation_raw.csv" not in names  # no MAWDO-1..4 in this plan


def test_results_table_columns_and_reconstructed_label(report_dir, reference_store):
    out, _ = report_dir
    rows = read_csv(out / "results_raw.csv")
    assert list(rows[0]) == ["Function", "Index", "GWO", "MEWDO (reconstructed)", "MAWDO"]
    assert [r["Index"] for r in rows[:4]] == ["Best", "Ave", "Std", "P"]
    assert [r["Function"] for r in rows[::4]] == ["F6", "F12", "F7"]
    md = (out / "results_raw.md").read_text()
    assert "| Function | Index | GWO | MEWDO (reconstructed) | MAWDO |" in md


def test_results_table_agrees_with_the_stored_runs(report_dir, reference_store):
    out, _ = report_dir
    rows = read_csv(out / "results_raw.csv")
    err_rows = read_csv(out / "results_error.csv")
    with Store.read(reference_store) as store:
        recs = store.rows(skip=("curve", "curve_nfev"))
    for fn, pid in (("quartic", "F6"), ("six_hump_camel", "F12"), ("rastrigin", "F7")):
        block = {r["Index"]: r for r in rows if r["Function"] == pid}
        eblock = {r["Index"]: r for r in err_rows if r["Function"] == pid}
        ref = np.array([r.fun for a, f, r in recs if a == "mawdo" and f == fn])
        for algo, col in (("gwo", "GWO"), ("mewdo", "MEWDO (reconstructed)"), ("mawdo", "MAWDO")):
            f = np.array([r.fun for a, g, r in recs if a == algo and g == fn])
            e = np.array([r.error for a, g, r in recs if a == algo and g == fn])
            assert float(block["Best"][col]) == f.min()
            assert float(block["Ave"][col]) == pytest.approx(f.mean(), rel=1e-14)
            assert float(block["Std"][col]) == pytest.approx(f.std(ddof=1), rel=1e-12)
            assert float(eblock["Ave"][col]) == pytest.approx(e.mean(), rel=1e-12, abs=1e-300)
            if algo != "mawdo":
                assert block["P"][col] == ranksum(ref, f).sign
        assert block["P"]["MAWDO"] == ""


def test_latex_is_booktabs_like_the_paper(report_dir):
    out, _ = report_dir
    tex = (out / "results_raw.tex").read_text()
    for piece in (
        "\\toprule",
        "\\midrule",
        "\\bottomrule",
        "\\multirow{4}{*}{F6}",
        "MEWDO (reconstructed)",
        "\\begin{tabular}{ccccc}",
    ):
        assert piece in tex
    body = tex.split("\\midrule")[1].split("\\bottomrule")[0]
    data_lines = [ln for ln in body.splitlines() if ln.endswith("\\\\")]
    assert len(data_lines) == 3 * 4
    assert all(ln.count("&") == 4 for ln in data_lines)
    assert re.search(r"& Best & -?\d\.\d\dE[+-]\d\d", tex)


def test_wilcoxon_and_friedman_tables(report_dir):
    out, _ = report_dir
    w = read_csv(out / "wilcoxon.csv")
    assert len(w) == 2 * 3  # rivals x functions
    p = np.array([float(r["p"]) for r in w])
    ph = np.array([float(r["p (Holm)"]) for r in w])
    assert np.all(ph >= p) and np.all(ph <= 1)
    totals = read_csv(out / "wilcoxon_totals.csv")
    assert [r["Rival"] for r in totals] == ["GWO", "MEWDO (reconstructed)"]
    assert all(int(r["+"]) + int(r["="]) + int(r["-"]) == 3 for r in totals)
    fr = read_csv(out / "friedman.csv")
    ranks = [float(r["Average rank"]) for r in fr]
    assert sum(ranks) == pytest.approx(3 * 4 / 2) and ranks == sorted(ranks)


def test_paper_comparison_marks_f12_to_f16_not_comparable(report_dir):
    out, _ = report_dir
    rows = read_csv(out / "paper_comparison.csv")
    f6 = {r["Index"]: r for r in rows if r["Function"] == "F6"}
    assert float(f6["Best"]["GWO paper"]) == TABLE3["F6"]["gwo"].best
    assert f6["P"]["MEWDO (reconstructed) paper"] == TABLE3["F6"]["mewdo"].sign
    f12 = [r for r in rows if r["Function"] == "F12"]
    assert f12 and all(r["MAWDO paper"] == "n.c." for r in f12)
    md = (out / "paper_comparison.md").read_text()
    assert "differs from the paper's protocol" in md and "runs=4 (paper 30)" in md
    assert "docs/functions.md#f-f12-f16" in md and "SPEC" not in md


def test_comparability_notes_sort_paper_ids_by_what_we_run():
    from mawdo.experiments.kinds.benchmark.paper_compare import comparability_notes

    same, other, nc = comparability_notes(["F1", "F9", "F12", "F7", "F11", "sphere_x"])
    # F1-F7 run the printed formula; F8-F11 a standard one (docs/functions.md); F12-F16 n.c.
    assert same.startswith("F1, F7: we run the formula the paper prints")
    assert other.startswith("F9, F11: we run a standard function in place of the printed")
    assert "F9 docs/functions.md#f-penalized, F11 docs/functions.md#f-f11" in other
    assert "not verified to be comparable" in other
    assert nc.startswith("F12: not comparable (n.c. in the tables)")
    assert comparability_notes(["F2"]) == [comparability_notes(["F2", "F8"])[0]]


def png_size(path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == PNG_SIGNATURE
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def test_figures_are_valid_pngs(report_dir):
    out, _ = report_dir
    for name in ("convergence.png", "boxplots.png"):
        w, h = png_size(out / name)
        assert w >= 600 and h >= 250
        assert (out / name).stat().st_size > 10_000
    assert (out / "convergence.svg").read_text().lstrip().startswith("<?xml")
    assert "![convergence](convergence.png)" in (out / "report.md").read_text()


def test_report_never_recomputes(reference_store, tmp_path, monkeypatch):
    def boom(*a, **k):
        raise AssertionError("the report must not run an optimizer")

    import sys

    import mawdo

    monkeypatch.setattr(bench_exec_mod, "minimize", boom)
    monkeypatch.setattr(runner_mod, "execute_task", boom)
    monkeypatch.setattr(mawdo, "minimize", boom)
    monkeypatch.setattr(sys.modules["mawdo.minimize"], "minimize", boom)
    monkeypatch.setattr(sys.modules["mawdo.optimizers.registry"], "make_optimizer", boom)
    files = write_report(reference_store, tmp_path / "r", plots=False)
    assert any(p.name == "results_raw.csv" for p in files)


def test_ablation_table_and_partial_store(tmp_path):
    plan = small_plan(
        algorithms=["mawdo1", "mawdo3", "mawdo"],
        functions=["sphere", "F12"],
        runs=3,
        max_iter=15,
        batch_size=3,
    )
    db = tmp_path / "abl.db"
    # store only part of the sweep: a report still works and says so
    from mawdo.experiments.runner import execute_task

    with Store.open(db, plan) as store:
        for task in plan.tasks()[:4]:
            store.write_task(execute_task(plan.task_spec(task)))
    out = tmp_path / "rep"
    write_report(db, out, plots=True)
    rows = read_csv(out / "ablation_raw.csv")
    assert list(rows[0]) == ["Function", "Index", "MAWDO-1", "MAWDO-3", "MAWDO"]
    assert [r["Index"] for r in rows[:3]] == ["Best", "Ave", "Std"]  # Table 5: no P row
    assert "Incomplete sweep: 12 of 18 runs stored" in (out / "ablation_raw.md").read_text()
    # the paper's MAWDO-3 numbers come from Table 5
    cmp_rows = read_csv(out / "paper_comparison.csv")
    f1 = {r["Index"]: r for r in cmp_rows if r["Function"] == "F1"}
    assert float(f1["Best"]["MAWDO-3 paper"]) == TABLE5["F1"]["mawdo3"].best
    assert png_size(out / "convergence.png")[0] > 0


def test_failed_runs_are_excluded_and_noted(tmp_path, monkeypatch):
    real = bench_exec_mod.minimize

    def flaky(fun, **kw):
        if kw["algorithm"] == "gwo" and kw["first_run"] == 0 and fun == "rastrigin":
            raise RuntimeError("boom")
        return real(fun, **kw)

    monkeypatch.setattr(bench_exec_mod, "minimize", flaky)
    db = tmp_path / "f.db"
    run_plan(small_plan(), db, progress=False)
    out = tmp_path / "rep"
    write_report(db, out, plots=False)
    md = (out / "results_raw.md").read_text()
    assert "GWO on F7: 2 failed runs excluded." in md
    summary = {(r["algorithm"], r["function"]): r for r in read_csv(out / "summary.csv")}
    cell = summary["gwo", "rastrigin"]
    assert (cell["failed"], cell["runs"]) == ("2", "2")


def test_paper_values_transcription_spot_checks():
    # hand-copied from the tex source: Table 3 F5 AWDO, F11 AWDO (≈), Table 5 F16 MAWDO
    assert TABLE3["F5"]["awdo"] == (4.12e-04, 2.49e01, 9.75e00, "-")
    assert TABLE3["F11"]["awdo"].sign == "="
    assert TABLE3["F3"]["woa"].ave == 6275.444
    assert TABLE5["F16"]["mawdo"].std is None
    assert all(len(v) == 6 for v in TABLE3.values()) and len(TABLE3) == 16
    assert all(len(v) == 5 for v in TABLE5.values()) and len(TABLE5) == 16
    # MAWDO's own numbers agree between the two tables wherever both give them
    for fid in TABLE3:
        a, b = TABLE3[fid]["mawdo"], TABLE5[fid]["mawdo"]
        assert a.best == b.best and a.ave == b.ave
        assert b.std is None or a.std == b.std
    assert paper_entry("mawdo2", "F9")[0] == "Table 5"
    assert paper_entry("gwo", None) is None
    assert math.isclose(paper_entry("mawdo", "F9")[1].best, 2.38e-07)


def test_wilcoxon_totals_quote_the_papers_own_counts_on_the_same_functions(report_dir):
    out, _ = report_dir
    md = (out / "wilcoxon_totals.md").read_text()
    # paper .tex, tab:results, P rows of F6, F7, F12 (this plan's quartic, rastrigin, camel):
    # GWO + = +, MEWDO = + +
    assert "against GWO: 2 +, 1 =, 0 - over 3 of these 3 functions." in md
    assert "against MEWDO: 2 +, 1 =, 0 - over 3 of these 3 functions." in md
