"""The committed results as the README and the results page state them.

The reports write their claims as sentences computed from the store (``summary.md``); the
results page (docs/results.md) quotes them verbatim, so a regenerated report that changes a
number fails here until the page follows. The README's tables are rendered from the committed
result files by docs/readme_tables.py; they must be exactly its rendering, and the numbers it
reads are recomputed here from the raw rows and tables.
"""

import contextlib
import csv
import hashlib
import importlib.util
import json
import lzma
import re
import shutil
import sqlite3
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import rankdata

ROOT = Path(__file__).resolve().parents[1]
SUMMARIES = sorted((ROOT / "docs" / "results").glob("**/summary.md"))
BBOB = ROOT / "docs" / "results" / "bbob"
RESULTS_PAGE = ROOT / "docs" / "results.md"


def readme_tables():
    """docs/readme_tables.py, the README tables' renderer."""
    spec = importlib.util.spec_from_file_location(
        "readme_tables", ROOT / "docs" / "readme_tables.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def unpack(packed: Path, folder: Path) -> Path:
    """A committed xz-compressed store, decompressed into ``folder``."""
    db = folder / packed.name.removesuffix(".xz")
    with lzma.open(packed) as src, open(db, "wb") as dst:
        shutil.copyfileobj(src, dst)
    return db


@pytest.mark.parametrize("summary", SUMMARIES, ids=lambda p: str(p.relative_to(ROOT)))
def test_the_results_page_quotes_the_generated_sentences(summary):
    page = RESULTS_PAGE.read_text(encoding="utf-8")
    lines = [s for s in summary.read_text(encoding="utf-8").splitlines() if s.strip()]
    assert lines, f"{summary} is empty"
    missing = [s for s in lines if s not in page]
    assert not missing, f"docs/results.md does not quote {summary}: {missing}"


def test_the_readme_tables_are_rendered_from_the_committed_results():
    """Run `python docs/readme_tables.py` after regenerating a report."""
    tables = readme_tables()
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    written = tables.tables_in(readme)
    assert (
        set(written)
        == set(tables.TABLES)
        == {
            "paper",
            "suites",
            "arena",
            "crowd",
            "swarm",
            "crowd_more",
        }
    )
    for name, render in tables.TABLES.items():
        rows = render()
        # a table: header, rule and at least three rows; the swarm's share, crowds: a sentence
        assert len(rows) == 1 if name in ("swarm", "crowd_more") else len(rows) >= 5, name
        assert written[name] == "\n".join(rows) + "\n", f"README table {name!r} is stale"
    assert tables.render(readme) == readme


def test_the_paper_table_ranks_are_those_of_the_committed_errors():
    """Friedman mean ranks recomputed from results_error.csv (mean error per function, rank 1 =
    best, ties averaged) agree with what the README's paper table states."""
    tables = readme_tables()
    for folder in ("paper-table3", "paper-table3-shifted", "paper-ablation"):
        path = ROOT / "docs" / "results" / folder / "results_error.csv"
        if folder == "paper-ablation":
            path = path.with_name("ablation_error.csv")
        with open(path, newline="", encoding="utf-8") as f:
            rows = [r for r in csv.DictReader(f) if r["Index"] == "Ave"]
        algos = [k for k in rows[0] if k not in ("Function", "Index")]
        ranks = np.mean([rankdata([float(r[a]) for a in algos]) for r in rows], axis=0)
        rank, place, of, best, best_rank = tables.friedman(folder, "MAWDO")
        mine = ranks[algos.index("MAWDO")]
        assert float(rank) == pytest.approx(mine, abs=0.005), folder
        assert (place, of) == (1 + int(np.sum(ranks < mine - 1e-12)), len(algos)), folder
        assert float(best_rank) == pytest.approx(ranks.min(), abs=0.005), folder


def test_the_readme_arena_table_is_the_store_s_headline():
    """Each arena row's success, colliding share and median gap is the headline sentence's."""
    tables = readme_tables()
    summary = (ROOT / "docs" / "results" / "arena-default" / "summary.md").read_text("utf-8")
    rows = tables.arena_table()[2:]
    assert len(rows) == 7
    for row in rows:
        planner, success, colliding, gap = (c.strip() for c in row.strip("|").split("|"))
        sentence = (
            f"- {planner}: {success.removesuffix(' %')} % success and "
            f"{colliding.removesuffix(' %')} % colliding runs over 600 scenes, median gap {gap};"
        )
        assert sentence in summary, row


@pytest.fixture(scope="module")
def bbob_stores(tmp_path_factory) -> list[Path]:
    """The committed BBOB stores (xz, one per dimension), unpacked."""
    folder = tmp_path_factory.mktemp("bbob")
    return [unpack(BBOB / f"store-d{d}.db.xz", folder) for d in (5, 20)]


def test_bbob_sentences_are_those_of_the_committed_store(bbob_stores):
    """The committed BBOB stores (xz, one per dimension) give exactly the committed sentences."""
    from mawdo.experiments.kinds.suite.data import load_runs
    from mawdo.experiments.kinds.suite.summary import headline

    summary = (BBOB / "summary.md").read_text(encoding="utf-8")
    assert headline(load_runs(bbob_stores)) == summary.splitlines()


def expand(listing: str) -> set[int]:
    """``"f1-f3, f7"`` -> ``{1, 2, 3, 7}``; ``"none"`` -> ``set()``."""
    out: set[int] = set()
    for part in listing.split(", "):
        if part != "none":
            a, _, b = part.partition("-")
            out |= set(range(int(a[1:]), int((b or a)[1:]) + 1))
    return out


def test_the_results_name_every_win_and_loss_against_random_search(bbob_stores):
    """ "median final precision is lower on 19 of 24" once read as worse and hid the five
    D = 5 functions where MAWDO's median error is above uniform random search's. Recomputed
    here from the raw rows with sqlite3 and numpy."""
    final: dict[tuple[str, int, int], list[float]] = {}
    for db in bbob_stores:
        rows = _query(
            db,
            "SELECT algorithm, function_id, dim, f_star, best_so_far FROM runs "
            "WHERE error_text IS NULL AND algorithm IN ('mawdo', 'random')",
        )
        for algo, fid, dim, f_star, best in rows:
            error = np.frombuffer(best, "<f8")[-1] - f_star
            final.setdefault((algo, fid, dim), []).append(max(error, 1e-8))
    readme = RESULTS_PAGE.read_text(encoding="utf-8")
    claims = re.findall(
        r"D = (\d+): median final error f - f_opt over instances and runs \(lower is better\), "
        r"mawdo against random: better on (\d+) of 24 functions \(([^)]*)\), worse on (\d+) "
        r"\(([^)]*)\), equal on (\d+)",
        readme,
    )
    assert [int(c[0]) for c in claims] == [5, 20]
    for dim, n_better, better, n_worse, worse, n_equal in claims:
        med = {
            (a, f): np.median(final[(a, f, int(dim))])
            for a in ("mawdo", "random")
            for f in range(1, 25)
        }
        truly_better = {f for f in range(1, 25) if med["mawdo", f] < med["random", f]}
        truly_worse = {f for f in range(1, 25) if med["mawdo", f] > med["random", f]}
        assert expand(better) == truly_better and int(n_better) == len(truly_better)
        assert expand(worse) == truly_worse and int(n_worse) == len(truly_worse)
        assert int(n_equal) == 24 - len(truly_better) - len(truly_worse)
    assert "precision is lower than" not in readme


def _query(db: Path, sql: str) -> list[tuple]:
    """Every row of ``sql`` on the store ``db`` (its connection closed after)."""
    with contextlib.closing(sqlite3.connect(db)) as conn:
        return conn.execute(sql).fetchall()


def stored_version(db: Path) -> str:
    return _query(db, "SELECT library_version FROM meta")[0][0]


def test_docs_say_which_mawdo_made_the_committed_stores(bbob_stores):
    """docs/bbob.md says resuming them is refused because of the version that made them."""
    docs = (BBOB.parents[2] / "docs" / "bbob.md").read_text(encoding="utf-8")
    said = re.findall(r"made by mawdo (\d+\.\d+\.\d+)", docs)
    assert said and set(said) == {stored_version(db) for db in bbob_stores}
    assert "nothing left to compute" not in docs
    report = (BBOB / "report.md").read_text(encoding="utf-8")
    assert f"made by mawdo {said[0]})" in report


def plain(text: str) -> str:
    """A CLI message on one line; it comes as plain ``error:`` lines, never in a frame."""
    assert not re.search(r"[│╭╮╰╯]", text), text
    return " ".join(text.split())


def test_resuming_a_committed_store_is_refused_and_keeps_its_runs(bbob_stores, tmp_path):
    db = shutil.copy(bbob_stores[0], tmp_path / "store-d5.db")
    before = hashlib.sha256(Path(db).read_bytes()).hexdigest()
    cmd = ["run", "--preset", "bbob-full", "--dims", "5", "--out", str(db)]
    done = subprocess.run(
        [sys.executable, "-m", "mawdo.cli", "bench", *cmd], capture_output=True, text=True
    )
    assert done.returncode == 2  # a store of another version given: bad input
    err = plain(done.stderr)
    assert f"belongs to mawdo {stored_version(Path(db))}" in err
    assert "Reports and exports read it as it is (read-only)" in err
    assert "Traceback" not in done.stderr
    assert hashlib.sha256(Path(db).read_bytes()).hexdigest() == before


@pytest.mark.slow
def test_the_committed_stores_report_through_the_command(bbob_stores, tmp_path):
    """docs/bbob.md: `mawdo bench report store-d5.db store-d20.db` rewrites the folder, and
    `mawdo bench export` writes IOHanalyzer logs, from stores made by an older mawdo."""
    out = tmp_path / "report"
    done = subprocess.run(
        [sys.executable, "-m", "mawdo.cli", "bench", "report", *map(str, bbob_stores)]
        + ["--out", str(out), "--no-plots"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    for name in ("summary.md", "friedman.csv", "art_d5.csv", "fixed_budget_d20.csv"):
        assert (out / name).read_text() == (BBOB / name).read_text(), name

    def text(path: Path) -> list[str]:  # the committed report also links its figures
        return [s for s in path.read_text().splitlines() if s and not s.startswith("![")]

    assert text(out / "report.md") == text(BBOB / "report.md")
    logs = tmp_path / "ioh"
    cli = [sys.executable, "-m", "mawdo.cli", "bench", "export", "--format", "ioh"]
    done = subprocess.run([*cli, str(bbob_stores[0]), str(logs)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    pairs = _query(bbob_stores[0], "SELECT DISTINCT algorithm, function_id FROM runs")
    written = {
        (p.parent.name, int(p.stem.split("_f")[1].split("_")[0])) for p in logs.glob("*/*.json")
    }
    assert written == set(pairs)


@pytest.mark.parametrize("folder", ["arena-default", "arena-large"])
def test_arena_sentences_are_those_of_the_committed_store(tmp_path, folder):
    """The committed arena store (xz) gives exactly the committed headline sentences, and each
    planner's T/T* median on the timed families, recomputed from the raw rows with sqlite3
    and numpy, is the one its sentence states."""
    from mawdo.experiments import Store
    from mawdo.experiments.kinds.arena.summary import headline

    db = unpack(ROOT / "docs" / "results" / folder / "store.db.xz", tmp_path)
    with Store.read(db) as store:
        lines = headline(store)
    summary = (ROOT / "docs" / "results" / folder / "summary.md").read_text("utf-8")
    assert lines == summary.splitlines()
    rows = _query(
        db,
        "SELECT algorithm, time_gap FROM runs WHERE t_star IS NOT NULL AND success = 1 "
        "AND error_text IS NULL",
    )
    timed = [s for s in lines if "T/T* median" in s]
    assert timed
    for line in timed:
        planner = line.removeprefix("- ").split(" ")[0]
        gaps = np.array([g for a, g in rows if a == planner])
        assert f"T/T* median {np.median(gaps):.3f}" in line, (planner, line)


def holm_by_hand(p: list[float]) -> list[float]:
    """Holm's step-down adjusted p-values, written out a second time."""
    order = sorted(range(len(p)), key=lambda i: p[i])
    out, running = [0.0] * len(p), 0.0
    for j, i in enumerate(order):
        running = max(running, min(1.0, (len(p) - j) * p[i]))
        out[i] = running
    return out


def test_the_swarm_share_is_that_of_the_committed_store(tmp_path):
    """The committed swarm_share.md is the report's table from the committed store, and its
    verdicts (which the README sentence names) are recomputed here from the raw rows with
    sqlite3, scipy's Wilcoxon (direction: the one-sided tests) and Holm by hand."""
    from scipy.stats import wilcoxon

    from mawdo.experiments import Store
    from mawdo.experiments.kinds.arena.share import share_table
    from mawdo.experiments.tables import to_markdown

    folder = ROOT / "docs" / "results" / "arena-default"
    db = unpack(folder / "store.db.xz", tmp_path)
    with Store.read(db) as store:
        assert to_markdown(share_table(store)) == (folder / "swarm_share.md").read_text("utf-8")
    conn = sqlite3.connect(db)
    gaps = {
        (a, f, n): g
        for a, f, n, g in conn.execute(
            "SELECT algorithm, problem, scene_name, CASE WHEN t_star IS NOT NULL THEN time_gap "
            "ELSE gap END FROM runs WHERE status = 'ok' AND error_text IS NULL AND success = 1"
        )
    }
    # runs in which the optimizer searched at least once: a plan the guide gate did not take
    searched = {
        (a, f): n
        for a, f, n in conn.execute(
            "SELECT algorithm, problem, SUM(replans > gated) FROM runs WHERE status = 'ok' "
            "AND error_text IS NULL GROUP BY algorithm, problem"
        )
    }
    conn.close()
    committed = {
        (r["planner"], r["family"]): r for r in readme_tables()._rows(folder / "swarm_share.md")
    }
    for planner in ("mawdo", "woa", "gwo"):
        families = [f for p, f in committed if p == planner.upper()]
        assert len(families) == 12
        p, lower, diff = [], [], []
        for f in families:
            both = sorted(
                n for a, g, n in gaps if a == planner and g == f and ("guide_only", f, n) in gaps
            )
            x = np.array([gaps[planner, f, n] for n in both])
            y = np.array([gaps["guide_only", f, n] for n in both])
            d = np.where(np.isclose(x, y, rtol=1e-9, atol=0), 0.0, x - y)
            nz = d[d != 0]
            p.append(wilcoxon(nz).pvalue if nz.size else 1.0)
            lower.append(bool(nz.size) and wilcoxon(nz, alternative="less").pvalue < 0.5)
            diff.append(d.mean())
        for f, adj, low, dm in zip(families, holm_by_hand(p), lower, diff, strict=True):
            row = committed[planner.upper(), f]
            verdict = ("helps" if low else "hurts") if adj < 0.05 else "no measurable difference"
            assert row["verdict"] == verdict, (planner, f)
            assert row["p Holm"] == f"{adj:.2g}" and row["mean difference"] == f"{dm:+.2g}"
            assert int(row["runs searched"]) == searched[planner, f], (planner, f)


@pytest.mark.slow
def test_the_committed_arena_figures_are_drawn_from_the_committed_store(tmp_path):
    """README's and docs/planning.md's arena figures are what the report draws from the store
    (the same picture up to anti-aliasing: at most 0.1 % of values off)."""
    import matplotlib.image as mpimg

    from mawdo.experiments.kinds.arena import write_arena_report

    committed = ROOT / "docs" / "results" / "arena-default"
    db = unpack(committed / "store.db.xz", tmp_path)
    out = tmp_path / "report"
    write_arena_report(db, out, gallery_limit=0, worst=0)
    for name in ("swarm.png", "ecdf_gap.png", "ecdf_runtime.png"):
        new, old = mpimg.imread(out / name), mpimg.imread(committed / name)
        assert new.shape == old.shape, name
        off = np.abs(new.astype(float) - old.astype(float)) > 3 / 255
        assert off.mean() <= 1e-3, f"{name}: {off.mean():.2%} of values differ"


def test_crowd_sentences_and_readme_table_are_those_of_the_committed_store(tmp_path):
    """The committed crowd store (xz) gives exactly the committed headline sentences, and the
    README's crowd table carries the store's success and robot-caused shares."""
    from mawdo.experiments import Store
    from mawdo.experiments.kinds.crowd import crowd_summary
    from mawdo.experiments.kinds.crowd.report import crowd_headline

    folder = ROOT / "docs" / "results" / "crowdnav-circle5"
    db = unpack(folder / "store.db.xz", tmp_path)
    with Store.read(db) as store:
        lines = crowd_headline(store)
        summary = crowd_summary(store)
    assert lines == (folder / "summary.md").read_text("utf-8").splitlines()
    rows = readme_tables().crowd_table()[2:]
    assert len(rows) == len(summary) == 7
    for row in rows:
        policy, _, success, caused, _ = (c.strip() for c in row.strip("|").split("|"))
        m = summary[("circle-5-invisible", policy)]
        assert success == f"{100 * m['success']:.1f} %" and m["episodes"] == 500
        assert caused == f"{100 * m['robot_caused']:.1f} %"


@pytest.mark.parametrize(
    ("name", "settings", "policies", "episodes"),
    [
        ("crowdnav-50", 12, 7, 50),
        ("crowdnav", 12, 7, 500),
        ("crowdnav-10", 4, 8, 500),
        ("crowdnav-noise", 2, 2, 200),
    ],
)
def test_every_crowd_setting_sentence_is_that_of_the_committed_store(
    tmp_path, name, settings, policies, episodes
):
    """docs/results/crowdnav-*: each store is its preset run in full and gives the committed
    sentences, on the results page too."""
    from mawdo.experiments import Store
    from mawdo.experiments.kinds.crowd import crowd_summary
    from mawdo.experiments.kinds.crowd.plan import crowd_preset
    from mawdo.experiments.kinds.crowd.report import crowd_headline, crowd_table
    from mawdo.experiments.tables import to_markdown

    folder = ROOT / "docs" / "results" / name
    with Store.read(unpack(folder / "store.db.xz", tmp_path)) as store:
        lines = crowd_headline(store)
        summary = crowd_summary(store)
        stored = store.plan.plan_hash
        table = to_markdown(crowd_table(store))  # the README's sentences read it
    assert table == (folder / "crowd_table.md").read_text("utf-8")
    assert stored == crowd_preset(name).plan_hash  # the preset as it stands, run in full
    assert lines == (folder / "summary.md").read_text("utf-8").splitlines()
    assert len(summary) == settings * policies
    assert {m["episodes"] for m in summary.values()} == {episodes}
    page = " ".join((ROOT / "docs" / "results.md").read_text("utf-8").split())
    assert all(" ".join(line.split()) in page for line in lines)


@pytest.mark.parametrize(
    ("policy", "run"),
    [("mawdo", 0), ("mawdo", 1), ("guide_only", 3), ("dwa", 2)],
)
def test_stored_crowd_episodes_are_what_the_code_computes(tmp_path, policy, run):
    """A few committed episodes of crowdnav-circle5 run again give the stored outcome (run 0
    of mawdo is one where someone starts within reach, so the robot plans without watching)."""
    import json

    from mawdo.experiments.kinds.crowd.execute import episode_row, run_one
    from mawdo.experiments.kinds.crowd.plan import CrowdPlan
    from mawdo.experiments.protocol import Task

    db = unpack(ROOT / "docs" / "results" / "crowdnav-circle5" / "store.db.xz", tmp_path)
    con = sqlite3.connect(db)
    plan = CrowdPlan.from_dict(json.loads(con.execute("SELECT plan_json FROM meta").fetchone()[0]))
    fields = ("success", "robot_caused", "steps", "time_s", "length_m", "discomfort")
    stored = con.execute(
        f"SELECT {', '.join(fields)} FROM runs WHERE algorithm = ? AND run = ?", (policy, run)
    ).fetchone()
    con.close()
    spec = plan.task_spec(Task(policy, "circle-5-invisible", run, 1))
    res, scene = run_one(spec, "circle-5-invisible", spec["seeds"][0])
    row = episode_row(res, scene)
    assert tuple(row[f] for f in fields) == stored


@pytest.mark.parametrize(
    "folder",
    [
        "crowdnav-circle5",
        "crowdnav-50",
        "crowdnav",
        "crowdnav-refiners",
        "crowdnav-10",
        "crowdnav-noise",
    ],
)
def test_the_crowd_share_is_that_of_the_committed_store(tmp_path, folder):
    """The committed crowd_share.md is the report's table from the committed crowd store."""
    from mawdo.experiments import Store
    from mawdo.experiments.kinds.crowd.report import crowd_share_table
    from mawdo.experiments.tables import to_markdown

    path = ROOT / "docs" / "results" / folder
    with Store.read(unpack(path / "store.db.xz", tmp_path)) as store:
        table = crowd_share_table(store)
    assert table is not None
    assert to_markdown(table) == (path / "crowd_share.md").read_text("utf-8")


def official_store(folder: str, tmp_path):
    """A committed official CEC study: its folder, the unpacked stores (``store.db.xz``, then
    any further store of the same protocol, ``NAME.db.xz`` beside ``NAME.plan.json``) and the
    main plan file; each store must hold what its plan file says, the further ones the main
    plan's protocol with other algorithms."""
    import json

    where = ROOT / "docs" / "results" / folder
    plan = json.loads((where / "plan.json").read_text("utf-8"))
    dbs = []
    # the main store first, then the others by name (a glob's order is the file system's)
    for packed in sorted(where.glob("*.db.xz"), key=lambda p: (p.name != "store.db.xz", p.name)):
        stem = packed.name.removesuffix(".db.xz")
        (tmp_path / stem).mkdir(exist_ok=True)
        db = unpack(packed, tmp_path / stem)
        own = plan if stem == "store" else json.loads((where / f"{stem}.plan.json").read_text())
        stored = json.loads(sqlite3.connect(db).execute("SELECT plan_json FROM meta").fetchone()[0])
        assert {k: stored[k] for k in own} == own
        protocol = {k: v for k, v in own.items() if k not in ("name", "algorithms")}
        assert protocol == {k: v for k, v in plan.items() if k not in ("name", "algorithms")}
        dbs.append(db)
    return where, dbs, plan


def assert_group_places_stated(study, by_group, dim: int) -> None:
    """docs/algorithms.md states WDO+'s place in each function group of ``by_group`` (the
    Friedman ranks per group), in order: 1 + the algorithms ranked strictly better."""
    n, ours = len(study.algorithms), study.algorithms.index("wdo_plus")
    places = []
    for r in by_group.rows:
        rank = np.array(r[3 : 3 + n])
        place = 1 + int(np.sum(rank < rank[ours]))
        suffix = {1: "st", 2: "nd", 3: "rd"}.get(place, "th")
        places.append(f"{r[1].split(' (')[0]} {place}{suffix}")
    algos_page = " ".join((ROOT / "docs" / "algorithms.md").read_text("utf-8").split())
    assert f"D = {dim}: {', '.join(places)}" in algos_page


@pytest.mark.parametrize(
    ("folder", "dim", "evaluations", "row", "anchor", "against_cmaes"),
    [
        ("cec2022-official-d10", 10, 200_000, -4, "cec2022-official", "level"),
        ("cec2022-official-d20", 20, 1_000_000, -3, "cec2022-official-d20", "ahead"),
    ],
)
def test_the_official_cec2022_ranks_are_those_of_the_committed_store(
    tmp_path, folder, dim, evaluations, row, anchor, against_cmaes
):
    """docs/results/cec2022-official-d*: the store holds CEC 2022's protocol (F1-F12, 30 runs,
    200 000 evaluations at D = 10, 1 000 000 at D = 20) as its plan file says, and gives the
    committed Friedman table and competition tables, from which the README's official suites
    rows and the results page's sentence are made."""

    from mawdo.experiments.kinds.suite.competition import competition_tables
    from mawdo.experiments.kinds.suite.data import load_runs
    from mawdo.experiments.kinds.suite.report import friedman_groups_table, friedman_table
    from mawdo.experiments.tables import to_markdown

    where, dbs, plan = official_store(folder, tmp_path)
    assert (plan["suite"], plan["dims"], plan["budget"] * dim, plan["runs"]) == (
        "cec2022", [dim], evaluations, 30,
    )  # fmt: skip
    assert plan["functions"] == list(range(1, 13)) and len(plan["algorithms"]) == 10
    study = load_runs(dbs)
    assert to_markdown(friedman_table(study)) == (where / "friedman.md").read_text("utf-8")
    by_group = friedman_groups_table(study)
    assert to_markdown(by_group) == (where / "friedman_groups.md").read_text("utf-8")
    # the four groups cover the twelve functions once; their ranks, weighted by their blocks,
    # average to the ranks over all functions (a block's ranks do not depend on the others)
    n = len(study.algorithms)
    sizes = np.array([r[2] for r in by_group.rows])
    assert list(sizes) == [1, 4, 3, 4]
    group_ranks = np.array([r[3 : 3 + n] for r in by_group.rows])
    np.testing.assert_allclose(sizes @ group_ranks / 12, friedman_table(study).rows[0][2 : 2 + n])
    # docs/algorithms.md gives WDO+'s place in each group
    ours = study.algorithms.index("wdo_plus")
    assert_group_places_stated(study, by_group, dim)
    # on the compositions WDO+ is ahead of CMA-ES or level with it, as the algorithms page says
    comp = by_group.rows[-1]
    mine, theirs = comp[3 + ours], comp[3 + study.algorithms.index("cmaes")]
    assert comp[1].startswith("composition")
    assert mine < theirs if against_cmaes == "ahead" else mine == theirs
    tables = {t.name: t for t in competition_tables(study, dim)}
    for name in (f"competition_d{dim}", f"checkpoints_d{dim}"):
        assert to_markdown(tables[name]) == (where / f"{name}.md").read_text("utf-8")
    line = readme_tables().suites_table()[row]
    assert line.startswith(f"| CEC 2022 F1-F12, D = {dim} (official") and "| WDO+ |" in line
    # the results page's sentence in the section on this study names, in order, every
    # algorithm ranked ahead of WDO+
    fr = friedman_table(study).rows[-1]  # the "all" row: label, blocks, ranks..., chi2, p
    ranks = dict(zip(study.algorithms, fr[2 : 2 + len(study.algorithms)], strict=True))
    order = sorted(ranks, key=ranks.get)
    top = [NAMES[a] for a in order[: order.index("wdo_plus")]]
    listed = ", ".join(top[:-1]) + f" and {top[-1]}"
    page = (ROOT / "docs" / "results.md").read_text("utf-8")
    section = page.split(f'<a id="{anchor}"></a>')[1].split("\n## ")[0].split("<a id=")[0]
    assert f"order them {listed}, then WDO+" in " ".join(section.split())
    # and the algorithms page names them in that order, with this report
    algos = " ".join((ROOT / "docs" / "algorithms.md").read_text("utf-8").split())
    assert f"behind {listed} ([report](results/{folder}/report.md)" in algos


#: The algorithms' names as the pages write them.
NAMES = {
    "nlshade_rsp": "NL-SHADE-RSP", "jso": "jSO", "lshade": "L-SHADE", "cmaes": "CMA-ES",
    "scipy_de": "scipy's DE", "wdo_plus": "WDO+", "gwo": "GWO", "wdo": "WDO", "woa": "WOA",
    "mawdo": "MAWDO", "random": "random search", "ea4eig": "EA4eig",
}  # fmt: skip


@pytest.mark.parametrize(
    ("folder", "dim", "algorithms", "row"),
    [("cec2017-official-d10", 10, 10, -2), ("cec2017-official-d30", 30, 4, -1)],
)
def test_the_official_cec2017_study_is_that_of_the_committed_store(
    tmp_path, folder, dim, algorithms, row
):
    """docs/results/cec2017-official-d*: the stores hold CEC 2017's protocol (F1-F30, 51 runs,
    10 000 x D evaluations) as their plan files say; they give the committed Friedman, group,
    score and competition tables, and the README row, the results page's order and the
    algorithms page's places by group are read from them."""

    from mawdo.experiments.kinds.suite.competition import competition_tables, score_table
    from mawdo.experiments.kinds.suite.data import load_runs
    from mawdo.experiments.kinds.suite.report import friedman_groups_table, friedman_table
    from mawdo.experiments.tables import to_markdown

    where, dbs, plan = official_store(folder, tmp_path)
    assert (plan["suite"], plan["dims"], plan["budget"] * dim, plan["runs"]) == (
        "cec2017", [dim], 10_000 * dim, 51,
    )  # fmt: skip
    assert plan["functions"] == list(range(1, 31)) and len(plan["algorithms"]) == algorithms
    study = load_runs(dbs)
    for db in dbs:  # every store complete: 30 functions x its algorithms x 51 runs
        con = sqlite3.connect(db)
        stored = json.loads(con.execute("SELECT plan_json FROM meta").fetchone()[0])
        n_runs = con.execute("SELECT count(*) FROM runs").fetchone()[0]
        assert n_runs == 30 * len(stored["algorithms"]) * 51, db
    assert to_markdown(friedman_table(study)) == (where / "friedman.md").read_text("utf-8")
    by_group = friedman_groups_table(study)
    assert to_markdown(by_group) == (where / "friedman_groups.md").read_text("utf-8")
    assert to_markdown(score_table(study)) == (where / "score.md").read_text("utf-8")
    tables = {t.name: t for t in competition_tables(study, dim)}
    for name in (f"competition_d{dim}", f"checkpoints_d{dim}"):
        assert to_markdown(tables[name]) == (where / f"{name}.md").read_text("utf-8")
    n = len(study.algorithms)
    sizes = np.array([r[2] for r in by_group.rows])
    assert list(sizes) == [3, 7, 10, 10]
    group_ranks = np.array([r[3 : 3 + n] for r in by_group.rows])
    np.testing.assert_allclose(sizes @ group_ranks / 30, friedman_table(study).rows[0][2 : 2 + n])
    line = readme_tables().suites_table()[row]
    assert line.startswith(f"| CEC 2017 F1-F30, D = {dim} (official") and "| WDO+ |" in line
    assert_group_places_stated(study, by_group, dim)
    # the results page names, in order, every algorithm ranked ahead of WDO+
    fr = friedman_table(study).rows[-1]
    ranks = dict(zip(study.algorithms, fr[2 : 2 + n], strict=True))
    order = sorted(ranks, key=ranks.get)
    ahead = [NAMES[a] for a in order[: order.index("wdo_plus")]]
    page = (ROOT / "docs" / "results.md").read_text("utf-8")
    section = page.split(f'<a id="{folder}"></a>')[1].split("\n## ")[0].split("<a id=")[0]
    listed = ", ".join(ahead[:-1]) + f" and {ahead[-1]}" if len(ahead) > 1 else ahead[0]
    assert f"order them {listed}, then WDO+" in " ".join(section.split())
    # and the score's order, best first, as the results page gives it
    score = score_table(study)
    top = [NAMES[r[1]] for r in score.rows]
    assert f"by the competition's score: {', '.join(top[:-1])} and {top[-1]}" in " ".join(
        section.split()
    )
