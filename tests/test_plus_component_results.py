"""The committed component study of WDO+ on CEC 2017 (docs/results/wdo-plus-components-cec2017).

The committed store must give exactly ``findings.md`` and the subsection of docs/algorithms.md;
the numbers those sentences state (final errors, ECDF areas, each switch's effect and its
bootstrap interval, the functions won against jSO, which changes hold WDO+ back) are recomputed
here from the raw rows with sqlite3 and numpy, not with the code that wrote them; the command
the docs give rebuilds the stored plan; and the current code re-runs a sample of stored runs
bit for bit (on a CPU of the store's kind: docs/deviations.md#d-cpu).
"""

from __future__ import annotations

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

ROOT = Path(__file__).resolve().parents[1]
FOLDER = ROOT / "docs" / "results" / "wdo-plus-components-cec2017"
GENERATOR = "mawdo.experiments.kinds.suite.plus_components_summary"
GROUPS = {  # the CEC 2017 technical report's groups (Awad et al. 2016, Table I)
    "all functions": range(1, 31),
    "unimodal": range(1, 4),
    "simple multimodal": range(4, 11),
    "hybrid": range(11, 21),
    "composition": range(21, 31),
}
SWITCHES = ("origin", "nopressure", "noadapt", "norestart", "clip", "best")
FIVE = SWITCHES[:5]
TARGETS = 10.0 ** np.linspace(2, -8, 51)
DIM, BUDGET, RUNS = 10, 1e4, 51
NAMES = {"WDO+": "wdo_plus", "jSO": "jso", "WDO": "wdo"}
NUM = r"([+-]\d+\.\d+)"


@pytest.fixture(scope="module")
def store(tmp_path_factory) -> Path:
    db = tmp_path_factory.mktemp("plus") / "store.db"
    with lzma.open(FOLDER / "store.db.xz") as src, open(db, "wb") as dst:
        shutil.copyfileobj(src, dst)
    return db


@pytest.fixture(scope="module")
def lines() -> list[str]:
    return (FOLDER / "findings.md").read_text(encoding="utf-8").splitlines()


class Raw:
    """Per run, from the raw columns: final error (<= 1e-8 counts as 0) and ECDF area."""

    def __init__(self, path: Path):
        conn = sqlite3.connect(path)
        got = conn.execute(
            "SELECT algorithm, function_id, run, f_star, evals, best_so_far FROM runs "
            "WHERE error_text IS NULL"
        ).fetchall()
        conn.close()
        self.err, self.area = {}, {}
        for algo, fid, run, f_star, ev, best in got:
            ev, prec = np.frombuffer(ev, "<i8"), np.frombuffer(best, "<f8") - f_star
            self.err[algo, fid, run] = prec[-1]
            hit = prec[:, None] <= TARGETS
            rt = np.where(hit.any(axis=0), ev[hit.argmax(axis=0)], np.inf)
            with np.errstate(divide="ignore"):
                frac = 1 - np.log(rt / DIM) / np.log(BUDGET)
            self.area[algo, fid, run] = np.clip(frac, 0, 1).mean()
        assert len(self.err) == 9 * 30 * RUNS

    def log_err(self, algo: str, fids) -> np.ndarray:
        """Per run: mean over ``fids`` of log10(max(error, 1e-8))."""
        return np.array([np.mean([np.log10(max(self.err[algo, f, r], 1e-8)) for f in fids])
                         for r in range(RUNS)])  # fmt: skip

    def areas(self, algo: str, fids) -> np.ndarray:
        return 100 * np.array([np.mean([self.area[algo, f, r] for f in fids])
                               for r in range(RUNS)])  # fmt: skip

    def mean_err(self, algo: str, fid: int) -> float:
        e = np.array([self.err[algo, fid, r] for r in range(RUNS)])
        return float(np.where(e <= 1e-8, 0.0, e).mean())

    @staticmethod
    def boot(d: np.ndarray) -> tuple[float, float, float]:
        idx = np.random.default_rng(29).integers(0, len(d), (1000, len(d)))
        lo, hi = np.percentile(d[idx].mean(axis=1), [2.5, 97.5])
        return d.mean(), lo, hi


@pytest.fixture(scope="module")
def raw(store) -> Raw:
    return Raw(store)


def _line(lines: list[str], start: str) -> str:
    found = [s for s in lines if s.startswith(start)]
    assert len(found) == 1, start
    return found[0]


def _label(group: str) -> str:
    fids = GROUPS[group]
    return group if group == "all functions" else f"{group} (F{fids[0]}-F{fids[-1]})"


def test_findings_and_docs_section_are_those_of_the_committed_store(store, lines, tmp_path):
    out = tmp_path / "out"
    done = subprocess.run(
        [sys.executable, "-m", GENERATOR, str(store), "--out", str(out)],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert (out / "findings.md").read_text(encoding="utf-8").splitlines() == lines
    section = done.stdout.rstrip("\n") + "\n"
    assert section in (ROOT / "docs" / "algorithms.md").read_text(encoding="utf-8")


def test_the_generator_names_a_store_that_is_not_the_study(tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", GENERATOR, "none.db", "--out", str(tmp_path / "o")],
        capture_output=True, text=True, check=False, cwd=tmp_path,
    )  # fmt: skip
    assert done.returncode == 2 and done.stderr.startswith("error: ") and "none.db" in done.stderr
    assert "Traceback" not in done.stderr and not (tmp_path / "o").exists()


@pytest.mark.parametrize("group", list(GROUPS))
def test_standing_against_jso_is_recomputed_from_the_raw_rows(raw, lines, group):
    text = _line(lines, f"{_label(group)}: mean log10 final error ")
    errs = re.findall(rf"(WDO\+|jSO|WDO) {NUM}[,;]", text)
    areas = re.findall(r"(WDO\+|jSO|WDO) (\d+\.\d) %", text)
    assert [n for n, _ in errs] == [n for n, _ in areas] == ["WDO+", "jSO", "WDO"]
    for n, v in errs:
        assert float(v) == pytest.approx(raw.log_err(NAMES[n], GROUPS[group]).mean(), abs=0.006)
    for n, v in areas:
        assert float(v) == pytest.approx(raw.areas(NAMES[n], GROUPS[group]).mean(), abs=0.051)
    pairs = [(raw.mean_err("wdo_plus", f), raw.mean_err("jso", f)) for f in GROUPS[group]]
    counts = (sum(a < b for a, b in pairs), sum(a > b for a, b in pairs),
              sum(a == b for a, b in pairs))  # fmt: skip
    said = re.search(r"below jSO's on (\d+) of (\d+) functions, above on (\d+), equal on (\d+)",
                     text).groups()  # fmt: skip
    assert tuple(map(int, said)) == (counts[0], len(GROUPS[group]), counts[1], counts[2])


@pytest.mark.parametrize("switch", SWITCHES)
def test_switch_effects_and_intervals_are_recomputed_from_the_raw_rows(raw, lines, switch):
    text = _line(lines, f"`{switch}`, ")
    errs, areas = text.split(" ECDF area, points: ")
    for part, measure, tol in ((errs, raw.log_err, 0.006), (areas, raw.areas, 0.051)):
        claims = re.findall(rf"([a-z ]+) {NUM} \[{NUM}, {NUM}\]", part)
        assert [g.strip() for g, *_ in claims] == list(GROUPS)
        for g, *vals in claims:
            fids = GROUPS[g.strip()]
            want = Raw.boot(measure(f"wdo_plus-{switch}", fids) - measure("wdo_plus", fids))
            assert tuple(map(float, vals)) == pytest.approx(want, abs=tol), (switch, g)


@pytest.mark.parametrize("group", list(GROUPS)[1:])
def test_the_verdicts_name_the_changes_whose_interval_says_so(raw, lines, group):
    text = _line(lines, f"{_label(group)}: WDO+ ")
    fids = GROUPS[group]
    worse = sum(raw.mean_err("wdo_plus", f) > raw.mean_err("jso", f) for f in fids)
    better = sum(raw.mean_err("wdo_plus", f) < raw.mean_err("jso", f) for f in fids)
    if worse <= better:
        assert "does not lose to jSO" in text
        return
    effects = {s: Raw.boot(raw.log_err(f"wdo_plus-{s}", fids) - raw.log_err("wdo_plus", fids))
               for s in FIVE}  # fmt: skip
    back = {s for s, (_, _, hi) in effects.items() if hi < 0}
    needed = {s for s, (_, lo, _) in effects.items() if lo > 0}
    head, _, tail = text.partition("The changes it needs there")
    named_back = set(re.findall(r"\((\w+) [+-]\d", head)) if "held back by" in head else set()
    assert named_back == back
    assert ("none of its five changes holds it back" in head) == (not back)
    assert set(re.findall(r"\((\w+) [+-]\d", tail.split("Gravity toward the best")[0])) == needed


def test_the_documented_command_rebuilds_the_stored_plan(store):
    from mawdo.cli.study import load_plan

    readme = (FOLDER / "README.md").read_text(encoding="utf-8")
    cmds = re.findall(r"^ +mawdo study run (\S+) -o store\.db$", readme, re.M)
    assert cmds == ["wdo-plus-components-cec2017"]
    conn = sqlite3.connect(store)
    stored, plan_json = conn.execute("SELECT plan_hash, plan_json FROM meta").fetchone()
    conn.close()
    assert load_plan(cmds[0], []).plan_hash == stored
    assert json.loads(plan_json)["runs"] == RUNS


SAMPLE = [  # (algorithm, problem): the base, every switch, WDO and jSO, each group
    ("wdo_plus", "f01_i01_d10"),
    ("wdo_plus-origin", "f05_i01_d10"),
    ("wdo_plus-best", "f09_i01_d10"),
    ("wdo_plus-nopressure", "f12_i01_d10"),
    ("wdo_plus-noadapt", "f17_i01_d10"),
    ("wdo_plus-norestart", "f22_i01_d10"),
    ("wdo_plus-clip", "f26_i01_d10"),
    ("wdo", "f30_i01_d10"),
    ("jso", "f14_i01_d10"),
]


@pytest.mark.slow
@pytest.mark.parametrize(("algo", "problem"), SAMPLE)
def test_current_code_reruns_stored_runs_bit_for_bit(store, algo, problem):
    """Runs 0 and 1 of a sample of tasks (every algorithm): the same rows as stored, so the
    findings are still true of the current code, on any CPU (docs/deviations.md#d-cpu)."""
    from mawdo.experiments.kinds.suite.execute import execute_suite_task
    from mawdo.experiments.protocol import Task
    from mawdo.experiments.store import Store

    with Store.read(store) as s:
        old = {r.run: r for _, _, r in s.rows(algo, problem)}
        spec = s.plan.task_spec(Task(algo, problem, 0, 2))
    new = execute_suite_task(spec)
    assert len(new) == 2
    for r in new:
        o = old[r.run]
        assert r.error_text is None and r.fun == o.fun and r.nfev == o.nfev, (algo, problem)
        assert np.array_equal(r.evals, o.evals) and np.array_equal(r.best_so_far, o.best_so_far)
        assert np.array_equal(r.best_x, o.best_x)


def test_the_readme_says_where_the_changes_hold_wdo_plus_back_as_the_findings_do(lines):
    readme = " ".join((ROOT / "README.md").read_text(encoding="utf-8").split())
    assert "its own changes hold it back only on the unimodal functions" in readme
    verdict = {  # each group's last line: its verdict (the first one is its standing)
        g: [x for x in lines if x.startswith(f"{g} (F")][-1] for g in list(GROUPS)[1:]
    }
    assert "held back by" in verdict["unimodal"]
    for group in ("simple multimodal", "hybrid"):
        assert "none of its five changes holds it back" in verdict[group]
    assert "does not lose to jSO" in verdict["composition"]
