"""The swarm's share table and sentences on a hand-built store whose answer is known by
construction: the p-values are scipy's Wilcoxon on the same numbers, Holm is done by hand."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import wilcoxon

from mawdo.experiments import Store
from mawdo.experiments.kinds.arena import ArenaPlan
from mawdo.experiments.kinds.arena.execute import ArenaRow
from mawdo.experiments.kinds.arena.share import (
    HELPS,
    HURTS,
    SAME,
    holm_verdicts,
    share_columns,
    share_rows,
    share_table,
    signed_rank,
    swarm_share,
)
from mawdo.experiments.kinds.arena.summary import headline
from mawdo.experiments.tables import to_csv, to_markdown

N = 10
PLAN = {
    "name": "share-by-hand",
    "families": ["forest", "dense", "doorway"],
    "n": N,
    "algorithms": ["mawdo", "woa"],
    "baselines": ["guide_only"],
    "planner": "quick",
    "seed": 0,
    "batch_size": 1,
}
BASE = 1.02 + 0.01 * np.arange(N)  # guide_only's gaps, scene k
# forest: mawdo shorter on every scene, by distinct amounts (no tied ranks)
FOREST = BASE - 0.001 * (1 + np.arange(N))
# doorway (timed): mawdo fails scenes 0 and 1 (the guide solves them), solves scene 2 (the
# guide fails it), and is slower on the 7 scenes both solve
DOORWAY = BASE + 0.002 * (1 + np.arange(N))
MAWDO_FAILS, GUIDE_FAILS = {0, 1}, {2}


def _row(k: int, family: str, gap: float, success: bool, latency: float,
         counts: tuple = (None, None)) -> ArenaRow:  # fmt: skip
    timed = family == "doorway"
    won = gap if success else float("nan")
    return ArenaRow(run=k, wall_time=0.1, status="ok", scene_name=f"{family}-{k}",
                    scene_toml="", scene_hash="h", l_star=100.0, planner_seed=k,
                    success=int(success), collision_free=int(success), length=100.0 * gap,
                    gap=won, latency_p95_ms=latency, t_star=40.0 if timed else None,
                    time_gap=won if timed else None, replans=counts[0],
                    gated=counts[1])  # fmt: skip


def _counts(planner: str, family: str, k: int) -> tuple:
    """(replans, gated): mawdo's every plan gated on even forest scenes (no search there), one
    of three elsewhere; woa's counts not stored (a store made before they were)."""
    if planner == "woa":
        return None, None
    return 3, 3 if (planner == "mawdo" and family == "forest" and k % 2 == 0) else 1


def _gaps(planner: str, family: str) -> tuple[np.ndarray, set[int]]:
    """(gaps per scene, failed scenes) of ``planner`` on ``family``, by construction."""
    if planner == "guide_only":
        return BASE, GUIDE_FAILS if family == "doorway" else set()
    if planner == "mawdo" and family == "forest":
        return FOREST, set()
    if planner == "mawdo" and family == "doorway":
        return DOORWAY, MAWDO_FAILS
    # woa and mawdo on dense: exactly the guide's gaps, up to float rounding on scene 0
    return BASE + np.r_[1e-16, np.zeros(N - 1)], GUIDE_FAILS if family == "doorway" else set()


def hand_store(db, plan, who, where, rows_of) -> None:
    """A store at ``db`` holding ``rows_of(who, where)`` for every pair (one task each)."""
    with Store.open(db, plan) as st:
        for a in who:
            for p in where:
                rows = rows_of(a, p)
                task = {"algorithm": a, "problem": p, "first_run": 0, "n_runs": len(rows)}
                st.write_task({"task": task, "rows": rows, "wall": 1.0, "worker": "test"})


def _rows(planner: str, family: str) -> list[ArenaRow]:
    gaps, failed = _gaps(planner, family)
    lat = 10.0 if planner == "guide_only" else 50.0
    return [_row(k, family, gaps[k], k not in failed, lat + k, _counts(planner, family, k))
            for k in range(N)]  # fmt: skip


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    plan = ArenaPlan.from_dict(PLAN)
    db = tmp_path_factory.mktemp("share") / "share.db"
    hand_store(db, plan, plan.planners, plan.families, _rows)
    with Store.read(db) as st:
        yield st


def _by(store) -> dict[tuple[str, str], dict]:
    return {(r["planner"], r["family"]): r for r in share_rows(store)}


def test_a_planner_better_on_every_pair_helps_with_scipys_exact_p(store):
    r = _by(store)["mawdo", "forest"]
    assert r["pairs"] == r["test"].n == r["test"].differ == N
    assert r["test"].pvalue == pytest.approx(wilcoxon(FOREST, BASE).pvalue)
    assert r["test"].pvalue == pytest.approx(2 / 2**N)  # every sign negative: 2 of 2^n
    assert r["test"].lower and r["verdict"] == HELPS
    assert r["median"] == pytest.approx(np.median(FOREST))
    assert r["base median"] == pytest.approx(np.median(BASE))
    assert r["median ratio"] == pytest.approx(np.median(FOREST / BASE))
    assert r["mean difference"] == pytest.approx(np.mean(FOREST - BASE))
    assert r["latency"] == pytest.approx(50.0 + np.median(np.arange(N)))
    assert r["base latency"] == pytest.approx(10.0 + np.median(np.arange(N)))


def test_identical_gaps_are_no_measurable_difference_with_p_one(store):
    for key in [("mawdo", "dense"), ("woa", "forest"), ("woa", "dense")]:
        r = _by(store)[key]
        # scene 0 differs by 1e-16, float rounding of the same route: a tie, not a vote
        assert r["pairs"] == N and r["test"].differ == 0, key
        assert r["test"].pvalue == 1.0 and r["p holm"] == 1.0 and r["verdict"] == SAME, key
        assert r["mean difference"] == 0.0 and r["median ratio"] == pytest.approx(1.0)


def test_failed_scenes_are_counted_and_left_out_of_the_pairs(store):
    r = _by(store)["mawdo", "doorway"]
    assert r["gap"] == "T/T*" and _by(store)["mawdo", "forest"]["gap"] == "L/L*"
    both = sorted(set(range(N)) - MAWDO_FAILS - GUIDE_FAILS)
    assert r["pairs"] == len(both) == 7
    assert r["success"] == pytest.approx((N - len(MAWDO_FAILS)) / N)
    assert r["base success"] == pytest.approx((N - len(GUIDE_FAILS)) / N)
    assert (r["only planner"], r["only base"]) == (len(GUIDE_FAILS), len(MAWDO_FAILS))
    assert r["test"].pvalue == pytest.approx(wilcoxon(DOORWAY[both], BASE[both]).pvalue)
    assert not r["test"].lower and r["verdict"] == HURTS


def test_holm_is_over_the_families_of_one_planner(store):
    """By hand: p_forest = 2/2^10 < p_doorway = 2/2^7 < p_dense = 1, so Holm multiplies them
    by 3, 2 and 1, each at least the one before."""
    by = _by(store)
    p_f, p_d = 2 / 2**N, 2 / 2**7
    assert by["mawdo", "forest"]["p holm"] == pytest.approx(3 * p_f)
    assert by["mawdo", "doorway"]["p holm"] == pytest.approx(max(3 * p_f, 2 * p_d))
    assert by["mawdo", "dense"]["p holm"] == 1.0


def test_holm_verdicts_by_hand():
    tests = [signed_rank([1, 2], [1, 2]), signed_rank([], []), signed_rank([0.5] * 3, [1] * 3)]
    assert tests[1].n == 0 and np.isnan(tests[1].pvalue)
    (p0, v0), (p1, v1), (p2, v2) = holm_verdicts(tests)
    # two tests have pairs: p = (1, 0.25) -> Holm (1, 0.5)
    assert (p0, v0) == (1.0, SAME) and np.isnan(p1) and v1 == "no pairs"
    assert p2 == pytest.approx(min(1.0, 2 * wilcoxon([-0.5] * 3).pvalue)) and v2 == SAME
    with pytest.raises(ValueError, match="differ in length"):
        signed_rank([1, 2], [1])


def test_the_table_columns_and_rows(store):
    t = share_table(store)
    assert t.name == "swarm_share"
    assert t.columns == share_columns("guide_only") == [
        "planner", "family", "gap", "pairs", "success", "guide_only success", "only planner",
        "only guide_only", "gap median", "guide_only gap median", "median ratio", "differ",
        "mean difference", "p", "p Holm", "verdict", "latency p95 (ms)",
        "guide_only latency p95 (ms)", "runs searched",
    ]  # fmt: skip
    assert [(r[0], r[1]) for r in t.rows] == [
        (p, f) for p in ("MAWDO", "WOA") for f in ("forest", "dense", "doorway")
    ]
    assert t.column("verdict") == [HELPS, SAME, HURTS, SAME, SAME, SAME]
    assert t.column("pairs") == [N, N, 7, N, N, 9]
    # over each planner's runs (failed ones too); unknown where the store holds no counts
    assert t.column("runs searched") == [N // 2, N, N, None, None, None]
    md = to_markdown(t)
    assert "| MAWDO | doorway | T/T* | 7 | 80% | 90% | 1 | 2 |" in md
    assert len(to_csv(t).splitlines()) == 1 + len(t.rows)


def test_the_summary_line_per_planner(store):
    lines = swarm_share(store)
    assert headline(store)[-2:] == lines
    by = _by(store)
    f, d = by["mawdo", "forest"], by["mawdo", "doorway"]
    lead = (
        "against guide_only (the same planner without its optimizer; Wilcoxon signed-rank test "
        "of the paired gaps on the scenes both solve, Holm over 3 families, 0.05)"
    )
    assert lines == [
        f"- mawdo {lead}: helps on forest (L/L* differs on 10 of 10 scenes, mean difference "
        f"{np.mean(FOREST - BASE):+.2g}, Holm p = {f['p holm']:.2g}); hurts on doorway (T/T* "
        f"differs on 7 of 7 scenes, mean difference {d['mean difference']:+.2g}, Holm p = "
        f"{d['p holm']:.2g}); no measurable difference on the other family.",
        f"- woa {lead}: helps on no family; hurts on no family; no measurable difference on "
        "the other 3 families.",
    ]


def test_no_table_without_the_guide(tmp_path):
    plan = ArenaPlan.from_dict({**PLAN, "baselines": ["straight"]})
    with Store.open(tmp_path / "s.db", plan) as st:
        assert share_table(st) is None and swarm_share(st) == [] and share_rows(st) == []
