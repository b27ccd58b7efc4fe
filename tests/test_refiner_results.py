"""Which swarm refines best (docs/planning.md, "Which optimizer refines best"): the numbers the
page quotes for the paper's cost and for comfort among people are those of the committed arena
and crowd stores, recomputed here; and committed crowd episodes of the other swarms run again
give the stored outcome."""

from __future__ import annotations

import json
import lzma
import shutil
import sqlite3
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "docs" / "results"


def _page() -> str:
    return " ".join((ROOT / "docs" / "planning.md").read_text(encoding="utf-8").split())


def _unpack(folder: str, tmp_path: Path) -> Path:
    db = tmp_path / f"{folder}.db"
    with lzma.open(RESULTS / folder / "store.db.xz") as src, open(db, "wb") as out:
        shutil.copyfileobj(src, out)
    return db


def test_the_arena_comparison_with_mawdo_is_the_stores(tmp_path):
    from mawdo.experiments import Store
    from mawdo.experiments.kinds.arena.share import share_rows

    with Store.read(_unpack("arena-default", tmp_path)) as store:
        rows = {(r["planner"], r["family"]): r for r in share_rows(store, base="mawdo")}
    woa_shorter = sorted(f for (p, f), r in rows.items() if p == "woa" and r["verdict"] == "helps")
    assert woa_shorter == ["corridor"]
    assert f"{-rows['woa', 'corridor']['mean difference']:.2g}" == "0.0015"
    # the guide gate took every plan of the three on the static families: the same routes
    for p in ("woa", "gwo"):
        for f in ("forest", "rooms", "maze", "u_trap"):
            assert rows[p, f]["differ"] == 0 and rows[p, f]["pairs"] == 50, (p, f)
    dense = rows["woa", "dense"]
    assert dense["verdict"] == "hurts" and f"{dense['mean difference']:.1g}" == "0.009"
    assert (f"{dense['median']:.3f}", f"{dense['base median']:.3f}") == ("1.011", "1.005")
    gwo = {f: r for (p, f), r in rows.items() if p == "gwo"}
    assert [f for f, r in gwo.items() if r["verdict"] == "helps"] == []
    assert gwo["dense"]["verdict"] == "hurts"
    assert f"{gwo['dense']['mean difference']:.2g}" == "0.026"
    page = _page()
    assert "WOA's routes are shorter than MAWDO's only in corridor, by 0.0015 in T/T*" in page
    assert "longer in `dense` by 0.009 (median L/L* 1.011 against 1.005)" in page
    assert "GWO is shorter nowhere and longer in `dense` by 0.026" in page


def test_the_crowd_comparison_with_mawdo_is_the_stores(tmp_path):
    from mawdo.experiments import Store
    from mawdo.experiments.kinds.crowd import crowd_summary
    from mawdo.experiments.kinds.crowd.report import crowd_share

    c5, c10 = "circle-5-invisible", "circle-10-invisible"
    with Store.read(_unpack("crowdnav-refiners", tmp_path)) as store:
        assert store.plan.name == "crowdnav-refiners" and store.plan.n == 100
        vs_guide = {(p, r["setting"]): r for p in ("mawdo", "woa", "gwo", "wdo_plus")
                    for r in crowd_share(store, p, "guide_only")}  # fmt: skip
        vs_mawdo = {(p, r["setting"]): r for p in ("woa", "gwo", "wdo_plus")
                    for r in crowd_share(store, p, "mawdo")}  # fmt: skip
        summary = crowd_summary(store)
    worst = max(r["time_s_holm"] for r in vs_guide.values())
    assert all(r["time_s_verdict"] == "helps" for r in vs_guide.values())
    gains = {p: r["time_s"][1] - r["time_s"][0] for (p, s), r in vs_guide.items() if s == c10}
    assert max(gains, key=gains.get) == "mawdo"
    m10 = vs_guide["mawdo", c10]["time_s"]
    page = _page()
    assert f"(Holm p <= {worst:.2g})" in page
    assert f"MAWDO gains the most ({m10[0]:.2f} s against {m10[1]:.2f} s)" in page
    same = {p: [vs_mawdo[p, s] for s in (c5, c10)] for p in ("woa", "wdo_plus")}
    assert all(r["time_s_verdict"] == "no measurable difference" for v in same.values() for r in v)
    woa, plus = same["woa"], same["wdo_plus"]
    assert (
        f"time p = {woa[0]['time_s_holm']:.2g} with 5 people, {woa[1]['time_s_holm']:.2g}" in page
    )
    assert f"({plus[0]['time_s_holm']:.2g} and {plus[1]['time_s_holm']:.2g})" in page
    slower = sorted((p, s) for (p, s), r in vs_mawdo.items() if r["time_s_verdict"] == "hurts")
    assert slower == [("gwo", c10)]
    for p, s in slower:
        r = vs_mawdo[p, s]
        said = f"{r['time_s'][0]:.2f} s against {r['time_s'][1]:.2f} s, p = {r['time_s_holm']:.2g}"
        assert said in page, said
    assert all(r["discomfort_verdict"] == "no measurable difference" for r in vs_mawdo.values())
    caused = {p: [summary[s, p]["robot_caused"] for s in (c5, c10)] for p in vs_guide_policies()}
    assert not any(any(v) for v in caused.values())
    full = {p: all(summary[s, p]["success"] == 1 for s in (c5, c10)) for p in vs_guide_policies()}
    every = [p for p, v in full.items() if v]
    assert every == ["mawdo", "gwo"]
    assert "None causes a collision; MAWDO and GWO reach the goal in every episode" in page


def vs_guide_policies() -> tuple[str, ...]:
    return ("mawdo", "woa", "gwo", "wdo_plus")


EPISODES = [("woa", "circle-5-invisible", 0), ("wdo_plus", "circle-10-invisible", 1)]


@pytest.mark.parametrize(("policy", "setting", "run"), EPISODES)
def test_stored_refiner_episodes_are_what_the_code_computes(tmp_path, policy, setting, run):
    from mawdo.experiments.kinds.crowd.execute import episode_row, run_one
    from mawdo.experiments.kinds.crowd.plan import CrowdPlan
    from mawdo.experiments.protocol import Task

    con = sqlite3.connect(_unpack("crowdnav-refiners", tmp_path))
    plan = CrowdPlan.from_dict(json.loads(con.execute("SELECT plan_json FROM meta").fetchone()[0]))
    fields = ("success", "robot_caused", "steps", "time_s", "length_m", "discomfort")
    stored = con.execute(
        f"SELECT {', '.join(fields)} FROM runs WHERE algorithm = ? AND problem = ? AND run = ?",
        (policy, setting, run),
    ).fetchone()
    con.close()
    spec = plan.task_spec(Task(policy, setting, run, 1))
    res, scene = run_one(spec, setting, spec["seeds"][0])
    row = episode_row(res, scene)
    assert tuple(row[f] for f in fields) == stored
