"""The committed hold-out study (docs/results/holdout) and the paragraph made from it.

The results page (docs/results.md) quotes ``summary.md`` verbatim (tests/test_readme_results.py
checks every committed summary); here the committed stores must give exactly that summary and
the rank table in docs/algorithms.md, and the numbers the page states (WDO+'s mean rank, place,
and its
better / worse / tied counts against each rival) are recomputed from the raw rows with sqlite3,
numpy and scipy, not with the code that wrote them.
"""

from __future__ import annotations

import lzma
import re
import shutil
import sqlite3
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import rankdata

ROOT = Path(__file__).resolve().parents[1]
HOLDOUT = ROOT / "docs" / "results" / "holdout"
STORES = ("cec2017", "cec2017_d30", "cec2022", "cec2022_d20", "paper", "paper_shifted")
RIVALS = {"CMA-ES": "cmaes", "DE (scipy)": "scipy_de", "GWO": "gwo", "MAWDO": "mawdo"}


@pytest.fixture(scope="module")
def stores(tmp_path_factory) -> list[Path]:
    """The committed stores (xz), unpacked, in report order."""
    folder = tmp_path_factory.mktemp("holdout")
    out = []
    for name in STORES:
        db = folder / f"{name}.db"
        with lzma.open(HOLDOUT / f"{name}.db.xz") as src, open(db, "wb") as dst:
            shutil.copyfileobj(src, dst)
        out.append(db)
    return out


def test_summary_and_rank_table_are_those_of_the_committed_stores(stores):
    from mawdo.experiments.kinds.suite.holdout_data import load_holdout
    from mawdo.experiments.kinds.suite.holdout_summary import headline, rank_table
    from mawdo.experiments.tables import to_markdown

    suites = [load_holdout(db) for db in stores]
    summary = (HOLDOUT / "summary.md").read_text(encoding="utf-8")
    assert headline(suites) == summary.splitlines()
    table = [s for s in to_markdown(rank_table(suites)).splitlines() if s.startswith("|")]
    for doc in (HOLDOUT / "ranks.md", ROOT / "docs" / "algorithms.md"):
        text = doc.read_text(encoding="utf-8")
        assert all(row in text for row in table), f"{doc.name} lacks the store's rank table"


def final_errors(db: Path) -> dict[tuple[str, str], float]:
    """Median over runs of the final f - f_opt, floored at 1e-8, per (algorithm, problem), from
    the raw columns: a suite row's last best-so-far minus f_star, a benchmark row's error."""
    conn = sqlite3.connect(db)
    cols = {r[1] for r in conn.execute("PRAGMA table_info(runs)")}
    if "best_so_far" in cols:
        rows = conn.execute(
            "SELECT algorithm, problem, best_so_far, f_star FROM runs WHERE error_text IS NULL"
        ).fetchall()
        errs = [(a, p, np.frombuffer(b, "<f8")[-1] - fs) for a, p, b, fs in rows]
    else:
        errs = conn.execute(
            "SELECT algorithm, problem, error FROM runs WHERE error_text IS NULL"
        ).fetchall()
    conn.close()
    acc: dict[tuple[str, str], list[float]] = {}
    for a, p, e in errs:
        acc.setdefault((a, p), []).append(max(float(e), 1e-8))
    return {k: float(np.median(v)) for k, v in acc.items()}


def test_the_stated_numbers_are_recomputed_from_the_raw_rows(stores):
    readme = (ROOT / "docs" / "results.md").read_text(encoding="utf-8")
    claims = re.findall(
        r"^[ -]*(.+?), \d+ evaluations per run \([^)]*\), \d+ runs, (\d+) functions: WDO\+ "
        r"([\d.]+), place (\d+) of (\d+),.*?; better / worse / tied on (.+?)\.$",
        readme,
        flags=re.MULTILINE,
    )
    assert [c[0] for c in claims] == [
        "CEC 2017 F1-F29, D = 10",
        "CEC 2017 F1-F29, D = 30",
        "CEC 2022 F1-F12, D = 10",
        "CEC 2022 F1-F12, D = 20",
        "F1-F16 unshifted",
        "F1-F16 shifted",
    ]
    for db, (_, n, rank, at, of, counts) in zip(stores, claims, strict=True):
        med = final_errors(db)
        algos = sorted({a for a, _ in med})
        problems = sorted({p for _, p in med})
        full = [p for p in problems if all((a, p) in med for a in algos)]
        ranks = np.mean([rankdata([med[a, p] for a in algos]) for p in full], axis=0)
        mine = ranks[algos.index("wdo_plus")]
        assert int(n) == len(full) and int(of) == len(algos) == 10
        assert float(rank) == pytest.approx(mine, abs=0.005)
        assert int(at) == 1 + int(np.sum(ranks < mine))
        for b, w, t, rival in re.findall(r"(\d+) / (\d+) / (\d+) against ([^,]+)", counts):
            both = [p for p in problems if ("wdo_plus", p) in med and (RIVALS[rival], p) in med]
            x = np.array([med["wdo_plus", p] for p in both])
            y = np.array([med[RIVALS[rival], p] for p in both])
            assert (int(b), int(w), int(t)) == (
                int(np.sum(x < y)),
                int(np.sum(x > y)),
                int(np.sum(x == y)),
            ), rival


def test_the_stores_are_the_registered_reduced_plans(stores):
    """Each store holds the plan its docs name: the quick CEC presets as they were when the
    suites cec2017/cec2022 meant opfunu's functions (CEC 2017: opfunu's F1-F29, the official
    F1 and F3-F30 the presets now name), and the F1-F16 presets with their runs and iterations
    cut (the commands in docs/results/holdout/README.md)."""
    from mawdo.experiments import Store
    from mawdo.experiments.kinds.benchmark.plan import PRESETS, ExperimentPlan
    from mawdo.experiments.kinds.suite import preset_plan
    from mawdo.experiments.kinds.suite.plan import PRESETS as SUITE_PRESETS
    from mawdo.experiments.kinds.suite.plan import SuitePlan
    from mawdo.suites.cec import official_id

    old17 = {**SUITE_PRESETS["holdout-quick-cec2017"], "functions": list(range(1, 30))}
    now = preset_plan("holdout-quick-cec2017").functions  # opfunu's F1-F29, by formula
    assert tuple(official_id(2017, f) for f in old17["functions"]) == now
    expected = [
        SuitePlan.from_dict(old17, stored=True),
        SuitePlan.from_dict({**old17, "dims": [30]}, stored=True),
        SuitePlan.from_dict(SUITE_PRESETS["holdout-quick-cec2022"], stored=True),
        SuitePlan.from_dict({**SUITE_PRESETS["holdout-quick-cec2022"], "dims": [20]}, stored=True),
        ExperimentPlan.from_dict({**PRESETS["holdout-paper"], "runs": 2, "max_iter": 200}),
        ExperimentPlan.from_dict({**PRESETS["holdout-paper-shifted"], "runs": 2, "max_iter": 200}),
    ]
    # summary.md: the full F1-F16 presets ask "50 x 500 evaluations and 30 runs"
    assert (PRESETS["holdout-paper"]["max_iter"], PRESETS["holdout-paper"]["runs"]) == (500, 30)
    for db, plan in zip(stores, expected, strict=True):
        with Store.read(db) as store:
            assert store.meta["plan_hash"] == plan.plan_hash, db.name
