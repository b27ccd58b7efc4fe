"""The headline sentences of a suite report state numbers recomputed from the raw store."""

from __future__ import annotations

import re

import numpy as np

from mawdo.experiments.bbob import write_suite_report

from .conftest import TINY
from .test_report import raw_runs, runtime

TARGETS = 10.0 ** np.linspace(2, -8, 51)


def ecdf_share(runs, algo, dim) -> float:
    """Fraction of (run, target) pairs solved within the budget, each function weighing the same."""
    budget = TINY["budget"] * dim
    per_fn = []
    for fid in TINY["functions"]:
        mine = [r for r in runs if r["algo"] == algo and r["fid"] == fid and r["dim"] == dim]
        hits = [runtime(r, t) <= budget for r in mine for t in TARGETS]
        per_fn.append(np.mean(hits))
    return float(np.mean(per_fn))


def median_final(runs, algo, fid, dim) -> float:
    fin = [
        max(r["best"][-1] - r["f_star"], 1e-8)
        for r in runs
        if r["algo"] == algo and r["fid"] == fid and r["dim"] == dim
    ]
    return float(np.median(fin))


def test_headline_numbers_are_the_stores(tiny_store, tmp_path):
    write_suite_report(tiny_store, tmp_path, plots=False)
    text = (tmp_path / "summary.md").read_text()
    assert text in (tmp_path / "report.md").read_text()
    runs = raw_runs(tiny_store)
    for dim in TINY["dims"]:
        line = next(s for s in text.splitlines() if s.startswith(f"- D = {dim}, "))
        shares = dict(re.findall(r"(\w+) (\d+) %", line))
        assert set(shares) == set(TINY["algorithms"])
        for algo, pct in shares.items():
            assert int(pct) == round(100 * ecdf_share(runs, algo, dim))
        w = t = lo = 0
        for fid in TINY["functions"]:
            a, b = median_final(runs, "mawdo", fid, dim), median_final(runs, "random", fid, dim)
            w, t, lo = w + (a < b), t + (a == b), lo + (a > b)
        solved = sum(
            r["best"][-1] - r["f_star"] <= 1e-8
            for r in runs
            if r["algo"] == "mawdo" and r["dim"] == dim
        )
        n = sum(r["algo"] == "mawdo" and r["dim"] == dim for r in runs)
        expect = (
            f"- D = {dim}: mawdo's median final precision is lower than random's on {w} of "
            f"{len(TINY['functions'])} functions ({t} equal, {lo} higher); {solved} of its {n} "
            "runs reach 1e-8."
        )
        assert expect in text


def test_no_headline_without_the_reference(tiny_store, tmp_path):
    write_suite_report(tiny_store, tmp_path, plots=False, reference="woa")
    assert not (tmp_path / "summary.md").exists()
