"""The headline sentences of a suite report state numbers recomputed from the raw store."""

from __future__ import annotations

import re

import numpy as np
import pytest

from mawdo.experiments.kinds.suite import write_suite_report
from mawdo.experiments.kinds.suite.summary import function_list

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
        better, equal, worse = [], [], []
        for fid in TINY["functions"]:
            a, b = median_final(runs, "mawdo", fid, dim), median_final(runs, "random", fid, dim)
            (better if a < b else worse if a > b else equal).append(f"f{fid}")
        solved = sum(
            r["best"][-1] - r["f_star"] <= 1e-8
            for r in runs
            if r["algo"] == "mawdo" and r["dim"] == dim
        )
        n = sum(r["algo"] == "mawdo" and r["dim"] == dim for r in runs)
        # TINY's functions (1, 12, 21) are never neighbours: each side is listed one by one
        expect = (
            f"- D = {dim}: median final error f - f_opt over instances and runs (lower is "
            f"better), mawdo against random: better on {len(better)} of "
            f"{len(TINY['functions'])} functions ({', '.join(better) or 'none'}), worse on "
            f"{len(worse)} ({', '.join(worse) or 'none'}), equal on {len(equal)}; {solved} of "
            f"mawdo's {n} runs reach f - f_opt <= 1e-8."
        )
        assert expect in text


@pytest.mark.parametrize(
    "fids, text",
    [
        ((), "none"),
        ((7,), "f7"),
        ((1, 2), "f1, f2"),
        ((3, 1, 2), "f1-f3"),
        (
            (1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 13, 14, 15, 17, 18, 19, 20, 23),
            "f1-f10, f12-f15, f17-f20, f23",
        ),
        ((11, 16, 21, 22, 24), "f11, f16, f21, f22, f24"),
    ],
)
def test_function_lists_name_every_function_once(fids, text):
    assert function_list(fids) == text


def test_no_headline_without_the_reference(tiny_store, tmp_path):
    write_suite_report(tiny_store, tmp_path, plots=False, reference="woa")
    assert not (tmp_path / "summary.md").exists()
