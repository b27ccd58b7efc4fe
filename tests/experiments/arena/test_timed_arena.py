"""Timed families in the arena (issue 27): the rows store T*, T/T* and the checker's active and
passive collisions; the sentences about them and about the swarm's share over ``guide_only``
state numbers recomputed here from the raw store with sqlite3."""

from __future__ import annotations

import statistics
from pathlib import Path

import numpy as np
import pytest

from mawdo.experiments import Store, run_plan
from mawdo.experiments.kinds.arena import ArenaPlan, arena_tables, write_arena_report
from mawdo.experiments.kinds.arena.plan import ARENA_PRESETS, TIMED_FAMILIES
from mawdo.experiments.kinds.arena.report import COLUMNS
from mawdo.experiments.kinds.arena.share import share_rows
from mawdo.experiments.kinds.arena.summary import (
    GAP_NOTE,
    headline,
    strengths,
    timed_lines,
    worst_runs,
)
from mawdo.planning.scenes import generate_scene

from .test_summary import _sql

TIMED = {
    "name": "timed-tiny",
    "families": ["forest", "doorway"],
    "n": 2,
    "algorithms": ["mawdo"],
    "baselines": ["guide_only", "straight"],
    "planner": "quick",
    "seed": 3,
    "batch_size": 1,
}


@pytest.fixture(scope="module")
def timed_store(tmp_path_factory) -> Path:
    db = tmp_path_factory.mktemp("timed") / "timed.db"
    assert run_plan(ArenaPlan.from_dict(TIMED), db, progress=False).complete
    return db


def test_the_default_arena_holds_the_timed_families_and_the_guide_alone():
    preset = ARENA_PRESETS["arena-default"]
    assert set(TIMED_FAMILIES) <= set(preset["families"]) and len(preset["families"]) == 12
    assert "guide_only" in preset["baselines"] and preset["n"] == 50


def test_timed_rows_store_the_scenes_earliest_arrival_and_the_time_gap(timed_store):
    rows = _sql(
        timed_store,
        "SELECT algorithm, problem, run, t_star, time_gap, success, active_collisions, "
        "passive_collisions, collision_free FROM runs WHERE status = 'ok'",
    )
    assert len(rows) == 3 * 2 * 2
    for algo, fam, run, t_star, time_gap, success, active, passive, free in rows:
        if fam == "forest":  # a static family has no T*
            assert t_star is None and time_gap is None and active is None
            continue
        assert t_star == pytest.approx(generate_scene(fam, run, seed=TIMED["seed"]).t_star)
        assert active is not None and passive is not None
        assert (active + passive > 0) == (not free) or algo == "straight"
        if success:
            # time_gap = arrival step / T*: an integer number of steps over T*
            steps = time_gap * t_star
            assert steps == pytest.approx(round(steps), abs=1e-6)
        else:
            assert time_gap is None or np.isnan(time_gap)


def test_timed_sentences_are_the_stores(timed_store):
    with Store.read(timed_store) as store:
        lines = timed_lines(store)
    rows = _sql(
        timed_store,
        "SELECT algorithm, success, time_gap, active_collisions FROM runs "
        "WHERE problem = 'doorway' AND status = 'ok' AND error_text IS NULL",
    )
    # the planners that predict motion: mawdo and guide_only (straight does not)
    assert [s.split(" on the ")[0] for s in lines] == ["- mawdo", "- guide_only"]
    for line in lines:
        mine = [r for r in rows if r[0] == line[2:].split(" ")[0]]
        succ = 100 * sum(r[1] for r in mine) / len(mine)
        gaps = [r[2] for r in mine if r[1]]
        active = sum(r[3] for r in mine)
        assert f"{succ:.1f} % success over {len(mine)} scenes with an earliest arrival T*" in line
        assert f", {active} active collisions," in line
        assert f"T/T* median {statistics.median(gaps):.3f}" in line
        assert f"p95 {np.percentile(gaps, 95):.3f}" in line
        early = [g for g in gaps if g < 1.0]
        if early:
            assert f"; {len(early)} runs arrived before T* (lowest T/T* {min(early):.3f}:" in line
        else:
            assert "arrived before T*" not in line


# the gap each run is judged by, computed independently of summary.judged_gap
JUDGED = "CASE WHEN t_star IS NOT NULL THEN time_gap ELSE gap END"


def test_headline_judges_timed_scenes_by_arrival_time_and_static_ones_by_length(timed_store):
    with Store.read(timed_store) as store:
        lines = headline(store)
        worst = worst_runs(store, "mawdo", k=4)
        tail = strengths(store)
    assert lines[0] == GAP_NOTE
    line = next(s for s in lines if s.startswith("- mawdo: "))
    gaps = [
        g
        for (g,) in _sql(
            timed_store,
            f"SELECT {JUDGED} FROM runs WHERE algorithm = 'mawdo' AND status = 'ok' "
            "AND error_text IS NULL AND success = 1",
        )
    ]
    assert f"median gap {statistics.median(gaps):.3f};" in line
    (g, fam) = max(
        _sql(
            timed_store,
            f"SELECT {JUDGED}, problem FROM runs WHERE algorithm = 'mawdo' AND status = 'ok' "
            "AND error_text IS NULL AND success = 1",
        )
    )
    assert f"mawdo {g:.3f} ({fam})" in next(s for s in tail if s.startswith("- Largest gap"))
    # the worst successes come by the judged gap, largest first
    judged = [r.time_gap if r.t_star is not None else r.gap for _, r in worst if r.success]
    assert judged == sorted(judged, reverse=True)


def test_swarm_share_compares_each_family_on_the_scenes_both_solve(timed_store):
    from scipy.stats import wilcoxon

    with Store.read(timed_store) as store:
        rows = {r["family"]: r for r in share_rows(store)}
    assert set(rows) == {"forest", "doorway"}
    for fam, col, sign in (("forest", "gap", "L/L*"), ("doorway", "time_gap", "T/T*")):
        got = {}
        for algo in ("mawdo", "guide_only"):
            got[algo] = dict(
                _sql(
                    timed_store,
                    f"SELECT scene_name, {col} FROM runs WHERE algorithm = ? AND problem = ? "
                    "AND status = 'ok' AND success = 1",
                    algo,
                    fam,
                )
            )
        both = sorted(set(got["mawdo"]) & set(got["guide_only"]))
        assert both, f"the tiny study needs a {fam} scene both solve"
        a = np.array([got["mawdo"][n] for n in both])
        b = np.array([got["guide_only"][n] for n in both])
        r = rows[fam]
        assert (r["gap"], r["pairs"]) == (sign, len(both))
        assert r["median"] == pytest.approx(statistics.median(a))
        assert r["base median"] == pytest.approx(statistics.median(b))
        d = a - b
        d = d[~np.isclose(a, b, rtol=1e-9, atol=0)]
        assert r["test"].pvalue == (pytest.approx(wilcoxon(d).pvalue) if d.size else 1.0)


def test_report_table_and_swarm_figure(timed_store, tmp_path):
    with Store.read(timed_store) as store:
        (table,) = arena_tables(store)
    by = {(r[0], r[1]): dict(zip(COLUMNS, r, strict=True)) for r in table.rows}
    cell = by["doorway", "MAWDO"]
    gaps = [
        g
        for (g,) in _sql(
            timed_store,
            "SELECT time_gap FROM runs WHERE algorithm = 'mawdo' AND problem = 'doorway' "
            "AND success = 1",
        )
    ]
    assert cell["T/T* median"] == pytest.approx(np.percentile(gaps, 50))
    assert np.isnan(by["forest", "MAWDO"]["T/T* median"])
    write_arena_report(timed_store, tmp_path, gallery_limit=0, worst=0)
    assert (tmp_path / "swarm.png").stat().st_size > 10_000
    report = (tmp_path / "arena.md").read_text(encoding="utf-8")
    assert "swarm.png" in report
    assert (tmp_path / "swarm_share.md").read_text(encoding="utf-8") in report
