"""The arena's headline sentences state numbers recomputed from the raw store; the worst runs
come failures first, then by gap, and their images are re-runs that reproduce the stored run."""

from __future__ import annotations

import hashlib
import re
import sqlite3
import statistics

import pytest

from mawdo.experiments import Store
from mawdo.experiments.kinds.arena.summary import headline, render_worst, strengths, worst_runs

from .test_arena import reference  # noqa: F401 - the module's tiny study, as a fixture


def raw(db, planner):
    conn = sqlite3.connect(db)
    try:
        return conn.execute(
            "SELECT success, collision_free, CASE WHEN t_star IS NOT NULL THEN time_gap "
            "ELSE gap END, problem FROM runs WHERE algorithm = ? "
            "AND status = 'ok' AND error_text IS NULL",
            (planner,),
        ).fetchall()
    finally:
        conn.close()


def test_headline_numbers_are_the_stores(reference):  # noqa: F811
    with Store.read(reference) as store:
        lines = headline(store)[:2]
    assert [s.split(":")[0] for s in lines] == ["- mawdo", "- straight"]
    for line in lines:
        planner = line[2:].split(":")[0]
        rows = raw(reference, planner)
        succ = 100 * sum(r[0] for r in rows) / len(rows)
        coll = 100 * sum(r[1] == 0 for r in rows) / len(rows)
        m = re.search(r"([\d.]+) % success and ([\d.]+) % colliding runs over (\d+) scenes", line)
        assert m, line
        assert float(m[1]) == round(succ, 1) and float(m[2]) == round(coll, 1)
        assert int(m[3]) == len(rows)
        gaps = [r[2] for r in rows if r[0]]
        if gaps:
            assert f"median gap {statistics.median(gaps):.3f};" in line


def test_worst_runs_put_failures_first_then_the_largest_gaps(reference):  # noqa: F811
    with Store.read(reference) as store:
        worst = worst_runs(store, "straight", k=6)
    bad = [not (r.success and r.collision_free) for _, r in worst]
    assert bad == sorted(bad, reverse=True)  # every failure before every success
    gaps = [r.gap for _, r in worst if r.success and r.collision_free]
    assert gaps == sorted(gaps, reverse=True)
    assert len(worst) == len(raw(reference, "straight"))


def test_worst_images_are_reruns_of_the_stored_runs(reference, tmp_path):  # noqa: F811
    made = render_worst(reference, tmp_path, "mawdo", k=2)
    assert len(made) == 2
    with Store.read(reference) as store:
        expect = [r.scene_name for _, r in worst_runs(store, "mawdo", k=2)]
    assert [m["scene"] for m in made] == expect
    for m in made:
        assert (tmp_path / m["image"]).stat().st_size > 10_000
        text = (tmp_path / m["scene_file"]).read_text(encoding="utf-8")
        conn = sqlite3.connect(reference)
        try:
            (stored,) = conn.execute(
                "SELECT scene_hash FROM runs WHERE algorithm = 'mawdo' AND scene_name = ?",
                (m["scene"],),
            ).fetchone()
        finally:
            conn.close()
        assert hashlib.sha256(text.encode("utf-8")).hexdigest() == stored


def _sql(db, query, *args):
    conn = sqlite3.connect(db)
    try:
        return conn.execute(query, args).fetchall()
    finally:
        conn.close()


def test_strength_sentences_are_the_stores(reference):  # noqa: F811
    with Store.read(reference) as store:
        lines = strengths(store)
        assert headline(store)[-len(lines) :] == lines
    ok = "status = 'ok' AND error_text IS NULL"
    hit = {
        n
        for (n,) in _sql(
            reference,
            f"SELECT scene_name FROM runs WHERE algorithm = 'straight' AND {ok} "
            "AND collision_free = 0",
        )
    }
    assert hit, "the tiny study needs a colliding straight line"
    ours = [
        r
        for r in _sql(
            reference,
            f"SELECT scene_name, success, gap FROM runs WHERE algorithm = 'mawdo' AND {ok}",
        )
        if r[0] in hit
    ]
    succ = 100 * sum(r[1] for r in ours) / len(ours)
    won = [r[2] for r in ours if r[1]]
    gap = f"median gap {statistics.median(won):.3f}" if won else "no successful run"
    expect = [
        f"- On the {len(hit)} scenes where straight's route collides: "
        f"mawdo {succ:.0f} % success, {gap}."
    ]
    gaps = _sql(
        reference,
        f"SELECT gap, problem FROM runs WHERE algorithm = 'mawdo' AND {ok} AND success = 1",
    )
    if gaps:
        g, fam = max(gaps)
        expect.append(f"- Largest gap of a successful run: mawdo {g:.3f} ({fam}).")
    p95 = {}
    for fam, v in _sql(
        reference,
        f"SELECT problem, latency_p95_ms FROM runs WHERE algorithm = 'mawdo' AND {ok}",
    ):
        if v is not None:  # a run whose plan was held to the goal has no replan
            p95.setdefault(fam, []).append(v)
    meds = [statistics.median(v) for v in p95.values()]
    expect.append(
        "- Replan latency p95, median over a family's scenes, lowest-highest family: "
        f"mawdo {min(meds):.1f}-{max(meds):.1f} ms (wall time on the machine that ran the study)."
    )
    assert lines == expect


def test_a_long_report_says_what_it_is_doing(reference, tmp_path):  # noqa: F811
    """The report's sub-steps reach a listener (the command's spinner or log lines): the
    tables, the figures, each gallery image and each re-run worst scene."""
    from mawdo.experiments.kinds.arena import write_arena_report
    from mawdo.experiments.progress import listening

    heard: list[str] = []
    with listening(heard.append):
        write_arena_report(reference, tmp_path, gallery_limit=2, worst=1)
    assert heard[:2] == ["tables and sentences", "ECDFs and the swarm's share"]
    assert "failure gallery: image 1 of at most 2" in heard
    assert "failure gallery: image 3 of at most 2" not in heard
    worst = [m for m in heard if m.startswith("re-running mawdo's worst scene 1 of 1 (")]
    assert len(worst) == 1


@pytest.mark.slow
def test_the_report_command_logs_its_sub_steps(reference, tmp_path):  # noqa: F811
    """In a log (stderr not a terminal) the report's step prints what it is doing, at most
    one line per 2 s, between its start and done lines."""
    import subprocess
    import sys

    proc = subprocess.run(
        [sys.executable, "-m", "mawdo.cli", "study", "report", str(reference), "--out",
         str(tmp_path / "rep")],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    msg = "writing the report of the arena study"
    lines = [s for s in proc.stderr.splitlines() if s.startswith("writing the report")]
    assert lines[0] == f"{msg} ..."
    assert lines[-1].startswith(f"{msg}: done in ")
    # between them, what the report is doing (how many lines depends on the machine's speed:
    # one at most every 2 s, progress.EVERY); its main steps, when shown, in their order
    order = ["tables and sentences", "ECDFs and the swarm's share", "failure gallery: image "]
    seen = []
    for line in lines[1:-1]:
        sub = line.removeprefix(f"{msg}: ")
        assert sub != line and sub.strip(), line
        seen += [k for k, o in enumerate(order) if sub.startswith(o)][:1]
    assert seen == sorted(seen)
