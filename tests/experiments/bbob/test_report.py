"""The suite report's numbers equal values recomputed from the raw store (sqlite3 + numpy,
loops written from COCO's definitions, none of the kind's code), and its figures exist."""

from __future__ import annotations

import csv
import sqlite3

import numpy as np
import pytest
from scipy.stats import rankdata

from mawdo.experiments.kinds.suite import write_suite_report
from mawdo.experiments.kinds.suite.data import load_runs
from mawdo.experiments.kinds.suite.measures import ecdf_curves

from .conftest import TINY


def raw_runs(path) -> list[dict]:
    conn = sqlite3.connect(path)
    try:
        rows = conn.execute(
            "SELECT algorithm, function_id, instance, dim, f_star, nfev, evals, best_so_far "
            "FROM runs WHERE error_text IS NULL"
        ).fetchall()
    finally:
        conn.close()
    keys = ("algo", "fid", "iid", "dim", "f_star", "nfev")
    return [
        {
            **dict(zip(keys, r[:6], strict=True)),
            "evals": np.frombuffer(r[6], "<i8"),
            "best": np.frombuffer(r[7], "<f8"),
        }
        for r in rows
    ]


def runtime(run, target):
    for e, y in zip(run["evals"], run["best"], strict=True):
        if y - run["f_star"] <= target:
            return float(e)
    return np.inf


def best_at(run, budget):
    seen = [y for e, y in zip(run["evals"], run["best"], strict=True) if e <= budget]
    return seen[-1] - run["f_star"] if seen else np.inf


def read_csv(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


@pytest.fixture(scope="module")
def report(tiny_store, tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    write_suite_report(tiny_store, out, plots=False)  # figures: test_report_figures
    return out


def test_art_table_equals_art_from_the_raw_store(tiny_store, report):
    runs = raw_runs(tiny_store)
    for dim in TINY["dims"]:
        for line in read_csv(report / f"art_d{dim}.csv"):
            fid = int(line["function"][1:])
            for algo in TINY["algorithms"]:
                sel = [r for r in runs if (r["algo"], r["fid"], r["dim"]) == (algo, fid, dim)]
                assert len(sel) == len(TINY["instances"]) * TINY["runs"]
                if line["target"] == "solved":
                    solved = sum(np.isfinite(runtime(r, 1e-8)) for r in sel)
                    assert line[algo] == f"{solved}/{len(sel)}"
                    continue
                rts = [runtime(r, float(line["target"])) for r in sel]
                ok = [t for t in rts if np.isfinite(t)]
                spent = sum(ok) + sum(r["nfev"] for r, t in zip(sel, rts, strict=True)
                                      if not np.isfinite(t))  # fmt: skip
                expected = spent / len(ok) if ok else np.inf
                assert float(line[algo]) == pytest.approx(expected, rel=1e-12)


def test_fixed_budget_table_equals_medians_from_the_raw_store(tiny_store, report):
    runs = raw_runs(tiny_store)
    for dim in TINY["dims"]:
        lines = read_csv(report / f"fixed_budget_d{dim}.csv")
        budgets = sorted({int(line["evaluations"]) for line in lines})
        assert budgets[-1] == TINY["budget"] * dim and budgets[0] == 10 * dim
        for line in lines:
            fid, b = int(line["function"][1:]), int(line["evaluations"])
            for algo in TINY["algorithms"]:
                sel = [r for r in runs if (r["algo"], r["fid"], r["dim"]) == (algo, fid, dim)]
                expected = np.median([best_at(r, b) for r in sel])
                assert float(line[algo]) == pytest.approx(expected, rel=1e-12, abs=0)


def test_friedman_ranks_equal_ranks_from_the_raw_store(tiny_store, report):
    runs = raw_runs(tiny_store)
    algos = TINY["algorithms"]
    lines = {line["dimensions"]: line for line in read_csv(report / "friedman.csv")}
    for label, dims in [("D=2", [2]), ("D=3", [3]), ("all", [2, 3])]:
        ranks = []
        for dim in dims:
            for fid in TINY["functions"]:
                for iid in TINY["instances"]:
                    med = []
                    for algo in algos:
                        sel = [r for r in runs if (r["algo"], r["fid"], r["dim"], r["iid"])
                               == (algo, fid, dim, iid)]  # fmt: skip
                        med.append(np.median([max(r["best"][-1] - r["f_star"], 1e-8)
                                              for r in sel]))  # fmt: skip
                    ranks.append(rankdata(med))
        assert int(lines[label]["blocks"]) == len(ranks)
        np.testing.assert_allclose(
            [float(lines[label][a]) for a in algos], np.mean(ranks, axis=0), rtol=1e-12
        )


def test_group_ranks_equal_ranks_from_the_raw_store(tiny_store, report):
    # f1, f12 and f21 lie in three of COCO's five groups, one function each
    runs = raw_runs(tiny_store)
    algos = TINY["algorithms"]
    lines = read_csv(report / "friedman_groups.csv")
    names = {1: "separable", 12: "high conditioning, unimodal", 21: "multimodal, weak"}
    assert len(lines) == len(TINY["dims"]) * len(names)
    for line in lines:
        dim = int(line["dimensions"][2:])
        (fid,) = [f for f, name in names.items() if line["group"].startswith(name)]
        ranks = []
        for iid in TINY["instances"]:
            med = []
            for algo in algos:
                sel = [r for r in runs if (r["algo"], r["fid"], r["dim"], r["iid"])
                       == (algo, fid, dim, iid)]  # fmt: skip
                med.append(np.median([max(r["best"][-1] - r["f_star"], 1e-8) for r in sel]))
            ranks.append(rankdata(med))
        assert int(line["blocks"]) == len(ranks)
        np.testing.assert_allclose([float(line[a]) for a in algos], np.mean(ranks, axis=0))


def test_ecdf_equals_the_fraction_of_solved_run_target_pairs(tiny_store):
    runs = raw_runs(tiny_store)
    targets = 10.0 ** np.linspace(2, -8, 51)
    study = load_runs(tiny_store)
    x = np.array([1.0, 10.0, 100.0, TINY["budget"]])
    for dim in TINY["dims"]:
        curves = ecdf_curves(study, dim, TINY["functions"], x)
        for algo in TINY["algorithms"]:
            per_fn = []
            for fid in TINY["functions"]:
                sel = [r for r in runs if (r["algo"], r["fid"], r["dim"]) == (algo, fid, dim)]
                rt = np.array([[runtime(r, t) for t in targets] for r in sel]) / dim
                per_fn.append([(rt <= b).mean() for b in x])
            np.testing.assert_allclose(curves[algo], np.mean(per_fn, axis=0), rtol=1e-12)
        assert np.all(np.diff(curves["cmaes"]) >= 0)


@pytest.mark.slow
def test_report_figures(tiny_store, tmp_path):
    write_suite_report(tiny_store, tmp_path, svg=True)
    names = {p.name for p in tmp_path.iterdir()}
    for dim in TINY["dims"]:
        for stem in (f"ecdf_d{dim}", f"convergence_d{dim}"):
            assert {f"{stem}.png", f"{stem}.svg"} <= names
            assert (tmp_path / f"{stem}.png").stat().st_size > 20_000  # drawn, not blank
    text = (tmp_path / "report.md").read_text()
    assert "Friedman" in text and "![ecdf_d2](ecdf_d2.png)" in text


def _line_look(line) -> tuple:
    """What tells a curve apart: its colour, its dash pattern (offset and on/off lengths, in
    points at its width) and its marker."""
    from matplotlib.colors import to_hex

    return to_hex(line.get_color()), str(line._unscaled_dash_pattern), line.get_marker()


def test_every_algorithm_differs_in_colour_dash_and_marker(tiny_store, tmp_path, monkeypatch):
    """Issue 28: the ECDFs of MAWDO, AWDO and random overlapped in look-alike colours."""
    from mawdo.experiments.kinds.suite import plots

    drawn = []
    monkeypatch.setattr(plots, "_save", lambda fig, path, svg: drawn.append(fig) or [path])
    eight = ("gwo", "woa", "wdo", "awdo", "mewdo", "mawdo", "cmaes", "random")  # the study's
    looks = plots.styles(eight + ("a", "b"))
    for key in ("color", "ls", "marker"):
        values = [repr(v[key]) for v in looks.values()]
        assert len(set(values)) == 10, f"two of 10 algorithms share a {key}: {values}"
    # an eleventh (the official CEC studies have eleven and more) looks like none of the ten,
    # and the ten look as they did
    twenty = plots.styles(eight + tuple("abcdefghijkl"))
    assert all(twenty[a] == looks[a] for a in eight + ("a", "b"))
    for key in ("color", "marker"):
        values = [repr(v[key]) for v in twenty.values()]
        assert len(set(values)) == 20, f"two of 20 algorithms share a {key}: {values}"
    study = load_runs(tiny_store)
    plots.plot_ecdfs(study, TINY["dims"][0], tmp_path)
    # four ECDF panels (all functions and three groups) on a 3 x 2 grid: the legend sits in
    # a free slot, over no curve
    holders = [ax for ax in drawn[0].axes if ax.get_legend() is not None]
    assert len(holders) == 1 and not holders[0].lines and holders[0].get_visible()
    assert len(holders[0].get_legend().get_texts()) == len(TINY["algorithms"])
    plots.plot_convergence(study, TINY["dims"][0], tmp_path)
    for fig in drawn:
        for ax in fig.axes:
            if not ax.get_visible() or not ax.lines:
                continue
            seen = {line.get_label(): _line_look(line) for line in ax.lines}
            assert set(seen) == set(TINY["algorithms"])
            for part in range(3):  # colour, dash, marker: each differs between any two
                assert len({look[part] for look in seen.values()}) == len(seen)
            solid = [a for a, look in seen.items() if look[1] == str((0, None))]
            assert len(solid) <= 1  # at most one plain solid line


def test_a_group_with_no_finished_run_has_no_row(tiny_store, tmp_path):
    # a study still running: f21 (the weak-structure group's only function) not yet run
    import shutil

    from mawdo.experiments.kinds.suite.report import friedman_groups_table

    part = tmp_path / "part.db"
    shutil.copy(tiny_store, part)
    conn = sqlite3.connect(part)
    with conn:
        conn.execute("DELETE FROM runs WHERE function_id = 21")
    conn.close()
    groups = [row[1] for row in friedman_groups_table(load_runs(part)).rows]
    assert len(groups) == 2 * len(TINY["dims"]) and not any(
        g.startswith("multimodal") for g in groups
    )
