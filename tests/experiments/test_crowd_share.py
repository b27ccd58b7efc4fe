"""mawdo against guide_only in the crowd report, episode by episode, on a hand-built store whose
answer is known by construction (p-values: scipy's Wilcoxon on the same numbers; Holm by hand)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import wilcoxon

from mawdo.experiments import Store
from mawdo.experiments.kinds.crowd import CrowdPlan, write_crowd_report
from mawdo.experiments.kinds.crowd.execute import CrowdRow
from mawdo.experiments.kinds.crowd.report import crowd_share, crowd_share_table

from .arena.test_share import hand_store

N = 12
CIRCLE, SQUARE = "circle-5-invisible", "square-5-visible"
PLAN = {"name": "crowd-by-hand", "settings": [CIRCLE, SQUARE], "n": N,
        "policies": ["mawdo", "guide_only"], "batch_size": N}  # fmt: skip
TIME = 10.0 + 0.25 * np.arange(N)  # guide_only's time to goal, episode k
FASTER = TIME - 0.05 * (1 + np.arange(N))  # mawdo on the circle: faster by distinct amounts
CALM = np.full(N, 0.01)  # discomfort
TENSE = CALM + 0.001 * (1 + np.arange(N))  # mawdo on the square: closer to people every time
FAILS = {("guide_only", CIRCLE): {0}, ("mawdo", SQUARE): {0, 1}}  # robot-caused collisions


def _row(k: int, time: float, discomfort: float, failed: bool) -> CrowdRow:
    return CrowdRow(run=k, wall_time=1.0, status="ok", people=5, visible=0,
                    success=int(not failed), robot_caused=int(failed), collision=int(failed),
                    timeout=0, time_s=None if failed else time, discomfort=discomfort,
                    min_separation_m=0.1, length_m=8.0, steps=40)  # fmt: skip


def _values(policy: str, setting: str) -> tuple[np.ndarray, np.ndarray]:
    if policy == "mawdo":
        return (FASTER, CALM) if setting == CIRCLE else (TIME, TENSE)
    return TIME, CALM


def _rows(policy: str, setting: str) -> list[CrowdRow]:
    time, disc = _values(policy, setting)
    bad = FAILS.get((policy, setting), set())
    return [_row(k, time[k], disc[k], k in bad) for k in range(N)]


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    plan = CrowdPlan.from_dict(PLAN)
    db = tmp_path_factory.mktemp("crowd") / "crowd.db"
    hand_store(db, plan, plan.policies, plan.settings, _rows)
    return db


def test_time_and_discomfort_are_tested_on_the_episodes_both_succeed(store):
    with Store.read(store) as st:
        circle, square = crowd_share(st)
    assert (circle["setting"], circle["pairs"]) == (CIRCLE, N - 1)
    assert (square["setting"], square["pairs"]) == (SQUARE, N - 2)
    assert circle["success"] == pytest.approx((1.0, (N - 1) / N))
    assert square["robot_caused"] == pytest.approx((2 / N, 0.0))
    # the circle: faster on each of the 11 pairs -> exact p = 2 / 2^11; Holm over 2 settings
    assert circle["time_s_test"].pvalue == pytest.approx(wilcoxon(FASTER[1:], TIME[1:]).pvalue)
    assert circle["time_s_test"].pvalue == pytest.approx(2 / 2 ** (N - 1))
    assert circle["time_s_holm"] == pytest.approx(2 * 2 / 2 ** (N - 1))
    assert circle["time_s_verdict"] == "helps"
    assert circle["time_s"] == pytest.approx((FASTER[1:].mean(), TIME[1:].mean()))
    # the square: the same times (p = 1), closer to people on each of the 10 pairs
    assert square["time_s_test"].pvalue == 1.0 and square["time_s_verdict"] == (
        "no measurable difference"
    )
    p = wilcoxon(TENSE[2:], CALM[2:]).pvalue
    assert square["discomfort_test"].pvalue == pytest.approx(p)
    assert square["discomfort_holm"] == pytest.approx(2 * p)
    assert square["discomfort_verdict"] == "hurts"
    assert circle["discomfort_holm"] == 1.0


def test_the_report_writes_the_table(store, tmp_path):
    write_crowd_report(store, tmp_path, figures=False)
    md = (tmp_path / "crowd_share.md").read_text(encoding="utf-8")
    assert md in (tmp_path / "crowd.md").read_text(encoding="utf-8")
    assert (tmp_path / "crowd_share.csv").exists() and (tmp_path / "crowd_share.tex").exists()
    with Store.read(store) as st:
        t = crowd_share_table(st)
    assert t.columns == [
        "policy", "setting", "pairs", "success", "guide_only success", "robot-caused",
        "guide_only robot-caused", "time (s)", "guide_only time (s)", "time p",
        "time p Holm", "time verdict", "discomfort", "guide_only discomfort",
        "discomfort p", "discomfort p Holm", "discomfort verdict",
    ]  # fmt: skip
    assert t.column("policy") == ["mawdo", "mawdo"]
    assert t.column("time verdict") == ["helps", "no measurable difference"]
    assert t.column("discomfort verdict") == ["no measurable difference", "hurts"]
    assert f"| mawdo | {SQUARE} | 10 | 0.833 | 1.000 | 0.167 | 0.000 |" in md


def test_every_swarm_in_mawdos_place_is_compared_and_nothing_else(tmp_path):
    # WOA drives like guide_only here (its rows are guide_only's values): no difference
    plan = CrowdPlan.from_dict({**PLAN, "policies": ["mawdo_oracle", "mawdo", "straight", "woa",
                                                     "guide_only"]})  # fmt: skip
    db = tmp_path / "crowd.db"
    hand_store(db, plan, plan.policies, plan.settings, _rows)
    with Store.read(db) as st:
        t = crowd_share_table(st)
        mawdo_rows = crowd_share(st, "mawdo")
    assert t.column("policy") == ["mawdo", "mawdo", "woa", "woa"]
    assert t.column("setting") == [CIRCLE, SQUARE, CIRCLE, SQUARE]
    assert t.column("time verdict")[:2] == [r["time_s_verdict"] for r in mawdo_rows]
    assert t.column("time p")[2:] == [1.0, 1.0]  # the same times as guide_only's
    assert t.column("pairs")[2:] == [N - 1, N]  # guide_only's failure on the circle


def test_no_table_unless_both_policies_ran(tmp_path):
    plan = CrowdPlan.from_dict({**PLAN, "policies": ["mawdo", "straight"]})
    with Store.open(tmp_path / "s.db", plan) as st:
        assert crowd_share_table(st) is None and crowd_share(st) == []
